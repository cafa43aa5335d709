//! `arbitrary::Arbitrary` for the public shape and ray types, for fuzzers.
//!
//! Enabled by the `arbitrary` feature. Every coordinate is a raw bit pattern:
//! an `f32` is built from 4 bytes and an `f64` from 8 (little-endian, through
//! `f32::from_bits` / `f64::from_bits`), so every float can come out: NaN
//! with any payload, both infinities, subnormals, `-0.0` and the largest
//! finite values. Nothing is filtered or normalised: most generated shapes
//! are degenerate or invalid, which is what a fuzzer checking "no panic, no
//! NaN" wants. When the input bytes run out, the remaining coordinates are
//! `+0.0` (arbitrary's rule for exhausted data), so short inputs give rays
//! and shapes at the coordinate origin.
//!
//! The impls are generic over the vector type, for both precisions
//! (`Vec3` and `DVec3`); the components are read in the order the fields are
//! declared, `x, y, z` each (a sphere's `center`, then its `radius`; a
//! disc's `center`, `normal`, `radius`, then `inner_radius`).

use ::arbitrary::{Arbitrary, Result, Unstructured, size_hint};

use crate::num::Vector;
use crate::{Aabb, Disc, Plane, Ray, Sphere, Triangle};

/// A vector from three raw-bit scalars, `x`, `y`, `z`.
fn vector<'a, V>(u: &mut Unstructured<'a>) -> Result<V>
where
    V: Vector,
    <V as Vector>::Scalar: Arbitrary<'a>,
{
    let x = <V as Vector>::Scalar::arbitrary(u)?;
    let y = <V as Vector>::Scalar::arbitrary(u)?;
    let z = <V as Vector>::Scalar::arbitrary(u)?;
    Ok(V::new(x, y, z))
}

/// The size hint of `n` vectors: `3 n` scalars.
fn vectors_hint<'a, V>(depth: usize, n: usize) -> (usize, Option<usize>)
where
    V: Vector,
    <V as Vector>::Scalar: Arbitrary<'a>,
{
    let one = <<V as Vector>::Scalar as Arbitrary<'a>>::size_hint(depth);
    size_hint::and_all(&[one; 9][..3 * n])
}

macro_rules! impl_arbitrary {
    ($(#[$doc:meta])* $T:ident { $($field:ident),+ }, $n:expr) => {
        $(#[$doc])*
        impl<'a, V> Arbitrary<'a> for $T<V>
        where
            V: Vector,
            <V as Vector>::Scalar: Arbitrary<'a>,
        {
            fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
                Ok(Self {
                    $($field: vector(u)?,)+
                })
            }

            fn size_hint(depth: usize) -> (usize, Option<usize>) {
                vectors_hint::<V>(depth, $n)
            }
        }
    };
}

impl_arbitrary!(
    /// Raw bit patterns for `origin` then `dir` (every float, NaN and
    /// infinities included; see the `arbitrary` feature).
    Ray { origin, dir },
    2
);
impl_arbitrary!(
    /// Raw bit patterns for `min` then `max`: inverted, NaN and infinite
    /// boxes included.
    Aabb { min, max },
    2
);
impl_arbitrary!(
    /// Raw bit patterns for `point` then `normal`: zero and non-finite
    /// normals included.
    Plane { point, normal },
    2
);
impl_arbitrary!(
    /// Raw bit patterns for `a`, `b`, `c`: zero-area and non-finite
    /// triangles included.
    Triangle { a, b, c },
    3
);

/// Raw bit patterns for `center`'s `x, y, z` then `radius`: negative, zero,
/// subnormal and non-finite radii included.
impl<'a, V> Arbitrary<'a> for Sphere<V>
where
    V: Vector,
    <V as Vector>::Scalar: Arbitrary<'a>,
{
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(Self {
            center: vector(u)?,
            radius: <V as Vector>::Scalar::arbitrary(u)?,
        })
    }

    fn size_hint(depth: usize) -> (usize, Option<usize>) {
        let one = <<V as Vector>::Scalar as Arbitrary<'a>>::size_hint(depth);
        size_hint::and(vectors_hint::<V>(depth, 1), one)
    }
}

/// Raw bit patterns for `center`'s `x, y, z`, `normal`'s, then `radius`
/// and `inner_radius`: zero and non-finite normals, negative, zero,
/// subnormal and non-finite radii, and holes larger than the disc included.
impl<'a, V> Arbitrary<'a> for Disc<V>
where
    V: Vector,
    <V as Vector>::Scalar: Arbitrary<'a>,
{
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(Self {
            center: vector(u)?,
            normal: vector(u)?,
            radius: <V as Vector>::Scalar::arbitrary(u)?,
            inner_radius: <V as Vector>::Scalar::arbitrary(u)?,
        })
    }

    fn size_hint(depth: usize) -> (usize, Option<usize>) {
        let one = <<V as Vector>::Scalar as Arbitrary<'a>>::size_hint(depth);
        size_hint::and_all(&[vectors_hint::<V>(depth, 2), one, one])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

    #[test]
    fn floats_come_from_raw_little_endian_bits() {
        // x = NaN (0x7fc00001), y = -0.0, z = smallest subnormal; then dir
        // runs out of data and is all +0.0.
        let bytes = [
            0x01, 0x00, 0xc0, 0x7f, 0x00, 0x00, 0x00, 0x80, 0x01, 0x00, 0x00, 0x00,
        ];
        let ray = Ray::<Vec3>::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
        assert_eq!(ray.origin.x.to_bits(), 0x7fc0_0001);
        assert_eq!(ray.origin.y.to_bits(), 0x8000_0000);
        assert_eq!(ray.origin.z, f32::from_bits(1));
        assert_eq!(ray.dir.to_array().map(f32::to_bits), [0; 3]);
    }

    #[test]
    fn sizes_match_the_precision() {
        assert_eq!(Ray::<Vec3>::size_hint(0), (24, Some(24)));
        assert_eq!(Triangle::<DVec3>::size_hint(0), (72, Some(72)));
        let bytes = [0xffu8; 72];
        let tri = Triangle::<DVec3>::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
        assert!(tri.c.z.is_nan());
    }

    #[test]
    fn a_sphere_is_its_centre_then_its_radius() {
        assert_eq!(Sphere::<Vec3>::size_hint(0), (16, Some(16)));
        assert_eq!(Sphere::<DVec3>::size_hint(0), (32, Some(32)));
        // Centre (1, -0.0, inf), radius -2; in f64 the radius runs out: +0.0.
        let mut bytes = [0u8; 16];
        for (i, x) in [1.0f32, -0.0, f32::INFINITY, -2.0].into_iter().enumerate() {
            bytes[4 * i..4 * i + 4].copy_from_slice(&x.to_le_bytes());
        }
        let s = Sphere::<Vec3>::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
        assert_eq!(
            s.center.to_array().map(f32::to_bits),
            [1.0f32, -0.0, f32::INFINITY].map(f32::to_bits)
        );
        assert_eq!(s.radius, -2.0);
        let s = Sphere::<DVec3>::arbitrary(&mut Unstructured::new(&[0xff; 24])).unwrap();
        assert!(s.center.z.is_nan());
        assert_eq!(s.radius.to_bits(), 0);
    }

    #[test]
    fn a_disc_is_its_centre_normal_then_radii() {
        assert_eq!(Disc::<Vec3>::size_hint(0), (32, Some(32)));
        assert_eq!(Disc::<DVec3>::size_hint(0), (64, Some(64)));
        // Centre (1, 2, 3), normal (0, 0, -0.0), radius NaN, inner radius
        // 0.5; in f64 the inner radius runs out: +0.0.
        let xs = [1.0f32, 2.0, 3.0, 0.0, 0.0, -0.0, f32::NAN, 0.5];
        let mut bytes = [0u8; 32];
        for (i, x) in xs.into_iter().enumerate() {
            bytes[4 * i..4 * i + 4].copy_from_slice(&x.to_le_bytes());
        }
        let d = Disc::<Vec3>::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
        assert_eq!(d.center, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(d.normal.to_array().map(f32::to_bits), [0, 0, 0x8000_0000]);
        assert!(d.radius.is_nan());
        assert_eq!(d.inner_radius, 0.5);
        let d = Disc::<DVec3>::arbitrary(&mut Unstructured::new(&[0xff; 56])).unwrap();
        assert!(d.radius.is_nan());
        assert_eq!(d.inner_radius.to_bits(), 0);
    }
}
