//! The `shadows` scene: shadow segments between two surfaces, and every
//! hit along a ray through the glass in order. A shadow segment from
//! `spawn_to` or `spawn_to_point` is never blocked by its own ends, a
//! ground point that geometry puts in full shadow gets no direct light
//! and one in the open all of it, and the walk through the glass finds
//! the exact number of crossings, in order, on camera and shadow rays.

use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Camera, Interval, Ray, Side, Surface, SurfacePoint, Triangle, exact, ray_aabb, ray_plane,
};
use rayhit_demo::renderer::Rng;
use rayhit_demo::shadows::{ShadowScene, Solid, render_shadows, shadow_scene};

use crate::common::{HEIGHT, WIDTH, luminance};

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
