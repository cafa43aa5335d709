//! The `demo` scene: the centre pixel sees the sphere placed there, a pixel
//! aimed above everything sees the sky, a ground point in a box's shadow
//! is darker than one in the open, more samples per pixel keep the centre
//! rays, rays leaving the ground or a box never hit it again, and the
//! checker filtered over each pixel's footprint is the box average and
//! removes the moire that point sampling shows.

use rayhit::glam::Vec3;
use rayhit::{Aabb, Camera, PinholeCamera, Ray, ray_aabb, ray_plane};
use rayhit_demo::demo::{Scene, Shape, demo_scene, render};
use rayhit_demo::renderer::{self, sky};

use crate::common::{HEIGHT, WIDTH, luminance};

/// The pixel whose square contains the image of `p`, by the camera model
/// (raster `(0, 0)` top-left, `y` down, pixel centres at `+0.5`).
fn project(camera: &PinholeCamera, p: Vec3) -> (u32, u32) {
    let d = p - camera.eye();
    let depth = d.dot(camera.forward());
    assert!(depth > 0.0, "{p} is behind the camera");
    let f = camera.focal_length();
    let x = camera.width() as f32 / 2.0 + f * d.dot(camera.right()) / depth;
    let y = camera.height() as f32 / 2.0 - f * d.dot(camera.up()) / depth;
    assert!(
        x >= 0.0 && y >= 0.0 && x < camera.width() as f32 && y < camera.height() as f32,
        "{p} is outside the image"
    );
    (x as u32, y as u32)
}

fn object(scene: &Scene, name: &str) -> usize {
    scene
        .objects
        .iter()
        .position(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object {name:?}"))
}

/// A box around each object except the ground plane.
fn bounds(scene: &Scene) -> Vec<Aabb> {
    scene
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::Plane(_) => None,
            Shape::Box(b) => Some(*b),
            Shape::Mesh(bvh) => {
                let p = &bvh.mesh.positions;
                let lo = p.iter().fold(Vec3::INFINITY, |a, &b| a.min(b));
                let hi = p.iter().fold(Vec3::NEG_INFINITY, |a, &b| a.max(b));
                Some(Aabb::new(lo, hi))
            }
        })
        .collect()
}

/// The centre and four edge directions of the sun's disc.
fn sun_directions(scene: &Scene) -> Vec<Vec3> {
    let (s1, s2) = scene.sun.any_orthonormal_pair();
    let r = scene.sun_radius;
    [Vec3::ZERO, s1 * r, -s1 * r, s2 * r, -s2 * r]
        .iter()
        .map(|&o| (scene.sun + o).normalize())
        .collect()
}

#[test]
fn the_centre_pixel_sees_the_sphere_placed_there() {
    let scene = demo_scene(WIDTH, HEIGHT);
    let (image, rays) = render(&scene, 1, &|| {});
    assert!(rays >= u64::from(WIDTH * HEIGHT));
    let sphere = object(&scene, "icosphere");
    let (i, j) = (WIDTH / 2, HEIGHT / 2);
    // The sphere of radius 1 at (0, 1, 0), which the icosphere approximates
    // to within 2% of the radius: the centre ray passes well inside it.
    let ray = scene.camera.pixel_ray(i, j);
    let to_centre = Vec3::new(0.0, 1.0, 0.0) - ray.origin;
    let miss_distance = (to_centre - ray.dir * to_centre.dot(ray.dir)).length();
    assert!(
        miss_distance < 0.5,
        "the centre ray passes {miss_distance} from the centre"
    );
    let k = (j * WIDTH + i) as usize;
    assert_eq!(image.seen[k], Some(sphere));
    // The sphere is red; its light, sun and sky, is near white.
    let c = image.pixels[k];
    assert!(
        c.x > 1.5 * c.y && c.x > 1.5 * c.z,
        "centre pixel {c} is not red"
    );
}

#[test]
fn a_pixel_aimed_above_everything_sees_the_sky() {
    let scene = demo_scene(WIDTH, HEIGHT);
    let (image, _) = render(&scene, 1, &|| {});
    let ray = scene.camera.pixel_ray(0, 0);
    // Upwards, so it cannot meet the ground, and clear of every object's box.
    assert!(ray.dir.y > 0.0);
    for b in bounds(&scene) {
        assert_eq!(ray_aabb(&ray, &b, f32::INFINITY), None);
    }
    assert_eq!(image.seen[0], None);
    assert_eq!(image.pixels[0], sky(ray.dir));
    assert!(image.pixels[0].z > image.pixels[0].x, "the sky is blue");
}

#[test]
fn the_shadow_of_a_box_is_darker_than_open_ground() {
    let scene = demo_scene(WIDTH, HEIGHT);
    let (image, _) = render(&scene, 1, &|| {});
    let ground = object(&scene, "ground");
    let Shape::Plane(plane) = scene.objects[ground].shape else {
        panic!("the ground is a plane")
    };
    let Shape::Box(blue) = scene.objects[object(&scene, "blue box")].shape else {
        panic!("the blue box is a box")
    };
    let boxes = bounds(&scene);
    // The light reaching the ground point a pixel's centre ray sees (the
    // pixel colour over the ground's albedo there, channel by channel), after checking that the
    // pixel sees the ground and that every direction of the sun's disc is
    // blocked by the blue box (`shadow`) or by nothing (open ground).
    let irradiance = |p: Vec3, shadow: bool| {
        let (i, j) = project(&scene.camera, p);
        let ray = scene.camera.pixel_ray(i, j);
        let t = ray_plane(&ray, &plane, f32::INFINITY).expect("the ray meets the ground");
        let q = ray.at(t);
        for dir in sun_directions(&scene) {
            let to_sun = Ray::new(q, dir);
            if shadow {
                assert!(ray_aabb(&to_sun, &blue, f32::INFINITY).is_some());
            } else {
                assert!(
                    boxes
                        .iter()
                        .all(|b| ray_aabb(&to_sun, b, f32::INFINITY).is_none())
                );
            }
        }
        let k = (j * WIDTH + i) as usize;
        assert_eq!(image.seen[k], Some(ground));
        let albedo = scene.objects[ground].material.albedo_at(q);
        luminance(image.pixels[k] / albedo)
    };
    // Straight below the centre of the box's top, seen from the sun: deep
    // in its shadow. And a point in front of everything, towards the sun.
    let top = Vec3::new(
        (blue.min.x + blue.max.x) / 2.0,
        blue.max.y,
        (blue.min.z + blue.max.z) / 2.0,
    );
    let shadowed = irradiance(top - scene.sun * (top.y / scene.sun.y), true);
    let lit = irradiance(Vec3::new(-0.5, 0.0, 2.5), false);
    // In the open the sun alone gives SUN * cos(angle) (the angle varies
    // over the sun's disc by far less than 10%); in the shadow only the
    // sky's light remains, at most SKY_LIGHT.
    let sun = luminance(renderer::SUN) * scene.sun.y;
    assert!(
        lit >= sun * 0.9,
        "open ground gets {lit}, the sun alone gives {sun}"
    );
    assert!(
        shadowed <= luminance(renderer::SKY_LIGHT) * 1.01,
        "shadowed ground gets {shadowed}"
    );
    assert!(shadowed < 0.5 * lit);
}

#[test]
fn more_samples_keep_the_centre_rays_and_add_jittered_ones() {
    let scene = demo_scene(WIDTH, HEIGHT);
    let (one, rays_one) = render(&scene, 1, &|| {});
    let (four, rays_four) = render(&scene, 4, &|| {});
    // The first sample of every pixel is still its centre ray.
    assert_eq!(one.seen, four.seen);
    assert!(rays_four > 3 * rays_one);
    assert_ne!(one.pixels, four.pixels);
    // The sky pixel averages nearby directions of the sky.
    let d = four.pixels[0] - one.pixels[0];
    assert!(d.abs().max_element() < 0.05, "{d}");
}

#[test]
fn rays_leaving_the_ground_or_a_box_never_hit_it_again() {
    let scene = demo_scene(WIDTH, HEIGHT);
    let (mut checked, mut unoffset_hits) = (0, 0);
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let ray = scene.camera.pixel_ray(i, j);
            let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
                continue;
            };
            // The ground and the boxes are convex: a ray leaving one on
            // the side the ray came from cannot meet it again. (The meshes
            // are left to the crate's own tests.)
            let shape = &scene.objects[hit.object].shape;
            let hits_again = |r: &Ray| match shape {
                Shape::Plane(plane) => ray_plane(r, plane, f32::INFINITY).is_some(),
                Shape::Box(b) => ray_aabb(r, b, f32::INFINITY).is_some(),
                Shape::Mesh(_) => unreachable!(),
            };
            if let Shape::Mesh(_) = shape {
                continue;
            }
            let n = hit.surface.normal.normalize();
            let n = if n.dot(ray.dir) > 0.0 { -n } else { n };
            let (t1, t2) = n.any_orthonormal_pair();
            // Towards the sun, along the normal, and grazing.
            let mut dirs = vec![scene.sun, n];
            for k in [0.5, 0.05, 1e-3] {
                dirs.extend([t1, -t1, t2, -t2].map(|t| (t + n * k).normalize()));
            }
            for dir in dirs.into_iter().filter(|d| d.dot(n) > 0.0) {
                assert!(
                    !hits_again(&hit.surface.spawn(dir)),
                    "pixel ({i}, {j}), {dir}"
                );
                unoffset_hits += u32::from(hits_again(&Ray::new(hit.surface.point, dir)));
                checked += 1;
            }
        }
    }
    assert!(checked > 10_000);
    // Without the offset, some of them do: the check can fail.
    assert!(unoffset_hits > 0, "{unoffset_hits} of {checked}");
}

/// The filtered checker: a footprint far smaller than a square gives the
/// point sample; a box covering whole squares in each direction averages
/// them exactly (half the area odd); and half a square's width either side
/// of the line between two squares averages the two. In `f32` each wave
/// is a difference of two triangle-wave values (each within a few
/// roundings of numbers below 1, `2^-22` together) over the width, so a
/// footprint of `1/100` leaves `2^-22 * 2 / 0.01 < 5e-5` per axis; wider
/// ones less.
#[test]
fn the_filtered_checker_is_the_box_average() {
    use rayhit_demo::renderer::checker_box_filtered;
    // (0.25, 0.25): floor sum 0, even; (1.25, 0.25): odd.
    assert!(checker_box_filtered(0.25, 0.25, 1e-2, 1e-2) < 1e-4);
    assert!((checker_box_filtered(1.25, 0.25, 1e-2, 1e-2) - 1.0).abs() < 1e-4);
    assert!((checker_box_filtered(0.3, 0.7, 2.0, 2.0) - 0.5).abs() < 1e-5);
    assert!((checker_box_filtered(0.3, 0.7, 4.0, 6.0) - 0.5).abs() < 1e-5);
    // Straddling x = 1 in z's even square: half even, half odd.
    assert!((checker_box_filtered(1.0, 0.5, 0.5, 0.2) - 0.5).abs() < 1e-5);
}

/// Filtering with ray differentials (or cones) removes the moire: in the
/// rows near the horizon, where a pixel spans many squares, the checker
/// value of each pixel's centre ray is compared with the pixel's average
/// over 64 jittered rays; point sampling is off by about half a colour
/// there (it picks one square at random), the filtered values much less.
#[test]
fn filtering_the_ground_removes_the_moire() {
    use rayhit_demo::demo::Filter;
    let mut scene = demo_scene(WIDTH, HEIGHT);
    scene.view = Box::new(scene.camera);
    let ground = object(&scene, "ground");
    let material = scene.objects[ground].material;
    let odd = |p: Vec3| {
        if material.albedo_at(p) == material.albedo {
            0.0
        } else {
            1.0
        }
    };
    let mut error = [0.0f64; 3];
    let mut pixels = 0;
    // The rows just below the horizon (the ground recedes there).
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let (x, y) = (i as f32 + 0.5, j as f32 + 0.5);
            let (diff, cone) = scene.primary(x, y, (0.5, 0.5));
            let Some(hit) = scene.intersect(&diff.ray, f32::INFINITY) else {
                continue;
            };
            if hit.object != ground || hit.t < 20.0 {
                continue;
            }
            let mut reference = 0.0;
            let mut all_ground = true;
            for k in 0..64 {
                let (dx, dy) = (
                    (k % 8) as f32 / 8.0 + 1.0 / 16.0,
                    (k / 8) as f32 / 8.0 + 1.0 / 16.0,
                );
                let (d, _) = scene.primary(i as f32 + dx, j as f32 + dy, (0.5, 0.5));
                match scene.intersect(&d.ray, f32::INFINITY) {
                    Some(h) if h.object == ground => reference += odd(h.surface.point) / 64.0,
                    _ => all_ground = false,
                }
            }
            if !all_ground {
                continue;
            }
            pixels += 1;
            for (k, filter) in [Filter::Off, Filter::Differentials, Filter::Cones]
                .into_iter()
                .enumerate()
            {
                scene.filter = filter;
                let value = match scene.footprint(&diff, &cone, &hit) {
                    Some((w, d)) => rayhit_demo::renderer::checker_box_filtered(
                        hit.surface.point.x,
                        hit.surface.point.z,
                        w,
                        d,
                    ),
                    None => odd(hit.surface.point),
                };
                error[k] += f64::from((value - reference).abs());
            }
        }
    }
    assert!(pixels > 50, "{pixels} far ground pixels");
    let mean = error.map(|e| e / f64::from(pixels));
    // Point sampling: off by about half on average where squares are far
    // below a pixel; the filters at most a third of that.
    assert!(
        mean[0] > 0.2,
        "point sampling is not aliased here: {mean:?}"
    );
    assert!(mean[1] < mean[0] / 3.0, "differentials: {mean:?}");
    assert!(mean[2] < mean[0] / 3.0, "cones: {mean:?}");
}
