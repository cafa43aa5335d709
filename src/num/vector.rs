//! Vectors: [`Vector`], implemented by glam's `Vec3`, `Vec3A` and `DVec3`
//! of every glam release the crate supports, and the safe normalisation
//! the camera uses.

use core::fmt::Debug;
use core::ops::{Add, Index, Mul, Neg, Sub};

use super::lanes::Axis;
use super::repr::{Bits, Components, Repr};
use super::round::max2;
use super::{S, Scalar};

/// A 3-component vector the kernels run on: glam's `Vec3` and `Vec3A`
/// (`f32`) and `DVec3` (`f64`), of the glam this crate re-exports and of
/// every older glam release whose feature is on (`glam-029` to
/// `glam-033`).
///
/// Sealed; see [`Scalar`]. The operations are glam's own or written out in
/// the order glam's `Vec3` uses, so every vector type of a precision gives
/// the same answers bit for bit, and a kernel written against this trait
/// compiles to the same code as one written against `Vec3` directly.
pub trait Vector:
    Components<Elem = <Self as Vector>::Scalar>
    + Copy
    + PartialEq
    + Debug
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<Output = Self>
    + Mul<<Self as Vector>::Scalar, Output = Self>
    + Index<usize, Output = <Self as Vector>::Scalar>
{
    /// The component type.
    type Scalar: Scalar;

    /// All zeros.
    const ZERO: Self;

    /// A vector from its components.
    #[must_use]
    fn new(x: Self::Scalar, y: Self::Scalar, z: Self::Scalar) -> Self;
    /// All three components equal to `v`.
    #[must_use]
    fn splat(v: Self::Scalar) -> Self;
    /// The `x` component.
    #[must_use]
    fn x(self) -> Self::Scalar;
    /// The `y` component.
    #[must_use]
    fn y(self) -> Self::Scalar;
    /// The `z` component.
    #[must_use]
    fn z(self) -> Self::Scalar;
    /// Dot product.
    #[must_use]
    fn dot(self, rhs: Self) -> Self::Scalar;
    /// Cross product (right-handed).
    #[must_use]
    fn cross(self, rhs: Self) -> Self;
    /// Component-wise absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// True when every component is finite.
    #[must_use]
    fn is_finite(self) -> bool;
    /// True when `self[k] <= rhs[k]` for every `k` (a NaN on either side
    /// makes it false). In `f32` on SIMD targets it is one packed
    /// comparison.
    #[must_use]
    fn all_le(self, rhs: Self) -> bool;
    /// Euclidean length.
    #[must_use]
    fn length(self) -> Self::Scalar;
    /// `self / |self|`, or zero when the length is zero or not finite.
    #[must_use]
    fn normalize_or_zero(self) -> Self;
}

macro_rules! impl_vector {
    ($V:ty, $f:ty, $all_le:expr) => {
        impl Components for $V {
            type Elem = $f;
            #[inline(always)]
            fn get(&self, k: Axis) -> $f {
                let a: &[$f; 3] = self.as_ref();
                a[k as usize]
            }
        }

        impl Vector for $V {
            type Scalar = $f;
            const ZERO: Self = <$V>::ZERO;

            #[inline]
            fn new(x: $f, y: $f, z: $f) -> Self {
                <$V>::new(x, y, z)
            }
            #[inline]
            fn splat(v: $f) -> Self {
                <$V>::splat(v)
            }
            #[inline]
            fn x(self) -> $f {
                self.x
            }
            #[inline]
            fn y(self) -> $f {
                self.y
            }
            #[inline]
            fn z(self) -> $f {
                self.z
            }
            // The products below are written out, in the order glam's `Vec3`
            // and `DVec3` use, so that every vector type of a precision gives
            // the same bits (glam's SIMD types may order a sum differently).
            #[inline]
            fn dot(self, rhs: Self) -> $f {
                (self.x * rhs.x) + (self.y * rhs.y) + (self.z * rhs.z)
            }
            #[inline]
            fn cross(self, rhs: Self) -> Self {
                <$V>::new(
                    self.y * rhs.z - rhs.y * self.z,
                    self.z * rhs.x - rhs.z * self.x,
                    self.x * rhs.y - rhs.x * self.y,
                )
            }
            #[inline]
            fn abs(self) -> Self {
                <$V>::abs(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$V>::is_finite(self)
            }
            #[inline]
            fn all_le(self, rhs: Self) -> bool {
                $all_le(self, rhs)
            }
            #[inline]
            fn length(self) -> $f {
                <$f as Scalar>::sqrt(Vector::dot(self, self))
            }
            #[inline]
            fn normalize_or_zero(self) -> Self {
                let rcp = 1.0 / Vector::length(self);
                if rcp.is_finite() && rcp > 0.0 {
                    self * rcp
                } else {
                    <$V>::ZERO
                }
            }
        }
    };
}

/// `Vec3`, `Vec3A` and `DVec3` of the glam crate `$glam` (the default one or
/// an older release under its renamed dependency). `Vec3A` is glam's SIMD
/// vector: `cmple` is one `cmpleps` on x86 (false for NaN, as `<=` is), and
/// `all` one `movmskps`; `Vec3` goes through it for the same reason.
macro_rules! impl_glam {
    ($glam:ident) => {
        impl_vector!($glam::Vec3, f32, |a: $glam::Vec3, b: $glam::Vec3| {
            $glam::Vec3A::from(a).cmple($glam::Vec3A::from(b)).all()
        });
        impl_vector!($glam::Vec3A, f32, |a: $glam::Vec3A, b: $glam::Vec3A| a
            .cmple(b)
            .all());
        impl_vector!($glam::DVec3, f64, |a: $glam::DVec3, b: $glam::DVec3| a
            .cmple(b)
            .all());
    };
}

impl_glam!(glam);
#[cfg(feature = "glam-029")]
impl_glam!(glam029);
#[cfg(feature = "glam-030")]
impl_glam!(glam030);
#[cfg(feature = "glam-031")]
impl_glam!(glam031);
#[cfg(feature = "glam-032")]
impl_glam!(glam032);
#[cfg(feature = "glam-033")]
impl_glam!(glam033);

/// `v / |v|`, computed on `w = v 2^-e`, `2^e` the binade of `v`'s largest
/// component (its largest component then in `[1, 2)`; see
/// [`Bits::inverse_binade`]), as glam's `normalize` computes it (`w * (1 /
/// sqrt(w . w))`), so that `w . w` neither overflows nor underflows; a NaN
/// vector when `v` is zero or not finite.
///
/// Scaling by a power of two is exact in the normal range, and it scales
/// `w . w` by the square, its square root and reciprocal by the power
/// itself, all exactly: so the result is glam's `normalize(v)` bit for bit
/// wherever `v . v` and its nonzero products `v_i^2` are normal floats,
/// and has the same error elsewhere. Components that the scaling pushes
/// below the normal range are below `2^-126` of the largest and change the
/// length by less than a rounding. (Lengths whose squares over- or
/// underflow come from a camera ray at a focal length of `1e30` pixels,
/// for instance.)
///
/// The scaling is applied always, with no test and no branch, so that a
/// loop computing many rays can be vectorised by the compiler.
pub(crate) fn unit<V: Vector>(v: V) -> V {
    unit_and_inverse_length(v).0
}

/// [`unit`] and `1 / |v|`, the factor the normalisation applied: `2^-e /
/// sqrt(w . w)` (as in [`unit`]), bit for bit `1 / sqrt(v . v)` where `v .
/// v` and its nonzero products are normal floats, with the same error
/// elsewhere except where the result is subnormal (a length above
/// `2^126`: up to `2^-149` more, absolutely) or overflows (infinity for a
/// length below `1 / MAX`). A NaN or zero vector gives NaN or infinity.
#[inline(always)]
pub(crate) fn unit_and_inverse_length<V: Vector>(v: V) -> (V, S<V>) {
    let a = v.abs();
    let m = max2(a.x(), max2(a.y(), a.z()));
    let s = <S<V> as Repr>::Bits::inverse_binade(m);
    let w = v * s;
    let rcp = S::<V>::ONE / w.dot(w).sqrt();
    (w * rcp, rcp * s)
}

/// `v` brought to unit length when it is already 1 within `256 u`
/// (`|v . v - 1| <= 512 u`): one Newton step for `1 / sqrt(v . v)` from
/// `1`, `v (3 - v . v) / 2`, with no square root and no division.
///
/// With `v . v = 1 + e`: `sqrt(1 + e) (1 - e/2) = 1 - (3/8) e^2 + O(e^3)`,
/// below `0.01 u` here. The dot product's rounding (`gamma(3)`, relative)
/// moves the factor by half that, the factor's own subtraction and the
/// products add a rounding each: the result's length is within `4 u` of
/// 1, and its direction is `v`'s within one rounding per component (the
/// factor is common). Outside the precondition the length is still finite
/// for finite `v` but not near 1; NaN stays NaN.
#[inline(always)]
pub(crate) fn unit_near<V: Vector>(v: V) -> V {
    let d = v.dot(v);
    v * (S::<V>::from_f64(1.5) - S::<V>::HALF * d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

    #[test]
    fn unit_is_normalize_where_that_works_and_unit_where_it_does_not() {
        // Bit for bit glam's normalize for an ordinary vector (the scaling
        // argument), in both precisions.
        let v = Vec3::new(0.3, -1.7, 2.9);
        assert_eq!(unit(v), v.normalize());
        let w = DVec3::new(1e-3, 5.0, -7.0);
        assert_eq!(unit(w), w.normalize());
        // Squares that underflow or overflow: glam gives zero or NaN, unit
        // gives the direction. The exact answer is (0.6, 0.8, 0); each
        // component is within gamma(6) (the camera's documented bound:
        // 3.6e-7 in f32, 6.7e-16 in f64) of it, plus the rounding of 0.6
        // and 0.8 themselves, well inside 1e-6 and 1e-15.
        for s in [1e-42_f32, 1e-30, 1e30, 8e37] {
            let u = unit(Vec3::new(3.0, 4.0, 0.0) * s);
            assert!(
                (u - Vec3::new(0.6, 0.8, 0.0)).abs().max_element() < 1e-6,
                "{s}: {u}"
            );
        }
        for s in [1e-320_f64, 1e-200, 1e200, 1e307] {
            let u = unit(DVec3::new(3.0, 4.0, 0.0) * s);
            assert!(
                (u - DVec3::new(0.6, 0.8, 0.0)).abs().max_element() < 1e-15,
                "{s}: {u}"
            );
        }
        // Zero and non-finite vectors give a non-finite result.
        for bad in [Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::NAN] {
            assert!(!unit(bad).is_finite());
        }
    }

    /// The inverse length, against `1 / |v|` computed in `f64` from the
    /// `f32` vector (exact squares, a sum and a square root each within half
    /// an `f64` ulp: far inside the `f32` bound), over lengths from
    /// subnormal to near overflow. Where `v . v` and its nonzero products
    /// are normal it is `1 / sqrt(v . v)` bit for bit (the scaling by a
    /// power of two commutes with every rounding there); elsewhere within
    /// `gamma(4)` (the dot
    /// product's three roundings and the square root's, halved, plus the
    /// division's), or `2^-149` absolutely where it is subnormal.
    #[test]
    fn inverse_length_is_one_over_the_length() {
        let base = [
            Vec3::new(3.0, 4.0, 0.0),
            Vec3::new(-1.0, 1e-3, 2.5),
            Vec3::new(0.1, 0.2, -0.3),
        ];
        for v0 in base {
            for k in -150..=127 {
                let v = v0 * 2f32.powi(k);
                if v == Vec3::ZERO || !v.is_finite() {
                    continue;
                }
                let (u, inv) = unit_and_inverse_length(v);
                let l2 = v.dot(v);
                let normal = |x: f32| (f32::MIN_POSITIVE..=f32::MAX).contains(&x);
                let products = [v.x, v.y, v.z].iter().all(|&c| c == 0.0 || normal(c * c));
                if normal(l2) && products {
                    assert_eq!(inv, 1.0 / l2.sqrt(), "{v}");
                    assert_eq!(u, v.normalize(), "{v}");
                }
                let exact = 1.0 / v.as_dvec3().length();
                let got = f64::from(inv);
                if exact > f64::from(f32::MAX) {
                    assert!(
                        inv.is_infinite() || got >= exact * (1.0 - 1e-6),
                        "{v}: {inv}"
                    );
                    continue;
                }
                let tol = exact * f64::from(f32::gamma_n(4)) + 2f64.powi(-149);
                assert!((got - exact).abs() <= tol, "{v}: {got} vs {exact}");
            }
        }
    }

    /// `unit_near` on vectors whose squared length is 1 within `512 u`
    /// (the extremes and between, in every direction drawn): the length
    /// within `4 u` of 1 (measured in `f64`: exact squares for `f32`), the
    /// direction within a rounding per component of the input's.
    #[test]
    fn unit_near_is_unit_within_four_u() {
        fn check<V: Vector>(dirs: &[[f64; 3]]) {
            let u = S::<V>::UNIT_ROUNDOFF.to_f64();
            let mut worst = 0f64;
            for d in dirs {
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                for e in [-256.0, -100.0, -1.0, 0.0, 1.0, 100.0, 255.0] {
                    // Length 1 + e u (squared: 1 + 2 e u, within 512 u).
                    let k = (1.0 + e * u) / n;
                    let v = V::new(
                        S::<V>::from_f64(d[0] * k),
                        S::<V>::from_f64(d[1] * k),
                        S::<V>::from_f64(d[2] * k),
                    );
                    let w = unit_near(v);
                    let l = (0..3)
                        .map(|i| w[i].to_f64() * w[i].to_f64())
                        .sum::<f64>()
                        .sqrt();
                    worst = worst.max((l - 1.0).abs() / u);
                    assert!((l - 1.0).abs() <= 4.0 * u, "{d:?} {e}: {l}");
                }
            }
            // Not vacuous: rounding shows.
            assert!(worst > 0.1, "{worst}");
        }
        let mut dirs = std::vec::Vec::new();
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..2000 {
            let mut c = [0f64; 3];
            for v in &mut c {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                *v = (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
            }
            dirs.push(c);
        }
        dirs.extend([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [1.0, 1.0, 1.0]]);
        check::<Vec3>(&dirs);
        check::<DVec3>(&dirs);
    }

    /// `x inverse_binade(x)` is in `[1, 2)` for every normal `x` below
    /// `2^126` (so it is `2^-e`, `2^e` the binade, a power of two by
    /// construction from the bits), and the clamps hold at the ends.
    #[test]
    fn inverse_binade_brings_into_one_two() {
        use crate::num::repr::{F32Bits, F64Bits};
        let mut x = f32::MIN_POSITIVE;
        while x < 2f32.powi(126) {
            for y in [x, x * 1.5, x.next_up(), (2.0 * x).next_down()] {
                let p = y * F32Bits::inverse_binade(y);
                assert!((1.0..2.0).contains(&p), "{y}: {p}");
                assert_eq!(F32Bits::inverse_binade(-y), F32Bits::inverse_binade(y));
            }
            x *= 2.0;
        }
        for big in [2f32.powi(126), f32::MAX, f32::INFINITY, f32::NAN] {
            assert_eq!(F32Bits::inverse_binade(big), 2f32.powi(-126), "{big}");
        }
        for small in [0.0, -0.0, 1e-45, f32::MIN_POSITIVE.next_down()] {
            assert_eq!(F32Bits::inverse_binade(small), 2f32.powi(127), "{small}");
        }
        let mut x = f64::MIN_POSITIVE;
        while x < 2f64.powi(1022) {
            for y in [x, x * 1.5, x.next_up(), (2.0 * x).next_down()] {
                let p = y * F64Bits::inverse_binade(y);
                assert!((1.0..2.0).contains(&p), "{y}: {p}");
            }
            x *= 2.0;
        }
        for big in [2f64.powi(1022), f64::MAX, f64::INFINITY, f64::NAN] {
            assert_eq!(F64Bits::inverse_binade(big), 2f64.powi(-1022), "{big}");
        }
        assert_eq!(F64Bits::inverse_binade(5e-324), 2f64.powi(1023));
    }
}
