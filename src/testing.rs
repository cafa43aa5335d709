//! The unit tests' source of inputs (compiled for the tests only): one
//! small deterministic generator (Marsaglia's xorshift64) and the float
//! mixes the bit-for-bit tests draw from, aimed at what a kernel's lanes
//! could get wrong: grid values (so that shared edges, face planes, zero
//! direction components and exactly zero edge functions are common), wide
//! random magnitudes, and the special values (signed zeros, infinities,
//! NaN, subnormals). The integration tests, fuzzers and benches draw from
//! the test kit instead; the unit tests stay with the published crate, so
//! they use nothing outside it.

/// A xorshift64 state.
pub(crate) struct Draws(pub(crate) u64);

impl Draws {
    /// The next 64 bits.
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A coordinate on the grid of quarters in `[-2, 2]`, or, one time in
    /// four, a float with 20 random bits and an exponent uniform in
    /// `[-spread / 2, spread / 2)`.
    pub(crate) fn coordinate(&mut self, spread: u64) -> f64 {
        let s = self.next();
        if s.is_multiple_of(4) {
            let m = ((s >> 11) % (1 << 20)) as f64 / (1 << 20) as f64;
            (m - 0.5) * 2f64.powi(((s >> 40) % spread) as i32 - (spread / 2) as i32)
        } else {
            ((s >> 8) % 17) as f64 / 4.0 - 2.0
        }
    }

    /// A point whose three coordinates are drawn by
    /// [`coordinate`](Self::coordinate), in `x`, `y`, `z` order.
    pub(crate) fn point<V: crate::num::Vector>(&mut self, spread: u64) -> V {
        use crate::num::Scalar;
        let mut c = || crate::num::S::<V>::from_f64(self.coordinate(spread));
        let (x, y, z) = (c(), c(), c());
        V::new(x, y, z)
    }

    /// A value on the grid of eighths in `[-4, 4]`.
    pub(crate) fn eighth(&mut self) -> f32 {
        ((self.next() % 65) as f32 - 32.0) / 8.0
    }

    /// A special value (signed zero, infinity, NaN, `MAX`, the smallest
    /// subnormal, one), a small integer, or a float with random bits.
    pub(crate) fn special_f32(&mut self) -> f32 {
        const SPECIAL: [f32; 8] = [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MAX,
            f32::from_bits(1),
            1.0,
        ];
        let s = self.next();
        match s % 4 {
            0 => SPECIAL[(s >> 8) as usize % 8],
            1 => ((s >> 16) % 9) as f32 - 4.0,
            _ => f32::from_bits((s >> 20) as u32),
        }
    }
}

/// A triangle test's answer as bits (`t`, `u`, `v` widened exactly to
/// `f64`, and the side), for the bit-for-bit comparisons.
pub(crate) fn hit_bits<F: crate::Scalar>(
    h: Option<crate::TriangleHit<F>>,
) -> Option<(u64, u64, u64, crate::Side)> {
    h.map(|h| {
        (
            h.t.to_f64().to_bits(),
            h.u.to_f64().to_bits(),
            h.v.to_f64().to_bits(),
            h.side,
        )
    })
}

/// Marsaglia's xorshift64 from `state` as a closure: [`Draws`]'s sequence,
/// for the exact-sign tests.
#[cfg(feature = "exact")]
pub(crate) fn xorshift(state: u64) -> impl FnMut() -> u64 {
    let mut draws = Draws(state);
    move || draws.next()
}

/// Three coordinates for the sign tests: with `wide`, `f64` values at
/// `scale` times `2^-59` to 1 (and, with `zeros`, an exact zero one
/// time in eight); otherwise arbitrary finite `f32` bit patterns.
#[cfg(feature = "exact")]
pub(crate) fn coords(
    wide: bool,
    zeros: bool,
    scale: f64,
    next: &mut dyn FnMut() -> u64,
) -> [f64; 3] {
    let unit =
        |next: &mut dyn FnMut() -> u64| (next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
    [0, 1, 2].map(|_| {
        if !wide {
            return loop {
                let x = f32::from_bits(next() as u32);
                if x.is_finite() {
                    break f64::from(x);
                }
            };
        }
        if zeros && next().is_multiple_of(8) {
            return 0.0;
        }
        let spread = crate::num::exact_sign::scale2(1.0, -((next() % 60) as i32));
        scale * spread * unit(next)
    })
}
