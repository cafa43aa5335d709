//! The crate's integration tests, one module per subject, in one test
//! binary (one link, and the kernels compiled once for all of them).
//!
//! Run one subject with its module path as the filter, for example
//! `cargo test --test suite oracle::`; the long runs are `#[ignore]`d, each
//! with its command in its module's documentation.
//!
//! `tests/batch.rs` and `tests/quantized.rs` are binaries of their own:
//! CI also builds them for the other instruction sets (aarch64 under qemu,
//! x86-64-v3), where the rest of the suite is not needed.

mod box_face;
mod camera;
mod cameras;
mod degenerate;
mod draw;
mod exact_api;
mod fuzz_regressions;
mod instance_meshes;
mod instances;
mod interval_sequences;
mod interval_shapes;
mod intervals;
mod oracle;
mod properties;
mod spawn_to;
