//! `sphere`: [`Sphere`]'s [`hit`](rayhit::Intersect::hit) over a `t_max`
//! and over an [`Interval`], its [`hit_error`](rayhit::Surface::hit_error)
//! and its [`surface_point`](rayhit::Surface::surface_point).
//!
//! Input: raw mode, a `Ray`, a `Sphere`, `t_max` and two ends `lo`, `hi`
//! as raw bits; structured mode, [`cases::spheres::sphere`] and two ends
//! drawn around the crossings (at them, an ulp either side, or anywhere up
//! to twice the farther).
//!
//! Checks, any input: no panic; a prepared ray gives the same answers bit
//! for bit; `t` finite (never NaN), in `(0, t_max]` for the `t_max` form
//! and in `(lo, hi]` for the interval form (where `Interval::new` takes the
//! ends); `None` for a ray that is not valid, a sphere with a NaN or
//! infinite value, and a NaN or negative `t_max`; a hit's surface point
//! never NaN, and its point and point error finite where the radius is
//! not zero.
//!
//! When every input is finite, against exact arithmetic
//! ([`rayhit::exact::oracle::sphere`]), with `T = min(t_max, MAX)` (no
//! crossing beyond `MAX` has a float `t`; [`Interval`]s cap their ends
//! there too):
//!
//! - the interval form, where its decision is exact ([`decided_exactly`]:
//!   every `f32` input, and `f64` inputs in the documented range): the
//!   exact verdict, the entry where the exact `t-` is in `(lo, min(hi,
//!   MAX)]`, else the exit where `t+` is, else none; a hit's `t` within
//!   `max(hit_error, succ(lo) - lo)` of the exact crossing on its side;
//! - the `t_max` form, where its exact fallback is in range (as for the
//!   interval `(0, T]`): a hit is an exact crossing ahead of the origin
//!   on the side it reports, within `max(hit_error, succ(0))` of it
//!   (`succ(0)`: where the bounds are unusable the form decides `(0,
//!   t_max]` as an interval), or, where the exact line misses the ball, a
//!   false hit of a line within rounding of tangent (documented; then only
//!   the range and finiteness are checked); a hit outside `(0, T]` exactly
//!   is within its bound of `T`; and where the exact verdict over `(0, T]`
//!   is a crossing the form does not report, that crossing is within twice
//!   its bound of `0` (dropped as not surely ahead) or within its bound of
//!   `T` (its computed value above `t_max`);
//! - a hit's surface point: the box within `point_error` of the point
//!   meets the exact sphere (the nearest point of the box is at most `r`
//!   from the centre, the farthest at least `r`).
//!
//! Cost: the exact values are big rationals of the inputs. Raw `f64` inputs
//! reach `2^±1074`, a few thousand bits per number, and each check takes a
//! few dozen operations on them: cheap enough that nothing is skipped
//! (about 5,000 inputs a second on one core, with CI's fuzzing flags).

use core::cmp::Ordering;

use arbitrary::Arbitrary;
use rayhit::exact::oracle::{ExactSphere, R, sphere as exact_sphere};
use rayhit::{Intersect, Interval, Ray, Scalar, Side, Sphere, SphereHit, Surface};
use rayhit::{SurfacePoint, Vector};

use super::exact::{difference_pairs, in_exact_range, int, r, scale_of};
use super::{Check, Input, S, ends_near, forms_in_range, raw};
use crate::cases;
use crate::source::Source;

/// The `sphere` target.
#[derive(Debug)]
pub struct SphereCheck;

/// One input: the ray, the sphere, `t_max`, and the interval's ends.
struct Case<V: Vector> {
    ray: Ray<V>,
    sphere: Sphere<V>,
    t_max: S<V>,
    lo: S<V>,
    hi: S<V>,
}

impl Check for SphereCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let case = match input {
            Input::Raw(u) => Case {
                ray: raw::<Ray<V>>(u),
                sphere: raw::<Sphere<V>>(u),
                t_max: raw::<S<V>>(u),
                lo: raw::<S<V>>(u),
                hi: raw::<S<V>>(u),
            },
            Input::Structured(src) => structured_case::<V>(src),
        };
        check(&case);
    }
}

/// A sphere case, and ends around its crossings.
fn structured_case<V: Vector>(src: &mut Source) -> Case<V> {
    let (sphere, ray, t_max) = cases::spheres::sphere::<V>(src);
    // The crossings over (0, inf], one after the other: each search past
    // the one before by its error bound (a reported `t` may lie below its
    // exact crossing, which a search from `t` would report again).
    let mut crossings = Vec::new();
    let mut from = S::<V>::ZERO;
    while let Some(h) = Interval::new(from, S::<V>::INFINITY).and_then(|w| sphere.hit(&ray, w)) {
        crossings.push(h.t);
        from = (h.t + sphere.hit_error(&ray, &h)).next_up();
        if crossings.len() == 2 || !from.is_finite() {
            break;
        }
    }
    let (lo, hi) = ends_near(src, &crossings);
    Case {
        ray,
        sphere,
        t_max,
        lo,
        hi,
    }
}

/// Whether the sphere's exact signs are documented to decide these inputs
/// against the ends `ends` (already capped at `MAX`), from [`Sphere`]'s
/// `hit` docs: always for `f32`; for `f64` where `c - o` does not overflow
/// and the nonzero values among `c - o` (and its rounding errors) and the
/// radius, each scaled by the power of two that puts their largest in `[1,
/// 2)`, the direction scaled likewise, and each end scaled to match (by
/// `2^(ed - ef)`, with `2^ed` and `2^ef` the two scales) are at least
/// `2^-150`. (An end scaled to `64` or more forms no product; it passes
/// this test too.)
pub fn decided_exactly<V: Vector>(ray: &Ray<V>, sphere: &Sphere<V>, ends: &[S<V>]) -> bool {
    if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        return true;
    }
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let (o, d, c) = (w(ray.origin), w(ray.dir), w(sphere.center));
    let rad = sphere.radius.to_f64().abs();
    let Some(f) = difference_pairs(c, o) else {
        return false;
    };
    let ef = scale_of(&[f[0].0, f[1].0, f[2].0, rad]);
    let ed = scale_of(&d);
    let ok = in_exact_range;
    f.iter().all(|p| ok(p.0, ef) && ok(p.1, ef))
        && ok(rad, ef)
        && d.iter().all(|&x| ok(x, ed))
        && ends.iter().all(|&x| ok(x.to_f64(), ef - ed))
}

/// `x` capped at `MAX`.
fn cap<F: Scalar>(x: F) -> F {
    if x < F::MAX { x } else { F::MAX }
}

/// Whether the exact crossing on `side` lies in `(lo, cap(hi)]` (empty
/// where `lo` is at least `cap(hi)`, an infinite `lo` among them).
fn side_in<F: Scalar>(e: &ExactSphere, side: Side, lo: F, hi: F) -> bool {
    if !(lo < cap(hi)) {
        return false;
    }
    let (lo, hi) = (r(lo), r(cap(hi)));
    match side {
        Side::Front => e.entry_in(&lo, Some(&hi)),
        Side::Back => e.exit_in(&lo, Some(&hi)),
    }
}

/// The exact verdict over `(lo, cap(hi)]`: the entry where it is in, else
/// the exit where it is.
fn verdict<F: Scalar>(e: &ExactSphere, lo: F, hi: F) -> Option<Side> {
    [Side::Front, Side::Back]
        .into_iter()
        .find(|&side| side_in(e, side, lo, hi))
}

/// Whether the exact crossing on `side` exists and is within `err` of `t`
/// (true for an infinite `err`).
fn within<F: Scalar>(e: &ExactSphere, side: Side, t: F, err: F) -> bool {
    if !err.is_finite() {
        return true;
    }
    let (lo, hi) = (r(t) - r(err), r(t) + r(err));
    let place = |x: &R| match side {
        Side::Front => e.entry_cmp(x),
        Side::Back => e.exit_cmp(x),
    };
    place(&lo).is_some_and(|o| o != Ordering::Less) && place(&hi) != Some(Ordering::Greater)
}

/// The larger of two bounds.
fn larger<F: Scalar>(a: F, b: F) -> F {
    if a > b { a } else { b }
}

/// All the sphere checks on one input.
fn check<V: Vector>(case: &Case<V>) {
    let Case {
        ray,
        sphere,
        t_max,
        lo,
        hi,
    } = *case;
    let zero = S::<V>::ZERO;
    let ctx = || format!("ray {ray:?}, sphere {sphere:?}, t_max {t_max:?}, ends {lo:?} {hi:?}");
    let finite = ray.is_valid() && sphere.center.is_finite() && sphere.radius.is_finite();

    // Both forms: range, the prepared ray, invalid input.
    let window = Interval::new(lo, hi);
    let (got, got_in) = forms_in_range(&sphere, &ray, t_max, (lo, hi), finite, |h| h.t, &ctx);
    for h in got.iter().chain(got_in.iter()) {
        surface_point(&ray, &sphere, h, &ctx);
    }
    if !finite {
        return;
    }
    let e = exact_sphere(&ray, sphere.center, sphere.radius)
        .unwrap_or_else(|| panic!("no exact values for a valid ray: {}", ctx()));
    let bound = |side: Side| sphere.hit_error(&ray, &SphereHit { t: zero, side });
    for side in [Side::Front, Side::Back] {
        let b = bound(side);
        assert!(b >= zero, "hit_error {b:?} on {side:?}: {}", ctx());
    }

    // The interval form against the exact verdict.
    if window.is_some() && decided_exactly(&ray, &sphere, &[lo, cap(hi)]) {
        assert_eq!(
            got_in.map(|h| h.side),
            verdict(&e, lo, hi),
            "interval form against the exact verdict: {got_in:?}: {}",
            ctx()
        );
        if let Some(h) = got_in {
            let err = larger(bound(h.side), lo.next_up() - lo);
            assert!(
                within(&e, h.side, h.t, err),
                "interval form: {h:?} beyond its bound {err:?}: {}",
                ctx()
            );
        }
    }

    // The t_max form against exact arithmetic, where it is documented to
    // decide exactly whatever path it takes (its fast path decides from
    // bounds alone, but where it is unsure it places the crossings with
    // the interval form's exact signs).
    if !(t_max >= zero && decided_exactly(&ray, &sphere, &[zero, cap(t_max)])) {
        return;
    }
    if got.is_some() && !e.line_hits() {
        // A false hit of a line within rounding of tangent (documented):
        // the range is all there is to check.
        return;
    }
    let top = cap(t_max);
    if let Some(h) = got {
        assert!(
            side_in(&e, h.side, zero, S::<V>::INFINITY),
            "t_max form: {h:?} not an exact crossing ahead: {}",
            ctx()
        );
        let err = larger(bound(h.side), zero.next_up());
        assert!(
            within(&e, h.side, h.t, err),
            "t_max form: {h:?} beyond its bound {err:?}: {}",
            ctx()
        );
        assert!(
            side_in(&e, h.side, zero, t_max) || within(&e, h.side, top, bound(h.side)),
            "t_max form: {h:?} beyond t_max by more than its bound: {}",
            ctx()
        );
    }
    let expected = verdict(&e, zero, t_max);
    if let Some(side) = expected.filter(|&s| got.map(|h| h.side) != Some(s)) {
        let err = bound(side);
        let twice = err + err;
        assert!(
            within(&e, side, zero, twice) || within(&e, side, top, err),
            "t_max form: {got:?} where exact arithmetic has the {side:?} crossing in (0, t_max], \
             not within its bound {err:?} of an end: {}",
            ctx()
        );
    }
}

/// A hit's surface point: never NaN; finite (point and error) where the
/// radius is not zero; and, where finite, its box meets the exact sphere.
fn surface_point<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    h: &SphereHit<S<V>>,
    ctx: &dyn Fn() -> String,
) {
    let SurfacePoint {
        point,
        point_error,
        normal,
        normal_error,
    } = sphere.surface_point(ray, h);
    let no_nan = |v: V| ![v.x(), v.y(), v.z()].iter().any(|x| x.to_f64().is_nan());
    assert!(
        no_nan(point) && no_nan(point_error) && no_nan(normal) && no_nan(normal_error),
        "NaN in the surface point of {h:?}: {point:?} {point_error:?} {normal:?} {normal_error:?}: {}",
        ctx()
    );
    if sphere.radius != S::<V>::ZERO {
        assert!(
            point.is_finite() && point_error.is_finite(),
            "surface point of {h:?} not finite: {point:?} {point_error:?}: {}",
            ctx()
        );
    }
    if !(point.is_finite() && point_error.is_finite()) {
        return;
    }
    // The box [point - point_error, point + point_error] meets the sphere:
    // its nearest point is at most r from the centre, its farthest at least
    // r.
    let (mut near, mut far) = (int(0), int(0));
    for i in 0..3 {
        let (p, e, c) = (r(point[i]), r(point_error[i]), r(sphere.center[i]));
        let (a, b) = (&p - &e - &c, &p + &e - &c);
        let zero = int(0);
        let gap = if a > zero {
            a.clone()
        } else if b < zero {
            -b.clone()
        } else {
            zero.clone()
        };
        let reach = if -a.clone() > b { -a } else { b };
        near += &gap * &gap;
        far += &reach * &reach;
    }
    let rr = r(sphere.radius) * r(sphere.radius);
    assert!(
        near <= rr && rr <= far,
        "surface point of {h:?}: {point:?} within {point_error:?} misses the sphere: {}",
        ctx()
    );
}
