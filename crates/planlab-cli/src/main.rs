//! `planlab`: command-line front end of planlab-core.
fn main() {}
