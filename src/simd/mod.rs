//! SIMD lanes: the lane interfaces of `crate::num` implemented once per
//! instruction set, and the one dispatch module that picks among them.
//!
//! | file | what |
//! | --- | --- |
//! | `portable.rs` | the lanes as arrays: the definition every register type is tested against, and the implementation for `f64` and targets without registers |
//! | `sse2.rs` | `f32` in SSE registers: four lanes in one, eight in two (every x86-64 target) |
//! | `neon.rs` | `f32` in NEON registers: four lanes in one, eight in two (every aarch64 target) |
//! | `avx2.rs` | `f32` in an AVX register, eight lanes; the [`Avx2`] token where the build picks at run time |
//! | `avx512.rs` | the [`Avx512`] token: AVX2's lanes compiled with AVX-512 |
//! | `dispatch.rs` | the lane types each precision uses on the build's target; [`TargetSimd`]; the kernel-body and instruction-set traits; the per-call choice |
//! | `rows.rs` | a batch's rows, eight lanes at a time |
//!
//! Which of them the build's target uses are the `cfg` values
//! `rayhit_lanes4` and `rayhit_lanes8`, set once in `build.rs`. Another
//! instruction set (simd128 on wasm32, say) is a file here
//! implementing `Lanes` and `Lanes8` for `f32` on its registers, values of
//! `rayhit_lanes4` and `rayhit_lanes8` for the targets that have it, and its
//! lines in `dispatch.rs`; the tests in `tests.rs` hold it to
//! `portable.rs` bit for bit. Where an instruction set is detected at run
//! time, its file also holds a token and the
//! `#[target_feature]` function that runs a kernel body, as `avx2.rs` does.

/// A lane-wise operation of a register type that wraps one register: the
/// intrinsic on both registers. Used by the instruction sets' files, whose
/// module docs carry the safety argument: the intrinsic needs only the
/// instruction set, which the file is compiled or called for, and touches
/// no memory.
#[cfg(any(rayhit_lanes4 = "sse2", rayhit_lanes4 = "neon", rayhit_runtime_avx))]
macro_rules! op2 {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> Self {
            // SAFETY: see the module docs (its instruction set, no memory access).
            Self(unsafe { $intrinsic(self.0, o.0) })
        }
    };
}

mod dispatch;
mod portable;
mod rows;

#[cfg(any(rayhit_lanes8 = "avx2", rayhit_runtime_avx))]
mod avx2;
#[cfg(rayhit_runtime_avx)]
mod avx512;
#[cfg(rayhit_lanes4 = "neon")]
mod neon;
#[cfg(rayhit_lanes4 = "sse2")]
mod sse2;
#[cfg(test)]
mod tests;

#[cfg(rayhit_runtime_avx)]
pub use avx2::Avx2;
#[cfg(rayhit_runtime_avx)]
pub use avx512::Avx512;
#[cfg(rayhit_runtime_avx)]
pub(crate) use avx512::Widest;
pub use dispatch::TargetSimd;
#[cfg(rayhit_runtime_avx)]
pub(crate) use dispatch::Work;
pub(crate) use dispatch::{Isa, Kernel, per_call};
#[cfg(test)]
pub(crate) use portable::Portable8;
pub(crate) use rows::{check_lanes, lanes_at, put};
