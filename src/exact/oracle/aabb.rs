//! The box in exact arithmetic: the slab distances, the entry and exit,
//! how far a ray passes from a box, the entry face, and whether a case is
//! outside the slab test's rounding band.

use std::vec::Vec;

use super::values::*;
use crate::{Aabb, BoxFace, Ray, Scalar, Vector};
use core::cmp::Ordering;
use num_traits::{Signed, Zero};

/// The exact slab distances of the ray for every axis it moves along:
/// `(near, far, axis)`, or `None` when an axis it does not move along
/// already excludes it (a miss that no rounding of the other axes can
/// change), when the ray does not move, or when a coordinate is not finite.
#[must_use]
pub fn box_slabs<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> Option<Vec<(R, R, usize)>> {
    let (o, d) = moving(ray)?;
    let (lo, hi) = (rv(b.min)?, rv(b.max)?);
    let mut slabs = Vec::new();
    for k in 0..3 {
        if d[k].is_zero() {
            if o[k] < lo[k] || o[k] > hi[k] {
                return None;
            }
            continue;
        }
        let t0 = (&lo[k] - &o[k]) / &d[k];
        let t1 = (&hi[k] - &o[k]) / &d[k];
        slabs.push(if t0 <= t1 { (t0, t1, k) } else { (t1, t0, k) });
    }
    Some(slabs)
}

/// The exact `(enter, exit)` of the ray against the closed box, clipped to
/// `[0, t_max]`, whether or not it is empty (`enter > exit` is a miss by
/// that much), or `None` as for [`box_slabs`].
#[must_use]
pub fn box_raw<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    let slabs = box_slabs(ray, b)?;
    let enter = slabs.iter().map(|s| s.0.clone()).chain([R::zero()]).max()?;
    let exit = slabs
        .iter()
        .map(|s| s.1.clone())
        .chain(limit(t_max))
        .min()?;
    Some((enter, exit))
}

/// How far (in space, along one axis) a ray passes from a box that it
/// misses, or how deep it goes into one it hits, exactly: the gap between
/// entry and exit in `t` times the speed along the axis that sets the entry
/// (at the exit time the ray is that far outside along it) or the exit
/// (likewise at the entry time), whichever is smaller. `t = 0` and `t_max`
/// count as limits with no axis, and contribute only through the other side.
/// `None` as for [`box_slabs`].
#[must_use]
pub fn box_gap<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<R> {
    let slabs = box_slabs(ray, b)?;
    let d = rv(ray.dir)?;
    let (enter, exit) = box_raw(ray, b, t_max)?;
    // The axes whose near (far) distance is the entry (exit), if any.
    let by_enter = slabs.iter().filter(|s| s.0 == enter).map(|s| d[s.2].abs());
    let by_exit = slabs.iter().filter(|s| s.1 == exit).map(|s| d[s.2].abs());
    let speed = by_enter.chain(by_exit).min()?;
    Some((enter - exit).abs() * speed)
}

/// How unambiguous the faces that set the entry and the exit are: the gap
/// between the exact entry and the next largest lower limit (another axis's
/// near distance, or 0), and likewise between the exit and the next
/// smallest upper limit (`10^6` when there is none: one moving axis and no
/// `t_max`). Near an edge one of them is small and a kernel may take either
/// face. `None` as for [`box_slabs`].
#[must_use]
pub fn box_face_margins<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    let slabs = box_slabs(ray, b)?;
    let mut nears: Vec<R> = slabs
        .iter()
        .map(|s| s.0.clone())
        .chain([R::zero()])
        .collect();
    let mut fars: Vec<R> = slabs
        .iter()
        .map(|s| s.1.clone())
        .chain(limit(t_max))
        .collect();
    nears.sort();
    fars.sort();
    let gap = |v: &[R], i: usize, j: usize| {
        v.get(j)
            .map_or_else(|| R::from_integer(1_000_000.into()), |x| (x - &v[i]).abs())
    };
    // The ray moves along some axis, so there is a slab besides the 0.
    let n = nears.len();
    Some((gap(&nears, n - 1, n - 2), gap(&fars, 0, 1)))
}

/// The exact entry face: the face of the largest positive entry-plane
/// distance, the lowest axis on a tie, `None` inside when no entry plane is
/// ahead; and whether it was a tie. `None` when a coordinate is not finite.
#[must_use]
pub fn box_face<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> Option<(Option<BoxFace>, bool)> {
    let (o, d, lo, hi) = (rv(ray.origin)?, rv(ray.dir)?, rv(b.min)?, rv(b.max)?);
    let mut best: Option<(usize, R)> = None;
    let mut tie = false;
    for k in 0..3 {
        if d[k].is_zero() {
            continue;
        }
        let plane = if d[k] > R::zero() { &lo[k] } else { &hi[k] };
        let t = (plane - &o[k]) / &d[k];
        if t <= R::zero() {
            continue;
        }
        match &best {
            Some((_, bt)) if t.cmp(bt) == Ordering::Equal => tie = true,
            Some((_, bt)) if t < *bt => {}
            _ => {
                best = Some((k, t));
                tie = false;
            }
        }
    }
    Some((
        best.and_then(|(k, _)| BoxFace::new(k, d[k] < R::zero())),
        tie,
    ))
}

/// Exact interval `[enter, exit]` of `t` in `[0, t_max]` with the ray inside
/// the closed box, or `None` when it is empty (or as for [`box_slabs`]).
#[must_use]
pub fn box_interval<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    box_raw(ray, b, t_max).filter(|(e, x)| e <= x)
}

/// True when some nonzero direction component is so small that its
/// reciprocal overflows (`|d_i| < 1/MAX`): the slab test's exit is then only
/// an upper bound, not within its relative band (see `ray_aabb`). False
/// when a component is not finite.
#[must_use]
pub fn reciprocal_overflows<V: Vector>(dir: V) -> bool {
    dir.is_finite()
        && [dir.x(), dir.y(), dir.z()]
            .into_iter()
            .any(|d| d != V::Scalar::ZERO && !(V::Scalar::ONE / d).is_finite())
}

/// True when some direction component is so large that its reciprocal is
/// subnormal (`|d_i| > 2^126` in `f32`, `2^1022` in `f64`): the slab test's
/// false-hit band is then `40u` instead of `16u` (see `ray_aabb`). False
/// when a component is not finite.
#[must_use]
pub fn reciprocal_subnormal<V: Vector>(dir: V) -> bool {
    dir.is_finite()
        && [dir.x(), dir.y(), dir.z()]
            .into_iter()
            .any(|d| d != V::Scalar::ZERO && (V::Scalar::ONE / d).abs() < V::Scalar::MIN_POSITIVE)
}

/// True when no nonzero direction component is subnormal (where the slab
/// test's bands stop being relative).
fn dir_normal<V: Vector>(dir: V) -> bool {
    [dir.x(), dir.y(), dir.z()]
        .into_iter()
        .all(|d| d == V::Scalar::ZERO || d.abs() >= V::Scalar::MIN_POSITIVE)
}

/// The box case is outside the slab test's rounding band: the exact
/// interval is more than `32u` (relative to the larger of entry and exit;
/// `80u` where a direction component's reciprocal is subnormal, twice the
/// test's `40u` there) plus four subnormals over the slowest moving
/// direction component from empty, or an axis the ray does not move along
/// rules it out; and no nonzero direction component is subnormal. False for
/// an invalid ray or box (the kernels' answer to those is a miss by rule,
/// not by arithmetic).
#[must_use]
pub fn box_clear<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> bool {
    let dmin = [ray.dir.x(), ray.dir.y(), ray.dir.z()]
        .into_iter()
        .filter(|d| *d != V::Scalar::ZERO)
        .filter_map(|d| r(d.abs()))
        .min();
    let Some(dmin) = dmin.filter(|_| ray.is_valid() && b.is_valid()) else {
        return false;
    };
    dir_normal(ray.dir)
        && match box_raw(ray, b, t_max) {
            None => true,
            Some((e, x)) => {
                let scale = if e.abs() > x.abs() { e.abs() } else { x.abs() };
                let absolute = constant(V::Scalar::TINY) * int(4) / dmin;
                let k = if reciprocal_subnormal(ray.dir) {
                    80
                } else {
                    32
                };
                (x - e).abs() > int(k) * constant(V::Scalar::UNIT_ROUNDOFF) * scale + absolute
            }
        }
}
