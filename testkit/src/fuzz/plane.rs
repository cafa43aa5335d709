//! `plane`: [`ray_plane`], [`Plane::hit_error`](rayhit::Surface::hit_error)
//! and [`Plane::surface_point`](rayhit::Surface::surface_point).
//!
//! Input: raw mode, a `Ray`, a `Plane` and `t_max` as raw bits; structured
//! mode, [`cases::planes::plane`].
//!
//! Checks, any input: no panic; `None` or `0 < t <= t_max` with `t` finite;
//! `None` for a ray that is not valid, a zero or non-finite plane, and a NaN
//! or negative `t_max`. When every input is finite and nothing underflows
//! ([`no_underflow`]; the crate's bounds assume it, and the structured
//! cases' tilted rays can break it too): `t` within
//! `Plane::hit_error` of the exact crossing, the hit point within
//! `Plane::surface_point`'s bound of the exact crossing, and a miss only
//! where the exact crossing is within that bound of `0` or `t_max` (or
//! overflows).

use arbitrary::Arbitrary;
use rayhit::{Plane, Ray, Scalar, Surface, Vector, ray_plane};

use super::exact::{abs, int, r, rv};
use super::{Check, Input, S, far_from_underflow, product_far_from_underflow, raw};
use crate::cases;
use crate::oracle;

/// The `plane` target.
#[derive(Debug)]
pub struct PlaneCheck;

impl Check for PlaneCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let (plane, ray, t_max) = match input {
            Input::Raw(u) => (raw::<Plane<V>>(u), raw::<Ray<V>>(u), raw::<S<V>>(u)),
            Input::Structured(src) => cases::planes::plane::<V>(src),
        };
        let guarded = no_underflow(&ray, &plane);
        check(&ray, &plane, t_max, guarded);
    }
}

/// Every product `ray_plane` and its bounds form is far from underflow:
/// `w_i n_i`, `d_i n_i` and `t d_j` (with `w = point - origin`), and `t`.
pub fn no_underflow<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> bool {
    let w = plane.point - ray.origin;
    let n = plane.normal;
    let t = w.dot(n) / ray.dir.dot(n);
    (0..3).all(|i| {
        product_far_from_underflow(w[i], n[i])
            && product_far_from_underflow(ray.dir[i], n[i])
            && product_far_from_underflow(t, ray.dir[i])
            && far_from_underflow(ray.origin[i])
    }) && far_from_underflow(t)
}

/// All the plane checks on one input.
/// `bounded`: hold the kernel to its error bounds (else only to the range
/// and invalid-input checks).
pub fn check<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: S<V>, bounded: bool) {
    let zero = S::<V>::ZERO;
    let got = ray_plane(ray, plane, t_max);
    let ctx = || format!("ray {ray:?}, plane {plane:?}, t_max {t_max:?}");
    if let Some(t) = got {
        assert!(
            t > zero && t <= t_max && t.is_finite(),
            "t = {t:?} out of range: {}",
            ctx()
        );
    }
    let valid = ray.is_valid()
        && plane.point.is_finite()
        && plane.normal.is_finite()
        && plane.normal != V::ZERO
        && t_max >= zero;
    if !valid {
        assert!(got.is_none(), "hit on invalid input: {}", ctx());
        return;
    }
    if !bounded {
        return;
    }
    // Valid and finite from here (t_max may be +inf).
    let exact = oracle::plane_t(ray, plane);
    if let Some(t) = got {
        let exact = exact.expect("a hit on a plane the ray is parallel to");
        let err = plane.hit_error(ray, &t);
        assert!(err >= zero, "t error bound {err:?}: {}", ctx());
        assert!(
            !err.is_finite() || oracle::close(t, &exact, err),
            "t = {t:?}, exact {}, bound {err:?}: {}",
            super::exact::f(&exact),
            ctx()
        );
        // The hit point is within its per-component bound of the exact
        // crossing o + t* d (which lies on the plane).
        let (p, perr) = {
            let s = plane.surface_point(ray, &t);
            (s.point, s.point_error)
        };
        let (o, d, p) = (rv(ray.origin), rv(ray.dir), p);
        for j in 0..3 {
            let e = perr[j];
            // Never NaN, even for an infinite `t` bound and a zero direction
            // component (tests/suite/<subject>/fuzz_regressions.rs).
            assert!(e >= zero, "hit point bound {perr:?}: {}", ctx());
            if e.is_finite() && p[j].is_finite() {
                let star = &o[j] + &exact * &d[j];
                assert!(
                    abs(&(r(p[j]) - &star)) <= r(e),
                    "hit point {p:?} off the exact crossing on axis {j} beyond {perr:?}: {}",
                    ctx()
                );
            }
        }
    } else if let Some(exact) = exact {
        // A miss where exact arithmetic hits: only within the error bound of
        // 0 or of t_max (the range tests run on the rounded t), or where t
        // itself overflows.
        let limit = oracle::limit(t_max);
        if exact > int(0) && limit.as_ref().is_none_or(|m| &exact <= m) {
            let t = S::<V>::from_f64(super::exact::f(&exact));
            let err = plane.hit_error(ray, &t).next_up();
            let unknown = !t.is_finite() || !err.is_finite();
            let near_zero = unknown || exact <= r(err);
            let near_max = !unknown && limit.as_ref().is_some_and(|m| m - &exact <= r(err));
            assert!(
                near_zero || near_max,
                "false miss at exact t = {}: {}",
                super::exact::f(&exact),
                ctx()
            );
        }
    }
}
