//! Fuzz target `equal_area`: see `rayhit_testkit::fuzz::targets::equal_area` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::equal_area(data));
