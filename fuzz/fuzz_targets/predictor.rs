#![no_main]
//! `cargo fuzz run predictor`: see `fuzz/README.md`.

#[path = "../../crates/planlab-core/tests/fuzz_targets/mod.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::predictor(data));
