//! Quads: planar quadrilaterals and parallelograms, each the two
//! triangles on either side of a diagonal, tested with the watertight
//! triangle test so that quads and triangles sharing an edge leave no
//! crack between them.

use core::hint::select_unpredictable;

use glam::Vec3;

use crate::aabb::Aabb;
use crate::num::round::min2;
use crate::num::round::outward::{add_up, mul_up};
use crate::num::{Axis, S, Scalar, Vector};
use crate::num::{Bits, L, Lanes, Repr};
use crate::patch::frame::{CornerLanes, RayFrame, RayParts};
use crate::query::sealed::Form;
use crate::query::{EdgeRule, Intersect, Range, RayForm, Search, Surface};
use crate::ray::{PreparedRay, Ray, t_max_ok};
use crate::surface::SurfacePoint;
use crate::triangle::{
    Packed, Side, Triangle, TriangleHit, TriangleHitError, det_sign_known_at_four_corners,
    det_sign_known_roughly_at_four_corners,
};

/// The quadrilateral with corners `a`, `b`, `c`, `d` in order around it:
/// the two closed triangles `a, b, c` and `a, c, d`, sharing the diagonal
/// from `a` to `c`.
///
/// That is the planar quad itself when the corners are coplanar and the
/// quad is convex (or concave at `b` or `d`): the walls and area lights of
/// a Cornell box, a mesh's quad faces, "The Next Week"'s `quad`. Corners
/// that are not coplanar give the two triangles, folded along `a`-`c` (for
/// the curved surface through four corners, use a bilinear patch).
///
/// Each triangle is tested by the watertight triangle test
/// ([`Triangle`]'s [`hit`](crate::Intersect::hit)), so a quad inherits its
/// guarantees: the side of each edge is decided from that edge's two
/// corners alone, so two quads, or a quad and a triangle, that share an
/// edge (the same two corners, bit for bit) leave no crack and no leak
/// between them, and with [`EdgeRule::OneHit`](crate::EdgeRule) a ray
/// through a shared edge or corner hits exactly one of them. The
/// diagonal is inside the quad: a ray through it is one hit.
///
/// The hit's `u` and `v` place it on the quad with `a` at `(0, 0)`, `b`
/// at `(1, 0)`, `c` at `(1, 1)` and `d` at `(0, 1)`, linearly on each
/// triangle: for a parallelogram the point is `a + u (b - a) + v (d - a)`
/// exactly. The winding `a -> b -> c -> d` gives the front side, as for a
/// [`Triangle`] (counter-clockwise seen from the front).
///
/// A plain [`Ray`] is sheared on each call; for one ray against many
/// quads, pass a [`PreparedRay`] (made once): the answers are the same,
/// bit for bit.
///
/// A quad with a collapsed edge (two neighbouring corners equal) is the
/// triangle it became, with the triangle's rules for zero-area triangles
/// on the collapsed half. A NaN or infinite coordinate makes each triangle
/// with that corner one nothing hits, as for a [`Triangle`]; the quad is
/// then hit only where a triangle without it is (a NaN in `d` leaves the
/// triangle `a, b, c`, which stays safe to shade and spawn from).
///
/// ```
/// use rayhit::{Intersect, Quad, Ray, Side, glam::Vec3};
/// // A 2 by 1 rectangle in the plane z = 0, facing +z.
/// let quad = Quad::parallelogram(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 3.0), -Vec3::Z);
/// let hit = quad.hit(&ray, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.u, hit.v, hit.side), (3.0, 0.25, 0.25, Side::Front));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quad<V = Vec3> {
    /// The first corner, at `(u, v) = (0, 0)`.
    pub a: V,
    /// The second corner, at `(1, 0)`.
    pub b: V,
    /// The third corner, at `(1, 1)`, opposite `a`.
    pub c: V,
    /// The fourth corner, at `(0, 1)`.
    pub d: V,
}

/// A ray/quad hit: `t` in units of the ray's `dir`, where on the quad, and
/// the side.
///
/// Only the quad's tests make one (it records which triangle of the quad
/// was hit, for the error bounds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// The coordinate along `a -> b` (and `d -> c`), in `[0, 1]`.
    pub u: F,
    /// The coordinate along `a -> d` (and `b -> c`), in `[0, 1]`.
    pub v: F,
    /// The side the ray arrived from, as for a [`Triangle`]: the sign of
    /// `dir . normal` on the triangle hit.
    pub side: Side,
    /// Which triangle: `a, b, c` (`false`) or `a, c, d` (`true`).
    second: bool,
}

impl<V: Vector> Quad<V> {
    /// The quad with corners `a`, `b`, `c`, `d` in order. Nothing is
    /// checked.
    #[inline]
    #[must_use]
    pub const fn new(a: V, b: V, c: V, d: V) -> Self {
        Self { a, b, c, d }
    }

    /// The parallelogram with a corner at `corner` and edges `edge_u` and
    /// `edge_v` from it ("The Next Week"'s `quad`): corners `corner`,
    /// `corner + edge_u`, `corner + edge_u + edge_v`, `corner + edge_v`,
    /// each rounded. (The rounding can leave the corners off one plane by
    /// an ulp: the quad is then folded along its diagonal by that much. Quads
    /// whose corners are given exactly, as a mesh's are, share them bit for
    /// bit with their neighbours; build those with [`Quad::new`].)
    #[inline]
    #[must_use]
    pub fn parallelogram(corner: V, edge_u: V, edge_v: V) -> Self {
        let b = corner + edge_u;
        Self::new(corner, b, b + edge_v, corner + edge_v)
    }

    /// Coordinate `k` of the four corners, in the order `a, b, c, d`.
    #[inline(always)]
    fn corner_lanes(&self, k: Axis) -> L<V> {
        L::<V>::new4(self.a.get(k), self.b.get(k), self.c.get(k), self.d.get(k))
    }

    /// The two triangles the quad is made of: `a, b, c` and `a, c, d`.
    #[inline]
    #[must_use]
    pub fn triangles(&self) -> [Triangle<V>; 2] {
        [
            Triangle::new(self.a, self.b, self.c),
            Triangle::new(self.a, self.c, self.d),
        ]
    }

    /// The quad's normal `(c - a) x (d - b)`, not normalised, rounded:
    /// for a planar quad its length is twice the area and its direction is
    /// the front side's.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> V {
        (self.c - self.a).cross(self.d - self.b)
    }

    /// The smallest box around the four corners (exact: no rounding), for
    /// a BVH built over quads.
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> Aabb<V> {
        let [a, b, c, d] = [self.a, self.b, self.c, self.d];
        let pick = |f: fn(S<V>, S<V>) -> S<V>, k: fn(V) -> S<V>| f(f(k(a), k(b)), f(k(c), k(d)));
        let lo = |p: S<V>, q: S<V>| if q < p { q } else { p };
        let hi = |p: S<V>, q: S<V>| if q > p { q } else { p };
        Aabb::new(
            V::new(pick(lo, V::x), pick(lo, V::y), pick(lo, V::z)),
            V::new(pick(hi, V::x), pick(hi, V::y), pick(hi, V::z)),
        )
    }

    /// The surface point at `(u, v)` (for points that come from no ray:
    /// samples on a quad light, the ends of a shadow segment), as
    /// [`surface_point`](Surface::surface_point) gives it for a hit there:
    /// on the triangle `a, b, c` where `u >= v`, else on `a, c, d`, with
    /// that triangle's bound and normal ([`Triangle::surface_point_at`]).
    ///
    /// ```
    /// use rayhit::{Quad, glam::Vec3};
    /// let light = Quad::parallelogram(Vec3::new(0.0, 3.0, 0.0), Vec3::X, Vec3::Z);
    /// let sample = light.surface_point_at(0.5, 0.25);
    /// assert_eq!(sample.point, Vec3::new(0.5, 3.0, 0.25));
    /// assert!(sample.normal.y < 0.0); // facing down
    /// ```
    #[inline]
    #[must_use]
    pub fn surface_point_at(&self, u: S<V>, v: S<V>) -> SurfacePoint<V> {
        let [first, second] = self.triangles();
        if u >= v {
            first.surface_point_at(u - v, v)
        } else {
            second.surface_point_at(u, v - u)
        }
    }
}

impl<F: Scalar> QuadHit<F> {
    /// The quad's hit from a hit on its first triangle (`a, b, c`, weights
    /// `u1` of `b`, `v1` of `c`) or its second (`a, c, d`, weights `u2` of
    /// `c`, `v2` of `d`): on the first `u = u1 + v1`, `v = v1`; on the
    /// second `u = u2`, `v = u2 + v2` (the point `a + u1 (b - a) + v1 (c -
    /// a)` written with `c = b + d - a`, which a parallelogram satisfies).
    #[inline(always)]
    fn from_triangle(hit: TriangleHit<F>, second: bool) -> Self {
        let sum = min2(hit.u + hit.v, F::ONE);
        let (u, v) = if second { (hit.u, sum) } else { (sum, hit.v) };
        Self {
            t: hit.t,
            u,
            v,
            side: hit.side,
            second,
        }
    }
}

/// The nearer of the two triangles' hits as the quad's, the first where
/// they tie.
#[inline(always)]
fn nearer<F: Scalar>(
    first: Option<TriangleHit<F>>,
    second: Option<TriangleHit<F>>,
) -> Option<QuadHit<F>> {
    let near = first.map(|h| QuadHit::from_triangle(h, false));
    let far = second.map(|h| QuadHit::from_triangle(h, true));
    match (near, far) {
        (Some(n), Some(f)) if f.t < n.t => Some(f),
        (None, f) => f,
        (n, _) => n,
    }
}

/// The closed test over a `t_max`, on a plain or a prepared ray: each
/// triangle's [`Triangle`] `hit`, bit for bit, with the ray's shear taken
/// once and the four corners framed once (a corner a lane, as the
/// triangle test frames a triangle's). The common
/// miss, where neither triangle covers the ray, leaves first; the rest
/// finishes both triangles side by side in lanes (the first in lanes 0
/// and 1, the second in 2 and 3) and takes the answer from the one that
/// covers the ray with no branch (which one does is a coin toss on rays
/// aimed at the quad, where a branch on it cost more than the lanes of
/// the other: BENCHMARKS.md). What the triangle test leaves to its
/// definition (an edge function of zero, a corner behind
/// the origin, a determinant of unknown sign) and a ray both triangles
/// cover (through the diagonal) go to [`quad_rare`]; where only the exact
/// threshold can tell whether the determinant's sign is known (a quad
/// small next to its distance), the test starts again out of line with
/// `EXACT` set ([`quad_far`]), so that the common path calls nothing it
/// returns from. The answer is packed (see [`pack`]), so that a miss and
/// a hit differ only in its code.
#[inline(always)]
fn quad_lanes<V: Vector, R: FramedRay<V>, const EXACT: bool>(
    ray: &R,
    quad: &Quad<V>,
    t_max: S<V>,
) -> Packed<S<V>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    if !(ray.valid() && t_max_ok(t_max)) {
        return pack::<S<V>>(None);
    }
    let splat = L::<V>::splat;
    let lanes_zero = splat(zero);
    let parts = ray.parts();
    let frame = R::frame(ray, &parts);
    let (c, pz) = CornerLanes::of(&frame, |k| quad.corner_lanes(k));
    // The triangle test's edge functions, each opposite a corner: b-c, c-a
    // and a-b on `a, b, c`; c-d, d-a and a-c on `a, c, d`; and the
    // corners' depths.
    let (edges, diagonals) = (c.edges(), c.diagonals());
    let [e_ab, e_bc, e_cd, e_da] = edges.to_array4();
    let [ac, _, ca, _] = diagonals.to_array4();
    let [za, zb, zc, zd] = c.z.to_array4();
    let pair = |first: S<V>, second: S<V>| L::<V>::new4(first, first, second, second);
    let (e0, e1, e2) = (pair(e_bc, e_cd), pair(ca, e_da), pair(e_ab, ac));
    let (z0, z1, z2) = (splat(za), pair(zb, zc), pair(zc, zd));
    // Bit 0 for the first triangle, bit 2 for the second: whether its edge
    // functions take both strict signs (it misses, whatever the exact sign
    // of one that rounds to zero), or one strict sign (it covers the ray;
    // else an edge function is zero, or NaN from overflow).
    let (low, high) = (e0.min(e1).min(e2), e0.max(e1).max(e2));
    let straddles = low.lt4(lanes_zero) & lanes_zero.lt4(high);
    let strict = lanes_zero.lt4(low) | high.lt4(lanes_zero);
    let covers = !straddles & 0b0101;
    if covers == 0 {
        return pack::<S<V>>(None);
    }
    // As the triangle test computes them (its lanes' `sum3` order).
    let det = e0.add(e1).add(e2);
    let t_scaled = e0.mul(z0).add(e1.mul(z1)).add(e2.mul(z2));
    let limit = splat(t_max).mul(det);
    let in_range = (lanes_zero.lt4(det) & lanes_zero.lt4(t_scaled) & t_scaled.le4(limit))
        | (det.lt4(lanes_zero) & t_scaled.lt4(lanes_zero) & limit.le4(t_scaled));
    // Every corner in front, and some corner. (A NaN depth makes `t_scaled`
    // NaN, out of range, and its corner's coordinates NaN, so that the
    // determinant's sign is not known: a NaN dropped by `min` or `max`
    // changes no answer.)
    let ahead = lanes_zero.lt4(z0.min(z1).min(z2));
    let some_ahead = lanes_zero.lt4(z0.max(z1).max(z2));
    let rough = det_sign_known_roughly_at_four_corners(c.x, c.y, pz, det);
    let asked = covers & some_ahead;
    let conditioned = if EXACT {
        rough | det_sign_known_at_four_corners(c.x, c.y, pz, det)
    } else if asked & !rough != 0 {
        return quad_far(ray, quad, t_max);
    } else {
        rough
    };
    // The triangle test's rare paths: an edge function of zero, in range
    // with a corner not in front, or a corner in front and the
    // determinant's sign not known.
    let unsure = !strict | (in_range & !ahead) | (some_ahead & !conditioned);
    if (covers == 0b0101) | (covers & unsure != 0) {
        return quad_rare(ray, quad, t_max);
    }
    let inv_det = splat(one).div(det);
    let t = t_scaled.mul(inv_det);
    // (`t > 0` makes `is_finite` the same as `t <= MAX`.)
    let in_reach = lanes_zero.lt4(t) & t.le4(splat(min2(S::<V>::MAX, t_max)));
    let hit = covers & in_range & in_reach;
    // The triangle's weights, then the quad's `(u, v)`: on the first
    // `(u1 + v1, v1)`, on the second `(u2, u2 + v2)`.
    let (u, v) = (
        e1.mul(inv_det).min(splat(one)),
        e2.mul(inv_det).min(splat(one)),
    );
    let sum = u.add(v).min(splat(one));
    let first_half = L::<V>::new4(zero, zero, one, one).lt_mask(splat(S::<V>::HALF));
    let (u, v) = (
        L::<V>::select(first_half, sum, u),
        L::<V>::select(first_half, v, sum),
    );
    // The second triangle's lanes, where it is the one.
    let second = covers & 1 == 0;
    let take = L::<V>::mask_all(second);
    let answer = |l: L<V>| L::<V>::select(take, l.roll4().roll4(), l).x();
    let back = (answer(det) > zero) == (frame.sz > zero);
    let code = 1 + u32::from(back) + 2 * u32::from(second);
    <<S<V> as Repr>::Bits as Bits>::pack(
        [answer(t), answer(u), answer(v)],
        select_unpredictable(hit != 0, code, 0),
    )
}

/// [`quad_lanes`] with the exact threshold, out of line.
#[cold]
#[inline(never)]
fn quad_far<V: Vector, R: FramedRay<V>>(ray: &R, quad: &Quad<V>, t_max: S<V>) -> Packed<S<V>> {
    quad_lanes::<V, R, true>(ray, quad, t_max)
}

/// A plain or a prepared ray, as [`quad_lanes`] reads it: whether it is
/// valid, and its frame (a plain ray's shear computed, once per call; a
/// prepared ray's borrowed).
trait FramedRay<V: Vector>: RayForm<V> {
    /// What the frame borrows from: a plain ray's shear, or nothing.
    type Parts;
    fn valid(&self) -> bool;
    fn parts(&self) -> Self::Parts;
    fn frame<'a>(&'a self, parts: &'a Self::Parts) -> RayFrame<'a, V>;
}

impl<V: Vector> FramedRay<V> for Ray<V> {
    type Parts = RayParts<V>;
    #[inline(always)]
    fn valid(&self) -> bool {
        self.is_valid()
    }
    #[inline(always)]
    fn parts(&self) -> RayParts<V> {
        RayParts::new(self)
    }
    #[inline(always)]
    fn frame<'a>(&'a self, parts: &'a RayParts<V>) -> RayFrame<'a, V> {
        RayFrame::plain(self, parts)
    }
}

/// (An invalid prepared ray's frame makes every edge function NaN, which
/// the test sends to the triangles' own tests, which miss it.)
impl<V: Vector> FramedRay<V> for PreparedRay<V> {
    type Parts = ();
    #[inline(always)]
    fn valid(&self) -> bool {
        true
    }
    #[inline(always)]
    fn parts(&self) {}
    #[inline(always)]
    fn frame<'a>(&'a self, _: &'a ()) -> RayFrame<'a, V> {
        RayFrame::prepared(self)
    }
}

/// The closed test's rare cases: the nearer of the two triangles' hits,
/// each the triangle's own `hit`. Out of line, its answer packed into
/// registers (see [`pack`]).
#[cold]
#[inline(never)]
fn quad_rare<V: Vector>(ray: &impl RayForm<V>, quad: &Quad<V>, t_max: S<V>) -> Packed<S<V>> {
    let [first, second] = quad.triangles();
    pack(nearer(first.hit(ray, t_max), second.hit(ray, t_max)))
}

/// A quad's answer packed as the triangle test's rare paths pack theirs:
/// `t`, `u`, `v` and a code, 0 for a miss, else 1 plus the side (0 front,
/// 1 back) plus 2 for the second triangle (the values of a miss are not
/// read).
#[inline(always)]
fn pack<F: Scalar>(hit: Option<QuadHit<F>>) -> Packed<F> {
    let (values, code) = match hit {
        None => ([F::ZERO; 3], 0),
        Some(h) => (
            [h.t, h.u, h.v],
            1 + u32::from(h.side == Side::Back) + 2 * u32::from(h.second),
        ),
    };
    F::Bits::pack(values, code)
}

/// The inverse of [`pack`], bit for bit.
#[inline(always)]
fn unpack<F: Scalar>(packed: Packed<F>) -> Option<QuadHit<F>> {
    let ([t, u, v], code) = F::Bits::unpack(packed);
    let side = if code & 1 != 0 {
        Side::Front
    } else {
        Side::Back
    };
    (code != 0).then_some(QuadHit {
        t,
        u,
        v,
        side,
        second: code > 2,
    })
}

/// The ray/quad test: the nearer hit of the quad's two triangles.
impl<V: Vector> Intersect<V> for Quad<V> {
    /// `t`, `u`, `v` and the side.
    type Hit = QuadHit<S<V>>;

    /// The nearest hit on the quad within `search`: each of its two
    /// triangles tested as [`Triangle`]'s [`hit`](Intersect::hit) tests
    /// it (with the search's edge rule), and the one with the smaller
    /// `t` reported (the first, `a, b, c`, where they tie). Every
    /// guarantee of the triangle test holds: watertight across every edge
    /// the quad shares with a quad or a triangle, `t > 0` decided
    /// conservatively for a `t_max` and the ends decided exactly for an
    /// [`Interval`](crate::Interval), so that consecutive intervals
    /// report a crossing once.
    ///
    /// ```
    /// use rayhit::{EdgeRule, Intersect, Interval, Quad, Ray, glam::Vec3};
    /// let floor = Quad::new(Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, -1.0), -Vec3::Z);
    /// // Straight down through the diagonal's midpoint: one hit, both rules.
    /// let ray = Ray::new(Vec3::new(0.5, 2.0, -0.5), -Vec3::Y);
    /// assert_eq!(floor.hit(&ray, f32::INFINITY).unwrap().t, 2.0);
    /// assert_eq!(floor.hit(&ray, (f32::INFINITY, EdgeRule::OneHit)).unwrap().t, 2.0);
    /// assert!(floor.hit(&ray, Interval::new(2.0, 9.0).unwrap()).is_none());
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        let search = search.into();
        match (search.edges, search.range, ray.form()) {
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Prepared(p)) => {
                unpack(quad_lanes::<V, _, false>(p, self, t_max))
            }
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Plain(r)) => {
                unpack(quad_lanes::<V, _, false>(r, self, t_max))
            }
            _ => {
                let [first, second] = self.triangles();
                nearer(first.hit(ray, search), second.hit(ray, search))
            }
        }
    }

    /// Whether either triangle is hit within `search`.
    #[inline(always)]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        let search = search.into();
        let [first, second] = self.triangles();
        first.occluded(ray, search) || second.occluded(ray, search)
    }
}

impl<V: Vector> Surface<V> for Quad<V> {
    /// Bounds on the errors of `t`, `u` and `v`.
    type HitError = TriangleHitError<S<V>>;

    /// Bounds on the errors of a hit's `t`, `u` and `v` against the exact
    /// crossing of the ray's line with the plane of the triangle hit, and
    /// the exact `(u, v)` there: the triangle's bounds
    /// ([`Triangle`]'s [`hit_error`](Surface::hit_error)), with the sum
    /// that makes `u` (on `a, b, c`) or `v` (on `a, c, d`) bounded by the
    /// two barycentrics' bounds and its rounding. Infinite where the
    /// triangle's are. For a hit of an interval form whose `t` was brought
    /// into the interval, `t` is within `max(bound, succ(t_min) - t_min)`
    /// of the crossing, as for the triangle.
    ///
    /// ```
    /// use rayhit::{Intersect, Quad, Ray, Surface, glam::Vec3};
    /// let quad = Quad::parallelogram(Vec3::new(0.0, 0.0, 3.0), Vec3::X, Vec3::Y);
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.1, 0.2, 1.0));
    /// let hit = quad.hit(&ray, f32::INFINITY).unwrap();
    /// let err = quad.hit_error(&ray, &hit);
    /// assert!((hit.t - 3.0).abs() <= err.t && err.t < 1e-5);
    /// // (0.3 and 0.6 in exact arithmetic; their f32 roundings differ by less.)
    /// assert!((hit.u - 0.3).abs() <= err.u + 1e-7 && (hit.v - 0.6).abs() <= err.v + 1e-7);
    /// ```
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> Self::HitError {
        let [first, second] = self.triangles();
        let tri = if hit.second { second } else { first };
        // The triangle's own weights were `(u - v, v)` on the first and
        // `(u, v - u)` on the second, before the sum's rounding. Its bound
        // on a weight grows with the weight, so it may be taken at any
        // value at least as large: `u` and `v` are (both weights are at
        // least zero), and its bound on `t` does not read them.
        let e = tri.hit_error(
            ray,
            &TriangleHit {
                t: hit.t,
                u: hit.u,
                v: hit.v,
                side: hit.side,
            },
        );
        // `fl(x + y)` is within `u |x + y|` of `x + y`, and the clamp to 1
        // only moves it towards an exact sum at most 1.
        let rounding = mul_up(
            S::<V>::UNIT_ROUNDOFF,
            if hit.second { hit.v } else { hit.u },
        );
        let sum = add_up(add_up(e.u, e.v), rounding);
        if hit.second {
            TriangleHitError {
                t: e.t,
                u: e.u,
                v: sum,
            }
        } else {
            TriangleHitError {
                t: e.t,
                u: sum,
                v: e.v,
            }
        }
    }

    /// The hit point on the triangle hit, from its barycentrics, with its
    /// bound and that triangle's normal and bound
    /// ([`Quad::surface_point_at`]). The ray is not read.
    ///
    /// ```
    /// use rayhit::{Intersect, Quad, Ray, Surface, glam::Vec3};
    /// let wall = Quad::parallelogram(Vec3::new(-1.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
    /// let ray = Ray::new(Vec3::new(0.3, 1.2, 3.0), Vec3::new(0.0, 0.0, -1.0));
    /// let hit = wall.hit(&ray, f32::INFINITY).unwrap();
    /// let here = wall.surface_point(&ray, &hit);
    /// // A reflection leaves the wall and never meets it again.
    /// let bounce = here.spawn(Vec3::new(0.1, 0.2, 1.0));
    /// assert!(wall.hit(&bounce, f32::INFINITY).is_none());
    /// ```
    #[inline]
    fn surface_point(&self, _ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V> {
        let [first, second] = self.triangles();
        // (`v >= u` on the second triangle and `u >= v` on the first, as
        // rounding the sum keeps it at least each term.)
        if hit.second {
            second.surface_point_at(hit.u, hit.v - hit.u)
        } else {
            first.surface_point_at(hit.u - hit.v, hit.v)
        }
    }
}
