//! The reference definitions of the triangle tests, one component at a
//! time: the watertight test (Woop, Benthin and Wald, JCGT 2013, as in
//! pbrt-v4) with both edge rules, [`watertight_definition`], and
//! Moller-Trumbore's, `mt_definition`. The one-hit rule
//! ([`EdgeRule::OneHit`]) runs the first itself; [`ray_triangle`],
//! `ray_triangle_prepared` and the triangle batches run its common case on
//! lanes, hand it their rare cases, and their tests hold them to it bit for
//! bit, as Moller-Trumbore's test holds it to the second.
//!
//! [`ray_triangle`]: crate::ray_triangle

use super::bounds::{ErrorBounds, HitCondition, longest_edge_t, max3};
use super::conditioning::det_sign_known;
use super::frame::Frame;
use super::one_hit::{one_hit_edges, unresolved_hit};
use super::{Side, Triangle, TriangleHit};
use crate::num::round::{max2, min2};
use crate::num::{S, Scalar, Vector};
pub(crate) use crate::query::EdgeRule;
use crate::ray::{Interval, Shear};

/// The watertight test for a valid ray, given its origin and shear, and a
/// `t_max >= 0`. [`ray_triangle`](crate::ray_triangle),
/// [`ray_triangle_prepared`](super::watertight::ray_triangle_prepared) and the
/// triangle batches' undecided lanes all come here.
#[inline(always)]
pub(crate) fn watertight_definition<V: Vector>(
    (origin, dir): (V, V),
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
    t_max: S<V>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let zero = S::<V>::ZERO;
    let shear = *shear;
    let f = Frame::new(origin, tri, &shear);

    // Inside test in the sheared plane.
    let [e0, e1, e2] = inside(&f, rule, (origin, dir), &shear, tri)?;
    let det = e0 + e1 + e2;
    if rule == EdgeRule::OneHit && !(det != zero && det.is_finite()) {
        // An exact one-hit hit that rounding leaves no determinant.
        let range = Interval::up_to(t_max)?;
        return unresolved_hit((origin, dir), &shear, tri, &f, range);
    }

    // Distance: interpolate the scaled z with the edge functions, and compare
    // against t_max * det before paying for the division.
    let z = f.scaled_z(&shear);
    let t_scaled = e0 * z[0] + e1 * z[1] + e2 * z[2];
    let in_range = if det > zero {
        t_scaled > zero && t_scaled <= t_max * det
    } else if det < zero {
        t_scaled < zero && t_scaled >= t_max * det
    } else {
        false // zero area in the sheared plane, or NaN
    };
    let inv_det = S::<V>::ONE / det;
    let plain = t_scaled * inv_det;
    let plain_ok = in_range && plain > zero && plain <= t_max && plain.is_finite();
    // t > 0 decided conservatively, by any of three sufficient tests, in
    // order of cost:
    // - every corner lies in front of the origin in exact arithmetic
    //   (z_i > 0: the sign of z_i = fl(fl(c_z - o_z) fl(1 / d_z)) is exact,
    //   as a rounded difference is zero only when the operands are equal
    //   and rounding keeps signs; an underflow to zero only makes the test
    //   fail): any crossing of the triangle is a convex combination of
    //   them, so it is in front too, however thin the triangle looks from
    //   the ray (this keeps small triangles far away, where the next two are
    //   too pessimistic, and a crack would open if they were the only ones);
    // - the scaled distance exceeds its rounding error bound (pbrt-v4's
    //   test): the exact numerator has the sign of det;
    // - where the determinant is well conditioned, t exceeds its own error
    //   bound: the exact crossing is at t > 0.
    // The first test needs no bound, so the other bounds are computed only
    // when it fails (they are pure functions of the same
    // values, so the order changes no answer). No corner in front of the
    // origin (every z_i <= 0, or NaN) likewise means no hit: every crossing
    // is at t <= 0.
    let ahead = z[0] > zero && z[1] > zero && z[2] > zero;
    let behind = !(z[0] > zero || z[1] > zero || z[2] > zero);
    let (m, w) = (max2(max3(&f.x), max3(&f.y)), max3(&f.pz));
    let t = if plain_ok && ahead && det_sign_known(det, m, w) {
        // (The common case, and the fast paths' answer: the full test
        // below would give the same, as the determinant's sign is known.)
        plain
    } else if behind {
        return None;
    } else {
        let bounds = ErrorBounds::new(&f, &z, &shear);
        match HitCondition::new(&bounds, det) {
            Some(c) => {
                let sure = ahead
                    || t_scaled.abs() > bounds.t_scaled
                    || plain > c.t_error(&bounds, &z, plain);
                if !(plain_ok && sure) {
                    return None;
                }
                plain
            }
            None if det != zero && tri.is_degenerate() => {
                // A triangle of zero area (its corners exactly collinear)
                // that rounding leaves a sliver in the ray's frame: `plain`
                // weighs the corners' depths almost arbitrarily, its sign
                // included. The depth of the longest edge's point nearest
                // the ray is well conditioned, and is where the ray passes
                // the segment; the hit stands where that is surely in front
                // (as it is when every corner is).
                let (t, bound) = longest_edge_t(&f, &z, &bounds)?;
                if !((ahead || t > bound) && t > zero && t <= t_max) {
                    return None;
                }
                t
            }
            // Otherwise (a ray within rounding of parallel to the triangle,
            // or a sliver far away), only where every corner is in front.
            None if plain_ok && ahead => plain,
            None => return None,
        }
    };
    hit_at(t, [e1, e2], det, inv_det, &shear)
}

/// The hit at distance `t`, given the edge functions `e1`, `e2`, their sum
/// `det` and its reciprocal: the barycentrics and the side. `None` when a
/// barycentric is not finite. Shared by every form of the watertight test.
#[inline(always)]
pub(crate) fn hit_at<F: Scalar>(
    t: F,
    [e1, e2]: [F; 2],
    det: F,
    inv_det: F,
    shear: &Shear<F>,
) -> Option<TriangleHit<F>> {
    let (zero, one) = (F::ZERO, F::ONE);
    // Each e_i / det is in [0, 1] exactly (all e_i share det's sign, and
    // |det| >= |e_i|); the rounded reciprocal can push it one ulp past 1.
    let u = min2(e1 * inv_det, one);
    let v = min2(e2 * inv_det, one);
    if !(u.is_finite() && v.is_finite()) {
        return None;
    }
    // In the frame before the z scaling (orientation preserving: a cyclic
    // permutation and a shear), the ray runs along +z with speed d_z and
    // det is the z component of the normal; dir . normal = d_z * det.
    let side = if (det > zero) != (shear.dz > zero) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleHit { t, u, v, side })
}

/// The watertight test's inside test in the sheared plane, with the edge
/// rule `rule`, for the ray `(origin, dir)` whose shear made `f`: the edge
/// functions the hit is computed from, or `None` outside.
///
/// The closed rule takes the computed signs (exact: see [`Frame`]), a zero
/// counting as inside, and answers with the frame's edge functions; NaN
/// edge functions (overflow) pass it, and the determinant's range test
/// rejects them instead. The one-hit rule decides exactly for the ray
/// moved off every edge line, and answers with the edge functions
/// [`one_hit_edges`] gives.
#[inline(always)]
pub(crate) fn inside<V: Vector>(
    f: &Frame<S<V>>,
    rule: EdgeRule,
    ray: (V, V),
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
) -> Option<[S<V>; 3]> {
    let zero = S::<V>::ZERO;
    let [e0, e1, e2] = f.e;
    match rule {
        EdgeRule::Closed => {
            let any_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
            let any_pos = (e0 > zero) | (e1 > zero) | (e2 > zero);
            (!(any_neg & any_pos)).then_some(f.e)
        }
        EdgeRule::OneHit => one_hit_edges(f, ray, shear, tri),
    }
}

#[cfg(test)]
pub(crate) use moller_trumbore::mt_definition;

/// Moller-Trumbore's definition, compiled for the tests.
#[cfg(test)]
mod moller_trumbore {
    use crate::num::round::bound_up;
    use crate::num::{S, Scalar, Vector};
    use crate::ray::{Ray, t_max_ok};
    use crate::triangle::{Side, Triangle, TriangleHit};

    /// Moller-Trumbore's definition: the test as written with glam's `cross`
    /// and `dot`, one component at a time, which [`Triangle::moller_trumbore`] (on
    /// lanes) must match bit for bit. (Compiled for the tests.)
    ///
    /// [`Triangle::moller_trumbore`]: crate::Triangle::moller_trumbore
    pub(crate) fn mt_definition<V: Vector>(
        ray: &Ray<V>,
        tri: &Triangle<V>,
        t_max: S<V>,
    ) -> Option<TriangleHit<S<V>>> {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        if !(ray.is_valid() && t_max_ok(t_max)) {
            return None;
        }
        let d = ray.dir;
        let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
        let (m1, m2) = (d.y() * e2.z(), d.z() * e2.y());
        let (m3, m4) = (d.z() * e2.x(), d.x() * e2.z());
        let (m5, m6) = (d.x() * e2.y(), d.y() * e2.x());
        let p = V::new(m1 - m2, m3 - m4, m5 - m6);
        let det = e1.dot(p);
        let mag = V::new(
            m1.abs() + m2.abs(),
            m3.abs() + m4.abs(),
            m5.abs() + m6.abs(),
        );
        let det_bound = bound_up(S::<V>::gamma_n(7) * e1.abs().dot(mag), 7);
        if !(det.abs() > det_bound) {
            return None;
        }
        let inv_det = one / det;
        let s = ray.origin - tri.a;
        let u = s.dot(p) * inv_det;
        if !(u >= zero && u <= one) {
            return None;
        }
        let q = s.cross(e1);
        let v = d.dot(q) * inv_det;
        if !(v >= zero && u + v <= one) {
            return None;
        }
        let t = e2.dot(q) * inv_det;
        if !(t > zero && t <= t_max && t.is_finite()) {
            return None;
        }
        let side = if det > zero { Side::Front } else { Side::Back };
        Some(TriangleHit { t, u, v, side })
    }
}
