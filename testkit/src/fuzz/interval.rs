//! `interval`: the queries over an [`Interval`]
//! ([`Triangle::hit`](rayhit::Intersect::hit), also with
//! [`EdgeRule::OneHit`], [`Plane::hit`](rayhit::Intersect::hit),
//! [`Aabb::hit`](rayhit::Intersect::hit) and
//! [`Aabb::clip`](rayhit::Bounds::clip)) on one ray, one triangle, one
//! plane and one box, over a window `(lo, hi]` cut in two at `mid`.
//!
//! Input: raw mode, the shapes, the ray and the three ends as raw bits;
//! structured mode, a triangle, a plane and a box case from
//! [`crate::cases`] for one ray, and ends drawn around the exact
//! crossings (at them, an ulp either side, or anywhere).
//!
//! Checks, any input: no panic; `Interval::new` refuses exactly the NaN,
//! negative and inverted ends; every `t` reported lies in its interval and
//! is finite; the box and face forms give the same `(enter, exit)`, with
//! `t_min <= enter <= exit <= t_max`. Where the crossings are decided
//! exactly (always for `f32`; for `f64` where every coordinate is zero or
//! within `2^-100` to `2^100` in magnitude, inside the documented range):
//! the two halves `(lo, mid]` and `(mid, hi]` report the triangle, the
//! plane and the box's entry face (`BoxHit::face`) exactly once between
//! them when the whole window reports it, and never otherwise (no skip, no
//! repeat); and a box the whole window reports is reported by a half that
//! ends past its entry. Structured inputs also: the plane's answer is the
//! exact one (`exact::ray_plane_in`), and a box exact arithmetic puts in
//! the window is never culled.

use arbitrary::Arbitrary;
use rayhit::{Aabb, Interval, Plane, Ray, Scalar, Triangle, Vector};
use rayhit::{Bounds, EdgeRule, Intersect, exact};

use super::{Check, Input, S, raw, raw_vec};
use crate::cases;
use crate::source::Source;

/// The `interval` target.
#[derive(Debug)]
pub struct IntervalCheck;

/// One input: the shapes, the ray, and the ends `lo <= mid <= hi` (when
/// valid).
struct Case<V: Vector> {
    ray: Ray<V>,
    tri: Triangle<V>,
    plane: Plane<V>,
    aabb: Aabb<V>,
    ends: [S<V>; 3],
}

impl Check for IntervalCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let structured = input.is_structured();
        let case = match input {
            Input::Raw(u) => Case {
                ray: raw::<Ray<V>>(u),
                tri: raw::<Triangle<V>>(u),
                plane: raw::<Plane<V>>(u),
                aabb: raw::<Aabb<V>>(u),
                ends: {
                    let e = raw_vec::<V>(u);
                    [e.x(), e.y(), e.z()]
                },
            },
            Input::Structured(src) => structured_case::<V>(src),
        };
        check(&case, structured);
    }
}

/// A triangle case's ray, with a plane and a box from their own cases
/// moved onto it (the plane through a point of the ray, the box around
/// one), and ends around the crossings.
fn structured_case<V: Vector>(src: &mut Source) -> Case<V> {
    let (tri, ray, _) = cases::triangles::with_fillers::<V>(src);
    let (plane, _, _) = cases::planes::plane::<V>(src);
    let (aabb, _, _) = cases::boxes::uniform::<V>(src);
    // Moved so that the ray meets them at some t in (0, 4].
    let at = ray.at(S::<V>::from_f64(src.range(0.0, 4.0)));
    let plane = Plane::new(at, plane.normal);
    let centre = (aabb.min + aabb.max) * S::<V>::HALF;
    let aabb = Aabb::new(aabb.min - centre + at, aabb.max - centre + at);
    // Candidate ends: the float crossings (where there are any), an ulp
    // either side, zero, and anywhere up to 8.
    let mut near = vec![S::<V>::ZERO, S::<V>::INFINITY];
    let all = Interval::up_to(S::<V>::INFINITY).expect("(0, inf]");
    near.extend(tri.hit(&ray, all).map(|h| h.t));
    near.extend(plane.hit(&ray, all));
    near.extend(aabb.hit(&ray, all).map(|h| h.enter));
    let mut end = || {
        let base = near[src.index(near.len())];
        match src.index(4) {
            0 => base,
            1 => base.next_up(),
            2 => base.next_down(),
            _ => S::<V>::from_f64(src.range(0.0, 8.0)),
        }
    };
    let mut ends = [end(), end(), end()];
    ends.sort_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
    Case {
        ray,
        tri,
        plane,
        aabb,
        ends,
    }
}

/// True when the crossings are decided exactly for these inputs: always in
/// `f32`; in `f64`, when every coordinate and end is zero, infinite (an
/// end) or of magnitude in `[2^-100, 2^100]`, well inside the range the
/// kernels document (coordinate differences and their rounding within a
/// factor `2^400` of each other).
fn in_exact_range<V: Vector>(case: &Case<V>) -> bool {
    if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        return true;
    }
    let ok = |x: S<V>| {
        let a = x.to_f64().abs();
        a == 0.0 || (a >= 2f64.powi(-100) && a <= 2f64.powi(100))
    };
    let v = |p: V| ok(p.x()) && ok(p.y()) && ok(p.z());
    let (t, b) = (&case.tri, &case.aabb);
    [case.ray.origin, case.ray.dir, t.a, t.b, t.c]
        .into_iter()
        .chain([case.plane.point, case.plane.normal, b.min, b.max])
        .all(v)
        && case.ends.iter().all(|&e| e == S::<V>::INFINITY || ok(e))
}

fn check<V: Vector>(case: &Case<V>, structured: bool) {
    let [lo, mid, hi] = case.ends;
    let ctx = || {
        format!(
            "ray {:?}, triangle {:?}, plane {:?}, box {:?}, ends {lo:?} {mid:?} {hi:?}",
            case.ray, case.tri, case.plane, case.aabb
        )
    };
    // Interval::new refuses exactly the NaN, negative and inverted ends.
    let valid = |a: S<V>, b: S<V>| S::<V>::ZERO <= a && a <= b;
    for (a, b) in [(lo, mid), (mid, hi), (lo, hi)] {
        assert_eq!(Interval::new(a, b).is_some(), valid(a, b), "{}", ctx());
    }
    let (Some(whole), Some(first), Some(second)) = (
        Interval::new(lo, hi),
        Interval::new(lo, mid),
        Interval::new(mid, hi),
    ) else {
        return;
    };
    let (ray, tri, plane, aabb) = (&case.ray, &case.tri, &case.plane, &case.aabb);
    // In range, finite, in every window.
    for w in [whole, first, second] {
        for t in [
            tri.hit(ray, w).map(|h| h.t),
            tri.hit(ray, (w, EdgeRule::OneHit)).map(|h| h.t),
            plane.hit(ray, w),
        ]
        .into_iter()
        .flatten()
        {
            assert!(
                w.contains(t) && t.is_finite(),
                "t {t:?} in {w:?}: {}",
                ctx()
            );
        }
        let face = aabb.hit(ray, w).map(|h| (h.enter, h.exit));
        assert_eq!(face, aabb.clip(ray, w), "{}", ctx());
        if let Some((enter, exit)) = face {
            assert!(
                w.min() <= enter && enter <= exit && exit <= w.max() && enter.is_finite(),
                "box ({enter:?}, {exit:?}) in {w:?}: {}",
                ctx()
            );
        }
    }
    if !in_exact_range(case) {
        return;
    }
    // No skip, no repeat: the halves report each crossing once between them.
    let once = |name: &str, f: &dyn Fn(Interval<S<V>>) -> bool| {
        let (w, a, b) = (f(whole), f(first), f(second));
        assert_eq!(w, a || b, "{name}: whole {w}, halves {a} {b}: {}", ctx());
        assert!(!(a && b), "{name}: reported in both halves: {}", ctx());
    };
    once("Triangle::hit", &|w| tri.hit(ray, w).is_some());
    once("Triangle::hit, EdgeRule::OneHit", &|w| {
        tri.hit(ray, (w, EdgeRule::OneHit)).is_some()
    });
    once("Plane::hit", &|w| plane.hit(ray, w).is_some());
    once("Aabb::hit's face", &|w| {
        aabb.hit(ray, w).and_then(|h| h.face).is_some()
    });
    // A box the whole window reports: some half reports it too (the halves
    // cover the window; the culling is conservative in each).
    if aabb.clip(ray, whole).is_some() {
        assert!(
            aabb.clip(ray, first).is_some() || aabb.clip(ray, second).is_some(),
            "box culled by both halves: {}",
            ctx()
        );
    }
    if !structured {
        return;
    }
    // Against exact arithmetic.
    for w in [whole, first, second] {
        let exact_plane = exact::ray_plane_in(ray, plane, w.min(), w.max())
            .filter(|t| t.value <= exact::oracle::r(S::<V>::MAX).expect("finite"));
        assert_eq!(
            plane.hit(ray, w).is_some(),
            exact_plane.is_some(),
            "Plane::hit over {w:?} against exact: {}",
            ctx()
        );
        if exact::ray_aabb_in(ray, aabb, w.min(), w.max()).is_some() {
            assert!(
                aabb.clip(ray, w).is_some(),
                "Aabb::clip culled a box exact arithmetic puts in {w:?}: {}",
                ctx()
            );
        }
    }
}
