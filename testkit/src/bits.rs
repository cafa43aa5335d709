//! Bit-for-bit comparisons: the kernels promise the same bits across their
//! forms (lanes, batches, instruction sets, vector types), so the tests
//! compare bits, which tell `-0.0` from `0.0` and one rounding from another.
//! Every NaN compares as one pattern: which NaN's payload an operation
//! passes on is the hardware's choice, only that it is NaN is specified.

use rayhit::{Scalar, Side, TriangleHit, Vector};

/// A float's bits (widened to `f64`, which is exact); every NaN alike.
pub fn bits<F: Scalar>(x: F) -> u64 {
    let x = x.to_f64();
    if x.is_nan() { u64::MAX } else { x.to_bits() }
}

/// A vector's bits, component by component.
pub fn vector_bits<V: Vector>(v: V) -> [u64; 3] {
    [v.x(), v.y(), v.z()].map(bits)
}

/// A vector's bits with NaN payloads as they are, for where a value must
/// come back unchanged, NaN included.
pub fn payload_bits<V: Vector>(v: V) -> [u64; 3] {
    [v.x(), v.y(), v.z()].map(|c| c.to_f64().to_bits())
}

/// A triangle hit's bits: `t`, `u`, `v` and the side.
pub fn hit_bits<F: Scalar>(h: Option<TriangleHit<F>>) -> Option<([u64; 3], Side)> {
    h.map(|h| ([bits(h.t), bits(h.u), bits(h.v)], h.side))
}

/// A box test's interval's bits.
pub fn interval_bits<F: Scalar>(x: Option<(F, F)>) -> Option<(u64, u64)> {
    x.map(|(a, b)| (bits(a), bits(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_tell_signed_zeros_apart_and_every_nan_alike() {
        assert_ne!(bits(0.0f32), bits(-0.0f32));
        assert_eq!(bits(f32::NAN), bits(-f64::NAN));
        assert_ne!(bits(1.0f64), bits(1.0f64.next_up()));
        let h = TriangleHit {
            t: 1.0f32,
            u: 0.0,
            v: -0.0,
            side: Side::Back,
        };
        assert_ne!(
            hit_bits(Some(h)),
            hit_bits(Some(TriangleHit { v: 0.0, ..h }))
        );
        assert_ne!(hit_bits(Some(h)), hit_bits::<f32>(None));
    }
}
