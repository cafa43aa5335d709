//! Fuzz target `spawn_to`: see `rayhit_testkit::fuzz::targets::spawn_to` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::spawn_to(data));
