//! The `leak` scene: the meshes of every scene are closed and wound
//! outwards, every counted ray really passes exactly through an interior
//! vertex of the closed mesh, the watertight kernel stops every one of
//! them there, and Moller-Trumbore lets some through (or the scene would
//! prove nothing).

use std::collections::{HashMap, HashSet};

use rayhit::glam::Vec3;
use rayhit::{Camera, PreparedRay, Side};
use rayhit_demo::instances::slab;
use rayhit_demo::leak::{FAR, NEAR, PatchKernel, leak_scene};
use rayhit_demo::mesh::{Kernel, Mesh, icosphere, signed_volume, torus};

/// True when every directed edge of the mesh has exactly one twin running
/// the other way: closed, and wound consistently.
fn closed_and_consistent(mesh: &Mesh) -> bool {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for &[a, b, c] in &mesh.indices {
        for e in [(a, b), (b, c), (c, a)] {
            *edges.entry(e).or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

#[test]
fn the_meshes_are_closed_and_wound_outwards() {
    let scene = leak_scene(16, 12);
    for mesh in [
        icosphere(Vec3::ZERO, 1.0, 2),
        torus(1.0, 0.3, 12, 8),
        slab(),
        scene.mesh.mesh.clone(),
    ] {
        assert!(closed_and_consistent(&mesh));
        assert!(signed_volume(&mesh) > 0.0);
    }
    // And the check can fail: one triangle turned over.
    let mut broken = icosphere(Vec3::ZERO, 1.0, 1);
    broken.indices[0].swap(1, 2);
    assert!(!closed_and_consistent(&broken));
}

#[test]
fn the_watertight_kernel_leaks_no_ray_and_moller_trumbore_does() {
    let scene = leak_scene(64, 48);
    let mesh = &scene.mesh.mesh;
    assert!(closed_and_consistent(mesh));
    let vertices: HashMap<[u32; 3], u32> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(k, p)| (p.to_array().map(f32::to_bits), k as u32))
        .collect();
    let mut triangles_at = vec![0u32; mesh.positions.len()];
    for tri in &mesh.indices {
        for &k in tri {
            triangles_at[k as usize] += 1;
        }
    }
    // Every counted ray passes exactly through a vertex of the mesh (its
    // point at t = NEAR, computed in f64 where the product is exact) with a
    // full fan of six triangles around it, all facing the ray: it crosses
    // into the solid there.
    let mut counted = HashSet::new();
    for j in 0..48 {
        for i in 0..64 {
            if !scene.must_enter(i, j) {
                continue;
            }
            let ray = scene.camera.pixel_ray(i, j);
            assert_eq!(ray.origin, Vec3::ZERO);
            let at_near = ray.dir.as_dvec3() * f64::from(NEAR);
            let vertex = at_near.as_vec3();
            assert_eq!(vertex.as_dvec3(), at_near, "NEAR * dir is exact");
            let k = vertices[&vertex.to_array().map(f32::to_bits)];
            assert_eq!(triangles_at[k as usize], 6);
            for tri in mesh.indices.iter().filter(|t| t.contains(&k)) {
                let [a, b, c] = tri.map(|v| mesh.positions[v as usize].as_dvec3());
                assert!((b - a).cross(c - a).dot(ray.dir.as_dvec3()) < 0.0);
            }
            counted.insert((i, j));
        }
    }
    // The middle half of the image, less the border of the tile.
    assert_eq!(counted.len(), 31 * 23);

    let reports = Kernel::ALL.map(|kernel| scene.run(kernel, &|| {}));
    let [watertight, moller_trumbore] = &reports;
    for r in &reports {
        assert_eq!(r.entering as usize, counted.len());
        assert!(r.escaped <= r.leaked && r.leaked <= r.entering);
    }
    assert_eq!(watertight.leaked, 0);
    assert!(
        moller_trumbore.leaked > 0,
        "the scene should catch Moller-Trumbore out"
    );

    // The watertight kernel stops each ray where it enters: at t = NEAR.
    for &(i, j) in &counted {
        let ray = scene.camera.pixel_ray(i, j);
        let (hit, _) = scene
            .mesh
            .intersect(
                &ray,
                &PreparedRay::new(&ray),
                f32::INFINITY,
                Kernel::Watertight,
                false,
            )
            .expect("a hit");
        assert_eq!(hit.side, Side::Front);
        assert!((hit.t - NEAR).abs() < 1e-5 * NEAR, "t = {}", hit.t);
        assert!(hit.t < FAR);
    }
}

#[test]
fn the_patch_tile_leaks_no_ray() {
    let scene = leak_scene(64, 48);
    let tile = &scene.patches;
    // Every face of the shell is one patch: a pair of triangles each.
    assert_eq!(2 * tile.patches.len(), scene.mesh.mesh.indices.len());
    // The curved surfaces' cells are not planar.
    let bent = tile
        .patches
        .iter()
        .filter(|p| {
            let n = (p.p10 - p.p00).cross(p.p01 - p.p00).as_dvec3();
            (p.p11 - p.p00).as_dvec3().dot(n).abs() > 1e-9 * n.length()
        })
        .count();
    assert!(bent > tile.patches.len() / 2, "{bent}");
    let reports = PatchKernel::ALL.map(|kernel| scene.run_patches(kernel, &|| {}));
    for r in &reports {
        println!(
            "{}: leaked {} of {} ({} through)",
            r.name, r.leaked, r.entering, r.escaped
        );
        assert_eq!(r.entering, 31 * 23);
    }
    let [rayhit, _textbook] = &reports;
    assert_eq!(rayhit.leaked, 0);
    // Every ray the triangles stop, the patches stop too, from outside.
    let triangles = scene.run(Kernel::Watertight, &|| {});
    assert_eq!(rayhit.outcomes, triangles.outcomes);
}
