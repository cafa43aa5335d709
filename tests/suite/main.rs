//! The crate's integration tests, in one test binary (one link, and the
//! kernels compiled once for all of them), on one axis: one module per
//! subject, the code under test.
//!
//! | module | subject |
//! | --- | --- |
//! | `aabb` | the box: slab and naive tests, entry face, intervals |
//! | `plane` | the plane: the test, its hit point, intervals |
//! | `disc` | the disc and annulus: the test over a `t_max` and over an interval, the rims decided exactly, the textbook test beside it |
//! | `quad` | the quad: its hit, `(u, v)` and bounds against exact arithmetic, closed quad meshes with no crack and no leak, the textbook test beside it |
//! | `sphere` | the sphere: the test over a `t_max` and over an interval, its error bound, the textbook test beside it |
//! | `triangle` | the triangle: watertight, one-hit and Moller-Trumbore tests, meshes, zero-area triangles, intervals, the walk along a ray |
//! | `shapes` | several shapes' kernels at once: metamorphic identities, the plane and box intervals' long run and bad input |
//! | `batch` | the batches and the compressed BVH node, bit for bit against the scalar kernels |
//! | `surface` | leaving a surface: rays spawned from surface points (triangles, quads, spheres, planes), shadow-ray segments |
//! | `instance` | instances: world boxes, rays and surface points, meshes placed by instances |
//! | `camera` | the cameras and ray differentials |
//! | `exact` | the public `rayhit::exact` module itself |
//! | `layering` | the crate's source files against CONTRIBUTING.md's map: none missing, no use of a later layer, no import circle |
//! | `common` | no subject: helpers the others share |
//!
//! Inside a subject, a file per technique, with the same names everywhere:
//!
//! - `oracle.rs`: the oracle suite, the kernels on the test kit's
//!   generators aimed at what breaks textbook code, every answer classified
//!   against exact arithmetic and tallied (`common::oracle`);
//! - `properties.rs`: proptest properties on `rayhit::strategies`, with
//!   bounds evaluated exactly (`common::props`);
//! - `fuzz_regressions.rs`: inputs the fuzzers (`fuzz/`) found, kept as
//!   literal floats;
//!
//! and a file per part of the subject that has tests of its own: an
//! `interval.rs` for the interval forms, `aabb::face`,
//! `triangle::degenerate`, `triangle::walk`, `surface::spawn_to`,
//! `batch::lanes`, `batch::node`, ...
//!
//! Where a new test goes: the module of the code it exercises (for a fuzz
//! find, the code at fault, or whose documented behaviour it pins down),
//! then the file of its technique or part. A test that holds several
//! shapes' kernels at once goes to `shapes`; one of a batch's lanes to
//! `batch`, even where it compares them with one shape's scalar test; one
//! of instances to `instance`, whatever shape they place. A shape's own hit
//! point and its bound (`surface_point`) stay with the shape; what is done
//! with a surface point (`spawn`, `spawn_to`) is `surface`'s.
//!
//! Each fuzz regression says which target found its input and what went
//! wrong. Where the fault was in the fuzzer's own check, the test pins
//! down the kernel's documented behaviour on that input. Where the kernel
//! was at fault, the test asserts what the docs promise (and failed before
//! the fix). Where the docs were (a guarantee stated without a
//! precondition it needs), the test shows that the input is outside the
//! precondition the docs now state, and that the answer is still safe (no
//! panic, no NaN, in range).
//!
//! Run a subject, a part or a technique with its module path as the
//! filter: `cargo test --test suite triangle::`, `cargo test --test suite
//! interval::`, `cargo test --test suite oracle::`. The long runs are
//! `#[ignore]`d, each with its command in its module's documentation (for
//! example `cargo test --release --test suite oracle:: -- --ignored
//! --nocapture`, the oracle suite's four). CI also runs `batch::` alone
//! for the other instruction sets (aarch64 under qemu, x86-64-v3 and v4).
//!
//! Case counts: every test's default, times `RAYHIT_CASES`
//! (`rayhit_testkit::case_count`). Proptest's saved seeds are in
//! `tests/proptest-regressions/`, at the test's module path
//! (`aabb/properties.txt` for `aabb::properties`): proptest reads them
//! from the directory beside the one holding `main.rs`.

mod aabb;
mod batch;
mod camera;
mod common;
mod disc;
mod exact;
mod instance;
mod layering;
mod patch;
mod plane;
mod quad;
mod shapes;
mod sphere;
mod surface;
mod triangle;
