//! Every file the CLI writes goes through `planlab_files::output` (shared
//! with the Python package): atomically, and never over an input of the
//! same command.

pub(crate) use planlab_files::output::{refuse_input, write_atomically, AtomicFile};
