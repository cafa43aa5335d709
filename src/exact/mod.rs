//! Exact answers: the crate's exact-arithmetic oracle, for holding any
//! ray/box, ray/triangle, ray/plane, ray/sphere, ray/disc, ray/quad or
//! ray/patch kernel to the truth.
//!
//! Every finite `f32` and `f64` is a dyadic rational, so each question a
//! kernel answers (does the ray hit, at which `t`, where on the triangle)
//! has one exact answer for the very floats the kernel saw. This module
//! computes it with big rationals ([`Rational`]) and judges a claimed answer
//! against it ([`judge`]), with the conventions of the crate's kernels:
//!
//! - box ([`ray_aabb`]): the closed box against `t` in `[0, t_max]`; over
//!   an interval ([`Aabb`'s `clip` over an interval](crate::Aabb#method.clip)), against `t_min < t <= t_max`;
//! - triangle ([`ray_triangle`], [`ray_mesh`]): closed and two-sided,
//!   `0 < t <= t_max`; over an interval ([`Triangle`'s `hit` over an interval](crate::Triangle#method.hit)),
//!   `t_min < t <= t_max`;
//! - plane ([`ray_plane`]): `0 < t <= t_max`, no hit when parallel; over
//!   an interval ([`Plane`'s `hit` over an interval](crate::Plane#method.hit)), `t_min < t <= t_max`;
//! - sphere ([`ray_sphere`]): the first crossing (entry, else exit) in
//!   `0 < t <= t_max`, its irrational `t` rounded to nearest by exact
//!   comparisons;
//! - disc ([`ray_disc`]): both circles closed, `0 < t <= t_max`, no hit
//!   when parallel;
//! - quad ([`ray_quad`]): its two closed triangles, the nearer crossing;
//! - bilinear patch ([`ray_patch`]): the nearest crossing in `0 < t <=
//!   t_max`, its irrational `t`, `u`, `v` rounded to nearest by exact
//!   comparisons;
//! - invalid input (a non-finite coordinate, a zero direction, an inverted
//!   box, a zero plane normal, a NaN `t_max`) is a miss, never a panic.
//!
//! The instance questions ([`Instance`](crate::Instance)) are answered for
//! the exact map `F(x) = M x + T` of the instance's floats ([`AffineMap`],
//! nested instances composed exactly): the exact image of a point
//! ([`instance_point`]) and of a box ([`instance_box`]), and how far a
//! world ray and its object ray are apart at the same `t`
//! ([`instance_ray_gap`]). [`judge_world_box`] decides whether a claimed
//! world box contains the exact image, [`judge_world_point`] and
//! [`judge_ray_map`] whether a claimed point or ray is within its claimed
//! error bound. Non-finite input gives `None`, never a panic.
//!
//! Each exact value comes with its correctly rounded float ([`Exact`],
//! rounding to nearest, ties to even). The pieces these answers are built
//! from (exact values of floats, exact vector arithmetic, the slab, triangle
//! and plane computations, the rounding bands [`judge`] uses) are public in
//! [`oracle`], for exact checks of your own.
//!
//! ```
//! use rayhit::{Aabb, Ray, glam::Vec3};
//! use rayhit::exact;
//! let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(3.0, 0.0, 0.0));
//! let hit = exact::ray_aabb(&ray, &Aabb::new(Vec3::ZERO, Vec3::ONE), f32::INFINITY).unwrap();
//! // Enters at x = 0 (t = 1/3, not a float) and leaves at x = 1 (t = 2/3).
//! assert_eq!(hit.enter.value, exact::Rational::new(1.into(), 3.into()));
//! assert_eq!(hit.enter.rounded, 1.0f32 / 3.0);
//! ```
//!
//! # Holding your kernel to it
//!
//! A property test (the repository's `corpus/tests/snippets.rs` runs this very
//! code; needs the `proptest` feature too):
//!
//! ```rust,ignore
//! use proptest::prelude::*;
//! use rayhit::exact::{self, Band, Case, Claim, Verdict};
//! use rayhit::glam::Vec3;
//! use rayhit::strategies;
//!
//! /// The kernel under test (yours here): textbook Moller-Trumbore, two-sided.
//! fn my_ray_triangle(o: Vec3, d: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, f32)> {
//!     let (e1, e2) = (b - a, c - a);
//!     let p = d.cross(e2);
//!     let det = e1.dot(p);
//!     if det == 0.0 {
//!         return None;
//!     }
//!     let (s, inv) = (o - a, 1.0 / det);
//!     let q = s.cross(e1);
//!     let (u, v, t) = (s.dot(p) * inv, d.dot(q) * inv, e2.dot(q) * inv);
//!     (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
//! }
//!
//! proptest! {
//!     #[test]
//!     fn my_kernel_agrees_with_exact((tri, ray) in strategies::triangle_and_ray::<Vec3>()) {
//!         let claim = match my_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c) {
//!             Some((t, u, v)) => Claim::Triangle { t, u, v },
//!             None => Claim::Miss,
//!         };
//!         let j = exact::judge(&Case::Triangle(ray, tri, f32::INFINITY), &claim, f64::INFINITY);
//!         // Outside the rounding band, hit or miss must be exactly right.
//!         prop_assert!(j.band == Band::Edge || j.verdict == Verdict::Right, "{:?}", j);
//!     }
//! }
//! ```
//!
//! A `cargo fuzz` target body (the repository's fuzz target `exact_judge`):
//!
//! ```rust,ignore
//! #![no_main]
//! use libfuzzer_sys::fuzz_target;
//! use rayhit::exact::{self, Band, Case, Claim, Verdict};
//! use rayhit::glam::Vec3;
//! use rayhit::{Ray, Triangle};
//!
//! /// The kernel under test (yours here): textbook Moller-Trumbore, two-sided.
//! fn my_ray_triangle(o: Vec3, d: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, f32)> {
//!     let (e1, e2) = (b - a, c - a);
//!     let p = d.cross(e2);
//!     let det = e1.dot(p);
//!     if det == 0.0 {
//!         return None;
//!     }
//!     let (s, inv) = (o - a, 1.0 / det);
//!     let q = s.cross(e1);
//!     let (u, v, t) = (s.dot(p) * inv, d.dot(q) * inv, e2.dot(q) * inv);
//!     (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
//! }
//!
//! // Coordinates on a grid of 1/64 within +-512: the scene scale the kernel is
//! // meant for (raw float bits would also feed it overflows and underflows).
//! fuzz_target!(|grid: [i16; 15]| {
//!     let p = |i: usize| Vec3::new(grid[i] as f32, grid[i + 1] as f32, grid[i + 2] as f32) / 64.0;
//!     let (ray, tri) = (Ray::new(p(0), p(3)), Triangle::new(p(6), p(9), p(12)));
//!     let claim = match my_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c) {
//!         Some((t, u, v)) => Claim::Triangle { t, u, v },
//!         None => Claim::Miss,
//!     };
//!     let j = exact::judge(
//!         &Case::Triangle(ray, tri, f32::INFINITY),
//!         &claim,
//!         f64::INFINITY,
//!     );
//!     // Outside the rounding band, hit or miss must be exactly right.
//!     assert!(
//!         j.band == Band::Edge || j.verdict == Verdict::Right,
//!         "{ray:?} {tri:?}: {j:?}"
//!     );
//! });
//! ```
//!
//! # Speed
//!
//! Exact arithmetic is slow. Cases per second on one thread (an x86-64
//! core shared with other work, cases from the repository's test kit
//! generators; `cargo run --release -p rayhit-testkit --features fuzz --example
//! exact_speed` measures it):
//!
//! | kernel   | f32: decide | f32: [`judge`] | f64: decide | f64: [`judge`] |
//! |----------|------------:|---------------:|------------:|---------------:|
//! | box      |      45 000 |         18 000 |      31 000 |         10 000 |
//! | triangle |      13 000 |          2 100 |       6 400 |          1 000 |
//! | plane    |      61 000 |         16 000 |      30 000 |          8 000 |
//!
//! Judging costs more than deciding because it also places the case in or
//! out of the rounding band ([`band`]) and measures its distance from the
//! boundary ([`distance_ulps`]). A fuzzer or property test running a few
//! thousand cases per second per core is typical.
//!
//! The dependencies are re-exported, so a dependent needs no version of its
//! own: [`num_bigint`], [`num_rational`], [`num_traits`].

use std::vec::Vec;

use num_traits::{Signed, Zero};

use crate::{Aabb, BoxFace, Plane, Ray, Scalar, Side, Triangle, Vector};

pub use num_bigint;
pub use num_rational;
pub use num_traits;

mod corpus;
mod instance;
mod measure;
pub mod oracle;
mod surfaces;
mod verdict;

pub use corpus::{
    CorpusCase, CorpusEntry, CorpusFields, CorpusLine, InstanceCorpusCase, InstanceCorpusEntry,
    InstanceQuestion, corpus, corpus_lines, instance_corpus, parse_bits, parse_case,
};

pub use instance::{
    AffineMap, ImageBox, PointJudgement, WorldBoxJudgement, instance_box, instance_point,
    instance_ray_gap, judge_ray_map, judge_world_box, judge_world_point, round_down, round_up,
};

pub use surfaces::*;

pub use verdict::{
    Band, Case, Claim, Field, Judgement, Tally, Verdict, band, distance_ulps, judge,
};

/// An exact rational number.
pub type Rational = num_rational::BigRational;

/// The exact value of a float, or `None` for an infinity or NaN.
#[must_use]
pub fn rational<F: Scalar>(x: F) -> Option<Rational> {
    oracle::r(x)
}

/// `x` rounded to the nearest float of precision `F`, ties to even; values
/// beyond the largest finite float round to an infinity as IEEE 754 says
/// (at or above `MAX + half an ulp`).
#[must_use]
pub fn round<F: Scalar>(x: &Rational) -> F {
    let single = F::UNIT_ROUNDOFF.to_f64() == f64::EPSILON * 0.5 * (1u64 << 29) as f64;
    // Significand bits, and the exponent of the smallest normal.
    let (p, emin, emax): (i64, i64, i64) = if single {
        (24, -126, 127)
    } else {
        (53, -1022, 1023)
    };
    F::from_f64(round_bits(x, p, emin, emax))
}

fn round_bits(x: &Rational, p: i64, emin: i64, emax: i64) -> f64 {
    use num_bigint::BigInt;
    if x.is_zero() {
        return 0.0;
    }
    let negative = x.is_negative();
    let n = x.numer().abs();
    let d = x.denom().abs();
    // 2^e <= |x| < 2^(e + 1).
    let mut e = n.bits() as i64 - d.bits() as i64;
    let shl = |v: &BigInt, k: i64| -> BigInt { if k >= 0 { v << (k as usize) } else { v.clone() } };
    if shl(&n, -e) < shl(&d, e) {
        e -= 1;
    }
    // The spacing of floats at |x| (subnormals share the smallest normal's).
    let q = e.max(emin) - (p - 1);
    let (num, den) = (shl(&n, -q), shl(&d, q));
    let mut m = &num / &den;
    let twice: BigInt = (&num - &m * &den) << 1usize;
    if twice > den || (twice == den && m.bit(0)) {
        m += 1;
    }
    // m <= 2^p, so it converts exactly; m 2^q overflows exactly when the
    // rounded value exceeds the largest finite float.
    let m = num_traits::ToPrimitive::to_f64(&m).unwrap_or(f64::INFINITY);
    let mag = if m == 0.0 {
        0.0
    } else if (m.log2().floor() as i64) + q > emax {
        f64::INFINITY
    } else {
        // Exact: multiply in two power-of-two steps, each representable.
        let half = q / 2;
        m * pow2(half) * pow2(q - half)
    };
    if negative { -mag } else { mag }
}

/// `2^k` as an `f64` for `-1074 <= k <= 1023` (0 below, infinity above).
fn pow2(k: i64) -> f64 {
    if k > 1023 {
        f64::INFINITY
    } else if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else if k >= -1074 {
        f64::from_bits(1u64 << (k + 1074))
    } else {
        0.0
    }
}

/// An exact value and its correctly rounded float.
#[derive(Clone, Debug, PartialEq)]
pub struct Exact<F> {
    /// The exact value.
    pub value: Rational,
    /// `value` rounded to the nearest float, ties to even.
    pub rounded: F,
}

impl<F: Scalar> Exact<F> {
    /// `value` with its rounding.
    #[must_use]
    pub fn new(value: Rational) -> Self {
        let rounded = round(&value);
        Self { value, rounded }
    }
}

fn valid_limit<F: Scalar>(t_max: F) -> bool {
    t_max.partial_cmp(&t_max).is_some()
}

/// The exact answer for a ray against a box that it hits.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxAnswer<F> {
    /// Where the ray enters the closed box, at least 0.
    pub enter: Exact<F>,
    /// Where it leaves the box or reaches `t_max`, whichever is first.
    pub exit: Exact<F>,
    /// The faces whose planes the ray crosses at `enter` on the way in: one,
    /// or two or three at an edge or corner; none when it starts strictly
    /// inside (a ray starting on a face, going in, lists that face). In
    /// axis order, x before y before z.
    pub entry_faces: Vec<BoxFace>,
    /// The faces whose planes it crosses at `exit` on the way out (none when
    /// `t_max` comes first).
    pub exit_faces: Vec<BoxFace>,
}

/// Exact ray/box: the interval of `t` in `[0, t_max]` with the ray in the
/// closed box, and the faces at its ends; `None` for a miss or invalid input
/// (see [`Ray::is_valid`], [`Aabb::is_valid`]; a NaN `t_max`). The same
/// question as [`ray_aabb`](crate::ray_aabb) answers with rounding.
///
/// ```
/// use rayhit::{Aabb, BoxFace, Ray, exact, glam::DVec3};
/// let b = Aabb::new(DVec3::ZERO, DVec3::ONE);
/// // Through the edge x = 0, y = 0.
/// let ray = Ray::new(DVec3::new(-1.0, -1.0, 0.5), DVec3::new(1.0, 1.0, 0.0));
/// let hit = exact::ray_aabb(&ray, &b, f64::INFINITY).unwrap();
/// assert_eq!(hit.entry_faces, [BoxFace::MinX, BoxFace::MinY]);
/// assert_eq!(hit.exit_faces, [BoxFace::MaxX, BoxFace::MaxY]);
/// assert!(exact::ray_aabb(&ray, &b, 0.5).is_none());
/// ```
#[must_use]
pub fn ray_aabb<V: Vector>(
    ray: &Ray<V>,
    b: &Aabb<V>,
    t_max: V::Scalar,
) -> Option<BoxAnswer<V::Scalar>> {
    if !(ray.is_valid() && b.is_valid() && valid_limit(t_max)) {
        return None;
    }
    let slabs = oracle::box_slabs(ray, b)?;
    let (enter, exit) = oracle::box_interval(ray, b, t_max)?;
    let entry = enter.clone();
    box_answer(&slabs, ray, enter, exit, Some(&entry))
}

/// Exact ray/box over an interval: the part of `(t_min, t_max]` the ray
/// spends inside the closed box, as its closure `[enter, exit]` with
/// `enter = max(E, t_min)` and `exit = min(X, t_max)` (`E`, `X` the exact
/// entry and exit); `None` when that part is empty (the box is left at or
/// before `t_min`, entered after `t_max`, or missed), for invalid input,
/// and for an interval that is not `0 <= t_min <= t_max` (NaN included).
/// The question [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip) answers
/// conservatively: where this is `Some`, it must be `Some`.
///
/// `entry_faces` lists the faces crossed at `E` only when the entry is
/// within the interval (`t_min < E`), and is empty otherwise (the ray is
/// inside at `t_min`); where it is not empty, its first face is the one
/// [`Aabb`'s `hit` over an interval](crate::Aabb#method.hit) reports. `exit_faces` as
/// for [`ray_aabb`]. With `t_min = 0` this differs from [`ray_aabb`] in
/// two ways, both from the open lower end: a box the ray leaves exactly at
/// `t = 0` is not hit, and a ray entering exactly at `t = 0` lists no
/// entry face.
///
/// ```
/// use rayhit::{Aabb, BoxFace, Ray, exact, glam::Vec3};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// // Enters through x = 0 at t = 1, leaves through x = 1 at t = 2.
/// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X);
/// let hit = exact::ray_aabb_in(&ray, &unit, 0.5, 4.0).unwrap();
/// assert_eq!((hit.enter.rounded, hit.exit.rounded), (1.0, 2.0));
/// assert_eq!(hit.entry_faces, [BoxFace::MinX]);
/// // From t = 1 on, the ray is inside: no entry face.
/// let later = exact::ray_aabb_in(&ray, &unit, 1.0, 4.0).unwrap();
/// assert_eq!((later.enter.rounded, later.entry_faces.len()), (1.0, 0));
/// assert!(exact::ray_aabb_in(&ray, &unit, 2.0, 4.0).is_none()); // left at t_min
/// ```
#[must_use]
pub fn ray_aabb_in<V: Vector>(
    ray: &Ray<V>,
    b: &Aabb<V>,
    t_min: V::Scalar,
    t_max: V::Scalar,
) -> Option<BoxAnswer<V::Scalar>> {
    let zero = <V::Scalar as Scalar>::ZERO;
    if !(zero <= t_min && t_min <= t_max && ray.is_valid() && b.is_valid()) {
        return None;
    }
    let slabs = oracle::box_slabs(ray, b)?;
    let lo = oracle::r(t_min)?;
    // A valid ray moves along some axis, so both exist.
    let e = slabs.iter().map(|s| s.0.clone()).max()?;
    let x = slabs.iter().map(|s| s.1.clone()).min()?;
    let enter = if e > lo { e.clone() } else { lo.clone() };
    let exit = match oracle::limit(t_max) {
        Some(m) if m < x => m,
        _ => x,
    };
    if !(enter <= exit && exit > lo) {
        return None;
    }
    let entry = (e > lo).then_some(&e);
    box_answer(&slabs, ray, enter, exit, entry)
}

/// The answer for the part `[enter, exit]` of a ray in a box, with its
/// faces: the entry faces are the slabs whose near plane is crossed at
/// `entry` (none for `None`), the exit faces those whose far plane is
/// crossed at `exit`.
fn box_answer<V: Vector>(
    slabs: &[(Rational, Rational, usize)],
    ray: &Ray<V>,
    enter: Rational,
    exit: Rational,
    entry: Option<&Rational>,
) -> Option<BoxAnswer<V::Scalar>> {
    let d = oracle::rv(ray.dir)?;
    let face = |k: usize, near: bool| {
        let max_side = (d[k] < Rational::zero()) == near;
        BoxFace::new(k, max_side).expect("axis below 3")
    };
    let entry_faces = slabs
        .iter()
        .filter(|s| entry == Some(&s.0))
        .map(|s| face(s.2, true))
        .collect();
    let exit_faces = slabs
        .iter()
        .filter(|s| s.1 == exit)
        .map(|s| face(s.2, false))
        .collect();
    Some(BoxAnswer {
        enter: Exact::new(enter),
        exit: Exact::new(exit),
        entry_faces,
        exit_faces,
    })
}

/// Where on a triangle a crossing is: inside, on one edge, or at a corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Place {
    /// Strictly inside.
    Interior,
    /// On an edge, not at its ends: 0 for `a-b`, 1 for `b-c`, 2 for `c-a`.
    Edge(usize),
    /// At a corner: 0, 1, 2 for `a`, `b`, `c`.
    Corner(usize),
}

/// The exact answer for a ray against a triangle that it crosses.
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleAnswer<F> {
    /// Distance along the ray, in units of `dir`.
    pub t: Exact<F>,
    /// Barycentric weight of `b`.
    pub u: Exact<F>,
    /// Barycentric weight of `c`.
    pub v: Exact<F>,
    /// The side the ray arrives from (the exact sign of `dir . normal`).
    pub side: Side,
    /// Inside, on an edge, or at a corner, exactly.
    pub place: Place,
}

/// Exact ray/triangle: closed and two-sided, `0 < t <= t_max`; `None` for a
/// miss, a line parallel to the triangle's plane (including a degenerate
/// triangle) or invalid input. The same question as
/// [`ray_triangle`](crate::ray_triangle) answers with rounding.
///
/// ```
/// use rayhit::{Ray, Side, Triangle, exact, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// // Straight down onto the middle of the edge b-c.
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 2.0), Vec3::new(0.0, 0.0, -1.0));
/// let hit = exact::ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// assert_eq!((hit.t.rounded, hit.u.rounded, hit.v.rounded), (2.0, 0.5, 0.5));
/// assert_eq!(hit.place, exact::Place::Edge(1));
/// assert_eq!(hit.side, Side::Front);
/// ```
#[must_use]
pub fn ray_triangle<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: V::Scalar,
) -> Option<TriangleAnswer<V::Scalar>> {
    if !triangle_input_valid(ray, tri, t_max) {
        return None;
    }
    ray_triangle_from_exact(ray, tri, &oracle::triangle(ray, tri)?, t_max)
}

/// [`ray_triangle`]'s answer from the exact crossing already computed:
/// `exact` must be [`oracle::triangle`]`(ray, tri)`, and then the answer is
/// [`ray_triangle`]'s, with no exact arithmetic beyond rounding `t`, `u`
/// and `v` to floats. For a caller that needs the exact crossing for more
/// than the answer (a rounding band, a window check), so it is computed
/// once.
///
/// ```
/// use rayhit::{Ray, Triangle, exact, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.25, 0.25, 2.0), Vec3::new(0.0, 0.0, -1.0));
/// let crossing = exact::oracle::triangle(&ray, &tri).unwrap();
/// let answer = exact::ray_triangle_from_exact(&ray, &tri, &crossing, f32::INFINITY);
/// assert_eq!(answer, exact::ray_triangle(&ray, &tri, f32::INFINITY));
/// assert_eq!(answer.unwrap().t.rounded, 2.0);
/// ```
#[must_use]
pub fn ray_triangle_from_exact<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &oracle::ExactTriangle,
    t_max: V::Scalar,
) -> Option<TriangleAnswer<V::Scalar>> {
    if !(triangle_input_valid(ray, tri, t_max) && exact.hits(&oracle::limit(t_max))) {
        return None;
    }
    let (t, (u, v)) = (exact.t.clone()?, exact.uv.clone()?);
    let zero = |k: usize| exact.signs[k] == core::cmp::Ordering::Equal;
    // Edge k runs from corner k to corner k + 1.
    let place = match (zero(0), zero(1), zero(2)) {
        (false, false, false) => Place::Interior,
        (true, false, false) => Place::Edge(0),
        (false, true, false) => Place::Edge(1),
        (false, false, true) => Place::Edge(2),
        (true, true, _) => Place::Corner(1),
        (false, true, true) => Place::Corner(2),
        (true, false, true) => Place::Corner(0),
    };
    // The side is the sign of `dir . n`, `n = (b - a) x (c - a)`: with the
    // corners taken from the origin, `n = a x b + b x c + c x a`, so `dir .
    // n` is the sum of the three edge products. On a hit their nonzero
    // signs agree and the sum is not zero (the line is not parallel), so it
    // has their sign.
    let side = if exact.signs.contains(&core::cmp::Ordering::Less) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleAnswer {
        t: Exact::new(t),
        u: Exact::new(u),
        v: Exact::new(v),
        side,
        place,
    })
}

/// The inputs [`ray_triangle`] answers for: a valid ray, finite corners,
/// a `t_max` that is not NaN.
fn triangle_input_valid<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: V::Scalar) -> bool {
    ray.is_valid()
        && tri.a.is_finite()
        && tri.b.is_finite()
        && tri.c.is_finite()
        && valid_limit(t_max)
}

/// Exact ray/triangle over an interval: closed and two-sided, a crossing
/// at `t_min < t <= t_max` (both ends floats, compared with the exact
/// crossing); `None` for a miss, a line parallel to the triangle's plane
/// (including a degenerate triangle), invalid input, or an interval that
/// is not `0 <= t_min <= t_max` (NaN included). The same question as
/// [`Triangle`'s `hit` over an interval](crate::Triangle#method.hit) answers; with `t_min = 0`
/// it is [`ray_triangle`]'s.
///
/// ```
/// use rayhit::{Ray, Triangle, exact, glam::Vec3};
/// let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(3.0, -1.0, 0.0), Vec3::new(-1.0, 3.0, 0.0));
/// // Crosses the plane z = 0 at exactly t = 2.
/// let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// assert!(exact::ray_triangle_in(&ray, &tri, 1.0, 2.0).is_some());
/// assert!(exact::ray_triangle_in(&ray, &tri, 2.0, 3.0).is_none());
/// assert!(exact::ray_triangle_in(&ray, &tri, 3.0, 1.0).is_none());
/// ```
#[must_use]
pub fn ray_triangle_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_min: V::Scalar,
    t_max: V::Scalar,
) -> Option<TriangleAnswer<V::Scalar>> {
    let zero = <V::Scalar as Scalar>::ZERO;
    if !(zero <= t_min && t_min <= t_max) {
        return None;
    }
    let answer = ray_triangle(ray, tri, t_max)?;
    (answer.t.value > oracle::r(t_min)?).then_some(answer)
}

/// One crossing of a ray through a mesh: the exact `t` and every triangle
/// the ray crosses there (several when it passes through a shared edge or
/// corner), with each triangle's answer.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshCrossing<F> {
    /// Where along the ray.
    pub t: Exact<F>,
    /// The triangles crossed at `t`, by index, in index order.
    pub triangles: Vec<(usize, TriangleAnswer<F>)>,
}

/// Exact ray/mesh: every crossing of the ray with the triangles (each
/// closed and two-sided, `0 < t <= t_max`), nearest first, the triangles
/// that share a crossing (equal exact `t`) grouped together. A watertight
/// kernel must report at least one triangle of each crossing whose triangles
/// close up around it.
///
/// ```
/// use rayhit::{Ray, Triangle, exact, glam::Vec3};
/// // Two triangles sharing the diagonal of the unit square.
/// let quad = [
///     Triangle::new(Vec3::ZERO, Vec3::X, Vec3::ONE.with_z(0.0)),
///     Triangle::new(Vec3::ZERO, Vec3::ONE.with_z(0.0), Vec3::Y),
/// ];
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z);
/// let crossings = exact::ray_mesh(&ray, &quad, f32::INFINITY);
/// assert_eq!(crossings.len(), 1);
/// assert_eq!(crossings[0].triangles.len(), 2);
/// ```
#[must_use]
pub fn ray_mesh<V: Vector>(
    ray: &Ray<V>,
    tris: &[Triangle<V>],
    t_max: V::Scalar,
) -> Vec<MeshCrossing<V::Scalar>> {
    let mut hits: Vec<(usize, TriangleAnswer<V::Scalar>)> = tris
        .iter()
        .enumerate()
        .filter_map(|(i, tri)| ray_triangle(ray, tri, t_max).map(|h| (i, h)))
        .collect();
    hits.sort_by(|x, y| x.1.t.value.cmp(&y.1.t.value).then(x.0.cmp(&y.0)));
    let mut out: Vec<MeshCrossing<V::Scalar>> = Vec::new();
    for (i, h) in hits {
        match out.last_mut() {
            Some(last) if last.t.value == h.t.value => last.triangles.push((i, h)),
            _ => out.push(MeshCrossing {
                t: h.t.clone(),
                triangles: std::vec![(i, h)],
            }),
        }
    }
    out
}

/// Exact ray/plane: the crossing `t` with `0 < t <= t_max`; `None` when the
/// ray is parallel to the plane, crosses it outside that range, or the
/// input is invalid (a zero or non-finite normal, a non-finite point). The
/// same question as [`ray_plane`](crate::ray_plane) answers with rounding.
///
/// ```
/// use rayhit::{Plane, Ray, exact, glam::Vec3};
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, -3.0, 0.0));
/// let t = exact::ray_plane(&ray, &floor, f32::INFINITY).unwrap();
/// assert_eq!(t.value, exact::Rational::new(1.into(), 3.into()));
/// ```
#[must_use]
pub fn ray_plane<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_max: V::Scalar,
) -> Option<Exact<V::Scalar>> {
    if !(ray.is_valid()
        && plane.point.is_finite()
        && plane.normal.is_finite()
        && valid_limit(t_max))
    {
        return None;
    }
    oracle::plane_hit(ray, plane, t_max).map(Exact::new)
}

/// Exact ray/plane over an interval: the crossing `t` with `t_min < t <=
/// t_max` (both ends floats, compared with the exact crossing); `None`
/// when the ray is parallel to the plane, crosses it outside the interval,
/// the input is invalid (as for [`ray_plane`]), or the interval is not
/// `0 <= t_min <= t_max` (NaN included). The question
/// [`Plane`'s `hit` over an interval](crate::Plane#method.hit) answers exactly (for crossings up
/// to `MAX`, the largest float `t` it can report); with `t_min = 0` it is
/// [`ray_plane`]'s.
///
/// ```
/// use rayhit::{Plane, Ray, exact, glam::Vec3};
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// // Crosses y = 0 at exactly t = 1/3.
/// let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, -3.0, 0.0));
/// let third = 1.0f32 / 3.0; // rounded up: 1/3 lies just below it
/// assert!(exact::ray_plane_in(&ray, &floor, 0.0, third).is_some());
/// assert!(exact::ray_plane_in(&ray, &floor, third, 1.0).is_none());
/// assert!(exact::ray_plane_in(&ray, &floor, third.next_down(), 1.0).is_some());
/// ```
#[must_use]
pub fn ray_plane_in<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_min: V::Scalar,
    t_max: V::Scalar,
) -> Option<Exact<V::Scalar>> {
    let zero = <V::Scalar as Scalar>::ZERO;
    if !(zero <= t_min && t_min <= t_max) {
        return None;
    }
    let answer = ray_plane(ray, plane, t_max)?;
    (answer.value > oracle::r(t_min)?).then_some(answer)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(m: i64, e: i32) -> Rational {
        oracle::dyadic(m, e)
    }

    #[test]
    fn round_is_to_nearest_ties_to_even() {
        // Ties between 1 and its neighbours: to the even significand.
        assert_eq!(round::<f32>(&(q(1, 0) + q(1, -24))), 1.0);
        assert_eq!(
            round::<f32>(&(q(1, 0) + q(3, -24))),
            1.0 + f32::EPSILON * 2.0
        );
        assert_eq!(round::<f64>(&(q(1, 0) + q(1, -53))), 1.0);
        assert_eq!(
            round::<f64>(&-(q(1, 0) + q(3, -53))),
            -(1.0 + f64::EPSILON * 2.0)
        );
        // Not a tie: just above half an ulp rounds up.
        assert_eq!(
            round::<f32>(&(q(1, 0) + q(1, -24) + q(1, -60))),
            1.0 + f32::EPSILON
        );
        // Subnormals: the tie between 0 and the smallest goes to 0, 3/2 of it to 2.
        assert_eq!(round::<f32>(&q(1, -150)).to_bits(), 0);
        assert_eq!(round::<f32>(&q(3, -150)).to_bits(), 2);
        assert_eq!(round::<f64>(&q(3, -1075)).to_bits(), 2);
        // Overflow (IEEE 754): from MAX + half an ulp (2^103 for f32) up,
        // infinity; a little less, MAX.
        let max32 = oracle::r(f32::MAX).unwrap();
        assert_eq!(round::<f32>(&(&max32 + q(1, 103))), f32::INFINITY);
        assert_eq!(round::<f32>(&(&max32 + q(1, 102))), f32::MAX);
        assert_eq!(round::<f64>(&Rational::new(1.into(), 3.into())), 1.0 / 3.0);
        assert_eq!(
            round::<f32>(&Rational::new((-2).into(), 3.into())),
            -2.0f32 / 3.0
        );
    }
}
