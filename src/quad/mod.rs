//! Quads: planar quadrilaterals and parallelograms, each the two
//! triangles on either side of a diagonal, tested with the watertight
//! triangle test so that quads and triangles sharing an edge leave no
//! crack between them.

use glam::Vec3;

use crate::aabb::Aabb;
use crate::num::round::min2;
use crate::num::round::outward::{add_up, mul_up};
use crate::num::{S, Scalar, Vector};
use crate::query::sealed::Form;
use crate::query::{EdgeRule, Intersect, Range, RayForm, Search, Surface};
use crate::ray::{PreparedRay, Ray, t_max_ok};
use crate::surface::SurfacePoint;
use crate::triangle::{
    EveryAxis, Side, Triangle, TriangleHit, TriangleHitError, every_axis_at, finish_lanes,
    frame_lanes_at, straddles,
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
/// on the collapsed half. A NaN or infinite coordinate makes a quad nothing
/// hits.
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

/// The closed test over a `t_max` on a prepared ray: each triangle's
/// [`Triangle`] `hit`, bit for bit, with the corners read from the quad
/// (no triangle built on the common path) and one test for the common
/// miss, where both triangles' edge functions straddle zero.
#[inline(always)]
fn quad_lanes<V: Vector>(
    ray: &PreparedRay<V>,
    quad: &Quad<V>,
    t_max: S<V>,
) -> Option<QuadHit<S<V>>> {
    if !t_max_ok(t_max) {
        return None;
    }
    let frame = |c: [&V; 3]| frame_lanes_at(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, c);
    let (first, second) = (
        frame([&quad.a, &quad.b, &quad.c]),
        frame([&quad.a, &quad.c, &quad.d]),
    );
    // (The triangles are built on the rare paths only.)
    let finish = |frame, half: usize| finish_lanes(ray, frame, t_max, || quad.triangles()[half]);
    match (straddles(first.3), straddles(second.3)) {
        (true, true) => None,
        (false, true) => finish(first, 0).map(|h| QuadHit::from_triangle(h, false)),
        (true, false) => finish(second, 1).map(|h| QuadHit::from_triangle(h, true)),
        // Both may be hit: a ray through the diagonal, or a folded quad
        // seen edge-on.
        (false, false) => nearer(finish(first, 0), finish(second, 1)),
    }
}

/// The closed test over a `t_max` on a plain ray: each triangle's
/// [`Triangle`] `hit` (the test on every main axis at once), bit for bit,
/// with the ray's shear computed once for both and the corners read from
/// the quad.
#[inline(always)]
fn quad_every_axis<V: Vector>(ray: &Ray<V>, quad: &Quad<V>, t_max: S<V>) -> Option<QuadHit<S<V>>> {
    if !(ray.is_valid() && t_max_ok(t_max)) {
        return None;
    }
    let shear = EveryAxis::new(ray);
    let half = |c: [&V; 3], k: usize| every_axis_at(ray, &shear, c, t_max, || quad.triangles()[k]);
    nearer(
        half([&quad.a, &quad.b, &quad.c], 0),
        half([&quad.a, &quad.c, &quad.d], 1),
    )
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
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Prepared(p)) => quad_lanes(p, self, t_max),
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Plain(r)) => {
                quad_every_axis(r, self, t_max)
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
