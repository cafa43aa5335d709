//! The demo, run small through its own code: each check is decided from the
//! scene's geometry by the test, not from the picture it is checking.
//!
//! The demo scene: the centre pixel sees the sphere placed there, a pixel
//! aimed above everything sees the sky, and a ground point in a box's
//! shadow is darker than one in the open. The leak scene: every counted ray
//! really passes exactly through an interior vertex of the closed mesh, the
//! watertight kernel stops every one of them there, and Moller-Trumbore
//! lets some through (or the scene would prove nothing). The shadows
//! scene: a shadow segment from `spawn_to` or `spawn_to_point` is never
//! blocked by its own ends, a ground point that geometry puts in full
//! shadow gets no direct light and one in the open all of it, and the
//! walk through the glass finds the exact number of crossings, in order,
//! on camera and shadow rays. The instances scene: no ray leaving an
//! instance hits the triangle it left once mapped back into the instance
//! (the usual offsets do), the instances' world boxes contain the exact
//! images of their vertices, the two-level traversal finds what testing
//! every triangle of every instance finds, and the picture has sky,
//! ground, mirrors, light and shadow where the geometry puts them.

use std::collections::{HashMap, HashSet};

use rayhit::exact::AffineMap;
use rayhit::exact::oracle::rv;
use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Camera, Instance, Interval, PinholeCamera, PreparedRay, Ray, Side, Surface, SurfacePoint,
    Triangle, exact, ray_aabb, ray_plane, ray_triangle,
};
use rayhit_demo::instances::{
    Content, InstanceHit, InstanceScene, On, Path, instance_scene, render_instances, slab,
};
use rayhit_demo::mesh::{Kernel, Mesh, icosphere, signed_volume, torus};
use rayhit_demo::scene::{self, FAR, NEAR, Rng, Scene, Shape, demo_scene, leak_scene, render, sky};
use rayhit_demo::shadows::{ShadowScene, Solid, render_shadows, shadow_scene};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 36;

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

/// Rec. 709 luminance.
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
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
    let sun = luminance(scene::SUN) * scene.sun.y;
    assert!(
        lit >= sun * 0.9,
        "open ground gets {lit}, the sun alone gives {sun}"
    );
    assert!(
        shadowed <= luminance(scene::SKY_LIGHT) * 1.01,
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

/// True when every directed edge of the mesh has exactly one twin running
/// the other way: closed, and wound consistently.
fn closed_and_consistent(mesh: &Mesh) -> bool {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for &[a, b, c] in &mesh.indices {
        for e in [(a, b), (b, c), (c, a)] {
            *edges.entry(e).or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

#[test]
fn the_meshes_are_closed_and_wound_outwards() {
    let scene = leak_scene(16, 12);
    for mesh in [
        icosphere(Vec3::ZERO, 1.0, 2),
        torus(1.0, 0.3, 12, 8),
        slab(),
        scene.mesh.mesh.clone(),
    ] {
        assert!(closed_and_consistent(&mesh));
        assert!(signed_volume(&mesh) > 0.0);
    }
    // And the check can fail: one triangle turned over.
    let mut broken = icosphere(Vec3::ZERO, 1.0, 1);
    broken.indices[0].swap(1, 2);
    assert!(!closed_and_consistent(&broken));
}

#[test]
fn the_watertight_kernel_leaks_no_ray_and_moller_trumbore_does() {
    let scene = leak_scene(64, 48);
    let mesh = &scene.mesh.mesh;
    assert!(closed_and_consistent(mesh));
    let vertices: HashMap<[u32; 3], u32> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(k, p)| (p.to_array().map(f32::to_bits), k as u32))
        .collect();
    let mut triangles_at = vec![0u32; mesh.positions.len()];
    for tri in &mesh.indices {
        for &k in tri {
            triangles_at[k as usize] += 1;
        }
    }
    // Every counted ray passes exactly through a vertex of the mesh (its
    // point at t = NEAR, computed in f64 where the product is exact) with a
    // full fan of six triangles around it, all facing the ray: it crosses
    // into the solid there.
    let mut counted = HashSet::new();
    for j in 0..48 {
        for i in 0..64 {
            if !scene.must_enter(i, j) {
                continue;
            }
            let ray = scene.camera.pixel_ray(i, j);
            assert_eq!(ray.origin, Vec3::ZERO);
            let at_near = ray.dir.as_dvec3() * f64::from(NEAR);
            let vertex = at_near.as_vec3();
            assert_eq!(vertex.as_dvec3(), at_near, "NEAR * dir is exact");
            let k = vertices[&vertex.to_array().map(f32::to_bits)];
            assert_eq!(triangles_at[k as usize], 6);
            for tri in mesh.indices.iter().filter(|t| t.contains(&k)) {
                let [a, b, c] = tri.map(|v| mesh.positions[v as usize].as_dvec3());
                assert!((b - a).cross(c - a).dot(ray.dir.as_dvec3()) < 0.0);
            }
            counted.insert((i, j));
        }
    }
    // The middle half of the image, less the border of the tile.
    assert_eq!(counted.len(), 31 * 23);

    let reports = Kernel::ALL.map(|kernel| scene.run(kernel, &|| {}));
    let [watertight, moller_trumbore] = &reports;
    for r in &reports {
        assert_eq!(r.entering as usize, counted.len());
        assert!(r.escaped <= r.leaked && r.leaked <= r.entering);
    }
    assert_eq!(watertight.leaked, 0);
    assert!(
        moller_trumbore.leaked > 0,
        "the scene should catch Moller-Trumbore out"
    );

    // The watertight kernel stops each ray where it enters: at t = NEAR.
    for &(i, j) in &counted {
        let ray = scene.camera.pixel_ray(i, j);
        let (hit, _) = scene
            .mesh
            .intersect(
                &ray,
                &PreparedRay::new(&ray),
                f32::INFINITY,
                Kernel::Watertight,
                false,
            )
            .expect("a hit");
        assert_eq!(hit.side, Side::Front);
        assert!((hit.t - NEAR).abs() < 1e-5 * NEAR, "t = {}", hit.t);
        assert!(hit.t < FAR);
    }
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
    use rayhit_demo::scene::checker_box_filtered;
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
    use rayhit_demo::scene::Filter;
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
                    Some((w, d)) => rayhit_demo::scene::checker_box_filtered(
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

// The shadows scene: shadow segments between two surfaces, and every hit
// along a ray through the glass in order.

/// The interval of a whole ray.
fn everything() -> Interval<f32> {
    Interval::up_to(f32::INFINITY).unwrap()
}

/// The smallest box around some points.
fn bounds_of(points: &[Vec3]) -> Aabb {
    let lo = points.iter().fold(Vec3::INFINITY, |a, &b| a.min(b));
    let hi = points.iter().fold(Vec3::NEG_INFINITY, |a, &b| a.max(b));
    Aabb::new(lo, hi)
}

/// The boxes around the shadows scene's objects that stand on the ground
/// or float above it (the sphere, the box and the glass), each with the
/// index of its opaque object (`None` for the glass).
fn obstacles(scene: &ShadowScene) -> Vec<(Option<usize>, Aabb)> {
    let mut out: Vec<(Option<usize>, Aabb)> = scene
        .opaque
        .iter()
        .enumerate()
        .filter_map(|(k, o)| match &o.shape {
            Solid::Plane(_) => None,
            Solid::Box(b) => Some((Some(k), *b)),
            Solid::Mesh(bvh) => Some((Some(k), bounds_of(&bvh.mesh.positions))),
        })
        .collect();
    out.push((None, bounds_of(&scene.glass.mesh.positions)));
    out
}

/// True when the straight segment from `p` to `q` meets none of the
/// obstacles' boxes, the one of object `skip` aside (the conservative slab
/// test: no box the exact segment meets is missed).
fn clear(scene: &ShadowScene, p: Vec3, q: Vec3, skip: Option<usize>) -> bool {
    let segment = Ray::new(p, q - p);
    obstacles(scene)
        .iter()
        .filter(|(k, _)| skip.is_none() || *k != skip)
        .all(|(_, b)| ray_aabb(&segment, b, 1.0).is_none())
}

/// The area light's corners.
fn light_corners(scene: &ShadowScene) -> [Vec3; 4] {
    let [t0, t1] = scene.light.triangles;
    [t0.a, t0.b, t0.c, t1.c]
}

/// The point on the ground below `(x, z)`, as a camera ray's hit would
/// give it.
fn ground_point(x: f32, z: f32) -> SurfacePoint {
    let ground = rayhit::Plane::new(Vec3::ZERO, Vec3::Y);
    let down = Ray::new(Vec3::new(x, 5.0, z), Vec3::new(0.0, -1.0, 0.0));
    let t = ray_plane(&down, &ground, f32::INFINITY).unwrap();
    ground.surface_point(&down, &t)
}

/// No acne: every shadow segment from a surface the camera sees to a point
/// of the area light or to a point light, where the straight segment is
/// clear of every other object's box, lets all the light through: neither
/// the surface it starts on nor the light's own triangles block it. The
/// ground, the sphere and the box are convex, so a segment leaving one of
/// them outwards cannot meet it again. Without the segment's offsets (the
/// computed point to the light point, over `(0, 1]`), some are blocked by
/// one end or the other: the check can fail.
#[test]
fn shadow_segments_never_hit_the_surfaces_at_their_ends() {
    let scene = shadow_scene(WIDTH, HEIGHT);
    let mut rng = Rng::new(23);
    let (mut checked, mut naive_blocked) = (0u32, 0u32);
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let ray = scene.camera.pixel_ray(i, j);
            let Some(hit) = scene.nearest(&ray, everything()) else {
                continue;
            };
            let Some(object) = hit.object else { continue };
            let x = hit.surface;
            let n = x.normal.normalize();
            let n = if n.dot(ray.dir) > 0.0 { -n } else { n };
            let mut targets: Vec<(Vec3, Option<SurfacePoint>)> = (0..6)
                .map(|_| {
                    let y = scene.light.sample(&mut rng);
                    (y.point, Some(y))
                })
                .collect();
            targets.extend(scene.points.iter().map(|l| (l.position, None)));
            for (q, on_light) in targets {
                let w = q - x.point;
                let faces_light = on_light.is_none() || scene.light.normal.dot(w) < 0.0;
                if n.dot(w) <= 0.0 || !faces_light || !clear(&scene, x.point, q, Some(object)) {
                    continue;
                }
                let segment = match &on_light {
                    Some(y) => x.spawn_to(y),
                    None => x.spawn_to_point(q),
                };
                let Some((shadow, interval)) = segment else {
                    continue;
                };
                assert_eq!(interval, Interval::up_to(1.0).unwrap());
                assert!(
                    !scene.blocked(&shadow, interval),
                    "pixel ({i}, {j}) to {q}: blocked"
                );
                assert_eq!(scene.transmittance(&shadow, interval), Vec3::ONE);
                checked += 1;
                let naive = Ray::new(x.point, q - x.point);
                naive_blocked += u32::from(scene.blocked(&naive, Interval::up_to(1.0).unwrap()));
            }
        }
    }
    assert!(checked > 3000, "{checked} segments checked");
    assert!(naive_blocked > 0, "{naive_blocked} of {checked}");
}

/// A ground point right beside the sphere's contact point, every one of
/// whose segments to the lights (the area light's corners, so its whole
/// rectangle, and both point lights) passes through a ball inside the
/// sphere mesh, gets no light at all; one whose segments are clear of
/// every object gets the full light of each.
#[test]
fn the_ground_in_shadow_gets_no_light_and_in_the_open_all_of_it() {
    let scene = shadow_scene(WIDTH, HEIGHT);
    let sphere = scene
        .opaque
        .iter()
        .find(|o| o.name == "sphere")
        .expect("a sphere");
    let Solid::Mesh(bvh) = &sphere.shape else {
        panic!("the sphere is a mesh")
    };
    let centre = bounds_of(&bvh.mesh.positions);
    let centre = (centre.min + centre.max) / 2.0;
    // Every face of an icosphere of radius 0.8 subdivided 3 times lies
    // farther than 0.78 from its centre (the faces' angular size is a few
    // degrees); the check below holds the mesh to that.
    let inner = 0.78;
    for &[a, b, c] in &bvh.mesh.indices {
        let [a, b, c] = [a, b, c].map(|k| bvh.mesh.positions[k as usize] - centre);
        let n = (b - a).cross(c - a).normalize();
        assert!(n.dot(a).abs() > inner);
    }
    let through_ball = |p: Vec3, q: Vec3| {
        let d = q - p;
        let t = ((centre - p).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        (p + d * t - centre).length() < inner * 0.99
    };
    let lights: Vec<Vec3> = light_corners(&scene)
        .into_iter()
        .chain(scene.points.iter().map(|l| l.position))
        .collect();

    let shadowed = ground_point(-1.873, -0.1);
    assert!((shadowed.point - Vec3::new(centre.x, 0.0, centre.z)).length() > 0.1);
    for &q in &lights {
        assert!(through_ball(shadowed.point, q), "{q}");
    }
    // Between the sphere and the box, under the light.
    let open = ground_point(0.25, -1.5);
    for &q in &lights {
        assert!(clear(&scene, open.point, q, None), "{q}");
    }

    let mut rng = Rng::new(5);
    let mut segments = 0;
    let (mut dark, mut lit) = (Vec3::ZERO, Vec3::ZERO);
    for _ in 0..64 {
        dark += scene.irradiance(&shadowed, Vec3::Y, Vec3::Y, &mut rng, &mut segments);
        lit += scene.irradiance(&open, Vec3::Y, Vec3::Y, &mut rng, &mut segments);
    }
    assert!(segments >= 64 * 2 * 3);
    assert_eq!(dark, Vec3::ZERO);
    // Each point light alone gives its intensity times cos / d^2 there.
    let points: Vec3 = scene
        .points
        .iter()
        .map(|l| {
            let w = l.position - open.point;
            l.intensity * (w.normalize().y / w.length_squared())
        })
        .sum();
    let lit = lit / 64.0;
    assert!(
        lit.cmpge(points).all(),
        "open ground gets {lit}, the point lights alone {points}"
    );
    // And the area light, about 2 there (radiance 9, area 2.88, 3.6 above).
    assert!(luminance(lit - points) > 1.0, "{lit} {points}");
}

/// The candidates for an exact count: the glass triangles whose boxes
/// the ray meets (the conservative slab test misses no box the exact ray
/// meets, so no crossing is lost).
fn glass_candidates(scene: &ShadowScene, ray: &Ray, t_max: f32) -> Vec<Triangle> {
    let mesh = &scene.glass.mesh;
    (0..mesh.indices.len())
        .map(|k| mesh.triangle(k))
        .filter(|t| ray_aabb(ray, &bounds_of(&[t.a, t.b, t.c]), t_max).is_some())
        .collect()
}

/// The walk over consecutive intervals finds every crossing of the closed
/// glass mesh once, in order: for each pixel-centre ray that meets the
/// glass's box, and for rays straight down through its vertices (each
/// crossing there is shared by a fan of triangles), the number of
/// crossings equals the exact count (`exact::ray_mesh` groups the triangles
/// of one crossing), and their `t` never decreases. The pixel rays, which
/// start and end outside, cross an even number of times, entering first.
///
/// Only vertices whose fan is seen from one side along the ray: where the
/// fan folds over as seen from above (near the tube's silhouette) the ray
/// touches the surface there, going in and out at one point, which the
/// walk rightly counts as two crossings or none and `ray_mesh` groups as
/// one.
#[test]
fn the_walk_counts_every_glass_crossing_exactly_once() {
    let scene = shadow_scene(WIDTH, HEIGHT);
    let glass_box = bounds_of(&scene.glass.mesh.positions);
    let mut histogram = [0u32; 7];
    let mut shared = 0;
    let mut check = |ray: &Ray, from_pixel: bool| {
        let crossings = scene.crossings(ray, everything());
        let exact = exact::ray_mesh(
            ray,
            &glass_candidates(&scene, ray, f32::INFINITY),
            f32::INFINITY,
        );
        assert_eq!(crossings.len(), exact.len(), "{ray:?}");
        assert!(crossings.windows(2).all(|w| w[0].hit.t <= w[1].hit.t));
        shared += exact.iter().filter(|c| c.triangles.len() > 1).count();
        histogram[crossings.len().min(6)] += 1;
        if from_pixel {
            assert_eq!(crossings.len() % 2, 0, "{ray:?}");
            if let Some(first) = crossings.first() {
                assert_eq!(first.hit.side, Side::Front);
            }
        }
    };
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let ray = scene.camera.pixel_ray(i, j);
            if ray_aabb(&ray, &glass_box, f32::INFINITY).is_some() {
                check(&ray, true);
            }
        }
    }
    let mesh = &scene.glass.mesh;
    let mut vertex_rays = 0;
    for (k, v) in mesh.positions.iter().enumerate().step_by(3) {
        let facing: Vec<f64> = mesh
            .indices
            .iter()
            .filter(|t| t.contains(&(k as u32)))
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
                let n = (b - a).cross(c - a).normalize();
                n.y
            })
            .collect();
        let one_side = facing.iter().all(|&y| y > 0.2) || facing.iter().all(|&y| y < -0.2);
        if one_side {
            // Exactly through the vertex: only y changes along the ray.
            check(&Ray::new(Vec3::new(v.x, 5.0, v.z), Vec3::NEG_Y), false);
            vertex_rays += 1;
        }
    }
    assert!(vertex_rays > 100, "{vertex_rays} rays through vertices");
    assert!(
        shared > 50,
        "{shared} crossings through shared edges or corners"
    );
    assert!(histogram[2] > 0 && histogram[4] > 0, "{histogram:?}");
}

/// Light through the glass is tinted once per surface the shadow segment
/// crosses: for segments from the ground below the glass to the lights,
/// not blocked by anything opaque, the transmittance is the tint raised to
/// the exact number of crossings within the segment.
#[test]
fn shadows_through_the_glass_are_tinted_once_per_surface() {
    let scene = shadow_scene(WIDTH, HEIGHT);
    let glass_box = bounds_of(&scene.glass.mesh.positions);
    let mut rng = Rng::new(11);
    let mut histogram = [0u32; 7];
    for k in 0..400 {
        let (a, b) = (rng.next_f32(), rng.next_f32());
        let x = ground_point(
            glass_box.min.x - 1.0 + a * (glass_box.max.x - glass_box.min.x + 2.0),
            glass_box.min.z - 1.0 + b * (glass_box.max.z - glass_box.min.z + 2.0),
        );
        let segment = if k % 3 == 0 {
            x.spawn_to(&scene.light.sample(&mut rng))
        } else {
            x.spawn_to_point(scene.points[k % 3 - 1].position)
        };
        let Some((ray, interval)) = segment else {
            continue;
        };
        if scene.blocked(&ray, interval) {
            continue;
        }
        let crossed = exact::ray_mesh(&ray, &glass_candidates(&scene, &ray, 1.0), 1.0).len();
        let expected = (0..crossed).fold(Vec3::ONE, |through, _| through * scene.tint);
        assert_eq!(scene.transmittance(&ray, interval), expected, "{ray:?}");
        histogram[crossed.min(6)] += 1;
    }
    assert!(histogram[0] > 0 && histogram[2] > 0, "{histogram:?}");
}

/// A small render of the shadows scene: every pixel finite and not
/// negative, the crossing count kept for each pixel's centre ray the one
/// the walk gives up to the opaque surface behind, and some centre rays
/// through four glass surfaces.
#[test]
fn the_shadows_scene_renders_without_nan() {
    let scene = shadow_scene(WIDTH, HEIGHT);
    let (image, rays, segments) = render_shadows(&scene, 2, &|| {});
    assert_eq!(rays, u64::from(2 * WIDTH * HEIGHT));
    assert!(segments > rays);
    for (k, c) in image.pixels.iter().enumerate() {
        assert!(c.is_finite() && c.min_element() >= 0.0, "pixel {k}: {c}");
    }
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let ray = scene.camera.pixel_ray(i, j);
            let end = scene
                .nearest(&ray, everything())
                .map_or(f32::INFINITY, |h| h.t);
            let walk = scene.crossings(&ray, Interval::up_to(end).unwrap()).len();
            assert_eq!(image.crossings[(j * WIDTH + i) as usize], walk);
        }
    }
    assert!(image.crossings.contains(&4));
}

// The instances scene: one mesh placed many times, far from the origin.

/// The instances along `path`, outermost first.
fn instances_on<'a>(scene: &'a InstanceScene, path: &Path) -> Vec<&'a Instance> {
    let (nodes, len) = scene.chain(path);
    nodes[..len].iter().map(|n| &n.instance).collect()
}

/// The nearest hit of `ray` (with `any`, the first found) by testing the
/// ground and every triangle of every instance, each instance with the
/// world ray mapped into it as the tracer maps it: no box and no BVH.
fn every_triangle(scene: &InstanceScene, ray: &Ray, any: bool) -> Option<(f32, On)> {
    let mut best = ray_plane(ray, &scene.ground, f32::INFINITY).map(|t| (t, On::Ground));
    for path in scene.paths() {
        let object = scene.object_ray(&path, ray);
        let mesh = &scene.leaf(&path).0.mesh;
        for k in 0..mesh.indices.len() {
            let t_max = best.map_or(f32::INFINITY, |b| b.0);
            if let Some(hit) = ray_triangle(&object, &mesh.triangle(k), t_max) {
                let on = On::Instance {
                    path,
                    triangle: k as u32,
                };
                // The BVH keeps the first of two hits at the same `t`.
                if best.is_none_or(|b| hit.t < b.0 || b.1 == On::Ground) {
                    best = Some((hit.t, on));
                }
                if any {
                    return best;
                }
            }
        }
    }
    best
}

/// No acne: every ray leaving an instance that a pixel's centre ray of
/// the 320x180 picture hits (towards the sun's centre and the four edges
/// of its disc, along the mirror's reflection, along the normal, and
/// tilted off the surface by 0.5, 0.05 and 0.001), spawned by the scene
/// with `Instance::spawn_through` and the hit's instances, then mapped
/// back into those instances as the tracer maps it, misses the triangle
/// it left. The usual ways do not: from the unmoved world point, or moved
/// 1e-4 along the normal (below half an ulp of the coordinates there, so
/// the move rounds away), tens of thousands hit it again: the check can
/// fail.
#[test]
fn rays_leaving_an_instance_never_hit_the_triangle_they_left() {
    let (width, height) = (320, 180);
    let scene = instance_scene(width, height);
    let (s1, s2) = scene.sun.any_orthonormal_pair();
    let r = scene.sun_radius;
    let sun: Vec<Vec3> = [Vec3::ZERO, s1 * r, -s1 * r, s2 * r, -s2 * r]
        .iter()
        .map(|&o| (scene.sun + o).normalize())
        .collect();
    let (mut checked, mut nested, mut mirrored) = (0u32, 0u32, 0u32);
    // Unmoved, and 1e-4 along the normal.
    let mut naive = [0u32; 2];
    for j in 0..height {
        for i in 0..width {
            let ray = scene.camera.pixel_ray(i, j);
            let Some(hit) = scene.nearest(&ray, f32::INFINITY) else {
                continue;
            };
            let On::Instance { path, .. } = hit.on else {
                continue;
            };
            let tri = scene.triangle(&hit.on).expect("a triangle");
            let flip = |n: Vec3| if n.dot(ray.dir) > 0.0 { -n } else { n };
            let n = flip(hit.surface.normal.normalize());
            let (t1, t2) = n.any_orthonormal_pair();
            let mut dirs = sun.clone();
            dirs.push(n);
            let mirror = scene.material(&hit.on).mirror > 0.0;
            if mirror {
                // As the tracer reflects.
                let reflected = ray.dir.reflect(flip(hit.shading));
                dirs.push(if reflected.dot(n) > 0.0 {
                    reflected
                } else {
                    ray.dir.reflect(n)
                });
            }
            for k in [0.5, 0.05, 1e-3] {
                dirs.extend([t1, -t1, t2, -t2].map(|t| (t + n * k).normalize()));
            }
            let hits_again =
                |r: &Ray| ray_triangle(&scene.object_ray(&path, r), &tri, f32::INFINITY).is_some();
            for dir in dirs.into_iter().filter(|d| d.dot(n) > 0.0) {
                let spawned = scene.spawn(&hit, dir);
                assert_ne!(
                    spawned.origin, hit.surface.point,
                    "pixel ({i}, {j}): not moved"
                );
                assert!(!hits_again(&spawned), "pixel ({i}, {j}), {dir}");
                let usual = [
                    Ray::new(hit.surface.point, dir),
                    Ray::new(hit.surface.point + n * 1e-4, dir),
                ];
                for (count, r) in naive.iter_mut().zip(&usual) {
                    *count += u32::from(hits_again(r));
                }
                checked += 1;
                nested += u32::from(path.indices().len() > 1);
                mirrored += u32::from(mirror);
            }
        }
    }
    assert!(
        checked > 100_000 && nested > 10_000 && mirrored > 5_000,
        "{checked} rays, {nested} from nested instances, {mirrored} from mirrors"
    );
    assert!(naive.iter().all(|&c| c > 0), "{naive:?} of {checked}");
}

/// The same over whole surfaces and every direction: from four random
/// points of every triangle of every instance (carried to the world by
/// `surface_to_world`, level by level), rays in eight random directions to
/// either side of the surface (not within 0.01 of tangent), spawned by the
/// scene and mapped back into the instances, never meet the triangle they
/// left. `SurfacePoint::spawn` from the same world point does, now and
/// then: its offset covers the world point's error but not the round trip
/// through the stored inverse, which grows with a matrix like the sheared
/// tori's (a rotation, an uneven scale, another rotation), whose inverse
/// mixes large entries. The check can fail on that too.
#[test]
fn rays_from_anywhere_on_an_instance_never_hit_the_triangle_they_left() {
    let scene = instance_scene(WIDTH, HEIGHT);
    let mut rng = Rng::new(1);
    let (mut checked, mut world_only) = (0u32, 0u32);
    for path in scene.paths() {
        let (nodes, len) = scene.chain(&path);
        let mesh = &scene.leaf(&path).0.mesh;
        for k in 0..mesh.indices.len() {
            let tri = mesh.triangle(k);
            for _ in 0..4 {
                let object = scene::random_point_on(&tri, &mut rng);
                let surface = nodes[..len]
                    .iter()
                    .rev()
                    .fold(object, |p, node| node.instance.surface_to_world(&p));
                let n = surface.normal.normalize();
                // What `scene.spawn` reads of a hit: where it is and on what
                // (`t` and the shading normal are not used).
                let hit = InstanceHit {
                    t: 0.0,
                    on: On::Instance {
                        path,
                        triangle: k as u32,
                    },
                    surface,
                    shading: n,
                };
                let hits_again = |r: &Ray| {
                    ray_triangle(&scene.object_ray(&path, r), &tri, f32::INFINITY).is_some()
                };
                for _ in 0..8 {
                    let mut c = || rng.next_f32() - 0.5;
                    let dir = Vec3::new(c(), c(), c()).normalize();
                    if dir.dot(n).abs() < 0.01 {
                        continue;
                    }
                    assert!(
                        !hits_again(&scene.spawn(&hit, dir)),
                        "{:?} triangle {k}: {dir}",
                        path.indices()
                    );
                    world_only += u32::from(hits_again(&surface.spawn(dir)));
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 300_000, "{checked}");
    assert!(world_only > 0, "{world_only} of {checked}");
}

/// Every instance's box, top-level or inside a group, contains the exact
/// image (in rationals, through the exact maps of the floats given) of
/// every vertex of what it places; for a top-level instance of a group,
/// through both levels. The box of the vertices mapped in `f32` (rounded
/// to nearest, as a renderer computing its boxes from transformed
/// vertices gets them) misses some of them: the check can fail.
#[test]
fn instance_boxes_contain_the_exact_image_of_every_vertex() {
    let scene = instance_scene(WIDTH, HEIGHT);
    let exact_box = |b: &Aabb| (rv(b.min).unwrap(), rv(b.max).unwrap());
    let inside = |(lo, hi): &([exact::Rational; 3], [exact::Rational; 3]),
                  p: &[exact::Rational; 3]| {
        (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k])
    };
    let (mut vertices, mut rounded_out) = (0u32, 0u32);
    for path in scene.paths() {
        let (nodes, len) = scene.chain(&path);
        let mesh = &scene.leaf(&path).0.mesh;
        let world = AffineMap::of_path(&instances_on(&scene, &path)).unwrap();
        let own = AffineMap::of(&nodes[len - 1].instance);
        // The vertices mapped in f32, innermost first.
        let rounded: Vec<Vec3> = mesh
            .positions
            .iter()
            .map(|&p| {
                nodes[..len].iter().rev().fold(p, |p, node| {
                    let [a, b, c] = node.instance.matrix_columns();
                    a * p.x + b * p.y + c * p.z + node.instance.translation()
                })
            })
            .collect();
        let rounded_box = exact_box(&Aabb::new(
            rounded.iter().fold(Vec3::INFINITY, |a, &b| a.min(b)),
            rounded.iter().fold(Vec3::NEG_INFINITY, |a, &b| a.max(b)),
        ));
        let top = exact_box(&nodes[0].bounds);
        let member = exact_box(&nodes[len - 1].bounds);
        for &p in &mesh.positions {
            let object = rv(p).unwrap();
            let exact = world.apply(&object);
            assert!(inside(&top, &exact), "{:?} {p}", path.indices());
            // The member's box in its group's space.
            assert!(inside(&member, &own.apply(&object)));
            rounded_out += u32::from(!inside(&rounded_box, &exact));
            vertices += 1;
        }
    }
    assert!(vertices > 5_000, "{vertices}");
    assert!(rounded_out > 0, "{rounded_out} of {vertices}");
    // Both kinds of nesting are there.
    let groups = scene
        .nodes
        .iter()
        .filter(|n| matches!(n.content, Content::Group(_)))
        .count();
    assert!(groups >= 2 && scene.paths().len() >= 8 + groups);
}

/// The two-level traversal (world boxes, one map per instance visit, the
/// mesh's BVH) finds the same nearest hit as testing every triangle of
/// every instance, for the centre ray of every other pixel in each
/// direction; and the ray towards the sun from that hit is blocked for
/// one exactly when for the other.
#[test]
fn the_two_level_traversal_finds_what_every_triangle_finds() {
    let scene = instance_scene(WIDTH, HEIGHT);
    let (mut instanced, mut blocked) = (0, 0);
    for j in (0..HEIGHT).step_by(2) {
        for i in (0..WIDTH).step_by(2) {
            let ray = scene.camera.pixel_ray(i, j);
            let hit = scene.nearest(&ray, f32::INFINITY);
            let brute = every_triangle(&scene, &ray, false);
            assert_eq!(hit.map(|h| (h.t, h.on)), brute, "pixel ({i}, {j})");
            let Some(hit) = hit else { continue };
            instanced += u32::from(hit.on != On::Ground);
            let to_sun = scene.spawn(&hit, scene.sun);
            let occluded = scene.occluded(&to_sun, f32::INFINITY);
            assert_eq!(
                occluded,
                every_triangle(&scene, &to_sun, true).is_some(),
                "pixel ({i}, {j})"
            );
            blocked += u32::from(occluded);
        }
    }
    assert!(instanced > 100 && blocked > 30, "{instanced} {blocked}");
}

/// A small render of the instances scene with a point sun: every pixel
/// finite and not negative; some pixels see the sky, the ground, the
/// mirrors, and instances nested in instances; and a ground pixel gets
/// the sun's light when its ray to the sun meets no triangle of any
/// instance (decided by testing them all) and none of it when it does:
/// both happen.
#[test]
fn the_instances_picture_has_light_shadow_and_mirrors_where_the_geometry_puts_them() {
    let mut scene = instance_scene(WIDTH, HEIGHT);
    scene.sun_radius = 0.0;
    let (image, rays) = render_instances(&scene, 1, &|| {});
    assert!(rays > u64::from(WIDTH * HEIGHT));
    for (k, c) in image.pixels.iter().enumerate() {
        assert!(c.is_finite() && c.min_element() >= 0.0, "pixel {k}: {c}");
    }
    let (mut sky, mut mirror, mut nested) = (0, 0, 0);
    let (mut lit, mut shadowed) = (0, 0);
    let sun = luminance(rayhit_demo::scene::SUN) * scene.sun.y;
    let sky_light = luminance(rayhit_demo::scene::SKY_LIGHT);
    for j in 0..HEIGHT {
        for i in 0..WIDTH {
            let k = (j * WIDTH + i) as usize;
            let Some(on) = image.seen[k] else {
                sky += 1;
                continue;
            };
            if let On::Instance { path, .. } = on {
                mirror += u32::from(scene.material(&on).mirror > 0.0);
                nested += u32::from(path.indices().len() > 1);
                continue;
            }
            let ray = scene.camera.pixel_ray(i, j);
            let hit = scene.nearest(&ray, f32::INFINITY).expect("the ground");
            assert_eq!(hit.on, On::Ground);
            // The direction the tracer samples from a sun of radius 0.
            let to_sun = scene.sun.normalize();
            let blocked = every_triangle(&scene, &scene.spawn(&hit, to_sun), true).is_some();
            let albedo = scene.ground_material.albedo_at(hit.surface.point);
            let light = luminance(image.pixels[k] / albedo);
            if blocked {
                assert!(light <= sky_light * 1.01, "pixel ({i}, {j}) gets {light}");
                shadowed += 1;
            } else {
                assert!(light >= sun * 0.99, "pixel ({i}, {j}) gets {light}");
                lit += 1;
            }
        }
    }
    assert!(
        sky > 100 && mirror > 20 && nested > 20,
        "{sky} {mirror} {nested}"
    );
    assert!(lit > 200 && shadowed > 50, "{lit} lit, {shadowed} shadowed");
}
