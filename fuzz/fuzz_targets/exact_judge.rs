#![no_main]
use libfuzzer_sys::fuzz_target;
use rayhit::exact::{self, Band, Case, Claim, Verdict};
use rayhit::glam::Vec3;
use rayhit::{Ray, Triangle};

/// The kernel under test (yours here): textbook Moller-Trumbore, two-sided.
fn my_ray_triangle(o: Vec3, d: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, f32)> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let (s, inv) = (o - a, 1.0 / det);
    let q = s.cross(e1);
    let (u, v, t) = (s.dot(p) * inv, d.dot(q) * inv, e2.dot(q) * inv);
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

// Coordinates on a grid of 1/64 within +-512: the scene scale the kernel is
// meant for (raw float bits would also feed it overflows and underflows).
fuzz_target!(|grid: [i16; 15]| {
    let p = |i: usize| Vec3::new(grid[i] as f32, grid[i + 1] as f32, grid[i + 2] as f32) / 64.0;
    let (ray, tri) = (Ray::new(p(0), p(3)), Triangle::new(p(6), p(9), p(12)));
    let claim = match my_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c) {
        Some((t, u, v)) => Claim::Triangle { t, u, v },
        None => Claim::Miss,
    };
    let j = exact::judge(
        &Case::Triangle(ray, tri, f32::INFINITY),
        &claim,
        f64::INFINITY,
    );
    // Outside the rounding band, hit or miss must be exactly right.
    assert!(
        j.band == Band::Edge || j.verdict == Verdict::Right,
        "{ray:?} {tri:?}: {j:?}"
    );
});
