//! The face a ray enters a box through, against exact arithmetic.
//!
//! The face `Aabb::hit` reports must be one whose plane the exact ray
//! crosses at the exact entry distance (the largest of the entry planes'
//! distances, over the axes the ray moves along, when it is positive),
//! the lowest such axis where several tie (edges and corners), and none
//! when the exact entry is at `t <= 0`. Every box generator of the oracle
//! suite, both precisions; rays aimed at every face; and properties. (The
//! ray spawned from the face point is `surface::properties`'s, the faces
//! of a batch's lanes `batch::face`'s.)

use crate::common::props::config;
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Aabb, BoxFace, Intersect, PreparedRay, Ray, Scalar, Vector, ray_aabb};
use rayhit_testkit::case_count;
use rayhit_testkit::cases;
use rayhit_testkit::cases::boxes;
use rayhit_testkit::oracle;
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

/// Every generator, both precisions: the face of every hit is the exact
/// one, the interval is `ray_aabb`'s bit for bit, and the prepared form
/// and the entry face of `Aabb::hit` with an infinite `t_max` agree.
fn check_generators<V: Vector>(cases: usize) -> (usize, usize, usize) {
    let (mut hits, mut faces, mut ties) = (0, 0, 0);
    for (name, seed, generate) in boxes::generators::<V>() {
        let mut rng = Source::seeded(seed ^ 0xface);
        for _ in 0..cases {
            let (aabb, ray, t_max) = generate(&mut rng);
            let got = aabb.hit(&ray, t_max);
            assert_eq!(
                got.map(|h| (h.enter, h.exit)),
                ray_aabb(&ray, &aabb, t_max),
                "{name}"
            );
            let prepared = PreparedRay::new(&ray);
            assert_eq!(aabb.hit(&prepared, t_max), got, "{name}");
            assert_eq!(
                got.and_then(|_| aabb.hit(&prepared, S::<V>::INFINITY).and_then(|h| h.face)),
                got.and_then(|h| h.face),
                "{name}"
            );
            let Some(hit) = got else { continue };
            hits += 1;
            let (expected, tie) = oracle::box_face(&ray, &aabb);
            assert_eq!(hit.face, expected, "{name}: {ray:?} {aabb:?}");
            faces += usize::from(expected.is_some());
            ties += usize::from(tie);
            // No face exactly when the reported entry is 0: the sign of the
            // exact entry is decided exactly.
            assert_eq!(
                hit.face.is_none(),
                hit.enter == S::<V>::ZERO,
                "{name}: {ray:?} {aabb:?}"
            );
        }
    }
    (hits, faces, ties)
}

#[test]
fn faces_are_exact_on_every_generator_f32() {
    let (hits, faces, ties) = check_generators::<Vec3>(case_count(5_000));
    assert!(
        hits > 15_000 && faces > 10_000 && ties > 100,
        "{hits} {faces} {ties}"
    );
}

#[test]
fn faces_are_exact_on_every_generator_f64() {
    let (hits, faces, ties) = check_generators::<DVec3>(case_count(5_000));
    assert!(
        hits > 15_000 && faces > 10_000 && ties > 100,
        "{hits} {faces} {ties}"
    );
}

/// Rays from outside aimed at a point of each face (inside the face, on its
/// edges and at its corners) report that face, or, at an edge or corner,
/// the lowest axis among the faces that meet there.
fn every_face_is_reported<V: Vector>() {
    let mut rng = Source::seeded(77);
    let mut seen = [0usize; 6];
    for _ in 0..case_count(3_000) {
        let (lo, hi) = boxes::grid_box(&mut rng);
        let aabb = boxes::to_box::<V>(lo, hi);
        let face = BoxFace::new(rng.below(3) as usize, rng.below(2) == 1).expect("axis < 3");
        let k = face.axis();
        // A point of the face: inside it, or on its border.
        let mut target = [0.0; 3];
        for i in 0..3 {
            let u = match rng.below(4) {
                0 => 0.0,
                1 => 1.0,
                _ => rng.unit(),
            };
            target[i] = lo[i] + (hi[i] - lo[i]) * u;
        }
        target[k] = if face.is_max() { hi[k] } else { lo[k] };
        let target = cases::v::<V>(target);
        // From outside the face's side, within 60 degrees of its normal.
        let n: V = face.normal();
        let mut dir = cases::v::<V>(rng.direction());
        if dir.dot(n) > S::<V>::ZERO {
            dir = -dir;
        }
        let dir = dir - n * S::<V>::from_f64(2.0);
        let origin = target - dir * S::<V>::from_f64(3.0);
        let ray = Ray::new(origin, target - origin);
        let Some(hit) = aabb.hit(&ray, S::<V>::INFINITY) else {
            // A target rounded off a grazing corner can miss; the exact
            // oracle says so.
            assert!(oracle::box_interval(&ray, &aabb, S::<V>::INFINITY).is_none());
            continue;
        };
        let (expected, _) = oracle::box_face(&ray, &aabb);
        assert_eq!(hit.face, expected, "{ray:?} {aabb:?}");
        if let Some(f) = hit.face {
            seen[f as usize] += 1;
        }
    }
    assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
}

#[test]
fn every_face_is_reported_f32() {
    every_face_is_reported::<Vec3>();
}

#[test]
fn every_face_is_reported_f64() {
    every_face_is_reported::<DVec3>();
}

/// The face and its normal, per face.
#[test]
fn faces_name_their_axis_side_normal_and_plane() {
    let b = Aabb::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 5.0, 6.0));
    let all = [
        (BoxFace::MinX, 0, false, -Vec3::X, 1.0),
        (BoxFace::MaxX, 0, true, Vec3::X, 4.0),
        (BoxFace::MinY, 1, false, -Vec3::Y, 2.0),
        (BoxFace::MaxY, 1, true, Vec3::Y, 5.0),
        (BoxFace::MinZ, 2, false, -Vec3::Z, 3.0),
        (BoxFace::MaxZ, 2, true, Vec3::Z, 6.0),
    ];
    for (f, axis, max, normal, plane) in all {
        assert_eq!(
            (f.axis(), f.is_max(), f.normal::<Vec3>(), f.plane(&b)),
            (axis, max, normal, plane)
        );
        assert_eq!(BoxFace::new(axis, max), Some(f));
    }
    assert_eq!(BoxFace::new(3, false), None);
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn face_is_exact_f32((aabb, ray) in strat::aabb_and_ray::<Vec3>()) {
        if let Some(hit) = aabb.hit(&ray, f32::INFINITY) {
            prop_assert_eq!(hit.face, oracle::box_face(&ray, &aabb).0);
        }
    }

    #[test]
    fn face_is_exact_f64((aabb, ray) in strat::aabb_and_ray::<DVec3>()) {
        if let Some(hit) = aabb.hit(&ray, f64::INFINITY) {
            prop_assert_eq!(hit.face, oracle::box_face(&ray, &aabb).0);
        }
    }
}

/// Invalid input: no hit, no face, no panic.
#[test]
fn invalid_input_has_no_face() {
    let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let ok = Ray::new(Vec3::splat(-1.0), Vec3::ONE);
    for (ray, aabb) in [
        (Ray::new(Vec3::NAN, Vec3::ONE), b),
        (Ray::new(Vec3::ZERO, Vec3::ZERO), b),
        (ok, Aabb::new(Vec3::ONE, Vec3::ZERO)),
        (ok, Aabb::new(Vec3::ZERO, Vec3::INFINITY)),
    ] {
        assert_eq!(aabb.hit(&ray, f32::INFINITY), None);
        assert_eq!(
            aabb.hit(&PreparedRay::new(&ray), f32::INFINITY)
                .and_then(|h| h.face),
            None
        );
    }
    assert_eq!(b.hit(&ok, f32::NAN), None);
    assert_eq!(b.hit(&ok, -1.0), None);
    // The exact sign comparison in a case the fast comparison cannot
    // decide: distances differing in the last bit.
    let near = 1.0f32;
    let ray = Ray::new(
        Vec3::new(-near, -near.next_up(), 0.5),
        Vec3::new(1.0, 1.0, 0.0),
    );
    assert_eq!(b.hit(&ray, 10.0).and_then(|h| h.face), Some(BoxFace::MinY));
    let _ = <f32 as Scalar>::ONE;
}
