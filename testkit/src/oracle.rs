//! `rayhit::exact::oracle` for inputs a test knows are finite: the same
//! names, where the ones that answer `None` for a non-finite input (`r`,
//! `rv`, `triangle`, `box_face`, `segment_crossing`, `mt_bounds`) panic
//! instead, which fails the test that passed such an input. Everything else
//! is the crate's own.

use rayhit::exact::oracle as exact;
pub use rayhit::exact::oracle::*;
use rayhit::{Aabb, BoxFace, Ray, Scalar, Triangle, Vector};

/// Why an exact value is missing: the caller's input was not finite.
const FINITE: &str = "a test input the caller made finite";

/// The exact value of a finite float.
pub fn r<F: Scalar>(x: F) -> R {
    exact::r(x).expect(FINITE)
}

/// The exact value of a finite vector.
pub fn rv<V: Vector>(v: V) -> R3 {
    exact::rv(v).expect(FINITE)
}

/// [`exact::triangle`] of finite inputs.
pub fn triangle<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> ExactTriangle {
    exact::triangle(ray, tri).expect(FINITE)
}

/// [`exact::box_face`] of finite inputs.
pub fn box_face<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> (Option<BoxFace>, bool) {
    exact::box_face(ray, b).expect(FINITE)
}

/// [`exact::segment_crossing`] of finite inputs, a moving ray and a
/// segment not seen end-on.
pub fn segment_crossing<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> R {
    exact::segment_crossing(ray, tri).expect("finite inputs, a segment not seen end-on")
}

/// [`exact::mt_bounds`] of finite inputs.
pub fn mt_bounds<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, u: &R, v: &R) -> (R, R, R) {
    exact::mt_bounds(ray, tri, u, v).expect(FINITE)
}
