//! `disc`: [`Disc`]'s [`hit`](rayhit::Intersect::hit) over a `t_max` and
//! over an [`Interval`], its [`hit_error`](rayhit::Surface::hit_error),
//! its [`surface_point`](rayhit::Surface::surface_point) and
//! [`Disc::bounds`].
//!
//! Input: raw mode, a `Ray`, a `Disc` (centre, normal, radius, inner
//! radius), `t_max` and two ends `lo`, `hi` as raw bits; structured mode,
//! [`cases::discs::disc`] and two ends drawn around the crossing (at it, an
//! ulp either side, or anywhere up to twice it).
//!
//! Checks, any input: no panic; a prepared ray gives the same answers bit
//! for bit; `t` finite (never NaN), in `(0, t_max]` for the `t_max` form
//! and in `(lo, hi]` for the interval form (where `Interval::new` takes the
//! ends); `None` for a ray that is not valid, a disc with a NaN or infinite
//! value or a zero normal, and a NaN or negative `t_max` (and a hole
//! larger than the disc, which the checks against exact arithmetic
//! cover where the decision is exact); a hit's surface point never NaN, with the disc's
//! normal, bit for bit, and a zero normal error.
//!
//! When every input is finite, against exact arithmetic
//! ([`rayhit::exact::oracle::disc`]: the crossing `t*` of the ray's line
//! with the disc's plane, and whether it lies within both closed circles),
//! with `T = min(t_max, MAX)` (no crossing beyond `MAX` has a float `t`;
//! [`Interval`]s cap their ends there too):
//!
//! - where the line meets the plane exactly within the circles (at any
//!   `t`, hit or not), that point lies in [`Disc::bounds`]; where `d . n`
//!   is exactly zero, both forms miss;
//! - the interval form, where its decision is documented exact
//!   ([`decided_exactly`]: every `f32` input, `f64` inputs in the
//!   documented range): a hit exactly where `t*` is in `(lo, min(hi,
//!   MAX)]` and within the circles, on the exact side (`Front` where `d .
//!   n < 0`); a hit's `t` within `max(hit_error, succ(lo) - lo)` of `t*`;
//! - the `t_max` form, in the same range: a hit's `t` is the plane test's
//!   ([`ray_plane`]) bit for bit, `t*` is ahead (`t* > 0`) and within the
//!   circles, on the exact side, and `t` within `hit_error` of it (so `t*`
//!   is at most `hit_error` beyond `t_max`); where `t*` is in `(0, T]`
//!   within the circles and the form misses, the plane test misses too (the
//!   ray within rounding of parallel, or the computed `t` not in `(0,
//!   t_max]`), or its `t` is within `hit_error` of `0` (dropped as not
//!   surely ahead);
//! - a hit's surface point is within its `point_error` of the exact
//!   crossing, per component (for the interval form, with the bound on `t`
//!   widened to `max(hit_error, succ(lo) - lo)` as `hit_error` documents).
//!
//! The bounds on `t` and on the point are relative-error arguments, which
//! assume that no intermediate product underflows (the crate's docs): they
//! are checked only where the plane check's [`no_underflow`] holds (for
//! structured inputs too, which scale positions and normals down to
//! `2^-46`); every decision, exact by contract, is checked everywhere.
//!
//! Cost: the exact values are big rationals of the inputs, a few dozen
//! operations on numbers of up to a few thousand bits for raw `f64` inputs.

use arbitrary::Arbitrary;
use rayhit::exact::oracle::{ExactDisc, R, disc as exact_disc};
use rayhit::{Aabb, Disc, DiscHit, Intersect, Interval, Plane, Ray, Scalar};
use rayhit::{Surface, SurfacePoint, Vector, ray_plane};

use super::exact::{abs, difference_pairs, in_exact_range, r, scale_of};
use super::plane::no_underflow;
use super::{Check, Input, S, ends_near, forms_in_range, raw};
use crate::cases;
use crate::source::Source;

/// The `disc` target.
#[derive(Debug)]
pub struct DiscCheck;

/// One input: the ray, the disc, `t_max`, and the interval's ends.
struct Case<V: Vector> {
    ray: Ray<V>,
    disc: Disc<V>,
    t_max: S<V>,
    lo: S<V>,
    hi: S<V>,
}

impl Check for DiscCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let case = match input {
            Input::Raw(u) => Case {
                ray: raw::<Ray<V>>(u),
                disc: raw::<Disc<V>>(u),
                t_max: raw::<S<V>>(u),
                lo: raw::<S<V>>(u),
                hi: raw::<S<V>>(u),
            },
            Input::Structured(src) => structured_case::<V>(src),
        };
        check(&case);
    }
}

/// A disc case, and ends around its crossing.
fn structured_case<V: Vector>(src: &mut Source) -> Case<V> {
    let (disc, ray, t_max) = cases::discs::disc::<V>(src);
    let crossing = Interval::up_to(S::<V>::INFINITY)
        .and_then(|w| disc.hit(&ray, w))
        .map(|h| h.t);
    let (lo, hi) = ends_near(src, crossing.as_slice());
    Case {
        ray,
        disc,
        t_max,
        lo,
        hi,
    }
}

/// Whether the disc's decisions are documented exact for these inputs,
/// from [`Disc`]'s `hit` docs: always for `f32`; for `f64` where `c - o`
/// does not overflow and the nonzero values among `c - o` (and its rounding
/// errors) with the radius asked about (the outer one, and the inner one
/// where it is not zero), each scaled by the power of two that puts their
/// largest in `[1, 2)`, and among `dir` and among `normal`, each scaled
/// likewise, are at least `2^-150`.
pub fn decided_exactly<V: Vector>(ray: &Ray<V>, disc: &Disc<V>) -> bool {
    if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        return true;
    }
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let (o, d, c, n) = (w(ray.origin), w(ray.dir), w(disc.center), w(disc.normal));
    let Some(f) = difference_pairs(c, o) else {
        return false;
    };
    let ok = in_exact_range;
    let (outer, inner) = (disc.radius.to_f64().abs(), disc.inner_radius.to_f64().abs());
    let radius_ok = |rad: f64| {
        let ef = scale_of(&[f[0].0, f[1].0, f[2].0, rad]);
        f.iter().all(|p| ok(p.0, ef) && ok(p.1, ef)) && ok(rad, ef)
    };
    let (ed, en) = (scale_of(&d), scale_of(&n));
    radius_ok(outer)
        && (inner == 0.0 || radius_ok(inner))
        && d.iter().all(|&x| ok(x, ed))
        && n.iter().all(|&x| ok(x, en))
}

/// `x` capped at `MAX`.
fn cap<F: Scalar>(x: F) -> F {
    if x < F::MAX { x } else { F::MAX }
}

/// Whether the disc is crossed exactly within `(lo, cap(hi)]` (empty where
/// `lo` is at least `cap(hi)`, an infinite `lo` among them).
fn verdict<F: Scalar>(e: &ExactDisc, lo: F, hi: F) -> bool {
    lo < cap(hi) && e.hit_in(&r(lo), Some(&r(cap(hi))))
}

/// Whether `t*` is within `err` of `t` (true for an infinite `err`).
fn within<F: Scalar>(e: &ExactDisc, t: F, err: F) -> bool {
    !err.is_finite() || abs(&(r(t) - &e.t)) <= r(err)
}

/// The larger of two bounds.
fn larger<F: Scalar>(a: F, b: F) -> F {
    if a > b { a } else { b }
}

/// All the disc checks on one input.
fn check<V: Vector>(case: &Case<V>) {
    let Case {
        ray,
        disc,
        t_max,
        lo,
        hi,
    } = *case;
    let zero = S::<V>::ZERO;
    let ctx = || format!("ray {ray:?}, disc {disc:?}, t_max {t_max:?}, ends {lo:?} {hi:?}");
    let finite = ray.is_valid()
        && disc.center.is_finite()
        && disc.normal.is_finite()
        && disc.radius.is_finite()
        && disc.inner_radius.is_finite();
    // A hole larger than the disc leaves nothing to hit, but that is a
    // decision of the rims, which is exact only in range (`f64`): checked
    // below, against exact arithmetic, where `decided_exactly`.
    let hittable = finite && disc.normal != V::ZERO;

    // Both forms: range, the prepared ray, invalid input.
    let window = Interval::new(lo, hi);
    let (got, got_in) = forms_in_range(&disc, &ray, t_max, (lo, hi), hittable, |h| h.t, &ctx);
    let surface = |h: &DiscHit<S<V>>| {
        let sp = disc.surface_point(&ray, h);
        no_nan(&sp, disc.normal, h, &ctx);
        sp
    };
    let (sp, sp_in) = (got.as_ref().map(surface), got_in.as_ref().map(surface));
    if !finite {
        return;
    }
    let Some(e) = exact_disc(&ray, &disc) else {
        // `d . n` exactly zero: no crossing.
        assert!(
            got.is_none() && got_in.is_none(),
            "a hit where the ray is exactly parallel to the plane: {got:?} {got_in:?}: {}",
            ctx()
        );
        return;
    };
    if e.within_rims() {
        in_bounds(&ray, &disc, &e, &ctx);
    }
    let plane = Plane::new(disc.center, disc.normal);
    let bounded = no_underflow(&ray, &plane);
    if !decided_exactly(&ray, &disc) {
        return;
    }
    let bound = |h: &DiscHit<S<V>>| disc.hit_error(&ray, h);

    // The interval form against the exact verdict.
    if window.is_some() {
        let expected = verdict(&e, lo, hi).then_some(e.side);
        assert_eq!(
            got_in.map(|h| h.side),
            expected,
            "interval form against the exact verdict {e:?}: {got_in:?}: {}",
            ctx()
        );
        if let (Some(h), Some(sp), true) = (got_in, sp_in, bounded) {
            let ulp = lo.next_up() - lo;
            let err = larger(bound(&h), ulp);
            assert!(
                within(&e, h.t, err),
                "interval form: {h:?} beyond its bound {err:?} of t* {}: {}",
                rayhit::exact::oracle::to_f64(&e.t),
                ctx()
            );
            // `t` within `max(b, ulp)` of `t*` rather than `b`: the point's
            // bound (`b |d_j|` plus rounding) grows by `(ulp - b) |d_j|`.
            let b = bound(&h);
            let extra = if b.is_finite() && ulp > b {
                r(ulp) - r(b)
            } else {
                r(zero)
            };
            point_near(&ray, &e, &sp, &extra, &h, &ctx);
        }
    }

    // The t_max form against exact arithmetic.
    if !(t_max >= zero) {
        return;
    }
    let plane_t = ray_plane(&ray, &plane, t_max);
    if let Some(h) = got {
        assert_eq!(
            Some(h.t),
            plane_t,
            "t_max form: {h:?} is not the plane test's t: {}",
            ctx()
        );
        assert!(
            e.t > r(zero) && e.within_rims() && h.side == e.side,
            "t_max form: {h:?} not an exact crossing ahead within the circles ({e:?}): {}",
            ctx()
        );
        if let (Some(sp), true) = (sp, bounded) {
            let err = bound(&h);
            assert!(
                within(&e, h.t, err),
                "t_max form: {h:?} beyond its bound {err:?} of t* {}: {}",
                rayhit::exact::oracle::to_f64(&e.t),
                ctx()
            );
            point_near(&ray, &e, &sp, &r(zero), &h, &ctx);
        }
    } else if verdict(&e, zero, t_max) {
        // A miss the docs allow: the plane test's own drop (within rounding
        // of parallel, or its computed `t` not in `(0, t_max]`), or a `t`
        // within its bound of `0`; or the bound outside its precondition
        // (underflow; or where the bound is unusable, see `unusable`).
        let allowed = plane_t.is_none_or(|t| {
            !bounded || unusable(&ray, &plane) || !(t > bound(&DiscHit { t, side: e.side }))
        });
        assert!(
            allowed,
            "t_max form: a miss where exact arithmetic has the crossing in (0, t_max] within \
             the circles ({e:?}), the plane test's t {plane_t:?} beyond its bound of 0: {}",
            ctx()
        );
    }
}

/// Whether the plane test's numerator `(point - origin) . normal`,
/// denominator `dir . normal` or quotient is below `8 MIN_POSITIVE / u`
/// (`2^-99` in `f32`, `2^-966` in `f64`): there the bound's derivation,
/// which counts every rounding as relative, does not cover underflow
/// ([`Plane`]'s `hit` docs), and the `t_max` form treats the bound as
/// infinite (drops the crossing as not surely ahead). (Reached through
/// cancellation even where no product underflows.)
fn unusable<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> bool {
    let floor = S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF;
    let numer = (plane.point - ray.origin).dot(plane.normal);
    let denom = ray.dir.dot(plane.normal);
    let t = numer / denom;
    !(numer.abs() >= floor && denom.abs() >= floor && t.abs() >= floor)
}

/// A hit's surface point: never NaN; the disc's normal, bit for bit, with
/// a zero error.
fn no_nan<V: Vector>(
    sp: &SurfacePoint<V>,
    disc_normal: V,
    h: &DiscHit<S<V>>,
    ctx: &dyn Fn() -> String,
) {
    let SurfacePoint {
        point,
        point_error,
        normal,
        normal_error,
    } = *sp;
    let no_nan = |v: V| ![v.x(), v.y(), v.z()].iter().any(|x| x.to_f64().is_nan());
    assert!(
        no_nan(point) && no_nan(point_error) && no_nan(normal) && no_nan(normal_error),
        "NaN in the surface point of {h:?}: {sp:?}: {}",
        ctx()
    );
    let bits = |v: V| [v.x(), v.y(), v.z()].map(|x| x.to_f64().to_bits());
    assert!(
        bits(normal) == bits(disc_normal) && normal_error == V::ZERO,
        "surface point of {h:?}: normal {normal:?} with error {normal_error:?}: {}",
        ctx()
    );
}

/// The exact crossing `p* = o + t* d` is within `point_error` of the
/// surface point, per component, with `extra |d_j|` added for a `t`
/// brought into an interval (`extra`: how far its documented bound exceeds
/// `hit_error`).
fn point_near<V: Vector>(
    ray: &Ray<V>,
    e: &ExactDisc,
    sp: &SurfacePoint<V>,
    extra: &R,
    h: &DiscHit<S<V>>,
    ctx: &dyn Fn() -> String,
) {
    for j in 0..3 {
        if !(sp.point[j].is_finite() && sp.point_error[j].is_finite()) {
            continue;
        }
        let d = r(ray.dir[j]);
        let star = r(ray.origin[j]) + &e.t * &d;
        let allowed = r(sp.point_error[j]) + extra * abs(&d);
        assert!(
            abs(&(r(sp.point[j]) - star)) <= allowed,
            "surface point of {h:?}: axis {j} of {:?} not within {:?} of the exact crossing: {}",
            sp.point,
            sp.point_error,
            ctx()
        );
    }
}

/// The exact crossing lies in [`Disc::bounds`] (an infinite face holds
/// everything on its side).
fn in_bounds<V: Vector>(ray: &Ray<V>, disc: &Disc<V>, e: &ExactDisc, ctx: &dyn Fn() -> String) {
    let Aabb { min, max } = disc.bounds();
    for i in 0..3 {
        let p: R = r(ray.origin[i]) + &e.t * r(ray.dir[i]);
        let above = |f: S<V>| f == -S::<V>::INFINITY || (f.is_finite() && r(f) <= p);
        let below = |f: S<V>| f == S::<V>::INFINITY || (f.is_finite() && p <= r(f));
        assert!(
            above(min[i]) && below(max[i]),
            "the exact crossing at {:?} is outside the bounds {min:?} {max:?} on axis {i}: {}",
            rayhit::exact::oracle::to_f64(&p),
            ctx()
        );
    }
}
