//! The peers table's pieces that its example (`examples/obvhs.rs`) shares:
//! the compressed-BVH scenes, traversals and leak counts.

pub mod cwbvh;
