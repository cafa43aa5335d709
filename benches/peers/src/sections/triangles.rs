//! The section `triangle`: ray `i` against triangle `i` on each triangle
//! workload, rayhit's tests next to the textbook tests, their floors,
//! `bvh`'s and `parry3d`'s.

use parry3d::query::RayCast;
use rayhit::{EdgeRule, Intersect, Interval, Side, ray_triangle};

use crate::data::TriData;
use crate::floors::{
    floor_mt, floor_watertight, floor_watertight_prepared, textbook_mt, textbook_watertight,
};
use crate::harness::loops::{agree, pairwise, t_sum};
use crate::harness::{INF, Kernel, kernel};
use crate::peers::bvh_hits;

/// Pairwise triangle kernels: ray `i` against triangle `i`.
pub fn triangle_kernels<'a>(d: &'a TriData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<Option<Side>> = (0..n)
        .map(|i| ray_triangle(&d.rays[i], &d.tris[i], INF).map(|h| h.side))
        .collect();
    let bvh_agree = agree(
        ours.iter().map(|s| *s == Some(Side::Front)),
        (0..n).map(|i| bvh_hits(&d.bvh_rays[i], &d.bvh_tris[i]).is_some()),
    );
    let parry_agree = agree(
        ours.iter().map(Option::is_some),
        (0..n).map(|i| {
            d.parry_tris[i]
                .cast_local_ray(&d.parry_rays[i], f32::MAX, true)
                .is_some()
        }),
    );
    let mt_agree = agree(
        ours.iter().map(Option::is_some),
        (0..n).map(|i| textbook_mt(&d.rays[i], &d.tris[i]).is_some()),
    );
    // (Against `Triangle::moller_trumbore`, whose answers this floor must
    // give.)
    let floor_mt_agree = agree(
        (0..n).map(|i| d.tris[i].moller_trumbore(&d.rays[i], INF).is_some()),
        (0..n).map(|i| floor_mt(&d.rays[i], &d.tris[i], INF).is_some()),
    );
    let woop_agree = agree(
        ours.iter().map(Option::is_some),
        (0..n).map(|i| textbook_watertight(&d.rays[i], &d.tris[i]).is_some()),
    );
    let floor_agree = agree(
        ours.iter().map(Option::is_some),
        (0..n).map(|i| {
            floor_watertight_prepared::<false>(&d.floor_rays[i], &d.tris[i], INF).is_some()
        }),
    );
    let (w, sec) = (d.name, "triangle");
    let all = Interval::up_to(INF).expect("a valid interval");
    out.extend([
        kernel(
            sec,
            "rayhit ray_triangle",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.tris, |r, t| {
                t_sum(ray_triangle(r, t, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.tris, |r, t| {
                t_sum(t.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay, Vec3A",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared_a, &d.tris_a, |r, t| {
                t_sum(t.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay, (0, inf]",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.tris, move |r, t| {
                t_sum(t.hit(r, all).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, (0, inf]",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.tris, move |r, t| {
                t_sum(t.hit(r, all).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, EdgeRule::OneHit, (0, inf]",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.tris, move |r, t| {
                t_sum(t.hit(r, (all, EdgeRule::OneHit)).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay, EdgeRule::OneHit, (0, inf]",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.tris, move |r, t| {
                t_sum(t.hit(r, (all, EdgeRule::OneHit)).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::moller_trumbore",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.tris, |r, t| {
                t_sum(t.moller_trumbore(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "textbook Moller-Trumbore (two-sided)",
            w,
            n,
            Some(mt_agree),
            pairwise(&d.order, &d.rays, &d.tris, |r, t| t_sum(textbook_mt(r, t))),
        ),
        kernel(
            sec,
            "floor: textbook Moller-Trumbore + the guarantee's checks",
            w,
            n,
            Some(floor_mt_agree),
            pairwise(&d.order, &d.rays, &d.tris, |r, t| {
                t_sum(floor_mt(r, t, INF))
            }),
        ),
        kernel(
            sec,
            "floor: textbook watertight, shear per call",
            w,
            n,
            Some(woop_agree),
            pairwise(&d.order, &d.rays, &d.tris, |r, t| {
                t_sum(textbook_watertight(r, t))
            }),
        ),
        kernel(
            sec,
            "floor: textbook watertight + the guarantee's checks, shear per call",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.tris, |r, t| {
                t_sum(floor_watertight(r, t, INF))
            }),
        ),
        kernel(
            sec,
            "floor: textbook watertight, prepared, four lanes",
            w,
            n,
            Some(floor_agree),
            pairwise(&d.order, &d.floor_rays, &d.tris, |r, t| {
                t_sum(floor_watertight_prepared::<false>(r, t, INF).map(|h| h.0))
            }),
        ),
        kernel(
            sec,
            "floor: textbook watertight + the guarantee's checks, prepared, four lanes",
            w,
            n,
            None,
            pairwise(&d.order, &d.floor_rays, &d.tris, |r, t| {
                t_sum(floor_watertight_prepared::<true>(r, t, INF).map(|h| h.0))
            }),
        ),
        kernel(
            sec,
            "bvh intersects_triangle (front only)",
            w,
            n,
            Some(bvh_agree),
            pairwise(&d.order, &d.bvh_rays, &d.bvh_tris, |r, t| {
                t_sum(bvh_hits(r, t))
            }),
        ),
        kernel(
            sec,
            "parry3d Triangle::cast_local_ray",
            w,
            n,
            Some(parry_agree),
            pairwise(&d.order, &d.parry_rays, &d.parry_tris, |r, t| {
                t_sum(t.cast_local_ray(r, f32::MAX, true))
            }),
        ),
    ]);
}
