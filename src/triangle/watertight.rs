//! The watertight test's fast paths: [`ray_triangle`] (every main axis at
//! once, on lanes), [`Triangle`'s `hit` on a prepared ray](crate::Triangle#method.hit) (the three corners in lanes),
//! and [`Triangle`'s `hit` with the one-hit rule](crate::Triangle#method.hit); every rare case goes to the definition, out
//! of line, and a test holds each to it bit for bit.

use super::bounds::ErrorBounds;
use super::conditioning::{
    det_sign_known_at_corners, det_sign_known_lanes, det_sign_known_roughly,
};
use super::definition::{EdgeRule, watertight_definition};
use super::frame::{Frame, edge_function};
use super::lanes::{DefinitionRay, Packed, frame_lanes, lanes_hit, pack, translated, unpack};
use super::{Side, Triangle, TriangleHit};
use crate::num::round::min2;
use crate::num::{L, Lanes, S, Scalar, Vector, lanes};
use crate::ray::{PreparedRay, Ray, Shear, largest_axis, t_max_ok};

/// The watertight test shared by [`ray_triangle`] and
/// [`Triangle`'s `hit` with the one-hit rule](crate::Triangle#method.hit).
#[inline(always)]
fn watertight<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    if !(ray.is_valid() && t_max_ok(t_max)) {
        return None;
    }
    match rule {
        EdgeRule::Closed => watertight_every_axis(ray, tri, t_max),
        EdgeRule::OneHit => watertight_definition(
            (ray.origin, ray.dir),
            &Shear::new(&ray.dir),
            tri,
            t_max,
            rule,
        ),
    }
}

/// The closed watertight test for a valid ray (not prepared) and a
/// `t_max >= 0`, computed for all three choices of the ray's main axis at
/// once, lane `k` being the test in the frame with `kz = k`, and decided
/// on the lane of the ray's actual main axis.
///
/// Lane `k` runs exactly the operations of [`watertight_definition`] with
/// `kz = k` (the shear factors `-d[k+1] / d[k]`, `-d[k+2] / d[k]` and
/// `1 / d[k]`, each one division; the corners translated in their natural
/// axis order, so that `p[k+1]`, `p[k+2]`, `p[k]` are the permuted `px`,
/// `py`, `pz`), so on the chosen lane its values are the definition's,
/// bit for bit. Nothing waits for the choice of the axis: on one ray
/// against one triangle, that shortens the chain of dependent operations
/// (the ray's shear is not known in advance) more than the two other
/// lanes cost. The rare cases go to [`watertight_definition`], as in
/// [`watertight_lanes`].
#[inline(always)]
fn watertight_every_axis<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    every_axis_at(
        ray,
        &EveryAxis::new(ray),
        [&tri.a, &tri.b, &tri.c],
        t_max,
        || *tri,
    )
}

/// The ray's part of [`watertight_every_axis`]: its origin and direction
/// in lanes, its main axis, and the three candidate shears, lane `k`
/// holding `-d[k+1] / d[k]`, `-d[k+2] / d[k]` and `1 / d[k]`.
struct EveryAxis<W> {
    o: W,
    d: W,
    kz: usize,
    sx: W,
    sy: W,
    sz: W,
}

impl<W: Lanes> EveryAxis<W>
where
    W::F: Scalar,
{
    #[inline(always)]
    fn new<V: Vector<Scalar = W::F>>(ray: &Ray<V>) -> Self {
        let one = W::splat(W::F::ONE);
        let (o, d) = (
            W::new(ray.origin.x(), ray.origin.y(), ray.origin.z()),
            W::new(ray.dir.x(), ray.dir.y(), ray.dir.z()),
        );
        Self {
            o,
            d,
            kz: largest_axis(d.abs().to_array()),
            sx: d.rot1().neg().div(d),
            sy: d.rot2().neg().div(d),
            sz: one.div(d),
        }
    }
}

/// [`watertight_every_axis`] for the triangle with corners `a, b, c`, the
/// ray's part computed; `tri` builds the triangle for the rare paths only,
/// so that a caller whose triangle is made on the spot (a patch's
/// collapsed half) makes none on the common path. (Given the triangle by
/// reference instead, the plain patch test built it on every call: 15%
/// slower on camera rays.)
#[inline(always)]
fn every_axis_at<V: Vector>(
    ray: &Ray<V>,
    shear: &EveryAxis<L<V>>,
    [a, b, c]: [&V; 3],
    t_max: S<V>,
    tri: impl Fn() -> Triangle<V>,
) -> Option<TriangleHit<S<V>>> {
    let splat = L::<V>::splat;
    let (zero, one) = (splat(S::<V>::ZERO), splat(S::<V>::ONE));
    let &EveryAxis {
        o,
        d,
        kz,
        sx,
        sy,
        sz,
    } = shear;
    let bit = 1 << kz;
    // Translate; then lane k of `x` is p[k+1] + sx[k] p[k], and so on.
    let p = [lanes(*a).sub(o), lanes(*b).sub(o), lanes(*c).sub(o)];
    let x = p.map(|p| p.rot1().add(sx.mul(p)));
    let y = p.map(|p| p.rot2().add(sy.mul(p)));
    let z = p.map(|p| p.mul(sz));
    let edge = |j: usize, k: usize| x[j].mul(y[k]).sub(y[j].mul(x[k]));
    let (e0, e1, e2) = (edge(1, 2), edge(2, 0), edge(0, 1));
    // Both signs among the edge functions: outside. (For values that are
    // not NaN, "some e_i < 0" is "min e_i < 0"; a NaN edge function, from
    // overflow, makes `det` NaN and fails the range test below, whatever
    // this says, as in the definition.)
    let neg = e0.min(e1).min(e2).lt(zero);
    let pos = zero.lt(e0.max(e1).max(e2));
    if neg & pos & bit != 0 {
        return None;
    }
    if (e0.eq(zero) | e1.eq(zero) | e2.eq(zero)) & bit != 0 {
        return definition_answer(ray, &tri(), t_max);
    }
    let det = e0.add(e1).add(e2);
    let t_scaled = e0.mul(z[0]).add(e1.mul(z[1])).add(e2.mul(z[2]));
    let limit = splat(t_max).mul(det);
    let ahead_range = zero.lt(det) & zero.lt(t_scaled) & t_scaled.le(limit);
    let behind_range = det.lt(zero) & t_scaled.lt(zero) & limit.le(t_scaled);
    // A plain miss stands where no corner is in front of the origin or the
    // determinant is well conditioned (see `watertight_lanes`). (Lane k is
    // the frame with kz = k, so the maxima over the corners are lane-wise
    // here.)
    let front = [0, 1, 2].map(|c| zero.lt(z[c]));
    let ahead = front[0] & front[1] & front[2] & bit != 0;
    let conditioned = || {
        let m = (0..3)
            .map(|c| x[c].abs().max(y[c].abs()))
            .fold(zero, |a, b| a.max(b));
        let w = d.abs().mul(z[0].abs().max(z[1].abs()).max(z[2].abs()));
        det_sign_known_roughly(det, m.max(w)) & bit != 0
            || det_sign_known_lanes(det, m, w) & bit != 0
    };
    // (Most misses are decided before the division.)
    let plain = if (ahead_range | behind_range) & bit != 0 {
        let inv_det = one.div(det);
        let t = t_scaled.mul(inv_det);
        // (`t > 0` makes `is_finite` the same as `t <= MAX`.)
        let big = splat(S::<V>::MAX);
        let t_ok = zero.lt(t) & t.le(splat(t_max)) & t.le(big);
        (t_ok & bit != 0).then_some((t, inv_det))
    } else {
        None
    };
    let Some((t, inv_det)) = plain else {
        return if (front[0] | front[1] | front[2]) & bit == 0 || conditioned() {
            None
        } else {
            definition_answer(ray, &tri(), t_max)
        };
    };
    // The first sufficient test for t > 0 (see `watertight_definition`), and
    // a well-conditioned determinant (see `watertight_lanes`).
    if !(ahead && conditioned()) {
        return definition_answer(ray, &tri(), t_max);
    }
    // u and v, finite here (see `watertight_lanes`).
    let u = e1.mul(inv_det).min(one);
    let v = e2.mul(inv_det).min(one);
    let pick = |w: L<V>| -> S<V> { Lanes::to_array(w)[kz] };
    let det = pick(det);
    let side = if (det > S::<V>::ZERO) != (pick(d) > S::<V>::ZERO) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleHit {
        t: pick(t),
        u: pick(u),
        v: pick(v),
        side,
    })
}

/// The closed watertight test for a prepared ray and a `t_max >= 0`, with
/// the three corners in the lanes of one register: the same operations as
/// [`watertight_definition`], lane by lane, so the same bits. An edge
/// function that rounds to zero has its sign recomputed exactly, as the
/// definition's frame does, out of line ([`exact_zero_edges`]), and the
/// test goes on. The rare cases go to [`watertight_definition`] itself: a
/// crossing for which the two cheapest sufficient tests for `t > 0` (every
/// corner in front of the origin, or the scaled distance beyond its error
/// bound: [`beyond_its_bound`]) fail or whose determinant's sign is not
/// surely known, and a plain miss that only the definition can settle.
///
/// An invalid ray needs no test of its own: its origin lanes are NaN
/// (`PreparedRay::new`), so every sheared coordinate, edge function and
/// depth is NaN, and every comparison below is false: no two edge
/// functions of opposite signs, none zero, the determinant out of range,
/// no corner in front. That is a plain miss with no corner in front, so
/// `None`, and no rare path is taken.
#[inline(always)]
pub(crate) fn watertight_lanes<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    let frame = frame_lanes(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, tri);
    if straddles(frame.3) {
        // Outside, whatever the exact sign of an edge function of zero.
        return None;
    }
    finish_lanes(ray, frame, t_max, || *tri)
}

/// Whether the edge functions `e` have both signs: the ray misses,
/// whatever the exact sign of one that rounds to zero.
#[inline(always)]
fn straddles<W: Lanes>(e: W) -> bool
where
    W::F: Scalar,
{
    let zero = W::splat(W::F::ZERO);
    e.lt(zero) != 0 && zero.lt(e) != 0
}

/// [`watertight_lanes`] after its first test: the frame
/// ([`frame_lanes`]'s values) of a triangle whose edge functions do not
/// [`straddle`](straddles) zero. `tri` builds the triangle, for the rare
/// paths only.
#[inline(always)]
fn finish_lanes<V: Vector>(
    ray: &PreparedRay<V>,
    (x, y, pz, e): (L<V>, L<V>, L<V>, L<V>),
    t_max: S<V>,
    tri: impl Fn() -> Triangle<V>,
) -> Option<TriangleHit<S<V>>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    let lanes_zero = L::<V>::splat(zero);
    // An edge function that rounds to zero (a ray through an edge or a
    // corner of the rounded triangle): its sign recomputed exactly, as
    // `Frame::new` recomputes it, after which the values are the
    // definition's, and the closed rule is a miss where the signs now
    // straddle zero and goes on below otherwise. Where both of its
    // products have a zero factor (the ray through a corner that lands
    // exactly on the origin of the sheared plane, as a ray aimed at a
    // vertex mostly does), it is exactly zero, and the recomputation
    // would give the same value (`Scalar::diff_of_products_exact_sign`):
    // no call.
    let zeros = e.eq(lanes_zero);
    let e = if zeros != 0 && zeros & !exact_zeros(x, y) != 0 {
        let e = exact_zero_edges::<V>(x, y, e);
        if straddles(e) {
            return None;
        }
        e
    } else {
        e
    };
    let det = e.sum3();
    let sz = ray.shear_lanes[2];
    let z = pz.mul(sz);
    let t_scaled = e.mul(z).sum3();
    let in_range = if det > zero {
        t_scaled > zero && t_scaled <= t_max * det
    } else if det < zero {
        t_scaled < zero && t_scaled >= t_max * det
    } else {
        false
    };
    // The definition's answer to a plain miss is a miss too, except for a
    // zero-area triangle whose determinant's sign is unknown, when it takes
    // `t` from the segment: so a miss stands where no corner is in front of
    // the origin (the depths' signs are exact: see `watertight_definition`),
    // or where the determinant is well conditioned
    // (`det_sign_known_at_corners`); otherwise the definition decides. (Decided
    // before the division, which most misses need not pay for.)
    let ahead = lanes_zero.lt(z);
    if !in_range {
        return if ahead == 0 || det_sign_known_at_corners(x, y, pz, det) {
            None
        } else {
            definition_answer(ray, &tri(), t_max)
        };
    }
    // The first sufficient test for t > 0 (every corner in front), or,
    // with some corner in front and some behind, the second (the scaled
    // distance beyond its error bound); and a well-conditioned
    // determinant. Else the definition decides. (Before the division, so
    // that no branch waits for it; the definition's tests are pure
    // functions of the same values, so their order changes no answer.)
    if !(det_sign_known_at_corners(x, y, pz, det)
        && (ahead == 0b111
            || (ahead != 0 && beyond_its_bound(ray, &tri(), [x, y, pz, z, e], t_scaled))))
    {
        return definition_answer(ray, &tri(), t_max);
    }
    let inv_det = one / det;
    let t = t_scaled * inv_det;
    // A plain miss with a well-conditioned determinant, as above. (`t > 0`
    // makes `is_finite` the same as `t <= MAX`, so the two upper limits are
    // one comparison.)
    if !(t > zero && t <= min2(S::<V>::MAX, t_max)) {
        return None;
    }
    // (`u` and `v` finite here: `1 / det` is finite, else `t` would be
    // infinite.)
    Some(lanes_hit(t, e, det, inv_det, sz.x()))
}

/// The definition's second test for `t > 0` (pbrt-v4's): whether the
/// scaled distance `t_scaled` exceeds its rounding error bound
/// (`ErrorBounds`' `t_scaled`), for a crossing with some corner in front
/// of the origin and some behind. The lanes hold the definition's frame
/// bit for bit (`x`, `y`, `p_z`, the scaled depths `z` and the edge
/// functions `e`, zeros recomputed; `p_x` and `p_y` are recomputed here
/// as `frame_lanes` computes them), and `ErrorBounds::new` runs on it, so
/// the bound is the definition's, and where this holds (and the
/// determinant's sign is known, so that `HitCondition::new` is `Some`)
/// the definition's answer is the plain one. Out of line: the rays that
/// need it start within about a triangle's size of the surface they hit
/// (a ray from next to a mesh, aimed at its vertices).
#[inline(never)]
fn beyond_its_bound<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    [x, y, pz, z, e]: [L<V>; 5],
    t_scaled: S<V>,
) -> bool {
    let [px, py, _] = translated(&ray.origin_lanes, &ray.axes, [&tri.a, &tri.b, &tri.c]);
    let frame = Frame {
        x: x.to_array(),
        y: y.to_array(),
        px: px.to_array(),
        py: py.to_array(),
        pz: pz.to_array(),
        e: e.to_array(),
    };
    t_scaled.abs() > ErrorBounds::new(&frame, &z.to_array(), &ray.shear()).t_scaled
}

/// Bit `i` set where both products of edge function `i` (`x[i+1]
/// y[i+2]` and `y[i+1] x[i+2]`, of sheared coordinates `x`, `y`) have a
/// zero factor, so that the edge function is exactly zero (checked on
/// the factors: a product of nonzero factors can underflow to zero).
#[inline(always)]
fn exact_zeros<W: Lanes>(x: W, y: W) -> u32
where
    W::F: Scalar,
{
    let zero = W::splat(W::F::ZERO);
    let (x1, y1, x2, y2) = (
        x.rot1().eq(zero),
        y.rot1().eq(zero),
        x.rot2().eq(zero),
        y.rot2().eq(zero),
    );
    (x1 | y2) & (y1 | x2)
}

/// The edge functions `e` (lane `i` that of the edge from corner `i + 1`
/// to corner `i + 2`, of sheared coordinates `x`, `y`) with each one that
/// rounded to zero recomputed with its sign exact, by `edge_function`, as
/// [`Frame::new`](super::frame::Frame) computes the definition's. Out of
/// line: rays through an edge or a corner are rare, except where they are
/// aimed there.
#[inline(never)]
fn exact_zero_edges<V: Vector>(x: L<V>, y: L<V>, e: L<V>) -> L<V> {
    let (x, y, mut e) = (x.to_array(), y.to_array(), e.to_array());
    for (i, e) in e.iter_mut().enumerate() {
        if *e == S::<V>::ZERO {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            *e = edge_function((x[j], y[j]), (x[k], y[k]));
        }
    }
    L::<V>::new(e[0], e[1], e[2])
}

/// [`definition_out_of_line`]'s answer, unpacked. (Called with what the
/// fast path was given, where a closure would build its environment on the
/// common path.)
#[inline(always)]
fn definition_answer<V: Vector, R: DefinitionRay<V>>(
    ray: &R,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    unpack(definition_out_of_line(ray, tri, t_max))
}

/// [`watertight_definition`] with the closed rule, out of the hot path: how
/// the fast paths answer their rare cases. It takes what the fast path was
/// given, so that the common path keeps no value alive for it.
#[cold]
#[inline(never)]
fn definition_out_of_line<V: Vector, R: DefinitionRay<V>>(
    ray: &R,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Packed<S<V>> {
    let (origin, shear) = ray.origin_and_shear();
    pack(watertight_definition(
        (origin, ray.direction()),
        &shear,
        tri,
        t_max,
        EdgeRule::Closed,
    ))
}

/// The watertight ray/triangle test (closed: edges and corners hit).
///
/// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT
/// 2(1), 2013, as in pbrt-v4: translate the corners to the ray origin,
/// permute the axes so that the ray runs mostly along `z`, shear so that it
/// runs exactly along `z`, and decide inside/outside with three 2-D edge
/// functions; an edge function that rounds to exactly zero is recomputed
/// with its sign exact (in `f64` for `f32`).
///
/// Conventions: two-sided (the [`Side`] is reported); `t` in units of
/// `ray.dir` with `0 < t <= t_max`; barycentrics as in [`TriangleHit`].
/// The triangle is closed in the ray's frame: an edge function of exactly
/// zero counts as inside. (A ray that exact arithmetic puts exactly on the
/// edge of a lone triangle can still miss it: translating and shearing the
/// corners rounds them by a few ulps, and the test is exact for the rounded
/// corners. Where two triangles share the edge, one of them is hit.)
///
/// Guarantees:
/// - **Watertight.** The signs of the edge functions are exact for the
///   rounded corners in the ray's frame, and two triangles that share an
///   edge (bit-identical corners) compute that edge's function as exact
///   negatives. So a ray that crosses a shared edge or corner of a mesh
///   (locally a proper surface, seen from one side) hits at least one of the
///   triangles around it: no ray leaks through.
/// - **`t > 0` decided conservatively**: the reported `t` is positive, and
///   the hit is in front of the origin in exact arithmetic by one of four
///   tests: all three corners are in front (so is any crossing), or the
///   scaled numerator exceeds its rounding error bound (pbrt-v4's test), or
///   `t` exceeds its error bound, or, for a triangle of zero area (corners
///   exactly collinear) that rounding leaves a sliver, the depth of the
///   point of its longest edge nearest the ray (where the ray passes the
///   segment, and then the reported `t`) exceeds its own error bound. Where
///   every corner is behind the origin there is no hit. A ray spawned from the triangle with
///   [`SurfacePoint::spawn`](crate::SurfacePoint::spawn) does not hit it again.
/// - `t`, `u` and `v` are within [`Triangle`'s `hit_error`](crate::Triangle#method.hit_error) of the
///   exact crossing (where that bound is finite); `t` always lies between
///   the nearest and farthest corner's depth along the ray, up to rounding.
/// - Triangles of zero area in the ray's sheared frame (after rounding),
///   non-finite triangles, invalid rays and NaN or negative `t_max` give
///   `None`; never panics, never NaN. A triangle of exactly zero area can
///   still be hit where rounding leaves it a sliver (see [`Triangle`]).
/// - Precondition for all of the above: coordinates relative to the ray
///   origin small enough that the edge-function products do not overflow
///   (`|coordinate| < 2^63` in `f32`, `2^511` in `f64`).
///
/// ```
/// use rayhit::{Ray, Side, Triangle, glam::Vec3, ray_triangle};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.u, hit.v, hit.side), (2.0, 0.25, 0.125, Side::Front));
/// // On the edge from b to c: closed, so a hit.
/// let edge = Ray::new(Vec3::new(1.0, 1.0, 4.0), Vec3::new(0.0, 0.0, -1.0));
/// assert!(ray_triangle(&edge, &tri, f32::INFINITY).is_some());
/// ```
#[inline]
#[must_use]
pub fn ray_triangle<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    watertight(ray, tri, t_max, EdgeRule::Closed)
}

/// [`ray_triangle`] on a [`PreparedRay`]: the same answer, bit for bit,
/// without recomputing the ray's shear (three divisions) per triangle.
// (Always inlined: it is the body of a traversal's inner loop, and its rare
// paths are out of line. Left to the inliner, a program that calls it from
// several places got one shared copy, which paid a call and returned its
// answer through memory, measurably slower in `benches/peers`.)
#[inline(always)]
#[must_use]
pub(crate) fn ray_triangle_prepared<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    if !t_max_ok(t_max) {
        return None;
    }
    watertight_lanes(ray, tri, t_max)
}

/// [`ray_triangle`] with the one-hit edge rule (see [`Triangle`]'s `hit`): the definition, with `EdgeRule::OneHit`.
#[inline]
#[must_use]
pub(crate) fn ray_triangle_one_hit<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    watertight(ray, tri, t_max, EdgeRule::OneHit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::IntersectLanes;
    use crate::testing::Draws;
    use glam::{DVec3, Vec3};

    /// The watertight test on lanes (what `ray_triangle` and
    /// `ray_triangle_prepared` run) and the triangle batch give, bit for
    /// bit, the answer of the one-component-at-a-time definition,
    /// `watertight_definition`, in both precisions and for any `t_max`: on
    /// random triangles, and on zero-area ones (T-junction fillers `a, m, b`
    /// with `m` the midpoint, and `a, b, a + 2 (b - a)`, all exact on the
    /// grid) with rays aimed at points of their segment, where the
    /// definition can hit what the plain test rejects (it takes `t` from the
    /// segment when the determinant's sign is unknown).
    #[test]
    fn fast_paths_are_the_definition() {
        fn check<V: Vector>(draws: &mut Draws, zero_area: bool) -> usize {
            let mut v = || {
                V::new(
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                )
            };
            let (a, b, c, origin) = (v(), v(), v(), v());
            let (filler, s) = (
                (draws.0 >> 20).is_multiple_of(2),
                ((draws.0 >> 24) % 9) as f64 / 8.0,
            );
            let (tri, on_segment) = if zero_area {
                let (half, two) = (S::<V>::HALF, S::<V>::TWO);
                let tri = if filler {
                    Triangle::new(a, (a + b) * half, b)
                } else {
                    Triangle::new(a, b, a + (b - a) * two)
                };
                (tri, Some(a + (b - a) * S::<V>::from_f64(s)))
            } else {
                (Triangle::new(a, b, c), None)
            };
            // Half of the rays aimed at an edge's midpoint, the centroid
            // (rounded) or a corner, for hits and edge cases.
            let half = S::<V>::HALF;
            let pick = draws.coordinate(40);
            let mut v = || {
                V::new(
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                )
            };
            let dir = match (on_segment, (pick * 6.0) as i64 % 6) {
                (Some(p), _) => p - origin,
                (None, 0) => (tri.a + tri.b) * half - origin,
                (None, 1) => (tri.a + tri.b + tri.c) * (S::<V>::ONE / S::<V>::from_u32(3)) - origin,
                (None, 2) => tri.c - origin,
                _ => v(),
            };
            let ray = Ray::new(origin, dir);
            let t_max = S::<V>::from_f64(draws.coordinate(40).abs() * 4.0);
            let mut hits = 0;
            for t_max in [t_max, S::<V>::INFINITY] {
                let expected = (ray.is_valid() && t_max_ok(t_max)).then(|| {
                    let shear = Shear::new(&ray.dir);
                    watertight_definition(
                        (ray.origin, ray.dir),
                        &shear,
                        &tri,
                        t_max,
                        EdgeRule::Closed,
                    )
                });
                let bits = crate::testing::hit_bits::<S<V>>;
                let expected = bits(expected.flatten());
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(ray_triangle(&ray, &tri, t_max)),
                    expected,
                    "{ray:?} {tri:?}"
                );
                let prepared = PreparedRay::new(&ray);
                assert_eq!(
                    bits(ray_triangle_prepared(&prepared, &tri, t_max)),
                    expected,
                    "{ray:?} {tri:?}"
                );
                if let Some(batch) = crate::batch::TriangleBatch::<V, 8>::from_slice(&[tri]) {
                    let h = batch.hit(&prepared, t_max);
                    let lane = (h.mask & 1 != 0).then(|| {
                        let side = if h.front & 1 != 0 {
                            Side::Front
                        } else {
                            Side::Back
                        };
                        (h.t[0].to_f64().to_bits(), side)
                    });
                    assert_eq!(lane, expected.map(|e| (e.0, e.3)), "{ray:?} {tri:?}");
                }
            }
            hits
        }
        let mut draws = Draws(0x1234_5678_9abc_def1);
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut draws, false) + check::<DVec3>(&mut draws, false);
        }
        // Enough hits that the comparison means something (about a third).
        assert!(hits > 100_000, "{hits}");
        let mut hits = 0;
        for _ in 0..50_000 {
            hits += check::<Vec3>(&mut draws, true) + check::<DVec3>(&mut draws, true);
        }
        // Zero-area triangles are hit only where rounding leaves them a
        // sliver; enough of them that the comparison means something.
        assert!(hits > 1_000, "{hits}");
    }
}
