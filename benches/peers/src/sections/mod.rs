//! The table's sections, a file each: the rows a section holds, in the
//! order the table prints them, and the data they run on beyond the
//! shared workloads (`crate::data`). `--only NAME` keeps the sections
//! whose name contains NAME.
//!
//! - `boxes`: `box`, ray `i` against box `i`;
//! - `triangles`: `triangle`, ray `i` against triangle `i`;
//! - `spheres`: `sphere`, ray `i` against sphere `i`;
//! - `quads`: `quad`, ray `i` against parallelogram `i`;
//! - `patches`: `patch`, ray `i` against bilinear patch `i`;
//! - `groups`: `box x8` and `triangle x8`, a ray against a group of eight,
//!   scalar and batched, with the batch floors;
//! - `sweep`: `box sweep` and `triangle sweep`, one ray against the first
//!   N shapes;
//! - `cwbvh`: `cwbvh (per ray)`, closest hit through obvhs's BVH, and the
//!   `--leaks` table;
//! - `camera`: `camera` and `camera differentials`, with the camera
//!   owned or reached by reference;
//! - `camera_refs`: the textbook and floor rows of the section `camera`;
//! - `instance`: `instance`, the mappings in and out of an instance;
//! - `traversal`: `traversal`, whole closest-hit and any-hit traversals
//!   of a CWBVH and a binary BVH per ray, rayhit's plain calls against
//!   obvhs's own, with the counts after the table and the
//!   `--traversal-leaks` table.

pub mod boxes;
pub mod camera;
pub mod camera_refs;
pub mod cwbvh;
pub mod groups;
pub mod instance;
pub mod patches;
pub mod quads;
pub mod spheres;
pub mod sweep;
pub mod traversal;
pub mod triangles;
