//! The triangle (`Triangle`): the watertight test, its one-hit variant and
//! Moller-Trumbore, on single triangles and on meshes; zero-area
//! triangles; the interval forms; and the walk along a ray, every hit in
//! order from a sequence of interval calls (`walk`).

mod degenerate;
mod fuzz_regressions;
mod interval;
mod oracle;
mod properties;
mod walk;
