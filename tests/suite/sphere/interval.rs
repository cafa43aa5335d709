//! The interval form of the sphere test (`Sphere::hit` over an interval,
//! on a `Ray` and on a `PreparedRay`) held to exact arithmetic, in `f32`
//! and `f64`.
//!
//! For every case of every kind (see the module's documentation) and
//! every window `(lo, hi]` with ends among 0, both crossings rounded and
//! two ulps either side, and a few fixed values: the answer is the exact
//! verdict (the entry where the exact `t-` is in the window, else the exit
//! where `t+` is, else none; compared in big rationals), the reported `t`
//! is finite, in the window and within `max(hit_error, succ(lo) - lo)` of
//! the exact crossing, and a prepared ray gives the same answer bit for
//! bit. Ends placed on the rounded crossings are where the error bound's
//! filter leaves the decision to the exact signs.
//!
//! 100 cases per kind and precision, times `RAYHIT_CASES`.

use super::{Kind, case, exact, verdict, within};
use crate::common::window::{ends, step};
use rayhit::exact::Rational;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Interval, PreparedRay, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

/// The crossings in `f64` (the textbook formula: only to place windows
/// near them; the exact comparison decides).
fn approx<V: Vector>(ray: &rayhit::Ray<V>, s: &rayhit::Sphere<V>) -> Vec<Rational> {
    let w = |v: V| [v.x().to_f64(), v.y().to_f64(), v.z().to_f64()];
    let (o, d, c) = (w(ray.origin), w(ray.dir), w(s.center));
    let f = [c[0] - o[0], c[1] - o[1], c[2] - o[2]];
    let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let (a, b) = (dot(d, d), dot(d, f));
    let r = s.radius.to_f64();
    let disc = b * b - a * (dot(f, f) - r * r);
    let root = disc.max(0.0).sqrt();
    [(b - root) / a, (b + root) / a]
        .into_iter()
        .filter(|t| t.is_finite() && *t > 0.0)
        .filter_map(Rational::from_float)
        .collect()
}

fn check<V: Vector>(seed: u64) {
    let mut rng = Pcg32::new(seed);
    let (mut windows, mut hits) = (0, 0);
    for kind in [Kind::Aimed, Kind::Grazing, Kind::Inside] {
        for _ in 0..case_count(100) {
            let (ray, s) = case::<V>(&mut rng, kind);
            let e = exact(&ray, &s);
            let prepared = PreparedRay::new(&ray);
            let cuts = ends::<V>(&mut rng, &approx(&ray, &s));
            for (i, &lo) in cuts.iter().enumerate() {
                for &hi in &cuts[i..] {
                    let window = Interval::new(lo, hi).unwrap();
                    let got = s.hit(&ray, window);
                    assert_eq!(got, s.hit(&prepared, window));
                    assert_eq!(
                        got.map(|h| h.side),
                        verdict(&e, lo, hi),
                        "({lo:?}, {hi:?}]: {got:?} {ray:?} {s:?}"
                    );
                    windows += 1;
                    if let Some(h) = got {
                        hits += 1;
                        assert!(
                            h.t > lo && h.t <= hi && h.t.is_finite(),
                            "{h:?} ({lo:?}, {hi:?}]"
                        );
                        let err = s.hit_error(&ray, &h);
                        let ulp = step(lo, 1) - lo;
                        let err = if err > ulp { err } else { ulp };
                        assert!(within(&e, h.side, h.t, err), "{h:?} {err:?} {ray:?} {s:?}");
                    }
                }
            }
        }
    }
    eprintln!("{windows} windows, {hits} hits");
    assert!(hits > windows / 10, "{hits} of {windows}");
}

#[test]
fn windows_against_exact_f32() {
    check::<Vec3>(31);
}

#[test]
fn windows_against_exact_f64() {
    check::<DVec3>(32);
}
