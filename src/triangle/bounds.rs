//! The rounding error bounds of a watertight hit, all derived here: those
//! of the sheared coordinates and edge functions ([`ErrorBounds`]), of the
//! determinant's sign ([`HitCondition`]), of `t`, `u` and `v`
//! ([`Triangle`'s `hit_error`](crate::Triangle#method.hit_error)), of the `t` taken from a zero-area
//! triangle's longest edge, and of a hit point ([`Triangle::surface_point_at`](crate::Triangle::surface_point_at)).

use super::frame::Frame;
use super::{Triangle, TriangleHit};
use crate::num::round::{bound_up, max2, min2};
use crate::num::{S, Scalar, Vector};
use crate::ray::{Ray, Shear};

/// Rounding error bounds of the watertight test's intermediate values, all
/// absolute, in terms of the computed quantities.
///
/// Notation: `u` the unit roundoff, `gamma(n) = n*u/(1 - n*u)`; `P` the exact
/// translated, permuted corners and `p` their computed values (one rounding
/// each); `X, Y, Z` the exact sheared and scaled coordinates, `x, y, z` the
/// computed ones; `E_i`, `e_i` the exact and computed edge functions. The
/// structure follows pbrt-v4 (`IntersectTriangle`; Pharr, Jakob and
/// Humphreys, "Physically Based Rendering", 4th ed., section 6.8.4), with
/// the shear error measured by the actual shear factor and the result, so
/// that it holds for a direction of any length, vanishes for an
/// axis-parallel ray and stays small where the shear cancels the
/// translation; second-order terms are kept.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ErrorBounds<F> {
    /// Bound on `|e_i - E_i|`.
    pub(crate) e: F,
    /// Bound on `|z_i - Z_i|`.
    pub(crate) z: F,
    /// Bound on `|t_scaled - sum E_i Z_i|`.
    pub(crate) t_scaled: F,
    /// `max |z_i|`.
    pub(crate) max_z: F,
    /// Bound on `|x_i - X_i|` and `|y_i - Y_i|`.
    pub(crate) xy: F,
}

impl<F: Scalar> ErrorBounds<F> {
    #[inline(always)]
    pub(crate) fn new(f: &Frame<F>, z: &[F; 3], shear: &Shear<F>) -> Self {
        let (mx, my) = (max3(&f.x), max3(&f.y));
        let (mpx, mpy, mpz) = (max3(&f.px), max3(&f.py), max3(&f.pz));
        let me = max3(&f.e);
        let dx = axis_error(mpx, mx, shear.sx, mpz);
        let dy = axis_error(mpy, my, shear.sy, mpz);
        let (mz, dz) = z_error(z);
        let de = edge_error(mx, my, dx, dy);
        // t_scaled = fl(sum e_i z_i): rounding adds gamma(3) sum |e_i z_i|;
        // replacing e, z by E, Z adds sum |e_i| dz + de (|z_i| + dz).
        // (At most 5 roundings on a path from de, dz.)
        let three = F::from_u32(3);
        let dt = bound_up(
            three * (F::gamma_n(3) * me * mz + me * dz + de * (mz + dz)),
            5,
        );
        Self {
            e: de,
            z: dz,
            t_scaled: dt,
            max_z: mz,
            xy: max2(dx, dy),
        }
    }
}

/// A bound on `|e_i - E_i|` for the edge functions of corners whose
/// computed sheared coordinates are at most `mx` and `my` in magnitude and
/// within `dx`, `dy` of the exact ones (upper bounds all).
///
/// Edge function e_0 = fl(fl(x1 y2) - fl(y1 x2)) (or the exact-sign
/// recomputation, which is closer): rounding adds gamma(2)(|x1 y2| +
/// |y1 x2|) <= 2 gamma(2) mx my, and x1 y2 - X1 Y2 = x1 (y2 - Y2) + (x1 -
/// X1) Y2 adds mx dy + dx (my + dy), twice. (At most 5 roundings on a path
/// from dx, dy.)
#[inline(always)]
pub(crate) fn edge_error<F: Scalar>(mx: F, my: F, dx: F, dy: F) -> F {
    bound_up(
        F::TWO * (F::gamma_n(2) * mx * my + mx * dy + my * dx + dx * dy),
        5,
    )
}

/// A bound on `|x_i - X_i|` (or `y`) of a corner in the ray's frame, from
/// the largest magnitudes of its translated coordinate `mp` (`p_x`), of
/// its sheared one `m` (`x`) and of the translated depth `mpz` (`p_z`),
/// `s` the shear factor `s_x` (or `s_y`); any upper bounds on those
/// magnitudes give a bound.
///
/// Shear: with p = P(1 + d1) (translation), s_x = S_x (1 + d3),
/// m = fl(s_x p_z) = S_x P_z (1 + theta_3) and x = fl(p_x + m) =
/// (p_x + m)(1 + d5):
///   x - X = P_x d1 + S_x P_z theta_3 + (p_x + m) d5,
/// so |x - X| <= u|P_x| + gamma(3)|S_x P_z| + u|x|/(1 - u)
///            <= gamma(1)(|p_x| + |x|) + gamma(4)|s_x p_z|
/// (|P_x| <= |p_x|/(1 - u), |S_x P_z| <= |m|/(1 - gamma(3))). The last
/// rounding is relative to the result, which is small exactly when
/// the shear cancels the translation. (3 roundings to evaluate.)
#[inline(always)]
pub(crate) fn axis_error<F: Scalar>(mp: F, m: F, s: F, mpz: F) -> F {
    bound_up(F::gamma_n(1) * (mp + m) + F::gamma_n(4) * s.abs() * mpz, 3)
}

/// `max |v_i|`, in the order every caller uses (so NaN propagates alike).
#[inline(always)]
pub(crate) fn max3<F: Scalar>(v: &[F; 3]) -> F {
    max2(v[0].abs(), max2(v[1].abs(), v[2].abs()))
}

/// `(max |z_i|, dz)` with `dz` the bound on `|z_i - Z_i|` of
/// [`ErrorBounds`].
///
/// Scale: z = fl(p_z fl(1/d_z)) = Z (1 + theta_3), so
/// |z - Z| <= gamma(3)|Z| <= gamma(4)|z|. (1 rounding.)
#[inline(always)]
pub(crate) fn z_error<F: Scalar>(z: &[F; 3]) -> (F, F) {
    let mz = max3(z);
    (mz, depth_error(mz))
}

/// [`z_error`]'s bound for depths of magnitude at most `mz`.
#[inline(always)]
pub(crate) fn depth_error<F: Scalar>(mz: F) -> F {
    bound_up(F::gamma_n(4) * mz, 1)
}

/// The `t` of a hit whose determinant's sign rounding leaves unknown: the
/// depth of the point of the triangle's longest edge in the sheared plane
/// nearest the ray (clamped to the edge), and a bound on its distance from
/// the same point of the exact edge. For a triangle whose corners are
/// exactly collinear, that point is where the ray passes the segment.
/// `None` when the edge is too short for the bound (the ray runs along it).
///
/// With `p` the edge's first corner and `D` the edge, `s = clamp(-(p . D) /
/// (D . D), 0, 1)` and `t = z_i + s (z_j - z_i)`; see [`EdgeLine::param`]
/// for `|s - s*|` (clamping does not increase it) and
/// [`EdgeLine::depth_error`] for `|t - t*|`.
#[cold]
#[inline(never)]
pub(crate) fn longest_edge_t<F: Scalar>(
    f: &Frame<F>,
    z: &[F; 3],
    b: &ErrorBounds<F>,
) -> Option<(F, F)> {
    let line = EdgeLine::new(f, z, b)?;
    let (sigma, es) = line.param(-line.px, -line.py, line.d, line.d)?;
    let s = min2(max2(sigma, F::ZERO), F::ONE);
    let t = line.zi + s * line.dzij;
    let bound = line.depth_error(line.zi.abs(), F::ONE, es);
    (t.is_finite() && bound.is_finite()).then_some((t, bound))
}

/// A bound on the distance of a `t` that [`longest_edge_t`] gave for a
/// triangle of zero area from where the ray passes the segment: its own
/// bound plus how far the third corner's depth is from the edge's depth line
/// (zero in exact arithmetic, as the corners are collinear; the computed
/// deviation carries the rounding of the coordinates, which this also
/// covers). The same sum bounds the distance from the exact plane's
/// crossing for a sliver the ray meets (the plane's depth is affine, so at
/// the ray it differs from the edge's by at most the third corner's
/// deviation), which is what makes it a natural bound; the test uses the
/// route only for zero-area triangles.
fn longest_edge_t_error<F: Scalar>(f: &Frame<F>, z: &[F; 3], b: &ErrorBounds<F>) -> Option<F> {
    let (_, bound) = longest_edge_t(f, z, b)?;
    let line = EdgeLine::new(f, z, b)?;
    let k = line.k;
    // The third corner relative to the first: each component within 2d
    // plus its rounding.
    let (ax, ay) = (f.x[k] - line.px, f.y[k] - line.py);
    let u = F::UNIT_ROUNDOFF;
    let (eax, eay) = (
        F::TWO * line.d + u * ax.abs(),
        F::TWO * line.d + u * ay.abs(),
    );
    let (sk, esk) = line.param(ax, ay, eax, eay)?;
    let on_line = line.zi + sk * line.dzij;
    // |Z_k - line*(sk*)| <= |z_k - on_line| + dz + depth_error(...).
    let deviation = bound_up(
        (z[k] - on_line).abs() + line.dz + line.depth_error(line.zi.abs(), sk.abs(), esk),
        3,
    );
    let total = bound_up(bound + deviation, 1);
    total.is_finite().then_some(total)
}

/// The longest edge `i -> j` of a triangle in the sheared plane, with what
/// [`longest_edge_t`] and its error bound need.
struct EdgeLine<F> {
    /// The third corner.
    k: usize,
    /// The first corner.
    px: F,
    py: F,
    /// The edge `D`, and bounds on its components' distances from the
    /// exact edge's: each coordinate is within `d` of the exact one, so
    /// each difference within `2d` plus its own rounding.
    dx: F,
    dy: F,
    edx: F,
    edy: F,
    /// `D . D`, and a bound on its distance from the exact edge's.
    den: F,
    eden: F,
    /// The first corner's depth, the edge's change in depth, and the
    /// bounds on the coordinates' and depths' errors.
    zi: F,
    dzij: F,
    d: F,
    dz: F,
}

impl<F: Scalar> EdgeLine<F> {
    fn new(f: &Frame<F>, z: &[F; 3], b: &ErrorBounds<F>) -> Option<Self> {
        let len2 = |i: usize, j: usize| {
            let (dx, dy) = (f.x[j] - f.x[i], f.y[j] - f.y[i]);
            dx * dx + dy * dy
        };
        let (mut i, mut j, mut k, mut best) = (0, 1, 2, len2(0, 1));
        for (a, c, r) in [(1, 2, 0), (2, 0, 1)] {
            let l = len2(a, c);
            if l > best {
                (i, j, k, best) = (a, c, r, l);
            }
        }
        let (px, py) = (f.x[i], f.y[i]);
        let (dx, dy) = (f.x[j] - px, f.y[j] - py);
        let den = dx * dx + dy * dy;
        let (d, u, two) = (b.xy, F::UNIT_ROUNDOFF, F::TWO);
        let (edx, edy) = (two * d + u * dx.abs(), two * d + u * dy.abs());
        // Rounding of the dot product, and the perturbation of each square.
        let eden = bound_up(
            F::gamma_n(2) * den + edx * (two * dx.abs() + edx) + edy * (two * dy.abs() + edy),
            12,
        );
        (den > eden && eden.is_finite()).then_some(Self {
            k,
            px,
            py,
            dx,
            dy,
            edx,
            edy,
            den,
            eden,
            zi: z[i],
            dzij: z[j] - z[i],
            d,
            dz: b.z,
        })
    }

    /// `sigma = (a . D) / (D . D)` for a vector `a` whose components are
    /// within `ea_x`, `ea_y` of the exact ones, and a bound on `|sigma -
    /// sigma*|` (`sigma*` from exact values). The numerator is within
    /// `en = gamma(2) (|a_x D_x| + |a_y D_y|) + sum_k (|a_k| eD_k + (|D_k| +
    /// eD_k) ea_k)` of the exact one and the denominator within `eden`;
    /// `sigma - sigma* = (num - num*) / den + sigma* (den* - den) / den`,
    /// with `|sigma*| <= (|num| + en) / (den - eden)`, and the division adds
    /// `gamma(1) |sigma|`.
    fn param(&self, ax: F, ay: F, eax: F, eay: F) -> Option<(F, F)> {
        let num = ax * self.dx + ay * self.dy;
        let sigma = num / self.den;
        let (adx, ady) = (self.dx.abs(), self.dy.abs());
        let en = bound_up(
            F::gamma_n(2) * (ax.abs() * adx + ay.abs() * ady)
                + ax.abs() * self.edx
                + ay.abs() * self.edy
                + (adx + self.edx) * eax
                + (ady + self.edy) * eay,
            12,
        );
        let exact = bound_up((num.abs() + en) / (self.den - self.eden), 4);
        let es = bound_up(
            F::gamma_n(1) * sigma.abs() + (en + exact * self.eden) / self.den,
            4,
        );
        (sigma.is_finite() && es.is_finite()).then_some((sigma, es))
    }

    /// A bound on `|z_i + s (z_j - z_i) - (Z_i + s* (Z_j - Z_i))|` for
    /// `|s| <= s_abs` and `|s - s*| <= es`: the rounding `gamma(3) (|z_i| +
    /// max(1, s_abs) |z_j - z_i|)`, the depths' errors `(1 + 2 max(1,
    /// s_abs)) dz`, and `es (|z_j - z_i| (1 + u) + 2 dz)`, evaluated with at
    /// most eight roundings.
    fn depth_error(&self, abs_zi: F, s_abs: F, es: F) -> F {
        let (u, two) = (F::UNIT_ROUNDOFF, F::TWO);
        let adz = self.dzij.abs();
        let s = max2(F::ONE, s_abs);
        bound_up(
            F::gamma_n(3) * (abs_zi + s * adz)
                + (F::ONE + two * s) * self.dz
                + es * (adz * (F::ONE + u) + two * self.dz),
            8,
        )
    }
}

/// The conditioning of a hit: lower and upper bounds of `|sum E_i|` (the
/// exact determinant) from the computed one. Exists only when the lower
/// bound is positive, i.e. when the exact determinant is known to have the
/// computed one's sign.
#[derive(Clone, Copy, Debug)]
pub(crate) struct HitCondition<F> {
    /// `<= |sum E_i|`, and `> 0`.
    lower: F,
    /// `>= |sum E_i|`.
    upper: F,
}

impl<F: Scalar> HitCondition<F> {
    /// `det = fl(fl(e0 + e1) + e2)` with all `e_i` of one sign, so
    /// `|sum e_i| / (1 + gamma(2)) <= |det| <= |sum e_i| (1 + gamma(2))`, and
    /// `|sum E_i - sum e_i| <= 3 de`. Outward rounding throughout; `4 de`
    /// (exact) stands in for `3 de` to absorb the rounding of the product.
    #[inline(always)]
    pub(crate) fn new(b: &ErrorBounds<F>, det: F) -> Option<Self> {
        use crate::num::round::outward::{add_up, mul_down, mul_up, sub_down};
        let g = F::gamma_n(4);
        let sum_lo = mul_down(det.abs(), F::ONE - g);
        let sum_hi = mul_up(det.abs(), F::ONE + g);
        let four_de = F::from_u32(4) * b.e;
        let lower = sub_down(sum_lo, four_de);
        (lower > F::ZERO).then(|| Self {
            lower,
            upper: add_up(sum_hi, four_de),
        })
    }

    /// A bound on `|t - t_exact|` for the reported `t`.
    ///
    /// Write `t(e, z) = sum e_i z_i / sum e_i`; the exact crossing is
    /// `t(E, Z)`, and the reported `t` comes from `t(e, z)` by rounding.
    /// - Rounding: `t = fl(fl(sum e_i z_i) fl(1/det))` is `t(e, z)` times
    ///   `(1 + eta)`, `|eta| <= gamma(4)`, plus `gamma(3) sum|e_i z_i| / |sum e_i|
    ///   <= gamma(3) max|z|` (the `e_i` share a sign); `|t(e, z)| <= max|z|`
    ///   (a convex combination), so `|t - t(e, z)| <= gamma(8) max|z|`.
    /// - Edge functions: for any `c`, `t(e, z) - c = sum e_i (z_i - c) /
    ///   sum e_i`. With `c = t(E, z)`, `sum E_i (z_i - c) = 0`, so
    ///   `t(e, z) - t(E, z) = sum (e_i - E_i)(z_i - c) / sum e_i`, and with
    ///   `S = sum |z_i - t(e, z)|`: `|t(e, z) - t(E, z)| <= de S / (|sum e| - 3 de)`.
    ///   (The sensitivity is to the spread of the `z_i`, not their size.)
    /// - Coordinates: `t(E, z) - t(E, Z) = sum E_i (z_i - Z_i) / sum E_i`,
    ///   at most `dz sum|E_i| / |sum E_i| <= dz (|sum e| + 3 de) / (|sum e| - 3 de)`.
    #[inline(always)]
    pub(crate) fn t_error(&self, b: &ErrorBounds<F>, z: &[F; 3], t: F) -> F {
        use crate::num::round::outward::{add_up, div_up, mul_up};
        let rounding = mul_up(F::gamma_n(8), b.max_z);
        let spread = |zi: F| (zi - t).abs().next_up();
        let s = add_up(add_up(spread(z[0]), spread(z[1])), spread(z[2]));
        let s = add_up(s, mul_up(F::from_u32(3), rounding));
        let edges = div_up(mul_up(b.e, s), self.lower);
        let coords = div_up(mul_up(b.z, self.upper), self.lower);
        add_up(add_up(rounding, edges), coords)
    }

    /// A bound on `|w - w_exact|` for a reported barycentric `w = min(e_i /
    /// det, 1)` (rounded; `w_exact = E_i / sum E_i`).
    ///
    /// Rounding: `w = (e_i / sum e_i)(1 + eta)`, `|eta| <= gamma(4)`, and
    /// clamping to 1 only moves it towards `e_i / sum e_i <= 1`; so the
    /// rounding error is at most `gamma(5) w`. Edge functions: `e_i/sum e -
    /// E_i/sum E = ((e_i - E_i) - w' sum (e_j - E_j)) / sum E` with
    /// `w' = e_i / sum e`, at most `de (1 + 3 w') / (|sum e| - 3 de)`.
    #[inline(always)]
    fn barycentric_error(&self, b: &ErrorBounds<F>, w: F) -> F {
        use crate::num::round::outward::{add_up, div_up, mul_up};
        let rounding = mul_up(F::gamma_n(5), w);
        let w_plain = add_up(w, rounding);
        let factor = add_up(F::ONE, mul_up(F::from_u32(3), w_plain));
        add_up(rounding, div_up(mul_up(b.e, factor), self.lower))
    }
}

/// The hit point of [`Triangle`]'s `surface_point` and its bound, derived
/// in its documentation.
#[must_use]
pub(crate) fn triangle_hit_point<V: Vector>(tri: &Triangle<V>, u: S<V>, v: S<V>) -> (V, V) {
    let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
    let (ue, ve) = (e1 * u, e2 * v);
    let p = tri.a + (ue + ve);
    let g5 = S::<V>::gamma_n(5);
    let err = (tri.a.abs() + ue.abs() + ve.abs()) * g5;
    let e = |j: usize| bound_up(err[j], 4);
    (p, V::new(e(0), e(1), e(2)))
}

/// Bounds on the errors of a watertight hit: `|t - t_exact|`,
/// `|u - u_exact|`, `|v - v_exact|`, where the exact values are those of the
/// crossing of the ray's line with the triangle's plane, computed exactly
/// from the same inputs. See [`Triangle`'s `hit_error`](crate::Triangle#method.hit_error).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct TriangleHitError<F = f32> {
    /// Bound on the error of `t`.
    pub t: F,
    /// Bound on the error of `u`.
    pub u: F,
    /// Bound on the error of `v`.
    pub v: F,
}

/// Bounds on the errors of a watertight hit (of `ray_triangle` or
/// `ray_triangle_one_hit`, and of the interval forms before a `t` is
/// brought into the interval): [`Triangle`]'s `hit_error`, whose
/// documentation states them; derived below.
#[must_use]
pub(crate) fn ray_triangle_error_bounds<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    hit: &TriangleHit<S<V>>,
) -> TriangleHitError<S<V>> {
    let inf = S::<V>::INFINITY;
    let unbounded = TriangleHitError {
        t: inf,
        u: inf,
        v: inf,
    };
    if !(ray.is_valid() && hit.t.is_finite() && hit.u.is_finite() && hit.v.is_finite()) {
        return unbounded;
    }
    let shear = Shear::new(&ray.dir);
    let f = Frame::new(ray.origin, tri, &shear);
    let z = f.scaled_z(&shear);
    let b = ErrorBounds::new(&f, &z, &shear);
    let zero = S::<V>::ZERO;
    // The edge functions the hit was computed from: the frame's, or, for a
    // one-hit hit near an edge, the frame's with those whose computed sign
    // is not the exact determinant's set to zero. Where the bound below is
    // finite, the computed determinant has the exact one's sign, so this
    // zeroes the same ones. (A computed edge function of the other sign is
    // within its error bound of zero, so zeroing the wrong ones, where the
    // computed determinant's sign is wrong, leaves a sum below the
    // determinant's error bound: the bounds are then infinite.)
    let positive = f.e[0] + f.e[1] + f.e[2] > zero;
    let e = f.e.map(|e| {
        if (e > zero) == positive || e == zero {
            e
        } else {
            zero
        }
    });
    let det = e[0] + e[1] + e[2];
    let same_sign = e.iter().all(|&e| e >= zero) || e.iter().all(|&e| e <= zero);
    // A bound whose arithmetic overflowed (an infinite term times a zero
    // one, or two infinite ones subtracted: a `t` at the top of an
    // interval, corners beyond the documented range) is NaN; it bounds
    // nothing, so it is infinite.
    // (Bounds are at least zero: NaN fails the comparison.)
    let known = |x: S<V>| if x >= zero { x } else { inf };
    match HitCondition::new(&b, det) {
        Some(c) if same_sign => TriangleHitError {
            t: known(c.t_error(&b, &z, hit.t)),
            u: known(c.barycentric_error(&b, hit.u)),
            v: known(c.barycentric_error(&b, hit.v)),
        },
        // The test took `t` from the longest edge.
        None if same_sign && det != zero && tri.is_degenerate() => TriangleHitError {
            t: longest_edge_t_error(&f, &z, &b).unwrap_or(inf),
            ..unbounded
        },
        _ => unbounded,
    }
}
