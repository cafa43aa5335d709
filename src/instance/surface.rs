//! An object hit in the world, and the rays that leave it.
//!
//! # The world point and normal
//!
//! An object [`SurfacePoint`] has a point `p` within `e` of a point `q` of
//! the exact object surface, and a normal `n` within `eta` of a normal
//! `N` of the exact object plane. Its world form:
//!
//! - point `p_w = fl(M p + T)`, a dot product of length four per
//!   component, so `|p_w - F(q)| <= |M| e + g(4) (|M||p| + |T|) + U`
//!   (`U` covers roundings into the subnormal range, see `inverse.rs`),
//!   and `F(q)` is on the exact world surface;
//! - normal `n_w = fl(A^T n)`. The exact world plane `F(plane)` has the
//!   normal `w = M^-T N` (for `x` on it, `(x - F(q)) . w = (M^-1 (x - F(q)))
//!   . N = 0`). From `M A = I + R`, `A^T = M^-T + R^T M^-T`, so
//!   `A^T N = w + R^T w`, and
//!
//!   ```text
//!   |n_w - w| <= |fl(A^T n) - A^T n| + |A^T (n - N)| + |R^T w|
//!             <= g(3) |A^T||n| + |A^T| eta + colsum(Rb) ||w||_inf
//!   ||w||_inf <= ||A^T N||_inf / (1 - rho)
//!             <= max_i (|n_w| + g(3) |A^T||n| + |A^T| eta)_i / (1 - rho)
//!   ```
//!
//!   (`w = A^T N - R^T w`, and `rho = ||R^T||_inf <= 1/2` is checked when
//!   the instance is built). `normal_residual = colsum(Rb) / (1 - rho)`.
//!
//! Both bounds are evaluated factored, with the same exact values:
//! `|M| (e + g(4)|p|) + c_p` (`c_p = g(4)|T| + U` stored with the
//! instance) and `s = |A^T| (g(3)|n| + eta)`, one matrix product each; the
//! rounding counts are at the code.
//!
//! So the world [`SurfacePoint`] bounds hold against the exact world
//! surface, with its normal `w`; a world point of a nested instance is the
//! outer instance's map of the inner one's, and the bounds hold again, now
//! against `M_1^-T M_2^-T N`.
//!
//! # Leaving the surface through the instance
//!
//! A renderer traces the spawned world ray `(o, d)` and, on reaching the
//! instance again, maps it with the stored inverse: `o' = fl(A o + b)`,
//! `d' = fl(A d)`, and tests the object triangle with that ray. It must not
//! report the triangle the ray left. `o'` is not `F^-1(o)`:
//! `F(o') = o + delta` with `|delta| <= K_o |o| + c_o` (`ray.rs` at `t = 0`).
//! The proof:
//!
//! 1. `offset_ray_origin` with the point error `e_w + D` (the world point's
//!    own error plus an extra `D`) moves `p_w` across the plane by more than
//!    `sum (e_w + D)_i (|n_w,i| + eta_w,i)`, measured as `(x - F(q)) . w`;
//!    the point started at most `sum e_w,i |w_i|` from it, so the origin
//!    `o` has `s (o - F(q)) . w >= sum D_i |w_i|`, with `s` the side `d`
//!    points into (the derivation at [`SurfacePoint::spawn`](crate::SurfacePoint::spawn)).
//! 2. If `D > K_o |o| + c_o >= |delta|` per component, then
//!    `s (F(o') - F(q)) . w > s (o - F(q)) . w - sum D_i |w_i| >= 0`:
//!    `F(o')` is strictly on side `s` of the world plane.
//! 3. Affine maps keep sides: `(F(x) - F(q)) . w = (x - q) . N`. So `o'` is
//!    strictly on side `s` of the exact object plane.
//! 4. The direction: `M d' = d + R d + M e_d`, and `d' . N = (M d') . w`,
//!    so `d' . N` has the sign `s` of `d . w` whenever `|d . w|` exceeds
//!    `sum (K_d |d| + c_d)_i |w_i|`, the precondition (a few ulps of the
//!    angle times the condition number). Then the object ray moves away
//!    from the plane: its exact crossing is at `t < 0`, and the watertight
//!    test, which decides `t > 0` conservatively, does not report it.
//!
//! `D` depends on `o`, which depends on `D`; [`Instance::spawn_through`]
//! does not guess: it offsets with `D = 2 (K_o |p_w| + c_o)`, evaluates
//! `K_o |o| + c_o` at the origin it got, and keeps the origin only when
//! that is strictly below `D` (it almost always is: the offset is tiny
//! against `|p_w|`); otherwise it doubles `D` from the new value and tries
//! again, a few times, then gives up as `offset_ray_origin` does where the
//! normal is not known: the ray starts at `p_w`, unmoved. Giving up happens
//! when the round trip's error grows with the origin faster than the
//! offset does (the world-space `K` of the whole path near or above one:
//! the product of the path's condition numbers near `1 / u`); a bigger
//! `D` cannot help there.
//!
//! For nested instances the check is the same with the chained `delta`:
//! mapping `o` through levels `1..k` (outermost first) gives
//! `F_1(...F_k(o_k)) = o + delta_1 + M_1 delta_2 + M_1 M_2 delta_3 ...`,
//! each `delta_j` bounded at the origin that level actually receives, so
//! `D` must exceed `K_1 o + c_1 + |M_1| (K_2 |o_1| + c_2 + |M_2| (...))`,
//! evaluated innermost first.
//!
//! [`SurfacePoint`]: crate::SurfacePoint
//! [`offset_ray_origin`]: crate::surface::offset_ray_origin

use super::{Instance, apply, bound_up_l, load3};
use crate::num::round::{bound_up, max2};
use crate::num::{L, Lanes, S, Scalar, Vector};
use crate::num::{lanes, vector};
use crate::ray::Interval;
use crate::surface::offset_ray_origin;
use crate::surface::{RayMapBound, segment, settle};
use crate::{Ray, SurfacePoint};

impl<V: Vector> Instance<V> {
    /// An object-space surface point in world space: the point `M p + T`
    /// and the normal `A^T n` (the inverse transpose, with the stored
    /// inverse), with error bounds against the exact world surface, the
    /// exact image of the exact object surface (derivation in the source;
    /// the inverse's own error is part of the normal's bound).
    ///
    /// The result is a world surface point like any other: spawning from it
    /// with [`SurfacePoint::spawn`] is safe against world-space geometry.
    /// A ray that will re-enter *this* instance (it is traced through the
    /// stored inverse) needs the extra margin of [`Instance::spawn`].
    /// Apply it level by level for nested instances, innermost first.
    /// Non-finite input gives non-finite output (never a panic).
    ///
    /// ```
    /// use rayhit::{Instance, Ray, Surface, SurfacePoint, Triangle, glam::{Affine3A, Quat, Vec3}, ray_triangle};
    /// let place = Affine3A::from_rotation_translation(Quat::from_rotation_x(1.0), Vec3::new(0.0, 3e4, 0.0));
    /// let inst = Instance::from_affine3a(place).unwrap();
    /// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    /// let object_ray = Ray::new(Vec3::new(0.2, 0.3, 1.0), -Vec3::Z);
    /// let hit = ray_triangle(&object_ray, &tri, f32::INFINITY).unwrap();
    /// let world = inst.surface_to_world(&tri.surface_point(&object_ray, &hit));
    /// let exact_ish = place.transform_point3(Vec3::new(0.2, 0.3, 0.0));
    /// assert!((world.point - exact_ish).abs().max_element() < 1e-2);
    /// assert!(world.point_error.max_element() < 1e-2);
    /// ```
    #[inline]
    #[must_use]
    pub fn surface_to_world(&self, object: &SurfacePoint<V>) -> SurfacePoint<V> {
        let (p, n) = (lanes(object.point), lanes(object.normal));
        let (e, eta) = (
            lanes(object.point_error).abs(),
            lanes(object.normal_error).abs(),
        );
        let splat = L::<V>::splat;
        let (g3, g4) = (splat(S::<V>::gamma_n(3)), splat(S::<V>::gamma_n(4)));
        // Every line below is per component, on whole registers; the
        // rounding counts are the longest paths from an input (the object
        // point's floats and the instance's stored ones, taken as exact) to
        // the bound, each product and sum one rounding.
        // Point: M p + T.
        let point = apply::<V>(&load3(&self.m_cols), p).add(self.t.load());
        // Its bound, |M| e + g(4) (|M||p| + |T|) + U, evaluated as
        // |M| (e + g(4)|p|) + c_p (the same exact value, with c_p = g(4)|T|
        // + U rounded up when the instance was built): g(4)|p| and the sum
        // with e (two roundings), the matrix product (three more) and the
        // sum with c_p: six.
        let point_error = bound_up_l::<V>(
            apply::<V>(&load3(&self.m_abs_cols), p.abs().mul(g4).add(e)).add(self.c_point.load()),
            6,
        );
        // Normal: A^T n, the rows of A weighted by n's components.
        let normal = apply::<V>(&load3(&self.a_rows), n);
        // s = g(3) |A^T||n| + |A^T| eta, evaluated as |A^T| (g(3)|n| + eta):
        // five roundings, as for the point's |M| (e + g(4)|p|).
        let s = apply::<V>(&load3(&self.a_abs_rows), n.abs().mul(g3).add(eta));
        // |A^T N| <= |n_w| + s: the computed normal and its rounding, not
        // |A^T| (|n| + eta), which would let the cancellation in A^T n (a
        // normal along A's small singular direction) inflate the residual's
        // term by the condition number. Six roundings.
        let w = bound_up_l::<V>(normal.abs().add(s), 6);
        // W = max_i w_i, in every lane (as scalars from lanes 0 to 2: fewer
        // instructions than a packed maximum, which reads lane 3 too).
        let [w0, w1, w2] = w.to_array();
        let big_w = L::<V>::splat(max2(max2(w0, w1), w2));
        // s + normal_residual W + U: seven roundings on s's path (its five,
        // two sums); three on W's (a product, two sums).
        let normal_error = bound_up_l::<V>(
            s.add(self.normal_residual.load().mul(big_w))
                .add(self.tiny_world.load()),
            7,
        );
        SurfacePoint {
            point: vector(point),
            point_error: vector(point_error),
            normal: vector(normal),
            normal_error: vector(normal_error),
        }
    }

    /// A ray leaving the world surface point `world` (from
    /// [`Instance::surface_to_world`] of a hit in this instance) along
    /// `dir`, that cannot meet the surface it left when it is mapped back
    /// into this instance with [`Instance::world_to_object`] and tested in
    /// object space, as a renderer does. The same as
    /// [`Instance::spawn_through`] with this instance alone; see there for
    /// the guarantee and its precondition.
    ///
    /// ```
    /// use rayhit::{Instance, Ray, Surface, SurfacePoint, Triangle, glam::{Affine3A, Quat, Vec3}, ray_triangle};
    /// let inst = Instance::from_affine3a(Affine3A::from_scale_rotation_translation(
    ///     Vec3::new(3.0, 0.5, 1e-2), Quat::from_rotation_y(2.0), Vec3::splat(-7e4))).unwrap();
    /// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    /// let ray = Ray::new(Vec3::new(0.3, 0.3, 1.0), -Vec3::Z);
    /// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
    /// let world = inst.surface_to_world(&tri.surface_point(&ray, &hit));
    /// // A bounce back the way the ray came, and one through the surface.
    /// for dir in [world.normal, -world.normal + Vec3::X * world.normal.length()] {
    ///     let again = inst.world_to_object(&inst.spawn(&world, dir));
    ///     assert!(ray_triangle(&again, &tri, f32::INFINITY).is_none());
    /// }
    /// ```
    #[must_use]
    pub fn spawn(&self, world: &SurfacePoint<V>, dir: V) -> Ray<V> {
        Self::spawn_through(&[self], world, dir)
    }

    /// A ray leaving `world`, a surface point of an object reached through
    /// the instances `path` (outermost first: `path[0]` maps the world to
    /// its object space, `path[1]` that space to its own, and so on; the
    /// point is [`Instance::surface_to_world`] applied innermost first), so
    /// that the ray mapped back through the same instances with
    /// [`Instance::world_to_object`] cannot meet the surface it left.
    ///
    /// Guarantee: the object ray the renderer computes has its origin
    /// strictly on the side of the exact object plane that its direction
    /// points away from, so its exact crossing with the plane is at `t < 0`
    /// and [`ray_triangle`](crate::ray_triangle) (which decides `t > 0`
    /// conservatively) does not report the surface. The proof is in the
    /// source: the origin is offset by [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) with the point
    /// error widened by the round trip's error through the stored inverses,
    /// evaluated at the origin actually returned and checked.
    ///
    /// Preconditions, as for [`SurfacePoint::spawn`], in the values `world`
    /// and the instances give: `dir` not within rounding of tangent to the
    /// surface, where rounding now includes the map of the direction. With
    /// `n` and `eta` the world point's `normal` and `normal_error`, and
    /// `p` the `per_t` of [`Instance::world_to_object_error`] for the ray
    /// (`Instance::world_to_object_error(&Ray::new(world.point, dir))`),
    /// it is enough that `|fl(dir . n)| > gamma(3) sum |dir_i n_i| + sum
    /// |dir_i| eta_i + sum p_i (|n_i| + eta_i)`: a few ulps of the angle
    /// times the matrix's condition number. And the normal must be known
    /// well enough to pick a side (not a sliver: `|n|^2` well above `sum
    /// |n_i| eta_i`).
    /// And the round trip's error must grow more slowly than the offset:
    /// the product of the condition numbers of the matrices along `path`
    /// well below `1 / u`. Where it is not, no offset can help (moving the
    /// origin by `x` moves the mapped origin's error by about `u` times
    /// that product times `x`), the check keeps failing, and the ray
    /// starts at `world.point`, unmoved, as it does where the normal is
    /// not known; a single instance with scales from `1e-3` to `1e3` is
    /// well inside, an `f32` nested pair of two such anisotropic scales is
    /// not always. An empty `path` is [`SurfacePoint::spawn`]. Never
    /// panics.
    ///
    /// ```
    /// use rayhit::{Instance, Ray, Surface, SurfacePoint, Triangle, glam::{DAffine3, DQuat, DVec3}, ray_triangle};
    /// let outer = Instance::from_daffine3(DAffine3::from_rotation_translation(DQuat::from_rotation_z(0.7), DVec3::new(1e5, 0.0, 0.0))).unwrap();
    /// let inner = Instance::from_daffine3(DAffine3::from_scale(DVec3::new(1e3, 1e-3, 1.0))).unwrap();
    /// let tri = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
    /// let object_ray = Ray::new(DVec3::new(0.1, 0.6, 2.0), -DVec3::Z);
    /// let hit = ray_triangle(&object_ray, &tri, f64::INFINITY).unwrap();
    /// let world = outer.surface_to_world(&inner.surface_to_world(&tri.surface_point(&object_ray, &hit)));
    /// let ray = Instance::spawn_through(&[&outer, &inner], &world, -world.normal);
    /// let again = inner.world_to_object(&outer.world_to_object(&ray));
    /// assert!(ray_triangle(&again, &tri, f64::INFINITY).is_none());
    /// ```
    ///
    /// [`SurfacePoint::spawn`]: crate::SurfacePoint::spawn
    #[must_use]
    pub fn spawn_through(path: &[&Self], world: &SurfacePoint<V>, dir: V) -> Ray<V> {
        let unmoved = Ray::new(world.point, dir);
        if path.is_empty() {
            return world.spawn(dir);
        }
        let e = world.point_error.abs();
        let place = |extra: V| {
            let widened = V::new(
                bound_up(e[0] + extra[0], 1),
                bound_up(e[1] + extra[1], 1),
                bound_up(e[2] + extra[2], 1),
            );
            let origin =
                offset_ray_origin(world.point, widened, world.normal, world.normal_error, dir);
            // Not moved: the normal is not known well enough, or the
            // input is not finite.
            (origin != world.point).then_some(origin)
        };
        let need = |origin: V| Self::path_error(path, &Ray::new(origin, dir)).at_origin;
        settle(need(world.point), place, need).map_or(unmoved, |origin| Ray::new(origin, dir))
    }

    /// The shadow-ray segment from `from`, a surface point of an object
    /// reached through the instances `from_path`, to `to`, one reached
    /// through `to_path` (each outermost first, as for
    /// [`Instance::spawn_through`]; an empty path is a world surface), as
    /// [`SurfacePoint::spawn_to`] makes it: a ray and the interval `(0,
    /// 1]`, for a segment traced through the whole scene, each instance
    /// visited with [`Instance::world_to_object`].
    ///
    /// Guarantees, with the object rays the renderer computes: the one in
    /// `from`'s object space has its origin strictly on the side of the
    /// exact object plane that its direction moves away from (its exact
    /// crossing is at `t < 0`), and the one in `to`'s object space is,
    /// at `t = 1`, strictly on the side its direction comes from (its
    /// crossing is at `t > 1`), so no interval kernel reports either
    /// surface over `(0, 1]`; and any surface the exact world segment
    /// crosses farther than the ends' moves from them is crossed in
    /// `(0, 1]`. With both paths empty, the segment is
    /// [`SurfacePoint::spawn_to`]'s, bit for bit.
    ///
    /// How: each end is offset as `spawn_to` offsets it, its point error
    /// widened by the round trip's error at that end (the path's
    /// [`InstanceRayError`](crate::instance::InstanceRayError) at `t = 0` for the
    /// start, at `t = 1` for the end), evaluated at the ends actually
    /// returned and checked, as [`Instance::spawn_through`] does; and the
    /// side tests of the direction include its mapped rounding (`per_t`).
    /// Every condition is checked: `Some` is proved.
    ///
    /// `None`: as for [`SurfacePoint::spawn_to`] (count the connection as
    /// blocked), and also where the round trip's error grows with an end's
    /// offset as fast as the offset does (the product of a path's
    /// condition numbers near `1 / u`). Never panics.
    ///
    /// ```
    /// use rayhit::{Instance, Intersect, Interval, Ray, Surface, SurfacePoint, Triangle, ray_triangle};
    /// use rayhit::glam::{Affine3A, Quat, Vec3};
    /// // A tile rotated and placed far away, and a lamp above it, each an instance of one triangle.
    /// let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(2.0, -1.0, 0.0), Vec3::new(-1.0, 2.0, 0.0));
    /// let place = |q: Quat, at: Vec3| Instance::from_affine3a(Affine3A::from_rotation_translation(q, at)).unwrap();
    /// let tile = place(Quat::from_rotation_x(0.3), Vec3::new(2e4, 0.0, 0.0));
    /// let lamp = place(Quat::from_rotation_x(3.0), Vec3::new(2e4, 0.0, 3.0));
    /// // Where a ray from the eye straight down (or up) meets an instance.
    /// let hit_on = |inst: &Instance, dir: Vec3| {
    ///     let ray = inst.world_to_object(&Ray::new(Vec3::new(2e4, 0.2, 1.5), dir));
    ///     inst.surface_to_world(&tri.surface_point(&ray, &ray_triangle(&ray, &tri, f32::INFINITY).unwrap()))
    /// };
    /// let on_tile = hit_on(&tile, -Vec3::Z);
    /// let on_lamp = hit_on(&lamp, Vec3::Z);
    /// let (shadow, segment) = Instance::spawn_to_through(&[&tile], &on_tile, &[&lamp], &on_lamp).unwrap();
    /// assert_eq!(segment, Interval::up_to(1.0).unwrap());
    /// // Traced into either instance, the segment meets neither end's surface.
    /// for inst in [&tile, &lamp] {
    ///     assert!(tri.hit(&inst.world_to_object(&shadow), segment).is_none());
    /// }
    /// ```
    ///
    /// [`SurfacePoint::spawn_to`]: crate::SurfacePoint::spawn_to
    #[must_use]
    pub fn spawn_to_through(
        from_path: &[&Self],
        from: &SurfacePoint<V>,
        to_path: &[&Self],
        to: &SurfacePoint<V>,
    ) -> Option<(Ray<V>, Interval<S<V>>)> {
        let from_map = |ray: &Ray<V>| Self::path_error(from_path, ray).parts();
        let to_map = |ray: &Ray<V>| Self::path_error(to_path, ray).parts();
        let maps: [Option<RayMapBound<'_, V>>; 2] = [
            (!from_path.is_empty()).then_some(&from_map),
            (!to_path.is_empty()).then_some(&to_map),
        ];
        segment(from, to.point, Some(to), maps)
    }

    /// The shadow-ray segment from `from`, a surface point reached through
    /// the instances `from_path`, to a point light at `light` (a world
    /// point, on no surface): [`Instance::spawn_to_through`] with the
    /// light as the end, unmoved, as [`SurfacePoint::spawn_to_point`] has
    /// it. The same guarantees for the start; `None` in the same cases.
    ///
    /// ```
    /// use rayhit::{Instance, Intersect, Ray, Surface, SurfacePoint, Triangle, ray_triangle};
    /// use rayhit::glam::{DAffine3, DQuat, DVec3};
    /// let tri = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
    /// let inst = Instance::from_daffine3(DAffine3::from_scale_rotation_translation(
    ///     DVec3::new(1e3, 1e-3, 1.0), DQuat::from_rotation_y(0.4), DVec3::splat(1e5))).unwrap();
    /// let ray = Ray::new(DVec3::new(0.2, 0.3, 1.0), -DVec3::Z);
    /// let here = inst.surface_to_world(&tri.surface_point(&ray, &ray_triangle(&ray, &tri, f64::INFINITY).unwrap()));
    /// let light = here.point + here.normal * 10.0 + DVec3::X;
    /// let (shadow, segment) = Instance::spawn_to_point_through(&[&inst], &here, light).unwrap();
    /// assert!(tri.hit(&inst.world_to_object(&shadow), segment).is_none());
    /// ```
    #[must_use]
    pub fn spawn_to_point_through(
        from_path: &[&Self],
        from: &SurfacePoint<V>,
        light: V,
    ) -> Option<(Ray<V>, Interval<S<V>>)> {
        let from_map = |ray: &Ray<V>| Self::path_error(from_path, ray).parts();
        let maps: [Option<RayMapBound<'_, V>>; 2] =
            [(!from_path.is_empty()).then_some(&from_map), None];
        segment(from, light, None, maps)
    }
}
