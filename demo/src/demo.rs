//! The `demo` scene: a checkered ground, boxes and meshes in soft
//! sunlight, seen through any camera, with the tracer for its objects and
//! its render loop.
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
    Aabb, Bounds, Camera, CameraSample, Intersect, PinholeCamera, Plane, PreparedRay, Ray, Surface,
    SurfacePoint, Triangle,
    camera::{RayCone, RayDifferential},
    ray_plane,
};

use crate::mesh::{Bvh, Kernel, icosphere, torus};
use crate::renderer::{
    MAX_DEPTH, Material, OCCLUSION_RANGE, Rng, SKY_LIGHT, SUN, facing, render_pixels, sky,
    toward_disc,
};

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
    /// the tests in `tests/render/` check; the `render` binary does not need it).
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
