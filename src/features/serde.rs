//! [`serde`] support (feature `serde`).
//!
//! [`Ray`](crate::Ray), [`Aabb`], [`Triangle`](crate::Triangle),
//! [`Plane`](crate::Plane), the hits ([`TriangleHit`](crate::TriangleHit),
//! [`TriangleHitError`](crate::TriangleHitError), [`BoxHit`](crate::BoxHit))
//! and [`Side`](crate::Side), [`BoxFace`](crate::BoxFace) derive
//! `Serialize` and `Deserialize`: a struct of its fields by name, each
//! vector as glam serializes it (a sequence `[x, y, z]`), an enum by its
//! variant's name. A [`ValidAabb`] is written as its [`Aabb`] and checked
//! when it is read: a box with `min > max` on an axis or a coordinate that is
//! not finite is an error, never an invalid
//! `ValidAabb`.
//!
//! Every float goes through serde's `f32` or `f64`, so a binary format that
//! stores floats as their bits (postcard, bincode, CBOR) gives back every
//! bit: NaN payloads, `-0.0`, infinities, subnormals. A text format may
//! not: JSON, for one, has no NaN or infinity.

use serde::{Deserialize, Deserializer, Serialize, Serializer, de::Error as _};

use crate::num::Vector;
use crate::{Aabb, ValidAabb};

impl<V: Vector + Serialize> Serialize for ValidAabb<V> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.aabb().serialize(serializer)
    }
}

impl<'de, V: Vector + Deserialize<'de>> Deserialize<'de> for ValidAabb<V> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let aabb = Aabb::<V>::deserialize(deserializer)?;
        ValidAabb::new(aabb).ok_or_else(|| {
            D::Error::custom(
                "not a valid box: every coordinate must be finite, and min <= max on every axis",
            )
        })
    }
}
