//! The section `cwbvh (per ray)`: closest hit through obvhs's compressed
//! wide BVH (`rayhit_peers::cwbvh`), obvhs's node and triangle tests next
//! to rayhit's, and the `--leaks` table of how many exactly aimed rays
//! slip through each pipeline.

use rayhit::batch::with_simd;
use rayhit::{PreparedRay, Ray};
use rayhit_peers::cwbvh;

use crate::harness::loops::agree;
use crate::harness::{INF, Kernel, kernel};

/// One mesh's CWBVH, its leak rays, and both pipelines' inputs.
pub struct CwbvhData {
    name: &'static str,
    /// obvhs's nodes as built, for obvhs's own pipeline.
    obvhs: cwbvh::Scene,
    /// The same build with the child bytes that rayhit's decoding would
    /// not contain rewritten by `QuantizedChildren::quantize`, for
    /// rayhit's.
    fixed: cwbvh::Scene,
    rays: Vec<Ray>,
    prepared: Vec<(PreparedRay, rayhit::glam::Vec3A)>,
}

impl CwbvhData {
    pub fn new(mesh: &cwbvh::Mesh, count: usize) -> Self {
        let obvhs = cwbvh::Scene::new(mesh);
        let mut fixed = cwbvh::Scene::new(mesh);
        fixed.check_quantization(true);
        let leak = cwbvh::LeakRays::new(mesh, count, 7);
        let rays: Vec<Ray> = leak.inside.into_iter().chain(leak.outside).collect();
        let prepared = rays
            .iter()
            .map(|r| (PreparedRay::new(r), r.dir.into()))
            .collect();
        Self {
            name: mesh.name,
            obvhs,
            fixed,
            rays,
            prepared,
        }
    }
}

/// Closest hit through a CWBVH: obvhs's own kernels against rayhit's, on
/// the same rays (half from inside the mesh, half from outside, all aimed
/// exactly at vertices or edge midpoints).
pub fn cwbvh_kernels<'a>(d: &'a CwbvhData, out: &mut Vec<Kernel<'a>>) {
    let (w, sec, n) = (d.name, "cwbvh (per ray)", d.rays.len());
    let agreement = agree(
        d.rays.iter().map(|r| cwbvh::rayhit_one(&d.fixed, r) < INF),
        d.rays.iter().map(|r| d.obvhs.obvhs_closest(r) < INF),
    );
    out.extend([
        kernel(
            sec,
            "rayhit QuantizedChildren::clip + Triangle::hit, with_simd",
            w,
            n,
            None,
            move || {
                with_simd(cwbvh::RayhitPipeline {
                    scene: &d.fixed,
                    rays: &d.prepared,
                })
            },
        ),
        kernel(
            sec,
            "obvhs CwBvh::ray_traverse (its node and triangle tests)",
            w,
            n,
            Some(agreement),
            move || {
                d.rays
                    .iter()
                    .map(|r| u64::from(d.obvhs.obvhs_closest(r).to_bits()))
                    .fold(0u64, u64::wrapping_add)
            },
        ),
    ]);
}

/// One row of a leak table: the mesh, its ray counts, the pipeline `name`
/// and its leaks `l`.
pub fn print_leak_row(mesh: &cwbvh::Mesh, rays: &cwbvh::LeakRays, name: &str, l: cwbvh::Leaks) {
    println!(
        "| {} | {} | {} | {} | {name} | {} | {} |",
        mesh.name,
        mesh.faces.len(),
        rays.inside.len(),
        rays.outside.len(),
        l.inside_missed,
        l.passed_through
    );
}

/// `--leaks`: the leak and pass-through counts of every pipeline on every
/// mesh, and how many of obvhs's quantized child boxes rayhit's decoding
/// had to widen.
pub fn print_leaks(meshes: &[cwbvh::Mesh], count: usize) {
    println!(
        "| mesh | triangles | rays from inside | rays from outside | pipeline | inside rays that hit nothing | outside rays past their target |"
    );
    println!("| --- | ---: | ---: | ---: | --- | ---: | ---: |");
    for mesh in meshes {
        let rays = cwbvh::LeakRays::new(mesh, count, 7);
        let obvhs = cwbvh::Scene::new(mesh);
        let mut fixed = cwbvh::Scene::new(mesh);
        let (children, bad) = fixed.check_quantization(true);
        let row = |name: &str, l: cwbvh::Leaks| print_leak_row(mesh, &rays, name, l);
        row(
            "obvhs nodes, obvhs triangles",
            cwbvh::count_leaks(&rays, |r| obvhs.obvhs_closest(r)),
        );
        row(
            "obvhs nodes, rayhit Triangle::hit",
            cwbvh::count_leaks(&rays, |r| obvhs.obvhs_nodes_rayhit_triangles(r)),
        );
        row(
            "rayhit QuantizedChildren::clip + Triangle::hit",
            cwbvh::count_leaks(&rays, |r| cwbvh::rayhit_one(&fixed, r)),
        );
        println!(
            "({}: {bad} of {children} occupied child boxes as obvhs quantized them were not contained in rayhit's decoding and were re-quantized with QuantizedChildren::quantize.)",
            mesh.name
        );
    }
}
