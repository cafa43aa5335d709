//! The patch oracle against its rational formulas: the integer path's
//! crossings against `Q(sqrt(D))` arithmetic written out, and [`Surd`]'s
//! comparisons against rational ones.

use super::super::tests::grid;
use super::super::values::*;
use super::*;
use crate::testing::Draws;
use crate::{Ray, Scalar, Vector};
use glam::{DVec3, Vec3};
use num_traits::{Signed, Zero};

use std::vec::Vec;

type S3 = [Surd; 3];

fn lift(v: &R3, d: &R) -> S3 {
    [0, 1, 2].map(|k| Surd::rational(v[k].clone(), d))
}

fn s_cross(a: &S3, b: &S3) -> S3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].clone() * b[k].clone() - a[k].clone() * b[j].clone()
    })
}

fn s_dot(a: &S3, b: &S3) -> Surd {
    a[0].clone() * b[0].clone() + a[1].clone() * b[1].clone() + a[2].clone() * b[2].clone()
}

/// `patch`'s rational formulas as they read before they were computed in
/// integers (every operation a big rational one; the roots rational where
/// the discriminant is a square): the reference it is held to.
fn patch_reference<V: Vector>(ray: &Ray<V>, patch: &crate::Patch<V>) -> Option<Vec<PatchCrossing>> {
    use core::cmp::Ordering;
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    if d.iter().all(Zero::is_zero) {
        return None;
    }
    let [p00, p10, p01, p11] = [patch.p00, patch.p10, patch.p01, patch.p11].map(rv);
    let (p00, p10, p01, p11) = (p00?, p10?, p01?, p11?);
    let w0 = sub(&p00, &o);
    let g = sub(&p10, &p00);
    let e0 = sub(&p01, &p00);
    let k = sub(&sub(&p11, &p10), &e0);
    let (w0d, gd) = (cross(&w0, &d), cross(&g, &d));
    let a = dot(&gd, &k);
    let b = dot(&w0d, &k) + dot(&gd, &e0);
    let c = dot(&w0d, &e0);
    let zero = R::zero();
    let roots: Vec<Surd> = if a.is_zero() {
        if b.is_zero() {
            Vec::new()
        } else {
            std::vec![Surd::rational(-c / b, &zero)]
        }
    } else {
        let disc = &b * &b - int(4) * &a * &c;
        if disc.is_negative() {
            return Some(Vec::new());
        }
        let p = -&b / (int(2) * &a);
        let (n, m) = (disc.numer().sqrt(), disc.denom().sqrt());
        if disc.is_zero() {
            std::vec![Surd::rational(p, &zero)]
        } else if &n * &n == *disc.numer() && &m * &m == *disc.denom() {
            let step = R::new(n, m) / (int(2) * &a);
            std::vec![
                Surd::rational(&p - &step, &zero),
                Surd::rational(p + step, &zero)
            ]
        } else {
            let q = int(1) / (int(2) * &a);
            std::vec![
                Surd {
                    p: p.clone(),
                    q: -q.clone(),
                    d: disc.clone()
                },
                Surd { p, q, d: disc },
            ]
        }
    };
    let mut crossings = Vec::new();
    for u in roots {
        let dd = u.d.clone();
        let one = int(1);
        let out = |x: &Surd| {
            x.cmp_rational(&zero) == Ordering::Less || x.cmp_rational(&one) == Ordering::Greater
        };
        if out(&u) {
            continue;
        }
        let lerp3 = |a: &R3, b: &R3| -> S3 {
            let (a, b) = (lift(a, &dd), lift(b, &dd));
            [0, 1, 2].map(|i| a[i].clone() + u.clone() * (b[i].clone() - a[i].clone()))
        };
        let (at_a, at_b) = (lerp3(&p00, &p10), lerp3(&p01, &p11));
        let (os, ds) = (lift(&o, &dd), lift(&d, &dd));
        let w: S3 = [0, 1, 2].map(|i| at_a[i].clone() - os[i].clone());
        let e: S3 = [0, 1, 2].map(|i| at_b[i].clone() - at_a[i].clone());
        let n = s_cross(&ds, &e);
        let nn = s_dot(&n, &n);
        let (v, t) = if nn.sign() == Ordering::Equal {
            let point = e.iter().all(|x| x.sign() == Ordering::Equal);
            let wd = s_cross(&w, &ds);
            if !(point && wd.iter().all(|x| x.sign() == Ordering::Equal)) {
                continue;
            }
            let dd2 = s_dot(&ds, &ds);
            let inv = Surd::rational(int(1) / &dd2.p, &dd);
            (Surd::rational(zero.clone(), &dd), s_dot(&w, &ds) * inv)
        } else {
            let conj = Surd {
                p: nn.p.clone(),
                q: -nn.q.clone(),
                d: dd.clone(),
            };
            let norm = (nn.clone() * conj.clone()).p;
            let inv = Surd {
                p: &conj.p / &norm,
                q: &conj.q / &norm,
                d: dd.clone(),
            };
            (
                s_dot(&s_cross(&w, &ds), &n) * inv.clone(),
                s_dot(&s_cross(&w, &e), &n) * inv,
            )
        };
        if out(&v) {
            continue;
        }
        let du: S3 = {
            let (g0, g1) = (lift(&g, &dd), lift(&sub(&p11, &p01), &dd));
            [0, 1, 2].map(|i| g0[i].clone() + v.clone() * (g1[i].clone() - g0[i].clone()))
        };
        let dv: S3 = {
            let (h0, h1) = (lift(&e0, &dd), lift(&sub(&p11, &p10), &dd));
            [0, 1, 2].map(|i| h0[i].clone() + u.clone() * (h1[i].clone() - h0[i].clone()))
        };
        let side = if s_dot(&ds, &s_cross(&du, &dv)).sign() == Ordering::Greater {
            crate::Side::Back
        } else {
            crate::Side::Front
        };
        crossings.push(PatchCrossing { u, v, t, side });
    }
    Some(crossings)
}

/// Whether two numbers of `Q(sqrt(d))`, written over radicands that
/// differ by a rational square factor (or are zero), are equal.
fn same_surd(a: &Surd, b: &Surd) -> bool {
    let rational = |x: &Surd| x.d.is_zero() || x.q.is_zero();
    match (rational(a), rational(b)) {
        (true, true) => a.p == b.p,
        (false, false) => {
            let ratio = &a.d / &b.d;
            let (n, m) = (ratio.numer().sqrt(), ratio.denom().sqrt());
            let square = &n * &n == *ratio.numer() && &m * &m == *ratio.denom();
            square && a.p == b.p && &a.q * R::new(n, m) == b.q
        }
        _ => false,
    }
}

/// `oracle::patch`, computed in integers, gives the rational formulas'
/// crossings (the same `u`, `v`, `t` and side, in the same order up to
/// the sort by `t`) on grid patches (exact zeros, collapsed edges, whose
/// quadratic's roots are rational and once made the conjugate's norm
/// zero, parallelograms, rulings parallel to the ray) and on wide ones,
/// in both precisions; and `patch_extended` holds them among its own.
#[test]
fn patch_crossings_are_the_rational_formulas() {
    fn check<V: Vector>(g: &mut Draws, kind: u64) -> usize {
        let v = |p: [f64; 3]| {
            V::new(
                V::Scalar::from_f64(p[0]),
                V::Scalar::from_f64(p[1]),
                V::Scalar::from_f64(p[2]),
            )
        };
        let point = |g: &mut Draws| match kind {
            0 => v([grid(g), grid(g), grid(g)]),
            _ => v([g.coordinate(40), g.coordinate(40), g.coordinate(40)]),
        };
        let ray = Ray::new(point(g), point(g));
        let mut c: [V; 4] = [0; 4].map(|_| point(g));
        match g.next() % 6 {
            0 => c[1] = c[0],
            1 => c[3] = c[1],
            2 => c[3] = c[2],
            3 => c[2] = c[0],
            4 => c[3] = c[1] + c[2] - c[0],
            _ => {}
        }
        let p = crate::Patch::new(c[0], c[1], c[2], c[3]);
        let (Some(got), Some(want)) = (patch(&ray, &p), patch_reference(&ray, &p)) else {
            assert!(patch(&ray, &p).is_none() && patch_reference(&ray, &p).is_none());
            return 0;
        };
        assert_eq!(got.crossings.len(), want.len(), "{ray:?} {p:?}");
        let matches = |x: &PatchCrossing, y: &PatchCrossing| {
            same_surd(&x.u, &y.u)
                && same_surd(&x.v, &y.v)
                && same_surd(&x.t, &y.t)
                && x.side == y.side
        };
        for w in &want {
            assert!(
                got.crossings.iter().any(|x| matches(x, w)),
                "{ray:?} {p:?}: {got:?} {want:?}"
            );
        }
        let extended = patch_extended(&ray, &p).expect("finite");
        for x in &got.crossings {
            assert!(
                extended.crossings.iter().any(|y| matches(x, y)),
                "{ray:?} {p:?}"
            );
        }
        want.len()
    }
    let mut g = Draws(0x7a7c_4e11_95d3_2f01);
    let mut crossings = 0;
    for i in 0..1200 {
        crossings += check::<Vec3>(&mut g, i % 2);
        crossings += check::<DVec3>(&mut g, i % 2);
    }
    assert!(crossings > 200, "{crossings}");
}

/// `Surd`'s signs and comparisons, made in integers on rationals that
/// need not be reduced (one shared denominator or two), against the same
/// questions asked in reduced rationals (`p - x` and the squares `p^2`,
/// `q^2 d`); and its estimate within a few ulps of the correctly rounded
/// value even where `p` and `q sqrt(d)` nearly cancel.
#[test]
fn surd_comparisons_are_the_rational_ones() {
    use core::cmp::Ordering;
    let reference = |s: &Surd, x: &R| {
        let p = &s.p - x;
        let (sp, sq) = (p.cmp(&R::zero()), s.q.cmp(&R::zero()));
        if sq == Ordering::Equal || s.d.is_zero() || sp == Ordering::Equal || sp == sq {
            return if sq == Ordering::Equal || s.d.is_zero() {
                sp
            } else {
                sq
            };
        }
        match (&p * &p).cmp(&(&s.q * &s.q * &s.d)) {
            Ordering::Greater => sp,
            Ordering::Less => sq,
            Ordering::Equal => Ordering::Equal,
        }
    };
    let mut g = Draws(0x51d0_c0de_1357_9bdf);
    let small = |g: &mut Draws| (g.next() % 2001) as i64 - 1000;
    let mut cancelled = 0;
    for i in 0..4000 {
        let den = (g.next() % 97 + 1) as i64;
        let raw = |n: i64, m: i64| R::new_raw(n.into(), m.into());
        let d = if i % 3 == 0 {
            let k = small(&mut g);
            int(k * k)
        } else {
            int(small(&mut g).abs())
        };
        // Two numbers, the second with p about -q sqrt(d) (cancelling).
        let q = raw(small(&mut g), den);
        let near = -(crate::exact::oracle::to_f64(&q) * crate::exact::oracle::to_f64(&d).sqrt());
        let p_close = R::from_float(near).unwrap_or_default() + raw(small(&mut g), 1 << 40);
        for p in [
            raw(small(&mut g), if i % 2 == 0 { den } else { den + 1 }),
            p_close,
        ] {
            let s = Surd {
                p,
                q: q.clone(),
                d: d.clone(),
            };
            for x in [R::zero(), raw(small(&mut g), den), raw(small(&mut g), 7)] {
                assert_eq!(s.cmp_rational(&x), reference(&s, &x), "{s:?} {x:?}");
            }
            assert_eq!(s.sign(), reference(&s, &R::zero()), "{s:?}");
            if s.sign() == Ordering::Greater {
                let exact: f64 = PatchCrossing::rounded(&s);
                let est = s.to_f64();
                let ulps = (est - exact).abs() / (exact.next_up() - exact);
                assert!(ulps <= 4.0, "{s:?}: {est} against {exact}");
                cancelled += usize::from(est < 1e-6 * crate::exact::oracle::to_f64(&s.p).abs());
            }
        }
    }
    assert!(cancelled > 100, "{cancelled}");
}
