//! The `cornell` scene: the Cornell box of "Ray Tracing: The Next Week",
//! every wall, block face and the light a [`Quad`], lit by the quad light
//! through shadow segments, with one diffuse bounce.
//!
//! Each quad is tested with `Quad::hit` (the two triangles of its
//! diagonal through the watertight test): the walls share their edges bit
//! for bit, so no ray slips out of the box between two walls, and the
//! blocks' faces share theirs. Light is gathered by sampling a point of
//! the light ([`Quad::surface_point_at`]) and tracing the segment to it
//! from the shaded point with [`SurfacePoint::spawn_to`] and
//! [`Intersect::occluded`] over its interval: neither the shaded surface
//! nor the light can block it, so there is no epsilon and no shadow acne.

use rayhit::glam::{Mat3, Vec3};
use rayhit::{Camera, CameraSample, Intersect, PinholeCamera, PreparedRay, Quad, Ray, Surface};
use rayhit::{QuadHit, SurfacePoint};

use crate::renderer::{Rng, camera_at, render_pixels};

/// One quad of the scene and its diffuse reflectance.
#[derive(Clone, Copy, Debug)]
pub struct Face {
    /// A name for messages.
    pub name: &'static str,
    /// Its geometry.
    pub quad: Quad,
    /// Its diffuse reflectance (black for the light).
    pub albedo: Vec3,
}

/// The scene.
#[derive(Debug)]
pub struct CornellScene {
    /// The camera, in front of the open side.
    pub camera: PinholeCamera,
    /// The walls, the blocks' faces and the light.
    pub faces: Vec<Face>,
    /// Index of the light in [`CornellScene::faces`].
    pub light: usize,
    /// The light's radiance, leaving its lower side.
    pub radiance: Vec3,
}

/// The nearest hit of a ray: the face and the hit.
#[derive(Clone, Copy, Debug)]
pub struct FaceHit {
    /// Index in [`CornellScene::faces`].
    pub face: usize,
    /// The hit.
    pub hit: QuadHit,
}

/// The eight corners of the block from the origin to `size`, turned about
/// `y` by `degrees` and moved by `offset`, and its six faces wound
/// outwards.
fn block(size: Vec3, degrees: f32, offset: Vec3) -> [Quad; 6] {
    let turn = Mat3::from_rotation_y(degrees.to_radians());
    let p = |x: f32, y: f32, z: f32| turn * Vec3::new(x * size.x, y * size.y, z * size.z) + offset;
    // Corner `xyz` for x, y, z each 0 or 1, computed once so that faces
    // share them bit for bit.
    let c: Vec<Vec3> = (0..8)
        .map(|i| p((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect();
    let q = |a: usize, b: usize, cc: usize, d: usize| Quad::new(c[a], c[b], c[cc], c[d]);
    [
        q(0, 2, 3, 1), // z = 0 side, normal -z
        q(4, 5, 7, 6), // z = 1, +z
        q(0, 4, 6, 2), // x = 0, -x
        q(1, 3, 7, 5), // x = 1, +x
        q(0, 1, 5, 4), // y = 0, -y
        q(2, 6, 7, 3), // y = 1, +y
    ]
}

/// The Cornell box of "The Next Week" (555 units a side, open towards the
/// camera), for a `width` by `height` picture.
pub fn cornell_scene(width: u32, height: u32) -> CornellScene {
    let camera = camera_at(
        Vec3::new(278.0, 278.0, -800.0),
        Vec3::new(278.0, 278.0, 0.0),
        width,
        height,
    );
    let (red, white, green) = (
        Vec3::new(0.65, 0.05, 0.05),
        Vec3::splat(0.73),
        Vec3::new(0.12, 0.45, 0.15),
    );
    let v = Vec3::new;
    let wall = |name, corner, u, w, albedo| Face {
        name,
        quad: Quad::parallelogram(corner, u, w),
        albedo,
    };
    let mut faces = vec![
        wall(
            "green wall",
            v(555., 0., 0.),
            v(0., 555., 0.),
            v(0., 0., 555.),
            green,
        ),
        wall(
            "red wall",
            v(0., 0., 0.),
            v(0., 0., 555.),
            v(0., 555., 0.),
            red,
        ),
        wall(
            "floor",
            v(0., 0., 0.),
            v(555., 0., 0.),
            v(0., 0., 555.),
            white,
        ),
        wall(
            "ceiling",
            v(555., 555., 555.),
            v(-555., 0., 0.),
            v(0., 0., -555.),
            white,
        ),
        wall(
            "back wall",
            v(0., 0., 555.),
            v(0., 555., 0.),
            v(555., 0., 0.),
            white,
        ),
    ];
    for quad in block(v(165., 330., 165.), 15.0, v(265., 0., 295.))
        .into_iter()
        .chain(block(v(165., 165., 165.), -18.0, v(130., 0., 65.)))
    {
        faces.push(Face {
            name: "block",
            quad,
            albedo: white,
        });
    }
    let light = faces.len();
    faces.push(wall(
        "light",
        v(343., 554., 332.),
        v(0., 0., -105.),
        v(-130., 0., 0.),
        Vec3::ZERO,
    ));
    CornellScene {
        camera,
        faces,
        light,
        radiance: Vec3::splat(15.0),
    }
}

impl CornellScene {
    /// The nearest hit of `ray` at `0 < t <= t_max`.
    pub fn nearest(&self, ray: &Ray, t_max: f32) -> Option<FaceHit> {
        let prepared = PreparedRay::new(ray);
        let mut best = None;
        let mut t_max = t_max;
        for (face, f) in self.faces.iter().enumerate() {
            if let Some(hit) = f.quad.hit(&prepared, t_max) {
                t_max = hit.t;
                best = Some(FaceHit { face, hit });
            }
        }
        best
    }

    /// Whether anything blocks the segment `(ray, interval)`.
    pub fn blocked(&self, ray: &Ray, interval: rayhit::Interval<f32>) -> bool {
        let prepared = PreparedRay::new(ray);
        self.faces
            .iter()
            .any(|f| f.quad.occluded(&prepared, interval))
    }

    /// A uniformly distributed point of the light, with the bounds a hit
    /// there would have.
    pub fn light_sample(&self, rng: &mut Rng) -> SurfacePoint {
        self.faces[self.light]
            .quad
            .surface_point_at(rng.next_f32(), rng.next_f32())
    }

    /// The light reaching `x` (a point of a diffuse surface with unit
    /// normal `n` facing the viewer) straight from the light: one sample
    /// of it, through a segment that neither end's surface can block.
    pub fn direct(&self, x: &SurfacePoint, n: Vec3, rng: &mut Rng, segments: &mut u64) -> Vec3 {
        let light = &self.faces[self.light].quad;
        let y = self.light_sample(rng);
        let w = y.point - x.point;
        let d2 = w.length_squared();
        let dir = w / d2.sqrt();
        // The light faces down: the cosine at its end is `dir . +y`.
        let (cos_x, cos_y) = (n.dot(dir), dir.y);
        if cos_x <= 0.0 || cos_y <= 0.0 {
            return Vec3::ZERO;
        }
        let Some((ray, segment)) = x.spawn_to(&y) else {
            return Vec3::ZERO;
        };
        *segments += 1;
        if self.blocked(&ray, segment) {
            return Vec3::ZERO;
        }
        // (The quad's normal is twice its area long.)
        let area = 0.5 * light.normal().length();
        self.radiance * (cos_x * cos_y * area / d2)
    }

    /// The light arriving along `ray` (reversed): the light's own where it
    /// is seen directly (`seen_light`), else at the nearest surface the
    /// direct light and, `bounces` times, one cosine-distributed bounce.
    /// `counts` gains the bounce rays and the shadow segments traced.
    pub fn radiance(
        &self,
        ray: &Ray,
        bounces: u32,
        seen_light: bool,
        rng: &mut Rng,
        counts: &mut [u64; 2],
    ) -> Vec3 {
        let Some(FaceHit { face, hit }) = self.nearest(ray, f32::INFINITY) else {
            return Vec3::ZERO;
        };
        if face == self.light {
            return if seen_light {
                self.radiance
            } else {
                Vec3::ZERO
            };
        }
        let f = &self.faces[face];
        let x = f.quad.surface_point(ray, &hit);
        let mut n = x.normal.normalize_or_zero();
        if n.dot(ray.dir) > 0.0 {
            n = -n;
        }
        // Diffuse: the direct irradiance times albedo / pi, and the bounce
        // (cosine-distributed, so its estimate is albedo times what it
        // brings back).
        let direct = self.direct(&x, n, rng, &mut counts[1]) / std::f32::consts::PI;
        let mut indirect = Vec3::ZERO;
        if bounces > 0 {
            let (a, b) = rng.disc();
            let (t1, t2) = n.any_orthonormal_pair();
            let dir = t1 * a + t2 * b + n * (1.0 - a * a - b * b).max(0.0).sqrt();
            counts[0] += 1;
            indirect = self.radiance(&x.spawn(dir), bounces - 1, false, rng, counts);
        }
        f.albedo * (direct + indirect)
    }
}

/// Renders the box with `samples` paths per pixel, two bounces each, on
/// all cores, calling `row_done` after each row: the pixels, and the rays
/// (camera and bounce) and shadow segments traced.
pub fn render_cornell(
    scene: &CornellScene,
    samples: u32,
    row_done: &(dyn Fn() + Sync),
) -> (Vec<Vec3>, [u64; 2]) {
    let camera = &scene.camera;
    let (pixels, _, counts) = render_pixels(
        (camera.width(), camera.height()),
        samples,
        row_done,
        |x, y, _, rng, counts| {
            let ray = camera.ray(CameraSample::new(x, y));
            (scene.radiance(&ray, 2, true, rng, counts), ())
        },
    );
    (pixels, counts)
}
