#![no_main]
//! `cargo fuzz run movingai_scen`: see `fuzz/README.md`.

#[path = "../../crates/planlab-core/tests/fuzz_targets/mod.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::movingai_scen(data));
