//! The interval forms of the plane and box tests (`Plane::hit`,
//! `Aabb::clip` and `Aabb::hit` over an interval, on a `Ray` and on a
//! `PreparedRay`) held to exact arithmetic, in `f32` (`Vec3`) and `f64`
//! (`DVec3`).
//!
//! Planes, decided exactly. The cases: random planes (scales 1e-3 to 1e3,
//! translated by up to 1e5) and rays of any direction length; origins far
//! away (1e6 to 1e8); directions nearly parallel to the plane (the in-plane
//! part of a random vector, rounded, sometimes tilted by a few ulps), where
//! `ray_plane` drops most; directions exactly parallel (the ray lying in the
//! plane, or beside it); crossings at exactly a float `t0` (grid inputs);
//! and tiny inputs (everything scaled by a power of two until the products
//! underflow). For every window `(lo, hi]` with ends among 0, the exact
//! crossing `t*` rounded and two ulps either side, and others: a hit exactly
//! when `lo < t* <= min(hi, MAX)`, compared in big rationals, and, on the
//! first windows of each case, `rayhit::exact::ray_plane_in` itself. The
//! reported `t` is in the window and finite, equal to `ray_plane`'s
//! quotient where that is in the window, and otherwise the upper end (no
//! farther from `t*` than the quotient) or the lower end's successor (no
//! farther than the quotient or one ulp);
//! with `(0, t_max]` it is `ray_plane`'s answer bit for bit where the exact
//! module says the case is clear of rounding (`oracle::plane_clear`).
//!
//! Boxes, conservatively. Random boxes (scales 1e-3 to 1e3, translated by
//! up to 1e5) and rays aimed at their interior, faces, edges and corners,
//! from nearby or far away; axis-parallel rays, some with the origin on a
//! slab plane; flat boxes; and boxes entered at exactly a float `t0`
//! (grid inputs). Windows with ends among 0, the exact entry and exit
//! rounded and two ulps either side, and others. Checked: no false miss
//! (where the exact segment inside the closed box meets the window, the
//! kernel hits, and its exit is at least the exact exit); `lo <= enter <=
//! exit <= hi`; the prepared and face forms give the same interval bit for
//! bit; the face is reported exactly when the exact entry `E*` is in the
//! window (where the exact ray meets the box), is the exact entry face,
//! and is `exact::ray_aabb_in`'s first entry face; `exact::ray_aabb_in`
//! agrees with the rational computation here.
//!
//! Partitions: `[0, T]` cut at random points and at `t*` (or `E*`) rounded
//! and its neighbours, and `(.., inf]` last: the plane is reported in
//! exactly one window when `t*` is in `(0, min(T, MAX)]` and in none
//! otherwise; a box's entry face likewise (at most once where the exact ray
//! misses the box by a rounding).
//!
//! Bad input: NaN or inverted intervals cannot be built; NaN rays, planes
//! and boxes miss, without a panic.
//!
//! 150 cases per kind and precision (about 5 s on 2 cores in the test
//! profile), times `RAYHIT_CASES`. The long run, ignored
//! by default: 100 times as many cases, in one test (so on one core);
//! about half an hour, estimated from the default run's times, not timed:
//!
//! ```sh
//! cargo test --release --test suite interval_shapes:: -- --ignored --nocapture
//! ```

use super::draw::{f, point, signed, v};
use rayhit::exact::num_traits::Signed;
use rayhit::exact::{self, Rational, oracle};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, Bounds, BoxFace, Intersect, Interval, Plane, PreparedRay, Ray, Scalar, Vector, ray_aabb,
    ray_plane,
};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// A value on a grid of `2^-k`, from `bits` random bits (few, so that
/// sums and products of them stay exact).
fn grid(rng: &mut Pcg32, bits: u32, k: i32) -> f64 {
    (f64::from(rng.below(1 << bits)) - f64::from(1u32 << (bits - 1))) * 2f64.powi(-k)
}

fn grid_v<V: Vector>(rng: &mut Pcg32, bits: u32, k: i32) -> V {
    v::<V>(grid(rng, bits, k), grid(rng, bits, k), grid(rng, bits, k))
}

/// `x` moved by `k` ulps (up for `k > 0`).
fn step<F: Scalar>(x: F, k: i32) -> F {
    let mut x = x;
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

fn single<V: Vector>() -> bool {
    S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10
}

fn r<F: Scalar>(x: F) -> Rational {
    oracle::r(x).expect("finite")
}

fn bits<F: Scalar>(x: F) -> u64 {
    x.to_f64().to_bits()
}

/// The ends windows are made of: 0, `around` rounded and two ulps either
/// side (each non-negative finite one), a few fixed values and one random
/// value; sorted, without repeats.
fn ends<V: Vector>(rng: &mut Pcg32, around: &[Rational]) -> Vec<S<V>> {
    let mut out = vec![
        S::<V>::ZERO,
        S::<V>::TINY,
        S::<V>::ONE,
        S::<V>::MAX,
        f::<V>(2f64.powi(rng.below(40) as i32 - 20)),
    ];
    for t in around {
        let t0 = exact::round::<S<V>>(t);
        for k in -2..=2 {
            out.push(step(t0, k));
        }
    }
    out.retain(|e| *e >= S::<V>::ZERO && e.is_finite());
    out.sort_by(|a, b| a.partial_cmp(b).unwrap());
    out.dedup_by(|a, b| bits(*a) == bits(*b) || (*a == S::<V>::ZERO && *b == S::<V>::ZERO));
    out
}

/// `lo < t <= hi`, exactly, with `hi` capped at `MAX` (`None` for an
/// infinite `hi`: no upper end below `MAX`).
fn in_window<F: Scalar>(t: &Rational, lo: F, hi: F) -> bool {
    let cap = if hi < F::MAX { hi } else { F::MAX };
    *t > r(lo) && *t <= r(cap)
}

#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    windows: usize,
    hits: usize,
    /// Windows where `ray_plane`'s quotient and `t*` lie on different
    /// sides of an end: a float comparison would have been wrong there.
    float_wrong: usize,
    /// Cases `ray_plane` drops (within rounding of parallel, or `t` not
    /// above 0) that cross the plane at `t* > 0`.
    dropped_by_plain: usize,
    /// Cases crossing at exactly a float.
    exact_float: usize,
    /// Clear cases where `(0, t_max]` matched `ray_plane` bit for bit.
    plain_equal: usize,
    /// Box windows the exact segment meets.
    exact_hits: usize,
    /// Box windows reported where the exact segment misses them.
    false_hits: usize,
    /// Box faces reported.
    faces: usize,
    /// Partitions checked, and those with a report.
    partitions: usize,
    reported_once: usize,
}

// ---------------------------------------------------------------- planes

/// A plane case of one of six kinds (see the file's docs).
fn plane_case<V: Vector>(rng: &mut Pcg32, kind: u32) -> (Ray<V>, Plane<V>) {
    let scale = 10f64.powi(rng.below(7) as i32 - 3);
    let far = 1e5 * f64::from(rng.below(3)) / 2.0;
    let centre = [far * signed(rng), far * signed(rng), far * signed(rng)];
    let normal_scale = 2f64.powi(rng.below(21) as i32 - 10);
    let normal = point::<V>(rng, normal_scale, [0.0; 3]);
    let p = point::<V>(rng, scale, centre);
    let length = 2f64.powi(rng.below(41) as i32 - 20);
    match kind {
        // Random, nearby.
        0 => {
            let o = point::<V>(rng, 4.0 * scale, centre);
            let target = point::<V>(rng, scale, centre);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Plane::new(p, normal),
            )
        }
        // Far away.
        1 => {
            let d = 10f64.powi(6 + rng.below(3) as i32);
            let o = point::<V>(rng, d, centre);
            let target = point::<V>(rng, scale, centre);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Plane::new(p, normal),
            )
        }
        // Nearly parallel: the in-plane part of a random vector, rounded,
        // sometimes tilted by a few ulps of itself towards the normal.
        2 => {
            let w = point::<V>(rng, 1.0, [0.0; 3]);
            let mut d = w - normal * (w.dot(normal) / normal.dot(normal));
            if rng.below(2) == 0 {
                let tilt = f::<V>(signed(rng) * 8.0) * S::<V>::UNIT_ROUNDOFF;
                d = d + normal * (tilt * d.length() / normal.length());
            }
            let o = point::<V>(rng, 4.0 * scale, centre);
            (Ray::new(o, d * f::<V>(length)), Plane::new(p, normal))
        }
        // Exactly parallel: `normal` orthogonal to `dir` in exact arithmetic
        // (the products `d_x d_y` cancel), the origin in the plane or not.
        3 => {
            let d = point::<V>(rng, 1.0, [0.0; 3]);
            let n = V::new(d.y(), -d.x(), S::<V>::ZERO);
            let o = if rng.below(2) == 0 {
                p
            } else {
                point::<V>(rng, 4.0 * scale, centre)
            };
            (Ray::new(o, d), Plane::new(p, n))
        }
        // A crossing at exactly a float `t0`: grid values, `p = o + t0 d`.
        4 => {
            let o = grid_v::<V>(rng, 10, 4);
            let d = grid_v::<V>(rng, 8, 3);
            let t0 = f::<V>(f64::from(1 + rng.below(1 << 10)) * 2f64.powi(-6));
            let n = grid_v::<V>(rng, 6, 2);
            (Ray::new(o, d), Plane::new(o + d * t0, n))
        }
        // Tiny: a random case scaled down until products underflow.
        _ => {
            let inner = rng.below(3);
            let (ray, plane) = plane_case::<V>(rng, inner);
            let k = if single::<V>() { 50 } else { 480 } + rng.below(30) as i32;
            let s = f::<V>(2f64.powi(-k));
            let n = f::<V>(2f64.powi(-(rng.below(20) as i32)));
            (
                Ray::new(ray.origin * s, ray.dir * s),
                Plane::new(plane.point * s, plane.normal * s * n),
            )
        }
    }
}

/// `ray_plane`'s quotient, computed as it computes it.
fn quotient<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> S<V> {
    (plane.point - ray.origin).dot(plane.normal) / ray.dir.dot(plane.normal)
}

/// One window: the kernel against the exact crossing; the answer returned.
fn plane_window<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_star: Option<&Rational>,
    lo: S<V>,
    hi: S<V>,
    with_exact_module: bool,
    tally: &mut Tally,
) -> Option<S<V>> {
    let window = Interval::new(lo, hi).unwrap();
    let got = plane.hit(ray, window);
    let expected = t_star.is_some_and(|t| in_window(t, lo, hi));
    assert_eq!(
        got.is_some(),
        expected,
        "({lo:?}, {hi:?}] t* = {:?}: {ray:?} {plane:?}",
        t_star.map(oracle::to_f64)
    );
    if with_exact_module {
        let cap = if hi < S::<V>::MAX { hi } else { S::<V>::MAX };
        assert_eq!(exact::ray_plane_in(ray, plane, lo, cap).is_some(), expected);
    }
    tally.windows += 1;
    let q = quotient(ray, plane);
    if t_star.is_some() {
        let q_in = q.is_finite() && in_window(&r(q), lo, hi);
        tally.float_wrong += usize::from(q_in != expected);
    }
    if let Some(t) = got {
        tally.hits += 1;
        let t_star = t_star.unwrap();
        assert!(
            window.contains(t) && t.is_finite(),
            "{t:?} outside {window:?}"
        );
        // (A quotient beyond MAX is out of reach of any window.)
        if window.contains(q) && q <= S::<V>::MAX {
            assert_eq!(bits(t), bits(q), "{ray:?} {plane:?} {window:?}");
        } else if q.is_finite() {
            // Brought in: to `hi`, no farther from t* than the quotient;
            // to `lo`'s successor, within the larger of that and one ulp.
            let dist = |x: S<V>| (r(x) - t_star).abs();
            let ulp = r(lo.next_up()) - r(lo);
            if q > hi {
                assert_eq!(bits(t), bits(hi));
                assert!(dist(t) <= dist(q), "{t:?} {q:?} {ray:?} {plane:?}");
            } else {
                assert_eq!(bits(t), bits(lo.next_up()));
                assert!(
                    dist(t) <= dist(q) || dist(t) <= ulp,
                    "{t:?} {q:?} ({lo:?}, {hi:?}] t* {} {ray:?} {plane:?}",
                    oracle::to_f64(t_star)
                );
            }
        }
    }
    got
}

fn plane_cases<V: Vector>(seed: u64, n: usize) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    for kind in 0..6 {
        for _ in 0..n {
            let (ray, plane) = plane_case::<V>(&mut rng, kind);
            if !(ray.is_valid() && plane.point.is_finite() && plane.normal.is_finite()) {
                continue;
            }
            tally.cases += 1;
            let t_star = oracle::plane_t(&ray, &plane);
            if kind == 3 {
                assert!(t_star.is_none(), "{ray:?} {plane:?}");
            }
            if let Some(t) = &t_star {
                let plain = ray_plane(&ray, &plane, inf);
                let positive = *t > r(S::<V>::ZERO) && in_window(t, S::<V>::ZERO, inf);
                tally.dropped_by_plain += usize::from(plain.is_none() && positive);
                tally.exact_float += usize::from(
                    exact::round::<S<V>>(t) == S::<V>::ZERO || {
                        let t0 = exact::round::<S<V>>(t);
                        t0.is_finite() && r(t0) == *t
                    },
                );
            }
            let ends = ends::<V>(&mut rng, t_star.as_slice());
            for (i, &lo) in ends.iter().enumerate() {
                for &hi in ends[i..].iter().chain([&inf]) {
                    let first = i == 0 || hi == inf;
                    plane_window(&ray, &plane, t_star.as_ref(), lo, hi, first, &mut tally);
                }
            }
            // (0, t_max] against ray_plane, where the case is clear of
            // rounding. Not for the tiny kind: `Plane::hit_error` (and so
            // `plane_clear`) assumes no product underflows (the crate's
            // standing precondition of its error bounds), which those
            // cases break on purpose; the interval form does not assume it.
            let clear_of_underflow = kind != 5;
            for &t_max in ends.iter().chain([&inf]).filter(|_| clear_of_underflow) {
                let plain = ray_plane(&ray, &plane, t_max);
                if plain.is_some() && oracle::plane_clear(&ray, &plane, t_max) {
                    let window = Interval::up_to(t_max).unwrap();
                    assert_eq!(
                        plane.hit(&ray, window).map(bits),
                        plain.map(bits),
                        "{ray:?} {plane:?} {t_max:?}"
                    );
                    tally.plain_equal += 1;
                }
            }
            plane_partition(&mut rng, &ray, &plane, t_star.as_ref(), &mut tally);
        }
    }
    tally
}

/// `[0, T]` cut at random points and around `around` (rounded, and two
/// ulps either side), then `(T, inf]`: the windows' ends, from 0.
fn partition<V: Vector>(rng: &mut Pcg32, around: Option<&Rational>) -> Vec<S<V>> {
    let t0 = around.map(exact::round::<S<V>>);
    let base = t0.filter(|t| t.is_finite() && *t > S::<V>::ZERO);
    let top = base.map_or(S::<V>::ONE, |t| {
        t * f::<V>(0.5 + 2.0 * f64::from(rng.unit()))
    });
    let mut cuts = vec![S::<V>::ZERO, top];
    for _ in 0..rng.below(6) {
        cuts.push(top * f::<V>(f64::from(rng.unit())));
    }
    if let Some(t) = base {
        for k in -2..=2 {
            if rng.below(2) == 0 {
                cuts.push(step(t, k));
            }
        }
    }
    cuts.retain(|c| *c >= S::<V>::ZERO && *c <= top);
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    cuts.dedup_by(|a, b| a == b);
    cuts.push(S::<V>::INFINITY);
    cuts
}

fn plane_partition<V: Vector>(
    rng: &mut Pcg32,
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_star: Option<&Rational>,
    tally: &mut Tally,
) {
    let cuts = partition::<V>(rng, t_star);
    let reports = cuts
        .windows(2)
        .filter(|w| plane.hit(ray, Interval::new(w[0], w[1]).unwrap()).is_some())
        .count();
    let expected = t_star.is_some_and(|t| in_window(t, S::<V>::ZERO, S::<V>::INFINITY));
    assert_eq!(reports, usize::from(expected), "{cuts:?} {ray:?} {plane:?}");
    tally.partitions += 1;
    tally.reported_once += reports;
}

// ----------------------------------------------------------------- boxes

/// A box case of one of five kinds (see the file's docs).
fn box_case<V: Vector>(rng: &mut Pcg32, kind: u32) -> (Ray<V>, Aabb<V>) {
    let scale = 10f64.powi(rng.below(7) as i32 - 3);
    let far = 1e5 * f64::from(rng.below(3)) / 2.0;
    let centre = [far * signed(rng), far * signed(rng), far * signed(rng)];
    let (a, b) = (
        point::<V>(rng, scale, centre),
        point::<V>(rng, scale, centre),
    );
    let mut min = V::new(
        a.x().min_of(b.x()),
        a.y().min_of(b.y()),
        a.z().min_of(b.z()),
    );
    let max = V::new(
        a.x().max_of(b.x()),
        a.y().max_of(b.y()),
        a.z().max_of(b.z()),
    );
    // A target inside, on a face, on an edge or at a corner: each
    // coordinate inside or on one of the two planes.
    let pick = |rng: &mut Pcg32, k: usize, on: bool| {
        if on {
            if rng.below(2) == 0 { min[k] } else { max[k] }
        } else {
            let s = f::<V>(f64::from(rng.unit()));
            min[k] + (max[k] - min[k]) * s
        }
    };
    let boundary = rng.below(4); // how many coordinates on a plane
    let target = V::new(
        pick(rng, 0, boundary >= 1),
        pick(rng, 1, boundary >= 2),
        pick(rng, 2, boundary >= 3),
    );
    let length = 2f64.powi(rng.below(41) as i32 - 20);
    match kind {
        0 | 1 => {
            let away = if kind == 0 {
                4.0 * scale
            } else {
                10f64.powi(6 + rng.below(3) as i32)
            };
            let o = point::<V>(rng, away, centre);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Aabb::new(min, max),
            )
        }
        // Axis-parallel: one or two direction components zero, the origin
        // sometimes on a slab plane of such an axis.
        2 => {
            let o = point::<V>(rng, 4.0 * scale, centre);
            let mut d = target - o;
            let mut o = o;
            let zero_axes = 1 + rng.below(2) as usize;
            let first = rng.below(3) as usize;
            for j in 0..zero_axes {
                let k = (first + j) % 3;
                let on = if rng.below(2) == 0 {
                    target[k]
                } else {
                    pick(rng, k, true)
                };
                o = with(o, k, on);
                d = with(d, k, S::<V>::ZERO);
            }
            (Ray::new(o, d * f::<V>(length)), Aabb::new(min, max))
        }
        // Flat: zero thickness on one axis.
        3 => {
            let k = rng.below(3) as usize;
            min = with(min, k, max[k]);
            let o = point::<V>(rng, 4.0 * scale, centre);
            let target = with(target, k, max[k]);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Aabb::new(min, max),
            )
        }
        // Entered at exactly a float `t0` through the face of axis `k`:
        // grid values, `q = o + t0 d` on the face, inside the others.
        _ => {
            let o = grid_v::<V>(rng, 10, 4);
            let d = grid_v::<V>(rng, 8, 3);
            let t0 = f::<V>(f64::from(1 + rng.below(1 << 10)) * 2f64.powi(-6));
            let q = o + d * t0;
            let k = rng.below(3) as usize;
            let size = |rng: &mut Pcg32| f::<V>(f64::from(1 + rng.below(64)) * 0.25);
            let mut lo = q - V::new(size(rng), size(rng), size(rng));
            let mut hi = q + V::new(size(rng), size(rng), size(rng));
            if d[k] > S::<V>::ZERO {
                lo = with(lo, k, q[k]);
            } else {
                hi = with(hi, k, q[k]);
            }
            (Ray::new(o, d), Aabb::new(lo, hi))
        }
    }
}

fn with<V: Vector>(p: V, k: usize, x: S<V>) -> V {
    match k {
        0 => V::new(x, p.y(), p.z()),
        1 => V::new(p.x(), x, p.z()),
        _ => V::new(p.x(), p.y(), x),
    }
}

trait MinMax: Sized {
    fn min_of(self, o: Self) -> Self;
    fn max_of(self, o: Self) -> Self;
}
impl<F: Scalar> MinMax for F {
    fn min_of(self, o: Self) -> Self {
        if o < self { o } else { self }
    }
    fn max_of(self, o: Self) -> Self {
        if o > self { o } else { self }
    }
}

/// The exact entry and exit over every moving axis (`None` when an axis
/// the ray does not move along excludes it), and the entry face with its
/// exact crossing when one is ahead (`t > 0`).
struct ExactBox {
    segment: Option<(Rational, Rational)>,
    face: Option<(BoxFace, Rational)>,
}

fn exact_box<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> ExactBox {
    let segment = oracle::box_slabs(ray, b).map(|slabs| {
        let e = slabs.iter().map(|s| s.0.clone()).max().unwrap();
        let x = slabs.iter().map(|s| s.1.clone()).min().unwrap();
        (e, x)
    });
    let face = oracle::box_face(ray, b).unwrap().0.map(|face| {
        let k = face.axis();
        let t = (r(face.plane(b)) - r(ray.origin[k])) / r(ray.dir[k]);
        (face, t)
    });
    ExactBox { segment, face }
}

type Answer<F> = Option<(F, F, Option<BoxFace>)>;

fn box_window<V: Vector>(
    ray: &Ray<V>,
    b: &Aabb<V>,
    ex: &ExactBox,
    lo: S<V>,
    hi: S<V>,
    with_exact_module: bool,
    tally: &mut Tally,
) -> Answer<S<V>> {
    let window = Interval::new(lo, hi).unwrap();
    let got = b.clip(ray, window);
    let prepared = PreparedRay::new(ray);
    let pair_bits = |h: Option<(S<V>, S<V>)>| h.map(|(e, x)| (bits(e), bits(x)));
    assert_eq!(pair_bits(b.clip(&prepared, window)), pair_bits(got));
    let face_hit = b.hit(ray, window);
    assert_eq!(b.hit(&prepared, window), face_hit);
    assert_eq!(
        pair_bits(face_hit.map(|h| (h.enter, h.exit))),
        pair_bits(got)
    );
    tally.windows += 1;
    // The exact segment inside the closed box, against the window.
    let (rlo, cap) = (r(lo), if hi.is_finite() { Some(r(hi)) } else { None });
    let meets = ex.segment.as_ref().and_then(|(e, x)| {
        let enter = if *e > rlo { e.clone() } else { rlo.clone() };
        let exit = match &cap {
            Some(c) if c < x => c.clone(),
            _ => x.clone(),
        };
        (enter <= exit && exit > rlo).then_some(exit)
    });
    if with_exact_module {
        let answer = exact::ray_aabb_in(ray, b, lo, hi);
        assert_eq!(
            answer.is_some(),
            meets.is_some(),
            "{ray:?} {b:?} {window:?}"
        );
        if let (Some(a), Some(h)) = (&answer, &face_hit)
            && let Some(first) = a.entry_faces.first()
        {
            assert_eq!(h.face, Some(*first), "{ray:?} {b:?} {window:?}");
        }
    }
    if let Some(exit) = &meets {
        tally.exact_hits += 1;
        let (_, k_exit) = got.unwrap_or_else(|| panic!("false miss: {ray:?} {b:?} {window:?}"));
        assert!(
            r(k_exit) >= *exit || !k_exit.is_finite(),
            "exit below exact"
        );
    } else if got.is_some() {
        // A false hit only within the slab test's band: the exact entry
        // (at least `lo`) beyond the exact exit (at most `hi`) by less than
        // a factor `1 + 16u` (`40u` where a reciprocal is subnormal) plus
        // four subnormals.
        tally.false_hits += 1;
        let (e, x) = ex
            .segment
            .clone()
            .unwrap_or_else(|| panic!("hit where an axis excludes: {ray:?} {b:?}"));
        let enter = if e > rlo { e } else { rlo.clone() };
        let exit = match &cap {
            Some(c) if *c < x => c.clone(),
            _ => x,
        };
        let k = if oracle::reciprocal_subnormal(ray.dir) {
            40
        } else {
            16
        };
        let band = Rational::from_integer(1.into()) + oracle::int(k) * r(S::<V>::UNIT_ROUNDOFF);
        let slack = oracle::int(4) * r(S::<V>::TINY);
        assert!(
            enter <= exit.clone() * band + slack,
            "false hit outside the band: {ray:?} {b:?} {window:?}"
        );
    }
    if let Some((enter, exit)) = got {
        assert!(
            lo <= enter && enter <= exit && exit <= hi && enter.is_finite(),
            "{enter:?} {exit:?} {window:?}"
        );
    }
    // The face: reported exactly when the exact entry is in the window
    // (where the exact ray meets the box).
    let ray_meets_box = ex.segment.as_ref().is_some_and(|(e, x)| e <= x);
    let face = face_hit.and_then(|h| h.face);
    if let Some(face) = face {
        tally.faces += 1;
        let (exact_face, t) = ex.face.as_ref().expect("a face only where one is ahead");
        assert_eq!(face, *exact_face);
        assert!(in_window(t, lo, hi), "face outside the window");
    } else if let (Some((_, t)), true, true) = (&ex.face, ray_meets_box, got.is_some()) {
        assert!(
            !in_window(t, lo, hi),
            "face missed: {ray:?} {b:?} {window:?}"
        );
    }
    got.map(|(e, x)| (e, x, face))
}

fn box_cases<V: Vector>(seed: u64, n: usize) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    for kind in 0..5 {
        for _ in 0..n {
            let (ray, b) = box_case::<V>(&mut rng, kind);
            if !(ray.is_valid() && b.is_valid()) || oracle::reciprocal_overflows(ray.dir) {
                continue;
            }
            tally.cases += 1;
            let ex = exact_box(&ray, &b);
            let mut around = Vec::new();
            if let Some((e, x)) = &ex.segment {
                around.extend([e.clone(), x.clone()]);
            }
            if let Some((_, t)) = &ex.face {
                tally.exact_float += usize::from({
                    let t0 = exact::round::<S<V>>(t);
                    r(t0) == *t
                });
            }
            let ends = ends::<V>(&mut rng, &around);
            for (i, &lo) in ends.iter().enumerate() {
                for &hi in ends[i..].iter().chain([&inf]) {
                    let first = i == 0 || hi == inf;
                    box_window(&ray, &b, &ex, lo, hi, first, &mut tally);
                }
            }
            // (0, t_max]: ray_aabb's answer, bit for bit.
            for &t_max in ends.iter().chain([&inf]) {
                let all = Interval::up_to(t_max).unwrap();
                assert_eq!(b.clip(&ray, all), ray_aabb(&ray, &b, t_max));
            }
            // A partition: the entry face once.
            let cuts = partition::<V>(&mut rng, ex.face.as_ref().map(|f| &f.1));
            let reports = cuts
                .windows(2)
                .filter(|w| {
                    let window = Interval::new(w[0], w[1]).unwrap();
                    b.hit(&ray, window).is_some_and(|h| h.face.is_some())
                })
                .count();
            let entry_ahead = ex
                .face
                .as_ref()
                .is_some_and(|(_, t)| in_window(t, S::<V>::ZERO, inf));
            let meets = ex.segment.as_ref().is_some_and(|(e, x)| e <= x);
            if entry_ahead && meets {
                assert_eq!(reports, 1, "{cuts:?} {ray:?} {b:?}");
            } else if entry_ahead {
                assert!(reports <= 1, "{cuts:?} {ray:?} {b:?}");
            } else {
                assert_eq!(reports, 0, "{cuts:?} {ray:?} {b:?}");
            }
            tally.partitions += 1;
            tally.reported_once += reports;
        }
    }
    tally
}

// ----------------------------------------------------------------- tests

const CASES: usize = 150;

#[test]
fn planes_are_decided_exactly_f32() {
    let t = plane_cases::<Vec3>(1, case_count(CASES));
    println!("f32 planes: {t:?}");
    assert!(
        t.hits > t.windows / 8 && t.float_wrong > 0 && t.dropped_by_plain > 0,
        "{t:?}"
    );
    assert!(t.exact_float > 0 && t.plain_equal > 0 && t.reported_once > t.partitions / 4);
}

#[test]
fn planes_are_decided_exactly_f64() {
    let t = plane_cases::<DVec3>(2, case_count(CASES));
    println!("f64 planes: {t:?}");
    assert!(
        t.hits > t.windows / 8 && t.float_wrong > 0 && t.dropped_by_plain > 0,
        "{t:?}"
    );
    assert!(t.exact_float > 0 && t.plain_equal > 0 && t.reported_once > t.partitions / 4);
}

#[test]
fn boxes_are_culled_conservatively_f32() {
    let t = box_cases::<Vec3>(3, case_count(CASES));
    println!("f32 boxes: {t:?}");
    assert!(t.exact_hits > t.windows / 8 && t.faces > 0, "{t:?}");
    assert!(
        t.exact_float > 0 && t.reported_once > t.partitions / 4,
        "{t:?}"
    );
}

#[test]
fn boxes_are_culled_conservatively_f64() {
    let t = box_cases::<DVec3>(4, case_count(CASES));
    println!("f64 boxes: {t:?}");
    assert!(t.exact_hits > t.windows / 8 && t.faces > 0, "{t:?}");
    assert!(
        t.exact_float > 0 && t.reported_once > t.partitions / 4,
        "{t:?}"
    );
}

/// The long run: a hundred times the default cases, every kind, both
/// precisions (see the file's docs for the command).
#[test]
#[ignore]
fn long_run() {
    let n = case_count(100 * CASES);
    for (i, t) in [
        plane_cases::<Vec3>(11, n),
        plane_cases::<DVec3>(12, n),
        box_cases::<Vec3>(13, n),
        box_cases::<DVec3>(14, n),
    ]
    .iter()
    .enumerate()
    {
        println!("{i}: {t:?}");
    }
}

/// Bad input: no panic, a miss; bad intervals cannot be built.
#[test]
fn bad_input_misses() {
    assert!(Interval::new(f32::NAN, 1.0).is_none());
    assert!(Interval::new(0.0, f32::NAN).is_none());
    assert!(Interval::new(2.0, 1.0).is_none());
    assert!(Interval::new(-1.0, 1.0).is_none());
    assert!(Interval::new(0.0f64, f64::NAN).is_none());
    let all = Interval::up_to(f32::INFINITY).unwrap();
    let floor = Plane::new(Vec3::ZERO, Vec3::Y);
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let ray = Ray::new(Vec3::new(0.5, 2.0, 0.5), Vec3::NEG_Y);
    assert_eq!(floor.hit(&ray, all), Some(2.0));
    assert!(unit.clip(&ray, all).is_some());
    for bad in [
        Ray::new(Vec3::NAN, Vec3::NEG_Y),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
        Ray::new(Vec3::ZERO, Vec3::new(0.0, f32::INFINITY, 0.0)),
        Ray::new(Vec3::new(0.0, f32::NEG_INFINITY, 0.0), Vec3::Y),
    ] {
        assert_eq!(floor.hit(&bad, all), None);
        assert_eq!(unit.clip(&bad, all), None);
        assert_eq!(unit.clip(&PreparedRay::new(&bad), all), None);
        assert_eq!(unit.hit(&bad, all), None);
        assert!(exact::ray_plane_in(&bad, &floor, 0.0, f32::INFINITY).is_none());
        assert!(exact::ray_aabb_in(&bad, &unit, 0.0, f32::INFINITY).is_none());
    }
    for plane in [
        Plane::new(Vec3::NAN, Vec3::Y),
        Plane::new(Vec3::ZERO, Vec3::new(0.0, f32::NAN, 0.0)),
        Plane::new(Vec3::ZERO, Vec3::new(f32::INFINITY, 1.0, 0.0)),
        Plane::new(Vec3::ZERO, Vec3::ZERO),
    ] {
        assert_eq!(plane.hit(&ray, all), None);
    }
    for b in [
        Aabb::new(Vec3::NAN, Vec3::ONE),
        Aabb::new(Vec3::ONE, Vec3::ZERO),
        Aabb::new(Vec3::ZERO, Vec3::new(1.0, f32::INFINITY, 1.0)),
    ] {
        assert_eq!(b.clip(&ray, all), None);
        assert_eq!(b.hit(&ray, all), None);
        assert_eq!(b.hit(&PreparedRay::new(&ray), all), None);
        assert!(exact::ray_aabb_in(&ray, &b, 0.0, f32::INFINITY).is_none());
    }
    // The exact module's intervals: inverted and NaN ends are no interval.
    assert!(exact::ray_plane_in(&ray, &floor, 3.0, 1.0).is_none());
    assert!(exact::ray_plane_in(&ray, &floor, f32::NAN, 1.0).is_none());
    assert!(exact::ray_aabb_in(&ray, &unit, 3.0, 1.0).is_none());
    // A crossing beyond MAX is reported by no interval: f32 inputs whose
    // exact t* = 2^127 * 3 > MAX.
    let steep = Ray::new(
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::new(1.0, -(2f32.powi(-127)), 0.0),
    );
    assert!(exact::ray_plane_in(&steep, &floor, 0.0, f32::INFINITY).is_some());
    assert_eq!(floor.hit(&steep, all), None);
    let past_max = Interval::new(f32::MAX, f32::INFINITY).unwrap();
    assert_eq!(floor.hit(&steep, past_max), None);
}
