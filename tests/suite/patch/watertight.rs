//! Closed meshes of bilinear patches with no crack and no leak: the quad
//! suite's cube of `n x n` patches a face, its torus of twisted (so
//! non-planar) patches, and its cube whose faces mix one patch, four
//! patches and two triangles, the T-junctions between them closed by
//! zero-area triangles. Scales `1e-3` to `1e3`, offsets to `1e5`.
//!
//! Rays from inside, aimed at the meshes' corners, edge midpoints and
//! points of the patches, must each hit the mesh, with both edge rules (a
//! miss is a leak); on the cubes, rays from outside through the same
//! points must hit too (a miss is a crack), and with the one-hit rule a
//! ray from inside is reported by exactly one face. The textbook patch
//! test (Reshetov's, with `t > 0`) is counted on the same rays.

use crate::quad::watertight::{Kind, assert_closed};

#[test]
fn closed_patch_meshes_have_no_crack_and_no_leak() {
    assert_closed(Kind::Patches);
}
