//! Fuzz target `matrix_camera`: see `rayhit_testkit::fuzz::targets::matrix_camera` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::matrix_camera(data));
