//! Ray differentials and ray cones: how a camera ray changes from one
//! pixel to the next, for filtering textures.

use glam::Vec3;

use crate::num::{S, Scalar, Vector};
use crate::ray::Ray;

/// A camera ray with its differentials: the derivatives of its origin and
/// direction with respect to the raster position, per pixel (Igehy,
/// "Tracing Ray Differentials", SIGGRAPH 1999).
///
/// `dx_origin` and `dx_dir` are the derivatives with respect to raster `x`
/// (one pixel to the right), `dy_origin` and `dy_dir` with respect to
/// raster `y` (one pixel down): the rays of pixels `(x + 1, y)` and
/// `(x, y + 1)` are `ray + offset` to first order, with the second-order
/// remainder each camera states (a fraction of a pixel's angle squared).
/// The derivatives are those of the ray the camera returns, direction
/// length included: a camera with unit directions has `dx_dir`
/// orthogonal to `dir`.
///
/// ```
/// use rayhit::{Camera, CameraSample, PinholeCamera, glam::Vec3};
/// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 100.0, 201, 201).unwrap();
/// let diff = cam.ray_differential(CameraSample::new(100.5, 100.5));
/// // At the centre, one pixel turns the ray by 1/100 radian, to the right.
/// assert!((diff.dx_dir - Vec3::X / 100.0).length() < 1e-8);
/// assert!((diff.dy_dir + Vec3::Y / 100.0).length() < 1e-8);
/// assert_eq!(diff.dx_origin, Vec3::ZERO);
/// // The ray one pixel to the right, to first order.
/// let next = diff.offset(1.0, 0.0);
/// assert!((next.dir - cam.ray(CameraSample::new(101.5, 100.5)).dir).length() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayDifferential<V = Vec3> {
    /// The ray itself.
    pub ray: Ray<V>,
    /// Derivative of the origin with respect to raster `x`.
    pub dx_origin: V,
    /// Derivative of the direction with respect to raster `x`.
    pub dx_dir: V,
    /// Derivative of the origin with respect to raster `y` (down).
    pub dy_origin: V,
    /// Derivative of the direction with respect to raster `y` (down).
    pub dy_dir: V,
}

impl<V: Vector> RayDifferential<V> {
    /// The first-order ray of raster position `(x + sx, y + sy)`:
    /// `origin + sx dx_origin + sy dy_origin`, `dir + sx dx_dir + sy
    /// dy_dir`, rounded.
    #[inline]
    #[must_use]
    pub fn offset(&self, sx: S<V>, sy: S<V>) -> Ray<V> {
        Ray::new(
            self.ray.origin + self.dx_origin * sx + self.dy_origin * sy,
            self.ray.dir + self.dx_dir * sx + self.dy_dir * sy,
        )
    }
}

/// A ray cone (Akenine-Moller et al., "Texture Level of Detail Strategies
/// for Real-Time Ray Tracing", Ray Tracing Gems, chapter 20, 2019): the
/// footprint of one pixel along a camera ray, as a width at the ray's
/// origin and a spread angle.
///
/// At a distance `s` along the ray (in world units: `t * |dir|`), the
/// cone is [`width_at(s)`](RayCone::width_at) `= width + spread * s`
/// wide, the chapter's first-order form (`2 s tan(spread / 2)` is `s *
/// spread` to third order in the angle, which is a pixel's).
///
/// ```
/// use rayhit::{Camera, PinholeCamera, glam::Vec3};
/// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 500.0, 640, 480).unwrap();
/// let cone = cam.ray_cone();
/// // One pixel is 1/500 of the distance wide, to first order.
/// assert!((cone.width_at(1000.0) - 2.0).abs() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayCone<F = f32> {
    /// The width at the ray's origin, in world units (zero for cameras whose
    /// rays start at one point).
    pub width: F,
    /// The spread angle, in radians: the angle one pixel subtends.
    pub spread: F,
}

impl<F: Scalar> RayCone<F> {
    /// The cone's width `width + spread * distance` at `distance` world
    /// units along the ray, rounded (two roundings).
    #[inline]
    #[must_use]
    pub fn width_at(&self, distance: F) -> F {
        self.width + self.spread * distance
    }
}

/// The differentials of a triangle hit: how the hit point and its
/// barycentrics move per pixel (Igehy 1999, section 3: the transfer of a
/// ray differential to a surface).
///
/// `dp_dx` and `dp_dy` are the derivatives of the hit point with respect
/// to raster `x` and `y`; `du_dx` ... `dv_dy` those of the barycentrics
/// `(u, v)` of [`TriangleHit`](crate::TriangleHit) (`point = (1 - u - v) a +
/// u b + v c`). With the texture coordinates `uv_a`, `uv_b`, `uv_c` of the
/// corners, a texture's coordinates move by `(uv_b - uv_a) du_dx + (uv_c -
/// uv_a) dv_dx` per pixel to the right: the footprint a texture filter
/// needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitDifferentials<V: Vector = Vec3> {
    /// Derivative of the hit point with respect to raster `x`.
    pub dp_dx: V,
    /// Derivative of the hit point with respect to raster `y`.
    pub dp_dy: V,
    /// Derivative of `u` with respect to raster `x`.
    pub du_dx: S<V>,
    /// Derivative of `v` with respect to raster `x`.
    pub dv_dx: S<V>,
    /// Derivative of `u` with respect to raster `y`.
    pub du_dy: S<V>,
    /// Derivative of `v` with respect to raster `y`.
    pub dv_dy: S<V>,
}

/// A number the transfer is computed in: a float, or a float with a bound
/// on its distance from the exact value ([`Tracked`]), so that the value
/// and its error bound come from one piece of code, in one order.
trait Arith:
    Copy
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Div<Output = Self>
    + core::ops::Neg<Output = Self>
{
    /// The computed value.
    type F: Scalar;
    fn value(self) -> Self::F;
}

impl<F: Scalar> Arith for F {
    type F = F;
    #[inline(always)]
    fn value(self) -> F {
        self
    }
}

/// A computed value `v` and a bound `e >= |v - exact|`, where `exact` is
/// the same expression evaluated exactly on the same inputs (running error
/// analysis). Each operation's bound, with `g = gamma(1)` (one rounding of
/// the result: `|fl(z) - z| <= g |fl(z)|`):
///
/// - `x + y`, `x - y`: `e_x + e_y + g |v|`;
/// - `x y`: `|x| e_y + |y| e_x + e_x e_y + g |v|` (from `XY - xy = x eta
///   + y xi + xi eta`);
/// - `x / y`: `(e_x + (1 + g) |v| e_y) / (|y| - e_y) + g |v|` (from `X/Y
///   - x/y = (xi y - x eta) / (Y y)` and `|Y| >= |y| - e_y`), infinite
///   unless `|y| > e_y`.
///
/// The bounds themselves are evaluated rounding upward (each operation's
/// result stepped up an ulp, the subtraction's down), so they stay bounds.
#[derive(Clone, Copy, Debug)]
struct Tracked<F> {
    v: F,
    e: F,
}

impl<F: Scalar> Tracked<F> {
    #[inline(always)]
    fn exact(v: F) -> Self {
        Self { v, e: F::ZERO }
    }
    #[inline(always)]
    fn rounding(v: F) -> F {
        mul_up(F::gamma_n(1), v.abs())
    }
}

use crate::num::round::outward::{add_up, div_up, mul_up, sub_down};

impl<F: Scalar> core::ops::Add for Tracked<F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let v = self.v + o.v;
        let e = add_up(add_up(self.e, o.e), Self::rounding(v));
        Self { v, e }
    }
}

impl<F: Scalar> core::ops::Sub for Tracked<F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let v = self.v - o.v;
        let e = add_up(add_up(self.e, o.e), Self::rounding(v));
        Self { v, e }
    }
}

impl<F: Scalar> core::ops::Neg for Tracked<F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            e: self.e,
        }
    }
}

impl<F: Scalar> core::ops::Mul for Tracked<F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let v = self.v * o.v;
        let cross = add_up(mul_up(self.v.abs(), o.e), mul_up(o.v.abs(), self.e));
        let e = add_up(add_up(cross, mul_up(self.e, o.e)), Self::rounding(v));
        Self { v, e }
    }
}

impl<F: Scalar> core::ops::Div for Tracked<F> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        let room = sub_down(o.v.abs(), o.e);
        let e = if room > F::ZERO {
            let grown = mul_up(add_up(F::ONE, F::gamma_n(1)), v.abs());
            let num = add_up(self.e, mul_up(grown, o.e));
            add_up(div_up(num, room), Self::rounding(v))
        } else {
            F::INFINITY
        };
        Self { v, e }
    }
}

impl<F: Scalar> Arith for Tracked<F> {
    type F = F;
    #[inline(always)]
    fn value(self) -> F {
        self.v
    }
}

type Vec3Of<T> = [T; 3];

#[inline(always)]
fn vsub<T: Arith>(a: Vec3Of<T>, b: Vec3Of<T>) -> Vec3Of<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn vadd<T: Arith>(a: Vec3Of<T>, b: Vec3Of<T>) -> Vec3Of<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
fn vscale<T: Arith>(a: Vec3Of<T>, s: T) -> Vec3Of<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline(always)]
fn vdot<T: Arith>(a: Vec3Of<T>, b: Vec3Of<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn vcross<T: Arith>(a: Vec3Of<T>, b: Vec3Of<T>) -> Vec3Of<T> {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}

/// The transfer, once for both number types: `None` where `d . n` or `|n|^2`
/// is zero (for [`Tracked`], where its value is).
#[inline(always)]
#[allow(clippy::type_complexity)]
fn transfer<T: Arith>(
    dir: Vec3Of<T>,
    moves: [(Vec3Of<T>, Vec3Of<T>); 2],
    tri: [Vec3Of<T>; 3],
    t: T,
) -> Option<[(Vec3Of<T>, T, T); 2]> {
    let zero = <T::F as Scalar>::ZERO;
    let (e1, e2) = (vsub(tri[1], tri[0]), vsub(tri[2], tri[0]));
    let n = vcross(e1, e2);
    let den = vdot(dir, n);
    let nn = vdot(n, n);
    if den.value() == zero || nn.value() == zero {
        return None;
    }
    let (bu, bv) = (vcross(e2, n), vcross(n, e1));
    Some(moves.map(|(d_origin, d_dir)| {
        // The point's move off the ray's own: q = do + t dd; the plane
        // takes it back along the ray by dt = -(q . n) / (d . n).
        let q = vadd(d_origin, vscale(d_dir, t));
        let dt = -(vdot(q, n) / den);
        let dp = vadd(q, vscale(dir, dt));
        (dp, vdot(dp, bu) / nn, vdot(dp, bv) / nn)
    }))
}

#[inline(always)]
fn arr<V: Vector>(v: V) -> [S<V>; 3] {
    [v.x(), v.y(), v.z()]
}

#[inline(always)]
fn tracked<V: Vector>(v: V) -> [Tracked<S<V>>; 3] {
    arr(v).map(Tracked::exact)
}

impl<V: Vector> crate::Triangle<V> {
    /// The differentials of a triangle hit at `t` (Igehy, "Tracing Ray
    /// Differentials", 1999): with `n = (b - a) x (c - a)` and, per raster
    /// direction, `q = d_origin + t d_dir`,
    ///
    /// `dt = -(q . n) / (dir . n)`, `dp = q + dt dir`,
    /// `du = dp . ((c - a) x n) / |n|^2`, `dv = dp . (n x (b - a)) / |n|^2`.
    ///
    /// `t` is the hit's distance ([`TriangleHit::t`](crate::TriangleHit)); `diff`
    /// the ray's differentials ([`Camera::ray_differential`](crate::Camera::ray_differential)).
    /// `None` when `dir . n` or `|n|^2` is zero (a ray in the triangle's plane, a
    /// zero-area triangle), so that nothing divides by zero; a ray within
    /// rounding of parallel gives huge differentials, as the exact ones are.
    /// Non-finite input gives non-finite output.
    ///
    /// Each value is within [`hit_differentials_error`](Self::hit_differentials_error) of the
    /// same formulas evaluated exactly on the same floats (the exact derivative
    /// of the hit point at parameter `t`). The exact hit is at `t*`, not `t`:
    /// that moves `dp` by `(t - t*) (d_dir - dir (d_dir . n) / (dir . n))`,
    /// with `|t - t*|` from [`hit_error`](crate::Surface::hit_error).
    ///
    /// ```
    /// use rayhit::{Camera, CameraSample, Intersect, PinholeCamera, Triangle, glam::Vec3};
    /// // A camera 10 units above a floor of two big triangles, looking down.
    /// let cam = PinholeCamera::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y, -Vec3::Z, 100.0, 201, 201).unwrap();
    /// let floor = Triangle::new(Vec3::new(-50.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 50.0), Vec3::new(-50.0, 0.0, -50.0));
    /// let diff = cam.ray_differential(CameraSample::new(100.5, 100.5));
    /// let hit = floor.hit(&diff.ray, f32::INFINITY).unwrap();
    /// let d = floor.hit_differentials(&diff, hit.t).unwrap();
    /// // One pixel is 10/100 = 0.1 units on the floor, to the right (+x) and down (+z).
    /// assert!((d.dp_dx - Vec3::new(0.1, 0.0, 0.0)).length() < 1e-5);
    /// assert!((d.dp_dy - Vec3::new(0.0, 0.0, 0.1)).length() < 1e-5);
    /// // The edge b - a is 100 units along x: u moves by 0.1 / 100 per pixel.
    /// assert!((d.du_dx - 0.001).abs() < 1e-7);
    /// ```
    #[must_use]
    pub fn hit_differentials(
        &self,
        diff: &RayDifferential<V>,
        t: S<V>,
    ) -> Option<HitDifferentials<V>> {
        triangle_hit_differentials(diff, self, t)
    }

    /// Bounds on the rounding errors of [`hit_differentials`](Self::hit_differentials): each
    /// field bounds the distance of the same field (per component for the
    /// points' derivatives) from the same formulas evaluated exactly on the
    /// same inputs, `t` included; every bound is infinite where the function
    /// returns `None`, where a divisor's sign is not certain (`|dir . n|` or
    /// `|n|^2` within its own rounding error) or for non-finite input.
    ///
    /// The bound is a running error analysis of the very operations the
    /// function performs, in the same order: each operation adds the
    /// propagated bounds of its operands and one rounding of its result (the
    /// rules are in the source, each derived there), evaluated rounding
    /// upward. It is tight to a small factor where nothing cancels, and
    /// grows as `dir . n` approaches its rounding error (a grazing ray, whose
    /// exact differentials grow too).
    ///
    /// ```
    /// use rayhit::{Camera, CameraSample, Intersect, PinholeCamera, Triangle, glam::Vec3};
    /// let cam = PinholeCamera::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y, -Vec3::Z, 100.0, 201, 201).unwrap();
    /// let floor = Triangle::new(Vec3::new(-50.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 50.0), Vec3::new(-50.0, 0.0, -50.0));
    /// let diff = cam.ray_differential(CameraSample::new(30.5, 150.5));
    /// let hit = floor.hit(&diff.ray, f32::INFINITY).unwrap();
    /// let d = floor.hit_differentials(&diff, hit.t).unwrap();
    /// let err = floor.hit_differentials_error(&diff, hit.t);
    /// assert!(err.du_dx < 1e-5 * d.du_dx.abs());
    /// ```
    #[must_use]
    pub fn hit_differentials_error(
        &self,
        diff: &RayDifferential<V>,
        t: S<V>,
    ) -> HitDifferentials<V> {
        triangle_hit_differentials_error(diff, self, t)
    }

    /// The width of a ray cone's footprint on a triangle hit at `t` by `ray`: the cone's
    /// width at the hit's distance (`t |dir|`), divided by the cosine of the
    /// angle between the ray and the triangle's normal (the footprint's long
    /// axis on the surface; Ray Tracing Gems, chapter 20, eq. 20.3's `|n .
    /// d|`). `None` for a ray in the triangle's plane or a zero-area
    /// triangle (a zero dot product or length), so that nothing divides by
    /// zero.
    ///
    /// Rounded: the width, the lengths and the quotient are a dozen roundings
    /// of non-negative quantities (within `gamma(12)` of the same formula on
    /// the computed normal and dot product); the computed normal and `dir .
    /// n` carry the errors [`Triangle::normal_error`](crate::Triangle::normal_error)
    /// and a dot product's, which grow relative to the result as the triangle
    /// thins and as the ray grazes it (where the footprint itself grows
    /// without bound). It is a filter's width: a few roundings do not matter,
    /// a NaN would, and none comes out of finite input.
    ///
    /// A texture level of detail follows as in the chapter: `log2(width /
    /// texel_size)`, with the texel size in world units at the hit.
    #[must_use]
    pub fn cone_width(&self, cone: &RayCone<S<V>>, ray: &Ray<V>, t: S<V>) -> Option<S<V>> {
        triangle_cone_width(cone, ray, self, t)
    }
}

/// See [`Triangle::hit_differentials`](crate::Triangle).
pub(crate) fn triangle_hit_differentials<V: Vector>(
    diff: &RayDifferential<V>,
    tri: &crate::Triangle<V>,
    t: S<V>,
) -> Option<HitDifferentials<V>> {
    let moves = [
        (arr(diff.dx_origin), arr(diff.dx_dir)),
        (arr(diff.dy_origin), arr(diff.dy_dir)),
    ];
    let tri = [arr(tri.a), arr(tri.b), arr(tri.c)];
    let [(px, ux, vx), (py, uy, vy)] = transfer(arr(diff.ray.dir), moves, tri, t)?;
    let v = |p: [S<V>; 3]| V::new(p[0], p[1], p[2]);
    Some(HitDifferentials {
        dp_dx: v(px),
        dp_dy: v(py),
        du_dx: ux,
        dv_dx: vx,
        du_dy: uy,
        dv_dy: vy,
    })
}

/// See [`Triangle::hit_differentials_error`](crate::Triangle).
pub(crate) fn triangle_hit_differentials_error<V: Vector>(
    diff: &RayDifferential<V>,
    tri: &crate::Triangle<V>,
    t: S<V>,
) -> HitDifferentials<V> {
    let inf = S::<V>::INFINITY;
    let infinite = HitDifferentials {
        dp_dx: V::splat(inf),
        dp_dy: V::splat(inf),
        du_dx: inf,
        dv_dx: inf,
        du_dy: inf,
        dv_dy: inf,
    };
    let inputs = [
        diff.ray.dir,
        diff.dx_origin,
        diff.dx_dir,
        diff.dy_origin,
        diff.dy_dir,
        tri.a,
        tri.b,
        tri.c,
    ];
    if !inputs.iter().all(|v| v.is_finite()) || !t.is_finite() {
        return infinite;
    }
    let moves = [
        (tracked(diff.dx_origin), tracked(diff.dx_dir)),
        (tracked(diff.dy_origin), tracked(diff.dy_dir)),
    ];
    let tri = [tracked(tri.a), tracked(tri.b), tracked(tri.c)];
    let Some([(px, ux, vx), (py, uy, vy)]) =
        transfer(tracked(diff.ray.dir), moves, tri, Tracked::exact(t))
    else {
        return infinite;
    };
    // A bound that is NaN (inf - inf inside) is no bound.
    let b = |x: Tracked<S<V>>| if x.e >= S::<V>::ZERO { x.e } else { inf };
    let v = |p: [Tracked<S<V>>; 3]| V::new(b(p[0]), b(p[1]), b(p[2]));
    HitDifferentials {
        dp_dx: v(px),
        dp_dy: v(py),
        du_dx: b(ux),
        dv_dx: b(vx),
        du_dy: b(uy),
        dv_dy: b(vy),
    }
}

/// See [`Triangle::cone_width`](crate::Triangle).
pub(crate) fn triangle_cone_width<V: Vector>(
    cone: &RayCone<S<V>>,
    ray: &Ray<V>,
    tri: &crate::Triangle<V>,
    t: S<V>,
) -> Option<S<V>> {
    let n = tri.normal();
    let cos = ray.dir.dot(n).abs();
    let scale = ray.dir.length() * n.length();
    if !(cos > S::<V>::ZERO) || !(scale > S::<V>::ZERO) {
        return None;
    }
    let width = cone.width_at(t * ray.dir.length());
    Some(width * (scale / cos))
}
