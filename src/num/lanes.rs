//! What the kernels need of a precision four and eight values at a time:
//! the interfaces [`Lanes`] (the three axes of a box, or the three corners
//! of a triangle, in one register) and [`Lanes8`] (one lane per shape of a
//! batch). Their implementations, one file per instruction set, and the
//! choice of one per precision and target are `crate::simd`'s.
//!
//! Every operation is defined lane by lane with the semantics of the
//! scalar code it replaces, so that a kernel written against these traits
//! gives the same bits as the one-component-at-a-time code: IEEE add,
//! subtract, multiply and divide; `max(a, b)` is `if a > b { a } else { b }`
//! and `min(a, b)` is `if a < b { a } else { b }` (so a NaN in `a` gives
//! `b`: the property the slab test's NaN-safe folds rely on); comparisons
//! are false for NaN. `crate::simd::portable` is that definition, written
//! out on arrays, and every register type is tested against it. In
//! [`Lanes`], only lanes 0 to 2 carry data; lane 3 is computed along and
//! never read.

use core::fmt::Debug;

/// A coordinate axis, as an index the compiler knows is below 3 (so that
/// indexing a three-component array with it needs no bounds check).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Axis {
    /// `x`, index 0.
    X = 0,
    /// `y`, index 1.
    Y = 1,
    /// `z`, index 2.
    Z = 2,
}

impl Axis {
    /// The axis of index `k`, for `k` in 0..3 (`z` for anything larger).
    #[inline(always)]
    pub(crate) fn from_index(k: usize) -> Self {
        match k {
            0 => Axis::X,
            1 => Axis::Y,
            _ => Axis::Z,
        }
    }
}

/// Four lanes of a precision; see the module docs for the semantics.
pub trait Lanes: Copy + Debug + Send + Sync + 'static {
    /// The scalar in each lane.
    type F: Copy;
    /// `(x, y, z)`; lane 3 repeats `z`.
    fn new(x: Self::F, y: Self::F, z: Self::F) -> Self;
    /// `(x, y, z)`, with `w` in lane 3 (any value: lane 3 is computed
    /// along and never read). Where `w` is the value stored next to `z`, the
    /// four lanes can come from one load.
    fn new4(x: Self::F, y: Self::F, z: Self::F, w: Self::F) -> Self;
    /// `v` in every lane.
    fn splat(v: Self::F) -> Self;
    /// Lanes 0, 1, 2.
    fn to_array(self) -> [Self::F; 3];
    /// Lane 0.
    fn x(self) -> Self::F;
    /// Lane-wise `self + o`.
    fn add(self, o: Self) -> Self;
    /// Lane-wise `self - o`.
    fn sub(self, o: Self) -> Self;
    /// Lane-wise `self * o`.
    fn mul(self, o: Self) -> Self;
    /// Lane-wise `self / o`.
    fn div(self, o: Self) -> Self;
    /// Lane-wise `if self > o { self } else { o }`.
    fn max(self, o: Self) -> Self;
    /// Lane-wise `if self < o { self } else { o }`.
    fn min(self, o: Self) -> Self;
    /// Lane-wise absolute value.
    fn abs(self) -> Self;
    /// Lane-wise negation (the sign bit flipped, as `-x` does).
    fn neg(self) -> Self;
    /// Bit `k` set when `self[k] < o[k]`, for `k` in 0..3.
    fn lt(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] <= o[k]`.
    fn le(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] == o[k]`.
    fn eq(self, o: Self) -> u32;
    /// `(y, z, x)`: lane `k` holds lane `k + 1` (mod 3).
    fn rot1(self) -> Self;
    /// `(z, x, y)`: lane `k` holds lane `k + 2` (mod 3).
    fn rot2(self) -> Self;
    /// `max(max(v[k], v[k + 1]), v[k + 2])` in lane `k` (indices mod 3),
    /// with [`Lanes::max`]'s semantics: for values that are not NaN, the
    /// largest of the three in every lane (a `+0`/`-0` tie aside).
    #[inline(always)]
    fn max_all(self) -> Self {
        self.max(self.rot1()).max(self.rot2())
    }
    /// The same with [`Lanes::min`]: the smallest of the three.
    #[inline(always)]
    fn min_all(self) -> Self {
        self.min(self.rot1()).min(self.rot2())
    }
    /// `(x + y) + z`, in that order.
    fn sum3(self) -> Self::F;
    /// Bit `k` set when `self[k] <= o[k]` fails (NaN included): `!le` on
    /// lanes 0 to 2, one comparison.
    fn nle(self, o: Self) -> u32;

    // Four independent lanes (two angles' sines and cosines, say), rather
    // than a vector's three axes: every lane counts below.

    /// A mask of the four lanes, each set or clear, as the comparisons
    /// below make it and [`Lanes::select`] reads it.
    type Mask: Copy;
    /// All four lanes.
    fn to_array4(self) -> [Self::F; 4];
    /// Lane `k` set when `self[k] < o[k]` (false for NaN), all four lanes.
    fn lt_mask(self, o: Self) -> Self::Mask;
    /// Every lane set where `b`, none where not: with [`Lanes::select`],
    /// a choice between two registers on a flag with no branch (where
    /// the flag is a coin toss).
    fn mask_all(b: bool) -> Self::Mask;
    /// `a`'s lane where `m` is set, `b`'s where it is clear: the bits of
    /// one operand, unchanged (NaN payloads and zeros' signs included).
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Lanes `(1, 2, 3, 0)`: lane `k` holds lane `k + 1` (mod 4).
    fn roll4(self) -> Self;
    /// Bit `k` set when `self[k] < o[k]` (false for NaN), for `k` in 0..4.
    fn lt4(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] <= o[k]` (false for NaN), for `k` in 0..4.
    fn le4(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] == o[k]` (false for NaN; `-0 == +0`),
    /// for `k` in 0..4.
    fn eq4(self, o: Self) -> u32;
}

/// Eight lanes of a scalar type: one lane per shape of a batch. The same
/// semantics as [`Lanes`] (see the module docs), on all eight lanes, with
/// comparisons giving a lane mask.
///
pub trait Lanes8: Copy {
    /// The scalar in each lane.
    type F: Copy;
    /// A per-lane flag, as the comparisons give it.
    type Mask: Copy;
    /// `v` in every lane.
    fn splat(v: Self::F) -> Self;
    /// The lanes from an array.
    fn load(a: &[Self::F; 8]) -> Self;
    /// The lanes into an array.
    fn store(self, a: &mut [Self::F; 8]);
    /// Eight bytes as numbers (exact).
    fn from_bytes(b: &[u8; 8]) -> Self;
    /// Lane-wise `self + o`.
    fn add(self, o: Self) -> Self;
    /// Lane-wise `self - o`.
    fn sub(self, o: Self) -> Self;
    /// Lane-wise `self * o`.
    fn mul(self, o: Self) -> Self;
    /// Lane-wise `self / o`.
    fn div(self, o: Self) -> Self;
    /// Lane-wise square root, correctly rounded (as IEEE 754 requires, so
    /// every instruction set gives the scalar `sqrt`'s bits).
    fn sqrt(self) -> Self;
    /// Lane-wise `if self > o { self } else { o }`.
    fn max(self, o: Self) -> Self;
    /// Lane-wise `if self < o { self } else { o }`.
    fn min(self, o: Self) -> Self;
    /// Lane-wise `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// Lane-wise `self <= o`.
    fn le(self, o: Self) -> Self::Mask;
    /// Lane-wise `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// Lane-wise `a && b`.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise `a || b`.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise `a && !b`.
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Bit `l` set when lane `l` is set.
    fn bits(m: Self::Mask) -> u32;
    /// Lane-wise `if m { a } else { b }`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}
