//! What the demo's scenes share: materials (a checker and its box filter
//! among them), the sun's and the sky's light, the sky itself, the
//! per-pixel random numbers, the shading helpers, the parallel pixel loop
//! and the conversion to 8-bit sRGB. The `render` binary and the tests in
//! `tests/render/` run this very code.

use rayhit::glam::Vec3;
use rayhit::{PinholeCamera, Ray, SurfacePoint, Triangle};
use rayon::prelude::*;

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

/// A pinhole camera at `eye` looking at `target`, `y` up, with a vertical
/// field of view of 40 degrees, for a `width` by `height` picture.
pub fn camera_at(eye: Vec3, target: Vec3, width: u32, height: u32) -> PinholeCamera {
    PinholeCamera::from_fov(
        eye,
        target - eye,
        Vec3::Y,
        40f32.to_radians(),
        width,
        height,
    )
    .expect("a valid camera")
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
