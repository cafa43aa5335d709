//! NEON registers (aarch64): four `f32` lanes in one register ([`F32x4`])
//! and eight in two ([`F32x4x2`]).
//!
//! NEON's own `FMAX`/`FMIN` propagate a NaN and `FMAXNM`/`FMINNM` drop one,
//! and both order `-0` below `+0`; the lane semantics (`max(a, b)` is
//! `if a > b { a } else { b }`) are neither, so `max` and `min` are a
//! comparison and a bit select, which return one operand's bits unchanged.
//! NEON has no instruction that gathers a mask's sign bits as SSE's
//! `movemask` does: a mask becomes bits by keeping one distinct power of two
//! per lane and adding the lanes. No operation fuses a multiply and an add.
//!
//! Safety of the `unsafe` blocks below: each calls a NEON intrinsic
//! (`core::arch::aarch64`), and the only precondition of those is that the
//! CPU supports NEON. This module is compiled only for aarch64 targets
//! with NEON enabled at compile time (`target_feature = "neon"`, part of
//! every aarch64 target's baseline), so every CPU the code can run on has
//! it. None of them touches memory except the loads and stores, whose
//! comments say why they stay inside their reference.
#![allow(unsafe_code)]

use core::arch::aarch64::*;

use crate::num::{Lanes, Lanes8};

/// Lane `k` holds `1 << k` for lanes 0 to 2, and lane 3 nothing: ANDed with
/// a comparison's mask and summed across, the mask of lanes 0 to 2 as bits.
const BITS3: [u32; 4] = [1, 2, 4, 0];

/// The bit of each lane of the low register of an eight-lane mask.
const BITS_LO: [u32; 4] = [1, 2, 4, 8];

/// The bit of each lane of the high register of an eight-lane mask.
const BITS_HI: [u32; 4] = [16, 32, 64, 128];

/// The register holding `a`.
#[inline(always)]
fn from_array(a: [f32; 4]) -> float32x4_t {
    // SAFETY: see the module docs (NEON); the load reads the 16 bytes of
    // `a`, a local array of four `f32`.
    unsafe { vld1q_f32(a.as_ptr()) }
}

/// The register holding `a`, as `u32` lanes.
#[inline(always)]
fn from_bits(a: &[u32; 4]) -> uint32x4_t {
    // SAFETY: see the module docs (NEON); the load reads the 16 bytes of
    // the four `u32` that `a` refers to.
    unsafe { vld1q_u32(a.as_ptr()) }
}

/// `if m { a } else { b }`, lane by lane, on the bits (`BSL`).
#[inline(always)]
fn select(m: uint32x4_t, a: float32x4_t, b: float32x4_t) -> float32x4_t {
    // SAFETY: see the module docs (NEON, no memory access).
    unsafe { vbslq_f32(m, a, b) }
}

/// `if a > b { a } else { b }`, lane by lane: `b` when either is NaN.
#[inline(always)]
fn max(a: float32x4_t, b: float32x4_t) -> float32x4_t {
    // SAFETY: see the module docs (NEON, no memory access).
    select(unsafe { vcgtq_f32(a, b) }, a, b)
}

/// `if a < b { a } else { b }`, lane by lane: `b` when either is NaN.
#[inline(always)]
fn min(a: float32x4_t, b: float32x4_t) -> float32x4_t {
    // SAFETY: see the module docs (NEON, no memory access).
    select(unsafe { vcltq_f32(a, b) }, a, b)
}

/// Four `f32` lanes in a NEON register.
#[derive(Clone, Copy)]
pub struct F32x4(float32x4_t);

impl core::fmt::Debug for F32x4 {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        self.to_array().fmt(f)
    }
}

/// A comparison of two registers, as a mask of lanes 0 to 2.
macro_rules! cmp {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> u32 {
            // SAFETY: see the module docs (NEON, no memory access).
            unsafe { vaddvq_u32(vandq_u32($intrinsic(self.0, o.0), from_bits(&BITS3))) }
        }
    };
}

/// A comparison of two registers, as a mask of all four lanes.
macro_rules! mask {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> uint32x4_t {
            // SAFETY: see the module docs (NEON, no memory access).
            unsafe { $intrinsic(self.0, o.0) }
        }
    };
}

impl Lanes for F32x4 {
    type F = f32;
    #[inline(always)]
    fn new(x: f32, y: f32, z: f32) -> Self {
        Self(from_array([x, y, z, z]))
    }
    #[inline(always)]
    fn new4(x: f32, y: f32, z: f32, w: f32) -> Self {
        Self(from_array([x, y, z, w]))
    }
    #[inline(always)]
    fn splat(v: f32) -> Self {
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vdupq_n_f32(v) })
    }
    #[inline(always)]
    fn to_array(self) -> [f32; 3] {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe {
            [
                vgetq_lane_f32::<0>(self.0),
                vgetq_lane_f32::<1>(self.0),
                vgetq_lane_f32::<2>(self.0),
            ]
        }
    }
    #[inline(always)]
    fn x(self) -> f32 {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vgetq_lane_f32::<0>(self.0) }
    }
    op2!(add, vaddq_f32);
    op2!(sub, vsubq_f32);
    op2!(mul, vmulq_f32);
    op2!(div, vdivq_f32);
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Self(max(self.0, o.0))
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Self(min(self.0, o.0))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        // FABS clears the sign bit and nothing else, NaN included.
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vabsq_f32(self.0) })
    }
    #[inline(always)]
    fn neg(self) -> Self {
        // FNEG flips the sign bit and nothing else, NaN included.
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vnegq_f32(self.0) })
    }
    cmp!(lt, vcltq_f32);
    cmp!(le, vcleq_f32);
    cmp!(eq, vceqq_f32);
    #[inline(always)]
    fn nle(self, o: Self) -> u32 {
        // BIC: the bits of lanes 0 to 2 where `le` is false.
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vaddvq_u32(vbicq_u32(from_bits(&BITS3), vcleq_f32(self.0, o.0))) }
    }
    #[inline(always)]
    fn rot1(self) -> Self {
        // (y, z, w, x) by rotating the register, then x copied into lane 2:
        // (y, z, x, x).
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vcopyq_laneq_f32::<2, 0>(vextq_f32::<1>(self.0, self.0), self.0) })
    }
    #[inline(always)]
    fn rot2(self) -> Self {
        // (w, x, y, z) by rotating the register, then z copied into lane 0:
        // (z, x, y, z).
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vcopyq_laneq_f32::<0, 2>(vextq_f32::<3>(self.0, self.0), self.0) })
    }
    #[inline(always)]
    fn sum3(self) -> f32 {
        let [x, y, z] = self.to_array();
        (x + y) + z
    }
    type Mask = uint32x4_t;
    #[inline(always)]
    fn to_array4(self) -> [f32; 4] {
        let [x, y, z] = self.to_array();
        // SAFETY: see the module docs (NEON, no memory access).
        [x, y, z, unsafe { vgetq_lane_f32::<3>(self.0) }]
    }
    mask!(lt_mask, vcltq_f32);
    #[inline(always)]
    fn mask_all(b: bool) -> uint32x4_t {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vdupq_n_u32(0u32.wrapping_sub(u32::from(b))) }
    }
    #[inline(always)]
    fn select(m: uint32x4_t, a: Self, b: Self) -> Self {
        Self(select(m, a.0, b.0))
    }
    #[inline(always)]
    fn roll4(self) -> Self {
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { vextq_f32::<1>(self.0, self.0) })
    }
    #[inline(always)]
    fn lt4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vaddvq_u32(vandq_u32(vcltq_f32(self.0, o.0), from_bits(&BITS_LO))) }
    }
    #[inline(always)]
    fn le4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vaddvq_u32(vandq_u32(vcleq_f32(self.0, o.0), from_bits(&BITS_LO))) }
    }
    #[inline(always)]
    fn eq4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe { vaddvq_u32(vandq_u32(vceqq_f32(self.0, o.0), from_bits(&BITS_LO))) }
    }
}

/// Eight `f32` lanes in two NEON registers.
#[derive(Clone, Copy, Debug)]
pub struct F32x4x2([float32x4_t; 2]);

impl F32x4x2 {
    /// `f` on the low registers and on the high ones.
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(float32x4_t, float32x4_t) -> float32x4_t) -> Self {
        Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }
}

/// A lane-wise operation of two register pairs.
macro_rules! op2x2 {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> Self {
            // SAFETY: see the module docs (NEON, no memory access).
            self.map2(o, |a, b| unsafe { $intrinsic(a, b) })
        }
    };
}

/// A comparison of two register pairs, as a mask pair.
macro_rules! cmpx2 {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> [uint32x4_t; 2] {
            // SAFETY: see the module docs (NEON, no memory access).
            [0, 1].map(|h| unsafe { $intrinsic(self.0[h], o.0[h]) })
        }
    };
}

/// A lane-wise operation of two mask pairs.
macro_rules! maskx2 {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(a: [uint32x4_t; 2], b: [uint32x4_t; 2]) -> [uint32x4_t; 2] {
            // SAFETY: see the module docs (NEON, no memory access).
            [0, 1].map(|h| unsafe { $intrinsic(a[h], b[h]) })
        }
    };
}

impl Lanes8 for F32x4x2 {
    type F = f32;
    type Mask = [uint32x4_t; 2];
    #[inline(always)]
    fn splat(v: f32) -> Self {
        // SAFETY: see the module docs (NEON, no memory access).
        let x = unsafe { vdupq_n_f32(v) };
        Self([x, x])
    }
    #[inline(always)]
    fn load(a: &[f32; 8]) -> Self {
        // SAFETY: see the module docs (NEON); each load reads 16 bytes
        // inside a reference to 8 `f32` (NEON loads need no alignment
        // beyond the element's).
        Self(unsafe { [vld1q_f32(a.as_ptr()), vld1q_f32(a.as_ptr().add(4))] })
    }
    #[inline(always)]
    fn store(self, a: &mut [f32; 8]) {
        // SAFETY: see the module docs (NEON); each store writes 16 bytes
        // inside a mutable reference to 8 `f32`.
        unsafe {
            vst1q_f32(a.as_mut_ptr(), self.0[0]);
            vst1q_f32(a.as_mut_ptr().add(4), self.0[1]);
        }
    }
    #[inline(always)]
    fn from_bytes(b: &[u8; 8]) -> Self {
        // SAFETY: see the module docs (NEON); the load reads 8 bytes from a
        // reference to 8 bytes. Bytes widen to 16 and then 32 bits with
        // zero extension, and every `u32` below 2^24 converts exactly.
        Self(unsafe {
            let words = vmovl_u8(vld1_u8(b.as_ptr()));
            [
                vcvtq_f32_u32(vmovl_u16(vget_low_u16(words))),
                vcvtq_f32_u32(vmovl_high_u16(words)),
            ]
        })
    }
    op2x2!(add, vaddq_f32);
    op2x2!(sub, vsubq_f32);
    op2x2!(mul, vmulq_f32);
    op2x2!(div, vdivq_f32);
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: see the module docs (NEON, no memory access).
        Self(unsafe { [vsqrtq_f32(self.0[0]), vsqrtq_f32(self.0[1])] })
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.map2(o, max)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.map2(o, min)
    }
    cmpx2!(lt, vcltq_f32);
    cmpx2!(le, vcleq_f32);
    cmpx2!(eq, vceqq_f32);
    maskx2!(and, vandq_u32);
    maskx2!(or, vorrq_u32);
    // BIC clears the bits of its first operand that its second has.
    maskx2!(and_not, vbicq_u32);
    #[inline(always)]
    fn bits(m: [uint32x4_t; 2]) -> u32 {
        // Each lane's own bit (lanes 0 to 3 in the low register, 4 to 7 in
        // the high one), then the sum across the lanes.
        // SAFETY: see the module docs (NEON, no memory access).
        unsafe {
            let lo = vandq_u32(m[0], from_bits(&BITS_LO));
            let hi = vandq_u32(m[1], from_bits(&BITS_HI));
            vaddvq_u32(vorrq_u32(lo, hi))
        }
    }
    #[inline(always)]
    fn select(m: [uint32x4_t; 2], a: Self, b: Self) -> Self {
        Self([0, 1].map(|h| select(m[h], a.0[h], b.0[h])))
    }
}
