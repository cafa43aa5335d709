//! The equirectangular (latitude-longitude) panoramic camera.

use glam::Vec3;

use super::{
    Basis, Camera, CameraError, CameraSample, RayCone, RayDifferential, bound_from_f64,
    by_components, centred, direction_angle, on_film, zero_vector,
};
use crate::num::trig::{atan_n, atan2_turns, sin_cos_turns, trig_n};
use crate::num::{S, Scalar, Vector, unit_near};
use crate::ray::Ray;

/// An equirectangular panoramic camera: the whole sphere of directions
/// around the eye, longitude across the image and latitude down it, as
/// environment maps and 360-degree captures are stored (pbrt's spherical
/// camera, equirectangular mapping).
///
/// Raster conventions as [`PinholeCamera`](crate::PinholeCamera) (`(0, 0)`
/// top-left, `y` down, pixel centres at `i + 0.5`), basis from eye, view and
/// up likewise. Raster `x` maps to the longitude `lon = 2 pi (x / width -
/// 1/2)`, from `-pi` at the left edge through `0` at the centre (straight
/// ahead) to `pi` at the right, increasing to the right; raster `y` to the
/// latitude `lat = pi (1/2 - y / height)`, from `pi/2` (straight up) at
/// the top to `-pi/2` at the bottom. The direction is
///
/// `cos(lat) sin(lon) right + sin(lat) true_up + cos(lat) cos(lon) forward`,
///
/// normalised. The centre of the image looks along the view direction,
/// the middle row is the horizon, and the left and right edges meet
/// behind the eye. A `2:1` image has square pixels at the horizon.
///
/// Angles are taken in turns (`x / width - 1/2` and `(1/2 - y / height) /
/// 2`), whose reduction is exact, and the sines and cosines are the
/// crate's own, within `gamma(26)` (`f32`) or `gamma(42)` (`f64`) of the
/// exact ones; so each component of the unnormalised direction is within
/// `3 gamma(26) + gamma(3)` (a product of two of them, a product with the
/// basis and a sum) of its exact value for the camera's basis. Its squared
/// length is therefore already 1 within about `210 u` (the local
/// components' errors, twice, the basis's departure from orthonormal and
/// the sum's roundings), so one Newton step brings it to unit length, with
/// no square root or division: the returned direction is unit within `4 u`.
///
/// ```
/// use rayhit::{Camera, CameraSample, camera::EquirectangularCamera, glam::Vec3};
/// let cam = EquirectangularCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 360, 180).unwrap();
/// // The centre looks ahead, the top row up, the left edge behind.
/// assert!((cam.ray(CameraSample::new(180.0, 90.0)).dir - -Vec3::Z).length() < 1e-6);
/// assert!((cam.ray(CameraSample::new(180.0, 0.0)).dir - Vec3::Y).length() < 1e-6);
/// assert!((cam.ray(CameraSample::new(0.0, 90.0)).dir - Vec3::Z).length() < 1e-6);
/// // Straight to the right is a quarter of the way from the centre.
/// assert!((cam.ray(CameraSample::new(270.0, 90.0)).dir - Vec3::X).length() < 1e-6);
/// // And back: the direction's raster position.
/// let (x, y) = cam.raster_position(Vec3::new(1.0, 1.0, 0.0)).unwrap();
/// assert!((x - 270.0).abs() < 1e-3 && (y - 45.0).abs() < 1e-3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EquirectangularCamera<V = Vec3>
where
    V: Vector,
{
    basis: Basis<V>,
    /// `1 / width` and `1 / (2 height)`, rounded.
    turns_per_pixel: (S<V>, S<V>),
    width: u32,
    height: u32,
}

impl<V: Vector> EquirectangularCamera<V> {
    /// A camera at `eye` whose image centre looks along `view_dir`, with
    /// `up` giving the upward direction (the image's top row), and an
    /// image of `width x height` pixels.
    ///
    /// # Errors
    ///
    /// As [`PinholeCamera::new`](crate::PinholeCamera::new), without the
    /// focal length.
    pub fn new(eye: V, view_dir: V, up: V, width: u32, height: u32) -> Result<Self, CameraError> {
        let basis = Basis::new(eye, view_dir, up)?;
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        let one = S::<V>::ONE;
        Ok(Self {
            basis,
            turns_per_pixel: (
                one / S::<V>::from_u32(width),
                one / (S::<V>::from_u32(height) * S::<V>::TWO),
            ),
            width,
            height,
        })
    }

    /// The longitude's and latitude's sines and cosines at `(x, y)`:
    /// `((sin lon, cos lon), (sin lat, cos lat))`.
    #[inline(always)]
    fn angles(&self, x: S<V>, y: S<V>) -> [(S<V>, S<V>); 2] {
        let (dx, dy) = centred(x, y, self.width, self.height);
        let (tx, ty) = self.turns_per_pixel;
        [sin_cos_turns(dx * tx), sin_cos_turns(dy * ty)]
    }

    /// The raster position whose ray has the direction of `dir` (any
    /// length): the inverse of [`ray`](Self::ray), `x` in `[0, width]` and
    /// `y` in `[0, height]`; `None` for a zero or non-finite `dir`.
    ///
    /// `lon = atan2(dir . right, dir . forward)` and `lat = atan2(dir .
    /// true_up, |(dir . right, dir . forward)|)`, in turns with the crate's
    /// arctangent (within `gamma(12)` turns in `f32`, `gamma(24)` in
    /// `f64`). Straight up or down (`lon` undefined) gives the centre
    /// column.
    ///
    /// Round trip: `raster_position(ray(x, y).dir)` is `(x, y)`, or the
    /// same direction a turn away in longitude, within
    /// [`raster_position_error`](Self::raster_position_error)`(x, y)`.
    #[must_use]
    pub fn raster_position(&self, dir: V) -> Option<(S<V>, S<V>)> {
        let (a, up, c) = self.basis.local(dir)?;
        let lon = atan2_turns(a, c);
        let horizontal = V::new(a, c, S::<V>::ZERO).length();
        let lat = atan2_turns(up, horizontal);
        let (w, h) = (S::<V>::from_u32(self.width), S::<V>::from_u32(self.height));
        Some((
            w * S::<V>::HALF + lon * w,
            h * S::<V>::HALF - lat * (h * S::<V>::TWO),
        ))
    }

    /// The bound on the round trip at `(x, y)`, in pixels, `(across,
    /// down)`: for a position in the image, `raster_position(ray(x,
    /// y).dir)` is within it of `(x, y)`, or of the same direction a turn
    /// away in longitude. Infinite for positions outside the image, and
    /// across at the poles, where the longitude is undefined.
    ///
    /// `w (theta / (2 pi cos(lat)) + gamma(A) + gamma(2)/2 + 2u)` across
    /// and `2h ((theta + 2u) / (2 pi) + gamma(A) + gamma(2)/4) + 2uh` down,
    /// where `lat = pi (1/2 - y/h)` and `theta` is the direction's angular
    /// error: `3 gamma(2T + 15) + 2 sqrt(3) u + sqrt(3) gamma(3) + 3 skew`,
    /// with `T = 26` and `A = 12` in `f32`, `T = 42` and `A = 24` in `f64`,
    /// and `skew` the basis's departure from orthonormal (the largest entry
    /// of `B^T B - I`, at most `gamma(13)` for every up vector the camera
    /// accepts): about `w (40 u / cos(lat) + 15 u)` and `107 u h` in `f32`,
    /// `w (55 u / cos(lat) + 27 u)` and `161 u h` in `f64`. The longitude
    /// is known to an angle over `cos(lat)`, so the columns crowd near the
    /// poles.
    ///
    /// Derivation. The longitude's turns `fl(dx fl(1 / w))` are within
    /// `gamma(2) |t| <= gamma(2) / 2` turns of `dx / w`, the latitude's
    /// within `gamma(2) / 4`. The direction is within `theta` (radians) of
    /// the exact one of its angles (its terms: the local components, two
    /// sines or cosines and a rounding; the world vector, three roundings
    /// more times the basis's magnitudes; normalising, in the map and again
    /// in the inverse; the inverse's dot products with the basis and the
    /// basis's skew); moving a direction by `theta` moves its longitude by
    /// at most `theta / cos(lat)` and its latitude by `theta`. The
    /// arctangents add `gamma(A)` turns each (the latitude's argument
    /// `hypot` two roundings more, relative: `2 u` radians). Back to
    /// pixels, `x = w/2 + lon w` and `y = h/2 - lat 2h` round twice: `2 u
    /// w` and `2 u h` in the image. `cos(lat)` is taken from below (the
    /// crate's cosine, less its error bound). Evaluated in `f64` and
    /// rounded up; held to in exact arithmetic by the test kit's panorama
    /// checks.
    ///
    /// ```
    /// use rayhit::{Camera, CameraSample, camera::EquirectangularCamera, glam::Vec3};
    /// let cam = EquirectangularCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 3600, 1800).unwrap();
    /// let (x, y) = (1234.5, 456.25);
    /// let (bx, by) = cam.raster_position_error(x, y);
    /// let (rx, ry) = cam.raster_position(cam.ray(CameraSample::new(x, y)).dir).unwrap();
    /// assert!((rx - x).abs() <= bx && (ry - y).abs() <= by);
    /// assert!(bx < 0.02 && by < 0.05); // hundredths of a pixel in f32
    /// ```
    #[must_use]
    pub fn raster_position_error(&self, x: S<V>, y: S<V>) -> (S<V>, S<V>) {
        let inf = S::<V>::INFINITY;
        let Some([_, y, w, h]) = on_film(x, y, self.width, self.height) else {
            return (inf, inf);
        };
        let g = |n: u32| S::<V>::gamma_n(n).to_f64();
        let u = S::<V>::UNIT_ROUNDOFF.to_f64();
        let a = atan_n::<S<V>>();
        let tau = core::f64::consts::TAU;
        let theta = direction_angle::<S<V>>(self.basis.skew());
        // cos(lat) from below: the cosine's `gamma(T)` absolute bound in
        // `f64`, and the argument's two roundings (below `1e-16` turns).
        let (_, cos) = sin_cos_turns::<f64>((0.5 - y / h) / 2.0);
        let t64 = trig_n::<f64>() + 2;
        let cos = cos - f64::gamma_n(t64) - 1e-15;
        let across = if cos > 0.0 {
            w * (theta / (tau * cos) + g(a) + g(2) / 2.0) + 2.0 * u * w
        } else {
            f64::INFINITY
        };
        let down = 2.0 * h * ((theta + 2.0 * u) / tau + g(a) + g(2) / 4.0) + 2.0 * u * h;
        (bound_from_f64(across), bound_from_f64(down))
    }

    super::basis_accessors!();
}

impl<V: Vector> Camera<V> for EquirectangularCamera<V> {
    /// The ray through raster position `(x, y)`: from the eye, along the
    /// unit direction of longitude `2 pi (x / width - 1/2)` and latitude
    /// `pi (1/2 - y / height)` (see [`EquirectangularCamera`]).
    ///
    /// Positions outside the image wrap around in longitude and go over
    /// the pole in latitude (the formula is periodic); a NaN or infinite
    /// position gives a NaN direction, which every kernel rejects.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let [x, y] = sample.film;
        let [(sl, cl), (sa, ca)] = self.angles(x, y);
        let b = &self.basis;
        let dir = b.right * (ca * sl) + b.up * sa + b.forward * (ca * cl);
        Ray::new(by_components(b.eye), unit_near(dir))
    }

    /// The ray through `(x, y)`, bit for bit [`ray`](Self::ray), with its
    /// differentials: the origin does not move, and the direction's
    /// derivatives are
    ///
    /// `dx_dir = (2 pi / width) cos(lat) (cos(lon) right - sin(lon) forward)`,
    /// `dy_dir = (pi / height) (sin(lat) (sin(lon) right + cos(lon) forward) - cos(lat) true_up)`,
    ///
    /// those of the exact mapping before normalising (the normalisation
    /// changes them by as much as the basis departs from orthonormal, a
    /// few roundings). Second order: the mapping's second derivatives in
    /// longitude and latitude are at most 1 long, so the rays of `(x + 1,
    /// y)` and `(x, y + 1)` are within `(2 pi / width)^2 / 2` and `(pi /
    /// height)^2 / 2` of `dir + dx_dir` and `dir + dy_dir`, plus rounding.
    /// Near the poles a pixel spans little longitude: `dx_dir` shrinks with
    /// `cos(lat)`.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let [x, y] = sample.film;
        let [(sl, cl), (sa, ca)] = self.angles(x, y);
        let b = &self.basis;
        let dir = unit_near(b.right * (ca * sl) + b.up * sa + b.forward * (ca * cl));
        let tau = S::<V>::from_f64(core::f64::consts::TAU);
        let (kx, ky) = (
            tau / S::<V>::from_u32(self.width),
            S::<V>::PI / S::<V>::from_u32(self.height),
        );
        RayDifferential {
            ray: Ray::new(by_components(b.eye), dir),
            dx_origin: zero_vector(),
            dx_dir: (b.right * cl - b.forward * sl) * (ca * kx),
            dy_origin: zero_vector(),
            dy_dir: ((b.right * sl + b.forward * cl) * sa - b.up * ca) * ky,
        }
    }

    /// The ray cone of every ray: zero width, and the spread angle of a
    /// pixel at the horizon, the larger of `2 pi / width` and `pi /
    /// height` (towards the poles a pixel spans less longitude, and the
    /// cone errs on the wide side).
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        let tau = S::<V>::from_f64(core::f64::consts::TAU);
        let across = tau / S::<V>::from_u32(self.width);
        let down = S::<V>::PI / S::<V>::from_u32(self.height);
        RayCone {
            width: S::<V>::ZERO,
            spread: if across > down { across } else { down },
        }
    }

    super::film_size!();
}
