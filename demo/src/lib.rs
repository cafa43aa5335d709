//! The demo's scenes and tracer, a library so that the `render` binary and
//! the tests run the very same code.

/// Triangle meshes and the bounding volume hierarchy (shared with the
/// crate's oracle tests, which build the same meshes).
#[path = "../../tests/support/mesh.rs"]
pub mod mesh;
pub mod scene;
