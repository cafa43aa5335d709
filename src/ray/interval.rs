//! [`Interval`]: the range `(min, max]` of `t` a kernel's interval form
//! searches.

use crate::num::Scalar;

/// The half-open range `min < t <= max` of distances along a ray, in units
/// of the ray's `dir`, that the interval forms of the kernels (such as
/// [`ray_triangle_in`](crate::ray_triangle_in)) search.
///
/// Open below, closed above, so that consecutive intervals `(t0, t1]`,
/// `(t1, t2]`, ... cover the ray without overlap: each exact crossing
/// distance falls in exactly one of them. `(0, max]` is the range every
/// kernel without a lower end searches.
///
/// Valid intervals only: `0 <= min <= max`, neither NaN; `max` may be
/// `+inf` (no upper end), and `min = max` is the empty interval. `-0.0`
/// counts as zero.
///
/// ```
/// use rayhit::Interval;
/// let window = Interval::new(1.0f32, 2.5).unwrap();
/// assert_eq!((window.min(), window.max()), (1.0, 2.5));
/// assert!(!window.contains(1.0) && window.contains(2.5));
/// assert!(Interval::new(2.0f32, 1.0).is_none()); // inverted
/// assert!(Interval::new(f32::NAN, 1.0).is_none());
/// assert!(Interval::new(-1.0f32, 1.0).is_none()); // only t >= 0 exists
/// assert_eq!(Interval::up_to(f32::INFINITY), Interval::new(0.0, f32::INFINITY));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval<F> {
    min: F,
    max: F,
}

impl<F: Scalar> Interval<F> {
    /// `(min, max]`, or `None` unless `0 <= min <= max` (NaN fails).
    #[inline]
    #[must_use]
    pub fn new(min: F, max: F) -> Option<Self> {
        (F::ZERO <= min && min <= max).then_some(Self { min, max })
    }

    /// `(0, max]`, the range of the kernels without a lower end; `None`
    /// for a NaN or negative `max`.
    #[inline]
    #[must_use]
    pub fn up_to(max: F) -> Option<Self> {
        Self::new(F::ZERO, max)
    }

    /// The lower end, excluded.
    #[inline]
    #[must_use]
    pub fn min(&self) -> F {
        self.min
    }

    /// The upper end, included (may be `+inf`).
    #[inline]
    #[must_use]
    pub fn max(&self) -> F {
        self.max
    }

    /// `min < t <= max`, for a float `t` (false for NaN).
    #[inline]
    #[must_use]
    pub fn contains(&self, t: F) -> bool {
        self.min < t && t <= self.max
    }
}
