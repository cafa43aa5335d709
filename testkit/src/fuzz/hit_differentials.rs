//! `hit_differentials`: [`Triangle::hit_differentials`] and
//! [`Triangle::hit_differentials_error`], the transfer of a camera ray's
//! differentials to a triangle hit.
//!
//! Input: raw mode, a ray's direction and its four offsets as raw-bit
//! vectors, a triangle and `t`; structured mode, a camera's ray
//! differential (pinhole, thin lens, orthographic or equirectangular, from
//! [`cases::cameras`](crate::cases::cameras)) and a triangle around a point of the ray, `1/2` to
//! `2^7` along it, `2^-4` to `2^4` across, hit by the watertight test, at
//! the hit's `t`.
//!
//! Checks, any input: no panic; `None` exactly where the computed `dir .
//! n` or `|n|^2` is zero, and then every bound infinite; every bound is
//! non-negative (never NaN). Structured inputs also, in exact arithmetic:
//! every derivative (each component of `dp_dx` and `dp_dy`, and `du_dx` to
//! `dv_dy`) is within its bound of the exact transfer at the same `t`
//! ([`rayhit::exact::oracle::hit_differential`]); and the bounds are
//! finite for a hit that is not grazing on a triangle that is not a
//! sliver.

use arbitrary::Arbitrary;
use rayhit::exact::oracle::hit_differential;
use rayhit::{Ray, Scalar, Triangle, Vector, camera::RayDifferential, ray_triangle};

use super::exact::{abs, r, rv};
use super::{Check, Input, S, raw, raw_vec};
use crate::cases::cameras::{differential, triangle_around};

/// The `hit_differentials` target.
#[derive(Debug)]
pub struct HitDifferentialsCheck;

impl Check for HitDifferentialsCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let mut vecs = [V::ZERO; 8];
                for x in vecs.iter_mut() {
                    *x = raw_vec::<V>(u);
                }
                let t = raw::<S<V>>(u);
                let diff = RayDifferential {
                    ray: Ray::new(V::ZERO, vecs[0]),
                    dx_origin: vecs[1],
                    dx_dir: vecs[2],
                    dy_origin: vecs[3],
                    dy_dir: vecs[4],
                };
                let tri = Triangle::new(vecs[5], vecs[6], vecs[7]);
                check(&diff, &tri, t, false);
            }
            Input::Structured(src) => {
                let Some(diff) = differential::<V>(src) else {
                    return;
                };
                let tri = triangle_around::<V>(src, &diff.ray);
                let Some(hit) = ray_triangle(&diff.ray, &tri, S::<V>::INFINITY) else {
                    return;
                };
                check(&diff, &tri, hit.t, true);
            }
        }
    }
}

/// The checks on one input; `exact`: hold the values to their bounds in
/// exact arithmetic (the running error analysis assumes nothing
/// underflows, which structured inputs ensure and raw bits do not).
pub fn check<V: Vector>(diff: &RayDifferential<V>, tri: &Triangle<V>, t: S<V>, exact: bool) {
    let ctx = || format!("{diff:?}, {tri:?}, t = {t:?}");
    let got = tri.hit_differentials(diff, t);
    let err = tri.hit_differentials_error(diff, t);
    let bounds = [
        err.dp_dx.x(),
        err.dp_dx.y(),
        err.dp_dx.z(),
        err.dp_dy.x(),
        err.dp_dy.y(),
        err.dp_dy.z(),
        err.du_dx,
        err.dv_dx,
        err.du_dy,
        err.dv_dy,
    ];
    assert!(
        bounds.iter().all(|b| *b >= S::<V>::ZERO),
        "a bound is NaN or negative: {err:?}: {}",
        ctx()
    );
    let n = tri.normal();
    let (den, nn) = (diff.ray.dir.dot(n), n.dot(n));
    let zero = S::<V>::ZERO;
    match got {
        None => {
            assert!(den == zero || nn == zero, "None for a transfer: {}", ctx());
            assert!(bounds.iter().all(|b| *b == S::<V>::INFINITY), "{}", ctx());
            return;
        }
        Some(_) => assert!(!(den == zero || nn == zero), "{}", ctx()),
    }
    let got = got.expect("checked");
    if !exact {
        return;
    }
    let inf = S::<V>::INFINITY;
    // Not grazing (the angle's cosine above 1/100) and not a sliver (the
    // normal's error bound below 2^-10 of its length): then the running
    // bounds of the two divisors, `|n|^2` and `dir . n`, stay well inside
    // their values, and the bounds are finite.
    let grazing = den.abs().to_f64() < 0.01 * diff.ray.dir.length().to_f64() * nn.sqrt().to_f64();
    let (normal, normal_error) = (tri.normal(), tri.normal_error());
    let sliver = normal_error.length().to_f64() > normal.length().to_f64() / 1024.0;
    if !grazing && !sliver {
        assert!(
            bounds.iter().all(|b| *b < inf),
            "infinite bound {err:?}: {}",
            ctx()
        );
    }
    for (name, d_origin, d_dir, dp, du, dv, ep, eu, ev) in [
        (
            "x",
            diff.dx_origin,
            diff.dx_dir,
            got.dp_dx,
            got.du_dx,
            got.dv_dx,
            err.dp_dx,
            err.du_dx,
            err.dv_dx,
        ),
        (
            "y",
            diff.dy_origin,
            diff.dy_dir,
            got.dp_dy,
            got.du_dy,
            got.dv_dy,
            err.dp_dy,
            err.du_dy,
            err.dv_dy,
        ),
    ] {
        let Some((xp, xu, xv)) = hit_differential(diff.ray.dir, d_origin, d_dir, tri, t) else {
            // No exact transfer: the inputs are finite, so the ray is
            // exactly parallel to the triangle's plane, and the computed
            // `dir . n` is rounding alone (the watertight test decides on
            // the sheared, rounded corners, and may report such a hit).
            // Every bound must then be infinite.
            assert!(
                [ep.x(), ep.y(), ep.z(), eu, ev].iter().all(|b| *b == inf),
                "a finite bound on the d{name} transfer of a ray exactly parallel to the plane: {err:?}: {}",
                ctx()
            );
            continue;
        };
        let gp = rv(dp);
        for k in 0..3 {
            if ep[k] < inf {
                assert!(
                    abs(&(&gp[k] - &xp[k])) <= r(ep[k]),
                    "dp_d{name}[{k}] {:?} off the exact one by more than {:?}: {}",
                    dp[k],
                    ep[k],
                    ctx()
                );
            }
        }
        for (what, value, exact_value, bound) in [("u", du, xu, eu), ("v", dv, xv, ev)] {
            if bound < inf {
                assert!(
                    abs(&(r(value) - exact_value)) <= r(bound),
                    "d{what}_d{name} {value:?} off the exact one by more than {bound:?}: {}",
                    ctx()
                );
            }
        }
    }
}
