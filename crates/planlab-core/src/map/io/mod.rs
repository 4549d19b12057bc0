//! Map and scenario file formats.
//!
//! Every reader takes text or bytes, never a path: core runs in WebAssembly
//! where there is no file system, so the caller (CLI, page) reads the files.

pub mod movingai;
pub mod ros;
pub mod scenario;
