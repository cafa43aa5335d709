//! Fuzz target `orthographic`: see `rayhit_testkit::fuzz::targets::orthographic` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::orthographic(data));
