//! The box (`Aabb`, `ValidAabb`): the slab test and the naive face test,
//! the entry face, and the interval forms.

mod face;
mod fuzz_regressions;
pub mod interval;
mod oracle;
mod properties;
