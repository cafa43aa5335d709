//! The sections `box x8` and `triangle x8`: ray `i` against shapes
//! `8i..8i+8`, one at a time and in batches of four and eight, next to
//! `bvh` and `parry3d`, and the eight-lane triangle batches next to their
//! AVX2 floors.

use parry3d::query::RayCast;
use rayhit::batch::{AabbBatch, TriangleBatch};
use rayhit::glam::Vec3;
use rayhit::{Bounds, Intersect, IntersectLanes, Interval, Side, ray_aabb, ray_triangle};
use rayhit_testkit::workloads::GROUP;

use crate::data::{BoxData, Groups, TriData};
#[cfg(target_arch = "x86_64")]
use crate::floors::batch as floor_batch;
use crate::harness::loops::{BatchRows, agree, batch_t_sum, chunked, lanes_t_sum, simd, t_sum};
use crate::harness::{INF, Kernel, kernel};
use crate::peers::bvh_hits;

/// The floors of the eight-lane triangle batches (`floors::batch`), in the
/// "triangle x8" section next to the batches they bound, with how often
/// their lanes agree with rayhit's (all but the rare lanes the floors leave
/// to stubs).
#[cfg(target_arch = "x86_64")]
pub fn batch_floor_kernels<'a>(
    t: &'a TriData,
    tb8: &'a [TriangleBatch<Vec3, 8>],
    fb8: &'a [floor_batch::FloorBatch],
    out: &mut Vec<Kernel<'a>>,
) {
    use floor_batch::{Question, floor_batch};
    if !floor_batch::available() {
        return;
    }
    let sec = "triangle x8";
    let all = Interval::up_to(INF).expect("(0, inf]");
    let per_ray = GROUP / 8;
    let lanes = |m: u32| (0..8).map(move |l| m >> l & 1 != 0);
    let floor_mask =
        |q, i: usize| floor_batch(q, &t.floor_rays[i / per_ray], &fb8[i], 0.0, INF).mask;
    let agree_with = |q, ours: &dyn Fn(usize) -> u32| {
        agree(
            (0..fb8.len()).flat_map(|i| lanes(ours(i))),
            (0..fb8.len()).flat_map(|i| lanes(floor_mask(q, i))),
        )
    };
    let plain = agree_with(Question::UpTo, &|i| {
        tb8[i].hit(&t.prepared[i / per_ray], INF).mask
    });
    let within = agree_with(Question::Within, &|i| {
        tb8[i].hit(&t.prepared[i / per_ray], all).mask
    });
    let w = "groups of 8";
    let row = |q, name: &str, agreement| {
        kernel(
            sec,
            name,
            w,
            t.tris.len(),
            Some(agreement),
            chunked(&t.floor_rays, fb8, per_ray, move |r, x| {
                let h = floor_batch(q, r, x, 0.0, INF);
                lanes_t_sum(h.mask, &h.t)
            }),
        )
    };
    out.extend([
        row(
            Question::UpTo,
            "floor: batch, 8 lanes, AVX2 + the guarantee's checks",
            plain,
        ),
        row(
            Question::Within,
            "floor: batch_in, 8 lanes, AVX2 + the guarantee's checks, (0, inf]",
            within,
        ),
    ]);
}

/// The floor of a plain call into an eight-box batch (`floors::boxes8`),
/// in the "box x8" section beside `AabbBatch::meets`, with how often its
/// lanes agree with rayhit's.
#[cfg(target_arch = "x86_64")]
pub fn box_floor_kernels<'a>(g: &'a Groups, out: &mut Vec<Kernel<'a>>) {
    use crate::floors::boxes8::meets;
    use rayhit_peers::avx512::Avx512;
    let Some(isa) = Avx512::detect() else {
        return;
    };
    let b = &g.gb;
    let per_ray = GROUP / 8;
    let lanes = |m: u32| (0..8).map(move |l| m >> l & 1 != 0);
    let agreement = agree(
        (0..g.bb8.len()).flat_map(|i| lanes(g.bb8[i].meets(&b.prepared[i / per_ray], INF))),
        (0..g.fbox8.len())
            .flat_map(|i| lanes(meets(isa, &g.fbox_rays[i / per_ray], &g.fbox8[i], INF))),
    );
    out.push(kernel(
        "box x8",
        "floor: a call per batch into an AVX-512 slab test, mask only",
        "groups of 8",
        b.boxes.len(),
        Some(agreement),
        chunked(&g.fbox_rays, &g.fbox8, per_ray, move |r, x| {
            u64::from(meets(isa, r, x, INF))
        }),
    ));
}

/// Groups: ray `i` against shapes `8i..8i+8`, scalar and batched.
pub fn group_kernels<'a>(
    b: &'a BoxData,
    bb4: &'a [AabbBatch<Vec3, 4>],
    bb8: &'a [AabbBatch<Vec3, 8>],
    t: &'a TriData,
    tb4: &'a [TriangleBatch<Vec3, 4>],
    tb8: &'a [TriangleBatch<Vec3, 8>],
    out: &mut Vec<Kernel<'a>>,
) {
    let nb = b.boxes.len();
    let group = |i: usize| i / GROUP;
    let ours: Vec<bool> = (0..nb)
        .map(|i| ray_aabb(&b.rays[group(i)], &b.boxes[i], INF).is_some())
        .collect();
    let bvh_agree = agree(
        ours.iter().copied(),
        (0..nb).map(|i| b.bvh_rays[group(i)].intersects_aabb(&b.bvh_boxes[i])),
    );
    let parry_agree = agree(
        ours.iter().copied(),
        (0..nb).map(|i| {
            b.parry_boxes[i]
                .cast_local_ray(&b.parry_rays[group(i)], f32::MAX, true)
                .is_some()
        }),
    );
    let (w, sec) = ("groups of 8", "box x8");
    out.extend([
        kernel(
            sec,
            "rayhit Aabb::clip, PreparedRay",
            w,
            nb,
            None,
            chunked(&b.prepared, &b.boxes, GROUP, |r, x| {
                u64::from(x.clip(r, INF).is_some())
            }),
        ),
        kernel(
            sec,
            "rayhit AabbBatch::clip, 4 lanes",
            w,
            nb,
            None,
            chunked(&b.prepared, bb4, GROUP / 4, |r, x| {
                u64::from(x.clip(r, INF).mask)
            }),
        ),
        kernel(
            sec,
            "rayhit AabbBatch::clip, 8 lanes",
            w,
            nb,
            None,
            chunked(&b.prepared, bb8, GROUP / 8, |r, x| {
                u64::from(x.clip(r, INF).mask)
            }),
        ),
        kernel(
            sec,
            "rayhit AabbBatch::meets, 8 lanes",
            w,
            nb,
            None,
            chunked(&b.prepared, bb8, GROUP / 8, |r, x| {
                u64::from(x.meets(r, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit AabbBatch::clip, 8 lanes, with_simd",
            w,
            nb,
            None,
            simd(BatchRows {
                rays: &b.prepared,
                batches: bb8,
                per_ray: GROUP / 8,
            }),
        ),
        kernel(
            sec,
            "bvh intersects_aabb",
            w,
            nb,
            Some(bvh_agree),
            chunked(&b.bvh_rays, &b.bvh_boxes, GROUP, |r, x| {
                u64::from(r.intersects_aabb(x))
            }),
        ),
        kernel(
            sec,
            "parry3d Aabb::cast_local_ray",
            w,
            nb,
            Some(parry_agree),
            chunked(&b.parry_rays, &b.parry_boxes, GROUP, |r, x| {
                u64::from(x.cast_local_ray(r, f32::MAX, true).is_some())
            }),
        ),
    ]);

    let nt = t.tris.len();
    let ours: Vec<Option<Side>> = (0..nt)
        .map(|i| ray_triangle(&t.rays[group(i)], &t.tris[i], INF).map(|h| h.side))
        .collect();
    let bvh_agree = agree(
        ours.iter().map(|s| *s == Some(Side::Front)),
        (0..nt).map(|i| bvh_hits(&t.bvh_rays[group(i)], &t.bvh_tris[i]).is_some()),
    );
    let parry_agree = agree(
        ours.iter().map(Option::is_some),
        (0..nt).map(|i| {
            t.parry_tris[i]
                .cast_local_ray(&t.parry_rays[group(i)], f32::MAX, true)
                .is_some()
        }),
    );
    let sec = "triangle x8";
    let all = Interval::up_to(INF).expect("(0, inf]");
    out.extend([
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay",
            w,
            nt,
            None,
            chunked(&t.prepared, &t.tris, GROUP, |r, x| {
                t_sum(x.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit TriangleBatch::hit, 4 lanes",
            w,
            nt,
            None,
            chunked(&t.prepared, tb4, GROUP / 4, |r, x| {
                batch_t_sum(&x.hit(r, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit TriangleBatch::hit, 8 lanes",
            w,
            nt,
            None,
            chunked(&t.prepared, tb8, GROUP / 8, |r, x| {
                batch_t_sum(&x.hit(r, INF))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::hit, PreparedRay, (0, inf]",
            w,
            nt,
            None,
            chunked(&t.prepared, &t.tris, GROUP, move |r, x| {
                t_sum(x.hit(r, all).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Triangle::occluded, PreparedRay, (0, inf]",
            w,
            nt,
            None,
            chunked(&t.prepared, &t.tris, GROUP, move |r, x| {
                u64::from(x.occluded(r, all))
            }),
        ),
        kernel(
            sec,
            "rayhit TriangleBatch::hit, 8 lanes, (0, inf]",
            w,
            nt,
            None,
            chunked(&t.prepared, tb8, GROUP / 8, move |r, x| {
                batch_t_sum(&x.hit(r, all))
            }),
        ),
        kernel(
            sec,
            "rayhit TriangleBatch::occluded, 8 lanes, (0, inf]",
            w,
            nt,
            None,
            chunked(&t.prepared, tb8, GROUP / 8, move |r, x| {
                u64::from(x.occluded(r, all))
            }),
        ),
        kernel(
            sec,
            "rayhit TriangleBatch::hit, 8 lanes, with_simd",
            w,
            nt,
            None,
            simd(BatchRows {
                rays: &t.prepared,
                batches: tb8,
                per_ray: GROUP / 8,
            }),
        ),
        kernel(
            sec,
            "bvh intersects_triangle (front only)",
            w,
            nt,
            Some(bvh_agree),
            chunked(&t.bvh_rays, &t.bvh_tris, GROUP, |r, x| {
                t_sum(bvh_hits(r, x))
            }),
        ),
        kernel(
            sec,
            "parry3d Triangle::cast_local_ray",
            w,
            nt,
            Some(parry_agree),
            chunked(&t.parry_rays, &t.parry_tris, GROUP, |r, x| {
                t_sum(x.cast_local_ray(r, f32::MAX, true))
            }),
        ),
    ]);
}
