//! The `spheres` scene: camera rays aimed at every sphere, from the ground
//! of radius `1e4` to droplets of radius `5e-4`, and the rays leaving each
//! hit (towards the sun, reflected, refracted in, and out again), traced
//! with rayhit and with the textbook kernel ("One Weekend", `t > 0.001`,
//! new rays from the unmoved point). Each ray's fate is judged against the
//! scene's geometry, decided exactly:
//!
//! - a *false miss*: a camera ray that misses a sphere, asked about it
//!   alone, which its exact line meets ahead (a ring on a sphere's rim);
//! - a *hole*: a ray refracted into a sphere that does not find that
//!   sphere's far side next;
//! - *acne*: a ray leaving a sphere outwards (towards the sun, reflected,
//!   refracted out) whose first hit is the sphere it left.
//!
//! Rayhit has neither, and its new rays are checked in exact arithmetic
//! too: a ray leaving outwards starts exactly outside its ball and its line
//! meets the ball nowhere ahead; a ray refracted in starts exactly inside.
//! The textbook shows both: the ground and the moon, ten thousand units
//! out, shadow themselves, and the droplets, shorter than `0.001` inside,
//! have no far side.

use std::cmp::Ordering;
use std::collections::BTreeMap;

use rayhit::exact::num_traits::Zero;
use rayhit::exact::oracle::{R, sphere as exact_sphere};
use rayhit::glam::Vec3;
use rayhit::{Camera, Ray, Side};
use rayhit_demo::spheres::{Hit, Kernel, Look, SphereScene, render_spheres, sphere_scene};

use crate::common::{HEIGHT, WIDTH};

/// What one kernel did with the scene's rays.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Fates {
    /// Camera rays traced.
    camera: usize,
    /// Rays leaving a sphere outwards.
    leaving: usize,
    /// Rays refracted into a sphere.
    entering: usize,
    /// Camera rays and spheres they miss that their exact lines meet ahead.
    false_misses: usize,
    /// Rays into a sphere that did not find its far side.
    no_far_side: usize,
    /// Rays leaving a sphere whose first hit was that sphere.
    self_hits: usize,
}

impl Fates {
    fn add(self, o: Fates) -> Fates {
        Fates {
            camera: self.camera + o.camera,
            leaving: self.leaving + o.leaving,
            entering: self.entering + o.entering,
            false_misses: self.false_misses + o.false_misses,
            no_far_side: self.no_far_side + o.no_far_side,
            self_hits: self.self_hits + o.self_hits,
        }
    }
}

/// The camera rays: every pixel centre, and rays from the eye aimed at
/// points of every sphere's disc as the eye sees it (the centre, rings out
/// to a ten-thousandth of the radius from the rim, and the rim itself).
fn camera_rays(scene: &SphereScene) -> Vec<Ray> {
    let camera = &scene.camera;
    let mut rays = Vec::new();
    for j in 0..camera.height() {
        for i in 0..camera.width() {
            rays.push(camera.pixel_ray(i, j));
        }
    }
    let eye = camera.eye();
    for ball in &scene.balls[1..] {
        let (c, r) = (ball.sphere.center, ball.sphere.radius);
        let (s1, s2) = (c - eye).normalize().any_orthonormal_pair();
        for rho in [0.0, 0.5, 0.9, 0.99, 0.9999, 1.0] {
            for k in 0..12 {
                let phi = k as f32 * std::f32::consts::TAU / 12.0 + 0.1;
                let p = c + (s1 * phi.cos() + s2 * phi.sin()) * (r * rho);
                rays.push(Ray::new(eye, p - eye));
            }
        }
    }
    rays
}

/// The exact line of `ray` against ball `ball`.
fn exact(scene: &SphereScene, ray: &Ray, ball: usize) -> rayhit::exact::oracle::ExactSphere {
    let s = scene.balls[ball].sphere;
    exact_sphere(ray, s.center, s.radius).expect("finite rays and spheres")
}

/// Whether the exact line of `ray` meets ball `ball` at some `t > 0`.
fn meets_ahead(scene: &SphereScene, ray: &Ray, ball: usize) -> bool {
    exact(scene, ray, ball).exit_cmp(&R::zero()) == Some(Ordering::Greater)
}

/// The unit direction of `dir` refracted through `normal` (facing `dir`)
/// with index ratio `eta`, or reflected where it cannot pass.
fn bend(dir: Vec3, normal: Vec3, eta: f32) -> Vec3 {
    let d = dir.normalize();
    let refracted = d.refract(normal, eta);
    if refracted == Vec3::ZERO {
        d.reflect(normal)
    } else {
        refracted
    }
}

/// The scene's rays with `kernel`, every fate counted by the name of the
/// sphere the camera ray hit (`sky` for none); with rayhit, the new rays'
/// origins and lines are also checked exactly (panicking on a failure).
fn trace(kernel: Kernel) -> BTreeMap<&'static str, Fates> {
    let scene = sphere_scene(WIDTH, HEIGHT, kernel);
    let checked = kernel == Kernel::Rayhit;
    let mut by_name = BTreeMap::<&'static str, Fates>::new();
    // A ray leaving `hit` outwards along `dir`.
    let leave_out = |fates: &mut Fates, hit: &Hit, dir: Vec3| {
        let ray = scene.leave(hit, dir);
        fates.leaving += 1;
        if scene
            .nearest(&ray, f32::INFINITY)
            .is_some_and(|h| h.ball == hit.ball)
        {
            fates.self_hits += 1;
        }
        if checked {
            let line = exact(&scene, &ray, hit.ball);
            assert!(
                line.q(&R::zero()) > R::zero(),
                "{ray:?} starts in ball {}",
                hit.ball
            );
            assert!(
                !meets_ahead(&scene, &ray, hit.ball),
                "{ray:?} meets ball {}",
                hit.ball
            );
        }
    };
    // A ray refracted into the ball at `hit` along `dir`: the far side it
    // finds.
    let enter = |fates: &mut Fates, hit: &Hit, dir: Vec3| -> Option<Hit> {
        let ray = scene.leave(hit, dir);
        fates.entering += 1;
        if checked {
            let line = exact(&scene, &ray, hit.ball);
            assert!(
                line.q(&R::zero()) < R::zero(),
                "{ray:?} starts outside ball {}",
                hit.ball
            );
        }
        match scene.nearest(&ray, f32::INFINITY) {
            Some(far) if far.ball == hit.ball && far.side == Side::Back => Some(far),
            _ => {
                fates.no_far_side += 1;
                None
            }
        }
    };
    for ray in camera_rays(&scene) {
        let first = scene.nearest(&ray, f32::INFINITY);
        let name = first.map_or("sky", |h| scene.balls[h.ball].name);
        let fates = by_name.entry(name).or_default();
        fates.camera += 1;
        for b in 0..scene.balls.len() {
            if scene.test(&ray, b, f32::INFINITY).is_none() && meets_ahead(&scene, &ray, b) {
                fates.false_misses += 1;
            }
        }
        let Some(hit) = first else { continue };
        // The eye is outside every ball: the first crossing is an entry.
        if checked {
            assert_eq!(hit.side, Side::Front, "{ray:?}");
        }
        let n = hit.outward;
        leave_out(fates, &hit, ray.dir.reflect(n));
        if n.dot(scene.sun) > 0.0 {
            leave_out(fates, &hit, scene.sun);
        }
        // Every sphere is treated as glass here, whatever it looks like.
        let ior = match scene.balls[hit.ball].look {
            Look::Glass(ior) => ior,
            _ => 1.5,
        };
        let inward = bend(ray.dir, n, 1.0 / ior);
        if let Some(far) = enter(fates, &hit, inward) {
            // Out through the far side, or reflected back inside.
            let out = bend(inward, -far.outward, ior);
            if out.dot(far.outward) > 0.0 {
                leave_out(fates, &far, out);
            } else {
                enter(fates, &far, out);
            }
        }
    }
    by_name
}

#[test]
fn rayhit_leaves_no_acne_and_no_holes_where_the_textbook_shows_both() {
    let kernels = [Kernel::Rayhit, Kernel::Textbook].map(|k| (k, trace(k)));
    println!(
        "| kernel | first hit | camera rays | false misses | rays in | no far side | \
         rays out | self-hits |"
    );
    println!("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    let [ours, textbook] = kernels.each_ref().map(|(kernel, by_name)| {
        let total = by_name.values().fold(Fates::default(), |a, &b| a.add(b));
        for (name, f) in by_name.iter().chain([(&"all", &total)]) {
            println!(
                "| {kernel:?} | {name} | {} | {} | {} | {} | {} | {} |",
                f.camera, f.false_misses, f.entering, f.no_far_side, f.leaving, f.self_hits
            );
        }
        total
    });
    assert_eq!(
        (ours.false_misses, ours.no_far_side, ours.self_hits),
        (0, 0, 0),
        "{ours:?}"
    );
    // Enough of each kind of ray for the zeros to mean something.
    assert!(
        ours.camera > 3000 && ours.entering > 1500 && ours.leaving > 4000,
        "{ours:?}"
    );
    // The textbook shows both failures on the same scene.
    assert!(textbook.self_hits > 0, "no acne: {textbook:?}");
    assert!(textbook.no_far_side > 0, "no holes: {textbook:?}");
}

#[test]
fn the_render_is_finite_and_each_droplet_is_seen() {
    let scene = sphere_scene(WIDTH, HEIGHT, Kernel::Rayhit);
    let (pixels, rays) = render_spheres(&scene, 2, &|| {});
    assert_eq!(pixels.len(), (WIDTH * HEIGHT) as usize);
    assert!(rays >= 2 * u64::from(WIDTH * HEIGHT));
    assert!(
        pixels
            .iter()
            .all(|p| p.is_finite() && p.min_element() >= 0.0)
    );
    // Each droplet's centre, seen from the eye, is in the picture and the
    // ray to it meets the droplet first.
    let eye = scene.camera.eye();
    for (index, ball) in scene.balls.iter().enumerate() {
        if ball.name != "droplet" {
            continue;
        }
        let ray = Ray::new(eye, ball.sphere.center - eye);
        let hit = scene
            .nearest(&ray, f32::INFINITY)
            .expect("the droplet is hit");
        assert_eq!(hit.ball, index);
        // In the picture: its raster position by the pinhole model.
        let (cam, d) = (&scene.camera, ray.dir);
        let depth = d.dot(cam.forward());
        let x = cam.width() as f32 / 2.0 + cam.focal_length() * d.dot(cam.right()) / depth;
        let y = cam.height() as f32 / 2.0 - cam.focal_length() * d.dot(cam.up()) / depth;
        assert!(depth > 0.0 && (0.0..cam.width() as f32).contains(&x), "{x}");
        assert!((0.0..cam.height() as f32).contains(&y), "{y}");
    }
}
