//! Fuzz target `triangle`: see `rayhit_testkit::fuzz::targets::triangle` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::triangle(data));
