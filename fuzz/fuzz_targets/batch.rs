//! Fuzz target `batch`: see `rayhit_testkit::fuzz::targets::batch` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::batch(data));
