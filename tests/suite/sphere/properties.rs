//! The sphere's properties, in both precisions, on the crate's strategies
//! (`rayhit::strategies::sphere_and_ray`: rays aimed at the surface,
//! inside the ball or just outside, grazing, from inside), over a `t_max`
//! and over an interval with ends at, beside or away from the crossings:
//!
//! - scaling every position (origin, centre, radius) by `2^k` scales every
//!   `t` by `2^k` exactly, and scaling `dir` by `2^k` scales it by `2^-k`,
//!   with the same side (the ranges scaled to match);
//! - the hit point `ray.at(t)` is within `hit_error |dir|_1` plus its own
//!   rounding of the sphere, checked exactly;
//! - no NaN, `t` in range, and the side consistent with where the origin
//!   is (exactly): never an entry from inside the ball or from its
//!   surface, never an exit over `(0, inf]` from outside;
//! - `Sphere::bounds` holds every surface point within its `point_error`.
//!
//! Bounds are evaluated exactly (see `common::props`).

use super::{S, exact, q, within};
use crate::common::props::{abs, config, ends_among, in_both_precisions};
use proptest::prelude::*;
use rayhit::exact::oracle::R;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Intersect, Interval, Ray, Scalar, Side, Sphere, SphereHit, Surface, Vector};
use rayhit_testkit::oracle::{gamma, int};

/// The crossings the sphere reports over `(0, inf]`, in order: each
/// search starts past the one before by its error bound (rounded up; as
/// `Walk` cuts its windows), since the reported `t` may lie below the exact
/// crossing, which the next window would then report again.
fn crossings<V: Vector>(ray: &Ray<V>, sph: &Sphere<V>) -> Vec<S<V>> {
    let mut found = Vec::new();
    let mut from = S::<V>::ZERO;
    while let Some(h) = Interval::new(from, S::<V>::INFINITY).and_then(|w| sph.hit(ray, w)) {
        found.push(h.t);
        from = (h.t + sph.hit_error(ray, &h)).next_up();
        if found.len() == 2 || !from.is_finite() {
            break;
        }
    }
    found
}

/// The farther of the reported crossings, or 1.
fn farther<V: Vector>(ray: &Ray<V>, sph: &Sphere<V>) -> S<V> {
    crossings(ray, sph)
        .into_iter()
        .fold(S::<V>::ONE, |m, t| if t > m { t } else { m })
}

/// Ends of an interval around the reported crossings ([`ends_among`]).
fn ends<V: Vector>(ray: &Ray<V>, sph: &Sphere<V>, picks: [f64; 2]) -> (S<V>, S<V>) {
    ends_among(&crossings(ray, sph), picks)
}

/// The answers over a `t_max` and over `(lo, hi]`.
type Answers<F> = (Option<SphereHit<F>>, Option<SphereHit<F>>);

fn answers<V: Vector>(
    ray: &Ray<V>,
    sph: &Sphere<V>,
    t_max: S<V>,
    (lo, hi): (S<V>, S<V>),
) -> Answers<S<V>> {
    let window = Interval::new(lo, hi).expect("ordered ends");
    (sph.hit(ray, t_max), sph.hit(ray, window))
}

/// `answers` on the transformed inputs are those on the originals with
/// every `t` mapped by `map` (its range mapped too), side for side.
#[allow(clippy::too_many_arguments)]
fn check_map<V: Vector>(
    (ray, sph): (Ray<V>, Sphere<V>),
    (ray2, sph2): (Ray<V>, Sphere<V>),
    t_max: S<V>,
    (lo, hi): (S<V>, S<V>),
    map: impl Fn(S<V>) -> S<V>,
) -> Result<(), TestCaseError> {
    let (plain, within_range) = answers(&ray, &sph, t_max, (lo, hi));
    let (plain2, within_range2) = answers(&ray2, &sph2, map(t_max), (map(lo), map(hi)));
    let mapped = |h: Option<SphereHit<S<V>>>| h.map(|h| SphereHit { t: map(h.t), ..h });
    prop_assert_eq!(plain2, mapped(plain), "t_max form, t_max {:?}", t_max);
    prop_assert_eq!(
        within_range2,
        mapped(within_range),
        "interval form, ({:?}, {:?}]",
        lo,
        hi
    );
    Ok(())
}

/// Scaling the origin, the centre and the radius by `2^k` (and keeping
/// `dir`) scales every `t` by `2^k` exactly: every quantity the kernel
/// forms scales by a power of two (`F`, `nd`, `C` by `2^k`; `ff`, `rr`,
/// `k`, `x` and the root's square by `4^k`), so every rounding and every
/// comparison with an error bound is the same, except for the bounds'
/// `MIN_POSITIVE` terms (underflow slack), which do not scale; within the
/// strategies' ranges (no value below `2^-40` where it is not zero) they
/// are far below an ulp of the sums they are added to and leave them
/// unchanged. The exact signs are scaled to `[1, 2)` before use (`f64`)
/// or exact (`f32`), so they decide alike.
fn check_position_scaling<V: Vector>(
    sph: Sphere<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (
        Ray::new(ray.origin * s, ray.dir),
        Sphere::new(sph.center * s, sph.radius * s),
    );
    let window = ends(&ray, &sph, picks);
    check_map((ray, sph), scaled, t_max, window, |t| t * s)
}

/// Scaling `dir` by `2^k` scales every `t` by `2^-k` exactly: `a` scales
/// by `4^k`, `nd` and `C` by `2^k`, `x` by `4^k`, the root and `q` by
/// `2^k`, and both `q / a` and `k / q` by `2^-k`, each bound with them
/// (the same `MIN_POSITIVE` terms aside, as for positions).
fn check_direction_scaling<V: Vector>(
    sph: Sphere<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (Ray::new(ray.origin, ray.dir * s), sph);
    let window = ends(&ray, &sph, picks);
    check_map((ray, sph), scaled, t_max, window, |t| t / s)
}

/// The hit point `p = fl(o + fl(t d))` is within `B` of the sphere: `|p -
/// c|` within `B` of `r`, where, with `t*` the exact crossing on the hit's
/// side (`|t - t*| <= err`, the kernel's bound) and `p* = o + t* d` on the
/// sphere, `|p - p*| <= err |d| + |p - (o + t d)|`, and each component of
/// the second term is at most `gamma(2) (|o_j| + |t d_j|)` (two
/// roundings); both norms are at most the sums of the components, so `B =
/// err |d|_1 + gamma(2) sum_j (|o_j| + |t d_j|)`. Checked exactly, as
/// `(r - B)^2 <= |p - c|^2 <= (r + B)^2` (the left where `r > B`).
fn point_near_sphere<V: Vector>(
    ray: &Ray<V>,
    sph: &Sphere<V>,
    h: &SphereHit<S<V>>,
    err: S<V>,
) -> Result<(), TestCaseError> {
    let p = ray.at(h.t);
    let (t, e) = (q(h.t), q(err));
    let g2 = gamma::<S<V>>(2);
    let mut b = int(0);
    let mut dist2 = int(0);
    for j in 0..3 {
        let (o, d) = (q(ray.origin[j]), q(ray.dir[j]));
        b += &e * abs(&d) + &g2 * (abs(&o) + &t * abs(&d));
        let off = q(p[j]) - q(sph.center[j]);
        dist2 += &off * &off;
    }
    let r = q(sph.radius.abs());
    let outer = (&r + &b) * (&r + &b);
    let inner: R = if r > b { (&r - &b) * (&r - &b) } else { int(0) };
    prop_assert!(
        inner <= dist2 && dist2 <= outer,
        "hit point {:?} of {:?} off the sphere by more than {} (bound {:?})",
        p,
        h,
        rayhit::exact::oracle::to_f64(&b),
        err
    );
    Ok(())
}

/// `point_near_sphere` for the `t_max` form over `t_max` and the interval
/// form over `(lo, hi]` (`t` brought into the interval: its bound is
/// `max(err, succ(lo) - lo)`), where the exact line meets the ball (a
/// false hit of a line within rounding of tangent has no exact crossing
/// to be near) and the bound is finite.
fn check_hit_point<V: Vector>(
    sph: Sphere<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
) -> Result<(), TestCaseError> {
    let e = exact(&ray, &sph);
    if !e.line_hits() {
        return Ok(());
    }
    let (lo, hi) = ends(&ray, &sph, picks);
    let (plain, within_range) = answers(&ray, &sph, t_max, (lo, hi));
    let floor = |lo: S<V>| lo.next_up() - lo;
    for (h, least) in [(plain, floor(S::<V>::ZERO)), (within_range, floor(lo))] {
        let Some(h) = h else { continue };
        let err = sph.hit_error(&ray, &h);
        let err = if err > least { err } else { least };
        if err.is_finite() {
            prop_assert!(within(&e, h.side, h.t, err), "{h:?} beyond {err:?}");
            point_near_sphere(&ray, &sph, &h, err)?;
        }
    }
    Ok(())
}

/// No NaN and `t` in range, for both forms; and the side against where the
/// origin is, exactly (`k = |c - o|^2 - r^2`): an origin inside the ball
/// (`k < 0`) or on the sphere (`k = 0`: the crossing there is at `t = 0`,
/// outside every range) never reports an entry, over any `t_max` or
/// interval; an origin outside (`k > 0`) never reports an exit over `(0,
/// inf]` (both crossings are then on one side of the origin, and where they
/// are ahead the entry comes first).
fn check_range_and_side<V: Vector>(
    sph: Sphere<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
) -> Result<(), TestCaseError> {
    let (lo, hi) = ends(&ray, &sph, picks);
    let (plain, within_range) = answers(&ray, &sph, t_max, (lo, hi));
    let (zero, inf) = (S::<V>::ZERO, S::<V>::INFINITY);
    let all = Interval::up_to(inf).expect("(0, inf]");
    let (plain_inf, all_inf) = (sph.hit(&ray, inf), sph.hit(&ray, all));
    for (h, top) in [(plain, t_max), (plain_inf, inf)] {
        if let Some(h) = h {
            prop_assert!(
                h.t > zero && h.t <= top && h.t.is_finite(),
                "{h:?} outside (0, {top:?}]"
            );
        }
    }
    for (h, (a, b)) in [(within_range, (lo, hi)), (all_inf, (zero, inf))] {
        if let Some(h) = h {
            prop_assert!(
                a < h.t && h.t <= b && h.t.is_finite(),
                "{h:?} outside ({a:?}, {b:?}]"
            );
        }
    }
    let e = exact(&ray, &sph);
    let k_sign = e.k.cmp(&int(0));
    if k_sign != core::cmp::Ordering::Greater {
        for h in [plain, plain_inf, within_range, all_inf]
            .into_iter()
            .flatten()
        {
            prop_assert_eq!(
                h.side,
                Side::Back,
                "an entry from an origin with k {:?} 0",
                k_sign
            );
        }
    } else if let Some(h) = all_inf {
        prop_assert_eq!(h.side, Side::Front, "an exit over (0, inf] from outside");
    }
    Ok(())
}

/// `Sphere::bounds` holds every surface point within its `point_error`:
/// the exact point `q` the bound is about lies on the sphere, so in the
/// ball, so in the box, and `|point_i - q_i| <= point_error_i`; so
/// `min_i - point_error_i <= point_i <= max_i + point_error_i`, checked
/// exactly. For the hits of both forms and for the point of the ray at a
/// `t` drawn up to twice the farther crossing (`surface_point` moves any
/// point onto the sphere).
fn check_bounds<V: Vector>(
    sph: Sphere<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    along: f64,
) -> Result<(), TestCaseError> {
    let (lo, hi) = ends(&ray, &sph, picks);
    let (plain, within_range) = answers(&ray, &sph, t_max, (lo, hi));
    let anywhere = SphereHit {
        t: S::<V>::from_f64(along) * farther(&ray, &sph),
        side: Side::Front,
    };
    let b = sph.bounds();
    for h in [plain, within_range, Some(anywhere)].into_iter().flatten() {
        let sp = sph.surface_point(&ray, &h);
        prop_assert!(sp.point.is_finite() && sp.point_error.is_finite(), "{sp:?}");
        for i in 0..3 {
            let (p, err) = (q(sp.point[i]), q(sp.point_error[i]));
            prop_assert!(
                q(b.min[i]) - &err <= p && p <= q(b.max[i]) + &err,
                "surface point {:?} (within {:?}) of {:?} outside the box {:?} on axis {}",
                sp.point,
                sp.point_error,
                h,
                b,
                i
            );
        }
    }
    Ok(())
}

in_both_precisions! {
    fn position_scaling((sph, ray) in strat::sphere_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), k in -8i32..=8) {
        check_position_scaling(sph, ray, t_max, picks, k)?;
    }

    fn direction_scaling((sph, ray) in strat::sphere_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), k in -8i32..=8) {
        check_direction_scaling(sph, ray, t_max, picks, k)?;
    }

    fn hit_point_on_sphere((sph, ray) in strat::sphere_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64)) {
        check_hit_point(sph, ray, t_max, picks)?;
    }

    fn range_and_side((sph, ray) in strat::sphere_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64)) {
        check_range_and_side(sph, ray, t_max, picks)?;
    }

    fn bounds_hold_surface_points((sph, ray) in strat::sphere_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), along in 0.0..=2.0f64) {
        check_bounds(sph, ray, t_max, picks, along)?;
    }
}
