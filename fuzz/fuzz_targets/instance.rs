//! Fuzz target `instance`: see `rayhit_testkit::fuzz::targets::instance` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::instance(data));
