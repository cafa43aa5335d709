//! Fuzz target `equirectangular`: see `rayhit_testkit::fuzz::targets::equirectangular` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::equirectangular(data));
