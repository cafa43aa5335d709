//! The one dispatch module: which lane types each precision uses on the
//! build's target (the `Repr` impls), the instruction sets a kernel body can
//! be compiled for ([`Isa`]: [`TargetSimd`] here, `Avx2` and `Avx512` in
//! their files), and the per-call choice among them ([`per_call`]).
//!
//! A batch kernel is a [`Kernel`]: its arithmetic written once, generic over
//! the instruction set's eight-lane type. Every instruction set runs any
//! kernel, so a new kernel needs no line per instruction set, and a new
//! instruction set no line per kernel.

use super::portable::{Portable, Portable8};
use crate::num::{F32Bits, F64Bits, Lanes8, Repr, Scalar};

/// An instruction set a kernel can be compiled for. Its values are
/// tokens: made only where the CPU is known to have the instruction set
/// (the target's own always, the others by run-time detection), so that
/// holding one is what makes running code compiled for it sound.
///
/// Public only as the sealed supertrait of [`Simd`](crate::batch::Simd); it is
/// not reachable from outside the crate.
pub trait Isa: Copy {
    /// The eight-lane type of precision `F` on this instruction set.
    type W<F: Scalar>: Lanes8<F = F>;
    /// Kernel `K` on `ray`, `shapes` and `t_max`, compiled for this
    /// instruction set.
    fn kernel<K: Kernel>(self, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output;
    /// `work`, compiled for this instruction set.
    fn work<B: Work>(self, work: B) -> B::Output;
}

/// A batch kernel: the arithmetic of one ray against a group of shapes,
/// written once against [`Isa::W`]. `run` must be `#[inline(always)]` and
/// call only functions that are too (no closures): an instruction set
/// compiles it by inlining it, whole, into a function with its target
/// features enabled. Its three arguments travel in registers to that
/// function, as they would to a plain one.
pub trait Kernel {
    /// The ray the kernel takes.
    type Ray;
    /// The shapes it tests the ray against.
    type Shapes: ?Sized;
    /// Its upper limit on `t`.
    type Limit: Copy;
    /// What it returns.
    type Output;
    /// Whether `Avx512` runs this kernel compiled with AVX-512 enabled, or
    /// (where that comes out slower) its AVX2 copy.
    const AVX512: bool = true;
    /// The kernel, on the lanes of `isa`.
    fn run<I: Isa>(
        isa: I,
        ray: &Self::Ray,
        shapes: &Self::Shapes,
        t_max: Self::Limit,
    ) -> Self::Output;
}

/// Work that runs many kernels (see [`SimdWork`](crate::batch::SimdWork)),
/// compiled for one instruction set as a kernel is.
pub trait Work {
    /// What the work returns.
    type Output;
    /// The work, on the lanes of `isa`.
    fn run<I: Isa>(self, isa: I) -> Self::Output;
}

/// The instruction set the build's target has (SSE2 on the default x86-64
/// target; AVX2 and more with `-C target-cpu=native` on such a CPU; NEON on
/// aarch64).
#[derive(Clone, Copy, Debug, Default)]
pub struct TargetSimd;

impl Isa for TargetSimd {
    type W<F: Scalar> = <F as Repr>::L8;

    #[inline(always)]
    fn kernel<K: Kernel>(self, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
        K::run(self, ray, shapes, t_max)
    }

    #[inline(always)]
    fn work<B: Work>(self, work: B) -> B::Output {
        work.run(self)
    }
}

/// Kernel `K` run once, on the widest instruction set the CPU has: where
/// the build picks at run time (see `rayhit_runtime_avx` in `build.rs`),
/// the copy `with_simd` would run (AVX-512's or AVX2's) on a CPU with
/// them, at the cost of one load and comparison (`Widest`, a detection
/// cached in one byte) and a call per batch; else the target's own.
#[inline(always)]
pub(crate) fn per_call<K: Kernel>(ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
    #[cfg(rayhit_runtime_avx)]
    return match super::Widest::get() {
        // (A kernel that runs its AVX2 copy on `Avx512` is called here
        // directly, not through `Avx512`'s out-of-line step.)
        super::Widest::Avx512(isa) if K::AVX512 => isa.kernel::<K>(ray, shapes, t_max),
        super::Widest::Avx512(isa) => isa.avx2().kernel::<K>(ray, shapes, t_max),
        super::Widest::Avx2(isa) => isa.kernel::<K>(ray, shapes, t_max),
        // (Out of line, so that the caller's loop holds a call on every
        // path rather than the kernel's SSE copy on one: the copy inlined
        // there took registers from the whole loop.)
        super::Widest::Target => target_out_of_line::<K>(ray, shapes, t_max),
    };
    #[cfg(not(rayhit_runtime_avx))]
    TargetSimd.kernel::<K>(ray, shapes, t_max)
}

/// Kernel `K` on the target's own lanes, out of line (see `per_call`).
#[cfg(rayhit_runtime_avx)]
#[inline(never)]
fn target_out_of_line<K: Kernel>(ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
    TargetSimd.kernel::<K>(ray, shapes, t_max)
}

/// The `f32` four lanes of this target: an SSE register on x86, a NEON
/// register on aarch64, an array elsewhere.
#[cfg(rayhit_lanes4 = "sse2")]
type F32Lanes = super::sse2::F32x4;
#[cfg(rayhit_lanes4 = "neon")]
type F32Lanes = super::neon::F32x4;
#[cfg(rayhit_lanes4 = "portable")]
type F32Lanes = Portable<f32>;

/// The `f32` eight lanes of this target: an AVX register where the target
/// has AVX2, two SSE registers on other x86 targets, two NEON registers on
/// aarch64, an array elsewhere.
#[cfg(rayhit_lanes8 = "avx2")]
type F32Lanes8 = super::avx2::F32x8;
#[cfg(rayhit_lanes8 = "sse2")]
type F32Lanes8 = super::sse2::pair::F32x4x2;
#[cfg(rayhit_lanes8 = "neon")]
type F32Lanes8 = super::neon::F32x4x2;
#[cfg(rayhit_lanes8 = "portable")]
type F32Lanes8 = Portable8<f32>;

impl Repr for f32 {
    type L4 = F32Lanes;
    type L8 = F32Lanes8;
    #[cfg(rayhit_runtime_avx)]
    type L8Avx2 = super::avx2::F32x8;
    type Bits = F32Bits;
}

/// `f64` runs on arrays everywhere (the kernels' `f64` paths are not
/// vectorized by hand).
impl Repr for f64 {
    type L4 = Portable<f64>;
    type L8 = Portable8<f64>;
    #[cfg(rayhit_runtime_avx)]
    type L8Avx2 = Portable8<f64>;
    type Bits = F64Bits;
}
