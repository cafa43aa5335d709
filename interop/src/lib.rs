//! Nothing here: the package is its tests (`tests/interop/`), which hold
//! rayhit to the other crates' types and formats: every older glam
//! release's vector types, bytemuck casts, serde round trips and the
//! `approx` comparisons.
