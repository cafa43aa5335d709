//! Moller-Trumbore: [`Triangle::moller_trumbore`], the fast test that is not
//! watertight, on lanes, held bit for bit to its definition
//! (`super::definition::mt_definition`).

use super::{Side, Triangle, TriangleHit};
use crate::num::round::{bound_up, min2};
use crate::num::{Bits, Lanes, Repr, S, Scalar, Vector, lanes};
use crate::ray::Ray;

impl<V: Vector> Triangle<V> {
    /// The Moller-Trumbore ray/triangle test: the textbook fast path, not
    /// watertight.
    ///
    /// Moller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection",
    /// JGT 1997: solve `origin + t dir = a + u (b - a) + v (c - a)` by Cramer's
    /// rule with the determinant `det = (b - a) . (dir x (c - a))`.
    ///
    /// Same conventions and invalid-input behaviour as
    /// [`ray_triangle`](crate::ray_triangle) (`0 < t <= t_max`, two-sided). **Not watertight**: `u`, `v` and `u + v <= 1` are
    /// tested on rounded values computed differently for each triangle, so a
    /// ray through a shared edge can miss both triangles. It agrees with
    /// [`ray_triangle`](crate::ray_triangle) away from edges.
    ///
    /// The determinant test is relative, not an absolute epsilon: the ray is
    /// treated as parallel to the triangle when `|det|` is not larger than its
    /// own rounding error bound (a sum of products of the magnitudes that make
    /// it up), i.e. when the sign of `det` is not known. That test does not
    /// change when the scene or the direction is scaled.
    ///
    /// ```
    /// use rayhit::{Ray, Side, Triangle, glam::Vec3};
    /// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
    /// let ray = Ray::new(Vec3::new(0.5, 0.25, -4.0), Vec3::new(0.0, 0.0, 2.0));
    /// let hit = tri.moller_trumbore(&ray, f32::INFINITY).unwrap();
    /// assert_eq!((hit.t, hit.u, hit.v, hit.side), (2.0, 0.25, 0.125, Side::Back));
    /// ```
    #[inline]
    #[must_use]
    pub fn moller_trumbore(&self, ray: &Ray<V>, t_max: S<V>) -> Option<TriangleHit<S<V>>> {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        // Invalid input needs no test of its own: a zero direction gives
        // `det = 0`, so `u` is NaN or infinite, a NaN or infinite coordinate
        // makes `det` or `u`, `v`, `t` NaN or infinite, and each fails a range
        // test, as does a NaN or negative `t_max`.
        let (a, d) = (lanes(self.a), lanes(ray.dir));
        let e1 = lanes(self.b).sub(a);
        let e2 = lanes(self.c).sub(a);
        // p = d x e2, lane k = d[k+1] e2[k+2] - d[k+2] e2[k+1], with the two
        // products of each component kept for the determinant's error bound.
        let (m1, m2) = (d.rot1().mul(e2.rot2()), d.rot2().mul(e2.rot1()));
        let p = m1.sub(m2);
        let det = e1.mul(p).sum3();
        let inv_det = one / det;
        let s = lanes(ray.origin).sub(a);
        let u = s.mul(p).sum3() * inv_det;
        // (One branch for both of `u`'s limits: on rays that mostly miss, `u`
        // falls on either side about equally, and two branches were each
        // unpredictable where one is not.)
        if !<<S<V> as Repr>::Bits as Bits>::in_unit_interval(u) {
            return None;
        }
        // q = s x e1.
        let q = s.rot1().mul(e1.rot2()).sub(s.rot2().mul(e1.rot1()));
        let v = d.mul(q).sum3() * inv_det;
        if !(v >= zero && u + v <= one) {
            return None;
        }
        let t = e2.mul(q).sum3() * inv_det;
        // (`t > 0` makes `is_finite` the same as `t <= MAX`, so the two upper
        // limits are one comparison; `min2` returns its second argument when
        // the comparison fails, so a NaN `t_max` stays NaN and fails it.)
        if !(t > zero && t <= min2(S::<V>::MAX, t_max)) {
            return None;
        }
        // The determinant's sign must be certain, or the ray is taken as
        // parallel. (Tested last, so that the common misses above skip it;
        // every test is a pure function of the same values, so the order
        // changes no answer: a determinant of zero makes `u` NaN or infinite,
        // which the first test rejects.)
        //
        // Each monomial e1_i d_j e2_k of det carries at most 7 roundings (two
        // edge subtractions, a product, a difference, a product, two sums), so
        // |det - det_exact| <= gamma(7) sum_i |e1_i| (|d_j e2_k| + |d_k e2_j|).
        // The sum is evaluated from the computed e1 and products m, which are
        // rounded versions of the exact ones (at most 6 roundings along any
        // path, with the sum's own), and `bound_up` makes it an upper bound.
        let mag = m1.abs().add(m2.abs());
        let det_bound = bound_up(S::<V>::gamma_n(7) * e1.abs().mul(mag).sum3(), 7);
        if !(det.abs() > det_bound) {
            return None;
        }
        // det = e1 . (d x e2) = -d . ((b - a) x (c - a)): positive when the ray
        // runs against the normal.
        let side = if det > zero { Side::Front } else { Side::Back };
        Some(TriangleHit { t, u, v, side })
    }
}

#[cfg(test)]
mod tests {
    use super::super::definition::mt_definition;
    use super::*;
    use crate::testing::Draws;
    use glam::{DVec3, Vec3};

    /// `Triangle::moller_trumbore` (on lanes, with no separate validity test) is bit
    /// for bit its definition, invalid input included.
    #[test]
    fn mt_lanes_are_the_definition() {
        fn check<V: Vector>(draws: &mut Draws) -> usize {
            let mut v = || {
                let special = [
                    S::<V>::NAN,
                    S::<V>::INFINITY,
                    -S::<V>::INFINITY,
                    S::<V>::ZERO,
                ];
                let c = |draws: &mut Draws| {
                    let x = draws.coordinate(40);
                    if draws.0.is_multiple_of(97) {
                        special[(draws.0 >> 9) as usize % 4]
                    } else {
                        S::<V>::from_f64(x)
                    }
                };
                V::new(c(draws), c(draws), c(draws))
            };
            let tri = Triangle::new(v(), v(), v());
            let (origin, other) = (v(), v());
            let dir = if draws.0.is_multiple_of(2) {
                (tri.a + tri.b + tri.c) * (S::<V>::ONE / S::<V>::from_u32(3)) - origin
            } else {
                other
            };
            let ray = Ray::new(origin, dir);
            let mut hits = 0;
            let t_max = S::<V>::from_f64(draws.coordinate(40) * 4.0);
            for t_max in [t_max, S::<V>::INFINITY, S::<V>::NAN] {
                let bits = crate::testing::hit_bits::<S<V>>;
                let expected = bits(mt_definition(&ray, &tri, t_max));
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(tri.moller_trumbore(&ray, t_max)),
                    expected,
                    "{ray:?} {tri:?} {t_max:?}"
                );
            }
            hits
        }
        let mut draws = Draws(0x0fed_cba9_8765_4321);
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut draws) + check::<DVec3>(&mut draws);
        }
        assert!(hits > 50_000, "{hits}");
    }
}
