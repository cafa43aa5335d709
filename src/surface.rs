//! Leaving a surface: a hit point with its error bounds ([`SurfacePoint`]),
//! the offset origin of a ray that cannot hit that surface again
//! ([`SurfacePoint::spawn`]), and the segment between two surface points,
//! or from one to a point light, that hits neither end
//! ([`SurfacePoint::spawn_to`], [`SurfacePoint::spawn_to_point`]). Shapes
//! give their points through [`Surface`](crate::Surface), so this sits
//! below them and reads no shape.

use glam::Vec3;

use crate::num::{S, Scalar, Vector};
use crate::ray::{Interval, Ray};

/// Moves a point computed on a surface to where a ray leaving it along `dir`
/// cannot meet that surface again: the origin for a shadow or bounce ray.
///
/// Inputs: the computed `point` and a per-component bound `point_error`
/// such that some point `q` of the exact surface has
/// `|point_i - q_i| <= point_error_i`; the surface's `normal` (any length)
/// and a per-component bound `normal_error` on its difference from the
/// exact plane's normal `N` (zero when the normal is exact, as for a
/// [`Plane`](crate::Plane)); and the new ray's `dir`. A shape's
/// [`surface_point`](crate::Surface::surface_point) gives these.
///
/// Returns `point + s * lambda * normal`, each component rounded away from
/// `point`, with `s` the sign of `dir . normal`. Guarantee: the returned
/// origin lies strictly on the side of the exact plane (through `q`, normal
/// `N`) that `dir` points into, so the new ray's exact crossing with that
/// plane is behind it (`t < 0`), and the watertight test, which decides
/// `t > 0` conservatively, does not report it.
///
/// Derivation: `|(point - q) . N| <= A = sum point_error_i (|n_i| + eta_i)`.
/// Moving by `lambda * n` changes `(x - q) . N` by `lambda n . N >=
/// lambda (|n|^2 - sum |n_i| eta_i)`; rounding each moved component away
/// from `point` adds, in the components whose sign agrees with `N_i`, only
/// more, and in the others (where `|n_i| <= eta_i`) takes back at most two
/// ulps of `|point_i| + lambda |n_i|`, below `4u` of it. So
/// `lambda = (A + 4u sum |point_i| eta_i) / (|n|^2 - (1 + 4u) sum |n_i| eta_i)`
/// suffices; it is evaluated with outward rounding, and pbrt-v4's
/// `OffsetRayOrigin` (the same idea with an exact normal) is the special case
/// `eta = 0`.
///
/// Preconditions: `dir` is not within rounding of parallel to the surface,
/// so that `s`, the sign of the *computed* `dir . normal`, is the side exact
/// arithmetic would pick: `|fl(dir . normal)|` must exceed the dot
/// product's own rounding bound `gamma(3) sum |dir_i normal_i|` plus the
/// normal's error `sum |dir_i| eta_i` (a few ulps of the angle for an exact
/// normal). And the normal must be known well enough that the denominator
/// above is positive; otherwise, and for non-finite input, the point is
/// returned unchanged. Never panics.
#[must_use]
pub(crate) fn offset_ray_origin<V: Vector>(
    point: V,
    point_error: V,
    normal: V,
    normal_error: V,
    dir: V,
) -> V {
    if !dir.is_finite() {
        return point;
    }
    offset_to_side(point, point_error, normal, normal_error, side(dir, normal)).unwrap_or(point)
}

/// The side [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) moves to for `dir`: the sign of the
/// computed `dir . normal`, `+1` where it is zero.
#[inline(always)]
fn side<V: Vector>(dir: V, normal: V) -> S<V> {
    if dir.dot(normal) < S::<V>::ZERO {
        -S::<V>::ONE
    } else {
        S::<V>::ONE
    }
}

/// [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) to a given side (`+1` or `-1` times `normal`), or
/// `None` where it returns the point unmoved (non-finite input, a normal
/// not known well enough).
fn offset_to_side<V: Vector>(
    point: V,
    point_error: V,
    normal: V,
    normal_error: V,
    side: S<V>,
) -> Option<V> {
    use crate::num::round::outward::{add_down, add_up, div_up, mul_down, mul_up, sub_down};
    let all_finite = point.is_finite()
        && point_error.is_finite()
        && normal.is_finite()
        && normal_error.is_finite();
    if !all_finite {
        return None;
    }
    let zero = S::<V>::ZERO;
    let (n, eta) = (normal.abs(), normal_error.abs());
    let four_u = S::<V>::from_u32(4) * S::<V>::UNIT_ROUNDOFF;
    let mut a = zero; // sum point_error_i (|n_i| + eta_i)
    let mut slack = zero; // 4u sum |point_i| eta_i
    let mut n2 = zero; // |n|^2, rounded down
    let mut cross = zero; // sum |n_i| eta_i, rounded up
    for i in 0..3 {
        a = add_up(a, mul_up(point_error[i].abs(), add_up(n[i], eta[i])));
        slack = add_up(slack, mul_up(four_u, mul_up(point[i].abs(), eta[i])));
        n2 = add_down(n2, mul_down(n[i], n[i]));
        cross = add_up(cross, mul_up(n[i], eta[i]));
    }
    let denom = sub_down(n2, mul_up(add_up(S::<V>::ONE, four_u), cross));
    if !(denom > zero) {
        return None;
    }
    let lambda = div_up(add_up(a, slack), denom);
    let step = lambda * side;
    let moved = |i: usize| {
        let off = step * normal[i];
        let p = point[i] + off;
        // Round away from the point so the move is at least `off`.
        if off > zero {
            p.next_up()
        } else if off < zero {
            p.next_down()
        } else {
            point[i]
        }
    };
    Some(V::new(moved(0), moved(1), moved(2)))
}

/// A point on a surface with the error bounds needed to leave it safely,
/// gathered so that they cannot be passed in the wrong order.
///
/// Get it from a hit with the shape's
/// [`surface_point`](crate::Surface::surface_point) (a box's is
/// [`Aabb::surface_point`](crate::Aabb::surface_point)), or fill in the
/// fields for a surface of your own; then [`spawn`](SurfacePoint::spawn)
/// bounce rays from it and [`spawn_to`](SurfacePoint::spawn_to) shadow
/// segments.
///
/// ```
/// use rayhit::{Intersect, Ray, Surface, Triangle, glam::Vec3};
/// let tri = Triangle::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, -1.0));
/// let ray = Ray::new(Vec3::new(0.1, 2.0, 0.0), Vec3::new(0.0, -1.0, -0.1));
/// let hit = tri.hit(&ray, f32::INFINITY).unwrap();
/// let surface = tri.surface_point(&ray, &hit);
/// // A shadow ray towards a light above: it cannot hit the triangle it left.
/// let shadow = surface.spawn(Vec3::new(0.3, 1.0, 0.2));
/// assert!(tri.hit(&shadow, f32::INFINITY).is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint<V = Vec3> {
    /// The computed point.
    pub point: V,
    /// Per component, a bound on its distance from a point of the exact
    /// surface.
    pub point_error: V,
    /// The surface's normal, any length.
    pub normal: V,
    /// Per component, a bound on the normal's difference from the exact
    /// surface's normal (zero when it is exact).
    pub normal_error: V,
}

impl<V: Vector> SurfacePoint<V> {
    /// A ray leaving the surface along `dir`, from an origin moved off the
    /// surface to the side `dir` points into: it does not meet the surface
    /// again (for `dir` not within rounding of tangent).
    ///
    /// The origin is `point + s * lambda * normal`, each component rounded
    /// away from `point`, with `s` the sign of `dir . normal`, and it lies
    /// strictly on the side of the exact plane (through a point `q` of the
    /// exact surface within `point_error` of `point`, normal `N` within
    /// `normal_error` of `normal`) that `dir` points into. So the new ray's
    /// exact crossing with that plane is behind it (`t < 0`), and no query
    /// reports it: the watertight triangle test decides `t > 0`
    /// conservatively, and the interval forms decide it exactly.
    ///
    /// Derivation: `|(point - q) . N| <= A = sum point_error_i (|n_i| +
    /// eta_i)` (`eta` the normal's error). Moving by `lambda * n` changes
    /// `(x - q) . N` by `lambda n . N >= lambda (|n|^2 - sum |n_i| eta_i)`;
    /// rounding each moved component away from `point` adds, in the
    /// components whose sign agrees with `N_i`, only more, and in the
    /// others (where `|n_i| <= eta_i`) takes back at most two ulps of
    /// `|point_i| + lambda |n_i|`, below `4u` of it. So `lambda = (A + 4u
    /// sum |point_i| eta_i) / (|n|^2 - (1 + 4u) sum |n_i| eta_i)` suffices;
    /// it is evaluated with outward rounding. pbrt-v4's `OffsetRayOrigin`
    /// (the same idea with an exact normal) is the special case `eta = 0`.
    ///
    /// Precondition: `dir` is not within rounding of tangent, so that `s`,
    /// the sign of the *computed* `dir . normal`, is the side exact
    /// arithmetic would pick: `|fl(dir . normal)|` must exceed the dot
    /// product's own rounding bound `gamma(3) sum |dir_i normal_i|` plus the
    /// normal's error `sum |dir_i| eta_i` (a few ulps of the angle for an
    /// exact normal).
    ///
    /// Where the normal is not known well enough to pick a side (the
    /// denominator above not positive: a zero or nearly zero normal, as on
    /// a zero-area triangle), and for non-finite input, the ray starts at
    /// `point` itself, unmoved: finite, but it may meet the surfaces through
    /// that point again at a tiny `t`. Never panics.
    ///
    /// ```
    /// use rayhit::{Intersect, Plane, Ray, Surface, glam::Vec3};
    /// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
    /// let ray = Ray::new(Vec3::new(0.1, 3.0, 0.2), Vec3::new(0.3, -1.0, 0.7));
    /// let t = floor.hit(&ray, f32::INFINITY).unwrap();
    /// // Bounce up and away: the new origin is strictly above the floor.
    /// let bounce = floor.surface_point(&ray, &t).spawn(Vec3::new(0.3, 1.0, 0.7));
    /// assert!(bounce.origin.y > 0.0);
    /// assert_eq!(floor.hit(&bounce, f32::INFINITY), None);
    /// ```
    #[inline]
    #[must_use]
    pub fn spawn(&self, dir: V) -> Ray<V> {
        let origin = offset_ray_origin(
            self.point,
            self.point_error,
            self.normal,
            self.normal_error,
            dir,
        );
        Ray::new(origin, dir)
    }

    /// The shadow-ray segment from this surface point to `target`, a point
    /// on another surface (an area light's sample, or a vertex of another
    /// path): a ray and the interval `(0, 1]` that hits neither end's
    /// surface and finds every occluder in between that is farther than the
    /// ends' error bounds from them, with no epsilon. Trace it with the
    /// interval forms ([`occluded`](crate::Intersect::occluded),
    /// [`Plane`'s `hit` over an interval](crate::Plane#method.hit),
    /// [`Aabb`'s `hit` over an interval](crate::Aabb#method.hit)).
    ///
    /// pbrt-v4's `SpawnRayTo` offsets both ends with `OffsetRayOrigin` and
    /// still stops at `1 - ShadowEpsilon`; here the end's offset also covers
    /// the rounding of the direction, and both ends are proved clear.
    ///
    /// The ray is `origin + t dir` with `origin` this point moved off its
    /// surface towards the target ([`SurfacePoint::spawn`](crate::SurfacePoint::spawn), the side of
    /// `(target.point - self.point) . self.normal`), and `dir = end -
    /// origin` rounded, where `end` is the target moved off its surface
    /// towards the origin by its error bound plus a bound on that rounding.
    /// The segment's exact end is `origin + 1 dir`, a few ulps from `end`.
    ///
    /// # Guarantees (when `Some`)
    ///
    /// Write `P` and `Q` for the exact planes of the two surfaces (through
    /// the exact points `self.point` and `target.point` stand for, normals
    /// within `normal_error` of `normal`), as [`spawn`](Self::spawn) does.
    ///
    /// 1. **Neither end is hit.** The exact ray's crossing with `P` is at
    ///    `t < 0` (it moves away from `P` from a start strictly on one
    ///    side), and its crossing with `Q` at `t > 1` (it moves towards `Q`
    ///    and its exact end is still strictly on the origin's side). The
    ///    interval forms decide `0 < t* <= 1` exactly, so they report
    ///    neither surface. With the plain triangle and plane kernels
    ///    (`ray_triangle(&ray, tri, 1.0)`) the start surface is not
    ///    reported either, for any `t_max` (as for [`spawn`](Self::spawn)),
    ///    but the target surface can be: they compare a rounded `t` with
    ///    `t_max`, and `t*` may be above `1` by less than the kernel's
    ///    error bound. With plain kernels, skip the target's own
    ///    primitive.
    /// 2. **Occluders are found.** Let `B_o = |origin - self.point|` and
    ///    `B_e = |origin + dir - target.point|` (exact, Euclidean): the
    ///    moves of the two ends. Each point `origin + t dir` of the
    ///    segment is within `(1 - t) B_o + t B_e` of `p + t (q - p)` on the
    ///    segment between the points as given. So a plane with `p` and
    ///    `q` strictly on opposite sides, `p` farther than `B_o` from it
    ///    and `q` farther than `B_e`, is crossed at an exact `0 < t* < 1`
    ///    and reported. A triangle in such a plane is reported where
    ///    `[p, q]` crosses it farther than `B (1 + |q - p| / (h_p + h_q -
    ///    B_o - B_e))` from its edges, with `B = max(B_o, B_e)` and `h_p`,
    ///    `h_q` the ends' distances from the plane (the crossing moves by at
    ///    most that). Against the exact surface points, add their error
    ///    bounds to `B_o` and `B_e`.
    ///
    /// The moves are about the error bounds: `B_o` is the offset of
    /// [`SurfacePoint::spawn`](crate::SurfacePoint::spawn), `lambda |normal|` plus two ulps per
    /// component (for an exact normal, `lambda |normal| <= |point_error|`;
    /// a computed normal adds its relative error), and `B_e` the same for
    /// the target with its error widened by `r` below, plus the rounding
    /// of `dir`, at most `u |end - origin|` per component: in all a few
    /// ulps of the points' coordinates and of the segment's length.
    ///
    /// # Derivation
    ///
    /// The end: let `e` be the target's error bound, `n` and `eta` its
    /// normal and the normal's error, `N` the exact normal of `Q`, `q*`
    /// its exact point, `o` the origin, and `d = fl(end - o)`. Then `o +
    /// d = end + delta` with `|delta_i| <= u |end_i - o_i|` (one rounded
    /// subtraction), and `|end_i - o_i| <= |q_i - o_i| + |end_i - q_i|`.
    /// The move `end - q` depends on `delta`'s bound, so the bound is
    /// fixed beforehand, with slack: with `m_i` the computed `|q_i - o_i|`
    /// stepped up one ulp (at least the exact value) and `L = max_i m_i`,
    /// take `r_i = u (m_i + L)`, rounded up. Offset `q` by
    /// [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) with the point error `e + r`; afterwards
    /// check that no component moved by more than `L` (stepped up one
    /// ulp). So `|end_i - o_i| <= m_i + L` and `|delta_i| <= r_i`.
    /// `offset_ray_origin`'s derivation moves the point across `Q` by more
    /// than `sum (e + r)_i (|n_i| + eta_i) >= sum (e_i + r_i) |N_i|`, and
    /// `q` started at most `sum e_i |N_i|` from it, so `s (end - q*) . N >
    /// sum r_i |N_i| >= |delta . N|`, with `s` the origin's side of `Q`:
    /// the exact end `o + d` is strictly on side `s` (as
    /// [`Instance::spawn_through`](crate::Instance::spawn_through) widens
    /// the error for the round trip).
    ///
    /// The direction: `d . N` differs from the computed `fl(d . n)` by at
    /// most `gamma(3) sum |d_i n_i| + sum |d_i| eta_i` (plus four
    /// subnormals for underflow), evaluated rounding up. Where `fl(d .
    /// n)` exceeds that bound with the sign pointing into side `s` of the
    /// start plane (the origin's side), the ray moves away from `P` and
    /// stays on side `s` for all `t >= 0`; where `-fl(d . n_q)` exceeds it
    /// with the sign of `s_q`, the ray approaches `Q` from side `s_q` and
    /// is on that side for every `t <= 1`. Both are checked, and decide
    /// the answer: `Some` is proved, not hoped for.
    ///
    /// # `None`
    ///
    /// - Any input not finite; an overflow.
    /// - Either normal not known well enough to pick a side (a zero or
    ///   nearly zero normal: a zero-area triangle, a sliver), where
    ///   [`spawn`](Self::spawn) would start unmoved. A zero-area triangle
    ///   has no plane to leave; use [`spawn`](Self::spawn) towards the
    ///   target and a `t_max` of your own if you must.
    /// - The segment within rounding of tangent to either surface, in the
    ///   values the points carry: with `d` the returned ray's direction
    ///   (the far end minus the moved origin) and `n`, `eta` an end's
    ///   normal and `normal_error`, `|fl(d . n)|` at most `gamma(3) sum
    ///   |d_i n_i| + sum |d_i| eta_i` (plus four subnormals): the side the
    ///   segment leaves or reaches that surface from is not known. This
    ///   includes coincident ends, ends on one plane, and ends closer than
    ///   their error bounds (the offsets would cross). For an exact unit
    ///   normal, the angle between the segment and the surface below about
    ///   `3u` radians plus `|eta|`.
    /// - The target's move longer than the segment's largest component
    ///   (the check above; the ends are then within about their error
    ///   bounds of each other).
    ///
    /// In each case the connection carries no light a renderer could
    /// resolve (a cosine at one end is zero within rounding, or the ends
    /// cannot be told apart): count it as blocked. Never panics.
    ///
    /// Instances: a world point from
    /// [`Instance::surface_to_world`](crate::Instance::surface_to_world) is
    /// a surface point like any other, and the guarantees hold against
    /// world-space geometry; a segment traced back into an end's instance
    /// through its stored inverse needs the extra margin of
    /// [`Instance::spawn_to_through`](crate::Instance::spawn_to_through).
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Plane, Ray, Surface, SurfacePoint, Triangle};
    /// use rayhit::{glam::Vec3, ray_plane, ray_triangle};
    /// // A point on the floor, and a point on a ceiling light facing down.
    /// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
    /// let down = Ray::new(Vec3::new(0.3, 5.0, 0.1), Vec3::new(0.1, -1.0, 0.2));
    /// let on_floor = floor.surface_point(&down, &ray_plane(&down, &floor, f32::INFINITY).unwrap());
    /// let light = Triangle::new(Vec3::new(-1.0, 3.0, -1.0), Vec3::new(0.0, 3.0, 2.0), Vec3::new(2.0, 3.0, -1.0));
    /// let up = Ray::new(Vec3::new(0.2, 0.0, 0.3), Vec3::new(0.0, 1.0, 0.05));
    /// let on_light = light.surface_point(&up, &ray_triangle(&up, &light, f32::INFINITY).unwrap());
    ///
    /// let (shadow, segment) = on_floor.spawn_to(&on_light).unwrap();
    /// assert_eq!(segment, Interval::up_to(1.0).unwrap());
    /// // Neither end's surface is hit...
    /// assert!(!light.occluded(&shadow, segment));
    /// assert_eq!(floor.hit(&shadow, segment), None);
    /// // ...and a shelf half way up is.
    /// let shelf = Triangle::new(Vec3::new(-5.0, 1.5, -5.0), Vec3::new(0.0, 1.5, 5.0), Vec3::new(5.0, 1.5, -5.0));
    /// assert!(shelf.occluded(&shadow, segment));
    /// // Coincident ends give no segment.
    /// assert!(on_floor.spawn_to(&on_floor).is_none());
    /// ```
    #[must_use]
    pub fn spawn_to(&self, target: &SurfacePoint<V>) -> Option<(Ray<V>, Interval<S<V>>)> {
        segment(self, target.point, Some(target), [None, None])
    }

    /// The shadow-ray segment from this surface point to a point light at
    /// `light` (an exact point, on no surface): a ray and the interval
    /// `(0, 1]` that does not hit this point's surface and finds every
    /// occluder in between farther than the ends' moves from them.
    ///
    /// As [`spawn_to`](Self::spawn_to), with the end the light itself (it
    /// is not moved: there is no surface to leave), so `B_e = |origin +
    /// dir - light|` is the rounding of `dir`, at most `u |light_i -
    /// origin_i|` in component `i`; guarantee 1 is for the start surface, whose crossing is
    /// at `t < 0` (so no kernel reports it, for any `t_max`). `None` for
    /// non-finite input, a normal not known well enough, and a light
    /// within rounding of the surface's plane (its angle with the surface
    /// below a few ulps plus the normal's relative error, or its distance
    /// from the plane below about the point's error bound), coincident
    /// points included: count it as blocked. Never panics.
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Plane, Ray, Surface, SurfacePoint, glam::DVec3, ray_plane};
    /// let wall = Plane::new(DVec3::new(0.0, 0.0, 4.0), DVec3::Z);
    /// let eye = Ray::new(DVec3::new(0.1, 0.2, 0.0), DVec3::new(0.3, -0.2, 1.0));
    /// let here = wall.surface_point(&eye, &ray_plane(&eye, &wall, f64::INFINITY).unwrap());
    /// let (shadow, segment) = here.spawn_to_point(DVec3::new(2.0, 1.0, 0.5)).unwrap();
    /// assert_eq!(wall.hit(&shadow, segment), None);
    /// // A pane of glass at z = 2 is between the wall and the light.
    /// let pane = Plane::new(DVec3::new(0.0, 0.0, 2.0), DVec3::Z);
    /// assert!(pane.hit(&shadow, segment).is_some());
    /// // A light in the wall's plane: no segment.
    /// assert!(here.spawn_to_point(DVec3::new(5.0, 5.0, 4.0)).is_none());
    /// ```
    #[must_use]
    pub fn spawn_to_point(&self, light: V) -> Option<(Ray<V>, Interval<S<V>>)> {
        segment(self, light, None, [None, None])
    }
}

/// A bound on how far the object ray of a world ray, mapped through a
/// path of instances, is from the world ray: per component, at `t = 0`
/// and per unit of `t` (the path's
/// [`InstanceRayError`](crate::instance::InstanceRayError)).
pub(crate) type RayMapBound<'a, V> = &'a dyn Fn(&Ray<V>) -> (V, V);

/// A point offset off a surface with its error widened by `extra`, for a
/// round trip through instances whose error grows with the point: `place`
/// offsets with a given `extra` (`None` where it cannot), `need` is the
/// extra the placed point needs. Starting from twice `first`, the point is
/// kept when what it needs is strictly below the extra it was placed with,
/// else the extra becomes twice the need, four times at most; `None`
/// when it does not settle (the round trip's error grows with the offset
/// as fast as the offset does) or `place` fails.
pub(crate) fn settle<V: Vector>(
    first: V,
    place: impl Fn(V) -> Option<V>,
    need: impl Fn(V) -> V,
) -> Option<V> {
    let mut extra = first * S::<V>::TWO;
    for _ in 0..4 {
        if !extra.is_finite() {
            return None;
        }
        let point = place(extra)?;
        let needed = need(point);
        if (0..3).all(|i| needed[i] < extra[i]) {
            return Some(point);
        }
        extra = needed * S::<V>::TWO;
    }
    None
}

/// The segment of [`SurfacePoint::spawn_to`] (`target` given) and
/// [`SurfacePoint::spawn_to_point`] (`to` exact); the derivation is at
/// `spawn_to`. `maps` are the start's and the target's instance paths'
/// bounds, for a segment traced back into them
/// ([`Instance::spawn_to_through`](crate::Instance::spawn_to_through)):
/// the ends are offset further by what the round trip moves the object
/// ray at `t = 0` (start) and `t = 1` (end), and the direction's mapped
/// rounding joins the side tests. Without maps nothing is widened, and
/// the segment is the world one, bit for bit.
pub(crate) fn segment<V: Vector>(
    from: &SurfacePoint<V>,
    to: V,
    target: Option<&SurfacePoint<V>>,
    maps: [Option<RayMapBound<'_, V>>; 2],
) -> Option<(Ray<V>, Interval<S<V>>)> {
    use crate::num::round::max2;
    use crate::num::round::outward::{add_up, mul_up};
    if !to.is_finite() {
        return None;
    }
    let widen = |e: V, extra: V| {
        V::new(
            add_up(e[0], extra[0]),
            add_up(e[1], extra[1]),
            add_up(e[2], extra[2]),
        )
    };
    // The origin, off the start plane on the target's side.
    let s_p = side(to - from.point, from.normal);
    let place_origin =
        |error: V| offset_to_side(from.point, error, from.normal, from.normal_error, s_p);
    let origin = match maps[0] {
        None => place_origin(from.point_error)?,
        Some(map) => settle(
            map(&Ray::new(from.point, to - from.point)).0,
            |extra| place_origin(widen(from.point_error.abs(), extra)),
            |o| map(&Ray::new(o, to - o)).0,
        )?,
    };
    if !origin.is_finite() {
        return None;
    }
    let (end, s_q) = match target {
        None => (to, S::<V>::ZERO),
        Some(t) => {
            // `m_i >= |q_i - o_i|`, `L` their largest, `r_i = u (m_i + L)`
            // rounded up: the rounding of `dir` where no component of the
            // end moves by more than `L`.
            let u = S::<V>::UNIT_ROUNDOFF;
            let m = V::new(
                (to.x() - origin.x()).abs().next_up(),
                (to.y() - origin.y()).abs().next_up(),
                (to.z() - origin.z()).abs().next_up(),
            );
            let big = max2(max2(m.x(), m.y()), m.z());
            let widened = |i: usize| add_up(t.point_error[i].abs(), mul_up(u, add_up(m[i], big)));
            let error = V::new(widened(0), widened(1), widened(2));
            let s_q = side(origin - to, t.normal);
            let place_end = |error: V| offset_to_side(to, error, t.normal, t.normal_error, s_q);
            let end = match maps[1] {
                None => place_end(error)?,
                // The object ray at `t = 1`: `at_origin + per_t`.
                Some(map) => {
                    let at_end = |e: V| {
                        let (a, p) = map(&Ray::new(origin, e - origin));
                        widen(a, p)
                    };
                    settle(at_end(to), |extra| place_end(widen(error, extra)), at_end)?
                }
            };
            // The premise of `r`: `|end_i - q_i| <= L`.
            let within = |i: usize| (end[i] - to[i]).abs().next_up() <= big;
            if !(within(0) && within(1) && within(2)) {
                return None;
            }
            (end, s_q)
        }
    };
    let dir = end - origin;
    let ray = Ray::new(origin, dir);
    if !ray.is_valid() {
        return None;
    }
    // The mapped direction's rounding, per unit of `t`.
    let per_t = |map: Option<RayMapBound<'_, V>>| map.map(|m| m(&ray).1);
    // Away from the start plane, into the origin's side `s_p`.
    if !moves_to_side(dir, from.normal, from.normal_error, s_p, per_t(maps[0])) {
        return None;
    }
    // Towards the target plane, from the origin's side `s_q`.
    if let Some(t) = target
        && !moves_to_side(dir, t.normal, t.normal_error, -s_q, per_t(maps[1]))
    {
        return None;
    }
    Some((ray, Interval::up_to(S::<V>::ONE)?))
}

/// Whether `s (D . N) > 0` for every normal `N` within `normal_error` of
/// `normal` (`s` is `+1` or `-1`) and `D = dir`, or, given `dir_error`,
/// every direction `D` within it of `dir`: the computed `dir . normal`,
/// times `s`, above its rounding bound `gamma(3) sum |dir_i normal_i|`
/// plus the normal's error `sum |dir_i| eta_i`, plus the direction's,
/// `sum dir_error_i (|normal_i| + eta_i)` (`|(D - dir) . N|` is at most
/// that, as `|N_i| <= |normal_i| + eta_i`), added rounding up.
///
/// Five roundings on any path of the bound (the path through `gamma(3)`,
/// itself rounded once, has three), so `bound_up(.., 5)`. Underflow: each
/// of the dot product's three products loses at most half a subnormal,
/// and the bound's own products as much; `4 TINY` covers them (where the
/// bound is at least `4 TINY / u`, `bound_up`'s slack does already, and
/// below that the addition is exact).
#[inline(always)]
fn moves_to_side<V: Vector>(
    dir: V,
    normal: V,
    normal_error: V,
    s: S<V>,
    dir_error: Option<V>,
) -> bool {
    use crate::num::round::bound_up;
    use crate::num::round::outward::{add_up, mul_up};
    let (d, n, eta) = (dir.abs(), normal.abs(), normal_error.abs());
    let dot = dir.x() * normal.x() + dir.y() * normal.y() + dir.z() * normal.z();
    let on_n = d.x() * n.x() + d.y() * n.y() + d.z() * n.z();
    let on_eta = d.x() * eta.x() + d.y() * eta.y() + d.z() * eta.z();
    let bound =
        bound_up(S::<V>::gamma_n(3) * on_n + on_eta, 5) + S::<V>::TINY * S::<V>::from_u32(4);
    let Some(dir_error) = dir_error else {
        return s * dot > bound;
    };
    let moved = (0..3).fold(bound, |acc, i| {
        add_up(acc, mul_up(dir_error[i].abs(), add_up(n[i], eta[i])))
    });
    s * dot > moved
}
