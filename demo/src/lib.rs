//! The demo's scenes and tracer, a library so that the `render` binary and
//! the tests run the very same code.

/// Triangle meshes and the bounding volume hierarchy: the test kit's (the
/// oracle tests and the benches build the same meshes).
pub use rayhit_testkit::mesh;
pub mod instances;
pub mod scene;
pub mod shadows;
