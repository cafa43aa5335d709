//! The `leak` scene: the watertightness experiment, a closed mesh with a
//! vertex on the centre ray of every pixel, traced with each triangle
//! kernel, and the rays that get into it unreported counted and drawn.

use rayhit::glam::Vec3;
use rayhit::{Camera, PinholeCamera, PreparedRay, Side};
use rayon::prelude::*;

use crate::mesh::{Bvh, Kernel, shell};

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
