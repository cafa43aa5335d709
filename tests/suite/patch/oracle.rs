//! The patch test against exact arithmetic, in `f32` and `f64`.
//!
//! Cases: non-planar patches (a square of side `s`, `1e-3` to `1e3`, in
//! any orientation, its corners raised off its plane by up to `0.4 s`
//! each, some of them folded as seen from the ray), centred up to `1e5`
//! from the origin; rays aimed at a point `P(u0, v0)` with `(u0, v0)` in
//! `[-0.1, 1.1]^2`, from `1` to `100` sizes away in any direction, or a
//! quarter of the time nearly along the patch (the corpus's generator,
//! `rayhit_testkit::cases::patches::twisted`).
//!
//! The exact crossing near a hit is found by Newton's method in big
//! rationals (`G(u, v, t) = P(u, v) - o - t d = 0`, three steps from the
//! hit, its residual checked). For every hit whose bound is finite (on a
//! patch whose rounded corners did not collapse an edge: that one is its
//! triangle, held by `degenerate.rs` and the triangle's tests), `t`, `u`
//! and `v` are within it of that crossing; the surface point is
//! within its bound of the exact `P(u, v)` at the reported `(u, v)`, its
//! normal within its bound of the exact `dP/du x dP/dv`. A ray aimed at a
//! point well inside the patch (`(u0, v0)` in `[0.1, 0.9]^2`, its exact
//! crossing there too) is hit, and `rayhit::exact::ray_patch` finds it,
//! with the same side and within the bounds. Rays spawned from every hit (reflected,
//! and continuing through) meet the patch again within a thousandth of
//! its size only where the exact crossing there is in front of their
//! origin (a curved patch may rise above the tangent plane the origin was
//! moved off; the crossing left behind is never reported). The textbook test
//! (Reshetov's formulas, `t > 0`, rays continued from the unmoved point
//! `o + t d`) on the same rays: its misses and self-hits print.

use rayhit::exact::Rational;
use rayhit::exact::num_traits::{Signed, Zero};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Patch, Ray, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::patches::twisted;
use rayhit_testkit::source::Source;

use super::reshetov;
use crate::common::draw::S;
use crate::sphere::q;

type R = Rational;

fn rv<V: Vector>(p: V) -> [R; 3] {
    [q(p.x()), q(p.y()), q(p.z())]
}

fn lerp(a: &R, b: &R, w: &R) -> R {
    a + (b - a) * w
}

/// `P(u, v)` of the exact corners.
fn at(c: &[[R; 3]; 4], u: &R, v: &R) -> [R; 3] {
    [0, 1, 2].map(|k| {
        lerp(
            &lerp(&c[0][k], &c[1][k], u),
            &lerp(&c[2][k], &c[3][k], u),
            v,
        )
    })
}

fn d_du(c: &[[R; 3]; 4], v: &R) -> [R; 3] {
    [0, 1, 2].map(|k| lerp(&(&c[1][k] - &c[0][k]), &(&c[3][k] - &c[2][k]), v))
}

fn d_dv(c: &[[R; 3]; 4], u: &R) -> [R; 3] {
    [0, 1, 2].map(|k| lerp(&(&c[2][k] - &c[0][k]), &(&c[3][k] - &c[1][k]), u))
}

fn det3(a: &[R; 3], b: &[R; 3], c: &[R; 3]) -> R {
    &a[0] * (&b[1] * &c[2] - &b[2] * &c[1]) - &a[1] * (&b[0] * &c[2] - &b[2] * &c[0])
        + &a[2] * (&b[0] * &c[1] - &b[1] * &c[0])
}

/// `x` on the grid of `2^-160` (so that Newton's iterates stay small).
fn snap(x: R) -> R {
    let grid = R::from_integer(rayhit::exact::num_bigint::BigInt::from(1) << 160);
    (x * &grid).round() / grid
}

/// Newton's method on `P(u, v) - o - t d` from `(u, v, t)`: up to eight
/// steps (each iterate snapped to a fine grid), or `None` where the
/// Jacobian is singular or the steps do not shrink below `1e-24` (no
/// convergence).
fn newton(c: &[[R; 3]; 4], o: &[R; 3], d: &[R; 3], start: [R; 3]) -> Option<[R; 3]> {
    let [mut u, mut v, mut t] = start;
    let mut last = R::zero();
    let tiny = R::new(1.into(), 10u64.pow(12).into()).pow(2);
    for _ in 0..8 {
        let p = at(c, &u, &v);
        let g: [R; 3] = [0, 1, 2].map(|k| &p[k] - &o[k] - &t * &d[k]);
        let (pu, pv) = (d_du(c, &v), d_dv(c, &u));
        let nd: [R; 3] = [0, 1, 2].map(|k| -&d[k]);
        let det = det3(&pu, &pv, &nd);
        if det.is_zero() {
            return None;
        }
        let ng: [R; 3] = [0, 1, 2].map(|k| -&g[k]);
        let du = det3(&ng, &pv, &nd) / &det;
        let dv = det3(&pu, &ng, &nd) / &det;
        let dt = det3(&pu, &pv, &ng) / &det;
        last = du.abs() + dv.abs() + dt.abs() / (t.abs() + R::from_integer(1.into()));
        u = snap(u + du);
        v = snap(v + dv);
        t = snap(t + dt);
        if last < tiny {
            break;
        }
    }
    // Converged: the last step far below any bound checked against it.
    (last < tiny).then_some([u, v, t])
}

/// The rounded point `P(w)` a case aims at.
fn target_of<V: Vector>(patch: &Patch<V>, w: [f64; 2]) -> V {
    patch.point_at(S::<V>::from_f64(w[0]), S::<V>::from_f64(w[1]))
}

#[derive(Debug, Default)]
struct Counts {
    hits: usize,
    certified: usize,
    aimed_inside: usize,
    spawned: usize,
    near_again: usize,
    collapsed: usize,
    from_surface_hits: usize,
    textbook_misses_inside: usize,
    textbook_self_hits: usize,
}

fn within(x: f64, exact: &R, err: f64) -> bool {
    let x = rayhit::exact::oracle::r(x).expect("finite");
    (x - exact).abs() <= rayhit::exact::oracle::r(err).expect("finite")
}

fn run<V: Vector>(seed: u64) -> Counts {
    let mut src = Source::seeded(seed);
    let mut n = Counts::default();
    let inf = S::<V>::INFINITY;
    for _ in 0..case_count(500) {
        let (patch, ray, w) = twisted::<V>(&mut src);
        if !ray.is_valid() {
            continue;
        }
        let c = [patch.p00, patch.p10, patch.p01, patch.p11].map(rv);
        let (o, d) = (rv(ray.origin), rv(ray.dir));
        let size = (patch.p11 - patch.p00).length().to_f64();
        let hit = patch.hit(&ray, inf);
        // Aimed well inside, with the exact crossing there too: a hit.
        let inside = (0.1..=0.9).contains(&w[0]) && (0.1..=0.9).contains(&w[1]);
        let guess = [
            q(S::<V>::from_f64(w[0])),
            q(S::<V>::from_f64(w[1])),
            q(S::<V>::ONE),
        ];
        let exact_aim = newton(&c, &o, &d, guess);
        let aim_inside = inside
            && exact_aim.as_ref().is_some_and(|e| {
                let (lo, hi) = (R::new(1.into(), 20.into()), R::new(19.into(), 20.into()));
                e[0] >= lo && e[0] <= hi && e[1] >= lo && e[1] <= hi && e[2].is_positive()
            });
        if aim_inside {
            n.aimed_inside += 1;
            assert!(hit.is_some(), "aimed inside, missed: {patch:?} {ray:?}");
            // The exact module agrees: a hit, its t, u, v (rounded to
            // nearest) within the kernel's bounds plus half an ulp.
            let e = rayhit::exact::ray_patch(&ray, &patch, inf).expect("an exact hit");
            let h = hit.expect("a hit");
            let err = patch.hit_error(&ray, &h);
            let half_ulp = |x: S<V>| (x.next_up() - x).to_f64();
            let near = |a: S<V>, b: S<V>, bound: S<V>| {
                (a.to_f64() - b.to_f64()).abs() <= bound.to_f64() + half_ulp(b)
            };
            assert_eq!(e.side, h.side, "{patch:?} {ray:?}");
            assert!(
                near(h.t, e.t, err.t) && near(h.u, e.u, err.u) && near(h.v, e.v, err.v),
                "{h:?} {err:?} exact {e:?}: {patch:?} {ray:?}"
            );
            let zero = S::<V>::ZERO;
            if reshetov(&ray, &patch, zero, inf).is_none() {
                n.textbook_misses_inside += 1;
            }
        }
        // From a point of the patch (rounded, so within rounding of the
        // surface on either side): a hit must be a crossing ahead in exact
        // arithmetic (`t > 0` decided conservatively).
        let from = Ray::new(target_of(&patch, w), ray.dir);
        if let Some(h) = patch.hit(&from, inf) {
            n.from_surface_hits += 1;
            let e = newton(&c, &rv(from.origin), &d, [q(h.u), q(h.v), q(h.t)]);
            assert!(
                e.as_ref().is_none_or(|e| e[2].is_positive()),
                "from the surface, behind: {from:?} {patch:?} {h:?} {e:?}"
            );
        }
        let Some(h) = hit else { continue };
        n.hits += 1;
        assert!(h.t > S::<V>::ZERO && h.t.is_finite(), "{h:?}");
        let err = patch.hit_error(&ray, &h);
        // (A patch whose rounded corners collapsed an edge is its
        // triangle, with the triangle's hit and bounds: the triangle's
        // tests and `degenerate.rs` hold those. At the triangle's apex the
        // bilinear map Newton's method solves here is singular.)
        let Patch { p00, p10, p01, p11 } = patch;
        let collapsed = p10 == p00 || p11 == p10 || p11 == p01 || p01 == p00;
        n.collapsed += usize::from(collapsed);
        if err.t.is_finite() && !collapsed {
            n.certified += 1;
            let start = [q(h.u), q(h.v), q(h.t)];
            let e = newton(&c, &o, &d, start)
                .unwrap_or_else(|| panic!("no convergence: {h:?} {err:?} {patch:?} {ray:?}"));
            let f = |x: S<V>| x.to_f64();
            assert!(
                within(f(h.t), &e[2], f(err.t)),
                "t {h:?} {err:?} {patch:?} {ray:?}"
            );
            assert!(
                within(f(h.u), &e[0], f(err.u)),
                "u {h:?} {err:?} {patch:?} {ray:?}"
            );
            assert!(
                within(f(h.v), &e[1], f(err.v)),
                "v {h:?} {err:?} {patch:?} {ray:?}"
            );
        }
        // The surface point and normal against the exact ones at (u, v).
        let sp = patch.surface_point(&ray, &h);
        let (uq, vq) = (q(h.u), q(h.v));
        let exact_p = at(&c, &uq, &vq);
        let (pu, pv) = (d_du(&c, &vq), d_dv(&c, &uq));
        let exact_n = [0, 1, 2].map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            &pu[j] * &pv[k] - &pu[k] * &pv[j]
        });
        let got = |x: V| [x.x(), x.y(), x.z()].map(|c| c.to_f64());
        let (p, pe, nn, ne) = (
            got(sp.point),
            got(sp.point_error),
            got(sp.normal),
            got(sp.normal_error),
        );
        // (Of a collapsed patch, the triangle's surface point, which the
        // triangle's tests hold.)
        for k in (0..3).filter(|_| !collapsed) {
            assert!(
                within(p[k], &exact_p[k], pe[k]),
                "point {k}: {sp:?} {patch:?} {h:?}"
            );
            assert!(
                within(nn[k], &exact_n[k], ne[k]),
                "normal {k}: {sp:?} {patch:?} {h:?}"
            );
        }
        // Spawned rays: reflected, and continuing through.
        let nrm = sp.normal;
        let dn = ray.dir.dot(nrm);
        let nn2 = nrm.dot(nrm);
        if !(nn2 > S::<V>::ZERO) {
            continue;
        }
        let reflected = ray.dir - nrm * (S::<V>::TWO * dn / nn2);
        let near = S::<V>::from_f64(1e-3 * size);
        for dir in [reflected, ray.dir] {
            let spawned = sp.spawn(dir);
            n.spawned += 1;
            // A hit near the new origin must be a crossing in front of it
            // in exact arithmetic (a curved patch can rise above the
            // tangent plane the origin was moved off), never the crossing
            // it left, which is behind it.
            let exact_t = |r: &Ray<V>, (u, v, t): (S<V>, S<V>, S<V>)| {
                newton(&c, &rv(r.origin), &rv(r.dir), [q(u), q(v), q(t)]).map(|e| e[2].clone())
            };
            if let Some(again) = patch.hit(&spawned, inf)
                && again.t * spawned.dir.length() <= near
            {
                n.near_again += 1;
                let t = exact_t(&spawned, (again.u, again.v, again.t));
                assert!(
                    t.as_ref().is_some_and(Signed::is_positive),
                    "self-hit: {spawned:?} {patch:?} {h:?} {again:?}, exact t {t:?}"
                );
            }
            // The textbook way: from the unmoved point, t > 0.
            let from = Ray::new(ray.at(h.t), dir);
            if let Some((t, u, v)) = reshetov(&from, &patch, S::<V>::ZERO, inf)
                && t * dir.length() <= near
                && !exact_t(&from, (u, v, t)).is_some_and(|t| t.is_positive())
            {
                n.textbook_self_hits += 1;
            }
        }
    }
    n
}

#[test]
fn patch_hits_within_their_bounds_of_exact_crossings() {
    for (name, n) in [("f32", run::<Vec3>(81)), ("f64", run::<DVec3>(82))] {
        println!("{name}: {n:?}");
        assert!(
            n.hits > 250 && n.certified > n.hits / 2 && n.aimed_inside > 150,
            "{n:?}"
        );
    }
}
