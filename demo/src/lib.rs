//! The demo's scenes and tracer, a library so that the `render` binary and
//! the tests run the very same code.
//!
//! [`renderer`] holds what the scenes share; each other module is one
//! scene, named as `render --scene` names it: [`demo`], [`leak`],
//! [`shadows`], [`instances`], [`spheres`] and [`cornell`].

/// Triangle meshes and the bounding volume hierarchy: the test kit's (the
/// oracle tests and the benches build the same meshes).
pub use rayhit_testkit::mesh;

pub mod cornell;
pub mod demo;
pub mod instances;
pub mod leak;
pub mod renderer;
pub mod shadows;
pub mod spheres;
