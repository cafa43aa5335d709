//! The lanes as arrays, each operation a loop over them: the definition of
//! the lane semantics (see `crate::num::lanes`), which every register type
//! is tested against bit for bit, and the implementation wherever no
//! register type is used (`f64`, and targets without one).

use crate::num::{Lanes, Lanes8, Scalar};

/// The six arithmetic operations of both widths, lane by lane through the
/// type's `map2`. `max` and `min` are the comparisons written out: with a
/// NaN operand the comparison is false and the second operand is the answer
/// (as SSE's `maxps` and `minps` do).
macro_rules! arithmetic {
    () => {
        #[inline(always)]
        fn add(self, o: Self) -> Self {
            self.map2(o, |a, b| a + b)
        }
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            self.map2(o, |a, b| a - b)
        }
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            self.map2(o, |a, b| a * b)
        }
        #[inline(always)]
        fn div(self, o: Self) -> Self {
            self.map2(o, |a, b| a / b)
        }
        #[inline(always)]
        fn max(self, o: Self) -> Self {
            self.map2(o, |a, b| if a > b { a } else { b })
        }
        #[inline(always)]
        fn min(self, o: Self) -> Self {
            self.map2(o, |a, b| if a < b { a } else { b })
        }
    };
}

/// The lanes as an array, each operation a loop over it: the definition of
/// the semantics, and the implementation wherever no register type is used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Portable<F>([F; 4]);

impl<F: Scalar> Portable<F> {
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(F, F) -> F) -> Self {
        let (a, b) = (self.0, o.0);
        Self([f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])])
    }

    #[inline(always)]
    fn mask(self, o: Self, f: impl Fn(F, F) -> bool) -> u32 {
        let (a, b) = (self.0, o.0);
        u32::from(f(a[0], b[0])) | u32::from(f(a[1], b[1])) << 1 | u32::from(f(a[2], b[2])) << 2
    }

    /// The same on all four lanes.
    #[inline(always)]
    fn mask4(self, o: Self, f: impl Fn(F, F) -> bool) -> u32 {
        self.mask(o, &f) | u32::from(f(self.0[3], o.0[3])) << 3
    }
}

impl<F: Scalar> Lanes for Portable<F> {
    type F = F;
    #[inline(always)]
    fn new(x: F, y: F, z: F) -> Self {
        Self([x, y, z, z])
    }
    #[inline(always)]
    fn new4(x: F, y: F, z: F, w: F) -> Self {
        Self([x, y, z, w])
    }
    #[inline(always)]
    fn splat(v: F) -> Self {
        Self([v; 4])
    }
    #[inline(always)]
    fn to_array(self) -> [F; 3] {
        [self.0[0], self.0[1], self.0[2]]
    }
    #[inline(always)]
    fn x(self) -> F {
        self.0[0]
    }
    arithmetic!();
    #[inline(always)]
    fn abs(self) -> Self {
        Self(self.0.map(F::abs))
    }
    #[inline(always)]
    fn neg(self) -> Self {
        Self(self.0.map(|x| -x))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> u32 {
        self.mask(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> u32 {
        self.mask(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> u32 {
        self.mask(o, |a, b| a == b)
    }
    #[inline(always)]
    fn nle(self, o: Self) -> u32 {
        self.mask(o, |a, b| !(a <= b))
    }
    #[inline(always)]
    fn rot1(self) -> Self {
        let a = self.0;
        Self([a[1], a[2], a[0], a[3]])
    }
    #[inline(always)]
    fn rot2(self) -> Self {
        let a = self.0;
        Self([a[2], a[0], a[1], a[3]])
    }
    #[inline(always)]
    fn sum3(self) -> F {
        let [x, y, z, _] = self.0;
        (x + y) + z
    }
    type Mask = [bool; 4];
    #[inline(always)]
    fn to_array4(self) -> [F; 4] {
        self.0
    }
    #[inline(always)]
    fn lt_mask(self, o: Self) -> [bool; 4] {
        core::array::from_fn(|l| self.0[l] < o.0[l])
    }
    #[inline(always)]
    fn mask_all(b: bool) -> [bool; 4] {
        [b; 4]
    }
    #[inline(always)]
    fn select(m: [bool; 4], a: Self, b: Self) -> Self {
        Self(core::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
    #[inline(always)]
    fn roll4(self) -> Self {
        let a = self.0;
        Self([a[1], a[2], a[3], a[0]])
    }
    #[inline(always)]
    fn lt4(self, o: Self) -> u32 {
        self.mask4(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le4(self, o: Self) -> u32 {
        self.mask4(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq4(self, o: Self) -> u32 {
        self.mask4(o, |a, b| a == b)
    }
}

/// Eight lanes as an array: the definition, and the implementation where
/// no register type is used.
#[derive(Clone, Copy, Debug)]
pub struct Portable8<F>([F; 8]);

impl<F: Scalar> Portable8<F> {
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(F, F) -> F) -> Self {
        Self(core::array::from_fn(|l| f(self.0[l], o.0[l])))
    }
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(F, F) -> bool) -> [bool; 8] {
        core::array::from_fn(|l| f(self.0[l], o.0[l]))
    }
}

impl<F: Scalar> Lanes8 for Portable8<F> {
    type F = F;
    type Mask = [bool; 8];
    #[inline(always)]
    fn splat(v: F) -> Self {
        Self([v; 8])
    }
    #[inline(always)]
    fn load(a: &[F; 8]) -> Self {
        Self(*a)
    }
    #[inline(always)]
    fn store(self, a: &mut [F; 8]) {
        *a = self.0;
    }
    #[inline(always)]
    fn from_bytes(b: &[u8; 8]) -> Self {
        Self(b.map(|x| F::from_u32(u32::from(x))))
    }
    arithmetic!();
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(self.0.map(F::sqrt))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a == b)
    }
    #[inline(always)]
    fn and(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] & b[l])
    }
    #[inline(always)]
    fn or(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] | b[l])
    }
    #[inline(always)]
    fn and_not(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] & !b[l])
    }
    #[inline(always)]
    fn bits(m: [bool; 8]) -> u32 {
        m.iter()
            .enumerate()
            .fold(0, |acc, (l, &b)| acc | u32::from(b) << l)
    }
    #[inline(always)]
    fn select(m: [bool; 8], a: Self, b: Self) -> Self {
        Self(core::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
}
