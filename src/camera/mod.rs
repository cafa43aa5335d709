//! Cameras: raster positions to primary rays.
//!
//! - `mod.rs`: [`CameraError`], and what every camera shares: the
//!   orthonormal basis from eye, view and up, and the raster offset from
//!   the image centre.
//! - `pinhole.rs`: [`PinholeCamera`].
//! - `thin_lens.rs`: [`ThinLensCamera`] and its [`FocusPoint`].
//! - `orthographic.rs`: [`OrthographicCamera`].
//! - `matrix.rs`: [`MatrixCamera`], from a rasterizer's matrices.
//! - `equirectangular.rs`: [`EquirectangularCamera`].
//! - `equal_area.rs`: [`EqualAreaCamera`] (Clarberg's octahedral map).
//! - `differential.rs`: [`RayDifferential`] and [`RayCone`], and their
//!   transfer to a triangle hit ([`HitDifferentials`]).

mod differential;
mod equal_area;
mod equirectangular;
mod matrix;
mod orthographic;
mod pinhole;
mod thin_lens;

use core::fmt;

use crate::num::{S, Scalar, Vector, unit};

pub use differential::{
    HitDifferentials, RayCone, RayDifferential, triangle_cone_width, triangle_hit_differentials,
    triangle_hit_differentials_error,
};
pub use equal_area::EqualAreaCamera;
pub use equirectangular::EquirectangularCamera;
pub use matrix::{ClipSpace, Columns, MatrixCamera};
pub use orthographic::OrthographicCamera;
pub use pinhole::PinholeCamera;
pub use thin_lens::{FocusPoint, ThinLensCamera};

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

/// What every camera with a `ray(x, y)` and fields `width` and `height`
/// has: `pixel_ray`, `width` and `height`, written once.
macro_rules! film_accessors {
    () => {
        /// The ray through the centre of pixel `(i, j)`: `ray(i + 0.5, j + 0.5)`.
        #[inline(always)]
        #[must_use]
        pub fn pixel_ray(&self, i: u32, j: u32) -> Ray<V> {
            let (x, y) = super::pixel_centre(i, j);
            self.ray(x, y)
        }

        /// The image width in pixels.
        #[inline]
        #[must_use]
        pub fn width(&self) -> u32 {
            self.width
        }

        /// The image height in pixels.
        #[inline]
        #[must_use]
        pub fn height(&self) -> u32 {
            self.height
        }
    };
}
use film_accessors;

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
