//! The equal-area panoramic camera: Clarberg's octahedral mapping of the
//! square onto the sphere.

use glam::Vec3;

use super::{
    Basis, Camera, CameraError, CameraSample, RayCone, RayDifferential, bound_from_f64,
    by_components, centred, direction_angle, on_film, zero_vector,
};
use crate::num::trig::{atan_n, atan2_turns, sin_cos_quadrant};
use crate::num::{Bits, Repr, S, Scalar, Vector, unit_near};
use crate::ray::Ray;

/// An equal-area panoramic camera: the whole sphere of directions around
/// the eye on a square-like image in which every pixel covers the same
/// solid angle, `4 pi / (width height)` steradians, with low distortion
/// (Clarberg, "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD",
/// Journal of Graphics Tools 13(3), 2008; pbrt-v4's
/// `EqualAreaSquareToSphere`). For environment maps that are sampled by
/// area, and for captures where no direction should be favoured.
///
/// Raster conventions and basis as [`PinholeCamera`](crate::PinholeCamera).
/// The image is the square `[-1, 1]^2` (`u = 2x / width - 1` to the right,
/// `v = 1 - 2y / height` up, so a non-square image stretches it) folded
/// onto an octahedron: the diamond `|u| + |v| <= 1` is the hemisphere in
/// front (its centre the view direction, `u` towards `right`, `v` towards
/// `true_up`), the four corners the hemisphere behind (the corners meet at
/// the direction straight back). With `r` the distance from the centre in
/// the diamond's own measure (`|u| + |v|` in front, `2 - |u| - |v|`
/// behind) and `phi` the angle around, a quarter turn per quadrant, the
/// direction is `(cos phi r sqrt(2 - r^2), sin phi r sqrt(2 - r^2), +-(1 -
/// r^2))` in `(right, true_up, forward)`, with the signs of `u` and `v` on
/// the first two, normalised.
///
/// The sines and cosines are the crate's own (angles in turns, exact
/// reduction), `r` is computed without cancellation near either pole (in
/// front from `|u| + |v|`, behind from `(1 - |u|) + (1 - |v|)`, each
/// difference exact), so the direction is known to a few ulps everywhere.
/// Its squared length is therefore already 1 within about `210 u`, and one
/// Newton step brings it to unit length, with no square root or division:
/// unit within `4 u`.
///
/// ```
/// use rayhit::{Camera, CameraSample, camera::EqualAreaCamera, glam::Vec3};
/// let cam = EqualAreaCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 256, 256).unwrap();
/// // The centre looks ahead, the middle of the right edge to the right
/// // (the diamond's corner), a corner of the image straight back.
/// assert!((cam.ray(CameraSample::new(128.0, 128.0)).dir - -Vec3::Z).length() < 1e-6);
/// assert!((cam.ray(CameraSample::new(256.0, 128.0)).dir - Vec3::X).length() < 1e-6);
/// // Halfway to the right edge (r = 1/2), the cosine to the view is 1 - r^2:
/// // the cap within it is 1/8 of the sphere, as the diamond |u| + |v| <= 1/2
/// // is 1/8 of the square.
/// assert!((cam.ray(CameraSample::new(192.0, 128.0)).dir.dot(-Vec3::Z) - 0.75).abs() < 1e-6);
/// assert!((cam.ray(CameraSample::new(0.0, 0.0)).dir - Vec3::Z).length() < 1e-6);
/// // And back.
/// let (x, y) = cam.raster_position(Vec3::new(0.3, -0.2, 0.5)).unwrap();
/// let back = cam.ray(CameraSample::new(x, y)).dir;
/// assert!((back - Vec3::new(0.3, -0.2, 0.5).normalize()).length() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EqualAreaCamera<V = Vec3>
where
    V: Vector,
{
    basis: Basis<V>,
    /// `2 / width` and `2 / height`, rounded.
    scale: (S<V>, S<V>),
    width: u32,
    height: u32,
}

/// The square's coordinates of one raster position, and the octahedral
/// map's quantities there.
struct Square<F> {
    /// `|u|`, `|v|`, and `1 - |u|`, `1 - |v|`.
    au: F,
    av: F,
    cu: F,
    cv: F,
    /// The signs of `u` and `v` (as the sign bits of `dx`, `dy`).
    su: F,
    sv: F,
    /// In front: `|u| + |v| <= 1`.
    front: bool,
    /// The diamond's radius and the angle around, in turns, in `[0, 1/4]`.
    r: F,
    phi: F,
}

impl<V: Vector> EqualAreaCamera<V> {
    /// A camera at `eye` whose image centre looks along `view_dir`, with
    /// `up` giving the upward direction, and an image of `width x height`
    /// pixels (square for square pixels).
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
        let two = S::<V>::TWO;
        Ok(Self {
            basis,
            scale: (
                two / S::<V>::from_u32(width),
                two / S::<V>::from_u32(height),
            ),
            width,
            height,
        })
    }

    /// The square's coordinates of `(x, y)`.
    ///
    /// `|u| = |dx| (2 / width)` and `1 - |u| = (width/2 - |dx|)(2 /
    /// width)`, the difference exact for positions on the half-pixel grid
    /// (both on it, the result smaller), so each is within two roundings,
    /// relative; so is `r` in front (`|u| + |v|`, one more) and behind
    /// (`(1 - |u|) + (1 - |v|)`), and the angle `phi = |v| / (4 r)` turns
    /// in front, `(1 - |u|) / (4 r)` behind (the map's `(pi/4)((|v| -
    /// |u|)/r + 1)`, simplified), within four. At the centre (`r = 0`)
    /// the angle is 0.
    #[inline(always)]
    fn square(&self, x: S<V>, y: S<V>) -> Square<S<V>> {
        let (dx, dy) = centred(x, y, self.width, self.height);
        let (kx, ky) = self.scale;
        let half = S::<V>::HALF;
        // Outside the image: its edge (a NaN stays NaN).
        let (hw, hh) = (
            S::<V>::from_u32(self.width) * half,
            S::<V>::from_u32(self.height) * half,
        );
        let clamp = |a: S<V>, m: S<V>| if a > m { m } else { a };
        let (adx, ady) = (clamp(dx.abs(), hw), clamp(dy.abs(), hh));
        let (au, av) = (adx * kx, ady * ky);
        let (cu, cv) = ((hw - adx) * kx, (hh - ady) * ky);
        let s = au + av;
        let front = s <= S::<V>::ONE;
        let r = if front { s } else { cu + cv };
        let along = if front { av } else { cu };
        let quarter = S::<V>::from_f64(0.25);
        let phi = if r == S::<V>::ZERO {
            S::<V>::ZERO
        } else {
            along / r * quarter
        };
        Square {
            au,
            av,
            cu,
            cv,
            su: <S<V> as Repr>::Bits::copysign(S::<V>::ONE, dx),
            sv: <S<V> as Repr>::Bits::copysign(S::<V>::ONE, dy),
            front,
            r,
            phi,
        }
    }

    /// The unnormalised direction of a square point, and `sin phi`, `cos
    /// phi` and `r sqrt(2 - r^2)`.
    #[inline(always)]
    fn local(&self, q: &Square<S<V>>) -> (V, S<V>, S<V>, S<V>) {
        let (sin, cos) = sin_cos_quadrant(q.phi);
        let r2 = q.r * q.r;
        let ring = q.r * (S::<V>::TWO - r2).sqrt();
        let z = S::<V>::ONE - r2;
        let b = &self.basis;
        let z = if q.front { z } else { -z };
        let dir = b.right * (q.su * cos * ring) + b.up * (q.sv * sin * ring) + b.forward * z;
        (dir, sin, cos, ring)
    }

    /// The raster position whose ray has the direction of `dir` (any
    /// length): the inverse of [`ray`](Self::ray), in `[0, width] x [0,
    /// height]`; `None` for a zero or non-finite `dir`.
    ///
    /// With `(a, b, c)` the components along `right`, `true_up` and
    /// `forward` and `n` their length: `r = sqrt(1 - |c|/n)`, computed as
    /// `sqrt((a^2 + b^2) / (n (n + |c|)))` (no cancellation at the pole),
    /// the angle `atan(min/max)` of `|a|, |b|` (the crate's arctangent), and
    /// pbrt-v4's `EqualAreaSphereToSquare` from there. Round trip:
    /// `raster_position(ray(x, y).dir)` is `(x, y)` (or, within that much
    /// of the image's edge, its mirror image across the centre line: the
    /// square's edges fold onto each other) within
    /// [`raster_position_error`](Self::raster_position_error).
    #[must_use]
    pub fn raster_position(&self, dir: V) -> Option<(S<V>, S<V>)> {
        let (a, bb, c) = self.basis.local(dir)?;
        let local = V::new(a, bb, c);
        let n = local.length();
        let (ax, ay, az) = (a.abs(), bb.abs(), c.abs());
        let r = ((ax * ax + ay * ay) / (n * (n + az))).sqrt();
        let (lo, hi) = if ax < ay { (ax, ay) } else { (ay, ax) };
        // atan(lo / hi) / (pi / 2), in [0, 1/2]: four times the turns.
        let mut phi = atan2_turns(lo, hi) * S::<V>::from_u32(4);
        if ax < ay {
            phi = S::<V>::ONE - phi;
        }
        let mut v = phi * r;
        let mut u = r - v;
        if c < S::<V>::ZERO {
            (u, v) = (S::<V>::ONE - v, S::<V>::ONE - u);
        }
        let u = <S<V> as Repr>::Bits::copysign(u, a);
        let v = <S<V> as Repr>::Bits::copysign(v, bb);
        let half = S::<V>::HALF;
        let (w, h) = (S::<V>::from_u32(self.width), S::<V>::from_u32(self.height));
        Some((w * half + u * (w * half), h * half - v * (h * half)))
    }

    /// The bound on the round trip at `(x, y)`, in pixels, `(across,
    /// down)`: for a position in the image, `raster_position(ray(x,
    /// y).dir)` is within it of `(x, y)` or, that close to the image's
    /// edge, of its mirror image across the centre line (the square's
    /// edges fold onto each other). The same everywhere in the image (about
    /// `225 u` of the width and of the height in `f32`, `313 u` in `f64`);
    /// infinite outside it.
    ///
    /// Derivation. Forward: the angle `phi` is `p / (4 r)` turns from
    /// values within three roundings each, so within `gamma(7) / 4` turns,
    /// which moves the direction by at most `2 pi gamma(7) / 4` (radians,
    /// times the distance from the axis, at most 1); `r sqrt(2 - r^2)` and
    /// `1 - r^2` add `3 gamma(10)`; and the direction is within the
    /// equirectangular camera's `theta` of the exact one of its values
    /// (see [`EquirectangularCamera::raster_position_error`]). Inverse: `r`
    /// of a direction `psi` from the view has `dr/dpsi = sqrt(2 - r^2) / 2
    /// <= 1 / sqrt(2)` and is computed within `gamma(5)`, relative; the
    /// angle's part of the square's coordinates, `phi' r` with `phi' = phi
    /// / (pi/2)`, moves by at most `(2 / pi) theta' / sqrt(2 - r^2) <= (2
    /// / pi) theta'`, plus `4 gamma(A)` (the arctangent's turns times four)
    /// and three roundings (`v = phi' r`, `u = r - v`, `1 - u`). So each
    /// square coordinate is within `(2/pi + 1/sqrt(2)) theta' + gamma(5) +
    /// 4 gamma(A) + 3 u`, and the pixels within `w/2` (or `h/2`) times that
    /// plus two roundings. Evaluated in `f64` and rounded up; held to in
    /// exact arithmetic by the test kit's panorama checks.
    ///
    /// [`EquirectangularCamera::raster_position_error`]: super::EquirectangularCamera::raster_position_error
    ///
    /// ```
    /// use rayhit::{Camera, CameraSample, camera::EqualAreaCamera, glam::Vec3};
    /// let cam = EqualAreaCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 2048, 2048).unwrap();
    /// let (x, y) = (300.25, 1700.5);
    /// let (bx, by) = cam.raster_position_error(x, y);
    /// let (rx, ry) = cam.raster_position(cam.ray(CameraSample::new(x, y)).dir).unwrap();
    /// assert!((rx - x).abs() <= bx && (ry - y).abs() <= by);
    /// assert!(bx < 0.03); // 225 u of 2048 pixels
    /// ```
    #[must_use]
    pub fn raster_position_error(&self, x: S<V>, y: S<V>) -> (S<V>, S<V>) {
        let inf = S::<V>::INFINITY;
        let Some([_, _, w, h]) = on_film(x, y, self.width, self.height) else {
            return (inf, inf);
        };
        let g = |n: u32| S::<V>::gamma_n(n).to_f64();
        let u = S::<V>::UNIT_ROUNDOFF.to_f64();
        let a = atan_n::<S<V>>();
        let theta = direction_angle::<S<V>>(self.basis.skew())
            + 3.0 * g(10)
            + core::f64::consts::TAU * g(7) / 4.0;
        let square =
            (2.0 / core::f64::consts::PI + 0.5f64.sqrt()) * theta + g(5) + 4.0 * g(a) + 3.0 * u;
        let px = |n: f64| bound_from_f64(n / 2.0 * square + 2.0 * u * n);
        (px(w), px(h))
    }

    super::basis_accessors!();
}

impl<V: Vector> Camera<V> for EqualAreaCamera<V> {
    /// The ray through raster position `(x, y)`: from the eye along the
    /// octahedral map's direction (see [`EqualAreaCamera`]), normalised.
    ///
    /// Positions outside the image give the direction of the nearest point
    /// of its edge (each coordinate clamped, infinities included); a NaN
    /// position gives a NaN direction, which every kernel rejects.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let [x, y] = sample.film;
        let (dir, ..) = self.local(&self.square(x, y));
        Ray::new(by_components(self.basis.eye), unit_near(dir))
    }

    /// The ray through `(x, y)`, bit for bit [`ray`](Self::ray), with its
    /// differentials: the origin does not move, and the direction's
    /// derivatives are those of the map in the face of the octahedron the
    /// position is on (at the image's edge for a position outside it, where
    /// the map is clamped; the map is smooth inside each of the eight
    /// triangles the image's centre lines and the diamond cut it into; on
    /// those lines, the one-sided derivative of the side the position is
    /// on, `+0` counting as positive and the diamond as in front; at the
    /// centre, the derivative along each axis).
    ///
    /// With `S(r) = r sqrt(2 - r^2)`, `S' = 2 (1 - r^2) / sqrt(2 - r^2)`,
    /// `phi = (pi/2) p / r` (`p` being `|v|` in front, `1 - |u|` behind) and
    /// `sigma = 1` in front, `-1` behind (`dr/d|u| = dr/d|v| = sigma`):
    ///
    /// `d/d|u| = (sigma cos(phi) S' + sin(phi) sqrt(2 - r^2) (pi/2) q / r,
    ///            sigma sin(phi) S' - cos(phi) sqrt(2 - r^2) (pi/2) q / r,
    ///            -2 r)` with `q = |v|` in front and `1 - |v|` behind,
    /// `d/d|v| = (sigma cos(phi) S' - sin(phi) sqrt(2 - r^2) (pi/2) p' / r,
    ///            sigma sin(phi) S' + cos(phi) sqrt(2 - r^2) (pi/2) p' / r,
    ///            -2 r)` with `p' = |u|` in front and `1 - |u|` behind,
    ///
    /// in `(right, true_up, forward)` with the signs of `u` and `v` on the
    /// first two components, and `du/dx = 2 / width`, `dv/dy = -2 /
    /// height`. The factors `q / r` and `p' / r` are at most 1, so the
    /// derivatives stay bounded at the poles (each at most `sqrt(2) pi`
    /// times `2 / width` or `2 / height` long). They are the derivatives
    /// of the exact map's unnormalised direction, whose length is 1.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let [x, y] = sample.film;
        let q = self.square(x, y);
        let (dir, sin, cos, _) = self.local(&q);
        let one = S::<V>::ONE;
        let zero = S::<V>::ZERO;
        let r = q.r;
        let sigma = if q.front { one } else { -one };
        let root = (S::<V>::TWO - r * r).sqrt();
        let ds = S::<V>::TWO * (one - r * r) / root;
        let half_pi = S::<V>::from_f64(core::f64::consts::FRAC_PI_2);
        // q / r and p' / r (see the doc), 0 at the centre: there the
        // derivative along u is taken at phi = 0 and along v at phi = pi/2.
        let ratio = |n: S<V>| if r == zero { zero } else { n / r };
        let (qv, pu) = if q.front {
            (ratio(q.av), ratio(q.au))
        } else {
            (ratio(q.cv), ratio(q.cu))
        };
        let (along_u_angle, along_v_angle) = if r == zero {
            ((zero, one), (one, zero))
        } else {
            ((sin, cos), (sin, cos))
        };
        let b = &self.basis;
        let along_u = {
            let (sin, cos) = along_u_angle;
            let turn = root * half_pi * qv;
            b.right * (q.su * (sigma * cos * ds + sin * turn))
                + b.up * (q.sv * (sigma * sin * ds - cos * turn))
                - b.forward * (S::<V>::TWO * r)
        };
        let along_v = {
            let (sin, cos) = along_v_angle;
            let turn = root * half_pi * pu;
            b.right * (q.su * (sigma * cos * ds - sin * turn))
                + b.up * (q.sv * (sigma * sin * ds + cos * turn))
                - b.forward * (S::<V>::TWO * r)
        };
        let (kx, ky) = self.scale;
        RayDifferential {
            ray: Ray::new(by_components(b.eye), unit_near(dir)),
            dx_origin: zero_vector(),
            dx_dir: along_u * (q.su * kx),
            dy_origin: zero_vector(),
            dy_dir: along_v * (-(q.sv * ky)),
        }
    }

    /// The ray cone of every ray: zero width, and the spread angle of a
    /// cone whose solid angle is a pixel's, `4 pi / (width height)`:
    /// `4 / sqrt(width height)` (from `pi spread^2 / 4`, the small cone's
    /// solid angle). Equal area makes it the same for every pixel.
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        let area = S::<V>::from_u32(self.width) * S::<V>::from_u32(self.height);
        RayCone {
            width: S::<V>::ZERO,
            spread: S::<V>::from_u32(4) / area.sqrt(),
        }
    }

    super::film_size!();
}
