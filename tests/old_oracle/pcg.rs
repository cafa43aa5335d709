//! PCG32 (O'Neill, 2014: XSH-RR output on a 64-bit LCG): the fixed-seed
//! generator of the oracle suite and of the benches' workloads (which
//! include this file by path and add their own `f32` helpers).

/// A PCG32 generator: same seed and stream, same numbers, on every machine.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

#[allow(dead_code)] // each includer uses part of it
impl Pcg32 {
    const MUL: u64 = 6_364_136_223_846_793_005;
    /// PCG's default stream.
    const DEFAULT_STREAM: u64 = 721_347_520_444_481_703;

    /// A generator for `seed` on the default stream.
    pub fn new(seed: u64) -> Self {
        Self::with_stream(seed, Self::DEFAULT_STREAM)
    }

    /// A generator for `seed` on stream `stream`.
    pub fn with_stream(seed: u64, stream: u64) -> Self {
        let mut rng = Self {
            state: 0,
            inc: (stream << 1) | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    /// The next 32 random bits.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(Self::MUL).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform integer in `[0, n)`.
    pub fn below(&mut self, n: u32) -> u32 {
        ((u64::from(self.next_u32()) * u64::from(n)) >> 32) as u32
    }
}
