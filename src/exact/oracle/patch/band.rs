//! The ray/patch test's rounding band: [`patch_clear`].

use super::super::filter::{coordinate_bound_up, edge_margin_up};
use super::super::main_axis;
use super::super::values::*;
use super::*;
use crate::num::round::outward::{add_up, div_up, mul_up};
use crate::{Patch, Ray, Scalar, Side, Triangle, Vector};
use core::cmp::Ordering;
use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use std::vec::Vec;

/// The factor by which the band of [`patch_clear`] widens the
/// discriminant's rounding.
const DISC_FACTOR: i64 = 1 << 10;

/// The factor by which the band of [`patch_clear`] widens the roots'
/// and the crossings' error estimates.
const PLACE_FACTOR: f64 = 16.0;

/// The patch case is outside the ray/patch test's rounding band (the
/// `t_max` form's, closed rule: see [`Patch`]): a kernel with the
/// crate's documented guarantees answers hit or miss, and the side, as
/// [`ray_patch`](crate::exact::ray_patch) does, and reports the crossing
/// it names. `false` (an `Edge` case) unless every condition below holds
/// in exact arithmetic.
///
/// A patch with a collapsed edge ([`collapsed_triangle`]) is that
/// triangle, bit for bit: its band is the watertight test's
/// ([`triangle_clear_watertight`](super::super::triangle_clear_watertight)).
/// Otherwise, in the ray's sheared frame (the triangle test's), where the
/// patch's boundary is decided by the edge functions of its two
/// triangles `p00, p10, p11` and `p00, p11, p01` and its crossings by the
/// quadratic `c(u) = b0 (1 - u)^2 + 2 b1 u (1 - u) + b2 u^2` with
/// discriminant `D = b1^2 - b0 b2` (Reshetov, Ray Tracing Gems ch. 8, in
/// that frame; every bound below is evaluated in `f64` rounded up, which
/// only widens the band, and compared exactly):
///
/// - (precondition) the corners relative to the origin are within the
///   documented range: every coordinate below `2^63` (`f32`) or `2^511`
///   (`f64`) in magnitude, and the largest at least `sqrt(MIN_POSITIVE) /
///   u`;
/// - (a) the line is clear of each boundary edge's line, `p00-p10`,
///   `p10-p11`, `p11-p01`, `p01-p00`: its exact edge function (the
///   Plucker product over `d_z`) farther from zero than the test's
///   rounding of it, [`edge_function_bound`](super::super::edge_function_bound)
///   of the triangle holding the edge. Then each computed edge function
///   has the exact sign. The diagonal `p00-p11` needs no margin where its
///   sign cannot change the winding number the test sums: both triangles
///   compute its edge function bit for bit, negated, and the sum of the
///   two triangles' windings changes with its sign by `[s1 = s2] - [s3 =
///   s4]` (`s_i` the boundary edges' signs in order), which is zero
///   whenever its exact edge function is zero (the line through the
///   origin and `q00` then holds `q11`, on the same side, making both
///   pairs differ, or on the other, making both agree); where the
///   diagonal is within its rounding and that difference is not zero,
///   the case is not clear;
/// - (b) the discriminant is decided with room: `|D| > 2^10 (dD + E^2)`,
///   `dD` the bound on the computed discriminant's error (the
///   coefficients' errors `E_i`: the edge functions' bounds, and for
///   `b1`, the mean of the diagonal's and of the cross product `q10 x
///   q01`, that one's rounding too, carried through `b1^2 - b0 b2`, and
///   `gamma(3)` of its terms for the scaling and the products), `E` the
///   largest `E_i`. With `dD` alone the computed discriminant's sign is
///   the exact one; the factor is chosen, not derived, for what follows
///   from it: at each crossing the projected Jacobian is `+-2 sqrt(D)`,
///   which must stay clear of the rounding of the corners' orientations
///   (a two-crossing fold is only looked for where they differ in sign)
///   and of the certificate's determinant, and a simple root of the
///   computed quadratic moves by about `E / sqrt(D)`. Held with one
///   crossing too (the test's `t > 0` decision certifies it). Where the
///   winding number is zero and `D < 0`, there is no crossing, and the
///   case is a clear miss;
/// - (b') with zero winding and `D > 0`, each root `u*` of the quadratic
///   is farther than `r_u = 16 (E + gamma(8) B) / sqrt(D)` (`B` the
///   largest `|b_i| + E_i`) from 0 and 1, and where it is between them
///   the place `v*` of the line on its ruling is farther than `r_v = r_u
///   (1 + |Q_u| / |Q_v|) + 16 r_c` from 0 and 1 (`Q_u`, `Q_v` the
///   projected patch's derivatives at `(u*, v*)` brought into the square,
///   `r_c` the certified `(u, v)` radius of
///   [`Patch`'s `hit_error`](crate::Patch#method.hit_error) at `(u*,
///   v*)`, finite), or, for a `v*` more than a half outside `[0, 1]`, `r_u
///   (1 + |Q_u| / |Q_v|)` is at most a quarter: the test's `0 <= u, v <=
///   1` checks on its computed roots then agree with the exact ones (a
///   first-order estimate of how far a computed root and its `v` move,
///   with a factor 16 for the solution's own roundings and the estimate's
///   slack);
/// - (c) every crossing in the square (behind the origin too) has `t`
///   farther than 16 times its certified bound (`hit_error`'s `t` at the
///   exact crossing; finite) from 0 and from `t_max` (from `MAX` for an
///   infinite one), and two crossings both in `(0, t_max]` are farther
///   apart than 16 times the sum of theirs. The test takes a crossing as
///   in front of the origin where every corner is, or where its `t`
///   exceeds its certified bound at its own `(u, v)`, which the factor
///   takes to be within 8 times the bound at the exact crossing (chosen,
///   not derived);
/// - (d) with zero winding and a crossing, the corners' exact sheared
///   coordinates reach past each of the frame's axes through the ray, on
///   both sides, by more than their rounding
///   (`dx`, `dy` of [`edge_function_bound`](super::super::edge_function_bound)'s
///   derivation, the larger of the two triangles'): the test's shortcut
///   that rules out a patch whose corners all lie on one side of such an
///   axis then sees them as they are.
///
/// False too when a value is not finite or the direction is zero.
///
/// ```
/// use rayhit::exact::oracle::patch_clear;
/// use rayhit::{Patch, Ray, glam::Vec3};
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// // Straight down at (0.3, 0.6): far from every edge and from t = 0.
/// let ray = Ray::new(Vec3::new(0.3, 0.6, 2.0), -Vec3::Z);
/// assert!(patch_clear(&ray, &saddle, f32::INFINITY));
/// // Through the edge v = 0, or ending at the crossing: not clear.
/// let edge = Ray::new(Vec3::new(0.3, 0.0, 2.0), -Vec3::Z);
/// assert!(!patch_clear(&edge, &saddle, f32::INFINITY));
/// assert!(!patch_clear(&ray, &saddle, 1.82));
/// ```
#[must_use]
pub fn patch_clear<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, t_max: V::Scalar) -> bool {
    patch_band(ray, patch, t_max).is_some()
}

/// [`patch_clear`]: `Some(())` for a clear case.
fn patch_band<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, t_max: V::Scalar) -> Option<()> {
    let Patch { p00, p10, p01, p11 } = *patch;
    let finite = [p00, p10, p01, p11].iter().all(|p| p.is_finite());
    if !(ray.is_valid() && finite && t_max.partial_cmp(&t_max).is_some()) {
        return None;
    }
    if let Some(tri) = collapsed_triangle(patch) {
        let exact = super::super::triangle(ray, &tri)?;
        return super::super::triangle_clear_watertight(ray, &tri, &exact, t_max).then_some(());
    }
    let line = PatchLine::new(ray, patch)?;
    in_range::<V::Scalar>(line.reach())?;
    // The margins, in units of the Plucker products (`d_z` times the edge
    // functions'), as `f64` upper bounds.
    let [first, second] = patch.triangles();
    let m1 = edge_margin_up(ray, &first)?;
    let m2 = edge_margin_up(ray, &second)?;
    let mx = edge_margin_up(ray, &Triangle::new(p10, p01, p00))?;
    let md = m1.min(m2);
    let exponent = line.plucker_exponent();
    let s = |i: usize, j: usize| line.plucker(i, j);
    // `|x| 2^exponent > m`, exactly.
    let beyond = |x: &BigInt, m: f64| above(x, exponent, m);
    // (a) The boundary edges 00-10, 10-11, 11-01, 01-00.
    let edges = [s(0, 1), s(1, 3), s(3, 2), s(2, 0)];
    if !edges
        .iter()
        .zip([m1, m1, m2, m2])
        .all(|(e, m)| beyond(e, m))
    {
        return None;
    }
    let sign = |x: &BigInt| x.is_positive();
    let pair = |a: usize, b: usize| sign(&edges[a]) == sign(&edges[b]);
    let diagonal = s(3, 0);
    if !beyond(&diagonal, md) && pair(0, 1) != pair(2, 3) {
        return None;
    }
    // The winding number, from the first triangle (00-10, 10-11, 11-00)
    // and the second (00-11, 11-01, 01-00); a diagonal of exactly zero
    // taken as positive (where the check above passed, either sign gives
    // the same sum).
    let covers = |e: [&BigInt; 3]| {
        let all = |f: fn(&BigInt) -> bool| e.iter().all(|x| f(x));
        i32::from(all(BigInt::is_positive)) - i32::from(all(BigInt::is_negative))
    };
    let signed = if diagonal.is_zero() {
        BigInt::from(1)
    } else {
        diagonal.clone()
    };
    let winding =
        covers([&edges[0], &edges[1], &signed]) + covers([&-&signed, &edges[2], &edges[3]]);
    let across = -diagonal.clone();
    // (b) The quadratic's Bernstein coefficients (`b1` twice over, to stay
    // in integers), bounds on their errors and on the discriminant's, all
    // rounded up.
    let b0 = -edges[3].clone();
    let b2 = edges[1].clone();
    let twice_b1 = &across + s(1, 2);
    let up = |x: &BigInt, halve: bool| {
        let e = exponent - i64::from(halve);
        scaled_f64(&x.abs(), e).next_up()
    };
    let (a0, a1, a2) = (up(&b0, false), up(&twice_b1, true), up(&b2, false));
    let u = V::Scalar::UNIT_ROUNDOFF.to_f64();
    let g = |n: f64| div_up(n * u, 1.0 - n * u);
    let tiny = V::Scalar::TINY.to_f64();
    let dz = ray.dir[main_axis(ray.dir)].to_f64().abs();
    let half_sum = mul_up(add_up(md, mx), 0.5);
    let e1 = add_up(
        add_up(half_sum, mul_up(u, add_up(a1, half_sum))),
        mul_up(tiny, dz),
    );
    let (e0, e2) = (m2, m1);
    let (g0, g1, g2) = (add_up(a0, e0), add_up(a1, e1), add_up(a2, e2));
    let e_max = e0.max(e1).max(e2);
    let b_max = g0.max(g1).max(g2);
    let disc_err = [
        mul_up(mul_up(2.0, a1), e1),
        mul_up(e1, e1),
        mul_up(a0, e2),
        mul_up(a2, e0),
        mul_up(e0, e2),
        mul_up(g(3.0), add_up(mul_up(g1, g1), mul_up(g0, g2))),
        mul_up(mul_up(4.0 * tiny, b_max), b_max),
    ]
    .into_iter()
    .fold(0.0, add_up);
    let threshold = mul_up(DISC_FACTOR as f64, add_up(disc_err, mul_up(e_max, e_max)));
    // `D = b1^2 - b0 b2 = four_d / 4`, in units of `2^(2 exponent)`.
    let four_d = &twice_b1 * &twice_b1 - BigInt::from(4) * &b0 * &b2;
    // `|D| > threshold`: `|four_d| 2^(2 exponent - 2) > threshold`.
    if !above(&four_d, 2 * exponent - 2, threshold) {
        return None;
    }
    let crossings: Vec<PatchCrossing> = if winding != 0 {
        let e = patch_crossings(&line);
        (e.len() == 1).then_some(e)?
    } else if four_d.is_negative() {
        // No root: a clear miss.
        return Some(());
    } else {
        // (b') Each root clear of the square's edges.
        let noise = add_up(e_max, mul_up(g(8.0), b_max));
        let r_u = PLACE_FACTOR * noise / scaled_f64(&four_d, 2 * exponent - 2).sqrt();
        let frame = Sheared::new(&line, main_axis(ray.dir));
        let mut found = Vec::new();
        for root in line.roots() {
            let u = line.u(&root);
            if !clear_of_ends(&u, r_u)? {
                return None;
            }
            let u_f = u.to_f64();
            if !(0.0 < u_f && u_f < 1.0) {
                continue;
            }
            let (v, _) = line.place(&root)?;
            let v_f = v.to_f64();
            // How far the computed root's `v` moves with it.
            let moved = r_u * (1.0 + frame.stretch(u_f, v_f.clamp(0.0, 1.0))?);
            if !(-0.5..=1.5).contains(&v_f) {
                // Far outside: the test's `v` would be off by more than a
                // half.
                if moved > 0.25 {
                    return None;
                }
                continue;
            }
            let r_v = moved + PLACE_FACTOR * certified(ray, patch, u_f, v_f)?.1;
            if !clear_of_ends(&v, r_v)? {
                return None;
            }
            if 0.0 < v_f && v_f < 1.0 {
                found.push(line.crossing(&root, true)?);
            }
        }
        if found.len() == 2 {
            // (d) The corners on both sides of each axis.
            let (x1, y1) = coordinate_bound_up(ray, &first)?;
            let (x2, y2) = coordinate_bound_up(ray, &second)?;
            if !(frame.straddles(0, x1.max(x2)) && frame.straddles(1, y1.max(y2))) {
                return None;
            }
        }
        (found.len() != 1).then_some(found)?
    };
    // (c) The crossings' t.
    let end = if t_max < V::Scalar::MAX {
        t_max.to_f64()
    } else {
        V::Scalar::MAX.to_f64()
    };
    let mut ahead = Vec::new();
    for x in &crossings {
        let (bound, _) = certified(ray, patch, x.u.to_f64(), x.v.to_f64())?;
        let room = PLACE_FACTOR * bound;
        if !(apart(&x.t, 0.0, room)? && apart(&x.t, end, room)?) {
            return None;
        }
        if x.t.cmp_rational(&R::zero()) == Ordering::Greater
            && x.t.cmp_rational(&sum(end, 0.0)?) != Ordering::Greater
        {
            ahead.push((x.t.clone(), bound));
        }
    }
    if let [(t1, b1), (t2, b2)] = ahead.as_slice() {
        let room = R::from_float(PLACE_FACTOR * (b1 + b2))?;
        let gap = t2.clone() - t1.clone();
        let gap = if gap.sign() == Ordering::Less {
            -gap
        } else {
            gap
        };
        (gap.cmp_rational(&room) == Ordering::Greater).then_some(())?;
    }
    Some(())
}

/// Whether `x` is farther than `room` (an `f64`, at least zero) from 0
/// and from 1; `None` where `room` is not finite.
fn clear_of_ends(x: &Surd, room: f64) -> Option<bool> {
    Some(apart(x, 0.0, room)? && apart(x, 1.0, room)?)
}

/// Whether `x` is farther than `room` from `y` (floats; `None` where one
/// is not finite).
fn apart(x: &Surd, y: f64, room: f64) -> Option<bool> {
    Some(
        x.cmp_rational(&sum(y, -room)?) == Ordering::Less
            || x.cmp_rational(&sum(y, room)?) == Ordering::Greater,
    )
}

/// `a + b` for floats, exactly, as a rational not reduced (`None` where
/// one is not finite).
fn sum(a: f64, b: f64) -> Option<R> {
    use num_traits::float::FloatCore;
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let part = |x: f64| {
        let (m, e, sign) = x.integer_decode();
        (BigInt::from(sign) * BigInt::from(m), i64::from(e))
    };
    let ((ma, ea), (mb, eb)) = (part(a), part(b));
    let e = ea.min(eb);
    let n = (ma << (ea - e).unsigned_abs()) + (mb << (eb - e).unsigned_abs());
    let one = BigInt::from(1);
    Some(if e >= 0 {
        R::new_raw(n << e.unsigned_abs(), one)
    } else {
        R::new_raw(n, one << e.unsigned_abs())
    })
}

/// [`Patch`'s `hit_error`](crate::Patch#method.hit_error) at `(u, v)`:
/// the bounds on `t` and on `u`, `v`, as `f64`; `None` where they are not
/// finite.
fn certified<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, u: f64, v: f64) -> Option<(f64, f64)> {
    let f = V::Scalar::from_f64;
    let probe = crate::PatchHit {
        t: V::Scalar::ONE,
        u: f(u),
        v: f(v),
        side: Side::Front,
    };
    let e = crate::Surface::hit_error(patch, ray, &probe);
    let (t, uv) = (e.t.to_f64(), e.u.to_f64());
    (t.is_finite() && uv.is_finite()).then_some((t, uv))
}

/// The corners' `x` and `y` in the ray's sheared frame (the triangle
/// test's, on the main axis `kz` of [`main_axis`]), exactly: `x = X 2^E /
/// d_kz` with the integer `X = q_kx d_kz - d_kx q_kz` (`q` a corner less
/// the origin, in the line's units), and `y` likewise.
struct Sheared {
    x: [BigInt; 4],
    y: [BigInt; 4],
    /// `d_kz` in the line's integers, and `E`.
    dz: BigInt,
    e: i64,
}

impl Sheared {
    fn new(line: &PatchLine, kz: usize) -> Self {
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let d = &line.d;
        let at = |k: usize| {
            line.offsets
                .clone()
                .map(|q| &q[k] * &d[kz] - &d[k] * &q[kz])
        };
        Self {
            x: at(kx),
            y: at(ky),
            dz: d[kz].clone(),
            e: line.exponents.0,
        }
    }

    /// `|Q_u| / |Q_v|` at `(u, v)`, in `f64` (the common factor `2^E /
    /// d_kz` cancels); `None` where `Q_v` is zero.
    fn stretch(&self, u: f64, v: f64) -> Option<f64> {
        let bits = self
            .x
            .iter()
            .chain(&self.y)
            .map(BigInt::bits)
            .max()
            .unwrap_or(0);
        let top = -i64::try_from(bits).ok()?;
        let f = |c: &[BigInt; 4]| c.clone().map(|x| scaled_f64(&x, top));
        let (x, y) = (f(&self.x), f(&self.y));
        let du = |c: &[f64; 4]| (1.0 - v) * (c[1] - c[0]) + v * (c[3] - c[2]);
        let dv = |c: &[f64; 4]| (1.0 - u) * (c[2] - c[0]) + u * (c[3] - c[1]);
        let qu = du(&x).hypot(du(&y));
        let qv = dv(&x).hypot(dv(&y));
        let ratio = qu / qv;
        ratio.is_finite().then_some(ratio)
    }

    /// Whether the corners' coordinate on axis `k` (0 for `x`, 1 for `y`)
    /// reaches beyond `-m` and beyond `m`: some `X 2^E / d_kz < -m` and
    /// some `> m`, decided in integers.
    fn straddles(&self, k: usize, m: f64) -> bool {
        let c = if k == 0 { &self.x } else { &self.y };
        let flip = |x: &BigInt| if self.dz.is_negative() { -x } else { x.clone() };
        let beyond = |x: BigInt| x.is_positive() && above_times(&x, self.e, m, &self.dz);
        c.iter().any(|x| beyond(-flip(x))) && c.iter().any(|x| beyond(flip(x)))
    }
}

/// The documented range of the patch test's guarantees, for `m` the
/// largest magnitude of a corner coordinate relative to the origin: below
/// `2^63` (`f32`) or `2^511` (`f64`), and at least `sqrt(MIN_POSITIVE) /
/// u`.
fn in_range<F: Scalar>(m: f64) -> Option<()> {
    let single = F::UNIT_ROUNDOFF.to_f64() > 1e-10;
    let top = if single {
        2f64.powi(63)
    } else {
        2f64.powi(511)
    };
    let floor = F::MIN_POSITIVE.to_f64().sqrt() / F::UNIT_ROUNDOFF.to_f64();
    (m < top && m >= floor).then_some(())
}
