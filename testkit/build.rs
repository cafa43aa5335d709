//! The README's example fuzz target (`fuzz/fuzz_targets/exact_judge.rs`:
//! a user's kernel held to `rayhit::exact`), without the two lines only
//! `cargo fuzz` can compile (`#![no_main]` and the `libfuzzer_sys` import),
//! for the kit's fuzz module to run (`TARGETS`), on its seeds in the
//! replay test as `cargo fuzz` would.

use std::path::Path;

fn main() {
    let dir = std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo");
    let target = Path::new(&dir).join("../fuzz/fuzz_targets/exact_judge.rs");
    println!("cargo::rerun-if-changed={}", target.display());
    let text = std::fs::read_to_string(&target).unwrap_or_default();
    let body: String = text
        .lines()
        .filter(|l| !matches!(*l, "#![no_main]" | "use libfuzzer_sys::fuzz_target;"))
        .map(|l| format!("{l}\n"))
        .collect();
    let out = std::env::var("OUT_DIR").expect("set by cargo");
    std::fs::write(Path::new(&out).join("exact_judge.rs"), body).expect("OUT_DIR is writable");
}
