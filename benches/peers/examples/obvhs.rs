//! Watertight traversal of a compressed wide BVH that another crate built:
//! obvhs's CWBVH over closed meshes, its nodes read in place by `rayhit`'s
//! `QuantizedChildren::clip`, `Triangle::hit` on a `PreparedRay` in the
//! leaves, in obvhs's own traversal order. Prints, for rays aimed exactly
//! at vertices and edge midpoints, how many slip through with obvhs's
//! kernels and with rayhit's.
//!
//! ```sh
//! cargo run --release --manifest-path benches/peers/Cargo.toml --example obvhs
//! ```
//!
//! The traversal itself is `Scene::rayhit_closest` in `src/cwbvh.rs`.

use rayhit_peers::cwbvh;

fn main() {
    for mesh in [cwbvh::Mesh::torus(250, 200), cwbvh::Mesh::icosphere(6)] {
        let rays = cwbvh::LeakRays::new(&mesh, 100_000, 7);
        let mut scene = cwbvh::Scene::new(&mesh);
        // rayhit's node test is conservative for the boxes it decodes; a
        // traversal is watertight when those contain the geometry, which
        // holds for obvhs's quantization here (else
        // `QuantizedChildren::quantize` rewrites the bytes in place).
        let (children, bad) = scene.check_quantization(true);
        println!(
            "{} ({} triangles; {children} child boxes, {bad} re-quantized; {} rays from inside, {} from outside):",
            mesh.name,
            mesh.faces.len(),
            rays.inside.len(),
            rays.outside.len()
        );
        for (name, leaks) in [
            (
                "obvhs node and triangle tests",
                cwbvh::count_leaks(&rays, |r| scene.obvhs_closest(r)),
            ),
            (
                "obvhs node test, rayhit Triangle::hit",
                cwbvh::count_leaks(&rays, |r| scene.obvhs_nodes_rayhit_triangles(r)),
            ),
            (
                "rayhit QuantizedChildren::clip and Triangle::hit",
                cwbvh::count_leaks(&rays, |r| cwbvh::rayhit_one(&scene, r)),
            ),
        ] {
            println!(
                "  {name:48} {:6} from inside hit nothing, {:5} from outside passed their target",
                leaks.inside_missed, leaks.passed_through
            );
        }
    }
}
