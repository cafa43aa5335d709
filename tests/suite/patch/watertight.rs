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

use rayhit::glam::{DVec3, Vec3};

use crate::quad::watertight::{Kind, check};

#[test]
fn closed_patch_meshes_have_no_crack_and_no_leak() {
    for counts in [
        check::<Vec3>("f32", Kind::Patches),
        check::<DVec3>("f64", Kind::Patches),
    ] {
        assert!(
            counts.from_inside > 1000 && counts.from_outside > 1000,
            "{counts:?}"
        );
        assert_eq!(
            (
                counts.leaks,
                counts.one_hit_leaks,
                counts.one_hit_repeats,
                counts.cracks,
                counts.one_hit_cracks
            ),
            (0, 0, 0, 0, 0),
            "{counts:?}"
        );
    }
}
