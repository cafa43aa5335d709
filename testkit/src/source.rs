//! [`Source`]: where every test case's randomness comes from, so that the
//! tests, the corpus tools and the fuzz targets draw their cases the same
//! way. It is a proptest runner: seeded for the tests and the corpus,
//! reading the fuzzer's bytes for the fuzz targets (proptest's
//! `PassThrough` generator, which hands out the bytes as they are, then
//! zeros). So every case family can draw from the crate's public
//! strategies ([`rayhit::strategies`]) as well as make its own choices.

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// A source of random choices: a proptest runner and the draws the case
/// generators make from it.
pub struct Source {
    runner: TestRunner,
}

impl core::fmt::Debug for Source {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("Source")
    }
}

impl Source {
    /// A source seeded with `seed`: the same choices on every machine.
    pub fn seeded(seed: u64) -> Self {
        let mut bytes = [0u8; 16];
        bytes[..8].copy_from_slice(&seed.to_le_bytes());
        bytes[8..].copy_from_slice(&(!seed).rotate_left(17).to_le_bytes());
        Self::with_rng(TestRng::from_seed(RngAlgorithm::XorShift, &bytes))
    }

    /// A source that reads `bytes` (a fuzz input), then zeros.
    pub fn from_bytes(bytes: &[u8]) -> Self {
        Self::with_rng(TestRng::from_seed(RngAlgorithm::PassThrough, bytes))
    }

    fn with_rng(rng: TestRng) -> Self {
        // Few local rejections: on a fuzzer's bytes (zeros once they run
        // out) a filter can reject every draw, and the case is then skipped.
        let config = Config {
            max_local_rejects: 256,
            ..Config::default()
        };
        Self {
            runner: TestRunner::new_with_rng(config, rng),
        }
    }

    /// A value of `strategy`, or `None` where its filters rejected every
    /// draw.
    pub fn draw<S: Strategy>(&mut self, strategy: &S) -> Option<S::Value> {
        strategy
            .new_tree(&mut self.runner)
            .ok()
            .map(|tree| tree.current())
    }

    /// 64 random bits.
    pub fn bits(&mut self) -> u64 {
        proptest::prelude::Rng::next_u64(self.runner.rng())
    }

    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// `2^x` for `x` uniform in `[lo, hi)`: log-uniform magnitudes.
    pub fn log2_range(&mut self, lo: f64, hi: f64) -> f64 {
        self.range(lo, hi).exp2()
    }

    /// `2^k` for an integer `k` uniform in `[lo, hi]`: an exact scale.
    pub fn pow2(&mut self, lo: i32, hi: i32) -> f64 {
        2f64.powi(lo + self.below((hi - lo + 1) as u32) as i32)
    }

    /// Uniform integer in `[0, n)` (0 for `n = 0`).
    pub fn below(&mut self, n: u32) -> u32 {
        (((self.bits() >> 32) * u64::from(n)) >> 32) as u32
    }

    /// An index uniform in `[0, n)`.
    pub fn index(&mut self, n: usize) -> usize {
        self.below(n as u32) as usize
    }

    /// True with probability `1/n`.
    pub fn one_in(&mut self, n: u32) -> bool {
        self.below(n) == 0
    }

    /// `1` or `-1`, equally likely.
    pub fn sign(&mut self) -> f64 {
        if self.one_in(2) { 1.0 } else { -1.0 }
    }

    /// A unit vector, uniform on the sphere (a point uniform in the unit
    /// ball's shell `0.2 < |p| <= 1`, normalised).
    pub fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [0; 3].map(|_| self.range(-1.0, 1.0));
            let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if l2 > 0.04 && l2 <= 1.0 {
                let l = l2.sqrt();
                return v.map(|x| x / l);
            }
            // On a fuzzer's exhausted bytes every draw is the same: give a
            // fixed direction rather than loop.
            if self.bits() == 0 {
                return [0.6, -0.8, 0.0];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seeded sources repeat; different seeds differ; draws stay in range.
    #[test]
    fn seeded_sources_repeat_and_draws_stay_in_range() {
        let (mut a, mut b, mut c) = (Source::seeded(7), Source::seeded(7), Source::seeded(8));
        let xs: Vec<u64> = (0..8).map(|_| a.bits()).collect();
        assert_eq!(xs, (0..8).map(|_| b.bits()).collect::<Vec<_>>());
        assert_ne!(xs, (0..8).map(|_| c.bits()).collect::<Vec<_>>());
        let mut seen = [false; 5];
        for _ in 0..1000 {
            let u = a.unit();
            assert!((0.0..1.0).contains(&u));
            seen[a.index(5)] = true;
            let d = a.direction();
            assert!(((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - 1.0).abs() < 1e-12);
        }
        assert!(seen.iter().all(|&s| s));
    }

    /// A fuzz input's bytes come out as they are, then zeros.
    #[test]
    fn bytes_come_out_as_they_are() {
        let mut s = Source::from_bytes(&[1, 0, 0, 0, 0, 0, 0, 0, 0xff]);
        assert_eq!(s.bits(), 1);
        assert_eq!(s.bits(), 0xff);
        assert_eq!(s.bits(), 0);
        assert_eq!(s.direction(), [0.6, -0.8, 0.0]);
    }
}
