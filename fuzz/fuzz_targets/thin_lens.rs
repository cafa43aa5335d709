//! Fuzz target `thin_lens`: see `rayhit_testkit::fuzz::targets::thin_lens` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::thin_lens(data));
