//! Fuzz target `triangle_watertight_vs_mt`: see `rayhit_testkit::fuzz::targets::triangle_watertight_vs_mt` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(
    |data: &[u8]| rayhit_testkit::fuzz::targets::triangle_watertight_vs_mt(data)
);
