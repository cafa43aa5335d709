//! Instance cases: a transform and an object box or point, for the
//! corpus's instance files.
//!
//! Transforms come from the crate's strategy
//! ([`rayhit::strategies::transform`]: rotations, scales from `1e-3` to
//! `1e3`, shears, translations up to `1e5`) three times in four, and
//! otherwise from the family it leaves out: axis permutations with signs
//! and power-of-two scales, whose products are exact, so the exact image
//! of a box corner is a float and an outward-rounded box can be tight.
//! Boxes: from [`rayhit::strategies::aabb`], or flat on one or more axes
//! (a face, an edge, a point), with `-0.0` corners, or tiny and far from
//! the object origin. Values are computed in `f64` and rounded once to the
//! precision of `V`.

use rayhit::{Aabb, Scalar, Vector, strategies};

use super::{S, v};
use crate::source::Source;

/// A transform: the matrix's columns and the translation.
pub type Transform<V> = ([V; 3], V);

/// A transform (see the module docs).
pub fn transform<V: Vector>(src: &mut Source) -> Option<Transform<V>> {
    if src.below(4) > 0 {
        return src.draw(&strategies::transform::<V>());
    }
    // A signed permutation with power-of-two scales.
    let perm = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ][src.index(6)];
    let cols = [0, 1, 2].map(|j| {
        let mut c = [0.0; 3];
        c[perm[j]] = src.sign() * src.pow2(-10, 10);
        v::<V>(c)
    });
    let t = match src.below(3) {
        0 => V::ZERO,
        1 => v(src.direction().map(|x| x * src.pow2(-4, 16))),
        _ => v([0; 3].map(|_| src.range(-1e5, 1e5))),
    };
    Some((cols, t))
}

/// An object box (see the module docs).
pub fn object_box<V: Vector>(src: &mut Source) -> Option<Aabb<V>> {
    let b = match src.below(4) {
        0 | 1 => src.draw(&strategies::aabb::<V>())?,
        2 => {
            // Tiny, far from the object origin.
            let centre = src.direction().map(|x| x * src.log2_range(0.0, 16.0));
            let half = [0; 3].map(|_| src.log2_range(-20.0, -4.0));
            Aabb::new(
                v([0, 1, 2].map(|k| centre[k] - half[k])),
                v([0, 1, 2].map(|k| centre[k] + half[k])),
            )
        }
        _ => {
            // Symmetric around the origin, corners at -0.0 or at ties.
            let half = [0; 3].map(|_| src.pow2(-3, 3) * f64::from(src.below(4)));
            let lo = V::new(
                neg_zero_or::<V>(-half[0]),
                neg_zero_or::<V>(-half[1]),
                neg_zero_or::<V>(-half[2]),
            );
            Aabb::new(lo, v(half))
        }
    };
    // Flat on an axis one time in four: a face, an edge or a point box.
    if src.one_in(4) {
        let k = src.index(3);
        let mut hi = [b.max.x(), b.max.y(), b.max.z()];
        hi[k] = b.min[k];
        let max = if src.one_in(3) {
            b.min
        } else {
            V::new(hi[0], hi[1], hi[2])
        };
        return Some(Aabb::new(b.min, max));
    }
    Some(b)
}

/// `x` in `V`'s precision, `-0.0` for zero.
fn neg_zero_or<V: Vector>(x: f64) -> S<V> {
    if x == 0.0 {
        S::<V>::from_f64(-0.0)
    } else {
        S::<V>::from_f64(x)
    }
}

/// An object point: a corner or a point of an object box.
pub fn object_point<V: Vector>(src: &mut Source) -> Option<V> {
    let b = object_box::<V>(src)?;
    let pick = |k: usize, s: f64| {
        S::<V>::from_f64(b.min[k].to_f64() + s * (b.max[k].to_f64() - b.min[k].to_f64()))
    };
    Some(if src.one_in(3) {
        V::new(pick(0, 0.0), pick(1, 1.0), pick(2, 0.0))
    } else {
        V::new(
            pick(0, src.unit()),
            pick(1, src.unit()),
            pick(2, src.unit()),
        )
    })
}
