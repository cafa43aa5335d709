//! The ray/sphere kernel: the line's two crossings with a sphere,
//! computed stably, the `t_max` form's fast decisions, and the error
//! bounds of both crossings, all derived here.
//!
//! The discriminant comes from the centre's distance to the line rather
//! than from `b^2 - a c`, which cancels when the line passes far from the
//! centre relative to its distance (Haines, Guenther and Akenine-Moller,
//! "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems
//! ch. 7, 2019): here as `a r^2 - |f x d|^2` (`|f x d|^2 = a |l|^2`, `l`
//! the centre's offset from the line), which needs no division. The
//! roots come in the stable pair `q / a`, `k / q` with `q = beta +
//! sign(beta) sqrt(a Delta)`, as there and in pbrt-v4 (Pharr, Jakob,
//! Humphreys, 4th ed., sec. 6.8, with interval arithmetic; here the
//! bounds are explicit).

use crate::num::round::bound_up;
use crate::num::round::outward::{add_up, div_up, mul_down, mul_up, sub_down};
use crate::num::{S, Scalar, Vector};

/// The computed quantities both forms share, in the notation of
/// [`crossings`]' derivation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line<V: Vector> {
    /// `F = fl(o - c)`.
    f: V,
    /// `fl(d . d)`.
    a: S<V>,
    /// `-fl(F . d)`.
    nd: S<V>,
    /// `fl(F . F)`.
    ff: S<V>,
    /// `fl(r r)`.
    rr: S<V>,
    /// `fl(ff - rr)`.
    k: S<V>,
    /// `C = fl(F x d)`.
    cross: V,
    /// `fl(C . C)`.
    cc: S<V>,
    /// `fl(a rr)`.
    ar: S<V>,
    /// `fl(ar - cc)`, the discriminant times `a`.
    x: S<V>,
}

impl<V: Vector> Line<V> {
    #[inline(always)]
    pub(crate) fn new(o: V, d: V, c: V, r: S<V>) -> Self {
        let f = o - c;
        let a = d.dot(d);
        let ff = f.dot(f);
        let rr = r * r;
        let cross = f.cross(d);
        let cc = cross.dot(cross);
        let ar = a * rr;
        Self {
            f,
            a,
            nd: -(f.dot(d)),
            ff,
            rr,
            k: ff - rr,
            cross,
            cc,
            ar,
            x: ar - cc,
        }
    }

    /// Whether the bounds below hold: every value finite, and `a` at
    /// least `8 T / u` (see [`crossings`]). A NaN or infinite input makes
    /// one of the sums NaN or infinite; a finite sum that overflows only
    /// sends the decision to the exact signs.
    #[inline(always)]
    fn usable(&self) -> bool {
        let floor = S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF;
        self.a >= floor && (self.x + self.ff + self.a).is_finite()
    }

    /// `M = max_i |F_i| sum_i |d_i|`, at least every `P_i` and `S` of the
    /// derivation.
    #[inline(always)]
    fn m(&self, d: V) -> S<V> {
        Self::m_of(self.f, d)
    }

    #[inline(always)]
    fn m_of(f: V, d: V) -> S<V> {
        let f = f.abs();
        let big = |p: S<V>, q: S<V>| if p > q { p } else { q };
        big(big(f.x(), f.y()), f.z()) * (d.x().abs() + d.y().abs() + d.z().abs())
    }

    /// `E_x`: `|x - a* Delta*|` at most this.
    #[inline(always)]
    fn err_x(&self, m: S<V>) -> S<V> {
        let (cross, cc, ar, x) = (self.cross, self.cc, self.ar, self.x);
        let g = S::<V>::gamma_n;
        let c = cross.abs();
        let tiny = S::<V>::MIN_POSITIVE;
        // Every E_C,i is at most e = gamma(3) M + 2 T.
        let e = g(3) * m + S::<V>::TWO * tiny;
        let c1 = c.x() + c.y() + c.z();
        bound_up(
            g(5) * ar
                + g(4) * cc
                + e * (S::<V>::TWO * c1 + S::<V>::from_u32(3) * e)
                + S::<V>::UNIT_ROUNDOFF * x.abs()
                // `8 T + a T` as one product: `a T` alone would be
                // subnormal for `a < 1`, and subnormal arithmetic is slow.
                + (self.a + S::<V>::from_u32(8)) * tiny,
            7,
        )
    }

    /// `E_nd`: `|nd - beta*|` at most this.
    #[inline(always)]
    fn err_nd(m: S<V>) -> S<V> {
        bound_up(S::<V>::gamma_n(4) * m + S::<V>::MIN_POSITIVE, 2)
    }

    /// `E_k`: `|k - k*|` at most this.
    #[inline(always)]
    fn err_k(&self) -> S<V> {
        Self::err_k_of(self.ff, self.rr)
    }

    #[inline(always)]
    fn err_k_of(ff: S<V>, rr: S<V>) -> S<V> {
        bound_up(
            S::<V>::gamma_n(8) * (ff + rr) + S::<V>::TWO * S::<V>::MIN_POSITIVE,
            3,
        )
    }

    /// `sqrt(max(x, 0))` and `q = nd + sign(nd) root`.
    #[inline(always)]
    fn q(&self) -> (S<V>, S<V>) {
        let zero = S::<V>::ZERO;
        let root = (if self.x > zero { self.x } else { zero }).sqrt();
        (
            root,
            if self.nd >= zero {
                self.nd + root
            } else {
                self.nd - root
            },
        )
    }
}

/// What the `t_max` form's fast path found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Fast<F> {
    /// The line surely misses the ball, or no crossing is surely ahead of
    /// the origin within `t_max` (`None`).
    Answer(Option<(F, bool)>),
    /// Undecided here (`beta` within rounding of zero, or a bound
    /// unusable): the exact decision.
    Unsure,
}

/// The `t_max` form's decision, where it can be made from signs alone;
/// `(t, entering)` for a hit.
///
/// The entry `t- = k* / Q*` (for `Q* > 0`) is ahead exactly when `k* > 0`
/// (the origin outside the ball), and the exit `Q* / a*` when `Q* > 0`;
/// for `Q* < 0` the entry `Q* / a*` is behind and the exit `k* / Q*` ahead
/// exactly when `k* < 0`. `nd` surely positive (beyond `E_nd`) makes
/// `beta* > 0` and so `Q* = beta* + sqrt(a* Delta*) > 0`, whatever the
/// root's error; likewise for negative. So with the signs of `beta*` and
/// `k*` known from their bounds, a crossing is reported only where it is
/// exactly ahead of the origin (where the line meets the ball), and the
/// reported value is the formula's, as [`crossings`] bounds it. An origin
/// within rounding of the sphere (`|k| <= E_k`) counts as on it: its
/// crossing there is dropped, and a ray into the ball finds the exit.
#[inline(always)]
pub(crate) fn fast<V: Vector>(o: V, d: V, c: V, r: S<V>, t_max: S<V>) -> Fast<S<V>> {
    let zero = S::<V>::ZERO;
    let line = Line::new(o, d, c, r);
    if !line.usable() {
        return Fast::Unsure;
    }
    let m = line.m(d);
    if line.x < zero && line.x < -line.err_x(m) {
        return Fast::Answer(None);
    }
    let (err_nd, err_k) = (Line::<V>::err_nd(m), line.err_k());
    let (_, q) = line.q();
    let ahead =
        |t: S<V>, entering: bool| Fast::Answer((t > zero && t <= t_max).then_some((t, entering)));
    if line.nd > err_nd {
        if line.k > err_k {
            ahead(line.k / q, true)
        } else {
            ahead(q / line.a, false)
        }
    } else if line.nd < -err_nd {
        if line.k < -err_k {
            ahead(line.k / q, false)
        } else {
            Fast::Answer(None)
        }
    } else {
        Fast::Unsure
    }
}

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
/// underflow). Exact values are starred, computed ones plain; `f = o - c`,
/// `beta* = -f . d`, `a* = d . d`, `k* = |f|^2 - r^2`.
///
/// - `F = fl(o - c)`: `|F_i - f_i| <= u |F_i|`.
/// - `a = fl(d . d)`: `|a - a*| <= gamma(3) a* <= gamma(4) a`.
/// - `nd = -fl(F . d)`: `|nd - beta*| <= gamma(4) S + T`, `S = sum |F_i
///   d_i|`, and `S <= M = max_i |F_i| sum_i |d_i|`: `E_nd = gamma(4) M +
///   T`.
/// - `C = fl(F x d)` against `c* = f x d`: `|C_i - c*_i| <= E_C,i =
///   gamma(3) P_i + 2 T <= e = gamma(3) M + 2 T`, `P_x = |F_y d_z| + |F_z
///   d_y|` and so on (two products and a difference, and `F`'s own
///   rounding), each at most `M`.
/// - The discriminant: `|c*|^2 = a* |l*|^2` (`l*` the centre's offset from
///   the line), so `y = a* r^2 - |c*|^2 = a* Delta*` with `Delta* = r^2 -
///   |l*|^2`, and `a* Delta* = beta*^2 - a* k*`: the line meets the closed
///   ball exactly where `y >= 0`. `x = fl(fl(a fl(r r)) - fl(C . C))`:
///   `|x - y| <= E_x = gamma(5) ar + gamma(4) cc + e (2 |C|_1 + 3 e) + u
///   |x| + 8 T + a T` (`ar` within `gamma(5)` of `a* r^2`, plus `a T` for
///   an `r r` that underflows; `cc` within
///   `gamma(4) cc` of `|C|^2`, which is within `sum E_C,i (|C_i| + |c*_i|)
///   <= e (2 |C|_1 + 3 e)` of `|c*|^2`). Where `x < -E_x` the line surely misses;
///   where `x > E_x` it surely meets the ball. Near the sphere's rim the
///   terms in `|C_i|` make the band a few ulps of `|l| |f|`, not of
///   `|f|^2`, which is what keeps far spheres whole.
/// - `root = fl(sqrt(max(x, 0)))` against `sqrt(y)` (where `y >= 0`):
///   `|sqrt x - sqrt y| <= min(sqrt(E_x), E_x / sqrt(x))`, so `|root -
///   sqrt y| <= E_r = min(sqrt(E_x), (1 + u) E_x / root) + u root`. (Near
///   tangency the first term is the square root of the discriminant's
///   error: the crossings of a nearly tangent line are that
///   ill-conditioned, whatever the formula.)
/// - `q = fl(nd + s root)`, `s` the sign of `nd` (no cancellation),
///   against `Q* = beta* + s sqrt(y)`: `|q - Q*| <= E_q = E_nd + E_r + u
///   |q|`.
/// - `q / a` against `Q* / a*`: at most `(E_q + gamma(5) (|q| + E_q)) /
///   a + u |t| + T`.
/// - `k = fl(fl(F . F) - fl(r r))` against `k*`: `|k - k*|` is at most
///   `gamma(7) ff + u rr + u |k| + 2 T`, so at most `E_k = gamma(8) (ff +
///   rr) + 2 T` (`|F|^2` against `|f|^2` adds `(2u + u^2) |F|^2`; `|k| <=
///   ff + rr`); `k / q` against `k* / Q*`: at most `E_k / |q| + (|k| +
///   E_k) E_q / (|q| (|q| - E_q)) + u |t| + T`, infinite unless `|q| >
///   E_q`.
///
/// Every bound is a sum of products of non-negative values, evaluated in
/// floating point and made an upper bound with `bound_up` (the
/// difference `|q| - E_q` and the quotients rounded outward); the `T`
/// terms cover underflow wherever `a` is at least `8 T / u`. A shorter
/// `dir`, and any overflow, give infinite bounds and `sure = false`,
/// leaving every decision to the exact signs.
#[inline(always)]
pub(crate) fn crossings<V: Vector>(o: V, d: V, c: V, r: S<V>) -> Option<Crossings<S<V>>> {
    let zero = S::<V>::ZERO;
    let inf = S::<V>::INFINITY;
    let r = r.abs();
    if !(o.is_finite() && c.is_finite() && r.is_finite() && d.is_finite()) {
        return None;
    }
    let line = Line::new(o, d, c, r);
    // (A `dir` whose `d . d` underflows to zero is still a ray: its
    // crossings are left to the exact signs, as `usable` fails.)
    let (root, q) = line.q();
    let label = |t1: S<V>, t2: S<V>, e1: S<V>, e2: S<V>, sure: bool| {
        let (entry, exit, entry_err, exit_err) = if line.nd >= zero {
            (t2, t1, e2, e1)
        } else {
            (t1, t2, e1, e2)
        };
        Crossings {
            entry,
            exit,
            entry_err,
            exit_err,
            sure,
        }
    };
    let t1 = q / line.a;
    let t2 = if q != zero { line.k / q } else { t1 };
    if !line.usable() {
        return Some(label(t1, t2, inf, inf, false));
    }
    let u = S::<V>::UNIT_ROUNDOFF;
    let g = S::<V>::gamma_n;
    let tiny = S::<V>::MIN_POSITIVE;
    let m = line.m(d);
    let err_x = line.err_x(m);
    if line.x < -err_x {
        return None;
    }
    let sure = line.x > err_x;
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
    let qa = q.abs();
    let err_q = add_up(add_up(Line::<V>::err_nd(m), err_root), mul_up(u, qa));
    let err1 = bound_up(
        (err_q + g(5) * (qa + err_q)) / line.a + u * t1.abs() + tiny,
        5,
    );
    let err1 = if t1.is_finite() { err1 } else { inf };
    let room = sub_down(qa, err_q);
    let err2 = if room > zero && t2.is_finite() {
        let err_k = line.err_k();
        let spread = div_up(
            mul_up(add_up(line.k.abs(), err_k), err_q),
            mul_down(qa, room),
        );
        add_up(bound_up(err_k / qa + u * t2.abs() + tiny, 3), spread)
    } else {
        inf
    };
    Some(label(t1, t2, err1, err2, sure))
}
