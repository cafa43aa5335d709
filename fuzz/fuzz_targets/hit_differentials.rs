//! Fuzz target `hit_differentials`: see `rayhit_testkit::fuzz::targets::hit_differentials` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::hit_differentials(data));
