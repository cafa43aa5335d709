//! Spheres (work in progress): the ray/sphere kernel's core, the
//! conservative miss test and the stable roots.
//!
//! Haines, Guenther and Akenine-Moller, "Precision Improvements for
//! Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7, 2019): the
//! discriminant from the centre's distance to the ray's line, `r^2 -
//! |l|^2`, rather than `b^2 - a c` (which cancels when the line passes far
//! from the centre relative to the distance), and the roots from `q = b +
//! sign(b) sqrt(a disc)` as `q / a` and `k / q`.
#![allow(dead_code)]

use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};
use crate::ray::Ray;

/// The sphere `|p - center| = radius` (its magnitude).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<V: Vector> {
    /// The centre.
    pub center: V,
    /// The radius; its sign is ignored.
    pub radius: S<V>,
}

/// The kernel's values for one ray and sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Roots<F> {
    /// The crossings, `near <= far`, where the line surely meets the
    /// ball or is within rounding of it (then both are the nearest point
    /// of the line, `b / a`).
    pub(crate) near: F,
    pub(crate) far: F,
}

/// The line's crossings with the closed ball, or `None` where the line
/// surely misses it: the exact line passes the centre farther than the
/// radius. Never `None` for a line that meets the ball in exact
/// arithmetic (no false miss); a line within rounding of the sphere may
/// be reported as touching it.
///
/// Error bound for the miss test, with `u` the unit roundoff and `F` the
/// computed `o - c` (`|F_i - f_i| <= gamma(1) |F_i|`): the line's closest
/// point to the centre is `l(f) = P f`, `P = I - d d^T / a` an orthogonal
/// projection, so `|l(F) - l(f)| <= |F - f| <= gamma(1) |F|`. The
/// computed `kappa = fl(fl(-F . d) / fl(d . d))` is within `gamma(9) S /
/// a_c` of `-F . d / (d . d)` (`S = sum |F_i d_i|`: the dot products'
/// `gamma(3)` each and the division), and `L_i = fl(F_i + fl(kappa d_i))`
/// within `|d_i| gamma(9) S / a_c + gamma(2) (|kappa d_i| + |L_i|)` of
/// `l(F)_i`. So `|L - l(f)| <= e = gamma(1) |F| + gamma(9) S |d| / a_c +
/// gamma(2) (|kappa| |d| + |L|)` (2-norms, each bounded above by the sum
/// of the components' magnitudes), and the line surely misses where `|L|
/// > r + e`, tested on squares rounded the safe way.
pub(crate) fn ray_sphere_roots<V: Vector>(ray: &Ray<V>, s: &Sphere<V>) -> Option<Roots<S<V>>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    let g = S::<V>::gamma_n;
    let r = s.radius.abs();
    let d = ray.dir;
    let f = ray.origin - s.center;
    let a = d.dot(d);
    let nd = -(f.dot(d));
    let kappa = nd / a;
    let l = f + d * kappa;
    let h2 = l.dot(l);
    if !(a > zero && h2.is_finite() && r.is_finite()) {
        return None;
    }
    // Norms bounded by sums of magnitudes (no square roots).
    let norm1 = |v: V| v.x().abs() + v.y().abs() + v.z().abs();
    let big_s = f.x().abs() * d.x().abs() + f.y().abs() * d.y().abs() + f.z().abs() * d.z().abs();
    let dn = norm1(d);
    let e = bound_up(
        g(1) * norm1(f) + g(9) * big_s * dn / a + g(2) * (kappa.abs() * dn + norm1(l)),
        8,
    );
    // Miss where |L| > r + e: |L|^2 >= h2 (1 - gamma(3)) and (r + e)^2
    // rounded up.
    let reach = bound_up(r + e, 1);
    let reach2 = bound_up(reach * reach, 1);
    let h2_low = h2 * (one - g(3));
    if h2_low > reach2 {
        return None;
    }
    // Inside the band or a sure hit: the discriminant, clamped at zero.
    let disc = r * r - h2;
    let disc = if disc > zero { disc } else { zero };
    let root = (a * disc).sqrt();
    let q = if nd >= zero { nd + root } else { nd - root };
    let k = f.dot(f) - r * r;
    let (t1, t2) = if q != zero {
        (q / a, k / q)
    } else {
        (kappa, kappa)
    };
    let (near, far) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
    Some(Roots { near, far })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::oracle;
    use crate::testing::Draws;
    use glam::{DVec3, Vec3};

    /// No false miss: far spheres (centres up to `1e5`, radii `1e-3` to
    /// `1e4`), rays aimed at a point of the ball (its surface, inside it,
    /// or just outside by a relative `1e-7`), from a few radii to far
    /// away; every line that meets the ball in exact arithmetic is
    /// reported, in both precisions.
    fn no_false_miss<V: Vector>() -> (usize, usize, usize) {
        let mut draws = Draws(91);
        let (mut met, mut reported_touch, mut textbook_misses) = (0, 0, 0);
        let f = S::<V>::from_f64;
        for _ in 0..20_000 {
            let unit = |d: &mut Draws| {
                let v = [d.coordinate(4), d.coordinate(4), d.coordinate(4)];
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                v.map(|x| x / n)
            };
            let far = 10f64.powf((draws.next() % 1000) as f64 / 200.0);
            let radius = 10f64.powf((draws.next() % 1400) as f64 / 200.0 - 3.0);
            let c = unit(&mut draws).map(|x| x * far);
            let toward = unit(&mut draws);
            let reach = [1.0, 0.5, 1.0 + 1e-7, 1.0 - 1e-7][(draws.next() % 4) as usize];
            let target = [0, 1, 2].map(|i| c[i] + toward[i] * radius * reach);
            let away = unit(&mut draws);
            let dist = radius * 10f64.powf((draws.next() % 800) as f64 / 200.0);
            let origin = [0, 1, 2].map(|i| target[i] + away[i] * dist);
            let v = |p: [f64; 3]| V::new(f(p[0]), f(p[1]), f(p[2]));
            let ray = Ray::new(v(origin), v(target) - v(origin));
            let sphere = Sphere {
                center: v(c),
                radius: f(radius),
            };
            let Some(exact) = oracle::sphere(&ray, sphere.center, sphere.radius) else {
                continue;
            };
            if exact.line_hits() {
                met += 1;
                let roots = ray_sphere_roots(&ray, &sphere);
                assert!(roots.is_some(), "a false miss: {ray:?} {sphere:?}");
                let r = roots.unwrap();
                assert!(r.near.is_finite() && r.far.is_finite() && r.near <= r.far);
                reported_touch += usize::from(r.near == r.far);
                textbook_misses += usize::from(textbook(&ray, &sphere).is_none());
            }
        }
        (met, reported_touch, textbook_misses)
    }

    /// The textbook test ("Ray Tracing in One Weekend"): `b^2 - a c` with
    /// `b = (o - c) . d`, for comparison only.
    fn textbook<V: Vector>(ray: &Ray<V>, s: &Sphere<V>) -> Option<S<V>> {
        let oc = ray.origin - s.center;
        let a = ray.dir.dot(ray.dir);
        let half_b = oc.dot(ray.dir);
        let c = oc.dot(oc) - s.radius * s.radius;
        let disc = half_b * half_b - a * c;
        (disc >= S::<V>::ZERO).then(|| (-half_b - disc.sqrt()) / a)
    }

    #[test]
    fn no_false_miss_f32() {
        let (met, touch, textbook) = no_false_miss::<Vec3>();
        std::eprintln!(
            "f32: {met} lines meet the ball; {touch} reported as touching; textbook misses {textbook}"
        );
        assert!(met > 5_000, "{met}");
    }

    #[test]
    fn no_false_miss_f64() {
        let (met, touch, textbook) = no_false_miss::<DVec3>();
        std::eprintln!(
            "f64: {met} lines meet the ball; {touch} reported as touching; textbook misses {textbook}"
        );
        assert!(met > 5_000, "{met}");
    }
}
