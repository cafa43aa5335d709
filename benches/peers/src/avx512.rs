//! The token of the floors compiled with AVX-512 (`floors::boxes8`,
//! `cwbvh::NodeFloor`): proof that the CPU has what they are compiled for.

/// Proof that the CPU has AVX2, AVX-512F and AVX-512VL: made only by
/// [`Avx512::detect`] (once, outside a row's loop), so that holding one is
/// what makes calling a function compiled with those features sound.
#[derive(Clone, Copy, Debug)]
pub struct Avx512(());

impl Avx512 {
    /// `Some` where the CPU has AVX2, AVX-512F and AVX-512VL.
    pub fn detect() -> Option<Self> {
        (std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl"))
        .then_some(Avx512(()))
    }
}
