//! The exact building blocks, for writing exact checks of your own: the
//! exact value of a float ([`r`], [`rv`]), vector arithmetic on exact
//! values, the exact slab, triangle and plane computations with the
//! crate's conventions (`t` in units of the ray's direction, closed boxes
//! and triangles, the watertight test's tie rules), and the rounding bands
//! [`judge`](super::judge) uses to call a case [`Clear`](super::Band::Clear)
//! or [`Edge`](super::Band::Edge).
//!
//! Every value here is exact: a big rational computed from the floats' exact
//! values, with no rounding anywhere. The one rule for bad input: a float
//! that has no exact value (NaN, an infinity) gives `None`, as does a ray
//! whose direction is zero where a function needs it to move; predicates
//! (`*_clear`, `*_clear_watertight`, [`close`], `surely_outside*`,
//! `reciprocal_*`) answer `false` for such input (the filter
//! [`surely_outside_watertight_filter`] `Some(false)`), and
//! [`hit_point_disagreement`], which looks for trouble, counts it as a
//! disagreement. Nothing here panics.
//!
//! For whole answers with the kernels' conventions (validity, `t_max`,
//! rounding to a float) use the parent module's checked entry points,
//! [`ray_aabb`](super::ray_aabb), [`ray_triangle`](super::ray_triangle),
//! [`ray_plane`](super::ray_plane) and [`judge`](super::judge).
//!
//! ```
//! use rayhit::exact::oracle;
//! use rayhit::{Plane, Ray, Surface, glam::Vec3, ray_plane};
//!
//! let ray = Ray::new(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.3, 0.7, 1.1));
//! let plane = Plane::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.1, 0.2, 1.0));
//! let t = ray_plane(&ray, &plane, f32::INFINITY).unwrap();
//! // The kernel's t is within its documented bound of the exact crossing.
//! let exact_t = oracle::plane_t(&ray, &plane).unwrap();
//! assert!(oracle::close(t, &exact_t, plane.hit_error(&ray, &t)));
//! // Floats without an exact value give None, never a panic.
//! assert!(oracle::r(f32::NAN).is_none());
//! ```

mod aabb;
mod differentials;
mod disc;
mod filter;
mod patch;
mod plane;
mod sphere;
mod triangle;
mod values;

#[cfg(test)]
mod tests;

pub use aabb::*;
pub use differentials::*;
pub use disc::*;
pub use filter::*;
pub use patch::*;
pub use plane::*;
pub use sphere::*;
pub use triangle::*;
pub use values::*;
