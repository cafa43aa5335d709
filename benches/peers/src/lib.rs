//! The peers table's pieces that its example (`examples/obvhs.rs`) shares:
//! the compressed-BVH scenes, traversals and leak counts (`cwbvh`), and the
//! binary BVH and ray sets of the section `traversal` (`traversal`).

pub mod cwbvh;
pub mod traversal;
