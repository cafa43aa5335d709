//! The interval forms of the box test (`Aabb::clip` and `Aabb::hit` over
//! an interval, on a `Ray` and on a `PreparedRay`) held to exact
//! arithmetic, in `f32` (`Vec3`) and `f64` (`DVec3`).
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
//! Partitions: `[0, T]` cut at random points and at `E*` rounded and its
//! neighbours, and `(.., inf]` last: the entry face is reported in exactly
//! one window when `E*` is in `(0, min(T, MAX)]` and in none otherwise (at
//! most once where the exact ray misses the box by a rounding).
//!
//! 150 cases per kind and precision (about 5 s for planes and boxes on 2
//! cores in the test profile), times `RAYHIT_CASES`. The long run and the
//! bad input, with the plane's: `shapes::interval`.

use crate::common::draw::{f, point, signed};
use crate::common::window::{CASES, Tally, bits, ends, grid_v, in_window, partition, r};
use rayhit::exact::{self, Rational, oracle};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, Bounds, BoxFace, Intersect, Interval, PreparedRay, Ray, Scalar, Vector, ray_aabb,
};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

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

pub fn box_cases<V: Vector>(seed: u64, n: usize) -> Tally {
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
