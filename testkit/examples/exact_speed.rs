//! How fast `rayhit::exact` decides and judges cases (the figures quoted in
//! its module docs): `cargo run --release -p rayhit-testkit --features fuzz
//! --example exact_speed`. Single thread, wall time of each loop on a quiet
//! machine, on the oracle suite's case families.

use std::time::Instant;

use rayhit::Vector;
use rayhit::exact::{self, Case, Claim};
use rayhit::glam::{DVec3, Vec3};
use rayhit_testkit::cases::{boxes, planes, triangles};
use rayhit_testkit::source::Source;

fn rate(n: usize, start: Instant) -> f64 {
    n as f64 / start.elapsed().as_secs_f64()
}

fn measure<V: Vector>(precision: &str, n: usize) {
    let mut src = Source::seeded(1);
    let boxes: Vec<_> = boxes::generators::<V>()
        .iter()
        .flat_map(|(_, _, g)| (0..n / 8).map(|_| g(&mut src)).collect::<Vec<_>>())
        .collect();
    let tris: Vec<_> = triangles::generators::<V>()
        .iter()
        .flat_map(|(_, _, g)| (0..n / 6).map(|_| g(&mut src)).collect::<Vec<_>>())
        .collect();
    let planes: Vec<_> = (0..n).map(|_| planes::plane::<V>(&mut src)).collect();

    let s = Instant::now();
    let hits = boxes
        .iter()
        .filter(|(b, r, t)| exact::ray_aabb(r, b, *t).is_some())
        .count();
    let box_decide = rate(boxes.len(), s);
    let s = Instant::now();
    for (b, r, t) in &boxes {
        let _ = exact::judge(&Case::Box(*r, *b, *t), &Claim::<V::Scalar>::Miss, 4.0);
    }
    let box_judge = rate(boxes.len(), s);

    let s = Instant::now();
    let _ = tris
        .iter()
        .filter(|(tri, r, t)| exact::ray_triangle(r, tri, *t).is_some())
        .count();
    let tri_decide = rate(tris.len(), s);
    let s = Instant::now();
    for (tri, r, t) in &tris {
        let _ = exact::judge(
            &Case::Triangle(*r, *tri, *t),
            &Claim::<V::Scalar>::Miss,
            4.0,
        );
    }
    let tri_judge = rate(tris.len(), s);

    let s = Instant::now();
    let _ = planes
        .iter()
        .filter(|(p, r, t)| exact::ray_plane(r, p, *t).is_some())
        .count();
    let plane_decide = rate(planes.len(), s);
    let s = Instant::now();
    for (p, r, t) in &planes {
        let _ = exact::judge(&Case::Plane(*r, *p, *t), &Claim::<V::Scalar>::Miss, 4.0);
    }
    let plane_judge = rate(planes.len(), s);
    println!(
        "{precision}: cases/s decide (judge): box {box_decide:.0} ({box_judge:.0}), triangle {tri_decide:.0} ({tri_judge:.0}), plane {plane_decide:.0} ({plane_judge:.0}); {hits} box hits"
    );
}

fn main() {
    measure::<Vec3>("f32", 24_000);
    measure::<DVec3>("f64", 24_000);
}
