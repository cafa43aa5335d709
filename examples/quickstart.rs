//! A first look: one ray per kernel, printed.
//!
//! `cargo run --example quickstart`

use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Camera, PinholeCamera, Plane, Ray, Surface, Triangle, ray_aabb, ray_plane, ray_triangle,
};

fn main() {
    // A 9x9-pixel camera at z = 5 looking down -z with a 60 degree field of view.
    let cam = PinholeCamera::from_fov(
        Vec3::new(0.0, 0.0, 5.0),
        -Vec3::Z,
        Vec3::Y,
        60f32.to_radians(),
        9,
        9,
    )
    .expect("a valid camera");
    let ray = cam.pixel_ray(4, 4);
    println!("centre pixel ray: origin {}, dir {}", ray.origin, ray.dir);

    let floor = Plane::from_coefficients(0.0, 0.0, 1.0, 1.0); // z = -1
    println!(
        "plane z = -1:     t = {:?}",
        ray_plane(&ray, &floor, f32::INFINITY)
    );

    let unit = Aabb::new(Vec3::splat(-0.5), Vec3::splat(0.5));
    println!(
        "box (slab):       {:?}",
        ray_aabb(&ray, &unit, f32::INFINITY)
    );
    println!(
        "box (naive):      {:?}",
        unit.clip_by_faces(&ray, f32::INFINITY)
    );

    let tri = Triangle::new(
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    );
    let hit = ray_triangle(&ray, &tri, f32::INFINITY).expect("the centre ray hits the triangle");
    let err = tri.hit_error(&ray, &hit);
    println!(
        "triangle:         t = {} (+- {:e}), u = {}, v = {}, {:?}",
        hit.t, err.t, hit.u, hit.v, hit.side
    );
    println!(
        "Moller-Trumbore:  {:?}",
        tri.moller_trumbore(&ray, f32::INFINITY)
    );

    // The cases that trip up textbook code.
    let in_face = Ray::new(Vec3::new(-2.0, 0.5, 0.0), Vec3::X); // lies in the box's face plane y = 0.5
    println!(
        "ray in a box face: {:?}",
        ray_aabb(&in_face, &unit, f32::INFINITY)
    );
    let nan = Ray::new(Vec3::ZERO, Vec3::new(f32::NAN, 0.0, -1.0));
    println!(
        "NaN direction:     {:?}",
        ray_triangle(&nan, &tri, f32::INFINITY)
    );
    let corner_pixel = cam.pixel_ray(0, 0);
    println!(
        "corner pixel dir:  {} (up and to the left)",
        corner_pixel.dir
    );
}
