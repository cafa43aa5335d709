//! The thin-lens camera: a pinhole camera with a lens of some radius,
//! focused at some distance, for depth of field.

use glam::Vec3;

use super::{
    Camera, CameraError, CameraSample, PinholeCamera, RayCone, RayDifferential, zero_vector,
};
use crate::num::round::{bound_up, max2};
use crate::num::trig::{sin_cos_quarter, trig_n};
use crate::num::{Bits, Repr};
use crate::num::{S, Scalar, Vector};
use crate::ray::Ray;

/// A thin-lens camera: the rays of one film point start on a lens disc and
/// all pass through one focus point on the plane of focus, so that what
/// lies there is sharp and the rest is blurred (depth of field).
///
/// The model is pbrt's perspective camera with a lens: a
/// [`PinholeCamera`] (the film, the conventions, the field of view), a
/// lens of radius `lens_radius` centred on the eye in the plane spanned by
/// `right` and `true_up`, and a plane of focus `focal_distance` in front of
/// the eye along the view direction. A lens sample `(s, t)` in `[0, 1)^2`
/// becomes a point of the lens disc by Shirley and Chiu's concentric
/// mapping ("A Low Distortion Map Between Disk and Square", Journal of
/// Graphics Tools 2(3), 1997), which keeps stratified samples stratified.
///
/// **The focus point.** [`focus(x, y)`](ThinLensCamera::focus) is computed
/// once per film point: `eye + focal_distance forward + k ((x - w/2) right
/// + (h/2 - y) true_up)` with `k = focal_distance / focal_length`, which is
/// `eye + k p` for `p` the pinhole camera's unnormalised direction towards
/// `(x, y)`, so it lies on the pinhole ray and on the plane of focus
/// (within rounding). The
/// ray of lens point `L` starts at `L` and has direction `F - L`: it
/// reaches the focus point `F` at `t = 1`.
///
/// **Meeting bit for bit.** Every ray of one film point passes through
/// the same float point `F`, exactly: in exact arithmetic, `origin + 1 *
/// dir = F`, and in floating point, `ray.at(1.0) == F` bit for bit. That
/// takes more than `F - L` rounded (whose rounding error moves the ray off
/// `F`, by up to half an ulp of `F - L`, which is far more than an ulp of
/// `F` where `|F_i|` is small next to `|L_i|`): per component, `F` and
/// every lens point are rounded to one grid, the multiples of
/// `g_i = 2^(e_i + 3 - p)` (`p` the precision, `2^e_i` the binade of
/// `max(|F_i|, M_i)`, `M_i` a bound on the lens points' `|L_i|`), on which
/// `F_i - L_i` is a float. So the focus point and the lens points move by
/// at most `g_i / 2`, two ulps of the larger of the focus point's and the
/// lens's coordinates. This holds for lens samples in `[0, 1]^2` and
/// coordinates below `MAX / 8`; beyond, the rays meet only within a
/// rounding. The rays are finite wherever the focus point is (a position
/// so far outside the image that it overflows gives a non-finite
/// direction, which every kernel rejects).
///
/// **The lens centre.** A lens sample that maps to the lens centre (`(0.5,
/// 0.5)`, or any sample when `lens_radius` is zero) gives the pinhole ray,
/// [`PinholeCamera::ray`], bit for bit: origin the eye, a unit direction.
/// It passes within a rounding of `F` (both lie on the pinhole ray), not
/// through it; a zero radius makes the camera the pinhole camera, bit for
/// bit.
///
/// Directions are not unit length (`|dir|` is the distance to the focus
/// point); `t` is in units of `dir` as for every ray.
///
/// ```
/// use rayhit::{Camera, CameraSample, PinholeCamera, camera::ThinLensCamera, glam::Vec3};
/// let pinhole = PinholeCamera::from_fov(Vec3::new(0.0, 1.0, 5.0), -Vec3::Z, Vec3::Y, 0.7, 320, 240).unwrap();
/// // A lens of radius 0.1, focused 5 units ahead.
/// let cam = ThinLensCamera::new(pinhole, 0.1, 5.0).unwrap();
/// let focus = cam.focus(100.5, 80.5);
/// for (s, t) in [(0.1, 0.2), (0.9, 0.35), (0.5, 0.99)] {
///     let ray = cam.ray_through(&focus, s, t);
///     // Every ray of the film point reaches the focus point at t = 1, bit for bit.
///     assert_eq!(ray.at(1.0), focus.point());
/// }
/// // The lens centre gives the pinhole ray.
/// assert_eq!(cam.ray(CameraSample::new(100.5, 80.5).with_lens(0.5, 0.5)), pinhole.ray(CameraSample::new(100.5, 80.5)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinLensCamera<V = Vec3>
where
    V: Vector,
{
    pinhole: PinholeCamera<V>,
    lens_radius: S<V>,
    focal_distance: S<V>,
    /// `focal_distance / focal_length`: world units per pixel on the plane
    /// of focus.
    scale: S<V>,
    /// `eye + focal_distance forward`: the centre of the plane of focus.
    centre: V,
    /// Per component, a bound on `|L_i|` for every lens point.
    lens_bound: V,
}

/// The focus point of one film point, with what its rays need: see
/// [`ThinLensCamera::focus`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FocusPoint<V = Vec3>
where
    V: Vector,
{
    point: V,
    /// Per component, `1.5 * 2^(e_i + 2)`: adding and subtracting it
    /// rounds to the grid (zero where no rounding is needed or possible).
    grid: V,
    /// The raster position, for the pinhole ray at the lens centre.
    raster: (S<V>, S<V>),
}

impl<V: Vector> FocusPoint<V> {
    /// The focus point: where every ray of the film point is at `t = 1`.
    #[inline]
    #[must_use]
    pub fn point(&self) -> V {
        self.point
    }
}

/// A lens sample `(s, t)` in `[0, 1]^2` as a point of the unit disc,
/// Shirley and Chiu's concentric mapping: the square `[-1, 1]^2` (`a = 2s
/// - 1`, `b = 2t - 1`) is cut into four triangles by its diagonals, and each
/// triangle's concentric squares go to concentric circles: for `|a| > |b|`
/// the radius is `a` and the angle `(pi/4)(b/a)`, else the radius `b` and
/// the angle `pi/2 - (pi/4)(a/b)`. `(0, 0)` for the centre.
///
/// Each coordinate is within `|radius| gamma(TRIG + 4)` of the exact map of
/// the rounded `a`, `b` (`TRIG` is 24 in `f32` and 40 in `f64`: the sine's
/// and cosine's bound; then the ratio's rounding, which moves the angle by
/// at most `(pi/4) u`, and the product's: two more would do), so the point
/// is in the disc to that much; the rounding of `2s - 1` is at most one,
/// relative. The angle is passed as `q/2` quarter turns, exactly.
#[inline(always)]
fn concentric_disc<F: Scalar>(s: F, t: F) -> (F, F) {
    let (zero, one) = (F::ZERO, F::ONE);
    let a = s * F::TWO - one;
    let b = t * F::TWO - one;
    // Selects, not branches: which triangle a sample falls in is a coin
    // toss, and a loop of rays vectorises only without branches.
    let wide = a.abs() > b.abs();
    let (r, n) = if wide { (a, b) } else { (b, a) };
    // At the centre (r = 0, so n = 0 too) the angle 0: the point (0, 0).
    let q = n / if r == zero { one } else { r };
    // (pi/4) q radians are q/2 quarter turns (exact).
    let (sin, cos) = sin_cos_quarter(q * F::HALF);
    let (x, y) = (r * cos, r * sin);
    if wide { (x, y) } else { (y, x) }
}

/// The constant that rounds a coordinate to the grid of [`FocusPoint`]:
/// `c = 6 * 2^e` with `2^e` the binade of `max(|focus|, bound)`.
///
/// Every value `x` with `|x| < 2^(e+1)` (the focus point's coordinate and
/// every lens point's) has `x + c` in `(4 * 2^e, 8 * 2^e)`, one binade,
/// whose floats are the multiples of `g = 2^(e + 3 - p)`: so `(x + c) - c`
/// is `x` rounded to a multiple of `g` (the subtraction is exact,
/// Sterbenz). Two such values differ by less than `2^(e+2) + g < 2^p g`, a
/// multiple of `g` that is a float: their difference is exact. Zero when the
/// larger value is zero or subnormal (then every such difference is exact
/// already: subnormal sums are) or above `MAX / 8` (where `c` would
/// overflow; no rounding, and no exactness).
#[inline(always)]
fn grid<F: Scalar>(focus: F, bound: F) -> F {
    let binade = <F as Repr>::Bits::binade(max2(focus.abs(), bound));
    if binade <= F::MAX * F::from_f64(0.125) {
        binade * F::from_u32(6)
    } else {
        F::ZERO
    }
}

/// `x` rounded to the grid of `c` (see [`grid`]).
#[inline(always)]
fn snap<F: Scalar>(x: F, c: F) -> F {
    (x + c) - c
}

impl<V: Vector> ThinLensCamera<V> {
    /// The pinhole camera `pinhole` with a lens of radius `lens_radius`
    /// (world units) focused at `focal_distance` (world units in front of
    /// the eye, along the view direction).
    ///
    /// # Errors
    ///
    /// [`CameraError::InvalidLensRadius`] for a negative, NaN or infinite
    /// radius, or one so large that the lens's coordinates overflow;
    /// [`CameraError::InvalidFocalDistance`] for a focal distance that is
    /// not positive and finite, or whose ratio to the focal length
    /// underflows to zero or overflows. A zero radius is the pinhole camera.
    ///
    /// ```
    /// use rayhit::{PinholeCamera, camera::{CameraError, ThinLensCamera}, glam::Vec3};
    /// let pinhole = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 100.0, 64, 64).unwrap();
    /// assert_eq!(ThinLensCamera::new(pinhole, -0.1, 5.0), Err(CameraError::InvalidLensRadius));
    /// assert_eq!(ThinLensCamera::new(pinhole, 0.1, 0.0), Err(CameraError::InvalidFocalDistance));
    /// ```
    pub fn new(
        pinhole: PinholeCamera<V>,
        lens_radius: S<V>,
        focal_distance: S<V>,
    ) -> Result<Self, CameraError> {
        let zero = S::<V>::ZERO;
        if !(lens_radius >= zero && lens_radius.is_finite()) {
            return Err(CameraError::InvalidLensRadius);
        }
        if !(focal_distance > zero && focal_distance.is_finite()) {
            return Err(CameraError::InvalidFocalDistance);
        }
        let scale = focal_distance / pinhole.focal_length();
        if !(scale > zero && scale.is_finite()) {
            return Err(CameraError::InvalidFocalDistance);
        }
        // A lens point is eye + right (radius x) + up (radius y), with
        // |x|, |y| <= 1 + gamma(TRIG + 4) (concentric_disc): each product
        // and sum rounds once (four roundings along the longest path), so
        // |L_i| <= (|eye_i| + radius (|right_i| + |up_i|)(1 + gamma(TRIG +
        // 4))) (1 + gamma(4)), which bound_up makes an upper bound after
        // its own roundings (at most five here).
        let slack = S::<V>::ONE + S::<V>::gamma_n(trig_n::<S<V>>() + 4);
        let (eye, r, u) = (pinhole.eye(), pinhole.right(), pinhole.up());
        let bound = |i: usize| {
            let reach = lens_radius * (r[i].abs() + u[i].abs()) * slack;
            bound_up(
                (eye[i].abs() + reach) * (S::<V>::ONE + S::<V>::gamma_n(4)),
                5,
            )
        };
        let lens_bound = V::new(bound(0), bound(1), bound(2));
        if !lens_bound.is_finite() {
            return Err(CameraError::InvalidLensRadius);
        }
        Ok(Self {
            pinhole,
            lens_radius,
            focal_distance,
            scale,
            centre: pinhole.eye() + pinhole.forward() * focal_distance,
            lens_bound,
        })
    }

    /// The focus point of raster position `(x, y)`, computed once for all
    /// its lens samples: `(eye + focal_distance forward) + (right (dx k) +
    /// true_up (dy k))` with `k = focal_distance / focal_length` and `(dx,
    /// dy)` the offsets from the image centre (`eye + k p`, `p` the pinhole
    /// camera's unnormalised direction), rounded to the grid on which every
    /// lens point's difference from it is exact (see [`ThinLensCamera`]).
    ///
    /// It lies on the plane of focus and on the pinhole ray of `(x, y)`,
    /// within [`focus_error`](Self::focus_error). A NaN or infinite
    /// position gives a NaN point.
    #[inline(always)]
    #[must_use]
    pub fn focus(&self, x: S<V>, y: S<V>) -> FocusPoint<V> {
        let (dx, dy) = super::centred(x, y, self.pinhole.width(), self.pinhole.height());
        let k = self.scale;
        let f = self.centre + (self.pinhole.right() * (dx * k) + self.pinhole.up() * (dy * k));
        let m = self.lens_bound;
        let grid = V::new(grid(f.x(), m.x()), grid(f.y(), m.y()), grid(f.z(), m.z()));
        FocusPoint {
            point: V::new(
                snap(f.x(), grid.x()),
                snap(f.y(), grid.y()),
                snap(f.z(), grid.z()),
            ),
            grid,
            raster: (x, y),
        }
    }

    /// A per-component bound on the distance of [`focus`](Self::focus)`(x,
    /// y)` from the exact point it stands for, `eye + focal_distance
    /// forward + k (dx right + dy true_up)` with `k = focal_distance /
    /// focal_length` exactly, for the camera's (rounded) basis and offsets
    /// `(dx, dy)` from the image centre. Infinite for a NaN or infinite
    /// position.
    ///
    /// `gamma(5) (|eye_i| + focal_distance |forward_i| + k |dx right_i| + k
    /// |dy up_i|) + 4u max(|F_i|, M_i) (1 + 8u)`, with `F` the focus point
    /// and `M` the lens's reach (`|eye_i| + radius (|right_i| + |up_i|)`,
    /// rounded up). Derivation: the plane's centre `fl(eye +
    /// fl(focal_distance forward))` is computed once (two roundings),
    /// `fl(dx fl(k))` and `fl(dy fl(k))` (two each), their products with
    /// `right` and `up` (one each), the sum of those (one) and the sum with
    /// the centre (one): along the longest path five roundings, so each
    /// component is within the first term of the exact value. The grid then
    /// moves it by at most `2^(e + 2 - p) = 4u 2^e <= 4u max(|F'_i|, M_i)`
    /// (`F'` before the grid, within `8u` of `F`: see `grid`). The terms
    /// are evaluated in the camera's precision, with `k` taken from above
    /// and the result rounded up; held to in exact arithmetic by the test
    /// kit's thin-lens checks.
    ///
    /// ```
    /// use rayhit::{PinholeCamera, camera::ThinLensCamera, glam::Vec3};
    /// let pinhole = PinholeCamera::from_fov(Vec3::new(0.0, 1.0, 5.0), -Vec3::Z, Vec3::Y, 0.7, 320, 240).unwrap();
    /// let cam = ThinLensCamera::new(pinhole, 0.1, 5.0).unwrap();
    /// let err = cam.focus_error(100.5, 80.5);
    /// // A few ulps of coordinates of about 5.
    /// assert!(err.max_element() < 2e-5);
    /// ```
    #[must_use]
    pub fn focus_error(&self, x: S<V>, y: S<V>) -> V {
        use crate::num::round::outward::{add_up, mul_up};
        let p = &self.pinhole;
        let (dx, dy) = super::centred(x, y, p.width(), p.height());
        let f = self.focus(x, y).point;
        if !(dx.is_finite() && dy.is_finite() && f.is_finite()) {
            return V::splat(S::<V>::INFINITY);
        }
        let u = S::<V>::UNIT_ROUNDOFF;
        // The exact k is within one rounding of `scale`.
        let k = mul_up(self.scale, S::<V>::ONE + u + u);
        let (g5, u4, grow) = (
            S::<V>::gamma_n(5).next_up(),
            u * S::<V>::from_u32(4),
            (S::<V>::ONE + u * S::<V>::from_u32(8)).next_up(),
        );
        let (eye, fwd, right, up) = (p.eye(), p.forward(), p.right(), p.up());
        let component = |i: usize| {
            let m = add_up(
                add_up(eye[i].abs(), mul_up(self.focal_distance, fwd[i].abs())),
                mul_up(
                    k,
                    add_up(
                        mul_up(dx.abs(), right[i].abs()),
                        mul_up(dy.abs(), up[i].abs()),
                    ),
                ),
            );
            let big = max2(mul_up(f[i].abs(), grow), self.lens_bound[i]);
            add_up(mul_up(g5, m), mul_up(u4, big))
        };
        V::new(component(0), component(1), component(2))
    }

    /// The point of the lens for sample `(s, t)` in `[0, 1)^2`, before
    /// rounding to a focus point's grid: `eye + radius (a right + b
    /// true_up)` with `(a, b)` Shirley and Chiu's concentric map of the
    /// sample onto the unit disc (each within `gamma(28)` of it in `f32`,
    /// `gamma(44)` in `f64`, for samples in `[0, 1]^2`). Samples
    /// outside `[0, 1]^2` map outside the disc; NaN gives NaN.
    #[inline]
    #[must_use]
    pub fn lens_point(&self, s: S<V>, t: S<V>) -> V {
        let (a, b) = concentric_disc(s, t);
        let radius = self.lens_radius;
        self.pinhole.eye()
            + (self.pinhole.right() * (radius * a) + self.pinhole.up() * (radius * b))
    }

    /// The lens offset `radius * concentric_disc(s, t)`, and whether the
    /// sample is at the lens centre (where the ray is the pinhole ray).
    #[inline(always)]
    fn lens_offset(&self, s: S<V>, t: S<V>) -> ((S<V>, S<V>), bool) {
        let radius = self.lens_radius;
        // A zero radius is the pinhole camera, whatever the sample (a NaN
        // one included); so is the sample at the lens centre. Any other
        // sample takes the lens's path, even where its offset underflows to
        // zero (a subnormal radius), so that its ray meets the focus point.
        let zero = S::<V>::ZERO;
        let (a, b) = concentric_disc(s, t);
        let centre = radius == zero || (a == zero && b == zero);
        ((radius * a, radius * b), centre)
    }

    /// The ray from the lens point at offset `(ra, rb)` through `focus`.
    #[inline(always)]
    fn through(&self, focus: &FocusPoint<V>, (ra, rb): (S<V>, S<V>)) -> Ray<V> {
        let lens = self.pinhole.eye() + (self.pinhole.right() * ra + self.pinhole.up() * rb);
        let g = focus.grid;
        let origin = V::new(
            snap(lens.x(), g.x()),
            snap(lens.y(), g.y()),
            snap(lens.z(), g.z()),
        );
        Ray::new(origin, focus.point - origin)
    }

    /// The ray of lens sample `(s, t)` (in `[0, 1)^2`) through `focus`:
    /// from the lens point `L` (rounded to the focus point's grid) along
    /// `F - L`, which is exact, so that the ray is at the focus point `F`
    /// at `t = 1`, in exact arithmetic and bit for bit in floating point.
    /// A sample at the lens centre (or a zero lens radius) gives the
    /// pinhole ray of the film point instead, bit for bit.
    #[inline(always)]
    #[must_use]
    pub fn ray_through(&self, focus: &FocusPoint<V>, s: S<V>, t: S<V>) -> Ray<V> {
        // A branch, taken only at the centre: a select computes the
        // pinhole ray for every sample, which a scalar loop pays for
        // (`benches/peers`' camera rows show it).
        let (offset, centre) = self.lens_offset(s, t);
        if centre {
            return self
                .pinhole
                .ray(CameraSample::new(focus.raster.0, focus.raster.1));
        }
        self.through(focus, offset)
    }

    /// The pinhole camera: the film, the eye and the basis.
    #[inline]
    #[must_use]
    pub fn pinhole(&self) -> &PinholeCamera<V> {
        &self.pinhole
    }

    /// The lens radius, in world units.
    #[inline]
    #[must_use]
    pub fn lens_radius(&self) -> S<V> {
        self.lens_radius
    }

    /// The distance of the plane of focus from the eye, along the view.
    #[inline]
    #[must_use]
    pub fn focal_distance(&self) -> S<V> {
        self.focal_distance
    }
}

impl<V: Vector> Camera<V> for ThinLensCamera<V> {
    /// The ray of raster position `(x, y)` and lens sample `(s, t)`:
    /// [`ray_through(&focus(x, y), s, t)`](ThinLensCamera::ray_through).
    /// A renderer taking many lens samples per film point computes the
    /// focus point once and calls `ray_through`.
    #[inline(always)]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V> {
        let ([x, y], [s, t]) = (sample.film, sample.lens);
        self.ray_through(&self.focus(x, y), s, t)
    }

    /// The ray of `(x, y)` and lens sample `(s, t)`, bit for bit
    /// [`ray`](ThinLensCamera::ray), with its differentials: for a fixed
    /// lens point the origin does not move and the direction `F - L`
    /// moves with the focus point, `dx_dir = (focal_distance /
    /// focal_length) right` and `dy_dir = -(focal_distance / focal_length)
    /// true_up` (one rounding each, and exact second order: the focus point
    /// is linear in the raster position; the grid rounding adds at most
    /// `g_i` per component to the difference of neighbouring rays). At the
    /// lens centre, the pinhole camera's differentials.
    #[inline(always)]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V> {
        let ([x, y], [s, t]) = (sample.film, sample.lens);
        // A branch, as in `ray_through`: a loop storing rays with
        // differentials (72 bytes each) mostly stays scalar, and there the
        // branch (taken only at the centre) is cheaper than computing the
        // pinhole camera's differentials for every ray (`benches/peers`'
        // camera rows show it).
        let (offset, centre) = self.lens_offset(s, t);
        if centre {
            return self.pinhole.ray_differential(sample);
        }
        RayDifferential {
            ray: self.through(&self.focus(x, y), offset),
            dx_origin: zero_vector(),
            dx_dir: self.pinhole.right() * self.scale,
            dy_origin: zero_vector(),
            dy_dir: -(self.pinhole.up() * self.scale),
        }
    }

    /// The ray cone of every ray: the pinhole camera's
    /// ([`PinholeCamera::ray_cone`]), a cone from the lens point with one
    /// pixel's angle (the film point's footprint on the plane of focus is
    /// `focal_distance / focal_length` wide, seen from `focal_distance`
    /// away).
    #[inline]
    fn ray_cone(&self) -> RayCone<S<V>> {
        self.pinhole.ray_cone()
    }

    #[inline]
    fn width(&self) -> u32 {
        self.pinhole.width()
    }

    #[inline]
    fn height(&self) -> u32 {
        self.pinhole.height()
    }
}
