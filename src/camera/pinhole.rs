//! The pinhole camera: an orthonormal basis from eye, view and up, and
//! raster position to primary ray.

use glam::Vec3;

use super::{
    Basis, Camera, CameraError, CameraSample, RayCone, RayDifferential, by_components, centred,
    dvec, linear_differential_error, zero_vector,
};
use crate::num::trig::atan2_turns;
use crate::num::{S, Scalar, Vector, unit, unit_and_inverse_length};
use crate::ray::Ray;

/// A pinhole camera: turns raster positions into primary rays.
///
/// Conventions: right-handed world. Raster coordinates have `(0, 0)` at the
/// image's top-left corner, `x` to the right and `y` down, in pixels; pixel
/// `(i, j)` covers `[i, i+1] x [j, j+1]` and has its centre at
/// `(i + 0.5, j + 0.5)`. The image plane is `focal_length` pixels in front of
/// the eye along the normalised view direction, centred on it. The basis is
/// `forward = normalize(view_dir)`, `right = normalize(forward x up)` (so
/// the up vector need not be unit or orthogonal to the view; only its
/// component orthogonal to the view is used) and `true_up = right x forward`,
/// orthonormal within `gamma(13)` per entry of `B^T B - I` even for an up
/// vector nearly parallel to the view (`right` has its rounding's component
/// along `forward` removed once more).
/// Width and height may differ; pixels are square.
///
/// Rays start at the eye and have unit-length directions (to a few ulps).
///
/// ```
/// use rayhit::{Camera, CameraSample, PinholeCamera, glam::Vec3};
/// // 3x3 image, 90 degree vertical field of view: focal length 1.5 pixels.
/// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 1.5, 3, 3).unwrap();
/// // The centre pixel looks straight along the view direction.
/// assert_eq!(cam.pixel_ray(1, 1).dir, -Vec3::Z);
/// // The top-left corner of the image is up and to the left: (-1.5, 1.5, -1.5) normalised.
/// let corner = cam.ray(CameraSample::new(0.0, 0.0)).dir;
/// assert!((corner - Vec3::new(-1.0, 1.0, -1.0).normalize()).length() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PinholeCamera<V = Vec3>
where
    V: Vector,
{
    eye: V,
    forward: V,
    right: V,
    up: V,
    focal_length: S<V>,
    width: u32,
    height: u32,
}

impl<V: Vector> PinholeCamera<V> {
    /// A camera at `eye` looking along `view_dir`, with `up` giving the
    /// upward direction, `focal_length` in pixels and an image of
    /// `width x height` pixels.
    ///
    /// # Errors
    ///
    /// One [`CameraError`] variant per bad input: non-finite `eye`, zero or
    /// non-finite `view_dir` or `up`, `up` parallel to `view_dir`, focal
    /// length not positive and finite, zero width or height.
    ///
    /// "Parallel" is decided against the rounding error: with both vectors
    /// normalised, `|forward x up|` is the sine of the angle between them.
    /// Each normalised component carries a relative error of at most
    /// `gamma(4)` (sum of squares, square root, reciprocal, product), so each
    /// cross product component `f_j u_k - f_k u_j` is within
    /// `gamma(10) (|f_j u_k| + |f_k u_j|)` of the exact one; those magnitudes
    /// form a vector of length at most `sqrt(2)`, and the length itself adds
    /// three roundings. So when the vectors are exactly parallel the computed
    /// sine is at most `sqrt(2) gamma(10) (1 + gamma(3)) < gamma(16)` (about
    /// `1e-6` in `f32`). A sine at or below that cannot be told from zero,
    /// and the basis it would give is noise.
    pub fn new(
        eye: V,
        view_dir: V,
        up: V,
        focal_length: S<V>,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        let Basis {
            eye,
            forward,
            right,
            up,
        } = Basis::new(eye, view_dir, up)?;
        if !(focal_length > S::<V>::ZERO && focal_length.is_finite()) {
            return Err(CameraError::InvalidFocalLength);
        }
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        Ok(Self {
            eye,
            forward,
            right,
            up,
            focal_length,
            width,
            height,
        })
    }

    /// A camera with a vertical field of view `fov_y` in radians, in
    /// `(0, pi)`: the focal length is `(height / 2) / tan(fov_y / 2)` pixels.
    ///
    /// # Errors
    ///
    /// As [`PinholeCamera::new`], and [`CameraError::InvalidFieldOfView`]
    /// for `fov_y` outside `(0, pi)` or NaN.
    ///
    /// ```
    /// use rayhit::{PinholeCamera, glam::Vec3};
    /// let cam = PinholeCamera::from_fov(Vec3::ZERO, -Vec3::Z, Vec3::Y, 90f32.to_radians(), 640, 480).unwrap();
    /// assert!((cam.focal_length() - 240.0).abs() < 1e-3);
    /// ```
    pub fn from_fov(
        eye: V,
        view_dir: V,
        up: V,
        fov_y: S<V>,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        if !(fov_y > S::<V>::ZERO && fov_y < S::<V>::PI) {
            return Err(CameraError::InvalidFieldOfView);
        }
        let half_height = S::<V>::from_u32(height) * S::<V>::HALF;
        let focal = half_height / (fov_y * S::<V>::HALF).tan();
        Self::new(eye, view_dir, up, focal, width, height)
    }

    /// The unnormalised direction towards raster position `(x, y)`:
    /// `focal * forward + (x - width/2) * right + (height/2 - y) * true_up`.
    #[inline(always)]
    pub(crate) fn film(&self, x: S<V>, y: S<V>) -> V {
        self.film_at(centred(x, y, self.width, self.height))
    }

    /// [`film`](Self::film) at the offsets `(dx, dy)` from the image centre.
    #[inline(always)]
    fn film_at(&self, (dx, dy): (S<V>, S<V>)) -> V {
        self.forward * self.focal_length + self.right * dx + self.up * dy
    }

    /// A bound on the length of the difference between each derivative of
    /// [`ray_differential`](Camera::ray_differential) at `(x, y)` (`dx_dir`,
    /// `dy_dir`) and the exact derivative of the unit direction at the
    /// camera's (rounded) basis and the position: with `p` the
    /// unnormalised direction and `K` the vector of `|focal forward_i| +
    /// |dx right_i| + |dy up_i|` (its magnitudes), `(|step| / |p|)
    /// (gamma(28) + 5 gamma(3) |K| / |p|)` for the computation (`|step|`
    /// the larger of `|right|` and `|true_up|`, one within `gamma(13)`),
    /// and `gamma(13) (focal_length + |dx| |right| + |dy| |true_up|) /
    /// ((1 - gamma(13)) |p|^2)` for using `dx` and `dy` in place of `p . right`
    /// and `p . true_up` (the basis is orthonormal within `gamma(13)`).
    /// Evaluated in `f64` and rounded up; infinite for a NaN or infinite
    /// position, or where `|p|` is not above twice the step. Held to in exact
    /// arithmetic, against the neighbouring pixels' rays, by the test
    /// kit's camera checks.
    ///
    /// ```
    /// use rayhit::{PinholeCamera, glam::Vec3};
    /// let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 500.0, 640, 480).unwrap();
    /// // A few ulps of the derivative's length, 1 / 500.
    /// assert!(cam.ray_differential_error(10.5, 20.5) < 1e-8);
    /// ```
    #[must_use]
    pub fn ray_differential_error(&self, x: S<V>, y: S<V>) -> S<V> {
        let offsets = centred(x, y, self.width, self.height);
        // `focal forward` exactly for `f32`, within a relative 2^-53 for `f64`.
        let c = dvec(self.forward) * self.focal_length.to_f64();
        let frame = S::<V>::gamma_n(13).to_f64();
        linear_differential_error(c, [self.right, self.up], offsets, frame)
    }

    /// The eye position: where every ray starts.
    #[inline]
    #[must_use]
    pub fn eye(&self) -> V {
        self.eye
    }

    /// The unit view direction.
    #[inline]
    #[must_use]
    pub fn forward(&self) -> V {
        self.forward
    }

    /// The unit vector pointing right in the image (`forward x up`).
    #[inline]
    #[must_use]
    pub fn right(&self) -> V {
        self.right
    }

    /// The unit vector pointing up in the image, orthogonal to `forward`.
    #[inline]
    #[must_use]
    pub fn up(&self) -> V {
        self.up
    }

    /// The focal length in pixels.
    #[inline]
    #[must_use]
    pub fn focal_length(&self) -> S<V> {
        self.focal_length
    }
}

impl<V: Vector> Camera<V> for PinholeCamera<V> {
    /// The ray through raster position `(x, y)` (continuous, in pixels, from
    /// the top-left corner, `y` down), starting at the eye, with a
    /// unit-length direction.
    ///
    /// `dir = normalize(focal * forward + (x - width/2) * right +
    /// (height/2 - y) * true_up)`. Positions outside the image give rays
    /// outside the field of view; a NaN or infinite position gives a ray with
    /// a non-finite direction, which every kernel rejects.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let [x, y] = sample.film;
        // A NaN position stays visible as a NaN direction (normalize_or_zero
        // would hide it as a zero one), and a focal length far outside the
        // usual range (whose squared length overflows) still gives a unit
        // direction. (by_components: so that a loop of rays vectorises.)
        Ray::new(by_components(self.eye), unit(self.film(x, y)))
    }

    /// The ray through raster position `(x, y)`, bit for bit
    /// [`ray(x, y)`](PinholeCamera::ray), with its differentials: the
    /// origin does not move, and with `p` the unnormalised direction
    /// (`dir = p / |p|`, `dp/dx = right`, `dp/dy = -true_up`),
    ///
    /// `dx_dir = (right - dir (dx / |p|)) / |p|`,
    /// `dy_dir = (dir (dy / |p|) - true_up) / |p|`,
    ///
    /// the derivatives of the unit direction (`1 / |p|` is the factor the
    /// normalisation used; `(dx, dy)` the offsets from the image centre,
    /// `p . right / |p|` and `p . true_up / |p|` for an orthonormal basis,
    /// which saves two dot products). `|p| >= focal_length` up to the
    /// basis's rounding, so each is at most `1 / focal_length` long: a
    /// pixel's angle.
    ///
    /// Bounds. Second order: with `dp/dx` of length 1, the unit direction's
    /// second derivative is at most `4 / |p|^2` long (its three terms are
    /// `2 (p . p') p' / |p|^4`, `p |p'|^2 / |p|^3` and `3 p (p . p')^2 /
    /// |p|^5`, the last two along `p` and of opposite signs), so
    /// `ray(x + 1, y).dir` is within `2 / (|p| - 1)^2 <= 2 / (focal_length -
    /// 1)^2` (roughly) of `dir + dx_dir`, and likewise for `y`. Rounding:
    /// `dx_dir` and `dy_dir` are within
    /// [`ray_differential_error`](PinholeCamera::ray_differential_error)
    /// of the exact derivatives at the camera's (rounded) basis and the
    /// given position. A NaN or infinite position gives NaN
    /// differentials, as it gives a NaN direction.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let [x, y] = sample.film;
        let (dx, dy) = centred(x, y, self.width, self.height);
        let (dir, inv) = unit_and_inverse_length(self.film_at((dx, dy)));
        let (r, u) = (self.right, self.up);
        RayDifferential {
            ray: Ray::new(by_components(self.eye), dir),
            dx_origin: zero_vector(),
            dx_dir: (r - dir * (dx * inv)) * inv,
            dy_origin: zero_vector(),
            dy_dir: (dir * (dy * inv) - u) * inv,
        }
    }

    /// The ray cone of every ray: zero width at the eye, and the spread
    /// angle `atan(1 / focal_length)` (the chapter's `atan(2 tan(fov_y / 2)
    /// / height)`), the angle the centre pixel subtends, to first order.
    ///
    /// The arctangent is the crate's own (its error derived in the
    /// source): within `2 pi gamma(12)` radians in `f32` and `2 pi
    /// gamma(24)` in `f64`.
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        let tau = S::<V>::from_f64(core::f64::consts::TAU);
        RayCone {
            width: S::<V>::ZERO,
            spread: atan2_turns(S::<V>::ONE, self.focal_length) * tau,
        }
    }

    super::film_size!();
}
