//! The `instances` scene: one mesh placed many times, far from the
//! origin. No ray leaving an instance hits the triangle it left once
//! mapped back into the instance (the usual offsets do), the instances'
//! world boxes contain the exact images of their vertices, the two-level
//! traversal finds what testing every triangle of every instance finds,
//! and the picture has sky, ground, mirrors, light and shadow where the
//! geometry puts them.

use rayhit::exact::AffineMap;
use rayhit::exact::oracle::rv;
use rayhit::glam::Vec3;
use rayhit::{Aabb, Camera, Instance, Ray, exact, ray_plane, ray_triangle};
use rayhit_demo::instances::{
    Content, InstanceHit, InstanceScene, On, Path, instance_scene, render_instances,
};
use rayhit_demo::renderer::{self, Rng};

use crate::common::{HEIGHT, WIDTH, luminance};

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
                let object = renderer::random_point_on(&tri, &mut rng);
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
    let sun = luminance(rayhit_demo::renderer::SUN) * scene.sun.y;
    let sky_light = luminance(rayhit_demo::renderer::SKY_LIGHT);
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

/// Every instance resolves what it places: for the centre ray of every
/// second pixel, and each instance on each path whose box that ray (mapped
/// as the tracer maps it) crosses, the object-space error bound of the
/// object ray (`Instance::object_error_at`) where the ray leaves the box
/// is below a quarter of the content's thinnest extent, so the content's
/// shape is not lost in the map. At 30,000 units from the origin, where a
/// world coordinate is a multiple of `2^-9`, the bound is 6% to 19% of the
/// thinnest extent (the errors themselves, measured exactly on the worst
/// rays, are 10 to 30 times smaller); the bound grows with the distance
/// from the origin, so the scene placed a few times farther out fails.
#[test]
fn every_instance_resolves_its_content_from_the_camera() {
    let scene = instance_scene(WIDTH, HEIGHT);
    let content_box = |node: &rayhit_demo::instances::Node| match &node.content {
        Content::Mesh { mesh, .. } => {
            let points = &scene.meshes[*mesh].mesh.positions;
            let (lo, hi) = points
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(*p), hi.max(*p))
                });
            hi - lo
        }
        Content::Group(members) => {
            let (lo, hi) = members
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), m| {
                    (lo.min(m.bounds.min), hi.max(m.bounds.max))
                });
            hi - lo
        }
    };
    let (mut checked, mut worst) = (0usize, 0f32);
    for y in (0..HEIGHT).step_by(2) {
        for x in (0..WIDTH).step_by(2) {
            let world = scene.camera.pixel_ray(x, y);
            for path in scene.paths() {
                let (nodes, len) = scene.chain(&path);
                let mut ray = world;
                for node in &nodes[..len] {
                    let Some((_, exit)) = rayhit::ray_aabb(&ray, &node.bounds, f32::INFINITY)
                    else {
                        break;
                    };
                    let err = node.instance.object_error_at(&ray, exit);
                    let share = (err / content_box(node)).max_element();
                    assert!(
                        share < 0.25,
                        "{}: error {err:?} at t = {exit} against a content of {:?}",
                        node.name,
                        content_box(node)
                    );
                    worst = worst.max(share);
                    checked += 1;
                    ray = node.instance.world_to_object(&ray);
                }
            }
        }
    }
    eprintln!("{checked} (ray, instance) pairs; the largest error is {worst:.1e} of the content");
    assert!(checked > 100, "{checked}");
}
