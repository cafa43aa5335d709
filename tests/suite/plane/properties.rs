//! The plane kernel's properties against the exact oracle, in both
//! precisions, on rays aimed at chosen points (see `rayhit::strategies`):
//! a hit's `t` in range and within its error bound, the hit point on the
//! plane within its bound, and a miss where exact arithmetic hits only
//! within the bound of `0` or `t_max`. Bounds are evaluated exactly (see
//! `common::props`).

use crate::common::props::{abs, config, in_both_precisions};
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Plane, Ray, Scalar, Surface, Vector, ray_plane};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, gamma, r, rv};

type S<V> = <V as Vector>::Scalar;

fn check_plane<V: Vector>(plane: Plane<V>, ray: Ray<V>, t_max: S<V>) -> Result<(), TestCaseError> {
    let got = ray_plane(&ray, &plane, t_max);
    let exact = oracle::plane_t(&ray, &plane);
    if let Some(t) = got {
        prop_assert!(
            t > S::<V>::ZERO && t <= t_max && t.is_finite(),
            "t = {t:?} out of range"
        );
        let exact = exact
            .as_ref()
            .expect("a hit on a plane the ray is parallel to");
        let err = plane.hit_error(&ray, &t);
        prop_assert!(
            oracle::close(t, exact, err),
            "t = {t:?}, exact {}, bound {err:?}",
            oracle::to_f64(exact)
        );

        // The hit point lies on the plane within its bound. With p* the
        // exact crossing, p = fl(o + fl(t d)) has |p_j - p*_j| <=
        // |t - t*| |d_j| + gamma(2) (|o_j| + |t d_j|) (two roundings), so
        // |(p - point) . n| <= sum_j |n_j| (err |d_j| + gamma(2)(|o_j| + |t d_j|)).
        let p = rv(ray.at(t));
        let (o, d, n) = (rv(ray.origin), rv(ray.dir), rv(plane.normal));
        let residual = abs(&oracle::dot(&oracle::sub(&p, &rv(plane.point)), &n));
        let (tr, er, g2) = (r(t), r(err), gamma::<S<V>>(2));
        let bound: R = (0..3)
            .map(|j| abs(&n[j]) * (&er * abs(&d[j]) + &g2 * (abs(&o[j]) + &tr * abs(&d[j]))))
            .sum();
        prop_assert!(
            residual <= bound,
            "hit point off the plane by {} > {}",
            oracle::to_f64(&residual),
            oracle::to_f64(&bound)
        );
    } else if let Some(exact) = exact {
        // A miss where exact arithmetic hits is allowed only within the
        // error bound of 0 or t_max (the range tests run on rounded t).
        let limit = oracle::limit(t_max);
        if exact > R::from_integer(0.into()) && limit.as_ref().is_none_or(|m| &exact <= m) {
            let t = S::<V>::from_f64(oracle::to_f64(&exact));
            let err = r(plane.hit_error(&ray, &t).next_up());
            let near_zero = exact <= err;
            let near_max = limit.as_ref().is_some_and(|m| m - &exact <= err);
            let overflow = !t.is_finite();
            prop_assert!(
                near_zero || near_max || overflow,
                "false miss at t = {}",
                oracle::to_f64(&exact)
            );
        }
    }
    Ok(())
}

in_both_precisions! {
    fn plane((plane, ray) in strat::plane_and_ray::<V>(), t_max in strat::t_max::<V>()) {
        check_plane(plane, ray, t_max)?;
    }
}
