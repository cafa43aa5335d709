//! One quad at a time against exact arithmetic: parallelograms and planar
//! convex quads at scales `1e-3` to `1e3` and offsets to `1e5`, rays aimed
//! at their interiors, edges, corners and diagonals from a few to a few
//! hundred sizes away (the corpus's generator,
//! `rayhit_testkit::cases::quads::aimed_quad`).
//!
//! Every hit's `t`, `u` and `v` are within their bounds
//! ([`Surface::hit_error`]) of the exact crossing with one triangle's
//! plane and the exact `(u, v)` there (the triangle's exact barycentrics,
//! summed as the quad sums them); the quad's answer is its two triangles'
//! nearer, bit for bit; `rayhit::exact::ray_quad` is the nearer exact
//! crossing of the two, its `(u, v)` so summed; and on parallelograms the textbook test ("The
//! Next Week") is tallied beside it: its false misses and its `t` beyond
//! rayhit's bound.

use rayhit::exact::oracle::{R, triangle as exact_triangle};
use rayhit::exact::{Rational, rational};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{EdgeRule, Intersect, Interval, PreparedRay, Scalar, Surface, TriangleHit, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::quads::aimed_quad;
use rayhit_testkit::source::Source;

use super::textbook;
use crate::common::draw::S;

/// Cases per precision, times `RAYHIT_CASES`.
const CASES: usize = 1_500;

/// The `t` of the nearer of two triangle hits, as the quad reports it.
fn nearer_t<F: PartialOrd + Copy>(pair: [Option<TriangleHit<F>>; 2]) -> Option<F> {
    match pair {
        [Some(a), Some(b)] => Some(if b.t < a.t { b.t } else { a.t }),
        [a, b] => a.or(b).map(|h| h.t),
    }
}

/// `|x - y| <= bound`, exactly.
fn within(x: &Rational, y: &R, bound: &Rational) -> bool {
    let d = x - y;
    let d = if d < Rational::from_integer(0.into()) {
        -d
    } else {
        d
    };
    d <= *bound
}

fn check<V: Vector>() -> [usize; 5] {
    let mut src = Source::seeded(0x5155_4144 + S::<V>::UNIT_ROUNDOFF.to_f64().to_bits() % 97);
    let inf = S::<V>::INFINITY;
    let (mut hits, mut parallelograms, mut exact_parallelogram_hits) = (0, 0, 0);
    let (mut textbook_misses, mut textbook_far, mut unbounded) = (0, 0, 0);
    let r = |x: S<V>| rational(x).expect("finite");
    for k in 0..case_count(CASES) {
        let parallelogram = k.is_multiple_of(2);
        let (quad, ray) = aimed_quad::<V>(&mut src, parallelogram);
        let [first, second] = quad.triangles();
        let hit = quad.hit(&ray, inf);
        // The two triangles' nearer, ties to the first.
        let expected = nearer_t([first.hit(&ray, inf), second.hit(&ray, inf)]);
        assert_eq!(hit.map(|h| h.t), expected, "{quad:?} {ray:?}");
        // Every form of the ray and both rules give the triangles' answer.
        let prepared = PreparedRay::new(&ray);
        assert_eq!(quad.hit(&prepared, inf), hit, "{quad:?} {ray:?}");
        for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
            let expected = nearer_t([first.hit(&ray, (inf, rule)), second.hit(&ray, (inf, rule))]);
            assert_eq!(quad.hit(&prepared, (inf, rule)).map(|h| h.t), expected);
            let window = Interval::up_to(inf).expect("valid");
            let expected = nearer_t([
                first.hit(&ray, (window, rule)),
                second.hit(&ray, (window, rule)),
            ]);
            assert_eq!(quad.hit(&ray, (window, rule)).map(|h| h.t), expected);
        }
        let exact = [first, second].map(|tri| exact_triangle(&ray, &tri).expect("finite"));
        // `exact::ray_quad` is the nearer of the two exact crossings, its
        // (u, v) summed as the quad sums them.
        let answer = rayhit::exact::ray_quad(&ray, &quad, inf);
        let ahead: Vec<(usize, &R)> = (0..2)
            .filter(|&i| exact[i].hits(&None))
            .filter_map(|i| exact[i].t.as_ref().map(|t| (i, t)))
            .collect();
        let nearest = ahead
            .iter()
            .fold(None, |m: Option<(usize, &R)>, &(i, t)| match m {
                Some((_, mt)) if mt <= t => m,
                _ => Some((i, t)),
            });
        assert_eq!(answer.is_some(), nearest.is_some(), "{quad:?} {ray:?}");
        if let (Some(a), Some((i, t))) = (&answer, nearest) {
            let (b, c) = exact[i].uv.clone().expect("a crossing has weights");
            let (u, v) = if i == 0 {
                (&b + &c, c)
            } else {
                (b.clone(), &b + &c)
            };
            assert!(
                a.t.value == *t && a.u.value == u && a.v.value == v,
                "{quad:?} {ray:?}"
            );
        }
        if let Some(h) = hit {
            hits += 1;
            let err = quad.hit_error(&ray, &h);
            // (Infinite where the triangle's determinant's sign is not
            // known: a ray within rounding of parallel to it.)
            if !(err.t.is_finite() && err.u.is_finite() && err.v.is_finite()) {
                unbounded += 1;
                continue;
            }
            // One triangle's exact crossing and (u, v) is within the bounds.
            let fits = exact.iter().enumerate().any(|(i, e)| {
                let (Some(t), Some((b, c))) = (&e.t, &e.uv) else {
                    return false;
                };
                let (u, v) = if i == 0 {
                    (b + c, c.clone())
                } else {
                    (b.clone(), b + c)
                };
                within(&r(h.t), t, &r(err.t))
                    && within(&r(h.u), &u, &r(err.u))
                    && within(&r(h.v), &v, &r(err.v))
            });
            assert!(fits, "{quad:?} {ray:?} {h:?} {err:?}");
            assert!(h.u >= S::<V>::ZERO && h.u <= S::<V>::ONE, "{h:?}");
            assert!(h.v >= S::<V>::ZERO && h.v <= S::<V>::ONE, "{h:?}");
        }
        if parallelogram {
            parallelograms += 1;
            let exact_hit = exact.iter().any(|e| e.hits(&None));
            exact_parallelogram_hits += usize::from(exact_hit);
            match textbook(&ray, &quad, S::<V>::ZERO, inf) {
                None if exact_hit => textbook_misses += 1,
                Some(t) => {
                    let far = exact.iter().filter(|e| e.line_hits()).all(|e| {
                        let bound = hit.map_or(inf, |h| quad.hit_error(&ray, &h).t);
                        bound.is_finite()
                            && e.t.as_ref().is_none_or(|x| !within(&r(t), x, &r(bound)))
                    });
                    textbook_far += usize::from(far && hit.is_some());
                }
                None => {}
            }
        }
    }
    println!(
        "{}: {hits} hits judged ({unbounded} with infinite bounds); parallelograms {parallelograms} ({exact_parallelogram_hits} \
         hit exactly): textbook false misses {textbook_misses}, textbook t beyond rayhit's \
         bound {textbook_far}",
        if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
            "f32"
        } else {
            "f64"
        }
    );
    assert!(
        unbounded * 100 <= hits,
        "{unbounded} of {hits} hits unbounded"
    );
    [
        hits,
        parallelograms,
        exact_parallelogram_hits,
        textbook_misses,
        textbook_far,
    ]
}

#[test]
fn hits_are_within_their_bounds_of_the_exact_crossing() {
    let [hits, _, exact_hits, ..] = check::<Vec3>();
    // Most rays aimed at a quad hit it (the others pass by a corner or an
    // edge by a rounding).
    assert!(hits > case_count(CASES) / 2 && exact_hits > case_count(CASES) / 4);
    let [hits, ..] = check::<DVec3>();
    assert!(hits > case_count(CASES) / 2);
}
