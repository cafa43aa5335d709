//! [`Interval`]: the range `(min, max]` of `t` a kernel's interval form
//! searches; and the decision of an exact crossing distance against its
//! ends, which every interval form shares (an error-bound filter, then
//! exact signs).

use super::exact_crossing::PlaneCrossing;
use crate::num::round::min2;
use crate::num::{Bits, Repr, Scalar};
use core::cmp::Ordering;

/// The half-open range `min < t <= max` of distances along a ray, in units
/// of the ray's `dir`, that the interval forms of the kernels (such as
/// [`Triangle`'s `hit` over an interval](crate::Triangle#method.hit)) search.
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

impl<F: Scalar> Interval<F> {
    /// The ends a kernel decides against: `(min, min(max, MAX))`. The
    /// largest distance a hit can report is `MAX` (a crossing beyond it
    /// has no finite `t`), so a crossing beyond `MAX` is reported by no
    /// interval.
    #[inline(always)]
    pub(crate) fn ends(&self) -> (F, F) {
        (self.min, min2(self.max, F::MAX))
    }
}

/// `t` brought into `(lo, hi]` (`0 <= lo < hi`): `lo`'s successor where `t` is
/// at most `lo` or NaN, `hi` where it is above. Where the exact `t*` is in
/// `(lo, hi]`: moving to `hi` only moves `t` towards `t*`; moving to
/// `lo`'s successor does too unless `t*` lies strictly between `lo` and
/// its successor, and then the result is within one ulp of `t*`. So
/// `|result - t*| <= max(|t - t*|, succ(lo) - lo)`. With `hi <= MAX` the
/// result is finite.
#[inline(always)]
pub(crate) fn bring_into<F: Scalar>(t: F, lo: F, hi: F) -> F {
    let t = if t > lo {
        t
    } else {
        <F as Repr>::Bits::successor(lo)
    };
    min2(t, hi)
}

/// Where a distance lies against one end of an interval.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Place {
    /// Surely on the near side of the filter's band.
    Below,
    /// Surely on the far side.
    Above,
    /// Within the band: the exact signs decide.
    Unknown,
}

/// The exact place of one crossing against a float, for [`decide`]'s
/// fallback: a plane's ([`PlaneCrossing`]), or one of a sphere's two.
pub(crate) trait ExactPlace {
    /// Whether the crossing exists (the line is not parallel to the plane;
    /// it meets the ball); `None` where the exact signs overflow.
    fn exists(&self) -> Option<bool>;
    /// The crossing `t*` of a line where [`exists`](Self::exists) holds,
    /// against `x`: `Greater` where `t* > x`. `None` where the exact signs
    /// overflow.
    fn place(&self, x: f64) -> Option<Ordering>;
}

/// A plane's crossing `t* = A . n / D`: it exists where `D` is not zero,
/// and `t* > x` exactly when `A . n - x D` has the sign of `D`.
impl ExactPlace for PlaneCrossing {
    fn exists(&self) -> Option<bool> {
        Some(self.den_sign()? != Ordering::Equal)
    }

    fn place(&self, x: f64) -> Option<Ordering> {
        let den = self.den_sign()?;
        let num = self.num_minus_t_den_sign(x)?;
        Some(if num == Ordering::Equal {
            Ordering::Equal
        } else if num == den {
            Ordering::Greater
        } else {
            Ordering::Less
        })
    }
}

/// Whether the exact crossing `t*` is in `(lo, hi]`, given a float `t`
/// within `err` of it (where `t*` exists), and the exact signs where the
/// band `[t - err, t + err]` leaves an end open; `None` where the exact
/// signs overflow (outside their documented range).
///
/// The filter: where the band lies on one side of an end (its bounds
/// rounded outward), that end is decided. Otherwise the exact place
/// ([`ExactPlace`]) decides: for a plane, `t* > lo` holds exactly when
/// `A . n - lo D` has the sign of `D` (and `D` is not zero), and `t* <=
/// hi` when `A . n - hi D` is zero or of the opposite sign
/// ([`PlaneCrossing`]). A NaN `t` or `err`, or an infinite `err`, leaves
/// both ends to the exact signs, which also answer "no crossing" where
/// there is none (`D` exactly zero). Shared by every interval form.
#[inline(always)]
pub(crate) fn decide<F: Scalar, E: ExactPlace>(
    t: F,
    err: F,
    lo: F,
    hi: F,
    exact: impl FnOnce() -> E,
) -> Option<bool> {
    match filter(t, err, lo, hi) {
        Ok(inside) => Some(inside),
        Err((low, high)) => exact_decide(low, high, lo, hi, exact()),
    }
}

/// The filter of [`decide`] alone: `Ok` with the answer where the band
/// `[t - err, t + err]` settles it, else `Err` with where the band lies
/// against each end (for the exact signs to finish).
#[inline(always)]
pub(crate) fn filter<F: Scalar>(t: F, err: F, lo: F, hi: F) -> Result<bool, (Place, Place)> {
    use crate::num::round::outward::{add_up, sub_down};
    let low = if sub_down(t, err) > lo {
        Place::Above
    } else if add_up(t, err) <= lo {
        Place::Below
    } else {
        Place::Unknown
    };
    if low == Place::Below {
        return Ok(false);
    }
    let high = if add_up(t, err) <= hi {
        Place::Below
    } else if sub_down(t, err) > hi {
        Place::Above
    } else {
        Place::Unknown
    };
    if high == Place::Above {
        return Ok(false);
    }
    if low == Place::Above && high == Place::Below {
        return Ok(true);
    }
    Err((low, high))
}

/// The exact half of [`decide`], out of line.
#[cold]
#[inline(never)]
fn exact_decide<F: Scalar, E: ExactPlace>(
    low: Place,
    high: Place,
    lo: F,
    hi: F,
    exact: E,
) -> Option<bool> {
    if !exact.exists()? {
        return Some(false);
    }
    let above_lo = low == Place::Above || exact.place(lo.to_f64())? == Ordering::Greater;
    if !above_lo {
        return Some(false);
    }
    Some(high == Place::Below || exact.place(hi.to_f64())? != Ordering::Greater)
}
