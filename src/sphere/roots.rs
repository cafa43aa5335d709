//! The ray/sphere kernel: the line's two crossings with a sphere,
//! computed stably, each with an error bound, and the miss test that
//! never drops a line meeting the ball.
//!
//! Haines, Guenther and Akenine-Moller, "Precision Improvements for
//! Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7, 2019): the
//! discriminant from the centre's distance to the ray's line, `r^2 -
//! |l|^2`, rather than `b^2 - a c` (which cancels when the line passes far
//! from the centre relative to the distance), and the roots from `q = b +
//! sign(b) sqrt(a disc)` as `q / a` and `k / q`. The error bounds are
//! derived below, term by term, in the style of pbrt-v4's interval
//! arithmetic (Pharr, Jakob, Humphreys, 4th ed., sec. 6.8), but as
//! explicit bounds on the computed values.

use crate::num::round::bound_up;
use crate::num::round::outward::{add_up, div_up, mul_down, mul_up, sub_down};
use crate::num::{S, Scalar, Vector};

/// A line's two crossings with a sphere and their error bounds.
///
/// The crossings are labelled exactly: with `s` the sign used in `q`,
/// `q / a` stands for `(beta + s sqrt(a* Delta*)) / a*` (the larger exact
/// root when `s = +1`) and `k / q` for the other, so `entry` is the
/// computed value of the exact smaller root `t-` and `exit` of the larger
/// `t+`, whatever their computed order (they may be swapped where they lie
/// within their bounds of each other).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Crossings<F> {
    /// The computed entry `t-`.
    pub(crate) entry: F,
    /// The computed exit `t+`.
    pub(crate) exit: F,
    /// `|entry - t-|` at most this where the line meets the ball;
    /// infinite where unknown.
    pub(crate) entry_err: F,
    /// `|exit - t+|` at most this, as `entry_err`.
    pub(crate) exit_err: F,
    /// The line surely meets the ball (the discriminant is surely
    /// positive). Where `false` it is within rounding of tangent, or the
    /// bounds are unusable, and may miss: the exact signs decide.
    pub(crate) sure: bool,
}

/// The line `o + t d` against the sphere with centre `c` and radius `r`
/// (its magnitude): `None` where the line surely misses the closed ball,
/// or an input is not finite, or `d` is zero. Never `None` for a line that
/// meets the ball in exact arithmetic (no false miss).
///
/// # Derivation
///
/// `u` is the unit roundoff, `gamma(n) = n u / (1 - n u)`, `T` the
/// smallest positive normal (`MIN_POSITIVE`), standing in for the
/// absolute error of every product or quotient that underflows (at most
/// `u T` each: sums and differences of floats are exact when they
/// underflow). Exact values are starred, computed ones plain; `f = o - c`.
///
/// - `F = fl(o - c)`: `|F_i - f_i| <= u |F_i|`.
/// - `a = fl(d . d)`: `|a - a*| <= gamma(3) a* <= gamma(4) a`.
/// - `nd = -fl(F . d)` against `beta* = -f . d`: `|nd - beta*| <= gamma(4)
///   S + T` with `S = sum |F_i d_i|`.
/// - `kappa = fl(nd / a)` against `kappa* = beta* / a*` (where the line
///   passes nearest the centre): `|kappa - kappa*| <= K = gamma(9) S / a +
///   T / a + T` (the numerator's error, `1/a` against `1/a*` (`gamma(3)/a`
///   times `|beta*| <= (1 + u) S`), and the division).
/// - `L = fl(F + fl(kappa d))` against `l* = f + kappa* d` (the centre's
///   offset from the line): per component `u |F_i| + K |d_i| + gamma(2)
///   (|kappa d_i| + |L_i|) + T`, so `|L - l*| <= e = gamma(1) |F|_1 + K
///   |d|_1 + gamma(2) (|kappa| |d|_1 + |L|_1) + 3 T`.
/// - The miss test: `h2 = fl(L . L) <= (1 + gamma(3)) |L|^2 + 3 u T`, so
///   `|l*| >= |L| - e > r` (a sure miss) where `h2 (1 - gamma(4)) - T >
///   (r + e)^2`, each side rounded the safe way.
/// - The discriminant `Delta* = r^2 - |l*|^2` (`a* Delta* = beta*^2 - a*
///   k*`, `k* = |f|^2 - r^2`): `disc = fl(fl(r r) - h2)` is within `E_D =
///   u rr + gamma(4) h2 + e (2 |L|_1 + e) + u |disc| + 2 T` of it. Where
///   `disc > E_D` the line surely meets the ball. Clamping a negative
///   `disc` to zero keeps `|disc - Delta*| <= E_D` wherever `Delta* >= 0`.
/// - `x = fl(a disc)` against `y = a* Delta*`: `|x - y| <= E_x = a E_D +
///   gamma(4) a (disc + E_D) + u x + T`; `root = fl(sqrt(x))` against
///   `sqrt(y)`: `|sqrt x - sqrt y| <= min(sqrt(E_x), E_x / sqrt(x))`, so
///   `|root - sqrt y| <= E_r = min(sqrt(E_x), (1 + u) E_x / root) + u
///   root`. (Near tangency the first term is the square root of the
///   discriminant's error: the crossings of a nearly tangent line are
///   that ill-conditioned, whatever the formula.)
/// - `q = fl(nd + s root)`, `s` the sign of `nd` (no cancellation),
///   against `Q* = beta* + s sqrt(y)`: `|q - Q*| <= E_q = gamma(4) S + T +
///   E_r + u |q|`.
/// - `q / a` against `Q* / a*`: `(E_q + gamma(5) (|q| + E_q)) / a + u |t|
///   + T`.
/// - `k = fl(fl(F . F) - fl(r r))` against `k*`: `|k - k*| <= E_k =
///   gamma(7) ff + u rr + u |k| + 2 T` (`|F|^2` against `|f|^2` adds
///   `(2u + u^2) |F|^2`); `k / q` against `k* / Q*`: `E_k / |q| + (|k| +
///   E_k) E_q / (|q| (|q| - E_q)) + u |t| + T`, infinite unless `|q| >
///   E_q`.
///
/// Every bound is a sum of products of non-negative values, evaluated in
/// floating point and made an upper bound with `bound_up` (the
/// difference `|q| - E_q` and the quotients rounded outward). The bounds
/// hold while no product underflows unless its error is covered by `T`:
/// `a` must be at least `8 T / u` (the quotients by `a` then turn each
/// `T` into at most `u / 8`); a shorter `dir`, and any overflow, give
/// infinite bounds and `sure = false`, leaving every decision to the
/// exact signs.
#[inline(always)]
pub(crate) fn crossings<V: Vector>(o: V, d: V, c: V, r: S<V>) -> Option<Crossings<S<V>>> {
    let zero = S::<V>::ZERO;
    let inf = S::<V>::INFINITY;
    let r = r.abs();
    let f = o - c;
    let a = d.dot(d);
    let nd = -(f.dot(d));
    let kappa = nd / a;
    let l = f + d * kappa;
    let h2 = l.dot(l);
    let rr = r * r;
    let ff = f.dot(f);
    let k = ff - rr;
    if !(o.is_finite() && c.is_finite() && r.is_finite() && a > zero) {
        return None;
    }
    let usable = a >= S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF
        && h2.is_finite()
        && ff.is_finite()
        && a.is_finite()
        && rr.is_finite()
        && kappa.is_finite();
    if !usable {
        // The computed roots, for the reported `t` (brought into the
        // interval); the exact signs decide.
        let disc = rr - h2;
        let root = (a * if disc > zero { disc } else { zero }).sqrt();
        let q = if nd >= zero { nd + root } else { nd - root };
        let (t1, t2) = (q / a, k / q);
        let (entry, exit) = if nd >= zero { (t2, t1) } else { (t1, t2) };
        return Some(Crossings {
            entry,
            exit,
            entry_err: inf,
            exit_err: inf,
            sure: false,
        });
    }
    let g = S::<V>::gamma_n;
    let u = S::<V>::UNIT_ROUNDOFF;
    let tiny = S::<V>::MIN_POSITIVE;
    let norm1 = |v: V| v.x().abs() + v.y().abs() + v.z().abs();
    let s_fd = f.x().abs() * d.x().abs() + f.y().abs() * d.y().abs() + f.z().abs() * d.z().abs();
    let (d1, l1) = (norm1(d), norm1(l));
    let big_k = g(9) * s_fd / a + tiny / a + tiny;
    let e = bound_up(
        g(1) * norm1(f) + big_k * d1 + g(2) * (kappa.abs() * d1 + l1) + S::<V>::from_u32(3) * tiny,
        8,
    );
    // The miss test: |l*| >= |L| - e > r.
    let reach = add_up(r, e);
    if h2 * (S::<V>::ONE - g(4)) - tiny > mul_up(reach, reach) {
        return None;
    }
    let disc_raw = rr - h2;
    let err_disc = bound_up(
        u * rr + g(4) * h2 + e * (S::<V>::TWO * l1 + e) + u * disc_raw.abs() + S::<V>::TWO * tiny,
        6,
    );
    let sure = disc_raw > err_disc;
    let disc = if disc_raw > zero { disc_raw } else { zero };
    let x = a * disc;
    let root = x.sqrt();
    let err_x = bound_up(
        a * err_disc + g(4) * a * (disc + err_disc) + u * x + tiny,
        4,
    );
    let near_tangent = bound_up(err_x.sqrt(), 1);
    let err_root = if root > zero {
        let far = div_up(mul_up(S::<V>::ONE + u, err_x), root);
        add_up(
            if far < near_tangent {
                far
            } else {
                near_tangent
            },
            mul_up(u, root),
        )
    } else {
        near_tangent
    };
    let q = if nd >= zero { nd + root } else { nd - root };
    let qa = q.abs();
    let err_q = bound_up(g(4) * s_fd + tiny + err_root + u * qa, 3);
    let t1 = q / a;
    let err1 = bound_up((err_q + g(5) * (qa + err_q)) / a + u * t1.abs() + tiny, 5);
    let room = sub_down(qa, err_q);
    let (t2, err2) = if room > zero {
        let t2 = k / q;
        let err_k = bound_up(g(7) * ff + u * rr + u * k.abs() + S::<V>::TWO * tiny, 3);
        let spread = div_up(mul_up(add_up(k.abs(), err_k), err_q), mul_down(qa, room));
        let err2 = add_up(bound_up(err_k / qa + u * t2.abs() + tiny, 3), spread);
        (t2, if t2.is_finite() { err2 } else { inf })
    } else {
        (kappa, inf)
    };
    let err1 = if t1.is_finite() { err1 } else { inf };
    let (entry, exit, entry_err, exit_err) = if nd >= zero {
        (t2, t1, err2, err1)
    } else {
        (t1, t2, err1, err2)
    };
    Some(Crossings {
        entry,
        exit,
        entry_err,
        exit_err,
        sure,
    })
}
