//! The patch's metamorphic properties, on the oracle suite's cases (and
//! rays from points of the patch), in `f32` and `f64`:
//!
//! - scaling every position (corners and origin) by `2^k` and the
//!   direction by `2^j` scales `t` by `2^(k - j)` and leaves `u`, `v` and
//!   the side unchanged, bit for bit, and the bounds scale alike (every
//!   step of the test and of its certificate is exact under such a
//!   scaling, away from underflow and overflow), with both edge rules;
//! - consecutive intervals: splitting `(0, inf]` at a float `a` (around
//!   the hit, anywhere, or tiny), the hit over the whole is the hit over
//!   `(0, a]` if there is one, else the hit over `(a, inf]`, bit for bit,
//!   misses included; and where the ray meets the
//!   patch twice, the second crossing is the hit over `(t1, t_max]`;
//! - a prepared ray gives the plain ray's answers, bit for bit.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{EdgeRule, Intersect, Interval, Patch, PreparedRay, Ray, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::patches::twisted;
use rayhit_testkit::source::Source;

use crate::common::draw::S;

fn scaled<V: Vector>(p: &Patch<V>, s: S<V>) -> Patch<V> {
    Patch::new(p.p00 * s, p.p10 * s, p.p01 * s, p.p11 * s)
}

fn pow2<F: Scalar>(k: i32) -> F {
    F::from_f64(2f64.powi(k))
}

fn run<V: Vector>(seed: u64) -> (usize, usize) {
    let mut src = Source::seeded(seed);
    let inf = S::<V>::INFINITY;
    let (mut hits, mut twice) = (0, 0);
    for _ in 0..case_count(2000) {
        let (patch, ray, w) = twisted::<V>(&mut src);
        // Half the time from a point of the patch itself.
        let ray = if src.below(2) == 0 {
            Ray::new(
                patch.point_at(S::<V>::from_f64(w[0]), S::<V>::from_f64(w[1])),
                ray.dir,
            )
        } else {
            ray
        };
        if !ray.is_valid() {
            continue;
        }
        let (k, j) = (src.below(21) as i32 - 10, src.below(21) as i32 - 10);
        let (sk, sj) = (pow2::<S<V>>(k), pow2::<S<V>>(j));
        let big = scaled(&patch, sk);
        let moved = Ray::new(ray.origin * sk, ray.dir * sj);
        for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
            let a = patch.hit(&ray, (inf, rule));
            let b = big.hit(&moved, (inf, rule));
            let expect = a.map(|h| (h.t * pow2::<S<V>>(k - j), h.u, h.v, h.side));
            assert_eq!(
                b.map(|h| (h.t, h.u, h.v, h.side)),
                expect,
                "{rule:?} 2^{k} 2^{j}: {patch:?} {ray:?}"
            );
            if let (Some(a), Some(b)) = (a, b) {
                let (ea, eb) = (patch.hit_error(&ray, &a), big.hit_error(&moved, &b));
                assert_eq!(eb.t, ea.t * pow2::<S<V>>(k - j), "{patch:?} {ray:?}");
                assert_eq!((eb.u, eb.v), (ea.u, ea.v), "{patch:?} {ray:?}");
            }
            let prepared = PreparedRay::new(&ray);
            assert_eq!(patch.hit(&prepared, (inf, rule)), a, "{patch:?} {ray:?}");
        }
        // A split point among the floats around the hit, anywhere, or
        // tiny (below a crossing rounding leaves too near the origin).
        let first = patch.hit(&ray, inf);
        let tiny = S::<V>::from_f64(10f64.powf(-3.0 - 12.0 * src.unit()));
        let a = match (first, src.below(5)) {
            (Some(h), 0) => h.t,
            (Some(h), 1) => h.t.next_down(),
            (Some(h), 2) => h.t * S::<V>::HALF,
            (Some(h), 3) => h.t * S::<V>::from_f64(1.0 + 3.0 * src.unit()),
            _ => tiny,
        };
        let low = patch.hit(&ray, Interval::new(S::<V>::ZERO, a).expect("valid"));
        let high = patch.hit(&ray, Interval::new(a, inf).expect("valid"));
        assert_eq!(low.or(high), first, "split at {a:?}: {patch:?} {ray:?}");
        let Some(first) = first else {
            continue;
        };
        hits += 1;
        if let Some(second) = patch.hit(&ray, Interval::new(first.t, inf).expect("valid")) {
            twice += 1;
            assert!(second.t > first.t, "{patch:?} {ray:?}");
        }
    }
    (hits, twice)
}

#[test]
fn scaling_by_powers_of_two_intervals_and_prepared_rays() {
    for (name, (hits, twice)) in [("f32", run::<Vec3>(91)), ("f64", run::<DVec3>(92))] {
        println!("{name}: {hits} hits, {twice} rays meeting a patch twice");
        assert!(hits > 500, "{hits}");
    }
}
