//! The peers table's pieces that its example (`examples/obvhs.rs`) shares:
//! the compressed-BVH scenes, traversals and leak counts (`cwbvh`), and the
//! binary BVH and ray sets of the section `traversal` (`traversal`); and
//! the token of the AVX-512 floors (`avx512`).

#[cfg(target_arch = "x86_64")]
pub mod avx512;
pub mod cwbvh;
pub mod traversal;
