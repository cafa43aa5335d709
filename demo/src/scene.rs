//! The scenes, the tracer and the render loops, shared by the `render`
//! binary and by `tests/render.rs`, so that the test checks the very code
//! the demo runs.
//!
//! Every geometric question goes to a kernel of `rayhit`: primary rays from
//! `PinholeCamera`, the ground from `ray_plane`, the boxes from the prepared
//! slab test and a `ray_plane` on the face it reports, the meshes from the
//! slab test on their bounding boxes and BVH nodes and then `ray_triangle`
//! (or `Triangle::moller_trumbore`). Every ray that leaves a surface
//! (towards the sun, towards the sky, or reflected) starts from
//! `SurfacePoint::spawn`, which offsets the origin by the hit point's error
//! bound and the normal's, so it cannot hit the surface it left.

use rayhit::glam::{Mat3, Vec3};
use rayhit::{
    Aabb, Bounds, Camera, CameraSample, Intersect, PinholeCamera, Plane, PreparedRay, Ray, Side,
    Surface, SurfacePoint, Triangle,
    camera::{RayCone, RayDifferential},
    ray_plane,
};
use rayon::prelude::*;

use crate::mesh::{Bvh, Kernel, icosphere, shell, torus};

/// The geometry of one object.
#[derive(Debug)]
pub enum Shape {
    /// An infinite plane.
    Plane(Plane),
    /// A solid box.
    Box(Aabb),
    /// A closed triangle mesh.
    Mesh(Box<Bvh>),
}

/// How an object reflects light.
#[derive(Clone, Copy, Debug)]
pub struct Material {
    /// Diffuse reflectance.
    pub albedo: Vec3,
    /// A second reflectance on alternate unit squares of the `xz` plane.
    pub checker: Option<Vec3>,
    /// The fraction of light reflected as by a mirror, in `[0, 1]`; the
    /// reflection is tinted by `albedo`, as by a metal.
    pub mirror: f32,
}

impl Material {
    /// A plain diffuse material.
    pub const fn diffuse(r: f32, g: f32, b: f32) -> Self {
        Self {
            albedo: Vec3::new(r, g, b),
            checker: None,
            mirror: 0.0,
        }
    }

    /// The diffuse reflectance at `point`.
    pub fn albedo_at(&self, point: Vec3) -> Vec3 {
        match self.checker {
            Some(other) if (point.x.floor() + point.z.floor()).rem_euclid(2.0) == 1.0 => other,
            _ => self.albedo,
        }
    }

    /// The diffuse reflectance averaged over a footprint around `point`:
    /// the checker box-filtered over `width` (in `x`) by `depth` (in `z`)
    /// world units, or [`Material::albedo_at`] without a footprint.
    pub fn albedo_over(&self, point: Vec3, footprint: Option<(f32, f32)>) -> Vec3 {
        match (self.checker, footprint) {
            (Some(other), Some((w, d))) => {
                let odd = checker_box_filtered(point.x, point.z, w, d);
                self.albedo.lerp(other, odd)
            }
            _ => self.albedo_at(point),
        }
    }
}

/// The fraction of a `wx` by `wz` box centred on `(x, z)` covered by the
/// checker's odd squares (those with `floor(x) + floor(z)` odd): the
/// checker box-filtered exactly (Inigo Quilez, "Filtering procedural
/// textures", the `checkersGrad` formula: the integral of each axis's
/// square wave over the box, multiplied).
pub fn checker_box_filtered(x: f32, z: f32, wx: f32, wz: f32) -> f32 {
    // The square wave's average over [a - w/2, a + w/2]: +1 on even unit
    // intervals, -1 on odd ones, from its integral (a triangle wave).
    let wave = |a: f32, w: f32| {
        let w = w.max(1e-4);
        let tri = |t: f32| ((t / 2.0).rem_euclid(1.0) - 0.5).abs();
        2.0 * (tri(a - 0.5 * w) - tri(a + 0.5 * w)) / w
    };
    0.5 - 0.5 * wave(x, wx) * wave(z, wz)
}

/// One object of a scene.
#[derive(Debug)]
pub struct Object {
    /// A name for messages.
    pub name: &'static str,
    /// Its geometry.
    pub shape: Shape,
    /// Its material.
    pub material: Material,
}

/// Light from the sun, per unit of `cos(angle)` to the surface normal.
pub const SUN: Vec3 = Vec3::new(2.1, 1.95, 1.7);
/// Light from the sky on a surface that sees it unobstructed (the sky is
/// uniform here, so orientation does not matter; obstruction does).
pub const SKY_LIGHT: Vec3 = Vec3::new(0.40, 0.48, 0.62);
/// How far an ambient-occlusion ray looks for something in the way.
pub const OCCLUSION_RANGE: f32 = 2.5;
/// Reflections followed, at most.
pub const MAX_DEPTH: u32 = 3;

/// The background seen by a ray that hits nothing: a gradient from the
/// horizon up.
pub fn sky(dir: Vec3) -> Vec3 {
    let up = (dir.normalize().y).clamp(0.0, 1.0);
    Vec3::new(0.85, 0.90, 1.0).lerp(Vec3::new(0.22, 0.40, 0.85), up.sqrt())
}

/// The nearest surface a ray meets, with what is needed to shade it and to
/// leave it.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Index of the object in `Scene::objects`.
    pub object: usize,
    /// The hit point and the geometric normal with their error bounds:
    /// `surface.spawn(dir)` starts a ray that cannot hit the surface it
    /// leaves.
    pub surface: SurfacePoint,
    /// The unit normal used for shading (interpolated on smooth meshes).
    pub shading: Vec3,
}

/// A small deterministic random number generator (SplitMix64), seeded per
/// pixel so that a render is the same whatever the thread schedule.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// The generator for one seed.
    pub fn new(seed: u64) -> Self {
        Self(seed ^ 0x5851_F42D_4C95_7F2D)
    }

    /// A uniform float in `[0, 1)`.
    pub fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A uniform point in the unit disc.
    pub fn disc(&mut self) -> (f32, f32) {
        let r = self.next_f32().sqrt();
        let phi = self.next_f32() * std::f32::consts::TAU;
        (r * phi.cos(), r * phi.sin())
    }
}

/// The camera the primary rays come from: the scene's pinhole camera, or
/// another built on its frame (a thin lens on it, an orthographic or an
/// equirectangular camera), any [`Camera`].
pub type View = Box<dyn Camera + Send + Sync>;

/// How the checkered ground is textured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Point-sampled at each ray's hit: aliased (moire) far away.
    Off,
    /// Box-filtered over the pixel's footprint from the ray differentials
    /// carried to the hit.
    Differentials,
    /// Box-filtered over a square as wide as the ray cone at the hit.
    Cones,
}

/// The ground as a triangle whose barycentrics are world `x` and `z`: `a`
/// at the origin, `b = a + x`, `c = a + z` (the transfer works on its
/// plane, inside the triangle or not).
const GROUND: Triangle = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Z);

/// A scene: a camera, objects, the sun and the triangle kernel.
#[derive(Debug)]
pub struct Scene {
    /// The pinhole camera: the frame and image every view is built on.
    pub camera: PinholeCamera,
    /// The camera the primary rays come from.
    pub view: View,
    /// How the ground's checker is filtered.
    pub filter: Filter,
    /// Everything that can be hit.
    pub objects: Vec<Object>,
    /// Unit vector towards the centre of the sun.
    pub sun: Vec3,
    /// The sun's angular radius (as the tangent): the width of penumbras.
    pub sun_radius: f32,
    /// The kernel the meshes are intersected with.
    pub kernel: Kernel,
}

impl Scene {
    /// The nearest hit of `ray` at `0 < t <= t_max`.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let prepared = PreparedRay::new(ray);
        let mut best: Option<Hit> = None;
        let mut t_max = t_max;
        for (index, object) in self.objects.iter().enumerate() {
            let hit = match &object.shape {
                Shape::Plane(plane) => {
                    ray_plane(ray, plane, t_max).map(|t| plane_hit(ray, plane, t))
                }
                Shape::Box(aabb) => box_hit(ray, &prepared, aabb, t_max),
                Shape::Mesh(bvh) => bvh
                    .intersect(ray, &prepared, t_max, self.kernel, false)
                    .map(|(hit, id)| {
                        let tri = bvh.mesh.triangle(id as usize);
                        let surface = tri.surface_point_at(hit.u, hit.v);
                        let shading = bvh.mesh.shading_normal(id as usize, hit.u, hit.v);
                        Hit {
                            t: hit.t,
                            object: 0,
                            surface,
                            // A zero-area triangle (a mesh's T-junction filler) can be hit
                            // and has no normal: fall back to facing the ray.
                            shading: shading
                                .or_else(|| surface.normal.try_normalize())
                                .unwrap_or(-ray.dir.normalize()),
                        }
                    }),
            };
            if let Some(hit) = hit {
                t_max = hit.t;
                best = Some(Hit {
                    object: index,
                    ..hit
                });
            }
        }
        best
    }

    /// True when anything lies on `ray` at `0 < t <= t_max` (a box also
    /// blocks a ray that starts inside it).
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let prepared = PreparedRay::new(ray);
        self.objects.iter().any(|object| match &object.shape {
            Shape::Plane(plane) => ray_plane(ray, plane, t_max).is_some(),
            Shape::Box(aabb) => aabb.clip(&prepared, t_max).is_some(),
            Shape::Mesh(bvh) => bvh
                .intersect(ray, &prepared, t_max, self.kernel, true)
                .is_some(),
        })
    }

    /// The light arriving along `ray` (reversed); `rays` counts every ray
    /// traced, this one included.
    pub fn radiance(&self, ray: &Ray, depth: u32, rng: &mut Rng, rays: &mut u64) -> Vec3 {
        *rays += 1;
        match self.intersect(ray, f32::INFINITY) {
            Some(hit) => self.shade(ray, &hit, depth, rng, rays),
            None => sky(ray.dir),
        }
    }

    /// The light leaving `hit` back along `ray`: sunlight if the sun is not
    /// blocked, skylight if a random direction towards the sky is not
    /// blocked nearby (ambient occlusion), and a mirror reflection.
    pub fn shade(&self, ray: &Ray, hit: &Hit, depth: u32, rng: &mut Rng, rays: &mut u64) -> Vec3 {
        self.shade_over(ray, hit, None, depth, rng, rays)
    }

    /// [`Scene::shade`] with the texture averaged over `footprint` (the
    /// widths in world `x` and `z` of the pixel's footprint on the ground).
    pub fn shade_over(
        &self,
        ray: &Ray,
        hit: &Hit,
        footprint: Option<(f32, f32)>,
        depth: u32,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> Vec3 {
        let material = &self.objects[hit.object].material;
        let (geometric, shading) = facing(ray, hit.surface.normal, hit.shading);
        let mut light = Vec3::ZERO;

        // The sun: a random point of its disc, for soft shadows.
        let to_sun = toward_disc(self.sun, self.sun_radius, rng);
        let cos = shading.dot(to_sun);
        if cos > 0.0 && geometric.dot(to_sun) > 0.0 {
            *rays += 1;
            if !self.occluded(&hit.surface.spawn(to_sun), f32::INFINITY) {
                light += SUN * cos;
            }
        }

        // The sky: one cosine-distributed direction; its light counts unless
        // something nearby is in the way.
        let (x, y) = rng.disc();
        let (t1, t2) = shading.any_orthonormal_pair();
        let dir = t1 * x + t2 * y + shading * (1.0 - x * x - y * y).max(0.0).sqrt();
        if dir.dot(geometric) > 0.0 {
            *rays += 1;
            if !self.occluded(&hit.surface.spawn(dir), OCCLUSION_RANGE) {
                light += SKY_LIGHT;
            }
        }

        let mut colour = material.albedo_over(hit.surface.point, footprint) * light;
        if material.mirror > 0.0 && depth < MAX_DEPTH {
            let mut dir = ray.dir.reflect(shading);
            if dir.dot(geometric) <= 0.0 {
                dir = ray.dir.reflect(geometric);
            }
            let reflected = self.radiance(&hit.surface.spawn(dir), depth + 1, rng, rays);
            colour = colour.lerp(reflected * material.albedo, material.mirror);
        }
        colour
    }
}

/// The hit record for `ray` crossing `plane` at `t`.
fn plane_hit(ray: &Ray, plane: &Plane, t: f32) -> Hit {
    Hit {
        t,
        object: 0,
        // A plane's normal is given, not computed: it has no error.
        surface: plane.surface_point(ray, &t),
        shading: plane.normal.normalize(),
    }
}

/// The hit of `ray` on the surface of a box: the slab test with the face
/// the ray enters through, and the point on that face with its error
/// bound. A ray that starts inside the box has no entry face, so no surface
/// in front of it to shade, and gets `None`; `Scene::occluded` treats such
/// a ray as blocked.
fn box_hit(ray: &Ray, prepared: &PreparedRay, aabb: &Aabb, t_max: f32) -> Option<Hit> {
    let hit = aabb.hit(prepared, t_max)?;
    let surface = aabb.surface_point(ray, &hit)?;
    Some(Hit {
        t: hit.enter,
        object: 0,
        surface,
        // The face's outward normal is exact and already of unit length.
        shading: surface.normal,
    })
}

/// The default scene: a checkered ground, a red icosphere in the middle, a
/// gold mirror torus standing on the left, boxes, and the sun on the left.
pub fn demo_scene(width: u32, height: u32) -> Scene {
    let eye = Vec3::new(0.0, 2.2, 7.2);
    let target = Vec3::new(0.0, 0.9, 0.0);
    let camera = PinholeCamera::from_fov(
        eye,
        target - eye,
        Vec3::Y,
        36f32.to_radians(),
        width,
        height,
    )
    .expect("a valid camera");
    let torus = torus(0.8, 0.3, 96, 40)
        .transformed(Mat3::from_rotation_y(0.5), Vec3::new(-2.3, 0.8 + 0.3, 0.2));
    let objects = vec![
        Object {
            name: "ground",
            shape: Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
            material: Material {
                checker: Some(Vec3::new(0.30, 0.33, 0.38)),
                ..Material::diffuse(0.72, 0.70, 0.66)
            },
        },
        Object {
            name: "icosphere",
            shape: Shape::Mesh(Box::new(Bvh::new(icosphere(
                Vec3::new(0.0, 1.0, 0.0),
                1.0,
                4,
            )))),
            material: Material::diffuse(0.80, 0.22, 0.16),
        },
        Object {
            name: "torus",
            shape: Shape::Mesh(Box::new(Bvh::new(torus))),
            material: Material {
                mirror: 0.85,
                ..Material::diffuse(0.95, 0.72, 0.35)
            },
        },
        Object {
            name: "blue box",
            shape: Shape::Box(Aabb::new(
                Vec3::new(1.5, 0.0, -0.6),
                Vec3::new(2.5, 1.0, 0.4),
            )),
            material: Material::diffuse(0.15, 0.30, 0.75),
        },
        Object {
            name: "green box",
            shape: Shape::Box(Aabb::new(
                Vec3::new(0.9, 0.0, 1.6),
                Vec3::new(1.5, 0.6, 2.2),
            )),
            material: Material::diffuse(0.20, 0.60, 0.25),
        },
        Object {
            name: "tall box",
            shape: Shape::Box(Aabb::new(
                Vec3::new(-1.4, 0.0, -3.2),
                Vec3::new(-0.4, 2.6, -2.2),
            )),
            material: Material::diffuse(0.78, 0.72, 0.62),
        },
    ];
    Scene {
        camera,
        view: Box::new(camera),
        filter: Filter::Differentials,
        objects,
        sun: Vec3::new(-1.0, 0.9, 0.45).normalize(),
        sun_radius: 0.04,
        kernel: Kernel::Watertight,
    }
}

/// A rendered image: linear colours, and which object the ray through each
/// pixel's centre hit.
#[derive(Clone, Debug)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear colours, row by row from the top.
    pub pixels: Vec<Vec3>,
    /// The object the pixel-centre ray hit first, if any, row by row (what
    /// `tests/render.rs` checks; the example does not need it).
    #[allow(dead_code)]
    pub seen: Vec<Option<usize>>,
}

/// Renders `scene` with `samples` rays per pixel (the first through the
/// pixel's centre, the others at random points of the pixel) on all cores,
/// calling `row_done` after each row. Returns the image and the number of
/// rays traced.
pub fn render(scene: &Scene, samples: u32, row_done: &(dyn Fn() + Sync)) -> (Image, u64) {
    let camera = &scene.camera;
    let (width, height) = (camera.width(), camera.height());
    let (pixels, seen, [rays, _]) = render_pixels(
        (width, height),
        samples,
        row_done,
        |x, y, first, rng, counts| {
            // The lens sample: the lens's centre for the first sample,
            // drawn after the pixel's jitter for the others.
            let lens = if first {
                (0.5, 0.5)
            } else {
                (rng.next_f32(), rng.next_f32())
            };
            let (diff, cone) = scene.primary(x, y, lens);
            let ray = diff.ray;
            let hit = scene.intersect(&ray, f32::INFINITY);
            let colour = match hit {
                Some(hit) => {
                    let footprint = scene.footprint(&diff, &cone, &hit);
                    scene.shade_over(&ray, &hit, footprint, 0, rng, &mut counts[0])
                }
                None => sky(ray.dir),
            };
            (colour, hit.map(|h| h.object))
        },
    );
    let image = Image {
        width,
        height,
        pixels,
        seen,
    };
    (image, rays)
}

/// A uniformly random point of `tri` as a surface point (barycentrics drawn
/// from `rng`, folded into the triangle), with its error bound:
/// `Triangle::surface_point_at` holds for any barycentrics.
pub fn random_point_on(tri: &Triangle, rng: &mut Rng) -> SurfacePoint {
    let (mut u, mut v) = (rng.next_f32(), rng.next_f32());
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    tri.surface_point_at(u, v)
}

/// The geometric normal (unit, or the shading normal where it has no
/// length) and the shading normal, both turned to face the incoming `ray`.
pub fn facing(ray: &Ray, geometric: Vec3, shading: Vec3) -> (Vec3, Vec3) {
    let flip = |n: Vec3| if n.dot(ray.dir) > 0.0 { -n } else { n };
    (
        flip(geometric.try_normalize().unwrap_or(shading)),
        flip(shading),
    )
}

/// A unit direction towards a random point of the disc of angular radius
/// about `radius` around the unit direction `centre` (a sun's disc, for
/// soft shadows).
pub fn toward_disc(centre: Vec3, radius: f32, rng: &mut Rng) -> Vec3 {
    let (a, b) = rng.disc();
    let (s1, s2) = centre.any_orthonormal_pair();
    (centre + (s1 * a + s2 * b) * radius).normalize()
}

/// The demo scenes' pixel loop, rows in parallel (`row_done` after each):
/// per pixel, `samples` calls of `sample(x, y, first, rng, counts)` at
/// raster position `(x, y)`, the first (`first` true) through the pixel's
/// centre and the others at uniform random points of the pixel (two draws
/// from the pixel's own `rng`, seeded by its index, so the picture does
/// not depend on the threads), each returning its colour and what the
/// pixel records of its first sample. Returns the pixels (the samples'
/// mean), the records, and the summed `counts`, where each sample counts
/// one camera ray in `counts[0]` and `sample` adds what else it traces.
pub fn render_pixels<T: Send + Clone + Default>(
    (width, height): (u32, u32),
    samples: u32,
    row_done: &(dyn Fn() + Sync),
    sample: impl Fn(f32, f32, bool, &mut Rng, &mut [u64; 2]) -> (Vec3, T) + Sync,
) -> (Vec<Vec3>, Vec<T>, [u64; 2]) {
    let mut pixels = vec![Vec3::ZERO; (width * height) as usize];
    let mut records = vec![T::default(); pixels.len()];
    let counts = pixels
        .par_chunks_mut(width as usize)
        .zip(records.par_chunks_mut(width as usize))
        .enumerate()
        .map(|(j, (row, record_row))| {
            let j = j as u32;
            let mut counts = [0; 2];
            for i in 0..width {
                let mut rng = Rng::new(u64::from(j * width + i));
                let mut sum = Vec3::ZERO;
                for s in 0..samples {
                    let (dx, dy) = if s == 0 {
                        (0.5, 0.5)
                    } else {
                        (rng.next_f32(), rng.next_f32())
                    };
                    counts[0] += 1;
                    let (colour, record) =
                        sample(i as f32 + dx, j as f32 + dy, s == 0, &mut rng, &mut counts);
                    if s == 0 {
                        record_row[i as usize] = record;
                    }
                    sum += colour;
                }
                row[i as usize] = sum / samples as f32;
            }
            row_done();
            counts
        })
        .reduce(|| [0; 2], |a, b| [a[0] + b[0], a[1] + b[1]]);
    (pixels, records, counts)
}

impl Scene {
    /// The primary ray of raster position `(x, y)` and lens sample `lens`,
    /// with its differentials and its ray cone, from [`Scene::view`].
    pub fn primary(&self, x: f32, y: f32, lens: (f32, f32)) -> (RayDifferential, RayCone) {
        let sample = CameraSample::new(x, y).with_lens(lens.0, lens.1);
        (self.view.ray_differential(sample), self.view.ray_cone())
    }

    /// The footprint of a primary ray's pixel on the checkered ground at
    /// `hit`, as the widths in world `x` and `z` to filter the checker
    /// over; `None` for other surfaces, or with filtering off.
    pub fn footprint(
        &self,
        diff: &RayDifferential,
        cone: &RayCone,
        hit: &Hit,
    ) -> Option<(f32, f32)> {
        let ground = matches!(self.objects[hit.object].shape, Shape::Plane(_))
            && self.objects[hit.object].material.checker.is_some();
        if !ground {
            return None;
        }
        match self.filter {
            Filter::Off => None,
            Filter::Differentials => {
                // On GROUND, u is world x and v world z.
                let d = GROUND.hit_differentials(diff, hit.t)?;
                Some((
                    d.du_dx.abs().max(d.du_dy.abs()),
                    d.dv_dx.abs().max(d.dv_dy.abs()),
                ))
            }
            Filter::Cones => {
                let w = GROUND.cone_width(cone, &diff.ray, hit.t)?;
                Some((w, w))
            }
        }
    }
}

/// A linear colour as 8-bit sRGB, after a soft exposure curve that keeps
/// highlights from clipping.
pub fn to_srgb8(colour: Vec3) -> [u8; 3] {
    colour.to_array().map(|c| {
        let c = 1.0 - (-1.1 * c.max(0.0)).exp();
        let s = if c <= 0.003_130_8 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0 + 0.5).clamp(0.0, 255.0) as u8
    })
}

/// The watertightness experiment: an axis-aligned camera at the origin and
/// a closed mesh in front of it, a thick curved tile whose front and back
/// surfaces have a vertex on the centre ray of every pixel: at `NEAR * dir`
/// and `FAR * dir`, `dir` the direction `PinholeCamera::pixel_ray` computed.
/// `NEAR` and `FAR` are powers of two, so those products are exact and every
/// pixel-centre ray through the tile passes exactly through a vertex shared
/// by six triangles, where rounding decides whether a kernel sees it.
#[derive(Debug)]
pub struct LeakScene {
    /// The camera.
    pub camera: PinholeCamera,
    /// The closed mesh.
    pub mesh: Bvh,
    /// The pixel columns `(first, last)` whose centre rays pass through a
    /// vertex inside the front surface (not on its border).
    pub columns: (u32, u32),
    /// The same for pixel rows.
    pub rows: (u32, u32),
}

/// Distance of the leak scene's front surface, along unit rays.
pub const NEAR: f32 = 4.0;
/// Distance of its back surface.
pub const FAR: f32 = 8.0;

/// The leak scene for an image of `width x height` pixels (each at least 4):
/// the tile covers the middle half of the image in each direction.
pub fn leak_scene(width: u32, height: u32) -> LeakScene {
    assert!(width >= 4 && height >= 4, "the leak scene needs 4x4 pixels");
    let camera = PinholeCamera::from_fov(
        Vec3::ZERO,
        -Vec3::Z,
        Vec3::Y,
        40f32.to_radians(),
        width,
        height,
    )
    .expect("a valid camera");
    let (first_column, columns) = (width / 4, width / 2 + 1);
    let (first_row, rows) = (height / 4, height / 2 + 1);
    let directions: Vec<Vec3> = (first_row..first_row + rows)
        .flat_map(|j| (first_column..first_column + columns).map(move |i| (i, j)))
        .map(|(i, j)| camera.pixel_ray(i, j).dir)
        .collect();
    let mesh = shell(&directions, columns, rows, NEAR, FAR);
    LeakScene {
        camera,
        mesh: Bvh::new(mesh),
        columns: (first_column + 1, first_column + columns - 2),
        rows: (first_row + 1, first_row + rows - 2),
    }
}

/// What a pixel-centre ray of the leak scene hit first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Nothing.
    Nothing,
    /// The mesh, from outside.
    Outside,
    /// The mesh, from inside: the ray got in without any triangle
    /// reporting it.
    Inside,
}

/// The leak experiment's result for one kernel.
#[derive(Clone, Debug)]
pub struct LeakReport {
    /// The kernel.
    pub kernel: Kernel,
    /// What each pixel's centre ray hit first, row by row.
    pub outcomes: Vec<Outcome>,
    /// Rays whose exact path enters the mesh through the front face.
    pub entering: u32,
    /// Of those, the rays that no triangle stopped on the way in: their
    /// nearest hit is on the inside of the mesh, or there is none.
    pub leaked: u32,
    /// Of the leaked rays, those that hit nothing at all.
    pub escaped: u32,
}

impl LeakScene {
    /// True when the centre ray of pixel `(i, j)` is one that must enter the
    /// mesh: it passes exactly through a vertex inside the front surface,
    /// where the surface is closed around it.
    pub fn must_enter(&self, i: u32, j: u32) -> bool {
        (self.columns.0..=self.columns.1).contains(&i) && (self.rows.0..=self.rows.1).contains(&j)
    }

    /// Traces every pixel-centre ray with `kernel` (on all cores, calling
    /// `row_done` after each row) and counts the leaks.
    pub fn run(&self, kernel: Kernel, row_done: &(dyn Fn() + Sync)) -> LeakReport {
        let (width, height) = (self.camera.width(), self.camera.height());
        let outcomes: Vec<Outcome> = (0..height)
            .into_par_iter()
            .flat_map_iter(|j| {
                let row = (0..width).map(move |i| {
                    let ray = self.camera.pixel_ray(i, j);
                    let prepared = PreparedRay::new(&ray);
                    match self
                        .mesh
                        .intersect(&ray, &prepared, f32::INFINITY, kernel, false)
                    {
                        None => Outcome::Nothing,
                        Some((hit, _)) if hit.side == Side::Front => Outcome::Outside,
                        Some(_) => Outcome::Inside,
                    }
                });
                let row: Vec<Outcome> = row.collect();
                row_done();
                row
            })
            .collect();
        let mut report = LeakReport {
            kernel,
            outcomes,
            entering: 0,
            leaked: 0,
            escaped: 0,
        };
        for j in 0..height {
            for i in 0..width {
                if self.must_enter(i, j) {
                    report.entering += 1;
                    match report.outcomes[(j * width + i) as usize] {
                        Outcome::Outside => {}
                        Outcome::Inside => report.leaked += 1,
                        Outcome::Nothing => {
                            report.leaked += 1;
                            report.escaped += 1;
                        }
                    }
                }
            }
        }
        report
    }
}

impl LeakReport {
    /// The picture: the mesh's outside grey, the background dark; a pixel
    /// whose ray got into the mesh unreported is red where the ray then
    /// saw the mesh from inside, yellow where it went through and out.
    pub fn colours(&self, scene: &LeakScene) -> Vec<[u8; 3]> {
        let width = scene.camera.width();
        (0..self.outcomes.len() as u32)
            .map(|k| {
                let (i, j) = (k % width, k / width);
                match self.outcomes[k as usize] {
                    Outcome::Outside => [170, 170, 170],
                    Outcome::Inside => [255, 30, 30],
                    Outcome::Nothing if scene.must_enter(i, j) => [255, 220, 0],
                    Outcome::Nothing => [40, 44, 52],
                }
            })
            .collect()
    }
}
