//! Cameras: the [`Camera`] trait, its six implementations, and what they
//! give beside a ray (differentials, ray cones, their transfer to a hit).
//!
//! | camera | rays | beside the trait |
//! | --- | --- | --- |
//! | [`PinholeCamera`] | perspective, from an eye | the frame's accessors |
//! | [`ThinLensCamera`] | depth of field: rays of one film point meet at its focus point exactly | [`ThinLensCamera::focus`] once per film point, [`ThinLensCamera::ray_through`] per lens sample |
//! | [`OrthographicCamera`] | parallel, one direction bit for bit | |
//! | [`MatrixCamera`] | from a rasterizer's view and projection matrices | [`MatrixCamera::from_mat4`] |
//! | [`EquirectangularCamera`] | latitude and longitude over the whole sphere | the inverse, `raster_position` |
//! | [`EqualAreaCamera`] | the whole sphere, every pixel the same solid angle | the inverse, `raster_position` |
//!
//! Every camera is built from checked parameters ([`CameraError`] says
//! which is bad) and answers [`Camera::ray`], [`Camera::ray_differential`]
//! ([`RayDifferential`]) and [`Camera::ray_cone`] ([`RayCone`]) for a
//! [`CameraSample`]; [`Triangle::hit_differentials`](crate::Triangle::hit_differentials)
//! carries the differentials to a hit ([`HitDifferentials`]).

// Files: `mod.rs`, the trait, the sample, the errors and what every camera
// shares (the orthonormal basis from eye, view and up, the raster offset
// from the image centre); one file per camera (`pinhole.rs`,
// `thin_lens.rs`, `orthographic.rs`, `matrix.rs`, `equirectangular.rs`,
// `equal_area.rs`); `differential.rs`, ray differentials and cones and
// their transfer to a triangle hit.

mod differential;
mod equal_area;
mod equirectangular;
mod matrix;
mod orthographic;
mod pinhole;
mod thin_lens;

use core::fmt;

use glam::{DVec3, Vec3};

use crate::num::{S, Scalar, Vector, unit};
use crate::ray::Ray;

pub use differential::{HitDifferentials, RayCone, RayDifferential};
pub use equal_area::EqualAreaCamera;
pub use equirectangular::EquirectangularCamera;
pub use matrix::{ClipSpace, MatrixCamera};
pub use orthographic::OrthographicCamera;
pub use pinhole::PinholeCamera;
pub use thin_lens::{FocusPoint, ThinLensCamera};

/// [`PinholeCamera`] in `f64`.
pub type DPinholeCamera = PinholeCamera<glam::DVec3>;
/// [`ThinLensCamera`] in `f64`.
pub type DThinLensCamera = ThinLensCamera<glam::DVec3>;
/// [`OrthographicCamera`] in `f64`.
pub type DOrthographicCamera = OrthographicCamera<glam::DVec3>;
/// [`MatrixCamera`] in `f64`.
pub type DMatrixCamera = MatrixCamera<glam::DVec3>;
/// [`EquirectangularCamera`] in `f64`.
pub type DEquirectangularCamera = EquirectangularCamera<glam::DVec3>;
/// [`EqualAreaCamera`] in `f64`.
pub type DEqualAreaCamera = EqualAreaCamera<glam::DVec3>;
/// [`RayDifferential`] in `f64`.
pub type DRayDifferential = RayDifferential<glam::DVec3>;
/// [`HitDifferentials`] in `f64`.
pub type DHitDifferentials = HitDifferentials<glam::DVec3>;
/// [`CameraSample`] in `f64`.
pub type DCameraSample = CameraSample<f64>;

/// Why a camera could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CameraError {
    /// The eye position has a NaN or infinite component.
    NonFiniteEye,
    /// The view direction is zero or has a NaN or infinite component.
    InvalidViewDir,
    /// The up vector is zero or has a NaN or infinite component.
    InvalidUp,
    /// The up vector is parallel to the view direction (within rounding), so
    /// it does not say which way is up.
    UpParallelToView,
    /// The focal length is not positive and finite.
    InvalidFocalLength,
    /// The vertical field of view is not in the open interval `(0, pi)`.
    InvalidFieldOfView,
    /// The image width or height is zero.
    EmptyImage,
    /// The lens radius is negative, NaN or infinite, or so large that the
    /// lens's coordinates overflow.
    InvalidLensRadius,
    /// The focal distance is not positive and finite, or its ratio to the
    /// focal length under- or overflows.
    InvalidFocalDistance,
    /// The pixel size is not positive and finite.
    InvalidPixelSize,
    /// A matrix has a NaN or infinite entry (or their product does).
    NonFiniteMatrix,
    /// The matrices do not define a camera: singular within rounding, or
    /// its eye or rays overflow.
    SingularMatrix,
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::NonFiniteEye => "camera eye position is not finite",
            Self::InvalidViewDir => "camera view direction is zero or not finite",
            Self::InvalidUp => "camera up vector is zero or not finite",
            Self::UpParallelToView => "camera up vector is parallel to the view direction",
            Self::InvalidFocalLength => "camera focal length is not positive and finite",
            Self::InvalidFieldOfView => "camera vertical field of view is not in (0, pi)",
            Self::EmptyImage => "camera image width or height is zero",
            Self::InvalidLensRadius => "camera lens radius is negative or not finite",
            Self::InvalidFocalDistance => "camera focal distance is not positive and finite",
            Self::InvalidPixelSize => "camera pixel size is not positive and finite",
            Self::NonFiniteMatrix => "camera matrix is not finite",
            Self::SingularMatrix => "camera matrices are singular",
        })
    }
}

impl core::error::Error for CameraError {}

/// The accessors of a camera's [`Basis`] (a field `basis`): `eye`,
/// `forward`, `right`, `up`, written once for the cameras that keep one.
macro_rules! basis_accessors {
    () => {
        /// The eye position: where every ray starts.
        #[inline]
        #[must_use]
        pub fn eye(&self) -> V {
            self.basis.eye
        }

        /// The unit view direction: the image centre's direction.
        #[inline]
        #[must_use]
        pub fn forward(&self) -> V {
            self.basis.forward
        }

        /// The unit vector to the right.
        #[inline]
        #[must_use]
        pub fn right(&self) -> V {
            self.basis.right
        }

        /// The unit vector up, orthogonal to `forward`.
        #[inline]
        #[must_use]
        pub fn up(&self) -> V {
            self.basis.up
        }
    };
}
use basis_accessors;

/// A camera's `width` and `height` from its fields of those names, for its
/// [`Camera`] implementation.
macro_rules! film_size {
    () => {
        #[inline]
        fn width(&self) -> u32 {
            self.width
        }

        #[inline]
        fn height(&self) -> u32 {
            self.height
        }
    };
}
use film_size;

/// Where on the film, where on the lens and when a camera ray starts:
/// what a renderer's sampler gives a [`Camera`] (pbrt-v4's
/// `CameraSample`).
///
/// `film` is the raster position `(x, y)`, continuous, in pixels from the
/// image's top-left corner, `y` down: pixel `(i, j)` covers `[i, i + 1) x
/// [j, j + 1)` and has its centre at `(i + 0.5, j + 0.5)`. `lens` is a
/// point of `[0, 1]^2` that a camera with a lens maps onto it
/// (`(0.5, 0.5)` is the lens centre); cameras without one ignore it.
/// `time` is in `[0, 1)`, the shutter interval; no camera reads it yet
/// (there for moving cameras and geometry).
///
/// ```
/// use rayhit::{Camera, CameraSample, PinholeCamera, glam::Vec3};
/// let cam = PinholeCamera::from_fov(Vec3::ZERO, -Vec3::Z, Vec3::Y, 1.0, 64, 48).unwrap();
/// let sample = CameraSample::new(32.0, 24.0); // the image's centre
/// assert_eq!(cam.ray(sample).dir, -Vec3::Z);
/// let pixel: CameraSample = CameraSample::pixel(3, 4);
/// assert_eq!(pixel.film, [3.5, 4.5]);
/// assert_eq!(pixel.with_lens(0.25, 0.75).lens, [0.25, 0.75]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample<F = f32> {
    /// The raster position `(x, y)`, in pixels.
    pub film: [F; 2],
    /// The lens sample, in `[0, 1]^2`.
    pub lens: [F; 2],
    /// The time, in `[0, 1)`.
    pub time: F,
}

impl<F: Scalar> CameraSample<F> {
    /// Raster position `(x, y)`, at the lens centre, at time 0.
    #[inline(always)]
    #[must_use]
    pub fn new(x: F, y: F) -> Self {
        Self {
            film: [x, y],
            lens: [F::HALF, F::HALF],
            time: F::ZERO,
        }
    }

    /// The centre of pixel `(i, j)`, `(i + 0.5, j + 0.5)`, at the lens
    /// centre, at time 0.
    #[inline(always)]
    #[must_use]
    pub fn pixel(i: u32, j: u32) -> Self {
        let (x, y) = pixel_centre(i, j);
        Self::new(x, y)
    }

    /// The same sample at lens sample `(s, t)`.
    #[inline(always)]
    #[must_use]
    pub fn with_lens(self, s: F, t: F) -> Self {
        Self {
            lens: [s, t],
            ..self
        }
    }

    /// The same sample at `time`.
    #[inline(always)]
    #[must_use]
    pub fn with_time(self, time: F) -> Self {
        Self { time, ..self }
    }
}

/// A camera: the ray of a [`CameraSample`], with its differentials and its
/// ray cone, for every camera the same way (pbrt-v4's `Camera`).
///
/// Implemented by [`PinholeCamera`], [`ThinLensCamera`],
/// [`OrthographicCamera`], [`MatrixCamera`], [`EquirectangularCamera`]
/// and [`EqualAreaCamera`]; each implementation states its guarantees.
/// Object safe: a renderer choosing its camera at run time holds a
/// `Box<dyn Camera>` (which is `Debug`, as every camera is).
///
/// Conventions, for every camera: right-handed world, raster `(0, 0)` at
/// the image's top-left corner, `x` right, `y` down. A NaN raster position
/// gives a ray with a NaN direction (which every query rejects); positions
/// outside the image give finite rays (each camera says which).
///
/// ```
/// use rayhit::{Camera, CameraSample, PinholeCamera, glam::Vec3};
/// use rayhit::camera::OrthographicCamera;
/// let cameras: [Box<dyn Camera>; 2] = [
///     Box::new(PinholeCamera::from_fov(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, Vec3::Y, 1.0, 32, 32).unwrap()),
///     Box::new(OrthographicCamera::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, Vec3::Y, 0.1, 32, 32).unwrap()),
/// ];
/// for cam in &cameras {
///     // The centre pixel of an even-sized image is half a pixel off the axis.
///     let ray = cam.ray(CameraSample::new(16.0, 16.0));
///     assert_eq!(ray.dir, -Vec3::Z);
///     assert_eq!((cam.width(), cam.height()), (32, 32));
/// }
/// ```
pub trait Camera<V: Vector = Vec3>: fmt::Debug {
    /// The ray of `sample`, in world space.
    #[must_use]
    fn ray(&self, sample: CameraSample<S<V>>) -> Ray<V>;

    /// The ray of `sample`, bit for bit [`ray`](Camera::ray), with its
    /// derivatives per pixel in raster `x` and `y` (for texture
    /// filtering: carry them to a hit with
    /// [`Triangle::hit_differentials`](crate::Triangle::hit_differentials)).
    #[must_use]
    fn ray_differential(&self, sample: CameraSample<S<V>>) -> RayDifferential<V>;

    /// The ray cone of the camera's rays (a cheaper footprint than
    /// differentials: one width and one spread angle).
    #[must_use]
    fn ray_cone(&self) -> RayCone<S<V>>;

    /// The image width in pixels.
    #[must_use]
    fn width(&self) -> u32;

    /// The image height in pixels.
    #[must_use]
    fn height(&self) -> u32;

    /// The ray through the centre of pixel `(i, j)`, at the lens centre:
    /// `ray(CameraSample::pixel(i, j))`.
    #[inline(always)]
    #[must_use]
    fn pixel_ray(&self, i: u32, j: u32) -> Ray<V> {
        self.ray(CameraSample::pixel(i, j))
    }
}

/// `v` rebuilt from its components: the same bits, moved as floats. A
/// vector copied whole from the camera into every ray (the eye, a fixed
/// direction) is moved as integers, and a loop storing rays then does not
/// vectorise.
#[inline(always)]
pub(crate) fn by_components<V: Vector>(v: V) -> V {
    V::new(v.x(), v.y(), v.z())
}

/// The zero vector, built from three zeros: the constant `V::ZERO` stored
/// into a ray with differentials is written by a call to `memset`, and a
/// loop of rays containing a call does not vectorise.
#[inline(always)]
pub(crate) fn zero_vector<V: Vector>() -> V {
    let z = S::<V>::ZERO;
    V::new(z, z, z)
}

/// A camera's position and orthonormal frame: `forward` along the view,
/// `right = normalize(forward x up)` with its component along `forward`
/// removed once more, `up = normalize(right x forward)`: orthonormal within
/// `gamma(13)` (each entry of `B^T B - I`) for every up vector accepted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Basis<V> {
    pub(crate) eye: V,
    pub(crate) forward: V,
    pub(crate) right: V,
    pub(crate) up: V,
}

impl<V: Vector> Basis<V> {
    /// The frame at `eye` looking along `view_dir` with `up` giving the
    /// upward direction; the first four checks of every camera, in this
    /// order: eye, view, up, up parallel to the view.
    ///
    /// "Parallel" is decided against the rounding error, as
    /// [`PinholeCamera::new`] derives: the sine of the angle between the
    /// normalised vectors must exceed `gamma(16)`.
    pub(crate) fn new(eye: V, view_dir: V, up: V) -> Result<Self, CameraError> {
        if !eye.is_finite() {
            return Err(CameraError::NonFiniteEye);
        }
        let forward = unit(view_dir);
        if !forward.is_finite() {
            return Err(CameraError::InvalidViewDir);
        }
        let up_unit = unit(up);
        if !up_unit.is_finite() {
            return Err(CameraError::InvalidUp);
        }
        let side = forward.cross(up_unit);
        if !(side.length() > S::<V>::gamma_n(16)) {
            return Err(CameraError::UpParallelToView);
        }
        // The cross product's rounding, over the sine of the angle (as
        // small as gamma(16)), would tilt `right` towards `forward` by up
        // to a third of a radian; removing the component along `forward`
        // once more (Gram-Schmidt) leaves only this step's own rounding:
        // `right . forward` within a few u whatever the angle.
        let right = unit(side - forward * forward.dot(side));
        let up = unit(right.cross(forward));
        Ok(Self {
            eye,
            forward,
            right,
            up,
        })
    }
}

impl<V: Vector> Basis<V> {
    /// The components of `dir` brought to unit length (scaled by a power
    /// of two where its square would under- or overflow, so that no square
    /// of them does) along `right`, `up` and `forward`; `None` for a zero
    /// or non-finite direction. The panoramas' inverse starts here.
    pub(crate) fn local(&self, dir: V) -> Option<(S<V>, S<V>, S<V>)> {
        if !dir.is_finite() || dir == V::ZERO {
            return None;
        }
        let dir = unit(dir);
        Some((dir.dot(self.right), dir.dot(self.up), dir.dot(self.forward)))
    }

    /// The basis's departure from orthonormal: the largest entry of `B^T B
    /// - I` (`B` with columns `right`, `up`, `forward`), and at least
    /// `gamma(13)`, the bound every accepted up vector gives (see
    /// [`Basis::new`]): measured, not assumed, for the panoramas' bounds.
    /// Evaluated in `f64`: for `f32` the products are exact and the sums
    /// within a few `f64` ulps; for `f64` each entry within `5` of its
    /// ulps; the `4 eps64` added covers both.
    pub(crate) fn skew(&self) -> f64 {
        let b = [self.right, self.up, self.forward];
        let d = |p: V, q: V| (0..3).map(|k| p[k].to_f64() * q[k].to_f64()).sum::<f64>();
        let mut m = S::<V>::gamma_n(13).to_f64();
        for i in 0..3 {
            for j in 0..3 {
                let target = if i == j { 1.0 } else { 0.0 };
                m = m.max((d(b[i], b[j]) - target).abs() + 4.0 * f64::EPSILON);
            }
        }
        m
    }
}

/// The angle, in radians, between a panorama's computed direction and the
/// exact direction of its computed angles, plus the inverse's recovery of
/// the local components, for a basis of departure `skew`
/// ([`Basis::skew`]); `T = trig_n + 2` is the sines' and cosines'
/// `gamma(T)` absolute bound (`num::trig::sin_cos_turns`):
///
/// - the local components `(X, Y, Z)`: products of two sines or cosines
///   and a rounding, within `gamma(2T + 2)`;
/// - the world vector `X right + Y up + Z forward`: the components' errors
///   times `|right_i| + |up_i| + |forward_i|`, and three roundings of the
///   sum: per component within `(|right_i| + |up_i| + |forward_i|)
///   gamma(2T + 15)`, a vector at most `3 gamma(2T + 15)` long (the basis
///   vectors have length 1 within `gamma(6)`);
/// - normalising, in the forward map and again in the inverse: a common
///   factor, and one rounding per component each time (`2 sqrt(3) u`);
/// - the inverse's dot products with the basis (`gamma(3)` each, `sqrt(3)
///   gamma(3)` as a vector) and the basis's departure from orthonormal:
///   `3 skew`.
pub(crate) fn direction_angle<F: Scalar>(skew: f64) -> f64 {
    let t = crate::num::trig::trig_n::<F>() + 2;
    let g = |n: u32| F::gamma_n(n).to_f64();
    let u = F::UNIT_ROUNDOFF.to_f64();
    let root3 = 3f64.sqrt();
    3.0 * g(2 * t + 15) + 2.0 * root3 * u + root3 * g(3) + 3.0 * skew
}

/// The rounding bound of a linear camera's direction derivatives (the
/// pinhole camera's and a perspective matrix camera's), as a length: for
/// the direction `p / |p|` of `p = c + dx a + dy b`, the computed
/// derivative along a step `a` (or `-b`) is within
///
/// `(|step| / |p|) (gamma(28) + 5 gamma(3) |K| / |p|) + e (|c| + |dx| |a|
/// + |dy| |b|) / ((1 - e) |p|^2)`
///
/// of the exact derivative at the camera's `c` (given in `f64`: exact, or
/// the exact product for the pinhole's `focal forward`), `a`, `b` and the
/// given offsets, where `K = |c| + |dx| |a| + |dy| |b|` (components'
/// magnitudes) and `e` the frame's departure from orthonormal for a camera
/// that uses `dx` and `dy` for `p . a` and `p . b` (zero for one that
/// computes the dot products). The first term: the direction's error twice
/// through `dir (dir . step)`, the dot product's `gamma(3)`, two more
/// roundings, and the factor `1 / |p|`'s error (`gamma(4)` and `p`'s own
/// `gamma(3) |K|`); the second: with `c = focal forward`, `p . a` is
/// within `e (focal + |dx| + |dy|)` of `dx`, and each unit vector at
/// least `1 - e` long, which through `dir (dir . step) / |p|` moves the
/// derivative by that over `|p|^2`. `|p|` is taken from below (its `f64`
/// value less `1e-15 |K|`). Infinite where `|p|` is not above twice the
/// step (there the derivative says nothing of the neighbour).
pub(crate) fn linear_differential_error<V: Vector>(
    c: DVec3,
    [a, b]: [V; 2],
    (dx, dy): (S<V>, S<V>),
    frame: f64,
) -> S<V> {
    let (a, b, dx, dy) = (dvec(a), dvec(b), dx.to_f64(), dy.to_f64());
    let k = c.abs() + a.abs() * dx.abs() + b.abs() * dy.abs();
    let step = a.length().max(b.length());
    let p = (c + a * dx + b * dy).length() - 1e-15 * k.length();
    if !(p > 2.0 * step) {
        return S::<V>::INFINITY;
    }
    let g = |n: u32| S::<V>::gamma_n(n).to_f64();
    let own = step / p * (g(28) + 5.0 * g(3) * k.length() / p);
    let reach = c.length() + dx.abs() * a.length() + dy.abs() * b.length();
    let shortcut = frame * reach / ((1.0 - frame) * p * p);
    bound_from_f64(own + shortcut)
}

/// `[x, y, width, height]` in `f64` for a raster position on the image
/// (its edges included); `None` off it, or for a NaN position.
pub(crate) fn on_film<F: Scalar>(x: F, y: F, width: u32, height: u32) -> Option<[f64; 4]> {
    let (w, h) = (f64::from(width), f64::from(height));
    let (x, y) = (x.to_f64(), y.to_f64());
    ((0.0..=w).contains(&x) && (0.0..=h).contains(&y)).then_some([x, y, w, h])
}

/// A vector's components in `f64` (exactly).
pub(crate) fn dvec<V: Vector>(v: V) -> DVec3 {
    DVec3::new(v.x().to_f64(), v.y().to_f64(), v.z().to_f64())
}

/// A bound evaluated in `f64` as the precision's: the `f64` evaluation's
/// own error covered (a relative `1e-9`, far above the few `f64` roundings
/// of these formulas), then rounded up. Positive infinity where the bound
/// is infinite or NaN.
pub(crate) fn bound_from_f64<F: Scalar>(bound: f64) -> F {
    // Four of the smallest subnormals more: below the normal range the
    // relative margin is no margin, and a rounding there is off by up to
    // half of one, absolutely; four cover eight such roundings, and
    // `MatrixCamera::raster_error`'s subnormal slack, the term that lands
    // there, takes two (its product with the pixel scale and the sum).
    let b = bound * (1.0 + 1e-9) + 4.0 * f64::from_bits(1);
    if b.is_nan() {
        return F::INFINITY;
    }
    F::from_f64(b).next_up()
}

/// Raster position `(x, y)` (from the top-left, `y` down) as offsets from
/// the centre of a `width x height` image: `(x - width/2, height/2 - y)`,
/// right and up.
///
/// `width/2` and `height/2` are exact (halving a float is exact, and the
/// sizes are below `2^24`), so each offset carries one rounding, and none
/// for positions on the half-pixel grid of an image below `2^23` pixels
/// (`i + 0.5 - width/2` is then a float on the same grid).
#[inline(always)]
pub(crate) fn centred<F: Scalar>(x: F, y: F, width: u32, height: u32) -> (F, F) {
    (
        x - F::from_u32(width) * F::HALF,
        F::from_u32(height) * F::HALF - y,
    )
}

/// The raster position of pixel `(i, j)`'s centre: `(i + 0.5, j + 0.5)`.
#[inline(always)]
pub(crate) fn pixel_centre<F: Scalar>(i: u32, j: u32) -> (F, F) {
    (F::from_u32(i) + F::HALF, F::from_u32(j) + F::HALF)
}
