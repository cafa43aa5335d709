//! The sphere (`Sphere`): the ray/sphere test over a `t_max` and over an
//! interval, its error bound, against exact arithmetic; what is done with
//! its surface points is `surface::sphere`'s.
//!
//! The cases (`case`), in `f32` and `f64`: far spheres (centres up to
//! `1e5` from the origin, radii `1e-3` to `1e4`) with rays aimed at their
//! surface, inside them or just outside (a relative `1e-7`), from a few
//! radii to ten thousand radii away; grazing rays (along a tangent,
//! moved off it by nothing or a relative `1e-7` or `1e-4` either way);
//! rays from inside; and the textbook test ("Ray Tracing in One
//! Weekend": `b^2 - a c`, and `t > 0.001`) on the same rays for
//! comparison.

mod interval;
mod oracle;
mod properties;
mod regressions;

use crate::common::draw::{f, signed};
use rayhit::exact::oracle::{ExactSphere, R, sphere};
use rayhit::exact::{Rational, oracle as exact_oracle};
use rayhit::{Ray, Scalar, Side, Sphere, Vector};
use rayhit_testkit::rng::Pcg32;
use std::cmp::Ordering;

pub type S<V> = <V as Vector>::Scalar;

/// What a case aims at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A point on, inside or just outside the ball, from outside.
    Aimed,
    /// Along a tangent, moved off it a little either way.
    Grazing,
    /// From inside the ball.
    Inside,
}

/// A unit vector, uniform on the sphere.
pub fn unit(rng: &mut Pcg32) -> [f64; 3] {
    loop {
        let v = [signed(rng), signed(rng), signed(rng)];
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.1 && n <= 1.0 {
            return v.map(|x| x / n);
        }
    }
}

fn pow10(rng: &mut Pcg32, lo: f64, hi: f64) -> f64 {
    10f64.powf(lo + (hi - lo) * f64::from(rng.unit()))
}

fn add(p: [f64; 3], v: [f64; 3], s: f64) -> [f64; 3] {
    [p[0] + v[0] * s, p[1] + v[1] * s, p[2] + v[2] * s]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn vec<V: Vector>(p: [f64; 3]) -> V {
    V::new(f::<V>(p[0]), f::<V>(p[1]), f::<V>(p[2]))
}

/// One case of `kind`: a sphere and a ray, both rounded to `V`'s
/// precision (the exact answers are for the rounded inputs).
pub fn case<V: Vector>(rng: &mut Pcg32, kind: Kind) -> (Ray<V>, Sphere<V>) {
    loop {
        let (ray, s) = draw::<V>(rng, kind);
        // A direction that rounded to zero (an origin within an ulp of
        // its target) is no case.
        if ray.is_valid() {
            return (ray, s);
        }
    }
}

fn draw<V: Vector>(rng: &mut Pcg32, kind: Kind) -> (Ray<V>, Sphere<V>) {
    let centre = add([0.0; 3], unit(rng), pow10(rng, 0.0, 5.0));
    let radius = pow10(rng, -3.0, 4.0);
    let normal = unit(rng);
    let (origin, target) = match kind {
        Kind::Aimed => {
            let reach = [1.0, 0.5, 1.0 + 1e-7, 1.0 - 1e-7, 0.0][rng.below(5) as usize];
            let target = add(centre, normal, radius * reach);
            let away = unit(rng);
            (add(target, away, radius * pow10(rng, 0.3, 4.0)), target)
        }
        Kind::Grazing => {
            let mut tangent = cross(normal, unit(rng));
            let n = tangent.iter().map(|x| x * x).sum::<f64>().sqrt();
            tangent = tangent.map(|x| x / n);
            let off = [0.0, 1e-7, -1e-7, 1e-4, -1e-4][rng.below(5) as usize];
            let touch = add(centre, normal, radius * (1.0 + off));
            let dist = radius * pow10(rng, -1.0, 3.0);
            (add(touch, tangent, -dist), touch)
        }
        Kind::Inside => {
            let origin = add(centre, unit(rng), radius * 0.999 * f64::from(rng.unit()));
            (origin, add(origin, unit(rng), radius))
        }
    };
    let (o, t) = (vec::<V>(origin), vec::<V>(target));
    let mut dir = t - o;
    if rng.below(2) == 0 {
        dir = dir.normalize_or_zero();
    }
    (
        Ray::new(o, dir),
        Sphere::new(vec::<V>(centre), f::<V>(radius)),
    )
}

/// The exact line/sphere values of a case.
pub fn exact<V: Vector>(ray: &Ray<V>, s: &Sphere<V>) -> ExactSphere {
    sphere(ray, s.center, s.radius).expect("finite case")
}

/// `x`, exactly.
pub fn q<F: Scalar>(x: F) -> R {
    exact_oracle::r(x).expect("finite")
}

/// Whether the exact crossing on `side` lies in `(lo, hi]` (`hi` capped at
/// `MAX`: no crossing beyond it has a float `t`).
pub fn side_in<F: Scalar>(e: &ExactSphere, side: Side, lo: F, hi: F) -> bool {
    let cap = if hi < F::MAX { hi } else { F::MAX };
    match side {
        Side::Front => e.entry_in(&q(lo), Some(&q(cap))),
        Side::Back => e.exit_in(&q(lo), Some(&q(cap))),
    }
}

/// The exact verdict over `(lo, hi]`: the entry where it is in, else the
/// exit where it is.
pub fn verdict<F: Scalar>(e: &ExactSphere, lo: F, hi: F) -> Option<Side> {
    if side_in(e, Side::Front, lo, hi) {
        Some(Side::Front)
    } else if side_in(e, Side::Back, lo, hi) {
        Some(Side::Back)
    } else {
        None
    }
}

/// Whether the exact crossing on `side` is within `err` of `t`.
pub fn within<F: Scalar>(e: &ExactSphere, side: Side, t: F, err: F) -> bool {
    if !err.is_finite() {
        return true;
    }
    let (lo, hi) = (q(t) - q(err), q(t) + q(err));
    let place = |x: &Rational| match side {
        Side::Front => e.entry_cmp(x),
        Side::Back => e.exit_cmp(x),
    };
    place(&lo) != Some(Ordering::Less)
        && place(&hi) != Some(Ordering::Greater)
        && place(&lo).is_some()
}

/// The textbook test ("Ray Tracing in One Weekend", with `b = d . (c - o)`
/// halved): `disc = b^2 - a c`, the near root unless it is at most
/// `t_min`, then the far one. For comparison only.
pub fn textbook<V: Vector>(ray: &Ray<V>, s: &Sphere<V>, t_min: S<V>) -> Option<(S<V>, Side)> {
    let oc = s.center - ray.origin;
    let a = ray.dir.dot(ray.dir);
    let h = ray.dir.dot(oc);
    let c = oc.dot(oc) - s.radius * s.radius;
    let disc = h * h - a * c;
    if !(disc >= S::<V>::ZERO) {
        return None;
    }
    let root = disc.sqrt();
    let near = (h - root) / a;
    if near > t_min {
        return Some((near, Side::Front));
    }
    let far = (h + root) / a;
    (far > t_min).then_some((far, Side::Back))
}
