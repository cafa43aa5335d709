//! Shared test support: generators, the random source, and the exact
//! oracle, which is the crate's public `rayhit::exact` module (its building
//! blocks in `rayhit::exact::oracle`, re-exported here under the short names
//! the tests use).
#![allow(dead_code)]

pub mod generators;
mod pcg;

pub use pcg::Pcg32;

#[allow(unused_imports)]
pub use rayhit::exact::oracle::*;

/// The oracle's `f64` draws (the generator itself is in `pcg.rs`).
impl Pcg32 {
    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn unit(&mut self) -> f64 {
        let hi = u64::from(self.next_u32()) << 21;
        let lo = u64::from(self.next_u32()) >> 11;
        (hi ^ lo) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// `2^x` for `x` uniform in `[lo, hi)`: log-uniform magnitudes.
    pub fn log2_range(&mut self, lo: f64, hi: f64) -> f64 {
        self.range(lo, hi).exp2()
    }

    /// True with probability `1/n`.
    pub fn one_in(&mut self, n: u32) -> bool {
        self.below(n) == 0
    }

    /// A point uniform in the unit ball's cube shell, as a direction: not
    /// too short, random orientation.
    pub fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            ];
            let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if l2 > 0.04 && l2 <= 1.0 {
                let l = l2.sqrt();
                return [v[0] / l, v[1] / l, v[2] / l];
            }
        }
    }
}
