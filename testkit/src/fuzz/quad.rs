//! `quad`: [`Quad`]'s [`hit`](rayhit::Intersect::hit) against its two
//! triangles, every ray form, edge rule and range.
//!
//! Input: raw mode, a `Ray`, a `Quad`, `t_max` and two ends `lo`, `hi` as
//! raw bits; structured mode, a triangle case of
//! [`cases::triangles::generators`] (a ray aimed at the triangle's
//! interior, edges or corners) made the first triangle `a, b, c` of a
//! quad, whose fourth corner completes a parallelogram or, one input in
//! two, folds it along the diagonal `a`-`c` (which rays aimed at the edge
//! `c`-`a` cross), and ends drawn around the hit ([`super::ends_near`]).
//!
//! Checks, any input: no panic; for a plain and a prepared ray, the closed
//! and the one-hit rule, over `t_max` and over the interval `(lo, hi]`
//! (where `Interval::new` takes the ends): the hit is the nearer of the
//! two triangles' hits ([`Quad::triangles`], the first where they tie),
//! bit for bit, with `u`, `v` summed from its barycentrics as the quad's
//! documentation says (so every guarantee of the triangle test carries
//! over, held by the `triangle` target); `occluded` is `hit.is_some()`;
//! `u` and `v` are in `[0, 1]`; the error bounds are never NaN; and where
//! the triangle test's precondition holds for both triangles, rays spawned
//! from the hit's surface point (along the ray, against it, along the
//! normal and against it) start at a finite point.

use arbitrary::Arbitrary;
use rayhit::{
    EdgeRule, Intersect, Interval, PreparedRay, Quad, QuadHit, Ray, RayForm, Scalar, Search,
    Surface, Triangle, TriangleHit, Vector,
};

use super::triangle::precondition;
use super::{Check, Input, S, ends_near, raw, raw_vec};
use crate::cases;
use crate::cases::triangles::corners;
use crate::source::Source;

/// The `quad` target.
#[derive(Debug)]
pub struct QuadCheck;

/// One input: the ray, the quad, `t_max`, and the interval's ends.
struct Case<V: Vector> {
    ray: Ray<V>,
    quad: Quad<V>,
    t_max: S<V>,
    lo: S<V>,
    hi: S<V>,
}

impl Check for QuadCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let case = match input {
            Input::Raw(u) => Case {
                ray: raw::<Ray<V>>(u),
                quad: Quad::new(raw_vec(u), raw_vec(u), raw_vec(u), raw_vec(u)),
                t_max: raw::<S<V>>(u),
                lo: raw::<S<V>>(u),
                hi: raw::<S<V>>(u),
            },
            Input::Structured(src) => structured_case::<V>(src),
        };
        check(&case);
    }
}

/// A triangle case made a quad, and ends around its hit.
fn structured_case<V: Vector>(src: &mut Source) -> Case<V> {
    let generators = cases::triangles::generators::<V>();
    let (tri, ray, t_max) = (generators[src.index(generators.len())].2)(src);
    let [a, b, c] = corners(&tri);
    let d: [f64; 3] = core::array::from_fn(|i| {
        let opposite = a[i] + c[i] - b[i];
        if src.index(2) == 0 {
            opposite
        } else {
            // Folded: lifted off the plane by up to a tenth of the edge.
            opposite + 0.1 * (c[i] - a[i]) * src.range(-1.0, 1.0)
        }
    });
    let quad = Quad::new(
        tri.a,
        tri.b,
        tri.c,
        V::new(
            S::<V>::from_f64(d[0]),
            S::<V>::from_f64(d[1]),
            S::<V>::from_f64(d[2]),
        ),
    );
    let crossing = quad.hit(&ray, S::<V>::INFINITY).map(|h| h.t);
    let (lo, hi) = ends_near(src, crossing.as_slice());
    Case {
        ray,
        quad,
        t_max,
        lo,
        hi,
    }
}

/// The quad's hit from its triangles' (as the quad's documentation says):
/// the nearer, the first where they tie, `u`, `v` summed from the
/// barycentrics.
fn expected<F: Scalar>(
    first: Option<TriangleHit<F>>,
    second: Option<TriangleHit<F>>,
) -> Option<(F, F, F, rayhit::Side)> {
    let sum = |h: &TriangleHit<F>| {
        let s = h.u + h.v;
        if s < F::ONE { s } else { F::ONE }
    };
    let near = first.map(|h| (h.t, sum(&h), h.v, h.side));
    let far = second.map(|h| (h.t, h.u, sum(&h), h.side));
    match (near, far) {
        (Some(n), Some(f)) if f.0 < n.0 => Some(f),
        (None, f) => f,
        (n, _) => n,
    }
}

fn check_one<V: Vector>(
    case: &Case<V>,
    ray: &impl RayForm<V>,
    triangles: &[Triangle<V>; 2],
    search: Search<S<V>>,
) {
    let hit = case.quad.hit(ray, search);
    let want = expected(triangles[0].hit(ray, search), triangles[1].hit(ray, search));
    let got = hit.map(|h: QuadHit<S<V>>| (h.t, h.u, h.v, h.side));
    let same = match (got, want) {
        (Some(g), Some(w)) => {
            g.0.to_f64().to_bits() == w.0.to_f64().to_bits()
                && g.1.to_f64().to_bits() == w.1.to_f64().to_bits()
                && g.2.to_f64().to_bits() == w.2.to_f64().to_bits()
                && g.3 == w.3
        }
        (None, None) => true,
        _ => false,
    };
    assert!(
        same,
        "quad {:?} ray {:?} {search:?}: {got:?} against the triangles' {want:?}",
        case.quad, case.ray
    );
    assert_eq!(
        case.quad.occluded(ray, search),
        hit.is_some(),
        "{:?} {:?}",
        case.quad,
        case.ray
    );
    if let Some(h) = hit {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        assert!(
            h.t.is_finite() && h.u >= zero && h.u <= one && h.v >= zero && h.v <= one,
            "{h:?}"
        );
        let err = case.quad.hit_error(ray, &h);
        assert!(
            !(nan(err.t) || nan(err.u) || nan(err.v)),
            "{:?} {:?} {h:?} {err:?} {search:?}",
            case.quad,
            case.ray
        );
        // Safe to spawn from, where the triangles' precondition holds (as
        // the `triangle` target checks it for a triangle's hit).
        if triangles.iter().all(|t| precondition(&case.ray, t)) {
            let p = case.quad.surface_point(ray, &h);
            for dir in [case.ray.dir, -case.ray.dir, p.normal, -p.normal] {
                let spawned = p.spawn(dir);
                assert!(
                    !p.point.is_finite() || spawned.origin.is_finite(),
                    "{:?} {:?} {h:?} {p:?}",
                    case.quad,
                    case.ray
                );
            }
        }
    }
}

/// `x` is NaN.
fn nan<F: Scalar>(x: F) -> bool {
    x.to_f64().is_nan()
}

fn check<V: Vector>(case: &Case<V>) {
    let triangles = case.quad.triangles();
    let prepared = PreparedRay::new(&case.ray);
    let mut searches: Vec<Search<S<V>>> = Vec::new();
    for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
        searches.push((case.t_max, rule).into());
        if let Some(w) = Interval::new(case.lo, case.hi) {
            searches.push((w, rule).into());
        }
    }
    for &search in &searches {
        check_one(case, &case.ray, &triangles, search);
        check_one(case, &prepared, &triangles, search);
    }
}
