//! Fuzz target `interval`: see `rayhit_testkit::fuzz::targets::interval` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::interval(data));
