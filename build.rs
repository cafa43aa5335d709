//! One `cfg` alias for the whole crate: `rayhit_runtime_avx` is set where
//! the batch kernels pick an AVX2 or AVX-512 copy at run time: x86-64 with
//! `std` (for the CPU detection), on a target that does not already assume
//! AVX2 (the default x86-64 target has only SSE2; with `-C
//! target-cpu=native` on a recent CPU the target's own copy is already the
//! AVX2 one).

fn main() {
    println!("cargo::rustc-check-cfg=cfg(rayhit_runtime_avx)");
    println!("cargo::rerun-if-changed=build.rs");
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let features = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let std = std::env::var_os("CARGO_FEATURE_STD").is_some();
    let avx2 = features.split(',').any(|f| f == "avx2");
    if arch == "x86_64" && std && !avx2 {
        println!("cargo::rustc-cfg=rayhit_runtime_avx");
    }
}
