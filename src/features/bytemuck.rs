//! [`bytemuck`] casts for the plain types (feature `bytemuck`): a slice of
//! rays, boxes, triangles or planes viewed as bytes, for a GPU buffer or a
//! file, and back, without copying.
//!
//! - [`Ray`], [`Aabb`], [`Triangle`], [`Plane`] and [`TriangleHitError`] are
//!   [`Zeroable`] over a `Zeroable` vector or scalar, and [`Pod`] over a
//!   `Pod` one: glam's `Vec3` and `DVec3`, and `f32`, `f64`. They are
//!   `#[repr(C)]`: the fields in the order they are declared, each vector
//!   as glam lays it out (`x, y, z`), with no padding, so a
//!   `Triangle<Vec3>` is nine `f32`, 36 bytes.
//! - glam's `Vec3A` is only `Zeroable` and `AnyBitPattern` (its fourth lane
//!   is not a value), so the shapes over it are only `Zeroable`; use `Vec3`
//!   for buffers.
//! - [`ValidAabb`] is [`NoUninit`] (it can be written as bytes) and
//!   [`CheckedBitPattern`]: bytes read back as a `ValidAabb` are checked
//!   with [`Aabb::is_valid`], so `bytemuck::checked::try_cast_slice` fails
//!   on an inverted or non-finite box instead of making an invalid one.
//! - The hits with an enum field ([`TriangleHit`](crate::TriangleHit),
//!   [`BoxHit`](crate::BoxHit)) are `#[repr(C)]` but not `Pod`: not every
//!   byte is a valid side or face.
//!
//! ```
//! use rayhit::{Triangle, glam::Vec3};
//! let tris = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y); 2];
//! let bytes: &[u8] = bytemuck::cast_slice(&tris);
//! assert_eq!(bytes.len(), 2 * 9 * 4);
//! // The second corner's x, as the GPU reads it.
//! assert_eq!(bytes[12..16], 1.0f32.to_ne_bytes());
//! let back: &[Triangle] = bytemuck::cast_slice(bytes);
//! assert_eq!(back, tris);
//! ```

// The impls below are `unsafe impl`s of bytemuck's marker traits: the
// crate's types are generic over the vector type, and bytemuck's derive
// does not accept a generic struct for `Pod` (it cannot see the padding).
// Each impl's soundness is argued at the macro and at `ValidAabb`.
#![allow(unsafe_code)]

use bytemuck::{CheckedBitPattern, NoUninit, Pod, Zeroable};

use crate::num::Vector;
use crate::{Aabb, Plane, Ray, Triangle, TriangleHitError, ValidAabb};

/// `Zeroable` and `Pod` for a `#[repr(C)]` struct all of whose fields have
/// the type parameter's type.
///
/// Sound for every such struct: (1) `Zeroable`: all fields zero is a valid
/// value when the field type is `Zeroable`. (2) `Pod`: a `repr(C)` struct
/// places its fields in order, each at the next offset aligned for it; all
/// fields have one type `T`, whose size is a multiple of its alignment, so
/// field `k` sits at `k * size_of::<T>()` and the struct's size is
/// `n * size_of::<T>()`, with no padding anywhere; every bit pattern of the
/// struct is then a bit pattern of each field, valid when `T: Pod`. The
/// structs are `Copy` and `'static` when `T` is, as `Pod` requires. The
/// tests check the sizes of the concrete types.
macro_rules! pod {
    ($($ty:ident),*) => {$(
        // SAFETY: (1) above.
        unsafe impl<T: Zeroable> Zeroable for $ty<T> {}
        // SAFETY: (2) above.
        unsafe impl<T: Pod> Pod for $ty<T> {}
    )*};
}

pod!(Ray, Aabb, Triangle, Plane, TriangleHitError);

// SAFETY: `ValidAabb` is `repr(transparent)` over an `Aabb<V>`, which is
// `Pod` for `V: Pod` (above), so its bytes are all initialised (no padding).
unsafe impl<V: Pod> NoUninit for ValidAabb<V> {}

// SAFETY: `Bits` is the `Aabb<V>` that `ValidAabb` is `repr(transparent)`
// over, so the two have one layout and any `Aabb<V>` bit pattern is a
// bit pattern of the `ValidAabb`; the ones accepted are exactly those
// `ValidAabb::new` accepts (`is_valid`), which is the type's invariant.
unsafe impl<V: Vector + Pod> CheckedBitPattern for ValidAabb<V> {
    type Bits = Aabb<V>;

    #[inline]
    fn is_valid_bit_pattern(bits: &Aabb<V>) -> bool {
        bits.is_valid()
    }
}
