//! Triangles.
//!
//! - `mod.rs`: [`Triangle`], [`Side`], [`TriangleHit`].
//! - `frame.rs`: a triangle in a ray's sheared frame, and its edge functions.
//! - `definition.rs`: the watertight test's reference definition, one
//!   component at a time, with both edge rules (closed, and one hit per
//!   crossing); the fast paths hand it their rare cases.
//! - `conditioning.rs`: whether the determinant's sign is known, the
//!   predicate that lets a fast path return the plain answer.
//! - `one_hit.rs`: the one-hit rule's inside test, decided exactly for
//!   the ray moved off every edge line.
//! - `bounds.rs`: the rounding error bounds of a hit, and the hit point's.
//! - `watertight.rs`: [`ray_triangle`] (a plain ray: every main axis at
//!   once), `ray_triangle_prepared` and `ray_triangle_one_hit`, held to
//!   the definition bit for bit.
//! - `interval.rs`: the watertight tests over an interval `(t_min,
//!   t_max]`, both ends decided exactly.
//! - `mt.rs`: Moller-Trumbore ([`Triangle::moller_trumbore`]) and its
//!   definition.
//! - `lanes.rs`: what the lane forms share (packed hits, a triangle's frame
//!   in the ray's lanes, the ray forms the definition takes).
//! - `batch.rs`: [`TriangleBatch`], the watertight test on eight lanes of
//!   triangles at a time, held to the definition bit for bit, and the
//!   one-hit rule's lanes.
//! - `batch_interval.rs`: the batch over an interval, each lane the scalar
//!   interval test's answer bit for bit.
//! - `query.rs`: the [`Intersect`](crate::Intersect) and
//!   [`Surface`](crate::Surface) implementations: each combination of ray
//!   form, range and edge rule sent to its kernel.

mod band;
mod batch;
mod batch_interval;
mod bounds;
mod conditioning;
mod definition;
mod frame;
mod interval;
mod lanes;
mod mt;
mod one_hit;
mod query;
mod watertight;

use glam::Vec3;

use crate::num::exact_sign::{scale_to_one, sum_of_products_sign, two_diff};
use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};

pub use batch::{TriangleBatch, TriangleBatchHits};
pub use bounds::TriangleHitError;
pub(crate) use bounds::{axis_error, depth_error};
pub(crate) use conditioning::{
    det_sign_known_at_four_corners, det_sign_known_roughly_at_four_corners,
};
pub(crate) use definition::inside;
pub(crate) use frame::{Frame, edge_function};
pub(crate) use lanes::Packed;
pub use watertight::ray_triangle;

/// The triangle with corners `a`, `b`, `c`.
///
/// The winding `a -> b -> c` defines the geometric normal
/// `(b - a) x (c - a)` (right-handed: counter-clockwise seen from the side it
/// points to) and so which side of a hit is [`Side::Front`]. The tests are
/// two-sided and report the side. A triangle with a NaN or infinite
/// coordinate is hit by nothing.
///
/// **Zero-area triangles** (corners collinear or coincident, exactly:
/// [`Triangle::is_degenerate`]) can be hit, on purpose. The watertight tests
/// with the closed rule hit one where, in the ray's sheared frame, its
/// rounded corners enclose the ray: rounding gives the segment a sliver of
/// area there. (With [`EdgeRule::OneHit`](crate::EdgeRule), decided in
/// exact arithmetic, a zero-area triangle is never hit: the neighbours
/// close the surface exactly.) Meshes close
/// T-junctions (a vertex on another triangle's edge, filled with the
/// zero-area triangle between that edge and the two halves) and collapsed
/// edges with such triangles, and in the rounded frame the filler is exactly
/// the sliver between the neighbours' edges; dropping it would open a crack
/// just there. A hit on one has `u`, `v` in range, the side of its rounded
/// determinant, and the `t` where the ray passes the segment, within the
/// finite bound [`hit_error`](crate::Surface::hit_error) gives; its normal
/// is zero or meaningless, so shade it with a neighbour's.
/// [`surface_point`](crate::Surface::surface_point) and
/// [`SurfacePoint::spawn`] stay finite: with a zero normal the spawned
/// ray starts at the hit point itself. Use [`Triangle::is_degenerate`] to
/// drop such triangles when loading a mesh that does not need them.
///
/// The queries are [`Intersect`](crate::Intersect) (the closest hit and the
/// any-hit answer over a `t_max` or an [`Interval`](crate::Interval), with
/// either [`EdgeRule`](crate::EdgeRule); the guarantees are on its
/// [`hit`](#method.hit)) and [`Surface`](crate::Surface) (the hit's error
/// bounds and the point it leaves from).
///
/// [`SurfacePoint::spawn`]: crate::SurfacePoint::spawn
///
/// ```
/// use rayhit::{Triangle, glam::Vec3};
/// let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(t.normal(), Vec3::Z);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct Triangle<V = Vec3> {
    /// First corner; barycentric weight `1 - u - v`.
    pub a: V,
    /// Second corner; barycentric weight `u`.
    pub b: V,
    /// Third corner; barycentric weight `v`.
    pub c: V,
}

impl<V: Vector> Triangle<V> {
    /// The triangle `a, b, c`. Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(a: V, b: V, c: V) -> Self {
        Self { a, b, c }
    }

    /// The geometric normal `(b - a) x (c - a)`, not normalised (its length
    /// is twice the area), rounded.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> V {
        (self.b - self.a).cross(self.c - self.a)
    }

    /// A per-component bound on the difference between
    /// [`Triangle::normal`] and the exact `(b - a) x (c - a)`.
    ///
    /// Each monomial `e1_j e2_k` of a component carries four roundings (two
    /// edge subtractions, the product, the difference), so the error is at
    /// most `gamma(4) (|e1_j e2_k| + |e1_k e2_j|)`, and `gamma(6)` with the
    /// computed edges; evaluating that adds three roundings. For a sliver
    /// triangle the bound can be as large as the normal itself: its
    /// direction is then not known, and
    /// [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) offsets
    /// accordingly.
    ///
    /// ```
    /// use rayhit::{Triangle, glam::Vec3};
    /// let t = Triangle::new(Vec3::ZERO, Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.0, 5.0, 0.0));
    /// // Exact products of exact differences: tiny bounds, and a normal of (0, 0, 15).
    /// assert_eq!(t.normal(), Vec3::new(0.0, 0.0, 15.0));
    /// assert!(t.normal_error().z <= 15.0 * 4.0 * f32::EPSILON);
    /// ```
    #[inline]
    #[must_use]
    pub fn normal_error(&self) -> V {
        let (e1, e2) = (self.b - self.a, self.c - self.a);
        let g6 = S::<V>::gamma_n(6);
        let m = |j: usize, k: usize| (e1[j] * e2[k]).abs() + (e1[k] * e2[j]).abs();
        let err = V::new(m(1, 2), m(2, 0), m(0, 1)) * g6;
        V::new(
            bound_up(err.x(), 3),
            bound_up(err.y(), 3),
            bound_up(err.z(), 3),
        )
    }

    /// True when the corners are collinear or coincide, in exact arithmetic:
    /// `(b - a) x (c - a)` is exactly zero. No tolerance: a triangle with
    /// the smallest area the coordinates allow is not degenerate.
    ///
    /// For loading meshes: the watertight tests still hit such a triangle
    /// where its rounded corners enclose the ray (see [`Triangle`]); drop
    /// it only where the mesh does not rely on it to stay closed.
    ///
    /// Exact: the rounded cross product decides when a component clearly
    /// exceeds its rounding error (almost always: a few dozen operations);
    /// otherwise each difference is split into its rounded value and exact
    /// error (Knuth's two-sum) and each component's sign is computed exactly
    /// from the sixteen products (Shewchuk's expansions; a few hundred
    /// operations). For `f64`, exact as long as no product of two
    /// coordinate differences, scaled to the largest, underflows (the
    /// differences within a factor `2^900` of each other).
    ///
    /// ```
    /// use rayhit::{Triangle, glam::Vec3};
    /// // c - a = 2 (b - a): collinear, exactly.
    /// let line = Triangle::new(Vec3::new(6.0, -5.0, 2.0), Vec3::new(4.0, -2.0, 5.0), Vec3::new(2.0, 1.0, 8.0));
    /// assert!(line.is_degenerate());
    /// // Off the line by one ulp: not degenerate.
    /// let sliver = Triangle::new(line.a, line.b, Vec3::new(2.0, 1.0, 8.0f32.next_up()));
    /// assert!(!sliver.is_degenerate());
    /// assert!(Triangle::new(Vec3::ONE, Vec3::ONE, Vec3::ONE).is_degenerate());
    /// ```
    #[must_use]
    pub fn is_degenerate(&self) -> bool {
        let (n, err) = (self.normal(), self.normal_error());
        if n.abs().x() > err.x() || n.abs().y() > err.y() || n.abs().z() > err.z() {
            return false;
        }
        // Exact differences: b - a = s1 + e1, c - a = s2 + e2.
        let split = |p: V, q: V| {
            let d = |k: usize| two_diff(p[k], q[k]);
            [d(0), d(1), d(2)]
        };
        let (u, v) = (split(self.b, self.a), split(self.c, self.a));
        // Scale each difference vector's parts by a common power of two
        // first (exact), so that tiny or huge coordinates neither underflow
        // nor overflow the products.
        let scale = |w: [(S<V>, S<V>); 3]| {
            let m = w.iter().fold(0.0f64, |m, (s, _)| m.max(s.to_f64().abs()));
            if m == 0.0 {
                return w.map(|(s, e)| (s.to_f64(), e.to_f64()));
            }
            w.map(|(s, e)| (scale_to_one(s.to_f64(), m), scale_to_one(e.to_f64(), m)))
        };
        let (u, v) = (scale(u), scale(v));
        // Component k of u x v: u_j v_l - u_l v_j, (j, l) = (k + 1, k + 2).
        (0..3).all(|k| {
            let (j, l) = ((k + 1) % 3, (k + 2) % 3);
            let ((uj, ej), (ul, el)) = (u[j], u[l]);
            let ((vj, fj), (vl, fl)) = (v[j], v[l]);
            let terms = [
                (uj, vl),
                (uj, fl),
                (ej, vl),
                (ej, fl),
                (-ul, vj),
                (-ul, fj),
                (-el, vj),
                (-el, fj),
            ];
            sum_of_products_sign(&terms) == core::cmp::Ordering::Equal
        })
    }

    /// The same triangle with the opposite winding (`a, c, b`): the normal
    /// flips, `u` and `v` swap, and front and back swap.
    #[inline]
    #[must_use]
    pub fn flipped(&self) -> Self {
        Self {
            a: self.a,
            b: self.c,
            c: self.b,
        }
    }
}

/// Which side of a triangle a ray arrived from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum Side {
    /// Against the geometric normal (`dir . normal < 0`): the side the normal
    /// points to, where the winding looks counter-clockwise.
    Front,
    /// Along the geometric normal (`dir . normal > 0`).
    Back,
}

/// A ray/triangle hit.
///
/// The hit point is `(1 - u - v) * a + u * b + v * c = origin + t * dir`;
/// `t` is in units of the ray's `dir`, `0 < t <= t_max`; `u` and `v` are each
/// in `[0, 1]` (their sum can exceed 1 by a rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct TriangleHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// Barycentric weight of corner `b`.
    pub u: F,
    /// Barycentric weight of corner `c`.
    pub v: F,
    /// The side the ray arrived from: the sign of the computed determinant
    /// (`dir . normal`), which is the exact sign whenever
    /// [`hit_error`](crate::Surface::hit_error) for the hit is finite (it is infinite
    /// exactly when that sign is not certain: a ray within rounding of
    /// parallel, or a sliver seen edge-on).
    pub side: Side,
}
