//! `patch`: [`Patch`]'s [`hit`](rayhit::Intersect::hit) and
//! [`occluded`](rayhit::Intersect::occluded), every ray form, edge rule and
//! range, and the degenerate patches against the shapes their definition
//! says they are.
//!
//! Input: raw mode, a `Ray`, the corners `p00`, `p10`, `p01`, `p11`,
//! `t_max` and two ends `lo`, `hi` as raw bits; structured mode, a patch
//! (`structured_case`: twisted, saddles, corners on a dyadic grid, bow
//! ties, one time in four a collapsed edge or an exact parallelogram; a
//! quarter of the time scaled by `2^k`, a quarter of the time moved
//! `10^3` to `10^7` away) and a ray aimed at a point `P(u, v)` of it (a
//! corner, an edge, the diagonals, the interior, around it or just off an
//! edge), from any direction, axis-parallel or grazing the tangent plane
//! there, from a few lengths away, from within a rounding of the surface,
//! or from beyond it; `t_max` and the ends drawn around its crossings
//! ([`super::ends_near`]).
//!
//! Checks, any input: no panic; for a plain and a prepared ray, the closed
//! and the one-hit rule, over `t_max`, over `Interval::up_to(t_max)` and
//! over the interval `(lo, hi]` (where `Interval::new` takes the ends): the
//! prepared ray's answer is the plain ray's, bit for bit; the `t_max` form
//! and `Interval::up_to(t_max)` answer the same, bit for bit (both `None`
//! for a NaN or negative `t_max`; for a patch with a collapsed edge, which
//! is its triangle, that triangle's answer instead, `t` and side bit for
//! bit); `occluded` is `hit.is_some()`; a hit has
//! a finite `t` in range and `u`, `v` in `[0, 1]` (never NaN); an invalid
//! ray or a corner with a NaN or infinite coordinate is never hit. The
//! same on the degenerate patches made from the input's corners (below).
//!
//! The degenerate patches, built from the input's corners ([`collapsed`],
//! [`parallelogram`]), with both rules over `t_max` (plain ray): each of
//! the four patches with a collapsed edge (one corner copied onto a
//! neighbour) is hit or missed as the [`Triangle`] of its other three
//! corners in the patch's winding, and the exact parallelogram (corners
//! `p00`, `p10`, `p01` and `p10 + p01 - p00`, where that sum is exact) as
//! the [`Quad`] of its corners; where both hit, on the same side (but on a
//! triangle of exactly zero area, whose side is meaningless). Held where
//! the input is finite, the triangle's precondition holds for the
//! triangles compared (for raw input also its frame in range,
//! [`super::triangle::frame_in_range`], as the `triangle` target asks),
//! the patch's edge functions are far from underflow
//! ([`edges_in_range`], which documents what this target found beyond
//! it), the patch has nonzero area (one of zero area, its corners on a
//! line, may be hit where rounding leaves one of its triangles a sliver:
//! see [`Patch`]), and `t_max` is at least zero. The two compute different `t`s and
//! the triangle decides `t > 0` conservatively, so a disagreement is
//! allowed at the ends of the range: where the other's `t_max` form and its
//! interval form over `(0, t_max]` (exact at the ends) disagree; where the
//! `t` of the one that hits is within the band of `0` (the patch's
//! [`band`], or the other's `t` bound at its crossing ahead or behind where
//! larger) and so is the other's crossing behind; where the patch misses
//! a crossing of the quad whose `t` its own certified bound there does
//! not exceed (its conservative `t > 0`); or where the one that
//! misses finds the crossing over an unbounded range within the band beyond
//! `t_max`. Elsewhere it is allowed only where exact arithmetic does not
//! decide the other's answer outside its rounding band ([`verdict`]: the
//! `triangle` target's band, which holds the triangle to it): a triangle
//! of exactly zero area has no such band (its hits are its rounded
//! slivers', at the `t` where the ray passes the segment), so there only
//! the ends excuse.
//!
//! Cost: the exact verdict (big rationals) only on a disagreement.

use arbitrary::Arbitrary;
use rayhit::{
    EdgeRule, Intersect, Interval, Patch, PatchHit, PreparedRay, Quad, QuadHit, Ray, Scalar,
    Search, Side, Surface, Triangle, TriangleHit, Vector,
};

use super::exact::r;
use super::triangle::{frame_in_range, precondition};
use super::{Check, Input, S, ends_near, raw, raw_vec};
use crate::cases::patches::{bilinear, corners, direction, place};
use crate::cases::{self, add, c};
use crate::oracle;
use crate::source::Source;

/// The `patch` target.
#[derive(Debug)]
pub struct PatchCheck;

/// One input: the ray, the patch, `t_max`, the interval's ends, and
/// whether it is structured (realistic ranges).
struct Case<V: Vector> {
    ray: Ray<V>,
    patch: Patch<V>,
    t_max: S<V>,
    lo: S<V>,
    hi: S<V>,
    structured: bool,
}

impl<V: Vector> Case<V> {
    fn ctx(&self) -> String {
        format!(
            "ray {:?}, patch {:?}, t_max {:?}, ends {:?} {:?}",
            self.ray, self.patch, self.t_max, self.lo, self.hi
        )
    }
}

impl Check for PatchCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let case = match input {
            Input::Raw(u) => Case {
                ray: raw::<Ray<V>>(u),
                patch: Patch::new(raw_vec(u), raw_vec(u), raw_vec(u), raw_vec(u)),
                t_max: raw::<S<V>>(u),
                lo: raw::<S<V>>(u),
                hi: raw::<S<V>>(u),
                structured: false,
            },
            Input::Structured(src) => structured_case::<V>(src),
        };
        check(&case);
    }
}

/// A structured case: a patch, a ray aimed at a point of it, `t_max` and
/// ends around its crossings.
fn structured_case<V: Vector>(src: &mut Source) -> Case<V> {
    // (The rarer choices are the high ones: a fuzz input's exhausted bytes
    // read as zeros, which pick the common ones.)
    let mut p = corners(src);
    match src.index(8) {
        // A collapsed edge: one corner copied onto a neighbour.
        6 => match src.index(4) {
            0 => p[3] = p[2],
            1 => p[1] = p[0],
            2 => p[2] = p[0],
            _ => p[3] = p[1],
        },
        // A parallelogram (exact on the dyadic grid, and after scaling by
        // `2^k`; the check tests exactness in `V`).
        7 => p[3] = [0, 1, 2].map(|k| p[1][k] + p[2][k] - p[0][k]),
        _ => {}
    }
    let (u, w) = place(src);
    let target = bilinear(&p, u, w);
    let dir = direction(src, &p, u, w);
    let s = match src.index(8) {
        // From within a rounding of the surface: `t` near 0.
        6 => src.log2_range(-40.0, -8.0),
        // The target behind the origin.
        7 => -src.log2_range(-4.0, 2.0),
        _ => src.log2_range(-2.0, 4.0),
    };
    // The scene scaled by `2^k` (exactly) and moved far away.
    let scale = if src.below(4) == 3 {
        src.pow2(-40, 40)
    } else {
        1.0
    };
    let offset = if src.below(4) == 3 {
        cases::far_offset(src)
    } else {
        [0.0; 3]
    };
    let place_at = |q: [f64; 3]| add(cases::scaled(q, scale), offset);
    let [p00, p10, p01, p11] = p.map(|q| cases::v::<V>(place_at(q)));
    let patch = Patch::new(p00, p10, p01, p11);
    let ray = cases::aimed::<V>(place_at(target), cases::scaled(dir, scale), s);
    // The crossings: the nearest, and the next one (a fold's second).
    let inf = S::<V>::INFINITY;
    let mut crossings = Vec::new();
    if let Some(h) = patch.hit(&ray, inf) {
        crossings.push(h.t);
        if let Some(h) = Interval::new(h.t, inf).and_then(|w| patch.hit(&ray, w)) {
            crossings.push(h.t);
        }
    }
    let t_max = match src.index(4) {
        0 => cases::t_max::<V>(src),
        1 => inf,
        _ => ends_near(src, &crossings).1,
    };
    let (lo, hi) = ends_near(src, &crossings);
    Case {
        ray,
        patch,
        t_max,
        lo,
        hi,
        structured: true,
    }
}

/// A hit's `t`, `u`, `v` as bits, and its side: equal exactly when the
/// hits are the same bit for bit.
fn bits<F: Scalar>(h: &PatchHit<F>) -> (u64, u64, u64, Side) {
    let b = |x: F| x.to_f64().to_bits();
    (b(h.t), b(h.u), b(h.v), h.side)
}

fn same<F: Scalar>(a: Option<PatchHit<F>>, b: Option<PatchHit<F>>) -> bool {
    a.as_ref().map(bits) == b.as_ref().map(bits)
}

fn check<V: Vector>(case: &Case<V>) {
    forms(case, &case.patch);
    // The degenerate patches made from the input's corners too.
    for (_, patch, _) in collapsed(&case.patch) {
        forms(case, &patch);
    }
    if let Some((patch, _)) = parallelogram(&case.patch) {
        forms(case, &patch);
    }
    let Patch { p00, p10, p01, p11 } = case.patch;
    if !(case.ray.is_valid() && [p00, p10, p01, p11].iter().all(|p| p.is_finite())) {
        return;
    }
    if !edges_in_range(&case.ray, &case.patch) {
        return;
    }
    let usable = |tri: &Triangle<V>| {
        precondition(&case.ray, tri) && (case.structured || frame_in_range(&case.ray, tri))
    };
    // (A patch of zero area, its corners on one line, is not compared:
    // see `Patch`'s docs.)
    for (what, patch, tri) in collapsed(&case.patch) {
        if usable(&tri) && !tri.is_degenerate() {
            let other = Other {
                shape: &tri,
                zero_area: tri.is_degenerate(),
                t_of: |h: &TriangleHit<S<V>>| h.t,
                side_of: |h: &TriangleHit<S<V>>| h.side,
                err_of: |h: &TriangleHit<S<V>>| tri.hit_error(&case.ray, h).t,
                verdict: || verdict(&case.ray, &tri, case.t_max),
                place_of: |_: &TriangleHit<S<V>>| None,
            };
            degenerate(case, what, &patch, other);
        }
    }
    if let Some((patch, quad)) = parallelogram(&case.patch)
        && quad.triangles().iter().all(usable)
        && !quad.triangles().iter().any(Triangle::is_degenerate)
    {
        let other = Other {
            shape: &quad,
            zero_area: quad.triangles().iter().any(Triangle::is_degenerate),
            t_of: |h: &QuadHit<S<V>>| h.t,
            side_of: |h: &QuadHit<S<V>>| h.side,
            err_of: |h: &QuadHit<S<V>>| quad.hit_error(&case.ray, h).t,
            verdict: || quad_verdict(&case.ray, &quad, case.t_max),
            // (A parallelogram's quad places a hit as the patch does.)
            place_of: |h: &QuadHit<S<V>>| Some((h.u, h.v)),
        };
        degenerate(case, "parallelogram", &patch, other);
    }
}

/// Whether the patch's edge functions are far from underflow: with `M`
/// the largest corner coordinate relative to the ray's origin, the edge
/// functions are products of coordinates up to `2M` in the ray's sheared
/// frame, and the patch's quadratic is made of them (divided by the
/// largest before it is squared); its roots keep their precision where
/// `M^2` is far from underflow ([`super::far_from_underflow`]: `M` at
/// least about `2^-39` in `f32`, `2^-500` in `f64`; the crate's bounds and
/// false-hit bands assume no intermediate underflow). Overflow is the
/// triangle's precondition, held by the triangles compared. (This target
/// found the quadratic overflowing at coordinates near `2^45` in `f32`,
/// and its discriminant underflowing near `2^-35`, before its
/// coefficients were scaled.)
pub fn edges_in_range<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> bool {
    let o = c(ray.origin);
    let m = [patch.p00, patch.p10, patch.p01, patch.p11]
        .iter()
        .map(|&p| c(p))
        .fold(0.0f64, |m, p| {
            (0..3).fold(m, |m, k| m.max((p[k] - o[k]).abs()))
        });
    let min = S::<V>::MIN_POSITIVE.to_f64();
    let u = S::<V>::UNIT_ROUNDOFF.to_f64();
    m * m >= min / (u * u)
}

/// Every ray form, rule and range on `patch` (the input's, or one made
/// from its corners) with the input's ray and ranges: the same answers on
/// both ray forms, `t_max` as `Interval::up_to(t_max)`, `occluded`, the
/// range, and no hit on invalid input.
fn forms<V: Vector>(case: &Case<V>, patch: &Patch<V>) {
    let prepared = PreparedRay::new(&case.ray);
    let Patch { p00, p10, p01, p11 } = *patch;
    let hittable = case.ray.is_valid() && [p00, p10, p01, p11].iter().all(|p| p.is_finite());
    let zero = S::<V>::ZERO;
    for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
        let t_max = case.t_max;
        let h = search(
            case,
            patch,
            &prepared,
            (t_max, rule).into(),
            (zero, t_max),
            hittable,
        );
        // (A patch with a collapsed edge answers as its triangle, whose
        // `t_max` form decides `t > 0` conservatively and its interval
        // form exactly: they may differ at the ends.)
        match Interval::up_to(t_max) {
            Some(_) if oracle::collapsed_triangle(patch).is_some() => {}
            Some(w) => {
                let up_to = search(
                    case,
                    patch,
                    &prepared,
                    (w, rule).into(),
                    (zero, t_max),
                    hittable,
                );
                assert!(
                    same(h, up_to),
                    "{rule:?}: over t_max {h:?}, over Interval::up_to(t_max) {up_to:?} on \
                     {patch:?}: {}",
                    case.ctx()
                );
            }
            None => assert!(
                h.is_none(),
                "{rule:?}: {h:?} on {patch:?} for a t_max Interval::up_to rejects: {}",
                case.ctx()
            ),
        }
        if let Some(w) = Interval::new(case.lo, case.hi) {
            search(
                case,
                patch,
                &prepared,
                (w, rule).into(),
                (case.lo, case.hi),
                hittable,
            );
        }
    }
}

/// One search on both ray forms: the same answer bit for bit, `occluded`
/// as `hit.is_some()`, a hit in `(lo, hi]` with `u`, `v` in `[0, 1]`, and
/// only on a `hittable` input. Returns the answer.
fn search<V: Vector>(
    case: &Case<V>,
    patch: &Patch<V>,
    prepared: &PreparedRay<V>,
    search: Search<S<V>>,
    (lo, hi): (S<V>, S<V>),
    hittable: bool,
) -> Option<PatchHit<S<V>>> {
    let hit = patch.hit(&case.ray, search);
    let again = patch.hit(prepared, search);
    if let Some(tri) = oracle::collapsed_triangle(patch) {
        let as_tri = tri
            .hit(&case.ray, search)
            .map(|h| (h.t.to_f64().to_bits(), h.side));
        assert_eq!(
            hit.map(|h| (h.t.to_f64().to_bits(), h.side)),
            as_tri,
            "{search:?}: a collapsed patch's {hit:?} is not its triangle's on {patch:?}: {}",
            case.ctx()
        );
    }
    assert!(
        same(hit, again),
        "{search:?}: the plain ray's {hit:?}, the prepared ray's {again:?} on {patch:?}: {}",
        case.ctx()
    );
    for occluded in [
        patch.occluded(&case.ray, search),
        patch.occluded(prepared, search),
    ] {
        assert_eq!(
            occluded,
            hit.is_some(),
            "{search:?}: occluded against {hit:?} on {patch:?}: {}",
            case.ctx()
        );
    }
    if let Some(h) = hit {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        assert!(
            h.t.is_finite() && lo < h.t && h.t <= hi,
            "{search:?}: {h:?} out of range on {patch:?}: {}",
            case.ctx()
        );
        assert!(
            zero <= h.u && h.u <= one && zero <= h.v && h.v <= one,
            "{search:?}: {h:?}: u, v not in [0, 1] on {patch:?}: {}",
            case.ctx()
        );
        assert!(
            hittable,
            "{search:?}: {h:?} on invalid input {patch:?}: {}",
            case.ctx()
        );
    }
    hit
}

/// The four patches with a collapsed edge made from `p`'s corners (one
/// corner copied onto a neighbour), each with the triangle of its other
/// three corners in the patch's winding.
pub fn collapsed<V: Vector>(p: &Patch<V>) -> [(&'static str, Patch<V>, Triangle<V>); 4] {
    let Patch { p00, p10, p01, p11 } = *p;
    [
        (
            "p11 = p01",
            Patch::new(p00, p10, p01, p01),
            Triangle::new(p00, p10, p01),
        ),
        (
            "p10 = p00",
            Patch::new(p00, p00, p01, p11),
            Triangle::new(p00, p11, p01),
        ),
        (
            "p01 = p00",
            Patch::new(p00, p10, p00, p11),
            Triangle::new(p00, p10, p11),
        ),
        (
            "p11 = p10",
            Patch::new(p00, p10, p01, p10),
            Triangle::new(p00, p10, p01),
        ),
    ]
}

/// The parallelogram on `p`'s corners `p00`, `p10`, `p01` (`p11 = p10 +
/// p01 - p00`) and its quad, where that sum is finite and exact.
pub fn parallelogram<V: Vector>(p: &Patch<V>) -> Option<(Patch<V>, Quad<V>)> {
    let Patch { p00, p10, p01, .. } = *p;
    let p11 = p10 + p01 - p00;
    if !([p00, p10, p01, p11].iter().all(|q| q.is_finite())) {
        return None;
    }
    let exact = (0..3).all(|k| r(p11[k]) == r(p10[k]) + r(p01[k]) - r(p00[k]));
    exact.then(|| {
        (
            Patch::new(p00, p10, p01, p11),
            Quad::new(p00, p10, p11, p01),
        )
    })
}

/// The width of the ends' rounding band for a patch's `t`: the patch's `t`
/// is its bilinear depth at its computed `(u, v)`, the depths of the
/// corners along the ray (in units of `dir`, measured along the
/// direction's largest component as the ray's sheared frame does)
/// interpolated, so it carries roundings of the size of the largest of
/// them, at most `Z = max |p - o|_inf / |dir|_inf` over the corners `p`:
/// `2^8 u Z` (`u` the unit roundoff), in `f64`.
pub fn band<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> f64 {
    let (o, d) = (c(ray.origin), c(ray.dir));
    let d_max = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let depth = |p: V| {
        let p = c(p);
        (0..3).fold(0.0f64, |m, k| m.max((p[k] - o[k]).abs())) / d_max
    };
    let z = [patch.p00, patch.p10, patch.p01, patch.p11]
        .map(depth)
        .iter()
        .fold(0.0f64, |m, &z| m.max(z));
    256.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * z
}

/// Exact arithmetic's answer for a triangle over `(0, t_max]`, where it
/// is decided outside the watertight test's rounding band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Decided: a hit or a miss ([`oracle::triangle_decided`], or
    /// [`oracle::surely_outside`] for a miss).
    Decided(bool),
    /// Within the band (or the line parallel to the plane): either answer.
    Band,
    /// A triangle of exactly zero area: hit only where rounding leaves it
    /// a sliver, at the `t` where the ray passes the segment (so no
    /// verdict excuses a disagreement; only the ends do).
    ZeroArea,
}

/// The [`Verdict`] for `tri` (finite, within the triangle test's
/// precondition).
pub fn verdict<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: S<V>) -> Verdict {
    if tri.is_degenerate() {
        return Verdict::ZeroArea;
    }
    let exact = oracle::triangle(ray, tri);
    let none = oracle::no_extra();
    match oracle::triangle_decided(ray, tri, &exact, t_max, &none) {
        Some(hit) => Verdict::Decided(hit),
        None if oracle::surely_outside(ray, tri, &exact, &none) => Verdict::Decided(false),
        None => Verdict::Band,
    }
}

/// The [`Verdict`] for a quad: its triangles', a hit where either is.
pub fn quad_verdict<V: Vector>(ray: &Ray<V>, quad: &Quad<V>, t_max: S<V>) -> Verdict {
    let [a, b] = quad.triangles().map(|t| verdict(ray, &t, t_max));
    match (a, b) {
        (Verdict::Decided(true), _) | (_, Verdict::Decided(true)) => Verdict::Decided(true),
        (Verdict::Decided(false), Verdict::Decided(false)) => Verdict::Decided(false),
        (Verdict::ZeroArea, _) | (_, Verdict::ZeroArea) => Verdict::ZeroArea,
        _ => Verdict::Band,
    }
}

/// What a degenerate patch is compared with: the shape, whether it has a
/// triangle of exactly zero area (whose side is its rounded determinant's,
/// meaningless), its hit's `t`, side and `t` bound, and its exact verdict.
struct Other<'a, X, T, D, E, W, P> {
    shape: &'a X,
    zero_area: bool,
    t_of: T,
    side_of: D,
    err_of: E,
    verdict: W,
    /// A hit's place on the patch, `(u, v)`, where the shape's hit has it.
    place_of: P,
}

/// A degenerate patch against the shape it is, both rules over `t_max`:
/// hit or missed alike, on the same side where both hit; a disagreement
/// only within the rounding of an end, or where exact arithmetic does not
/// decide the other's answer outside its rounding band (see the module
/// docs).
fn degenerate<V, X, T, D, E, W, P>(
    case: &Case<V>,
    what: &str,
    patch: &Patch<V>,
    other: Other<X, T, D, E, W, P>,
) where
    V: Vector,
    X: Intersect<V> + core::fmt::Debug,
    X::Hit: core::fmt::Debug,
    T: Fn(&X::Hit) -> S<V>,
    D: Fn(&X::Hit) -> Side,
    E: Fn(&X::Hit) -> S<V>,
    W: Fn() -> Verdict,
    P: Fn(&X::Hit) -> Option<(S<V>, S<V>)>,
{
    let (ray, t_max) = (&case.ray, case.t_max);
    if !(t_max >= S::<V>::ZERO) {
        return;
    }
    let shape = other.shape;
    let inf = S::<V>::INFINITY;
    let reversed = Ray::new(ray.origin, -ray.dir);
    let f = |x: S<V>| x.to_f64();
    for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
        let p = patch.hit(ray, (t_max, rule));
        let o = shape.hit(ray, (t_max, rule));
        let ctx = || {
            format!(
                "{what} {rule:?}: patch {patch:?}, {shape:?}, ray {ray:?}, t_max {t_max:?} \
                 (input {})",
                case.ctx()
            )
        };
        match (&p, &o) {
            (Some(p), Some(o)) => {
                assert!(
                    other.zero_area || p.side == (other.side_of)(o),
                    "sides differ: {p:?} against {o:?}: {}",
                    ctx()
                );
                continue;
            }
            (None, None) => continue,
            _ => {}
        }
        // The other's `t_max` form and its interval form over `(0,
        // t_max]`, which decides the ends exactly, disagree: its crossing is
        // within its bound of an end.
        let exact_ends = Interval::up_to(t_max).and_then(|w| shape.hit(ray, (w, rule)));
        if exact_ends.is_some() != o.is_some() {
            continue;
        }
        // The other's crossings ahead (`t* > 0`, exactly) and behind (the
        // reversed ray's), with either rule, and the band of the ends: the
        // patch's ([`band`]), or the other's bound at a crossing where
        // larger (infinite where the side of its plane is not certain).
        let whole = Interval::up_to(inf);
        let crossings = |r: &Ray<V>| {
            [EdgeRule::Closed, EdgeRule::OneHit]
                .map(|rule| whole.and_then(|w| shape.hit(r, (w, rule))))
        };
        let (ahead, behind) = (crossings(ray), crossings(&reversed));
        let b = ahead
            .iter()
            .chain(&behind)
            .chain([&o])
            .flatten()
            .map(|h| f((other.err_of)(h)))
            .fold(band(ray, patch), |m, e| if e > m { e } else { m });
        // Within the band of `0`: the patch's or the other's `t`, and the
        // other's crossing behind, if any.
        let near_zero = |t: f64| t <= b && behind.iter().flatten().all(|h| f((other.t_of)(h)) <= b);
        let ahead_here = ahead[usize::from(rule == EdgeRule::OneHit)].as_ref();
        let near_end = match (&p, &o) {
            (Some(p), None) => {
                near_zero(f(p.t)) || ahead_here.is_some_and(|h| f((other.t_of)(h)) - f(t_max) <= b)
            }
            (None, Some(o)) => {
                // The patch decides `t > 0` by its own certified bound,
                // which may be the larger: at the other's place, its
                // bound at least `t` (or none) excuses a miss.
                let own = (other.place_of)(o).map(|(u, v)| {
                    let at = PatchHit {
                        t: (other.t_of)(o),
                        u,
                        v,
                        side: (other.side_of)(o),
                    };
                    f(patch.hit_error(ray, &at).t)
                });
                own.is_some_and(|e| !(e < f((other.t_of)(o))))
                    || near_zero(f((other.t_of)(o)))
                    || patch
                        .hit(ray, (inf, rule))
                        .is_some_and(|h| f(h.t) - f(t_max) <= b)
            }
            _ => unreachable!(),
        };
        if near_end {
            continue;
        }
        let verdict = (other.verdict)();
        assert!(
            verdict == Verdict::Band,
            "the degenerate patch's {p:?} against {o:?}, exact arithmetic's {verdict:?} \
             (band of the ends {b:?}; the other's crossings ahead {ahead:?}, behind \
             {behind:?}): {}",
            ctx()
        );
    }
}
