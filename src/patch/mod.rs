//! Bilinear patches: the surface through four corners, not necessarily
//! coplanar, `P(u, v) = (1 - u)(1 - v) p00 + u (1 - v) p10 + (1 - u) v
//! p01 + u v p11`, decided on its boundary by the watertight triangle
//! test's edge functions so that it leaves no crack against the patches
//! and triangles it shares edges with.
//!
//! The method. In the ray's sheared frame (the triangle test's: origin at
//! zero, the ray along `+z`) the patch projects to the bilinear patch of
//! the projected corners `q_ij`, and the ray meets the patch where that
//! projection covers the origin. For each `u` the points `A(u)` (on the
//! edge `v = 0`) and `B(u)` (on `v = 1`) span a segment; the origin lies
//! on its line where the 2-D cross product `c(u) = A(u) x B(u)` vanishes,
//! a quadratic with the Bernstein coefficients `q00 x q01`, `(q00 x q11 +
//! q10 x q01) / 2` and `q10 x q11` (the first and last are the edge
//! functions of the edges `u = 0` and `u = 1`), discriminant `b1^2 - b0
//! b2`. `v` places the origin on the segment, and the depth is the
//! patch's bilinear depth at `(u, v)`. (Reshetov, "Cool Patches: A
//! Geometric Approach to Ray/Bilinear Patch Intersections", Ray Tracing
//! Gems, ch. 8, 2019, solves the same quadratic in world space; pbrt-v4's
//! `BilinearPatch` carries it.)
//!
//! How many crossings there are is decided on the boundary, exactly: the
//! number of crossings counted with their orientation is the winding
//! number of the projected boundary around the origin, and that is the sum
//! of the winding numbers of the two triangles `p00, p10, p11` and `p00,
//! p11, p01` (the diagonal cancels). Each triangle's inside test is the
//! watertight test's, with its edge rule, on edge functions that any
//! triangle or patch sharing the edge computes bit for bit (negated). A
//! nonzero winding number means exactly one crossing (a four-sided loop
//! winds at most once), which the patch reports; zero means none or two,
//! which the quadratic decides, in floating point.

mod bounds;
mod collapsed;
pub(crate) mod frame;

use glam::Vec3;

use crate::aabb::Aabb;
use crate::num::round::{max2, min2};
use crate::num::{Bits, L, Lanes, Repr, S, Scalar, Vector};
use crate::query::{EdgeRule, Form, Intersect, Range, RayForm, Search, Surface};
use crate::ray::t_max_ok;
use crate::surface::SurfacePoint;
use crate::triangle::{Frame, Side, Triangle, TriangleHitError, inside};

use bounds::{normal_error, point_error};
use frame::{CornerLanes, Cover, Framed, Projected, RayFrame, RayParts, frames};

/// A bilinear patch: the surface `P(u, v) = (1 - u)(1 - v) p00 + u (1 -
/// v) p10 + (1 - u) v p01 + u v p11` for `(u, v)` in the closed unit
/// square, with corners that need not be coplanar (pbrt-v4's
/// `BilinearPatch`; a quad mesh's faces taken as they are, not split).
///
/// Watertight: the side of each of the four edges is decided from that
/// edge's two corners alone, by the edge functions of the watertight
/// triangle test, so a ray never passes between two patches, or a patch
/// and a triangle, that share an edge (the same two corners, bit for bit).
/// With [`EdgeRule::OneHit`] a ray through a shared edge or corner
/// crosses exactly one of them, decided exactly as for triangles.
///
/// What is exact and what is not: whether the ray crosses the patch an
/// odd number of times (once) is decided exactly (from the rounded
/// corners in the ray's frame with the closed rule, from the exact ones
/// with the one-hit rule); where it crosses once, the crossing is
/// reported wherever it lies in the range (one within rounding of the
/// origin excepted, see below). Where
/// it crosses an even number of times (none, or twice where the patch
/// folds over itself as seen from the ray), the quadratic is solved in
/// floating point: rays within rounding of the patch's silhouette, where
/// the two crossings meet, may be reported as touching or missing. `t`,
/// `u` and `v` come with bounds ([`hit_error`](Surface::hit_error)): a
/// certificate that the exact patch meets the exact ray within them.
/// `t > 0` is decided conservatively: a hit is reported where every
/// corner is in front of the origin, or where `t` exceeds its certified
/// bound, so a reported crossing is in front of the origin in exact
/// arithmetic, and a ray spawned from the patch
/// ([`SurfacePoint::spawn`]) never reports the crossing it left (a curved
/// patch may still rise into its path further on, a crossing in front of
/// it). Over an [`Interval`](crate::Interval), the ends are decided on
/// the computed `t` (and `t > 0` as above), so that exactly one of two
/// consecutive intervals reports each crossing.
///
/// `(u, v)` is the hit's place: `p00` at `(0, 0)`, `p10` at `(1, 0)`,
/// `p01` at `(0, 1)`, `p11` at `(1, 1)`. The front side is the one
/// `dP/du x dP/dv` points to at the hit (for a planar patch the side the
/// winding `p00 -> p10 -> p11 -> p01` is counter-clockwise from, as for a
/// [`Quad`](crate::Quad) with those corners).
///
/// Degenerate patches, as their definition says: a patch with a collapsed
/// edge (two neighbouring corners equal, bit for bit) is the triangle of
/// the other three, and is tested as that [`Triangle`] (its answers, `t`
/// and side bit for bit, zero-area slivers included, with `(u, v)` from
/// its barycentrics; the surface point and bounds the triangle's); a
/// planar parallelogram is hit where the [`Quad`](crate::Quad) of its
/// corners is, at the same `(u, v)` up to rounding (each decides `t > 0`
/// conservatively by its own bound, so they may differ on a crossing
/// within those bounds of the origin); a twisted patch is hit where its
/// surface is. A patch of
/// zero area with no collapsed edge (four distinct corners on one line)
/// may be hit where rounding leaves one of its triangles a sliver, as a
/// zero-area triangle is, and a ray along it may be reported at no
/// particular point of it: unlike a zero-area triangle it closes no mesh,
/// so it is best left out. A NaN or infinite coordinate makes a patch
/// nothing hits.
///
/// Precondition for the guarantees, as for the triangle: coordinates
/// relative to the ray origin below `2^63` in `f32` (`2^511` in `f64`),
/// so that the edge functions do not overflow, and not so small that they
/// underflow (above about `2^-39` in `f32`, `2^-500` in `f64`).
///
/// A plain [`Ray`](crate::Ray) is sheared on each call (three
/// divisions); for one ray against many patches, pass a
/// [`PreparedRay`](crate::PreparedRay) (made once): the answers are the
/// same, bit for bit.
///
/// ```
/// use rayhit::{Intersect, Patch, Ray, glam::Vec3};
/// // A saddle over the unit square: corners at heights 0, 0, 0 and 1.
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 3.0), -Vec3::Z);
/// let hit = saddle.hit(&ray, f32::INFINITY).unwrap();
/// // P(1/2, 1/2) has height 1/4.
/// assert_eq!((hit.u, hit.v, hit.t), (0.5, 0.5, 2.75));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Patch<V = Vec3> {
    /// The corner at `(u, v) = (0, 0)`.
    pub p00: V,
    /// The corner at `(1, 0)`.
    pub p10: V,
    /// The corner at `(0, 1)`.
    pub p01: V,
    /// The corner at `(1, 1)`.
    pub p11: V,
}

/// A ray/patch hit: `t` in units of the ray's `dir`, the place `(u, v)`
/// on the patch, and the side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// The coordinate along `p00 -> p10`, in `[0, 1]`.
    pub u: F,
    /// The coordinate along `p00 -> p01`, in `[0, 1]`.
    pub v: F,
    /// The side the ray arrived from: [`Side::Front`] where `dir . (dP/du
    /// x dP/dv) < 0` at the hit.
    pub side: Side,
}

impl<V: Vector> Patch<V> {
    /// The patch with the given corners (in the order `p00, p10, p01,
    /// p11`: the `u = 0` and `u = 1` ends of the edge `v = 0`, then of
    /// `v = 1`). Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(p00: V, p10: V, p01: V, p11: V) -> Self {
        Self { p00, p10, p01, p11 }
    }

    /// The point `P(u, v)`, rounded: `p00`, `p10`, `p01`, `p11` exactly at
    /// the corners.
    ///
    /// ```
    /// use rayhit::{Patch, glam::Vec3};
    /// let p = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
    /// assert_eq!(p.point_at(1.0, 1.0), Vec3::new(1.0, 1.0, 1.0));
    /// assert_eq!(p.point_at(0.5, 0.5), Vec3::new(0.5, 0.5, 0.25));
    /// ```
    #[inline]
    #[must_use]
    pub fn point_at(&self, u: S<V>, v: S<V>) -> V {
        let near = lerp_v(self.p00, self.p10, u);
        let far = lerp_v(self.p01, self.p11, u);
        lerp_v(near, far, v)
    }

    /// The patch's normal `dP/du x dP/dv` at `(u, v)`, not normalised,
    /// rounded; zero where the patch is degenerate there (at a collapsed
    /// edge).
    ///
    /// ```
    /// use rayhit::{Patch, glam::Vec3};
    /// let p = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
    /// assert_eq!(p.normal_at(0.3, 0.7), Vec3::Z);
    /// ```
    #[inline]
    #[must_use]
    pub fn normal_at(&self, u: S<V>, v: S<V>) -> V {
        let du = lerp_v(self.p10 - self.p00, self.p11 - self.p01, v);
        let dv = lerp_v(self.p01 - self.p00, self.p11 - self.p10, u);
        du.cross(dv)
    }

    /// The two triangles `p00, p10, p11` and `p00, p11, p01` whose inside
    /// tests decide the patch's boundary (the planar quad of the corners,
    /// when they are coplanar).
    #[inline]
    #[must_use]
    pub fn triangles(&self) -> [Triangle<V>; 2] {
        [
            Triangle::new(self.p00, self.p10, self.p11),
            Triangle::new(self.p00, self.p11, self.p01),
        ]
    }

    /// The smallest box around the four corners (exact: no rounding); the
    /// patch, a convex combination of its corners, lies in it.
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> Aabb<V> {
        let c = [self.p00, self.p10, self.p01, self.p11];
        let fold = |f: fn(S<V>, S<V>) -> S<V>| {
            let k = |a: fn(V) -> S<V>| f(f(a(c[0]), a(c[1])), f(a(c[2]), a(c[3])));
            V::new(k(V::x), k(V::y), k(V::z))
        };
        Aabb::new(fold(min_of), fold(max_of))
    }
}

/// The smaller, NaN-free where one is.
fn min_of<F: Scalar>(a: F, b: F) -> F {
    if b < a { b } else { a }
}

/// The larger, NaN-free where one is.
fn max_of<F: Scalar>(a: F, b: F) -> F {
    if b > a { b } else { a }
}

/// `(1 - w) a + w b`: exactly `a` at `w = 0` and `b` at `w = 1`.
#[inline(always)]
fn lerp<F: Scalar>(a: F, b: F, w: F) -> F {
    (F::ONE - w) * a + w * b
}

#[inline(always)]
fn lerp_v<V: Vector>(a: V, b: V, w: S<V>) -> V {
    V::new(
        lerp(a.x(), b.x(), w),
        lerp(a.y(), b.y(), w),
        lerp(a.z(), b.z(), w),
    )
}

/// The ray/patch test for a valid ray with `shear` its shear: the nearest
/// crossing with `lo < t <= hi` (`0 <= lo <= hi`), with `rule` on the
/// boundary. The ends are decided on the computed `t`, and `t > 0`
/// conservatively besides: every corner in front of the origin, or `t`
/// above its certified bound.
#[inline(always)]
fn patch_hit<V: Vector>(
    r: &RayFrame<V>,
    patch: &Patch<V>,
    c: &CornerLanes<V>,
    (lo, hi): (S<V>, S<V>),
    rule: EdgeRule,
) -> Option<PatchHit<S<V>>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    let lanes_zero = L::<V>::splat(zero);
    // No corner in front: every crossing is at t <= 0.
    let front = lanes_zero.lt4(c.z);
    if front == 0 {
        return None;
    }
    // A corner that is not finite, or whose coordinates in the ray's
    // frame overflow: nothing is hit. (`w - w` is zero for a finite `w`,
    // NaN for an infinity or NaN, and a sum with a NaN is NaN.)
    let (x, y, z) = (c.x, c.y, c.z);
    if x.sub(x).add(y.sub(y)).add(z.sub(z)).eq4(lanes_zero) != 0b1111 {
        return None;
    }
    let fr = Framed::new(c);
    let p = &fr.p;
    // The closed rule's common miss: neither triangle covers the ray (its
    // edge functions straddle zero, whatever the exact sign of one that
    // rounds to zero) and every corner lies on one side of an axis
    // through it, so the projected patch, in their hull, does not reach
    // it: no fold can cross it either.
    // (`&` of the two, not `==` on the pair: compared as one 16-bit word,
    // the two flags were stored a byte each and read back as a word, a
    // store-forwarding stall on every test.)
    if rule == EdgeRule::Closed && (fr.straddles[0] & fr.straddles[1]) {
        // (`|`, not `||`: one branch, where the outcomes are a coin toss.)
        let side = |a: L<V>| (lanes_zero.lt4(a) == 0b1111) | (a.lt4(lanes_zero) == 0b1111);
        if side(c.x) | side(c.y) {
            return None;
        }
    }
    // Whether each triangle covers the ray, and its orientation there.
    let (in1, in2) = match rule {
        EdgeRule::Closed => (
            Cover::closed(fr.e1, fr.straddles[0]),
            Cover::closed(fr.e2, fr.straddles[1]),
        ),
        EdgeRule::OneHit => {
            let tris = patch.triangles();
            let (ray, shear) = (r.ray(), r.shear());
            let covers = |f: &Frame<S<V>>, tri: &Triangle<V>| {
                inside(f, rule, (ray.origin, ray.dir), &shear, tri).map_or(Cover::NONE, Cover::of)
            };
            let [f1, f2] = frames(r, patch);
            (covers(&f1, &tris[0]), covers(&f2, &tris[1]))
        }
    };
    // Exactly one crossing where the boundary winds around the ray: one
    // triangle covers it, or both with one orientation (the ray on the
    // diagonal).
    let single = (in1.any() | in2.any()) & !((in1.pos & in2.neg) | (in1.neg & in2.pos));
    // A winding number of zero: two crossings need a fold, where the
    // projected Jacobian (affine in u and v) takes both signs, so both
    // signs at the corners; with one sign the map is one to one and
    // there is no crossing. (Most misses end here.)
    if !single && !c.may_fold() {
        return None;
    }
    // The quadratic c(u) in Bernstein form: b0 = q00 x q01 (the edge
    // u = 0), b2 = q10 x q11 (the edge u = 1), b1 the mean of the
    // diagonals' products.
    let (x, y) = (&p.x, &p.y);
    let b0 = -fr.e2[1];
    let b2 = fr.e1[0];
    let b1 = (fr.e2[2] + (x[1] * y[3] - y[1] * x[3])) * S::<V>::HALF;
    // Scaled by the power of two that brings the largest into [1, 2)
    // (exactly), so that squaring them neither overflows nor underflows
    // (they are squares of coordinates: the discriminant is a fourth
    // power). The roots do not change; `2^k` scalings of the inputs leave
    // these values unchanged, bit for bit. (All zero: no finite root.)
    let largest = max2(max2(b0.abs(), b1.abs()), b2.abs());
    let scale = <S<V> as Repr>::Bits::inverse_binade(largest);
    let (b0, b1, b2) = (b0 * scale, b1 * scale, b2 * scale);
    let disc = b1 * b1 - b0 * b2;
    // (Where the crossing is single the exact discriminant is at least
    // zero.)
    let disc = if single {
        max2(disc, zero)
    } else if disc >= zero {
        disc
    } else {
        return None;
    };
    // c(u) = a u^2 + 2 b u + b0, its roots by the stable pair.
    let a = (b0 + b2) - (b1 + b1);
    let b = b1 - b0;
    let root = disc.sqrt();
    let q = -(b + if b < zero { -root } else { root });
    // (The smaller root first: `b0 / q` is stable, and for a nearly
    // planar patch `a` is nearly zero and `q / a` far off.)
    let near_root = b0 / q;
    // Every corner in front makes every crossing so (the depth is a
    // convex combination of theirs); else a crossing stands in front of
    // the origin where its `t` exceeds its certified bound.
    let ahead = front == 0b1111;
    let side_of = |det: S<V>| {
        if (det > zero) != (r.dz > zero) {
            Side::Front
        } else {
            Side::Back
        }
    };
    if !single {
        let (u, v, t) = two_crossings(r, patch, &fr, [near_root, q / a], ahead, (lo, hi))?;
        return Some(PatchHit {
            t,
            u,
            v,
            side: side_of(p.orientation(u, v)),
        });
    }
    let (u, v) = match in_square(p, near_root) {
        Some(place) => place,
        None => off_square(p, near_root, q / a, in1.any().then_some(fr.e1), fr.e2),
    };
    let t = p.t_at(u, v);
    if !(ends(t, (lo, hi)) && (ahead || t > fr.certify(r, patch, u, v).t)) {
        return None;
    }
    // The covering triangle's orientation: the crossing's, exactly.
    let det = if in1.pos | in2.pos { one } else { -one };
    Some(PatchHit {
        t,
        u,
        v,
        side: side_of(det),
    })
}

/// Whether `t` is in `(lo, hi]` and finite. (The same test for every
/// interval, whatever its ends, so that consecutive intervals split the
/// crossings between them.)
#[inline(always)]
fn ends<F: Scalar>(t: F, (lo, hi): (F, F)) -> bool {
    (lo < t) & (t <= hi) & (t <= F::MAX)
}

/// A winding number of zero and a fold: none or two crossings, `roots`
/// the quadratic's. Each root whose `(u, v)` is in the square and where
/// the exact patch is certified to meet the ray (which no rounding noise
/// of a patch of zero area, and no spurious root of a collapsed edge, can
/// be); the nearer in range, as `(u, v, t)`. (The nearer candidate is
/// certified first: where it holds, the farther needs no certificate.)
#[inline(always)]
fn two_crossings<V: Vector>(
    r: &RayFrame<V>,
    patch: &Patch<V>,
    fr: &Framed<S<V>>,
    roots: [S<V>; 2],
    ahead: bool,
    range: (S<V>, S<V>),
) -> Option<(S<V>, S<V>, S<V>)> {
    let candidate = |u: S<V>| {
        in_square(&fr.p, u)
            .map(|(u, v)| (u, v, fr.p.t_at(u, v)))
            .filter(|&(_, _, t)| ends(t, range))
    };
    // (Each root by name: `roots.map` was a call that returned its
    // answers through memory, read back wider than written.)
    let (first, second) = match (candidate(roots[0]), candidate(roots[1])) {
        (Some(a), Some(b)) if b.2 < a.2 => (Some(b), Some(a)),
        (a, b) => (a, b),
    };
    // (With every corner ahead only the crossing's existence is in
    // question, which a test without division settles most of the time.)
    let certified = |c: &(S<V>, S<V>, S<V>)| {
        if ahead && fr.meets(r, patch, c.0, c.1) {
            return true;
        }
        let bound = fr.certify(r, patch, c.0, c.1).t;
        bound.is_finite() && (ahead || c.2 > bound)
    };
    first.filter(certified).or_else(|| second.filter(certified))
}

/// `(u, v)` at the root `u` where both are in `[0, 1]`.
#[inline(always)]
fn in_square<F: Scalar>(p: &Projected<F>, u: F) -> Option<(F, F)> {
    let (zero, one) = (F::ZERO, F::ONE);
    if !((zero <= u) & (u <= one)) {
        return None;
    }
    let v = p.v_at(u);
    ((zero <= v) & (v <= one)).then_some((u, v))
}

/// The place of the single crossing where the near root's is not in the
/// square: the far root's if it is (`far`), else, of the roots brought
/// into the square and the covering triangle's own place (as a planar
/// quad's, [`from_triangle`]), the one whose point lies nearest the ray: a
/// crossing within rounding of an edge; a collapsed edge's spurious root,
/// its segment a point away from the ray; a patch seen edge-on, whose
/// quadratic's coefficients cancel (the ray nearly along one family of
/// its segments, where the triangle's edge functions still place it);
/// a quadratic that rounding left with no coefficient.
#[cold]
#[inline(never)]
fn off_square<F: Scalar>(
    p: &Projected<F>,
    near: F,
    far: F,
    first: Option<[F; 3]>,
    second: [F; 3],
) -> (F, F) {
    if let Some(place) = in_square(p, far) {
        return place;
    }
    let (zero, one) = (F::ZERO, F::ONE);
    let clamp = |w: F| min2(max2(w, zero), one);
    let (u, v) = from_triangle(first, second);
    let mut best = (u, v, p.miss_at(u, v));
    for u in [near, far] {
        if !u.is_finite() {
            continue;
        }
        let u = clamp(u);
        // (A point segment's NaN `v` becomes 0: `max2` keeps the zero.)
        let v = clamp(p.v_at(u));
        let miss = p.miss_at(u, v);
        if miss < best.2 {
            best = (u, v, miss);
        }
    }
    (best.0, best.1)
}

/// `(u, v)` of the origin on the covering triangle (`first`'s edge
/// functions where `p00, p10, p11` covers it, else `second`'s, of `p00,
/// p11, p01`), as on a parallelogram: on the first `(u1 + v1, v1)`, on the
/// second `(u2, u2 + v2)`, each weight its edge function over the
/// determinant.
#[cold]
fn from_triangle<F: Scalar>(first: Option<[F; 3]>, second: [F; 3]) -> (F, F) {
    let e = first.unwrap_or(second);
    let det = e[0] + e[1] + e[2];
    let (w1, w2) = (e[1] / det, e[2] / det);
    let clamp = |w: F| {
        if w.is_finite() {
            min2(max2(w, F::ZERO), F::ONE)
        } else {
            F::ZERO
        }
    };
    let sum = clamp(w1 + w2);
    if first.is_some() {
        (sum, clamp(w2))
    } else {
        (clamp(w1), sum)
    }
}

/// The ray/patch test.
impl<V: Vector> Intersect<V> for Patch<V> {
    /// `t`, `u`, `v` and the side.
    type Hit = PatchHit<S<V>>;

    /// The nearest crossing of the ray with the patch within `search`
    /// (a `t_max`: `0 < t <= t_max`, `t > 0` decided conservatively; an
    /// [`Interval`](crate::Interval): `t_min < t <= t_max`, decided on the
    /// computed `t`, so that of consecutive intervals exactly one reports
    /// a crossing), with the search's edge rule on the boundary. Where the
    /// ray meets the patch twice, the nearer; the farther is the hit over
    /// the interval that starts at the nearer's `t`. See [`Patch`] for
    /// what is decided exactly.
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Patch, Ray, glam::Vec3};
    /// // The saddle z = x y over [-1, 1]^2: the line (s, s, 1/4) meets it
    /// // at s = -1/2 and s = 1/2, once from each side.
    /// let saddle = Patch::new(
    ///     Vec3::new(-1.0, -1.0, 1.0),
    ///     Vec3::new(1.0, -1.0, -1.0),
    ///     Vec3::new(-1.0, 1.0, -1.0),
    ///     Vec3::new(1.0, 1.0, 1.0),
    /// );
    /// let ray = Ray::new(Vec3::new(-1.0, -1.0, 0.25), Vec3::new(1.0, 1.0, 0.0));
    /// let first = saddle.hit(&ray, f32::INFINITY).unwrap();
    /// let after = Interval::new(first.t, f32::INFINITY).unwrap();
    /// let second = saddle.hit(&ray, after).unwrap();
    /// assert!((first.t - 0.5).abs() < 1e-6 && (second.t - 1.5).abs() < 1e-6);
    /// assert!((first.u - 0.25).abs() < 1e-6 && (second.v - 0.75).abs() < 1e-6);
    /// assert_ne!(first.side, second.side);
    /// ```
    #[inline]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        let search = search.into();
        let ends = match search.range {
            Range::UpTo(t_max) => t_max_ok(t_max).then_some((S::<V>::ZERO, t_max))?,
            Range::Within(interval) => interval.ends(),
        };
        // (A prepared ray holds its frame, the very one `Shear::new`
        // computes.)
        let parts;
        let r = match ray.form() {
            Form::Plain(r) => {
                if !r.is_valid() {
                    return None;
                }
                parts = RayParts::new(r);
                RayFrame::plain(r, &parts)
            }
            // (An invalid ray is prepared from `+inf`: every corner's depth
            // comes out `-inf` or NaN, and the test below misses it.)
            Form::Prepared(p) => RayFrame::prepared(p),
        };
        let c = CornerLanes::new(&r, self);
        // A collapsed edge: the triangle it became.
        if let Some((collapse, tri)) = self.collapsed_at(c.collapsed) {
            return tri.hit(ray, search).map(|h| collapse.hit(h));
        }
        patch_hit(&r, self, &c, ends, search.edges)
    }

    /// Whether the patch is crossed within `search`.
    #[inline]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        self.hit(ray, search).is_some()
    }
}

impl<V: Vector> Surface<V> for Patch<V> {
    /// Bounds on the errors of `t`, `u` and `v`.
    type HitError = TriangleHitError<S<V>>;

    /// Bounds on the distance of a hit's `t`, `u` and `v` from a crossing
    /// of the exact ray with the exact patch: a certificate, derived in
    /// the source, that the exact patch (extended bilinearly past its
    /// edges by at most the `u`, `v` bound) meets the exact ray within
    /// that distance of the computed `(u, v)`, and the depth's variation
    /// over it. Infinite where no crossing can be certified near the hit:
    /// the ray within rounding of tangent to the patch (at its
    /// silhouette, or grazing it), or a patch too thin, seen from the
    /// ray, for its rounded corners to place the crossing. For a hit over
    /// an [`Interval`](crate::Interval), the same bounds: the patch does
    /// not move `t` into the interval.
    ///
    /// ```
    /// use rayhit::{Intersect, Patch, Ray, Surface, glam::Vec3};
    /// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
    /// let ray = Ray::new(Vec3::new(0.3, 0.6, 2.0), -Vec3::Z);
    /// let hit = saddle.hit(&ray, f32::INFINITY).unwrap();
    /// let err = saddle.hit_error(&ray, &hit);
    /// // The crossing is P(0.3, 0.6), at height 0.18.
    /// assert!((hit.t - 1.82).abs() <= err.t + 1e-7 && err.t < 1e-5);
    /// assert!((hit.u - 0.3).abs() <= err.u + 1e-7 && (hit.v - 0.6).abs() <= err.v + 1e-7);
    /// ```
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> Self::HitError {
        if let Some((collapse, tri)) = self.collapsed() {
            return collapsed::hit_error(collapse, &tri, ray, hit);
        }
        let r = ray.to_ray();
        let inf = S::<V>::INFINITY;
        if !r.is_valid() {
            return TriangleHitError {
                t: inf,
                u: inf,
                v: inf,
            };
        }
        let parts = RayParts::new(&r);
        let frame = RayFrame::plain(&r, &parts);
        let c = Framed::new(&CornerLanes::new(&frame, self)).certify(&frame, self, hit.u, hit.v);
        TriangleHitError {
            t: c.t,
            u: c.uv,
            v: c.uv,
        }
    }

    /// The point `P(u, v)` of the hit ([`Patch::surface_point_at`]): a
    /// point of the patch within its bound, with the patch's normal there.
    /// The ray is not read. A ray spawned from it does not meet the patch
    /// again where it left it (the crossing there is behind its origin,
    /// and the test decides `t > 0` conservatively); a curved patch may
    /// still be met again elsewhere, as its shape says.
    ///
    /// ```
    /// use rayhit::{Intersect, Patch, Ray, Surface, glam::Vec3};
    /// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
    /// let ray = Ray::new(Vec3::new(0.3, 0.6, 2.0), -Vec3::Z);
    /// let hit = saddle.hit(&ray, f32::INFINITY).unwrap();
    /// let here = saddle.surface_point(&ray, &hit);
    /// // Back up and away: no second meeting.
    /// let bounce = here.spawn(Vec3::new(0.1, 0.2, 1.0));
    /// assert!(saddle.hit(&bounce, f32::INFINITY).is_none());
    /// ```
    #[inline]
    fn surface_point(&self, _ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V> {
        self.surface_point_at(hit.u, hit.v)
    }
}

impl<V: Vector> Patch<V> {
    /// The surface point at `(u, v)` (in `[0, 1]`): `P(u, v)` with a bound
    /// on each coordinate's distance from the exact `P(u, v)`, and the
    /// normal `dP/du x dP/dv` there with its bound. For points that come
    /// from no ray: samples on a patch light, the ends of a shadow
    /// segment ([`SurfacePoint::spawn_to`]).
    ///
    /// ```
    /// use rayhit::{Patch, glam::Vec3};
    /// let p = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
    /// let s = p.surface_point_at(0.5, 0.5);
    /// assert_eq!(s.point, Vec3::new(0.5, 0.5, 0.25));
    /// assert_eq!(s.normal, p.normal_at(0.5, 0.5));
    /// ```
    #[inline]
    #[must_use]
    pub fn surface_point_at(&self, u: S<V>, v: S<V>) -> SurfacePoint<V> {
        if let Some((collapse, tri)) = self.collapsed() {
            let (b, c) = collapse.weights(u, v);
            return tri.surface_point_at(b, c);
        }
        let c = [self.p00, self.p10, self.p01, self.p11];
        let m = |k: fn(V) -> S<V>| c.iter().fold(S::<V>::ZERO, |m, &p| max2(m, k(p).abs()));
        let m = [m(V::x), m(V::y), m(V::z)];
        let du = lerp_v(self.p10 - self.p00, self.p11 - self.p01, v);
        let dv = lerp_v(self.p01 - self.p00, self.p11 - self.p10, u);
        let arr = |w: V| [w.x(), w.y(), w.z()];
        let vec = |a: [S<V>; 3]| V::new(a[0], a[1], a[2]);
        SurfacePoint {
            point: self.point_at(u, v),
            point_error: vec(point_error(m)),
            normal: du.cross(dv),
            normal_error: vec(normal_error(arr(du), arr(dv), m)),
        }
    }
}
