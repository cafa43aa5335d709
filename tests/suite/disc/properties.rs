//! The disc's properties, in both precisions, on the crate's strategies
//! (`rayhit::strategies::disc_and_ray`: discs, annuli and rings of no
//! width; rays aimed at either circle, just off them, inside the annulus,
//! in the hole or outside, from anywhere, nearly along the plane or from
//! the plane itself), over a `t_max` and over an interval with ends at,
//! beside or away from the crossing:
//!
//! - scaling every position (origin, centre) and both radii by `2^k`
//!   scales every `t` by `2^k` exactly, scaling `dir` by `2^k` scales it by
//!   `2^-k`, and scaling the normal by `2^k` changes nothing, with the same
//!   side, bit for bit (the ranges scaled to match);
//! - a hit's point is within its `point_error` of the exact plane and of
//!   the exact crossing, which lies ahead and within the closed annulus,
//!   all judged exactly;
//! - a hit's side is the exact side of the plane the origin is on (and an
//!   origin exactly on the plane has no hit);
//! - three consecutive intervals `(0, a]`, `(a, b]`, `(b, inf]` report a
//!   crossing exactly once, in the interval that holds it exactly, and
//!   none where exact arithmetic has none;
//! - `Disc::bounds` holds the exact crossing of the ray's line with the
//!   plane wherever that is within the circles (hit or not, at any `t`).
//!
//! Bounds are evaluated exactly (see `common::props`).

use crate::common::props::{abs, config, ends_among, in_both_precisions};
use crate::sphere::q;
use proptest::prelude::*;
use rayhit::exact::oracle::{ExactDisc, R, disc as exact_disc, dot, rv, sub};
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Disc, DiscHit, Intersect, Interval, Ray, Scalar, Side, Surface, Vector};
use rayhit_testkit::oracle::int;
use std::cmp::Ordering;

type S<V> = <V as Vector>::Scalar;

/// The crossing the disc reports over `(0, inf]`, if any.
fn crossing<V: Vector>(ray: &Ray<V>, d: &Disc<V>) -> Option<S<V>> {
    Interval::up_to(S::<V>::INFINITY)
        .and_then(|w| d.hit(ray, w))
        .map(|h| h.t)
}

/// Ends of an interval around the reported crossing ([`ends_among`]).
fn ends<V: Vector>(ray: &Ray<V>, d: &Disc<V>, picks: [f64; 2]) -> (S<V>, S<V>) {
    ends_among(crossing(ray, d).as_slice(), picks)
}

/// The answers over a `t_max` and over `(lo, hi]`.
type Answers<F> = (Option<DiscHit<F>>, Option<DiscHit<F>>);

fn answers<V: Vector>(
    ray: &Ray<V>,
    d: &Disc<V>,
    t_max: S<V>,
    (lo, hi): (S<V>, S<V>),
) -> Answers<S<V>> {
    let window = Interval::new(lo, hi).expect("ordered ends");
    (d.hit(ray, t_max), d.hit(ray, window))
}

/// `answers` on the transformed inputs are those on the originals with
/// every `t` mapped by `map` (its range mapped too), side for side. Two
/// exceptions, both where a power-of-two scaling is not exact: a `t`
/// brought into `(lo, hi]` is the successor of `lo` (documented), which
/// scales with `lo` only where both are normal (the successor of `0` is the
/// smallest subnormal at every scale); and ends that are subnormal before
/// or after mapping do not map exactly, so the interval form is not
/// compared there.
fn check_map<V: Vector>(
    (ray, d): (Ray<V>, Disc<V>),
    (ray2, d2): (Ray<V>, Disc<V>),
    t_max: S<V>,
    (lo, hi): (S<V>, S<V>),
    map: impl Fn(S<V>) -> S<V>,
) -> Result<(), TestCaseError> {
    let (plain, within_range) = answers(&ray, &d, t_max, (lo, hi));
    let (plain2, within_range2) = answers(&ray2, &d2, map(t_max), (map(lo), map(hi)));
    let mapped = |h: Option<DiscHit<S<V>>>| h.map(|h| DiscHit { t: map(h.t), ..h });
    prop_assert_eq!(plain2, mapped(plain), "t_max form, t_max {:?}", t_max);
    let normal = |x: S<V>| x.abs() >= S::<V>::MIN_POSITIVE || x == S::<V>::ZERO;
    let exact_ends = [lo, hi].iter().all(|&x| normal(x) && normal(map(x)));
    let brought_in = matches!(
        (within_range, within_range2),
        (Some(a), Some(b)) if a.t == lo.next_up() && b.t == map(lo).next_up() && a.side == b.side
    );
    if exact_ends && !brought_in {
        prop_assert_eq!(
            within_range2,
            mapped(within_range),
            "interval form, ({:?}, {:?}]",
            lo,
            hi
        );
    }
    Ok(())
}

/// Scaling the origin, the centre and both radii by `2^k` (and keeping
/// `dir` and the normal) scales every `t` by `2^k` exactly: `c - o` and so
/// the numerator scale by `2^k`, the denominator is unchanged, and the
/// quotient, its bound, the hit point, `|p - c|^2` and the squared radii
/// (by `4^k`) scale with them; every rounding and every comparison with a
/// bound is the same, but for the rims' underflow slack (`MIN_POSITIVE`
/// terms, which do not scale): where that moves a decision from the filter
/// to the exact signs, those decide exactly, alike at both scales.
fn check_position_scaling<V: Vector>(
    d: Disc<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (
        Ray::new(ray.origin * s, ray.dir),
        Disc::annulus(d.center * s, d.normal, d.radius * s, d.inner_radius * s),
    );
    let window = ends(&ray, &d, picks);
    check_map((ray, d), scaled, t_max, window, |t| t * s)
}

/// Scaling `dir` by `2^k` scales every `t` by `2^-k` exactly: the
/// denominator and its bound scale by `2^k`, the numerator is unchanged,
/// so `t` and its bound scale by `2^-k`, and `t dir`, the hit point and
/// the rims' test are unchanged.
fn check_direction_scaling<V: Vector>(
    d: Disc<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (Ray::new(ray.origin, ray.dir * s), d);
    let window = ends(&ray, &d, picks);
    check_map((ray, d), scaled, t_max, window, |t| t / s)
}

/// Scaling the normal by `2^k` changes no answer: numerator, denominator
/// and their bounds all scale by `2^k`, their quotients do not.
fn check_normal_scaling<V: Vector>(
    d: Disc<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (
        ray,
        Disc {
            normal: d.normal * s,
            ..d
        },
    );
    let window = ends(&ray, &d, picks);
    check_map((ray, d), scaled, t_max, window, |t| t)
}

/// The exact values of a case (the strategies' normals are never zero,
/// but a ray may be exactly parallel to the plane).
fn exact<V: Vector>(ray: &Ray<V>, d: &Disc<V>) -> Option<ExactDisc> {
    exact_disc(ray, d)
}

/// A hit's surface point `p` with its bound `e` (`|p_j - p*_j| <= e_j`
/// documented, for the exact crossing `p*`; for a `t` brought into an
/// interval the bound on `t` is `max(hit_error, succ(lo) - lo)`, which adds
/// `(succ(lo) - lo - hit_error) |d_j|` where positive): the exact crossing
/// lies ahead of `lo` (`t* > lo`) and within the closed annulus; `p` is
/// within `e` of it, and so the box `[p - e, p + e]` meets the exact plane
/// (checked on its own: `n . (p - c)` is within `sum_j |n_j| e_j` of zero).
/// The `t_max` form's bound is always finite; the interval form's is
/// infinite for a ray within rounding of parallel (then only `t*` is
/// checked).
fn check_point<V: Vector>(
    ray: &Ray<V>,
    d: &Disc<V>,
    h: &DiscHit<S<V>>,
    lo: S<V>,
    interval_form: bool,
) -> Result<(), TestCaseError> {
    let e = exact(ray, d);
    prop_assert!(e.is_some(), "{h:?} where the ray is parallel to the plane");
    let e = e.expect("checked");
    prop_assert!(e.t > q(lo), "{h:?}: t* {:?} not above {lo:?}", e.t);
    prop_assert!(
        e.within_rims(),
        "{h:?}: the exact crossing is off the annulus"
    );
    let sp = d.surface_point(ray, h);
    let err = d.hit_error(ray, h);
    if interval_form && !err.is_finite() {
        // A ray within rounding of parallel, decided exactly by the
        // interval form: its `t` has no error bound (documented), nor has
        // its point.
        return Ok(());
    }
    prop_assert!(
        sp.point.is_finite() && sp.point_error.is_finite(),
        "{h:?}: {sp:?}"
    );
    let ulp = lo.next_up() - lo;
    let extra = if interval_form && ulp > err {
        q(ulp) - q(err)
    } else {
        int(0)
    };
    let mut off_plane = int(0);
    let mut slack = int(0);
    for j in 0..3 {
        let dj = q(ray.dir[j]);
        let star = q(ray.origin[j]) + &e.t * &dj;
        let (p, pe) = (q(sp.point[j]), q(sp.point_error[j]));
        prop_assert!(
            abs(&(&p - star)) <= &pe + &extra * abs(&dj),
            "{h:?}: axis {j} of {:?} beyond {:?} of the exact crossing",
            sp.point,
            sp.point_error
        );
        let n = q(d.normal[j]);
        off_plane += &n * (&p - q(d.center[j]));
        slack += abs(&n) * (&pe + &extra * abs(&dj));
    }
    prop_assert!(
        abs(&off_plane) <= slack,
        "{h:?}: the box around {:?} misses the plane",
        sp.point
    );
    Ok(())
}

/// `check_point` on the hits of both forms.
fn check_hit_point<V: Vector>(
    d: Disc<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
) -> Result<(), TestCaseError> {
    let (lo, hi) = ends(&ray, &d, picks);
    let (plain, within_range) = answers(&ray, &d, t_max, (lo, hi));
    if let Some(h) = plain {
        check_point(&ray, &d, &h, S::<V>::ZERO, false)?;
    }
    if let Some(h) = within_range {
        check_point(&ray, &d, &h, lo, true)?;
    }
    Ok(())
}

/// Every hit (over `t_max`, `(lo, hi]`, `inf` and `(0, inf]`) in range,
/// and arriving from the side of the plane the origin is on, exactly: the
/// sign of `n . (o - c)`, positive for `Front` (a crossing ahead means the
/// ray runs against the normal), negative for `Back`; an origin exactly
/// on the plane has its crossing at `t = 0`, outside every range: no hit.
fn check_side<V: Vector>(
    d: Disc<V>,
    ray: Ray<V>,
    t_max: S<V>,
    picks: [f64; 2],
) -> Result<(), TestCaseError> {
    let (lo, hi) = ends(&ray, &d, picks);
    let (plain, within_range) = answers(&ray, &d, t_max, (lo, hi));
    let (zero, inf) = (S::<V>::ZERO, S::<V>::INFINITY);
    let all = Interval::up_to(inf).expect("(0, inf]");
    let (plain_inf, all_inf) = (d.hit(&ray, inf), d.hit(&ray, all));
    for (h, (a, b)) in [
        (plain, (zero, t_max)),
        (plain_inf, (zero, inf)),
        (within_range, (lo, hi)),
        (all_inf, (zero, inf)),
    ] {
        if let Some(h) = h {
            prop_assert!(
                a < h.t && h.t <= b && h.t.is_finite(),
                "{h:?} outside ({a:?}, {b:?}]"
            );
        }
    }
    let (o, c, n) = (
        rv(ray.origin).expect("finite"),
        rv(d.center).expect("finite"),
        rv(d.normal).expect("finite"),
    );
    let height: R = dot(&sub(&o, &c), &n);
    let expected = match height.cmp(&int(0)) {
        Ordering::Greater => Some(Side::Front),
        Ordering::Less => Some(Side::Back),
        Ordering::Equal => None,
    };
    for h in [plain, plain_inf, within_range, all_inf]
        .into_iter()
        .flatten()
    {
        prop_assert_eq!(
            Some(h.side),
            expected,
            "{:?} from an origin at height {:?} over the plane",
            h,
            height
        );
    }
    Ok(())
}

/// `(0, a]`, `(a, b]` and `(b, inf]` (`a <= b` from `ends`): where the
/// exact crossing is ahead, at most `MAX` and within the circles, exactly
/// the window holding it reports it (with the exact side); else none does.
fn check_windows<V: Vector>(d: Disc<V>, ray: Ray<V>, picks: [f64; 2]) -> Result<(), TestCaseError> {
    let (a, b) = ends(&ray, &d, picks);
    let (zero, inf) = (S::<V>::ZERO, S::<V>::INFINITY);
    let e = exact(&ray, &d);
    let max = q(S::<V>::MAX);
    let hit = e.as_ref().filter(|e| e.hit_in(&q(zero), Some(&max)));
    let mut reports = 0;
    for (x, y) in [(zero, a), (a, b), (b, inf)] {
        let Some(window) = Interval::new(x, y) else {
            continue;
        };
        let got = d.hit(&ray, window);
        let holds = hit.is_some_and(|e| {
            x < y && e.t > q(x) && e.t <= q(if y < S::<V>::MAX { y } else { S::<V>::MAX })
        });
        prop_assert_eq!(
            got.map(|h| h.side),
            hit.filter(|_| holds).map(|e| e.side),
            "window ({:?}, {:?}], t* {:?}",
            x,
            y,
            e.as_ref().map(|e| rayhit::exact::oracle::to_f64(&e.t))
        );
        reports += usize::from(got.is_some());
    }
    prop_assert_eq!(reports, usize::from(hit.is_some()), "reports over (0, inf]");
    Ok(())
}

/// `Disc::bounds` holds the exact crossing `o + t* d` of the ray's line
/// with the plane wherever that lies within the closed annulus, at any
/// `t*` (ahead, behind, hit or not), checked exactly.
fn check_bounds<V: Vector>(d: Disc<V>, ray: Ray<V>) -> Result<(), TestCaseError> {
    let Some(e) = exact(&ray, &d) else {
        return Ok(());
    };
    if !e.within_rims() {
        return Ok(());
    }
    let b = d.bounds();
    for i in 0..3 {
        let p = q(ray.origin[i]) + &e.t * q(ray.dir[i]);
        prop_assert!(
            q(b.min[i]) <= p && p <= q(b.max[i]),
            "the exact crossing at {} is outside {:?} on axis {}",
            rayhit::exact::oracle::to_f64(&p),
            b,
            i
        );
    }
    Ok(())
}

in_both_precisions! {
    fn position_scaling((d, ray) in strat::disc_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), k in -8i32..=8) {
        check_position_scaling(d, ray, t_max, picks, k)?;
    }

    fn direction_scaling((d, ray) in strat::disc_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), k in -8i32..=8) {
        check_direction_scaling(d, ray, t_max, picks, k)?;
    }

    fn normal_scaling((d, ray) in strat::disc_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64), k in -8i32..=8) {
        check_normal_scaling(d, ray, t_max, picks, k)?;
    }

    fn hit_point_on_disc((d, ray) in strat::disc_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64)) {
        check_hit_point(d, ray, t_max, picks)?;
    }

    fn range_and_side((d, ray) in strat::disc_and_ray::<V>(), t_max in strat::t_max::<V>(), picks in prop::array::uniform2(0.0..1.0f64)) {
        check_side(d, ray, t_max, picks)?;
    }

    fn consecutive_windows_report_once((d, ray) in strat::disc_and_ray::<V>(), picks in prop::array::uniform2(0.0..1.0f64)) {
        check_windows(d, ray, picks)?;
    }

    fn bounds_hold_the_crossing((d, ray) in strat::disc_and_ray::<V>()) {
        check_bounds(d, ray)?;
    }
}
