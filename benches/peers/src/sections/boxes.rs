//! The section `box`: ray `i` against box `i` on each box workload,
//! rayhit's tests next to the plain slab test, `bvh`'s and `parry3d`'s.

use parry3d::query::RayCast;
use rayhit::{Bounds, ray_aabb};

use crate::data::BoxData;
use crate::floors::plain_slab;
use crate::harness::loops::{agree, pairwise};
use crate::harness::{INF, Kernel, kernel};

/// Pairwise box kernels: ray `i` against box `i`.
pub fn box_kernels<'a>(d: &'a BoxData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<bool> = (0..n)
        .map(|i| ray_aabb(&d.rays[i], &d.boxes[i], INF).is_some())
        .collect();
    let bvh_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| d.bvh_rays[i].intersects_aabb(&d.bvh_boxes[i])),
    );
    let parry_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| {
            d.parry_boxes[i]
                .cast_local_ray(&d.parry_rays[i], f32::MAX, true)
                .is_some()
        }),
    );
    let plain_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| plain_slab(&d.plain[i], &d.boxes[i])),
    );
    let (w, sec) = (d.name, "box");
    let hit = |x: Option<(f32, f32)>| u64::from(x.is_some());
    out.extend([
        kernel(
            sec,
            "rayhit ray_aabb",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.boxes, move |r, b| {
                hit(ray_aabb(r, b, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit Aabb::clip, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.boxes, move |r, b| {
                hit(b.clip(r, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit ValidAabb::clip, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.valid, move |r, b| {
                hit(b.clip(r, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit Aabb::clip, PreparedRay, Vec3A",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared_a, &d.boxes_a, move |r, b| {
                hit(b.clip(r, INF))
            }),
        ),
        kernel(
            sec,
            "textbook plain slab",
            w,
            n,
            Some(plain_agree),
            pairwise(&d.order, &d.plain, &d.boxes, |r, b| {
                u64::from(plain_slab(r, b))
            }),
        ),
        kernel(
            sec,
            "bvh intersects_aabb",
            w,
            n,
            Some(bvh_agree),
            pairwise(&d.order, &d.bvh_rays, &d.bvh_boxes, |r, b| {
                u64::from(r.intersects_aabb(b))
            }),
        ),
        kernel(
            sec,
            "parry3d Aabb::cast_local_ray",
            w,
            n,
            Some(parry_agree),
            pairwise(&d.order, &d.parry_rays, &d.parry_boxes, |r, b| {
                u64::from(b.cast_local_ray(r, f32::MAX, true).is_some())
            }),
        ),
    ]);
}
