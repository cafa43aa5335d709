//! rayhit with the crates users combine it with, in one test binary: every
//! vector type of every enabled glam release (`vector_types`), slices cast
//! with bytemuck and serde round trips (`bytes`), and the `approx`
//! comparisons (`approx_traits`).

mod approx_traits;
mod bytes;
mod vector_types;
