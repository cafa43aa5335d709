//! Numbers: the two precisions ([`Scalar`]) and the vector types
//! ([`Vector`]) every kernel is written against once, and the arithmetic
//! the error bounds and exact fallbacks need.
//!
//! - `scalar`: [`Scalar`], for `f32` and `f64`.
//! - `vector`: [`Vector`], for glam's `Vec3`, `Vec3A` and `DVec3`.
//! - `lanes`: what a precision offers four and eight values at a time (the
//!   interfaces; `crate::simd` implements them per instruction set).
//! - `repr`: the private supertraits that tie a precision to its lane
//!   types and bit tricks, and a vector to its components by axis.
//! - `round`: evaluating error bounds so that they stay bounds.
//! - `exact_sign`: exact signs and error-free transformations.
//! - `trig`: sines, cosines and arctangents in turns, with their error
//!   bounds, for the cameras.

mod lanes;
mod repr;
mod scalar;
mod vector;

pub(crate) mod exact_sign;
pub(crate) mod round;
pub(crate) mod trig;

pub(crate) use lanes::{Axis, Lanes, Lanes8};
pub(crate) use repr::{Bits, F32Bits, F64Bits, Repr};
pub use scalar::Scalar;
pub use vector::Vector;
pub(crate) use vector::{unit, unit_and_inverse_length, unit_near};

/// The scalar type of the vector type `V`.
pub(crate) type S<V> = <V as Vector>::Scalar;
/// The four-lane type of the vector type `V`'s scalar.
pub(crate) type L<V> = <S<V> as Repr>::L4;

/// `v` in lanes 0 to 2 (lane 3 repeats `z`).
#[inline(always)]
pub(crate) fn lanes<V: Vector>(v: V) -> L<V> {
    L::<V>::new(v.x(), v.y(), v.z())
}

/// Lanes 0 to 2 as a vector.
#[inline(always)]
pub(crate) fn vector<V: Vector>(l: L<V>) -> V {
    let [x, y, z] = l.to_array();
    V::new(x, y, z)
}
