//! Fuzz target `aabb_slab_vs_naive`: see `rayhit_testkit::fuzz::targets::aabb_slab_vs_naive` for the input layout and the checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::targets::aabb_slab_vs_naive(data));
