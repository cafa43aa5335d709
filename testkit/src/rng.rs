//! PCG32 (O'Neill, 2014: XSH-RR output on a 64-bit LCG): the benches'
//! fixed-seed generator. Their workloads are the benchmark's definition, so
//! they keep this generator and their own draws, and a table stays
//! comparable with earlier runs; test cases come from the `source` module
//! instead.

use rayhit::glam::Vec3;

/// A PCG32 generator: same seed and stream, same numbers, on every machine.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

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

/// The workloads' `f32` draws.
impl Pcg32 {
    /// Uniform in `[0, 1)`, 24 random bits.
    pub fn unit(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// A point uniform in the cube `[-s, s]^3`.
    pub fn cube(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }

    /// A unit vector uniform on the sphere.
    pub fn sphere(&mut self) -> Vec3 {
        loop {
            let p = self.cube(1.0);
            let l2 = p.length_squared();
            if l2 > 0.01 && l2 <= 1.0 {
                return p / l2.sqrt();
            }
        }
    }

    /// A unit vector along a random axis, either sign.
    pub fn axis(&mut self) -> Vec3 {
        let mut d = Vec3::ZERO;
        d[self.below(3) as usize] = if self.below(2) == 0 { 1.0 } else { -1.0 };
        d
    }
}
