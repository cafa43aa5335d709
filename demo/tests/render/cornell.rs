//! The `cornell` scene: no ray from inside leaves the box between two
//! walls, rayhit's `Quad` against the textbook quad ("The Next Week") on
//! the same rays; no shadow segment is
//! blocked by the surface it starts on or by the light it ends on; and the
//! render is finite, with the light seen where it is.

use rayhit::glam::Vec3;
use rayhit::{Intersect, Quad, Ray};
use rayhit_demo::cornell::{CornellScene, cornell_scene, render_cornell};
use rayhit_demo::renderer::Rng;

use crate::common::{HEIGHT, WIDTH};

/// The textbook ray/quad test ("The Next Week"), `t` in `(0.001, inf)`.
fn textbook(ray: &Ray, quad: &Quad) -> bool {
    let (q, u, v) = (quad.a, quad.b - quad.a, quad.d - quad.a);
    let n = u.cross(v);
    let normal = n.normalize();
    let denom = normal.dot(ray.dir);
    if denom.abs() < 1e-8 {
        return false;
    }
    let t = (normal.dot(q) - normal.dot(ray.origin)) / denom;
    if t.is_nan() || t <= 0.001 {
        return false;
    }
    let w = n / n.dot(n);
    let p = ray.at(t) - q;
    let (alpha, beta) = (w.dot(p.cross(v)), w.dot(u.cross(p)));
    (0.0..=1.0).contains(&alpha) && (0.0..=1.0).contains(&beta)
}

/// Every corner, edge midpoint and centre of the walls and the light, and
/// points along each diagonal: where rays slip between quads if any can.
/// (Not the blocks': a ray at a block's corner may pass it, and out of the
/// open side.)
fn targets(scene: &CornellScene) -> Vec<Vec3> {
    let mut out = Vec::new();
    for f in scene.faces.iter().filter(|f| f.name != "block") {
        let q = f.quad;
        let mid = |a: Vec3, b: Vec3| (a + b) * 0.5;
        out.extend([q.a, q.b, q.c, q.d]);
        out.extend([mid(q.a, q.b), mid(q.b, q.c), mid(q.c, q.d), mid(q.d, q.a)]);
        for w in [0.1, 0.37, 0.5, 0.81] {
            out.push(q.a + (q.c - q.a) * w);
        }
    }
    out
}

#[test]
fn no_ray_slips_between_quads() {
    let scene = cornell_scene(WIDTH, HEIGHT);
    // Inside the box, above the blocks (the tall one is 330 high) and
    // below the light.
    let mut rng = Rng::new(3);
    let starts: Vec<Vec3> = (0..32)
        .map(|_| {
            let mut c = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
            Vec3::new(c(20.0, 535.0), c(340.0, 540.0), c(20.0, 535.0))
        })
        .collect();
    let (mut rays, mut leaks, mut textbook_leaks) = (0, 0, 0);
    for start in starts {
        for target in targets(&scene) {
            // The open side is z = 0: a target on it may be passed by.
            if target.z <= 0.0 {
                continue;
            }
            let ray = Ray::new(start, target - start);
            rays += 1;
            leaks += usize::from(scene.nearest(&ray, f32::INFINITY).is_none());
            textbook_leaks += usize::from(!scene.faces.iter().any(|f| textbook(&ray, &f.quad)));
        }
    }
    println!(
        "{rays} rays from inside at edges and corners: rayhit {leaks} leaks, textbook {textbook_leaks}"
    );
    assert!(rays > 1500, "{rays}");
    assert_eq!(leaks, 0);
}

#[test]
fn shadow_segments_are_not_blocked_by_their_ends() {
    let scene = cornell_scene(WIDTH, HEIGHT);
    let light = scene.faces[scene.light].quad;
    let mut rng = Rng::new(7);
    let (mut segments, mut blocked_by_ends) = (0, 0);
    for (i, f) in scene.faces.iter().enumerate() {
        if i == scene.light {
            continue;
        }
        for k in 0..200 {
            // Points inside, on the edges and at the corners of the face.
            let (u, v) = match k % 4 {
                0 | 1 => (rng.next_f32(), rng.next_f32()),
                2 => (rng.next_f32(), 0.0),
                _ => (1.0, 1.0),
            };
            let x = f.quad.surface_point_at(u, v);
            let y = scene.light_sample(&mut rng);
            let Some((ray, segment)) = x.spawn_to(&y) else {
                continue;
            };
            segments += 1;
            let ends = f.quad.occluded(&ray, segment) || light.occluded(&ray, segment);
            blocked_by_ends += usize::from(ends);
        }
    }
    println!("{segments} segments, {blocked_by_ends} blocked by their own ends");
    assert!(segments > 2000, "{segments}");
    assert_eq!(blocked_by_ends, 0);
}

#[test]
fn the_render_is_finite_and_sees_the_light() {
    let scene = cornell_scene(WIDTH, HEIGHT);
    let (pixels, [rays, segments]) = render_cornell(&scene, 2, &|| {});
    assert!(
        pixels
            .iter()
            .all(|p| p.is_finite() && p.min_element() >= 0.0)
    );
    assert!(rays > 0 && segments > u64::from(WIDTH * HEIGHT));
    // The ray from the eye to the light's centre meets the light first.
    let light = scene.faces[scene.light].quad;
    let centre = (light.a + light.c) * 0.5;
    let eye = rayhit::Camera::ray(&scene.camera, rayhit::CameraSample::new(0.5, 0.5)).origin;
    let hit = scene
        .nearest(&Ray::new(eye, centre - eye), f32::INFINITY)
        .expect("a hit");
    assert_eq!(hit.face, scene.light);
}
