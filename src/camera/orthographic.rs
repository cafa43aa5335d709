//! The orthographic camera: parallel rays from a plane.

use glam::Vec3;

use super::{
    Basis, Camera, CameraError, CameraSample, RayCone, RayDifferential, by_components, centred,
    zero_vector,
};
use crate::num::{S, Scalar, Vector};
use crate::ray::Ray;

/// An orthographic camera: parallel rays, all with the same direction,
/// starting on a plane in front of the scene (CAD views, previews, baking,
/// shadow maps).
///
/// Conventions as [`PinholeCamera`](crate::PinholeCamera): right-handed,
/// raster `(0, 0)` at the top-left, `x` right, `y` down, pixel `(i, j)`
/// centred at `(i + 0.5, j + 0.5)`, basis `forward = normalize(view_dir)`,
/// `right = normalize(forward x up)`, `true_up = right x forward`. Pixels
/// are square, `pixel_size` world units wide.
///
/// **Where rays start.** The ray of raster position `(x, y)` starts at
/// `centre + ((x - width/2) pixel_size) right + ((height/2 - y)
/// pixel_size) true_up`, on the plane through `centre` facing the view:
/// the camera stores no other position and adds nothing far away. Put
/// `centre` just in front of the scene (the near plane): each origin
/// component is then within `gamma(4)` of its exact value relative to
/// `|centre_i| + |offsets|`, the rounding of the scene's own coordinates,
/// and `t` counts from there, so a hit point `origin + t dir` is as
/// precise as the scene's coordinates allow. A sensor placed far away (a
/// camera `10^6` units back, its rays starting there) would add an ulp of
/// `10^6` to every origin and make `t` large, and both show in the picture
/// as rings and noise on surfaces that are flat and close together.
///
/// **Directions.** Every ray has the same direction, `forward` (unit within
/// `gamma(4)`, as [`PinholeCamera::forward`](crate::PinholeCamera::forward)),
/// bit for bit: the rays are exactly parallel.
///
/// ```
/// use rayhit::{Camera, camera::OrthographicCamera, glam::Vec3};
/// // Looking down at the ground from y = 10, 0.5 units per pixel, 4x2 pixels.
/// let cam = OrthographicCamera::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y, -Vec3::Z, 0.5, 4, 2).unwrap();
/// let ray = cam.pixel_ray(0, 0);
/// assert_eq!(ray.dir, -Vec3::Y);
/// // Pixel (0, 0) is 1.5 pixels left and half a pixel up of the centre.
/// assert_eq!(ray.origin, Vec3::new(-0.75, 10.0, -0.25));
/// assert_eq!(cam.pixel_ray(3, 1).dir, ray.dir);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrthographicCamera<V = Vec3>
where
    V: Vector,
{
    basis: Basis<V>,
    pixel_size: S<V>,
    width: u32,
    height: u32,
}

impl<V: Vector> OrthographicCamera<V> {
    /// A camera whose centre ray starts at `centre` and looks along
    /// `view_dir`, with `up` giving the upward direction, square pixels of
    /// `pixel_size` world units and an image of `width x height` pixels.
    ///
    /// # Errors
    ///
    /// As [`PinholeCamera::new`](crate::PinholeCamera::new) (a non-finite
    /// `centre` is [`CameraError::NonFiniteEye`]), and
    /// [`CameraError::InvalidPixelSize`] for a pixel size that is not
    /// positive and finite.
    pub fn new(
        centre: V,
        view_dir: V,
        up: V,
        pixel_size: S<V>,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        let basis = Basis::new(centre, view_dir, up)?;
        if !(pixel_size > S::<V>::ZERO && pixel_size.is_finite()) {
            return Err(CameraError::InvalidPixelSize);
        }
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        Ok(Self {
            basis,
            pixel_size,
            width,
            height,
        })
    }

    /// Where the centre ray starts.
    #[inline]
    #[must_use]
    pub fn centre(&self) -> V {
        self.basis.eye
    }

    /// The unit view direction: every ray's direction.
    #[inline]
    #[must_use]
    pub fn forward(&self) -> V {
        self.basis.forward
    }

    /// The unit vector pointing right in the image.
    #[inline]
    #[must_use]
    pub fn right(&self) -> V {
        self.basis.right
    }

    /// The unit vector pointing up in the image, orthogonal to `forward`.
    #[inline]
    #[must_use]
    pub fn up(&self) -> V {
        self.basis.up
    }

    /// The width of a pixel, in world units.
    #[inline]
    #[must_use]
    pub fn pixel_size(&self) -> S<V> {
        self.pixel_size
    }

    /// A per-component bound on the distance of the origin of the ray of
    /// `(x, y)` from the exact point `centre + (dx s) right + (dy s)
    /// true_up` (`s` the pixel size, `(dx, dy)` the offsets from the image
    /// centre, the camera's own basis): `gamma(4) (|centre_i| + |dx s
    /// right_i| + |dy s up_i|)`. Each origin component carries four
    /// roundings (the offset's product by `s`, its product with the basis
    /// vector, the sum of the two offsets and the sum with the centre).
    /// Evaluated with outward rounding; infinite for a NaN or infinite
    /// position. Held to in exact arithmetic by the test kit's
    /// orthographic checks.
    ///
    /// ```
    /// use rayhit::camera::OrthographicCamera;
    /// use rayhit::glam::Vec3;
    /// let cam = OrthographicCamera::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y, -Vec3::Z, 0.5, 640, 480).unwrap();
    /// // A few ulps of coordinates of about 10 and 160.
    /// assert!(cam.origin_error(0.5, 0.5).max_element() < 1e-4);
    /// ```
    #[must_use]
    pub fn origin_error(&self, x: S<V>, y: S<V>) -> V {
        use crate::num::round::outward::{add_up, mul_up};
        let (dx, dy) = super::centred(x, y, self.width, self.height);
        if !(dx.is_finite() && dy.is_finite()) {
            return V::splat(S::<V>::INFINITY);
        }
        let b = &self.basis;
        let g4 = S::<V>::gamma_n(4).next_up();
        let (a, c) = (
            mul_up(dx.abs(), self.pixel_size),
            mul_up(dy.abs(), self.pixel_size),
        );
        let k = |i: usize| {
            let m = add_up(
                add_up(b.eye[i].abs(), mul_up(a, b.right[i].abs())),
                mul_up(c, b.up[i].abs()),
            );
            mul_up(g4, m)
        };
        V::new(k(0), k(1), k(2))
    }
}

impl<V: Vector> Camera<V> for OrthographicCamera<V> {
    /// The ray through raster position `(x, y)`: from
    /// `centre + ((x - width/2) s) right + ((height/2 - y) s) true_up`
    /// (`s` the pixel size) along `forward`.
    ///
    /// Each origin component is within
    /// [`origin_error`](OrthographicCamera::origin_error) of the exact
    /// point, and within the same of the plane through `centre` (up to the
    /// basis's own rounding). Positions outside the image give rays outside the
    /// view; a NaN or infinite position gives a non-finite origin, which
    /// every kernel rejects.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let [x, y] = sample.film;
        let (dx, dy) = centred(x, y, self.width, self.height);
        let s = self.pixel_size;
        let b = &self.basis;
        Ray::new(
            b.eye + (b.right * (dx * s) + b.up * (dy * s)),
            by_components(b.forward),
        )
    }

    /// The ray through `(x, y)`, bit for bit [`ray`](Self::ray), with its
    /// differentials: the origin moves by `pixel_size right` per pixel to
    /// the right and `-pixel_size true_up` per pixel down (one rounding
    /// each; exact second order, the origin being linear in the position),
    /// the direction does not move.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let s = self.pixel_size;
        RayDifferential {
            ray: self.ray(sample),
            dx_origin: self.basis.right * s,
            dx_dir: zero_vector(),
            dy_origin: -(self.basis.up * s),
            dy_dir: zero_vector(),
        }
    }

    /// The ray cone of every ray: one pixel wide, not spreading.
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        RayCone {
            width: self.pixel_size,
            spread: S::<V>::ZERO,
        }
    }

    super::film_size!();
}
