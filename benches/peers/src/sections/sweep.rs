//! The sections `box sweep` and `triangle sweep`: one ray against the
//! first N boxes, every one tested, and through the first N triangles for
//! the nearest hit, for N from 8 to 1024: rayhit's tests one at a time and
//! in batches next to `bvh`'s.

use rayhit::batch::{AabbBatch, TriangleBatch};
use rayhit::glam::Vec3;
use rayhit::{Aabb, Bounds, Intersect, IntersectLanes, PreparedRay, Triangle};
use rayhit_testkit::workloads::{box_sweep, triangle_sweep};

use crate::harness::loops::{BatchRows, every, nearest, simd};
use crate::harness::{INF, Kernel, kernel};
use crate::peers::{BvhTri, bvh_box, bvh_hits, bvh_ray, bvh_tri};

/// The sweep's sizes N.
pub const SWEEP: [usize; 6] = [8, 16, 64, 256, 512, 1024];

/// One ray against the first N boxes (all tested) and the first N
/// triangles (nearest hit, `t_max` shrinking as hits are found; `bvh` has
/// no `t_max`, so it keeps the smallest distance).
pub struct Sweep {
    rays: Vec<PreparedRay>,
    bvh_rays: Vec<bvh::ray::Ray<f32, 3>>,
    boxes: Vec<Aabb>,
    bvh_boxes: Vec<bvh::aabb::Aabb<f32, 3>>,
    b8: Vec<Vec<AabbBatch<Vec3, 8>>>,
    b16: Vec<Vec<AabbBatch<Vec3, 16>>>,
    t_rays: Vec<PreparedRay>,
    t_bvh_rays: Vec<bvh::ray::Ray<f32, 3>>,
    tris: Vec<Triangle>,
    bvh_tris: Vec<BvhTri>,
    t8: Vec<Vec<TriangleBatch<Vec3, 8>>>,
    t16: Vec<Vec<TriangleBatch<Vec3, 16>>>,
}

impl Sweep {
    pub fn new() -> Self {
        let (rays, boxes) = box_sweep();
        let (t_rays, tris) = triangle_sweep();
        let b8 = SWEEP
            .iter()
            .map(|&n| {
                boxes[..n]
                    .chunks(8)
                    .map(|c| AabbBatch::from_slice(c).expect("8"))
                    .collect()
            })
            .collect();
        let b16 = SWEEP
            .iter()
            .map(|&n| {
                boxes[..n]
                    .chunks(16)
                    .map(|c| AabbBatch::from_slice(c).expect("16"))
                    .collect()
            })
            .collect();
        let t8 = SWEEP
            .iter()
            .map(|&n| {
                tris[..n]
                    .chunks(8)
                    .map(|c| TriangleBatch::from_slice(c).expect("8"))
                    .collect()
            })
            .collect();
        let t16 = SWEEP
            .iter()
            .map(|&n| {
                tris[..n]
                    .chunks(16)
                    .map(|c| TriangleBatch::from_slice(c).expect("16"))
                    .collect()
            })
            .collect();
        Self {
            bvh_rays: rays.iter().map(bvh_ray).collect(),
            rays: rays.iter().map(PreparedRay::new).collect(),
            bvh_boxes: boxes.iter().map(bvh_box).collect(),
            boxes,
            b8,
            b16,
            t_bvh_rays: t_rays.iter().map(bvh_ray).collect(),
            t_rays: t_rays.iter().map(PreparedRay::new).collect(),
            bvh_tris: tris.iter().map(bvh_tri).collect(),
            tris,
            t8,
            t16,
        }
    }
}

pub fn sweep_kernels<'a>(s: &'a Sweep, out: &mut Vec<Kernel<'a>>) {
    for (i, &n) in SWEEP.iter().enumerate() {
        let w = format!("N = {n}");
        let (w, sec) = (w.as_str(), "box sweep");
        let tests = s.rays.len() * n;
        let count = |m: u32| u64::from(m);
        out.extend([
            kernel(
                sec,
                "rayhit Aabb::clip, PreparedRay",
                w,
                tests,
                None,
                every(&s.rays, &s.boxes[..n], |r, x| {
                    u64::from(x.clip(r, INF).is_some())
                }),
            ),
            kernel(
                sec,
                "rayhit AabbBatch::clip, 8 lanes",
                w,
                tests,
                None,
                every(&s.rays, &s.b8[i], move |r, x| count(x.clip(r, INF).mask)),
            ),
            kernel(
                sec,
                "rayhit AabbBatch::clip, 16 lanes",
                w,
                tests,
                None,
                every(&s.rays, &s.b16[i], move |r, x| count(x.clip(r, INF).mask)),
            ),
            kernel(
                sec,
                "rayhit AabbBatch::clip, 8 lanes, with_simd",
                w,
                tests,
                None,
                simd(BatchRows {
                    rays: &s.rays,
                    batches: &s.b8[i],
                    per_ray: 0,
                }),
            ),
            kernel(
                sec,
                "rayhit AabbBatch::clip, 16 lanes, with_simd",
                w,
                tests,
                None,
                simd(BatchRows {
                    rays: &s.rays,
                    batches: &s.b16[i],
                    per_ray: 0,
                }),
            ),
            kernel(
                sec,
                "bvh intersects_aabb",
                w,
                tests,
                None,
                every(&s.bvh_rays, &s.bvh_boxes[..n], |r, x| {
                    u64::from(r.intersects_aabb(x))
                }),
            ),
        ]);
        let sec = "triangle sweep";
        let tests = s.t_rays.len() * n;
        out.extend([
            kernel(
                sec,
                "rayhit Triangle::hit, PreparedRay",
                w,
                tests,
                None,
                nearest(&s.t_rays, &s.tris[..n], |r, x, t_max| {
                    x.hit(r, t_max).map(|h| h.t)
                }),
            ),
            kernel(
                sec,
                "rayhit TriangleBatch::hit, 8 lanes",
                w,
                tests,
                None,
                nearest(&s.t_rays, &s.t8[i], |r, x, t_max| {
                    x.hit(r, t_max).nearest().map(|(_, h)| h.t)
                }),
            ),
            kernel(
                sec,
                "rayhit TriangleBatch::hit, 16 lanes",
                w,
                tests,
                None,
                nearest(&s.t_rays, &s.t16[i], |r, x, t_max| {
                    x.hit(r, t_max).nearest().map(|(_, h)| h.t)
                }),
            ),
            // bvh's test has no limit to cull with: it computes every hit.
            kernel(
                sec,
                "bvh intersects_triangle (front only)",
                w,
                tests,
                None,
                nearest(&s.t_bvh_rays, &s.bvh_tris[..n], |r, x, _| bvh_hits(r, x)),
            ),
        ]);
    }
}
