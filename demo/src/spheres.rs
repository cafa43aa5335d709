//! The `spheres` scene: spheres of every size, from a ground sphere of
//! radius ten thousand and a moon thirteen thousand units away to glass
//! droplets a thousandth of a unit across a few centimetres from the lens,
//! traced with no epsilon anywhere, or with the textbook test for
//! comparison.
//!
//! With [`Kernel::Rayhit`] every sphere is tested with `Sphere::hit`
//! (eight at a time, `SphereBatch`), every hit becomes a point on its sphere
//! with `Surface::surface_point`, and every ray that leaves a sphere (to the
//! sun, reflected, refracted in or out) starts from `SurfacePoint::spawn`:
//! a ray leaving a sphere never meets it again, and one refracted into a
//! sphere always finds its far side, at any size and any distance.
//!
//! [`Kernel::Textbook`] is the quadratic of "Ray Tracing in One Weekend"
//! (`b^2 - a c`, then the near root or the far one above `t = 0.001`),
//! each new ray starting at the unmoved hit point: the ground's hits land
//! off its surface by more than 0.001 (acne: it shadows itself), the
//! droplets are shorter than 0.001 inside (holes: a ray refracted in never
//! finds the way out), and the moon's rim cancels in the discriminant.

use rayhit::batch::SphereBatch;
use rayhit::glam::Vec3;
use rayhit::{
    Camera, CameraSample, Intersect, IntersectLanes, PinholeCamera, PreparedRay, Ray, Side, Sphere,
    Surface, SurfacePoint,
};

use crate::renderer::{Material, Rng, SKY_LIGHT, SUN, camera_at, render_pixels, sky, toward_disc};

/// How a sphere's surface treats light.
#[derive(Clone, Copy, Debug)]
pub enum Look {
    /// Diffuse, lit by the sun and the sky.
    Matte(Material),
    /// A mirror, its reflection tinted by the colour.
    Mirror(Vec3),
    /// Clear glass of this index of refraction.
    Glass(f32),
}

/// One sphere of the scene.
#[derive(Clone, Copy, Debug)]
pub struct Ball {
    /// A name for messages.
    pub name: &'static str,
    /// Its geometry.
    pub sphere: Sphere,
    /// Its surface.
    pub look: Look,
}

/// Which ray/sphere test the scene is traced with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// `Sphere::hit`, with surface points and spawned rays.
    Rayhit,
    /// The textbook quadratic with `t > 0.001`, new rays from the hit point.
    Textbook,
}

/// The smallest `t` the textbook kernel accepts, as in "One Weekend".
pub const TEXTBOOK_T_MIN: f32 = 0.001;

/// The textbook ray/sphere test ("Ray Tracing in One Weekend", with `h =
/// d . (c - o)`): the near root of `a t^2 - 2 h t + c` if it is in
/// `(TEXTBOOK_T_MIN, t_max)`, else the far one, with the side. For
/// comparison only.
pub fn textbook(ray: &Ray, sphere: &Sphere, t_max: f32) -> Option<(f32, Side)> {
    let oc = sphere.center - ray.origin;
    let a = ray.dir.dot(ray.dir);
    let h = ray.dir.dot(oc);
    let c = oc.dot(oc) - sphere.radius * sphere.radius;
    let disc = h * h - a * c;
    // (A NaN discriminant misses too.)
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let inside = |t: f32| t > TEXTBOOK_T_MIN && t < t_max;
    let near = (h - root) / a;
    if inside(near) {
        return Some((near, Side::Front));
    }
    let far = (h + root) / a;
    inside(far).then_some((far, Side::Back))
}

/// Where a ray meets the scene: what is needed to shade the point and to
/// leave it.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Index of the sphere in [`SphereScene::balls`].
    pub ball: usize,
    /// Whether the ray enters the ball here ([`Side::Front`]) or leaves it.
    pub side: Side,
    /// The point with its error bound and the outward normal (the textbook
    /// kernel's: the computed point, no bound).
    pub surface: SurfacePoint,
    /// The unit outward normal.
    pub outward: Vec3,
}

/// The scene: a camera, the spheres, the sun and the kernel.
#[derive(Debug)]
pub struct SphereScene {
    /// The camera.
    pub camera: PinholeCamera,
    /// Every sphere.
    pub balls: Vec<Ball>,
    /// The spheres eight at a time, lane `l` of batch `b` being ball `8 b +
    /// l`.
    pub batches: Vec<SphereBatch<Vec3, 8>>,
    /// Unit vector towards the centre of the sun.
    pub sun: Vec3,
    /// The sun's angular radius (as the tangent).
    pub sun_radius: f32,
    /// The ray/sphere test.
    pub kernel: Kernel,
}

/// Reflections and refractions followed, at most.
pub const MAX_BOUNCES: u32 = 12;

impl SphereScene {
    /// The nearest hit of `ray` at `0 < t <= t_max` (for the textbook,
    /// `0.001 < t < t_max`).
    pub fn nearest(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (mut best, mut t_max) = (None, t_max);
        match self.kernel {
            Kernel::Rayhit => {
                let prepared = PreparedRay::new(ray);
                for (b, batch) in self.batches.iter().enumerate() {
                    if let Some((lane, hit)) = batch.hit(&prepared, t_max).nearest() {
                        (t_max, best) = (hit.t, Some((8 * b + lane, hit.t, hit.side)));
                    }
                }
            }
            Kernel::Textbook => {
                for i in 0..self.balls.len() {
                    if let Some((t, side)) = self.test(ray, i, t_max) {
                        (t_max, best) = (t, Some((i, t, side)));
                    }
                }
            }
        }
        best.map(|(ball, t, side)| self.hit_on(ray, ball, t, side))
    }

    /// Ball `ball` alone against `ray` at `0 < t <= t_max` (for the
    /// textbook, `0.001 < t < t_max`): `t` and the side.
    pub fn test(&self, ray: &Ray, ball: usize, t_max: f32) -> Option<(f32, Side)> {
        let sphere = &self.balls[ball].sphere;
        match self.kernel {
            Kernel::Rayhit => sphere.hit(ray, t_max).map(|h| (h.t, h.side)),
            Kernel::Textbook => textbook(ray, sphere, t_max),
        }
    }

    /// The hit record for `ray` meeting ball `ball` at `t`, on `side`.
    pub fn hit_on(&self, ray: &Ray, ball: usize, t: f32, side: Side) -> Hit {
        let sphere = &self.balls[ball].sphere;
        let surface = match self.kernel {
            Kernel::Rayhit => sphere.surface_point(ray, &rayhit::SphereHit { t, side }),
            Kernel::Textbook => {
                let point = ray.at(t);
                let normal = (point - sphere.center) / sphere.radius;
                SurfacePoint {
                    point,
                    point_error: Vec3::ZERO,
                    normal,
                    normal_error: Vec3::ZERO,
                }
            }
        };
        let outward = surface
            .normal
            .try_normalize()
            .unwrap_or(-ray.dir.normalize());
        Hit {
            t,
            ball,
            side,
            surface,
            outward,
        }
    }

    /// A ray leaving `hit` along `dir`: spawned off the surface by its
    /// error bound, or, for the textbook, from the hit point itself.
    pub fn leave(&self, hit: &Hit, dir: Vec3) -> Ray {
        match self.kernel {
            Kernel::Rayhit => hit.surface.spawn(dir),
            Kernel::Textbook => Ray::new(hit.surface.point, dir),
        }
    }

    /// The fraction of light that gets through along `ray` (to the sun):
    /// nothing past a mirror or a matte sphere, 70% through each glass
    /// sphere it meets.
    pub fn transmittance(&self, ray: &Ray) -> f32 {
        let mut through = 1.0;
        for (i, ball) in self.balls.iter().enumerate() {
            if self.test(ray, i, f32::INFINITY).is_some() {
                match ball.look {
                    Look::Glass(_) => through *= 0.7,
                    _ => return 0.0,
                }
            }
        }
        through
    }

    /// The light arriving along `ray` (reversed); `rays` counts every ray
    /// traced, this one included.
    pub fn radiance(&self, ray: &Ray, bounces: u32, rng: &mut Rng, rays: &mut u64) -> Vec3 {
        *rays += 1;
        let Some(hit) = self.nearest(ray, f32::INFINITY) else {
            return sky(ray.dir);
        };
        // The normal on the ray's side, and the direction onwards.
        let facing = if hit.side == Side::Front {
            hit.outward
        } else {
            -hit.outward
        };
        let dir = ray.dir.normalize();
        let onwards = |next: Vec3, rng: &mut Rng, rays: &mut u64| {
            if bounces >= MAX_BOUNCES {
                Vec3::ZERO
            } else {
                self.radiance(&self.leave(&hit, next), bounces + 1, rng, rays)
            }
        };
        match self.balls[hit.ball].look {
            Look::Matte(material) => {
                let to_sun = toward_disc(self.sun, self.sun_radius, rng);
                let cos = facing.dot(to_sun);
                let mut light = SKY_LIGHT;
                if cos > 0.0 {
                    *rays += 1;
                    light += SUN * cos * self.transmittance(&self.leave(&hit, to_sun));
                }
                material.albedo_at(hit.surface.point) * light
            }
            Look::Mirror(tint) => tint * onwards(dir.reflect(facing), rng, rays),
            Look::Glass(ior) => {
                let eta = if hit.side == Side::Front {
                    1.0 / ior
                } else {
                    ior
                };
                let refracted = dir.refract(facing, eta);
                // Schlick's approximation of Fresnel's reflectance.
                let cos = (-dir.dot(facing)).clamp(0.0, 1.0);
                let r0 = ((1.0 - ior) / (1.0 + ior)).powi(2);
                let reflectance = r0 + (1.0 - r0) * (1.0 - cos).powi(5);
                if refracted == Vec3::ZERO || rng.next_f32() < reflectance {
                    onwards(dir.reflect(facing), rng, rays)
                } else {
                    onwards(refracted, rng, rays)
                }
            }
        }
    }
}

/// The scene, seen by a `width` by `height` camera: a checkered ground
/// sphere of radius `1e4`, a matte, a glass and a mirror sphere of radius
/// 1, a ring of small spheres, a moon of radius `2e3` thirteen thousand
/// units away, and five droplets (radii `5e-4` to `1e-3`) three
/// centimetres in front of the camera.
pub fn sphere_scene(width: u32, height: u32, kernel: Kernel) -> SphereScene {
    let eye = Vec3::new(0.0, 1.6, 6.5);
    let target = Vec3::new(0.0, 0.8, 0.0);
    let camera = camera_at(eye, target, width, height);
    let matte = |r: f32, g: f32, b: f32| Look::Matte(Material::diffuse(r, g, b));
    let ball = |name, center, radius, look| Ball {
        name,
        sphere: Sphere::new(center, radius),
        look,
    };
    let mut balls = vec![
        ball(
            "ground",
            Vec3::new(0.0, -1e4, 0.0),
            1e4,
            Look::Matte(Material {
                checker: Some(Vec3::new(0.30, 0.33, 0.38)),
                ..Material::diffuse(0.72, 0.70, 0.66)
            }),
        ),
        ball(
            "moon",
            Vec3::new(-5e3, 2.6e3, -1.2e4),
            2e3,
            matte(0.85, 0.83, 0.78),
        ),
        ball(
            "matte",
            Vec3::new(-2.2, 1.0, 0.0),
            1.0,
            matte(0.80, 0.22, 0.16),
        ),
        ball("glass", Vec3::new(0.0, 1.0, 0.0), 1.0, Look::Glass(1.5)),
        ball(
            "mirror",
            Vec3::new(2.2, 1.0, 0.0),
            1.0,
            Look::Mirror(Vec3::new(0.95, 0.80, 0.55)),
        ),
    ];
    // A ring of small spheres around the three, every third glass, every
    // fifth a mirror.
    for k in 0..18 {
        let angle = k as f32 / 18.0 * std::f32::consts::TAU + 0.2;
        let radius = 0.22 + 0.06 * (k % 3) as f32;
        let distance = 3.6 + 0.5 * (k % 2) as f32;
        let center = Vec3::new(angle.cos() * distance, radius, angle.sin() * distance - 0.4);
        let hue = k as f32 / 18.0;
        let look = if k % 3 == 0 {
            Look::Glass(1.5)
        } else if k % 5 == 0 {
            Look::Mirror(Vec3::new(0.85, 0.85, 0.9))
        } else {
            matte(
                0.3 + 0.6 * (hue * 6.3).sin().abs(),
                0.3 + 0.6 * (hue * 4.1 + 1.0).sin().abs(),
                0.3 + 0.6 * (hue * 2.7 + 2.0).sin().abs(),
            )
        };
        balls.push(ball("small", center, radius, look));
    }
    // Droplets three centimetres from the lens, in the lower right of the
    // picture.
    let (forward, right, up) = (camera.forward(), camera.right(), camera.up());
    let droplets = [
        (0.004, -0.0060, 5e-4, Look::Glass(1.33)),
        (
            0.007,
            -0.0050,
            7e-4,
            Look::Mirror(Vec3::new(0.9, 0.9, 0.95)),
        ),
        (0.010, -0.0068, 1e-3, Look::Glass(1.33)),
        (0.013, -0.0045, 6e-4, matte(0.2, 0.5, 0.9)),
        (0.015, -0.0075, 5e-4, Look::Glass(1.33)),
    ];
    for (x, y, radius, look) in droplets {
        let center = eye + forward * 0.03 + right * x + up * y;
        balls.push(ball("droplet", center, radius, look));
    }
    let spheres: Vec<Sphere> = balls.iter().map(|b| b.sphere).collect();
    let batches = spheres
        .chunks(8)
        .map(|chunk| SphereBatch::from_slice(chunk).expect("at most eight spheres"))
        .collect();
    SphereScene {
        camera,
        balls,
        batches,
        sun: Vec3::new(-1.0, 0.9, 0.45).normalize(),
        sun_radius: 0.04,
        kernel,
    }
}

/// Renders `scene` with `samples` rays per pixel on all cores, calling
/// `row_done` after each row: the pixels (linear, row by row from the top)
/// and the number of rays traced.
pub fn render_spheres(
    scene: &SphereScene,
    samples: u32,
    row_done: &(dyn Fn() + Sync),
) -> (Vec<Vec3>, u64) {
    let camera = &scene.camera;
    let (pixels, _, [rays, _]) = render_pixels(
        (camera.width(), camera.height()),
        samples,
        row_done,
        |x, y, _, rng, counts| {
            let ray = camera.ray(CameraSample::new(x, y));
            (scene.radiance(&ray, 0, rng, &mut counts[0]), ())
        },
    );
    (pixels, rays)
}
