//! The batch kernels against the scalar ones, bit for bit.
//!
//! `AabbBatch::clip` must give, in every lane, the hit or miss and the
//! entry `t` of `Aabb::clip` with a `PreparedRay` on that lane's box (and
//! likewise over intervals whose lower end lies before, at and within the
//! lanes' boxes); `TriangleBatch::hit` the hit or miss, `t`, `u`, `v` and
//! side of `ray_triangle` on that lane's triangle (and over intervals those
//! of `Triangle::hit` with a `PreparedRay`, with `TriangleBatch::occluded`
//! true exactly when it hits a lane); and `Triangle::hit` with a
//! `PreparedRay` exactly `ray_triangle`. Since the scalar kernels are held
//! to the exact oracle elsewhere (`properties`, `oracle`, `corpus`),
//! identity carries every guarantee over.
//!
//! Inputs: the crate's aimed strategies, with the other lanes filled by
//! copies of the aimed shape moved along the ray (several hits per batch,
//! at different `t`), reversed copies, unrelated shapes, invalid shapes
//! (inverted, NaN, infinite, zero-area) and empty lanes. (The `batch` fuzz
//! target's check runs on arbitrary bit patterns in the test kit's
//! `fuzz_replay` test.)

use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{
    Aabb, Bounds, Intersect, IntersectLanes, Interval, PreparedRay, Ray, Scalar, Triangle,
    TriangleHit, Vector,
    batch::{AabbBatch, Simd, TargetSimd, TriangleBatch},
    ray_triangle,
};
use rayhit_testkit::bits::{bits, hit_bits};
use rayhit_testkit::case_count;
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: case_count(1024).try_into().unwrap_or(u32::MAX),
        ..ProptestConfig::default()
    }
}

// ------------------------------------------------------------------ boxes

/// Checks every lane of a batch of `N` against the scalar test, for a
/// batch built from `boxes` (at most `N`; `None` entries are left empty).
fn check_boxes<V: Vector, const N: usize>(
    ray: &Ray<V>,
    boxes: &[Option<Aabb<V>>],
    t_max: S<V>,
) -> Result<(), String> {
    let mut batch = AabbBatch::<V, N>::empty();
    for (lane, b) in boxes.iter().enumerate().take(N) {
        if let Some(b) = b {
            batch.set(lane, b);
        }
    }
    let prepared = PreparedRay::new(ray);
    let hits = batch.clip(&prepared, t_max);
    for lane in 0..N {
        let expected = match boxes.get(lane) {
            Some(Some(b)) => b.clip(&prepared, t_max).map(|(enter, _)| enter),
            _ => None,
        };
        let got = hits.get(lane);
        if got.map(bits) != expected.map(bits) {
            return Err(format!(
                "lane {lane} of {N}: batch {got:?}, scalar {expected:?}; ray {ray:?}, box {:?}, t_max {t_max:?}",
                boxes.get(lane)
            ));
        }
        if got.is_none() && bits(hits.enter[lane]) != bits(S::<V>::INFINITY) {
            return Err(format!(
                "lane {lane} missed but enter is {:?}",
                hits.enter[lane]
            ));
        }
    }
    if hits.mask & !batch.mask() != 0 {
        return Err(format!("mask {:b} outside the used lanes", hits.mask));
    }
    // `meets` is `clip`'s mask, from its own copy of the kernel (the
    // entries dropped), and for each box `clip(..).is_some()`.
    let meets = batch.meets(&prepared, t_max);
    if meets != hits.mask {
        return Err(format!("meets {meets:b}, clip's mask {:b}", hits.mask));
    }
    for (lane, b) in boxes.iter().enumerate().take(N) {
        if let Some(b) = b
            && b.meets(&prepared, t_max) != b.clip(&prepared, t_max).is_some()
        {
            return Err(format!("lane {lane}: Aabb::meets is not clip's answer"));
        }
    }
    // Over intervals: lower ends at zero (both signs), at and just past the
    // first box's entry and exit, and halfway to `t_max`.
    let mut lower = vec![S::<V>::ZERO, -S::<V>::ZERO, t_max * S::<V>::HALF];
    if let Some(Some(b)) = boxes.first()
        && let Some((enter, exit)) = b.clip(&prepared, t_max)
    {
        lower.extend([enter, enter.next_up(), exit, exit.next_down()]);
    }
    for lo in lower {
        let Some(interval) = Interval::new(lo, t_max) else {
            continue;
        };
        let hits = batch.clip(&prepared, interval);
        if batch.meets(&prepared, interval) != hits.mask {
            return Err(format!("meets over {interval:?} is not clip's mask"));
        }
        for lane in 0..N {
            let expected = match boxes.get(lane) {
                Some(Some(b)) => b.clip(&prepared, interval).map(|(enter, _)| enter),
                _ => None,
            };
            let got = hits.get(lane);
            if got.map(bits) != expected.map(bits)
                || (got.is_none() && bits(hits.enter[lane]) != bits(S::<V>::INFINITY))
            {
                return Err(format!(
                    "lane {lane} of {N} over {interval:?}: batch {got:?} (enter {:?}), scalar {expected:?}; ray {ray:?}, box {:?}",
                    hits.enter[lane],
                    boxes.get(lane)
                ));
            }
        }
    }
    Ok(())
}

fn check_all_box_sizes<V: Vector>(
    ray: &Ray<V>,
    boxes: &[Option<Aabb<V>>],
    t_max: S<V>,
) -> Result<(), String> {
    check_boxes::<V, 4>(ray, boxes, t_max)?;
    check_boxes::<V, 8>(ray, boxes, t_max)?;
    check_boxes::<V, 16>(ray, boxes, t_max)?;
    // The same boxes in another order, and a lone one.
    let mut rev = boxes.to_vec();
    rev.reverse();
    check_boxes::<V, 16>(ray, &rev, t_max)?;
    check_boxes::<V, 1>(ray, &boxes[..1], t_max)
}

/// Lane contents for the box batches: the aimed box moved along the ray by
/// `shift * dir` (so hit at another `t`), an unrelated box, an invalid box,
/// or nothing.
fn box_lanes<V: Vector>(
    aimed: Aabb<V>,
    ray: Ray<V>,
) -> impl Strategy<Value = Vec<Option<Aabb<V>>>> {
    let lane = prop_oneof![
        4 => (-8i32..=8).prop_map(move |k| {
            // Shifts by multiples of 1/4 of dir: exact when dir and the
            // box's coordinates allow, rounded otherwise; both are fine.
            let s = S::<V>::from_f64(f64::from(k) * 0.25);
            Some(Aabb::new(aimed.min + ray.dir * s, aimed.max + ray.dir * s))
        }),
        2 => strat::aabb::<V>().prop_map(Some),
        1 => Just(Some(Aabb::new(aimed.max, aimed.min))),
        1 => Just(Some(Aabb::new(aimed.min, V::splat(S::<V>::INFINITY)))),
        1 => Just(Some(Aabb::new(V::splat(S::<V>::NAN), aimed.max))),
        1 => Just(None),
    ];
    prop::collection::vec(lane, 15).prop_map(move |mut lanes| {
        lanes.insert(0, Some(aimed));
        lanes
    })
}

fn box_case<V: Vector>() -> impl Strategy<Value = (Ray<V>, Vec<Option<Aabb<V>>>, S<V>)> {
    (strat::aabb_and_ray::<V>(), strat::t_max::<V>())
        .prop_flat_map(|((aimed, ray), t_max)| (Just(ray), box_lanes(aimed, ray), Just(t_max)))
}

// -------------------------------------------------------------- triangles

fn check_triangles<V: Vector, const N: usize>(
    ray: &Ray<V>,
    tris: &[Option<Triangle<V>>],
    t_max: S<V>,
) -> Result<(), String> {
    let mut batch = TriangleBatch::<V, N>::empty();
    for (lane, t) in tris.iter().enumerate().take(N) {
        if let Some(t) = t {
            batch.set(lane, t);
        }
    }
    let prepared = PreparedRay::new(ray);
    let hits = batch.hit(&prepared, t_max);
    let mut nearest: Option<(usize, TriangleHit<S<V>>)> = None;
    for lane in 0..N {
        let expected = match tris.get(lane) {
            Some(Some(t)) => ray_triangle(ray, t, t_max),
            _ => None,
        };
        let got = hits.get(lane);
        if hit_bits(got) != hit_bits(expected) {
            return Err(format!(
                "lane {lane} of {N}: batch {got:?}, scalar {expected:?}; ray {ray:?}, triangle {:?}, t_max {t_max:?}",
                tris.get(lane)
            ));
        }
        if let Some(Some(t)) = tris.get(lane) {
            let prepared_hit = t.hit(&prepared, t_max);
            if hit_bits(prepared_hit) != hit_bits(expected) {
                return Err(format!(
                    "Triangle::hit, PreparedRay {prepared_hit:?} != ray_triangle {expected:?}"
                ));
            }
        }
        if let Some(h) = expected {
            if nearest.is_none_or(|(_, n)| h.t < n.t) {
                nearest = Some((lane, h));
            }
        } else if bits(hits.t[lane]) != bits(S::<V>::INFINITY) {
            return Err(format!("lane {lane} missed but t is {:?}", hits.t[lane]));
        }
    }
    let got = hits.nearest();
    let same_nearest = match (got, nearest) {
        (None, None) => true,
        (Some((a, x)), Some((b, y))) => a == b && hit_bits(Some(x)) == hit_bits(Some(y)),
        _ => false,
    };
    if !same_nearest {
        return Err(format!("nearest {got:?}, expected {nearest:?}"));
    }
    // Over intervals: lower ends at zero (both signs), at the nearest hit
    // and an ulp either side, and halfway to `t_max`.
    let mut lower = vec![S::<V>::ZERO, -S::<V>::ZERO, t_max * S::<V>::HALF];
    if let Some((_, h)) = nearest {
        lower.extend([h.t, h.t.next_up(), h.t.next_down()]);
    }
    for lo in lower {
        let Some(interval) = Interval::new(lo, t_max) else {
            continue;
        };
        let hits = batch.hit(&prepared, interval);
        for lane in 0..N {
            let expected = match tris.get(lane) {
                Some(Some(t)) => t.hit(&prepared, interval),
                _ => None,
            };
            let got = hits.get(lane);
            if hit_bits(got) != hit_bits(expected)
                || (got.is_none() && bits(hits.t[lane]) != bits(S::<V>::INFINITY))
            {
                return Err(format!(
                    "lane {lane} of {N} over {interval:?}: batch {got:?} (t {:?}), scalar {expected:?}; ray {ray:?}, triangle {:?}",
                    hits.t[lane],
                    tris.get(lane)
                ));
            }
        }
        let via_simd = batch.hit(&TargetSimd.ray(&prepared), interval);
        if via_simd.mask != hits.mask || via_simd.t.map(bits) != hits.t.map(bits) {
            return Err(format!(
                "TriangleBatch::hit through Simd::ray differs over {interval:?}"
            ));
        }
        let occluded = batch.occluded(&prepared, interval);
        if occluded != (hits.mask != 0)
            || occluded != batch.occluded(&TargetSimd.ray(&prepared), interval)
        {
            return Err(format!(
                "occluded {occluded} but mask {:b} over {interval:?}; ray {ray:?}",
                hits.mask
            ));
        }
    }
    Ok(())
}

fn check_all_triangle_sizes<V: Vector>(
    ray: &Ray<V>,
    tris: &[Option<Triangle<V>>],
    t_max: S<V>,
) -> Result<(), String> {
    check_triangles::<V, 4>(ray, tris, t_max)?;
    check_triangles::<V, 8>(ray, tris, t_max)?;
    check_triangles::<V, 16>(ray, tris, t_max)?;
    let mut rev = tris.to_vec();
    rev.reverse();
    check_triangles::<V, 16>(ray, &rev, t_max)?;
    check_triangles::<V, 1>(ray, &tris[..1], t_max)
}

fn triangle_lanes<V: Vector>(
    aimed: Triangle<V>,
    ray: Ray<V>,
) -> impl Strategy<Value = Vec<Option<Triangle<V>>>> {
    let shift = move |t: Triangle<V>, k: i32| {
        let s = S::<V>::from_f64(f64::from(k) * 0.25);
        let d = ray.dir * s;
        Triangle::new(t.a + d, t.b + d, t.c + d)
    };
    let nan = S::<V>::NAN;
    let lane = prop_oneof![
        4 => (-8i32..=8).prop_map(move |k| Some(shift(aimed, k))),
        2 => (-8i32..=8).prop_map(move |k| Some(shift(aimed.flipped(), k))),
        2 => strat::triangle::<V>().prop_map(Some),
        1 => Just(Some(Triangle::new(aimed.a, aimed.a, aimed.c))),
        1 => Just(Some(Triangle::new(aimed.a, aimed.b, V::splat(nan)))),
        1 => Just(Some(Triangle::new(aimed.a, V::splat(S::<V>::INFINITY), aimed.c))),
        1 => Just(None),
    ];
    prop::collection::vec(lane, 15).prop_map(move |mut lanes| {
        lanes.insert(0, Some(aimed));
        lanes
    })
}

fn triangle_case<V: Vector>() -> impl Strategy<Value = (Ray<V>, Vec<Option<Triangle<V>>>, S<V>)> {
    (strat::triangle_and_ray::<V>(), strat::t_max::<V>())
        .prop_flat_map(|((aimed, ray), t_max)| (Just(ray), triangle_lanes(aimed, ray), Just(t_max)))
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn box_batches_f32((ray, boxes, t_max) in box_case::<Vec3>()) {
        check_all_box_sizes(&ray, &boxes, t_max).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn box_batches_f64((ray, boxes, t_max) in box_case::<DVec3>()) {
        check_all_box_sizes(&ray, &boxes, t_max).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn triangle_batches_f32((ray, tris, t_max) in triangle_case::<Vec3>()) {
        check_all_triangle_sizes(&ray, &tris, t_max).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn triangle_batches_f64((ray, tris, t_max) in triangle_case::<DVec3>()) {
        check_all_triangle_sizes(&ray, &tris, t_max).map_err(TestCaseError::fail)?;
    }
}

/// Rays that start among their triangles' corners' depths: on or within a
/// few ulps of the plane, or a little in front of or behind it, so that
/// some corners are behind the origin. Hits there skip the first
/// sufficient test for `t > 0` (every corner in front); the batch decides
/// most of them with the second (the scaled distance above its error
/// bound), and crossings within rounding of `t = 0` go to the scalar code.
/// Every lane must be the scalar test's answer bit for bit, and both
/// answers must be common (so that the path is exercised).
#[test]
fn rays_starting_among_the_corners_depths() {
    fn run<V: Vector>(rng: &mut Source) -> (usize, usize) {
        let mut coord = || S::<V>::from_f64(f64::from(rng.below(1 << 16)) / 8192.0 - 4.0);
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..case_count(3000) {
            let mut v = || V::new(coord(), coord(), coord());
            let tri = Triangle::new(v(), v(), v());
            let dir = v();
            let (u, w) = (S::<V>::from_f64(0.3), S::<V>::from_f64(0.25));
            let on_plane = tri.a + (tri.b - tri.a) * u + (tri.c - tri.a) * w;
            let lanes: Vec<Option<Triangle<V>>> = (0..16)
                .map(|k: i32| {
                    // Lane k moves the triangle along the ray by 2^-k of
                    // the direction (down to a few ulps in f32), or back by
                    // a little for the last lanes.
                    let s = if k < 12 {
                        2f64.powi(-k)
                    } else {
                        -(2f64.powi(10 - k))
                    };
                    let s = S::<V>::from_f64(s);
                    let d = dir * s;
                    Some(Triangle::new(tri.a + d, tri.b + d, tri.c + d))
                })
                .collect();
            let ray = Ray::new(on_plane, dir);
            check_all_triangle_sizes(&ray, &lanes, S::<V>::INFINITY).unwrap();
            for t in lanes.iter().flatten() {
                let depths = [t.a, t.b, t.c].map(|p| (p - ray.origin).dot(dir).to_f64());
                if depths.iter().any(|&z| z < 0.0) && depths.iter().any(|&z| z > 0.0) {
                    match ray_triangle(&ray, t, S::<V>::INFINITY) {
                        Some(_) => hits += 1,
                        None => misses += 1,
                    }
                }
            }
        }
        (hits, misses)
    }
    let mut rng = Source::seeded(0x5eed_0001);
    for (hits, misses) in [run::<Vec3>(&mut rng), run::<DVec3>(&mut rng)] {
        assert!(hits > 2000 && misses > 2000, "{hits} hits, {misses} misses");
    }
}

/// Rays through the shared corners of a grid mesh along the axes: every
/// edge function through the corner is exactly zero, so these lanes take
/// the exact-sign path; and rays in the plane of a box face.
#[test]
fn exact_zero_edge_functions_and_face_planes() {
    for precision_f64 in [false, true] {
        let mut tris = Vec::new();
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let p = |x: i32, y: i32| Vec3::new((i + x) as f32, (j + y) as f32, 0.0);
            tris.push(Triangle::new(p(0, 0), p(1, 0), p(0, 1)));
            tris.push(Triangle::new(p(1, 0), p(1, 1), p(0, 1)));
        }
        for x in 0..=2 {
            for y in 0..=2 {
                for dir in [-Vec3::Z, Vec3::Z, Vec3::new(0.0, 0.0, -0.5)] {
                    let o = Vec3::new(x as f32, y as f32, -2.0 * dir.z.signum());
                    let ray = Ray::new(o, dir);
                    let lanes: Vec<_> = tris.iter().copied().map(Some).collect();
                    if precision_f64 {
                        let d = |v: Vec3| v.as_dvec3();
                        let ray = Ray::new(d(ray.origin), d(ray.dir));
                        let lanes: Vec<_> = lanes
                            .iter()
                            .map(|t| t.map(|t| Triangle::new(d(t.a), d(t.b), d(t.c))))
                            .collect();
                        check_all_triangle_sizes(&ray, &lanes, f64::INFINITY).unwrap();
                    } else {
                        check_all_triangle_sizes(&ray, &lanes, f32::INFINITY).unwrap();
                    }
                }
            }
        }
    }
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let boxes = [Some(unit); 8];
    for o in [
        Vec3::new(-1.0, 1.0, 0.5),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ] {
        for dir in [
            Vec3::X,
            Vec3::new(1.0, -0.0, 0.0),
            Vec3::new(1.0, 0.0, -0.0),
        ] {
            let ray = Ray::new(o, dir);
            check_all_box_sizes(&ray, &boxes, f32::INFINITY).unwrap();
            assert_eq!(
                AabbBatch::<Vec3, 8>::from_slice(&[unit; 8])
                    .unwrap()
                    .clip(&PreparedRay::new(&ray), f32::INFINITY)
                    .mask,
                0xff,
                "a ray in a face plane of the closed box hits"
            );
        }
    }
}

/// Invalid rays prepare into equal values (nothing of the invalid input is
/// kept), and hit nothing in any batch.
#[test]
fn invalid_rays_prepare_alike_and_hit_nothing() {
    let nan = f32::NAN;
    let bad = [
        Ray::new(Vec3::splat(nan), Vec3::X),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
        Ray::new(Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0)),
        Ray::new(Vec3::new(0.0, nan, 0.0), Vec3::new(nan, 1.0, 0.0)),
    ];
    let tri = Triangle::new(-Vec3::ONE, Vec3::new(1.0, -1.0, 0.0), Vec3::Y);
    let boxes = AabbBatch::<Vec3, 4>::from_slice(&[Aabb::new(-Vec3::ONE, Vec3::ONE)]).unwrap();
    let tris = TriangleBatch::<Vec3, 4>::from_slice(&[tri]).unwrap();
    for ray in bad {
        let p = PreparedRay::new(&ray);
        assert_eq!(p, PreparedRay::new(&bad[1]));
        assert_eq!(boxes.clip(&p, f32::INFINITY).mask, 0);
        assert_eq!(tris.hit(&p, f32::INFINITY).mask, 0);
        assert_eq!(tri.hit(&p, f32::INFINITY), None);
    }
}
