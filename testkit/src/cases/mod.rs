//! The case generators: rays and shapes aimed at what breaks textbook code,
//! for the oracle suite, the corpus, the fuzz targets' structured inputs and
//! the property tests.
//!
//! They are built on the crate's public strategies
//! ([`rayhit::strategies`]: aimed rays, boxes, triangles, planes,
//! spheres and discs in realistic ranges), drawn from a [`Source`], and add the families those
//! leave out: rays exactly through edges and corners on dyadic grids, on
//! slab planes and in face planes, grazing rays, tiny and signed-zero
//! direction components, thin triangles and zero-area fillers, far-away
//! and tiny or huge scenes, far spheres of every size, discs and annuli
//! at their circles, quads' diagonals and folds, bilinear patches' folds,
//! silhouettes and collapsed edges. Values are computed in `f64` and
//! rounded once to the precision of `V`.

pub mod boxes;
pub mod cameras;
pub mod discs;
pub mod instances;
pub mod patches;
pub mod planes;
pub mod quads;
pub mod spheres;
pub mod triangles;

use rayhit::strategies;
use rayhit::{Ray, Scalar, Vector};

use crate::source::Source;

/// The scalar of a vector type.
pub type S<V> = <V as Vector>::Scalar;

/// A named case family with its seed.
pub type Generator<C> = (&'static str, u64, fn(&mut Source) -> C);

/// A point of precision `V` from `f64` coordinates (rounded once each).
pub fn v<V: Vector>(p: [f64; 3]) -> V {
    V::new(
        S::<V>::from_f64(p[0]),
        S::<V>::from_f64(p[1]),
        S::<V>::from_f64(p[2]),
    )
}

/// The components of a vector as `f64` (exact).
pub fn c<V: Vector>(p: V) -> [f64; 3] {
    [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()]
}

/// A ray of precision `V` aimed at `target` from `s` direction lengths
/// back: the direction rounded first, the origin `target - s dir` computed
/// in `f64` from it and rounded.
pub fn aimed<V: Vector>(target: [f64; 3], dir: [f64; 3], s: f64) -> Ray<V> {
    let d: V = v(dir);
    let dc = c(d);
    Ray::new(v([0, 1, 2].map(|k| target[k] - dc[k] * s)), d)
}

/// A direction from the crate's strategy ([`strategies::direction`]:
/// random, axis-parallel or with a signed-zero component, length `2^-6` to
/// `2^6`).
pub fn direction<V: Vector>(src: &mut Source) -> V {
    src.draw(&strategies::direction::<V>())
        .unwrap_or_else(|| v([0.6, -0.8, 0.0]))
}

/// A point from the crate's strategy: each coordinate uniform in
/// `[-scale, scale]`.
pub fn point<V: Vector>(src: &mut Source, scale: f64) -> V {
    src.draw(&strategies::point::<V>(scale)).unwrap_or(V::ZERO)
}

/// A `t_max` from the crate's strategy: `+inf` half the time, else in
/// `[0, 128]`.
pub fn t_max<V: Vector>(src: &mut Source) -> S<V> {
    src.draw(&strategies::t_max::<V>())
        .unwrap_or(S::<V>::INFINITY)
}

/// A unit vector of `f64` components times `scale`.
pub fn scaled(d: [f64; 3], scale: f64) -> [f64; 3] {
    d.map(|x| x * scale)
}

/// A far-away offset: a random direction times `10^3` to `10^7`.
pub fn far_offset(src: &mut Source) -> [f64; 3] {
    let dist = 10f64.powf(src.range(3.0, 7.0));
    scaled(src.direction(), dist)
}

/// `p + offset`, in `f64`.
pub fn add(p: [f64; 3], offset: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| p[k] + offset[k])
}
