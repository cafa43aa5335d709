//! What the tests draw their inputs with: floats in a precision, uniform
//! values and points from the test kit's `Pcg32`, and vectors from raw
//! bits.

use rayhit::glam::Vec3;
use rayhit::{Scalar, Vector};
use rayhit_testkit::rng::Pcg32;

/// The scalar of a vector type.
pub type S<V> = <V as Vector>::Scalar;

/// `x` rounded to the precision of `V`.
pub fn f<V: Vector>(x: f64) -> S<V> {
    S::<V>::from_f64(x)
}

/// The vector `(x, y, z)`, each rounded to the precision of `V`.
pub fn v<V: Vector>(x: f64, y: f64, z: f64) -> V {
    V::new(f::<V>(x), f::<V>(y), f::<V>(z))
}

/// A uniform value in `[-1, 1)` with 53 random bits.
pub fn signed(rng: &mut Pcg32) -> f64 {
    let bits = (u64::from(rng.next_u32()) << 21) ^ u64::from(rng.next_u32());
    (bits & ((1 << 53) - 1)) as f64 / (1u64 << 52) as f64 - 1.0
}

/// A point uniform in the cube of half-side `scale` around `centre`.
pub fn point<V: Vector>(rng: &mut Pcg32, scale: f64, centre: [f64; 3]) -> V {
    v::<V>(
        centre[0] + scale * signed(rng),
        centre[1] + scale * signed(rng),
        centre[2] + scale * signed(rng),
    )
}

/// A `Vec3` from raw `f32` bits, as the fuzz regressions give inputs.
pub fn bits(x: [u32; 3]) -> Vec3 {
    Vec3::from_array(x.map(f32::from_bits))
}
