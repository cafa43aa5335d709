//! The one-hit rule's inside test, decided exactly.
//!
//! The ray is moved by an infinitesimal `(eps1, eps2)`, `0 < eps2 <<
//! eps1`, in its exact sheared plane (the plane across the ray, `x` and
//! `y` the permuted axes that [`Shear`] picks), and each triangle answers
//! whether the moved ray crosses it, in exact arithmetic. Edge `i` (from
//! corner `P = c[i+1]` to `Q = c[i+2]`) has the exact edge function
//!
//! ```text
//! E_i = d . ((P - o) x (Q - o)) / d_z
//! ```
//!
//! (the frame's `x_P y_Q - y_P x_Q` before rounding: with `X = d_z x` and
//! `Y = d_z y`, `X_P Y_Q - Y_P X_Q = d_z d . ((P - o) x (Q - o))`, and the
//! cyclic permutation keeps the triple product). Where `E_i = 0` the moved
//! ray decides: `E_i(eps) = E_i + D_x eps2 - D_y eps1` with `D = Q - P`
//! in the sheared plane, so its sign is that of `-D_y`, or of `D_x` where
//! `D_y = 0` (Edelsbrunner and Mucke's simulation of simplicity, 1990),
//! and `d_z D_y = d_z (Q - P)_y - d_y (Q - P)_z`, `d_z D_x` likewise.
//!
//! What this gives: every triangle answers for the same moved ray in
//! exact arithmetic, so around a point where the ray crosses a mesh, the
//! moved ray crosses the exact surface the triangles form, once per sheet.
//! A triangle of exactly zero area is never crossed (its three perturbed
//! edge functions sum to its area, zero, so they cannot share a strict
//! sign), and two edges on one line (a T-junction's long edge and the two
//! short ones that split it, the split vertex exactly on the line) decide
//! alike, their edge functions being positive multiples of each other.
//!
//! The computed edge functions decide wherever their signs are surely
//! exact ([`edge_signs_known_at_corners`], the interval forms' filter);
//! only the rest, within rounding of an edge, pays for the exact signs
//! (three [`PlaneCrossing`] determinants and, on an edge line, a
//! two-by-two determinant).

use super::conditioning::edge_signs_known_at_corners;
use super::frame::Frame;
use super::{Side, Triangle, TriangleHit};
use crate::num::exact_sign::{exponent, scale2, sum_of_products_sign, two_diff};
use crate::num::{S, Scalar, Vector, lanes};
use crate::ray::{Interval, PlaneCrossing, Shear, bring_into, decide};
use core::cmp::Ordering;

/// The edge functions a one-hit hit is computed from, or `None` where the
/// moved ray misses `tri` (or an input is not finite): the frame's, with
/// each one whose computed sign is not the exact sign of the crossing set
/// to zero. Each stays within its rounding error bound of the exact value
/// (a computed value of the wrong sign is within its bound of zero, and
/// the exact value lies beyond zero), and all share the exact sign or
/// are zero, so their sum has the exact determinant's sign or is zero.
#[inline(always)]
pub(crate) fn one_hit_edges<V: Vector>(
    f: &Frame<S<V>>,
    (origin, dir): (V, V),
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
) -> Option<[S<V>; 3]> {
    let zero = S::<V>::ZERO;
    let e = f.e;
    let (xl, yl, pzl) = (
        lanes(V::new(f.x[0], f.x[1], f.x[2])),
        lanes(V::new(f.y[0], f.y[1], f.y[2])),
        lanes(V::new(f.pz[0], f.pz[1], f.pz[2])),
    );
    let known = |v: S<V>| v > zero && edge_signs_known_at_corners(xl, yl, pzl, v);
    let (lo, hi) = (min3(e), max3(e));
    // Surely of both signs: a miss. Surely all of one: a hit, as computed.
    if known(hi) && known(-lo) {
        return None;
    }
    if known(lo) || known(-hi) {
        return Some(e);
    }
    exact_edges(e, (origin, dir), shear, tri)
}

/// [`one_hit_edges`] where some computed sign may not be exact.
#[cold]
#[inline(never)]
fn exact_edges<V: Vector>(
    e: [S<V>; 3],
    (origin, dir): (V, V),
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
) -> Option<[S<V>; 3]> {
    if !(tri.a.is_finite() && tri.b.is_finite() && tri.c.is_finite()) {
        return None;
    }
    let zero = S::<V>::ZERO;
    let corners = [tri.a, tri.b, tri.c];
    let mut positive = [false; 3];
    for (i, s) in positive.iter_mut().enumerate() {
        let (p, q) = (corners[(i + 1) % 3], corners[(i + 2) % 3]);
        *s = exact_edge_positive(origin, dir, shear, p, q)?;
    }
    if !(positive[0] == positive[1] && positive[1] == positive[2]) {
        return None;
    }
    let agrees = |v: S<V>| if positive[0] { v > zero } else { v < zero };
    Some(e.map(|v| if agrees(v) { v } else { zero }))
}

/// Whether the moved ray's edge function for the edge `p -> q` is
/// positive, decided exactly; `None` for an edge parallel to the ray (its
/// edge function is zero wherever the ray is moved) or a non-finite input.
///
/// Exact for every `f32` input; for `f64` while the conditions of
/// [`PlaneCrossing`] hold (nonzero coordinate differences and their
/// rounding errors within `2^250` of the largest, the direction's nonzero
/// components within `2^250` of its largest).
fn exact_edge_positive<V: Vector>(
    origin: V,
    dir: V,
    shear: &Shear<S<V>>,
    p: V,
    q: V,
) -> Option<bool> {
    // The triangle `(o, p, q)`: its normal is `(p - o) x (q - o)`.
    let triple = crossing(origin, dir, &Triangle::new(origin, p, q)).den_sign()?;
    let dz_positive = shear.dz > S::<V>::ZERO;
    match triple {
        Ordering::Greater => return Some(dz_positive),
        Ordering::Less => return Some(!dz_positive),
        Ordering::Equal => {}
    }
    // On the edge's line: `-D_y`, else `D_x`, in the sheared plane; each
    // is `(d_z (q - p)_k - d_k (q - p)_z) / d_z`.
    let w = |v: V| [v.x().to_f64(), v.y().to_f64(), v.z().to_f64()];
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    let (p, q, mut d) = (w(p), w(q), w(dir));
    let [kx, ky, kz] = [shear.kx, shear.ky, shear.kz].map(|k| k as usize);
    let mut diff = [0, 1, 2].map(|k| two_diff(q[k], p[k]));
    if wide {
        let m = diff.iter().fold(0.0f64, |m, x| m.max(x.0.abs()));
        let n = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !(m > 0.0 && m.is_finite() && n > 0.0 && n.is_finite()) {
            return None;
        }
        let (em, en) = (exponent(m), exponent(n));
        diff = diff.map(|(h, l)| (scale2(h, -em), scale2(l, -em)));
        d = d.map(|x| scale2(x, -en));
    }
    let sheared = |k: usize| {
        let (dk, dz) = (diff[k], diff[kz]);
        sum_of_products_sign(&[(d[kz], dk.0), (d[kz], dk.1), (-d[k], dz.0), (-d[k], dz.1)])
    };
    // `sign(D_k) = sign(d_z D_k) sign(d_z)`.
    let positive = |s: Ordering| (s == Ordering::Greater) == dz_positive;
    match sheared(ky) {
        Ordering::Equal => match sheared(kx) {
            Ordering::Equal => None,
            s => Some(positive(s)),
        },
        s => Some(!positive(s)),
    }
}

/// The exact crossing's signs for the ray and the triangle.
#[cold]
#[inline(never)]
pub(crate) fn crossing<V: Vector>(origin: V, dir: V, tri: &Triangle<V>) -> PlaneCrossing {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    // `f64` inputs are scaled; `f32` ones are in range as they are.
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    PlaneCrossing::new(w(origin), w(dir), w(tri.a), w(tri.b), w(tri.c), wide)
}

/// The hit of a triangle the moved ray crosses (exactly) where rounding
/// leaves the edge functions no usable sum (every one within its rounding
/// of zero: a sliver seen from the ray), over `interval`: the range
/// decided exactly against the exact crossing; `t` the corners' mean
/// depth (the exact crossing is a convex combination of the exact
/// depths, so `t` is within their spread of it), brought into the
/// interval; `u = v = 1/3`; the side the exact `d . n`'s. Its error
/// bounds are infinite ([`Surface::hit_error`](crate::Surface)). `None`
/// where the crossing is not in the interval, or the exact signs overflow.
#[cold]
#[inline(never)]
pub(crate) fn unresolved_hit<V: Vector>(
    (origin, dir): (V, V),
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
    f: &Frame<S<V>>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    // (A corner that is not finite makes a triangle nothing hits; its
    // exact signs below would not say so.)
    if !(tri.a.is_finite() && tri.b.is_finite() && tri.c.is_finite()) {
        return None;
    }
    let z = f.scaled_z(shear);
    let t = (z[0] + z[1] + z[2]) / S::<V>::from_u32(3);
    let (lo, hi) = interval.ends();
    let exact = crossing(origin, dir, tri);
    let side = match exact.den_sign()? {
        Ordering::Less => Side::Front,
        Ordering::Greater => Side::Back,
        Ordering::Equal => return None,
    };
    if !decide(t, S::<V>::INFINITY, lo, hi, || exact)? {
        return None;
    }
    let third = S::<V>::ONE / S::<V>::from_u32(3);
    Some(TriangleHit {
        t: bring_into(t, lo, hi),
        u: third,
        v: third,
        side,
    })
}

fn min3<F: Scalar>(v: [F; 3]) -> F {
    crate::num::round::min2(v[0], crate::num::round::min2(v[1], v[2]))
}

fn max3<F: Scalar>(v: [F; 3]) -> F {
    crate::num::round::max2(v[0], crate::num::round::max2(v[1], v[2]))
}
