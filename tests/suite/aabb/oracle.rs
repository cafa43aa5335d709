//! The box kernels against the exact oracle (see `common::oracle`): the
//! slab test (`ray_aabb`) and the naive face test (`Aabb::clip_by_faces`)
//! on every box generator of the test kit (`rayhit_testkit::cases::boxes`):
//! rays through box edges and corners, axis-parallel rays on slab planes,
//! rays in face planes, grazing rays, tiny and `-0.0` direction
//! components, scenes far from the origin, tiny and huge boxes. Asserted:
//! no false miss of the slab test; the rest is tallied.
//!
//! `cargo test --test suite aabb::oracle::` runs 10,000 cases per generator
//! and precision; the long run, 1,000,000 per generator:
//! `cargo test --release --test suite aabb::oracle:: -- --ignored --nocapture`.

use crate::common::oracle::{DEFAULT_CASES, Tally, long, precision, report};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, Ray, Scalar, Vector, ray_aabb};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::boxes::{self, BoxCase};
use rayhit_testkit::oracle::{self, R, r};
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

/// How far a ray passes from a box it misses (or how deep it goes into one
/// it hits), in ulps of the largest coordinate (see `oracle::box_gap`).
fn box_gap_ulps<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: S<V>) -> f64 {
    rayhit::exact::distance_ulps(&rayhit::exact::Case::Box(*ray, *b, t_max))
}

fn run_boxes<V: Vector>(name: &str, seed: u64, n: usize, generator: fn(&mut Source) -> BoxCase<V>) {
    let mut rng = Source::seeded(seed);
    let (mut slab, mut naive) = (Tally::default(), Tally::default());
    let mut beyond_range = 0usize;
    for i in 0..n {
        let (b, ray, t_max) = generator(&mut rng);
        if !(ray.is_valid() && b.is_valid()) {
            continue;
        }
        let interval = oracle::box_interval(&ray, &b, t_max);
        // The documented precondition: exact distances below MAX / 2. Beyond
        // it a hit cannot be reported in this precision, and a direction
        // component below 1/MAX (whose reciprocal overflows) can make the
        // slab test report a "hit" that exact arithmetic places beyond MAX.
        let half_max = r(S::<V>::MAX) / R::from_integer(2.into());
        if oracle::box_raw(&ray, &b, t_max).is_some_and(|(e, x)| e > half_max || x > half_max) {
            beyond_range += 1;
            continue;
        }
        let exact = interval.is_some();
        let got = ray_aabb(&ray, &b, t_max);
        slab.record(got.is_some(), exact, || box_gap_ulps(&ray, &b, t_max));
        naive.record(b.clip_by_faces(&ray, t_max).is_some(), exact, || {
            box_gap_ulps(&ray, &b, t_max)
        });
        assert!(
            got.is_some() || !exact,
            "{name} case {i}: slab false miss for {ray:?} {b:?} t_max {t_max:?}"
        );
    }
    report(
        precision::<V>(),
        name,
        &[("slab", &slab), ("naive", &naive)],
    );
    if beyond_range > 0 {
        println!(
            "{:>3} {name:<22} {beyond_range} cases with an exact entry or exit beyond MAX / 2 left out (precondition)",
            precision::<V>()
        );
    }
}

fn all_boxes<V: Vector>(n: usize) {
    for (name, seed, generator) in boxes::generators::<V>() {
        run_boxes::<V>(name, seed, n, generator);
    }
}

#[test]
fn boxes_f32() {
    all_boxes::<Vec3>(case_count(DEFAULT_CASES));
}

#[test]
fn boxes_f64() {
    all_boxes::<DVec3>(case_count(DEFAULT_CASES));
}

#[test]
#[ignore = "long: cargo test --release --test suite aabb::oracle:: -- --ignored --nocapture"]
fn long_boxes() {
    long(all_boxes::<Vec3>, all_boxes::<DVec3>);
}
