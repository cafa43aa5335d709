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
/// use rayhit::{PinholeCamera, glam::Vec3};
/// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 100.0, 201, 201).unwrap();
/// let diff = cam.ray_differential(100.5, 100.5);
/// // At the centre, one pixel turns the ray by 1/100 radian, to the right.
/// assert!((diff.dx_dir - Vec3::X / 100.0).length() < 1e-8);
/// assert!((diff.dy_dir + Vec3::Y / 100.0).length() < 1e-8);
/// assert_eq!(diff.dx_origin, Vec3::ZERO);
/// // The ray one pixel to the right, to first order.
/// let next = diff.offset(1.0, 0.0);
/// assert!((next.dir - cam.ray(101.5, 100.5).dir).length() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
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
/// use rayhit::{PinholeCamera, glam::Vec3};
/// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 500.0, 640, 480).unwrap();
/// let cone = cam.ray_cone();
/// // One pixel is 1/500 of the distance wide, to first order.
/// assert!((cone.width_at(1000.0) - 2.0).abs() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
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
