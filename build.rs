//! The crate's `cfg` aliases, so that no target predicate is written twice:
//!
//! - `rayhit_lanes4` and `rayhit_lanes8` name the registers the `f32` lanes
//!   use on the build's target, four and eight at a time: `"sse2"` on x86
//!   targets with SSE2 (the default x86-64 target among them), for eight
//!   lanes `"avx2"` instead where AVX2 is enabled at compile time (as with
//!   `-C target-cpu=native` on a recent CPU), `"neon"` on aarch64 targets
//!   with NEON (all of them: it is in the architecture's baseline), and
//!   `"portable"` (arrays) on every other target.
//! - `rayhit_runtime_avx` is set where the batch kernels pick an AVX2 or
//!   AVX-512 copy at run time: x86-64 with `std` (for the CPU detection),
//!   on a target that does not already assume AVX2.
//!
//! `RUSTFLAGS="--cfg rayhit_portable"` makes every target use the arrays,
//! so that the register types' code can be compared with the portable
//! code's on the same target (as BENCHMARKS.md does for NEON); the answers
//! are the same bits either way.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(rayhit_runtime_avx)");
    println!("cargo::rustc-check-cfg=cfg(rayhit_portable)");
    println!("cargo::rustc-check-cfg=cfg(rayhit_lanes4, values(\"sse2\", \"neon\", \"portable\"))");
    println!(
        "cargo::rustc-check-cfg=cfg(rayhit_lanes8, values(\"avx2\", \"sse2\", \"neon\", \"portable\"))"
    );
    println!("cargo::rerun-if-changed=build.rs");
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let features = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let has = |feature: &str| features.split(',').any(|f| f == feature);
    let std = std::env::var_os("CARGO_FEATURE_STD").is_some();
    let portable = std::env::var("CARGO_CFG_RAYHIT_PORTABLE").is_ok();
    let x86 = arch == "x86" || arch == "x86_64";
    let lanes4 = if portable {
        "portable"
    } else if x86 && has("sse2") {
        "sse2"
    } else if arch == "aarch64" && has("neon") {
        "neon"
    } else {
        "portable"
    };
    let lanes8 = if !portable && arch == "x86_64" && has("avx2") {
        "avx2"
    } else {
        lanes4
    };
    println!("cargo::rustc-cfg=rayhit_lanes4=\"{lanes4}\"");
    println!("cargo::rustc-cfg=rayhit_lanes8=\"{lanes8}\"");
    if !portable && arch == "x86_64" && std && !has("avx2") {
        println!("cargo::rustc-cfg=rayhit_runtime_avx");
    }
}
