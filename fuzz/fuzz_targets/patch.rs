//! A fuzz target: the check `rayhit_testkit::fuzz::TARGETS` gives this
//! binary's name (its `[[bin]]` in `fuzz/Cargo.toml`), whose module
//! documents the input layout and the checks. Every target's file but the
//! README's example (`exact_judge.rs`) is this one.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rayhit_testkit::fuzz::run(env!("CARGO_BIN_NAME"), data));
