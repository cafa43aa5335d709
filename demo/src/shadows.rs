//! The `shadows` scene: an area light and two point lights whose shadow
//! rays are segments from `SurfacePoint::spawn_to` and
//! `SurfacePoint::spawn_to_point`, and a glass torus traced as the
//! sequence of its crossings.
//!
//! Every shadow ray is a segment `(ray, (0, 1])` between a shading point
//! and a point on a light, and every occluder is asked about that interval
//! with an interval or any-hit kernel: `Plane::hit` for the ground,
//! `Aabb::hit` for the box (blocked when it enters the box within the
//! segment: the `BoxHit` has an entry face), `Aabb::clip` and
//! `Triangle::occluded` for the meshes behind their BVH and for the light's
//! own two triangles. The segment's ends are placed off both surfaces by
//! their error bounds, so the light's triangles never block a segment that
//! ends on them and the shading point's surface never blocks one that
//! starts on it: there is no epsilon anywhere.
//!
//! The glass torus is walked hit by hit with a `Walk`: the nearest
//! crossing of what is left of the interval gives a window (its `t` plus
//! its error bound from `Triangle::hit_error`, rounded up), every crossing
//! of the window is collected and sorted by `t`, and the walk goes on past
//! the window. Consecutive windows hold each exact crossing exactly once,
//! and `Triangle::hit` with `EdgeRule::OneHit` gives a crossing through a
//! shared edge or corner to exactly one triangle, so no surface is skipped
//! or counted twice. Each surface crossed tints the light behind it, on
//! camera rays and on shadow rays alike.

use rayhit::glam::{Mat3, Vec3};
use rayhit::{
    Aabb, Camera, CameraSample, Intersect, Interval, PinholeCamera, Plane, PreparedRay, Ray,
    Surface, SurfacePoint, Triangle, TriangleHit, Walk,
};

use crate::mesh::{Bvh, icosphere, torus};
use crate::renderer::{Material, Rng, camera_at, facing, random_point_on, render_pixels, sky};

/// The geometry of an opaque object.
#[derive(Debug)]
pub enum Solid {
    /// An infinite plane.
    Plane(Plane),
    /// A solid box.
    Box(Aabb),
    /// A closed triangle mesh.
    Mesh(Box<Bvh>),
}

/// An opaque object of the shadows scene.
#[derive(Debug)]
pub struct Opaque {
    /// A name for messages.
    pub name: &'static str,
    /// Its geometry.
    pub shape: Solid,
    /// Its material.
    pub material: Material,
}

/// A rectangle that emits light from one side, as two triangles sharing a
/// diagonal.
#[derive(Clone, Copy, Debug)]
pub struct AreaLight {
    /// The two triangles, equal in area, wound so that their normal is
    /// [`AreaLight::normal`].
    pub triangles: [Triangle; 2],
    /// The unit normal of the side that emits.
    pub normal: Vec3,
    /// The light leaving each point of the emitting side, in every
    /// direction of that side.
    pub radiance: Vec3,
    /// The rectangle's area.
    pub area: f32,
}

impl AreaLight {
    /// A horizontal rectangle from `min` to `max` in `x` and `z` at height
    /// `y`, shining down.
    pub fn ceiling(y: f32, min: (f32, f32), max: (f32, f32), radiance: Vec3) -> Self {
        let p = |x: f32, z: f32| Vec3::new(x, y, z);
        let (a, b) = (p(min.0, min.1), p(max.0, min.1));
        let (c, d) = (p(max.0, max.1), p(min.0, max.1));
        // Seen from below, a -> b -> c runs clockwise: (b - a) x (c - a)
        // points down.
        let triangles = [Triangle::new(a, b, c), Triangle::new(a, c, d)];
        Self {
            triangles,
            normal: Vec3::NEG_Y,
            radiance,
            area: (max.0 - min.0) * (max.1 - min.1),
        }
    }

    /// A uniformly distributed point of the rectangle, as a point on one of
    /// its triangles with the error bounds of a triangle hit at those
    /// barycentrics: what `SurfacePoint::spawn_to` needs at the far end.
    pub fn sample(&self, rng: &mut Rng) -> SurfacePoint {
        let tri = &self.triangles[usize::from(rng.next_f32() >= 0.5)];
        random_point_on(tri, rng)
    }
}

/// A light at a point, the same in every direction.
#[derive(Clone, Copy, Debug)]
pub struct PointLight {
    /// Where it is.
    pub position: Vec3,
    /// Its intensity: the irradiance it gives a surface facing it at
    /// distance 1.
    pub intensity: Vec3,
}

/// The light that every pixel gets whatever the shadows: a stand-in for
/// indirect light, so that shadows are not black.
pub const AMBIENT: Vec3 = Vec3::new(0.06, 0.07, 0.08);

/// A surface hit by a camera ray.
#[derive(Clone, Copy, Debug)]
pub struct OpaqueHit {
    /// Distance along the ray.
    pub t: f32,
    /// Index in [`ShadowScene::opaque`], or `None` for the area light.
    pub object: Option<usize>,
    /// The point and the geometric normal with their error bounds.
    pub surface: SurfacePoint,
    /// The unit normal used for shading.
    pub shading: Vec3,
}

/// One crossing of a ray with the glass.
#[derive(Clone, Copy, Debug)]
pub struct Crossing {
    /// The hit: `t`, barycentrics and the side the ray came from.
    pub hit: TriangleHit,
    /// The triangle's index in the glass mesh.
    pub triangle: u32,
}

/// The shadows scene.
#[derive(Debug)]
pub struct ShadowScene {
    /// The camera.
    pub camera: PinholeCamera,
    /// The ground, a box and a sphere.
    pub opaque: Vec<Opaque>,
    /// The glass: a closed mesh, each of whose surfaces lets through
    /// [`ShadowScene::tint`] of the light.
    pub glass: Bvh,
    /// The fraction of light, per channel, that passes one surface of the
    /// glass.
    pub tint: Vec3,
    /// The area light (also seen by the camera, and an occluder like any
    /// other surface).
    pub light: AreaLight,
    /// The point lights.
    pub points: Vec<PointLight>,
}

/// The shadows scene for an image of `width x height` pixels: a ground, a
/// red sphere, a blue box, a glass torus tilted towards the camera, a
/// square light above them and a warm and a cool point light either side.
pub fn shadow_scene(width: u32, height: u32) -> ShadowScene {
    let eye = Vec3::new(0.0, 2.6, 7.0);
    let target = Vec3::new(0.0, 0.8, 0.0);
    let camera = camera_at(eye, target, width, height);
    let glass = torus(0.7, 0.3, 64, 20).transformed(
        Mat3::from_rotation_y(0.3) * Mat3::from_rotation_x(-1.62),
        Vec3::new(0.2, 1.0, 0.7),
    );
    let opaque = vec![
        Opaque {
            name: "ground",
            shape: Solid::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
            material: Material {
                checker: Some(Vec3::new(0.55, 0.55, 0.55)),
                ..Material::diffuse(0.75, 0.74, 0.72)
            },
        },
        Opaque {
            name: "sphere",
            shape: Solid::Mesh(Box::new(Bvh::new(icosphere(
                Vec3::new(-1.7, 0.8, -0.2),
                0.8,
                3,
            )))),
            material: Material::diffuse(0.80, 0.22, 0.16),
        },
        Opaque {
            name: "box",
            shape: Solid::Box(Aabb::new(
                Vec3::new(1.3, 0.0, -1.0),
                Vec3::new(2.3, 1.4, 0.0),
            )),
            material: Material::diffuse(0.20, 0.35, 0.78),
        },
    ];
    ShadowScene {
        camera,
        opaque,
        glass: Bvh::new(glass),
        tint: Vec3::new(0.60, 0.84, 0.78),
        light: AreaLight::ceiling(3.6, (-0.9, -1.6), (0.9, 0.2), Vec3::splat(9.0)),
        points: vec![
            PointLight {
                position: Vec3::new(3.6, 2.2, -2.2),
                intensity: Vec3::new(5.0, 2.9, 1.4),
            },
            PointLight {
                position: Vec3::new(-3.8, 2.0, -1.8),
                intensity: Vec3::new(1.3, 2.2, 4.6),
            },
        ],
    }
}

/// The smaller interval `(interval.min(), t]` for a `t` inside `interval`.
fn up_to(interval: Interval<f32>, t: f32) -> Interval<f32> {
    Interval::new(interval.min(), t).unwrap_or(interval)
}

impl ShadowScene {
    /// The nearest opaque surface (or the light) on `ray` within
    /// `interval`.
    pub fn nearest(&self, ray: &Ray, interval: Interval<f32>) -> Option<OpaqueHit> {
        let prepared = PreparedRay::new(ray);
        let mut window = interval;
        let mut best = None;
        for (index, object) in self.opaque.iter().enumerate() {
            let hit = match &object.shape {
                Solid::Plane(plane) => plane.hit(ray, window).map(|t| OpaqueHit {
                    t,
                    object: Some(index),
                    surface: plane.surface_point(ray, &t),
                    shading: plane.normal.normalize(),
                }),
                Solid::Box(aabb) => aabb.hit(&prepared, window).and_then(|hit| {
                    let surface = aabb.surface_point(ray, &hit)?;
                    Some(OpaqueHit {
                        t: hit.enter,
                        object: Some(index),
                        surface,
                        shading: surface.normal,
                    })
                }),
                Solid::Mesh(bvh) => {
                    bvh.nearest_one_hit_in(ray, &prepared, window)
                        .map(|(hit, id)| {
                            let surface = bvh
                                .mesh
                                .triangle(id as usize)
                                .surface_point(&prepared, &hit);
                            let shading = bvh
                                .mesh
                                .shading_normal(id as usize, hit.u, hit.v)
                                .or_else(|| surface.normal.try_normalize())
                                .unwrap_or(-ray.dir.normalize());
                            OpaqueHit {
                                t: hit.t,
                                object: Some(index),
                                surface,
                                shading,
                            }
                        })
                }
            };
            if let Some(hit) = hit {
                window = up_to(window, hit.t);
                best = Some(hit);
            }
        }
        for tri in &self.light.triangles {
            if let Some(hit) = tri.hit(&prepared, window) {
                window = up_to(window, hit.t);
                best = Some(OpaqueHit {
                    t: hit.t,
                    object: None,
                    surface: tri.surface_point(&prepared, &hit),
                    shading: self.light.normal,
                });
            }
        }
        best
    }

    /// True when an opaque surface or the light lies on `ray` within
    /// `interval`; the box blocks when the ray enters it there.
    pub fn blocked(&self, ray: &Ray, interval: Interval<f32>) -> bool {
        let prepared = PreparedRay::new(ray);
        let opaque = self.opaque.iter().any(|object| match &object.shape {
            Solid::Plane(plane) => plane.hit(ray, interval).is_some(),
            Solid::Box(aabb) => aabb
                .hit(&prepared, interval)
                .is_some_and(|hit| hit.face.is_some()),
            Solid::Mesh(bvh) => bvh.occluded_in(&prepared, interval),
        });
        opaque
            || self
                .light
                .triangles
                .iter()
                .any(|tri| tri.occluded(&prepared, interval))
    }

    /// Every crossing of `ray` with the glass within `interval`, in order
    /// along the ray: the walk over consecutive intervals described in the
    /// module's documentation.
    pub fn crossings(&self, ray: &Ray, interval: Interval<f32>) -> Vec<Crossing> {
        let prepared = PreparedRay::new(ray);
        let mut out = Vec::new();
        let mut found = Vec::new();
        let mut walk = Walk::new(interval);
        while let Some(rest) = walk.rest() {
            let Some((nearest, id)) = self.glass.nearest_one_hit_in(ray, &prepared, rest) else {
                break;
            };
            let tri = self.glass.mesh.triangle(id as usize);
            let Some(window) = walk.window(nearest.t, tri.hit_error(ray, &nearest).t) else {
                break;
            };
            found.clear();
            self.glass.one_hits_in(ray, &prepared, window, &mut found);
            let sorted = walk.advance(&mut found, |found| found.0.t);
            out.extend(
                sorted
                    .iter()
                    .map(|&(hit, triangle)| Crossing { hit, triangle }),
            );
        }
        out
    }

    /// The fraction of light, per channel, that passes along `ray` within
    /// `interval` (a shadow segment): zero when an opaque surface blocks
    /// it, otherwise [`ShadowScene::tint`] once for each surface of the
    /// glass crossed.
    pub fn transmittance(&self, ray: &Ray, interval: Interval<f32>) -> Vec3 {
        if self.blocked(ray, interval) {
            return Vec3::ZERO;
        }
        self.crossings(ray, interval)
            .iter()
            .fold(Vec3::ONE, |through, _| through * self.tint)
    }

    /// The light arriving at a surface point from one sample of the area
    /// light and from each point light, per unit area of a surface whose
    /// shading normal is `shading` (turned to face the light's side by
    /// the caller), each through the shadow segment's transmittance.
    /// `geometric` is the unit geometric normal on the same side.
    pub fn irradiance(
        &self,
        x: &SurfacePoint,
        shading: Vec3,
        geometric: Vec3,
        rng: &mut Rng,
        segments: &mut u64,
    ) -> Vec3 {
        let mut light = Vec3::ZERO;
        // The area light, sampled uniformly over its area: the estimate is
        // L cos_x cos_y A / d^2.
        let y = self.light.sample(rng);
        let w = y.point - x.point;
        let d2 = w.length_squared();
        let dir = w / d2.sqrt();
        let (cos_x, cos_y) = (shading.dot(dir), -self.light.normal.dot(dir));
        if cos_x > 0.0
            && geometric.dot(dir) > 0.0
            && cos_y > 0.0
            && let Some((ray, segment)) = x.spawn_to(&y)
        {
            *segments += 1;
            let through = self.transmittance(&ray, segment);
            light += self.light.radiance * through * (cos_x * cos_y * self.light.area / d2);
        }
        for point in &self.points {
            let w = point.position - x.point;
            let d2 = w.length_squared();
            let dir = w / d2.sqrt();
            let cos_x = shading.dot(dir);
            if cos_x > 0.0
                && geometric.dot(dir) > 0.0
                && let Some((ray, segment)) = x.spawn_to_point(point.position)
            {
                *segments += 1;
                let through = self.transmittance(&ray, segment);
                light += point.intensity * through * (cos_x / d2);
            }
        }
        light
    }

    /// The light leaving `hit` back along `ray`.
    pub fn shade(&self, ray: &Ray, hit: &OpaqueHit, rng: &mut Rng, segments: &mut u64) -> Vec3 {
        let Some(object) = hit.object else {
            // The light, bright on its emitting side only.
            return if ray.dir.dot(self.light.normal) < 0.0 {
                self.light.radiance
            } else {
                Vec3::splat(0.05)
            };
        };
        let (geometric, shading) = facing(ray, hit.surface.normal, hit.shading);
        let e = self.irradiance(&hit.surface, shading, geometric, rng, segments);
        let albedo = self.opaque[object].material.albedo_at(hit.surface.point);
        albedo * (AMBIENT + e / std::f32::consts::PI)
    }

    /// The light arriving along a camera ray, and the number of glass
    /// surfaces it crossed: whatever is behind the glass, tinted once per
    /// surface, with a faint sheen added at each surface (weighted by what
    /// the surfaces in front of it let through, so the order matters).
    pub fn radiance(&self, ray: &Ray, rng: &mut Rng, segments: &mut u64) -> (Vec3, usize) {
        let everything = Interval::up_to(f32::INFINITY).expect("a valid interval");
        let hit = self.nearest(ray, everything);
        let behind = match &hit {
            Some(hit) => self.shade(ray, hit, rng, segments),
            None => sky(ray.dir) * 0.5,
        };
        let t_end = hit.map_or(f32::INFINITY, |h| h.t);
        let crossings = self.crossings(ray, up_to(everything, t_end));
        let unit = ray.dir.normalize();
        let mut colour = Vec3::ZERO;
        let mut through = Vec3::ONE;
        for c in &crossings {
            let n = self.glass.mesh.triangle(c.triangle as usize).normal();
            let cos = n.normalize_or_zero().dot(unit).abs();
            colour += through * SHEEN * (0.15 + (1.0 - cos).powi(3));
            through *= self.tint;
        }
        (colour + through * behind, crossings.len())
    }
}

/// The glass's own sheen per surface crossed, before the grazing-angle
/// term.
const SHEEN: Vec3 = Vec3::new(0.45, 0.60, 0.62);

/// A rendered image of the shadows scene.
#[derive(Clone, Debug)]
pub struct ShadowImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear colours, row by row from the top.
    pub pixels: Vec<Vec3>,
    /// How many glass surfaces the ray through each pixel's centre
    /// crossed, row by row.
    pub crossings: Vec<usize>,
}

/// Renders the shadows scene with `samples` rays per pixel (the first
/// through the pixel's centre, the others at random points of the pixel;
/// each takes its own sample of the area light) on all cores, calling
/// `row_done` after each row. Returns the image, the number of camera rays
/// and the number of shadow segments traced.
pub fn render_shadows(
    scene: &ShadowScene,
    samples: u32,
    row_done: &(dyn Fn() + Sync),
) -> (ShadowImage, u64, u64) {
    let camera = &scene.camera;
    let (width, height) = (camera.width(), camera.height());
    let (pixels, crossings, [rays, segments]) = render_pixels(
        (width, height),
        samples,
        row_done,
        |x, y, _, rng, counts| {
            scene.radiance(&camera.ray(CameraSample::new(x, y)), rng, &mut counts[1])
        },
    );
    let image = ShadowImage {
        width,
        height,
        pixels,
        crossings,
    };
    (image, rays, segments)
}
