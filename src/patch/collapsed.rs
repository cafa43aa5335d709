//! A patch with a collapsed edge (two neighbouring corners equal) is the
//! triangle of its other three corners, and is tested as that triangle:
//! its answers are the [`Triangle`]'s, with the triangle's barycentrics
//! `(b, c)` (the weights of its second and third corners) turned into the
//! patch's `(u, v)` and their bounds carried over.
//!
//! The four collapses, each triangle wound as the patch (`P` its
//! bilinear point):
//!
//! | collapse | triangle | weights | `(u, v)` |
//! | --- | --- | --- | --- |
//! | `p10 = p00` | `p00, p11, p01` | `b = u v`, `c = (1 - u) v` | `(b / (b + c), b + c)` |
//! | `p11 = p10` | `p00, p10, p01` | `b = u`, `c = (1 - u) v` | `(b, c / (1 - b))` |
//! | `p11 = p01` | `p00, p10, p01` | `b = u (1 - v)`, `c = v` | `(b / (1 - c), c)` |
//! | `p01 = p00` | `p00, p10, p11` | `b = u (1 - v)`, `c = u v` | `(b + c, c / (b + c))` |
//!
//! At the apex (a quotient `0 / 0`) `u` or `v` is any value; it is `0`.

use super::{Patch, PatchHit};
use crate::num::Axis::{X, Y, Z};
use crate::num::round::outward::{add_up, div_up, mul_up, sub_down};
use crate::num::round::{max2, min2};
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::triangle::{Triangle, TriangleHit, TriangleHitError};

/// Which edge collapsed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Collapse {
    /// `p10 = p00`: the edge `v = 0`.
    V0,
    /// `p11 = p10`: the edge `u = 1`.
    U1,
    /// `p11 = p01`: the edge `v = 1`.
    V1,
    /// `p01 = p00`: the edge `u = 0`.
    U0,
}

/// `a / s` brought into `[0, 1]`, `0` where it is not a number (`0 / 0`).
#[inline(always)]
fn ratio<F: Scalar>(a: F, s: F) -> F {
    // (`max2` keeps the zero where `q` is NaN.)
    min2(max2(a / s, F::ZERO), F::ONE)
}

impl<V: Vector> Patch<V> {
    /// The collapsed edge and the triangle the patch is, if an edge
    /// collapsed (the first in the order of [`Collapse`]).
    #[inline]
    pub(super) fn collapsed(&self) -> Option<(Collapse, Triangle<V>)> {
        let corners = |k| self.boundary_lanes(k);
        self.collapsed_at(equal_neighbours([corners(X), corners(Y), corners(Z)]))
    }

    /// [`Patch::collapsed`] from the boundary's [`equal_neighbours`].
    #[inline(always)]
    pub(super) fn collapsed_at(&self, equal: u32) -> Option<(Collapse, Triangle<V>)> {
        let Self { p00, p10, p01, p11 } = *self;
        // Bit `i`: the edge from corner `i` of `00, 10, 11, 01` to the
        // next, in the order of `Collapse`.
        match equal.trailing_zeros() {
            0 => Some((Collapse::V0, Triangle::new(p00, p11, p01))),
            1 => Some((Collapse::U1, Triangle::new(p00, p10, p01))),
            2 => Some((Collapse::V1, Triangle::new(p00, p10, p01))),
            3 => Some((Collapse::U0, Triangle::new(p00, p10, p11))),
            _ => None,
        }
    }
}

/// Bit `i` set where corner `i` of the boundary (`00, 10, 11, 01`, a
/// corner a lane, one lane set per axis in any order) equals the next in
/// every coordinate (`-0 == +0`, as `V`'s equality).
#[inline(always)]
pub(super) fn equal_neighbours<L: Lanes>(axes: [L; 3]) -> u32 {
    let [a, b, c] = axes.map(|l| l.eq4(l.roll4()));
    a & b & c
}

impl<V: Vector> Patch<V> {
    /// Coordinate `k` of the four corners in the boundary's order, `00,
    /// 10, 11, 01`.
    #[inline(always)]
    pub(super) fn boundary_lanes(&self, k: Axis) -> L<V> {
        let Self { p00, p10, p01, p11 } = self;
        L::<V>::new4(p00.get(k), p10.get(k), p11.get(k), p01.get(k))
    }
}

impl Collapse {
    /// The patch's hit from the triangle's.
    #[inline]
    pub(super) fn hit<F: Scalar>(self, h: TriangleHit<F>) -> PatchHit<F> {
        let (u, v) = self.place(h.u, h.v);
        PatchHit {
            t: h.t,
            u,
            v,
            side: h.side,
        }
    }

    /// `(u, v)` from the triangle's weights `(b, c)`.
    #[inline]
    pub(super) fn place<F: Scalar>(self, b: F, c: F) -> (F, F) {
        let one = F::ONE;
        let sum = min2(b + c, one);
        match self {
            Collapse::V0 => (ratio(b, b + c), sum),
            Collapse::U1 => (b, ratio(c, one - b)),
            Collapse::V1 => (ratio(b, one - c), c),
            Collapse::U0 => (sum, ratio(c, b + c)),
        }
    }

    /// The triangle's weights `(b, c)` at the patch's `(u, v)`.
    #[inline]
    pub(super) fn weights<F: Scalar>(self, u: F, v: F) -> (F, F) {
        let one = F::ONE;
        match self {
            Collapse::V0 => (u * v, (one - u) * v),
            Collapse::U1 => (u, (one - u) * v),
            Collapse::V1 => (u * (one - v), v),
            Collapse::U0 => (u * (one - v), u * v),
        }
    }

    /// Bounds on `u` and `v` from the triangle's bounds `e` on its
    /// weights, at the hit `(u, v)` with weights `(b, c)`. A weight moved
    /// by `db` and `dc`: a sum moves by at most `eb + ec`; a quotient `p /
    /// q` (`u` or `v` the computed quotient) by at most `(ep + x eq) / (q -
    /// eq)` (`x` the quotient; infinite where `q - eq <= 0`), plus the
    /// quotient's own rounding, `gamma(3) x`, and the clamp into `[0, 1]`
    /// only moves it closer.
    pub(super) fn errors<F: Scalar>(
        self,
        (u, v): (F, F),
        (b, c): (F, F),
        e: &TriangleHitError<F>,
    ) -> (F, F) {
        let (eb, ec) = (e.u, e.v);
        let one = F::ONE;
        // (The weights here are recomputed from `(u, v)`, within a few
        // roundings of the triangle's: `gamma(4)` of the denominator
        // more covers that.)
        let quotient = |x: F, ep: F, q: F, eq: F| {
            let slack = mul_up(F::gamma_n(4), q.abs());
            let denom = sub_down(sub_down(q, eq), slack);
            if denom > F::ZERO {
                add_up(
                    div_up(
                        add_up(add_up(ep, slack), mul_up(x, add_up(eq, slack))),
                        denom,
                    ),
                    mul_up(F::gamma_n(3), x),
                )
            } else {
                F::INFINITY
            }
        };
        let sum = add_up(add_up(eb, ec), mul_up(F::gamma_n(1), add_up(b, c)));
        match self {
            Collapse::V0 => (quotient(u, eb, b + c, sum), sum),
            Collapse::U1 => (eb, quotient(v, ec, one - b, eb)),
            Collapse::V1 => (quotient(u, eb, one - c, ec), ec),
            Collapse::U0 => (sum, quotient(v, ec, b + c, sum)),
        }
    }
}

/// The triangle's hit error for a patch hit, with `u`, `v` bounds carried
/// over: the triangle's bound on a weight grows with the weight, so it is
/// taken at weights `(1, 1)`, at least the hit's.
pub(super) fn hit_error<V: Vector>(
    collapse: Collapse,
    tri: &Triangle<V>,
    ray: &impl crate::RayForm<V>,
    hit: &PatchHit<S<V>>,
) -> TriangleHitError<S<V>> {
    use crate::Surface;
    let one = S::<V>::ONE;
    let e = tri.hit_error(
        ray,
        &TriangleHit {
            t: hit.t,
            u: one,
            v: one,
            side: hit.side,
        },
    );
    let (b, c) = collapse.weights(hit.u, hit.v);
    let (eu, ev) = collapse.errors((hit.u, hit.v), (b, c), &e);
    TriangleHitError {
        t: e.t,
        u: eu,
        v: ev,
    }
}

#[cfg(test)]
mod tests {
    use super::Collapse;
    use crate::Patch;
    use glam::DVec3;

    /// For each collapse, on a grid of `(u, v)`: the patch's bilinear
    /// point is the triangle's point at `weights(u, v)` (the table in the
    /// module docs, checked against the geometry), and `place` inverts
    /// `weights` wherever the quotient's denominator is not small (near
    /// the apex `u` or `v` is not determined).
    #[test]
    fn weights_are_the_triangles_and_place_inverts_them() {
        let corners = [
            DVec3::new(0.1, -0.2, 0.3),
            DVec3::new(1.3, 0.1, -0.4),
            DVec3::new(-0.2, 1.1, 0.6),
            DVec3::new(0.9, 1.4, 1.2),
        ];
        let [p00, p10, p01, p11] = corners;
        let patches = [
            (Collapse::V0, Patch::new(p00, p00, p01, p11)),
            (Collapse::U1, Patch::new(p00, p10, p01, p10)),
            (Collapse::V1, Patch::new(p00, p10, p01, p01)),
            (Collapse::U0, Patch::new(p00, p10, p00, p11)),
        ];
        for (collapse, patch) in patches {
            let (found, tri) = patch.collapsed().expect("an edge collapsed");
            assert_eq!(found, collapse);
            for i in 0..=16 {
                for j in 0..=16 {
                    let (u, v) = (f64::from(i) / 16.0, f64::from(j) / 16.0);
                    let (b, c) = collapse.weights(u, v);
                    let on_triangle = tri.a + (tri.b - tri.a) * b + (tri.c - tri.a) * c;
                    // Both points are a dozen roundings of coordinates
                    // below 2 (each within 2^-52 relative): under 1e-14.
                    let d = (patch.point_at(u, v) - on_triangle).abs().max_element();
                    assert!(d < 1e-14, "{collapse:?} at ({u}, {v}): {d}");
                    let (pu, pv) = collapse.place(b, c);
                    // The denominators of the quotients in `place`.
                    let denom = match collapse {
                        Collapse::V0 | Collapse::U0 => b + c,
                        Collapse::U1 => 1.0 - b,
                        Collapse::V1 => 1.0 - c,
                    };
                    // The weights carry a few roundings (about 2^-52 each);
                    // a sum or `1 - w` reads them back to 1e-15, a
                    // quotient divides that by its denominator (1e-12
                    // where it exceeds 1e-3).
                    let (du, dv) = ((pu - u).abs(), (pv - v).abs());
                    match collapse {
                        Collapse::V0 | Collapse::V1 => {
                            assert!(dv < 1e-15, "{collapse:?} v {v}: {pv}")
                        }
                        Collapse::U1 | Collapse::U0 => {
                            assert!(du < 1e-15, "{collapse:?} u {u}: {pu}")
                        }
                    }
                    if denom > 1e-3 {
                        assert!(
                            du < 1e-12 && dv < 1e-12,
                            "{collapse:?} ({u}, {v}): ({pu}, {pv})"
                        );
                    }
                }
            }
        }
    }
}
