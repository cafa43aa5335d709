//! The demo, run small through its own code, in one test binary (one
//! link): one module per scene, named as `render --scene` names it, and
//! `common` for what they share. Each check is decided from the scene's
//! geometry by the test, not from the picture it is checking.
//!
//! Run one scene's checks with its module path as the filter, for example
//! `cargo test -p rayhit-demo --test render shadows::`.

mod common;
mod cornell;
mod demo;
mod instances;
mod leak;
mod shadows;
mod spheres;
