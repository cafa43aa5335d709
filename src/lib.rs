//! Pinhole-camera primary rays and ray/plane, ray/box and ray/triangle
//! intersection, as small pure functions over [`glam`] vectors, with error
//! bounds that are derived, documented and tested against exact arithmetic.
//!
//! ```
//! use rayhit::{Aabb, PinholeCamera, Triangle, ray_aabb, ray_triangle, glam::Vec3};
//!
//! let cam = PinholeCamera::from_fov(
//!     Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, Vec3::Y, 60f32.to_radians(), 64, 48,
//! ).unwrap();
//! let ray = cam.pixel_ray(32, 24);
//! let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
//! let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
//! assert!((hit.t - 5.0).abs() < 1e-3);
//! let bounds = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
//! let (enter, _exit) = ray_aabb(&ray, &bounds, f32::INFINITY).unwrap();
//! assert!(enter <= hit.t);
//! ```
//!
//! # Conventions
//!
//! - A [`Ray`] is `origin + t * dir` for `t >= 0`. `dir` need not be unit
//!   length; every `t` is measured in multiples of `dir`. A zero or
//!   non-finite `dir` (or origin) hits nothing.
//! - A surface ([`Plane`], [`Triangle`]) is hit at `0 < t <= t_max`: a hit at
//!   exactly `t = 0` is the ray's own starting surface and is not reported.
//! - A box ([`Aabb`]) is a closed solid: the result is the interval
//!   `[max(t_enter, 0), min(t_exit, t_max)]` when it is not empty, so a ray
//!   starting inside has `enter = 0`.
//! - Shapes are closed: a ray through a box face, edge or corner, or through
//!   a triangle edge or corner, hits ([`ray_triangle_one_hit`] is the
//!   deliberate exception, for meshes).
//! - Triangle hits carry barycentrics `(u, v)` with
//!   `point = (1 - u - v) * a + u * b + v * c`, each in `[0, 1]`, and the
//!   [`Side`] the ray came from; the tests are two-sided.
//! - Camera: right-handed world, raster `(0, 0)` at the image's top-left,
//!   `x` right, `y` down, pixel `(i, j)` centred at `(i + 0.5, j + 0.5)`,
//!   `right = normalize(view x up)`; see [`PinholeCamera`].
//! - Bad input (NaN, infinities, zero vectors, degenerate shapes, inverted
//!   boxes, NaN or negative `t_max`) gives `None` or a [`CameraError`];
//!   nothing panics and no `t` is NaN.
//!
//! # Precision
//!
//! Every type and function is generic over the vector type: [`glam::Vec3`]
//! (`f32`, the default type parameter, so `Ray` means `Ray<Vec3>`) or
//! [`glam::DVec3`] (`f64`). The kernels are written once, against the sealed
//! [`Vector`] and [`Scalar`] traits, and each error bound is derived in
//! terms of the unit roundoff `u` of the precision in use (`2^-24` for `f32`,
//! `2^-53` for `f64`), with `gamma(n) = n*u / (1 - n*u)` ([`Scalar::gamma_n`])
//! bounding `n` chained roundings.
//!
//! # Numerical guarantees
//!
//! "Exact" below means the answer real arithmetic gives on the same
//! floating-point inputs. Preconditions: no intermediate overflows (the
//! kernels' docs give the ranges) and round-to-nearest, which is Rust's.
//!
//! | kernel | guarantee |
//! | --- | --- |
//! | [`ray_aabb`], [`ray_aabb_prepared`] | no false miss, ever (axis-parallel rays, rays in a face plane, zero-thickness boxes, `-0.0` and tiny direction components included); false hits only within a few ulps (a factor `1 + 16u`) of the boundary |
//! | [`ray_aabb_naive`] | reference: faces as planes; agrees with the slab test away from edges |
//! | [`ray_triangle`] | watertight: no ray passes between two triangles sharing an edge; `t > 0` decided conservatively; `t`, `u`, `v` within [`ray_triangle_error_bounds`] |
//! | [`ray_triangle_one_hit`] | as [`ray_triangle`], and exactly one hit per crossing of a consistently wound mesh |
//! | [`ray_triangle_mt`] | fast path; agrees with [`ray_triangle`] away from edges; **not** watertight |
//! | [`ray_plane`] | `t` within [`ray_plane_t_error`] (a few ulps without cancellation) |
//! | [`PinholeCamera`] | unit directions to a few ulps; the centre pixel of an odd-sized image looks along the view direction |
//!
//! # Features
//!
//! - `std` (default): float math from the standard library.
//! - `libm`: float math from the `libm` crate, for `no_std` targets
//!   (`default-features = false, features = ["libm"]`). One of the two must
//!   be on.
//! - `proptest`: the public `strategies` module, the generators the
//!   crate's property tests use (aimed rays, boxes, triangles, planes), for
//!   testing your own kernels against this crate's.
//! - `arbitrary`: `arbitrary::Arbitrary` for [`Ray`], [`Aabb`], [`Plane`] and
//!   [`Triangle`] in both precisions, every coordinate a raw bit pattern (NaN,
//!   infinities, subnormals and `-0.0` included), for fuzzers.

#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "rayhit needs float math from somewhere: enable the `std` feature (the default) \
     or, for no_std targets, the `libm` feature"
);

pub use glam;

mod aabb;
#[cfg(feature = "arbitrary")]
mod arbitrary;
mod camera;
mod plane;
mod ray;
mod real;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;
mod triangle;

pub use aabb::{Aabb, PreparedRay, ray_aabb, ray_aabb_naive, ray_aabb_prepared};
pub use camera::{CameraError, PinholeCamera};
pub use plane::{Plane, ray_plane, ray_plane_hit_point, ray_plane_t_error};
pub use ray::{Ray, offset_ray_origin};
pub use real::{Scalar, Vector};
pub use triangle::{
    Side, Triangle, TriangleHit, TriangleHitError, ray_triangle, ray_triangle_error_bounds,
    ray_triangle_mt, ray_triangle_one_hit, triangle_hit_point,
};
