//! AVX-512 (F and VL, with AVX2): the [`Avx512`] token and the function
//! that runs a kernel body compiled with AVX-512 enabled. The lanes are
//! AVX2's eight (`super::avx2::F32x8`); compiled with AVX-512 they get twice
//! the vector registers, so a ray's prepared values stay in registers
//! across a node's boxes, and comparisons into mask registers.
#![allow(unsafe_code)]

use core::sync::atomic::{AtomicU8, Ordering};

use super::avx2::Avx2;
use super::{Isa, Kernel, Work};
use crate::num::{Repr, Scalar};

/// AVX-512 (with its 256-bit forms, AVX-512VL), on a CPU that has it and
/// AVX2: [`with_simd`](crate::batch::with_simd) makes one only after checking
/// (the same builds as [`Avx2`]).
///
/// The box kernels run on the same eight lanes as with [`Avx2`], compiled
/// with AVX-512 enabled: twice the vector registers, so a ray's prepared
/// values stay in registers across a node's boxes, and comparisons into
/// mask registers. The triangle batch runs its AVX2 copy (compiled with
/// AVX-512 it comes out slower). The answers are the same bits.
#[derive(Clone, Copy, Debug)]
pub struct Avx512(Avx2);

impl Avx512 {
    /// `Some` when the CPU has AVX2, AVX-512F and AVX-512VL: where an
    /// `Avx512` is made, from the `Avx2` that detection gave (and, from
    /// its cached answer, in [`Widest::get`]).
    #[inline]
    pub(crate) fn detect() -> Option<Self> {
        let avx2 = Avx2::detect()?;
        (std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl"))
            .then_some(Avx512(avx2))
    }

    /// The AVX2 token this one holds (a CPU with AVX-512 has AVX2).
    #[inline(always)]
    pub(crate) fn avx2(self) -> Avx2 {
        self.0
    }
}

/// The widest instruction set the per-call kernels can use on this CPU:
/// detected on the first call, then read from one byte.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Widest {
    /// Neither AVX2 nor AVX-512: the target's own.
    Target,
    Avx2(Avx2),
    Avx512(Avx512),
}

/// [`Widest`] as found by detection: `UNKNOWN` until the first call.
static WIDEST: AtomicU8 = AtomicU8::new(UNKNOWN);
const UNKNOWN: u8 = 0;
const TARGET: u8 = 1;
const AVX2: u8 = 2;
/// The one code with the high bit set: the common answer is one test of
/// the byte's sign.
const AVX512: u8 = 0x80;

impl Widest {
    /// The widest instruction set, from the cache: one load and a
    /// comparison, where the detection macros load and test a word per
    /// feature (three for AVX-512).
    #[inline(always)]
    pub(crate) fn get() -> Self {
        let code = WIDEST.load(Ordering::Relaxed);
        // SAFETY (both blocks): `WIDEST` holds `AVX512` or `AVX2` only
        // where `Widest::detect` stored it, after `Avx2::detect` (and, for
        // `AVX512`, `Avx512::detect`) returned `Some` in this process.
        if code & AVX512 != 0 {
            Widest::Avx512(Avx512(unsafe { Avx2::detected() }))
        } else if code == AVX2 {
            Widest::Avx2(unsafe { Avx2::detected() })
        } else if code == TARGET {
            Widest::Target
        } else {
            Self::detect()
        }
    }

    /// Detection, once per process (or a few times, if threads race: each
    /// stores the same answer).
    #[cold]
    #[inline(never)]
    fn detect() -> Self {
        let (widest, code) = if let Some(isa) = Avx512::detect() {
            (Widest::Avx512(isa), AVX512)
        } else if let Some(isa) = Avx2::detect() {
            (Widest::Avx2(isa), AVX2)
        } else {
            (Widest::Target, TARGET)
        };
        WIDEST.store(code, Ordering::Relaxed);
        widest
    }
}

impl Isa for Avx512 {
    type W<F: Scalar> = <F as Repr>::L8Avx2;

    #[inline(always)]
    fn kernel<K: Kernel>(self, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
        if K::AVX512 {
            // SAFETY: the one precondition of calling a function compiled
            // with `#[target_feature(enable = "avx2,avx512f,avx512vl")]` is
            // that the CPU has those; an `Avx512` exists only where
            // `Avx512::detect` found them.
            unsafe { kernel::<K>(self, ray, shapes, t_max) }
        } else {
            avx2_out_of_line::<K>(self.0, ray, shapes, t_max)
        }
    }

    #[inline(always)]
    fn work<B: Work>(self, work: B) -> B::Output {
        // SAFETY: as above.
        unsafe { run(self, work) }
    }
}

/// Kernel `K`, compiled with AVX-512 enabled (the kernel is inlined, whole,
/// into this function).
#[target_feature(enable = "avx2,avx512f,avx512vl")]
#[inline]
fn kernel<K: Kernel>(isa: Avx512, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
    K::run(isa, ray, shapes, t_max)
}

/// `work`, compiled with AVX-512 enabled.
#[target_feature(enable = "avx2,avx512f,avx512vl")]
#[inline]
fn run<B: Work>(isa: Avx512, work: B) -> B::Output {
    work.run(isa)
}

/// Kernel `K`'s AVX2 copy, kept out of line so that it is not inlined into
/// (and recompiled for) an AVX-512 caller.
#[inline(never)]
fn avx2_out_of_line<K: Kernel>(
    isa: Avx2,
    ray: &K::Ray,
    shapes: &K::Shapes,
    t_max: K::Limit,
) -> K::Output {
    isa.kernel::<K>(ray, shapes, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cached choice is what detection finds, on the call that
    /// detects and on the calls that read the cache.
    #[test]
    fn the_cached_choice_is_the_detection() {
        let detected = if Avx512::detect().is_some() {
            AVX512
        } else if Avx2::detect().is_some() {
            AVX2
        } else {
            TARGET
        };
        for _ in 0..3 {
            let got = match Widest::get() {
                Widest::Avx512(_) => AVX512,
                Widest::Avx2(_) => AVX2,
                Widest::Target => TARGET,
            };
            assert_eq!(got, detected);
            assert_eq!(WIDEST.load(Ordering::Relaxed), detected);
        }
    }
}
