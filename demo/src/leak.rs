//! The `leak` scene: the watertightness experiment, a closed mesh with a
//! vertex on the centre ray of every pixel, traced with each triangle
//! kernel, and the same tile made of bilinear patches traced with each
//! patch kernel; the rays that get into it unreported counted and drawn.

use std::collections::HashMap;

use rayhit::glam::Vec3;
use rayhit::{Camera, Intersect, Patch, PinholeCamera, PreparedRay, Ray, Side};
use rayhit_testkit::textbook::reshetov;
use rayon::prelude::*;

use crate::mesh::{Bvh, Kernel, Mesh, shell};

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
    /// The same tile as bilinear patches.
    pub patches: PatchTile,
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
        patches: PatchTile::new(&mesh, columns, rows, (first_column, first_row)),
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
    /// The kernel's name.
    pub name: &'static str,
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
        self.report(kernel.name(), row_done, |_, _, ray| {
            let prepared = PreparedRay::new(ray);
            self.mesh
                .intersect(ray, &prepared, f32::INFINITY, kernel, false)
                .map(|(hit, _)| hit.side)
        })
    }

    /// The same for the tile of bilinear patches, with `kernel`.
    pub fn run_patches(&self, kernel: PatchKernel, row_done: &(dyn Fn() + Sync)) -> LeakReport {
        self.report(kernel.name(), row_done, |i, j, ray| {
            let mut nearest: Option<(f32, Side)> = None;
            for &k in &self.patches.candidates(i, j) {
                let patch = &self.patches.patches[k];
                let t_max = nearest.map_or(f32::INFINITY, |n| n.0);
                let hit = match kernel {
                    PatchKernel::Rayhit => patch.hit(ray, t_max).map(|h| (h.t, h.side)),
                    PatchKernel::Reshetov => reshetov(ray, patch, 0.0, t_max).map(|(t, u, v)| {
                        let side = if ray.dir.dot(patch.normal_at(u, v)) < 0.0 {
                            Side::Front
                        } else {
                            Side::Back
                        };
                        (t, side)
                    }),
                };
                if hit.is_some() {
                    nearest = hit;
                }
            }
            nearest.map(|n| n.1)
        })
    }

    /// Traces every pixel-centre ray (on all cores, calling `row_done`
    /// after each row), `first` giving the side of its first hit, and
    /// counts the leaks.
    fn report(
        &self,
        name: &'static str,
        row_done: &(dyn Fn() + Sync),
        first: impl Fn(u32, u32, &Ray) -> Option<Side> + Sync,
    ) -> LeakReport {
        let (width, height) = (self.camera.width(), self.camera.height());
        let outcomes: Vec<Outcome> = (0..height)
            .into_par_iter()
            .flat_map_iter(|j| {
                let row: Vec<Outcome> = (0..width)
                    .map(|i| match first(i, j, &self.camera.pixel_ray(i, j)) {
                        None => Outcome::Nothing,
                        Some(Side::Front) => Outcome::Outside,
                        Some(_) => Outcome::Inside,
                    })
                    .collect();
                row_done();
                row
            })
            .collect();
        let mut report = LeakReport {
            name,
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

/// The patch experiment's kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatchKernel {
    /// `Patch::hit`: watertight.
    Rayhit,
    /// Reshetov's textbook formulas, `t > 0`.
    Reshetov,
}

impl PatchKernel {
    /// Both kernels, rayhit's first.
    pub const ALL: [PatchKernel; 2] = [PatchKernel::Rayhit, PatchKernel::Reshetov];

    /// The function this kernel calls.
    pub fn name(self) -> &'static str {
        match self {
            PatchKernel::Rayhit => "Patch::hit (watertight)",
            PatchKernel::Reshetov => "Reshetov's patch test (textbook)",
        }
    }
}

/// The leak scene's tile as bilinear patches: each cell of the front and
/// back surfaces, and each wall, the patch through the four corners of
/// the shell's two triangles there (so the cells of the curved surfaces
/// are not planar), wound as they are. Every corner lies on a pixel-centre
/// ray, and a patch lies in the cone of its corners' rays from the
/// origin, so a pixel-centre ray can only meet the patches with a corner
/// on its own ray or a neighbouring one: those are its candidates.
#[derive(Clone, Debug)]
pub struct PatchTile {
    /// The patches: per cell, row by row, the front then the back; then
    /// the walls.
    pub patches: Vec<Patch>,
    /// Grid points per row and per column.
    columns: u32,
    rows: u32,
    /// The pixel of grid point `(0, 0)`.
    first: (u32, u32),
    /// The walls with a corner on each grid point's ray.
    walls: HashMap<(u32, u32), Vec<usize>>,
}

impl PatchTile {
    /// The tile of the shell `mesh` of a `columns x rows` grid (as
    /// `shell` builds it: per cell a front and a back pair of triangles,
    /// then a pair per wall along the border), its grid point `(0, 0)` on
    /// pixel `first`.
    fn new(mesh: &Mesh, columns: u32, rows: u32, first: (u32, u32)) -> Self {
        let patches: Vec<Patch> = mesh
            .indices
            .chunks(2)
            .map(|pair| {
                let [t1, t2] = [pair[0], pair[1]];
                // The two triangles of a quad around its diagonal, wound
                // alike: [a, b, c] and [a, c, d], or after the shell's
                // flip [a, c, b] and [a, d, c].
                let cycle = if t1[2] == t2[1] {
                    [t1[0], t1[1], t1[2], t2[2]]
                } else {
                    [t2[0], t2[1], t2[2], t1[2]]
                };
                let [a, b, c, d] = cycle.map(|k| mesh.positions[k as usize]);
                Patch::new(a, b, d, c)
            })
            .collect();
        let cells = 2 * ((columns - 1) * (rows - 1)) as usize;
        let mut border: Vec<(u32, u32)> = Vec::new();
        border.extend((0..columns - 1).map(|i| (i, 0)));
        border.extend((0..rows - 1).map(|j| (columns - 1, j)));
        border.extend((1..columns).rev().map(|i| (i, rows - 1)));
        border.extend((1..rows).rev().map(|j| (0, j)));
        let mut walls: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
        for (k, &point) in border.iter().enumerate() {
            let next = border[(k + 1) % border.len()];
            walls.entry(point).or_default().push(cells + k);
            walls.entry(next).or_default().push(cells + k);
        }
        Self {
            patches,
            columns,
            rows,
            first,
            walls,
        }
    }

    /// The patches pixel `(i, j)`'s centre ray may meet: the cells around
    /// its grid point (front and back) and the walls with a corner on it.
    fn candidates(&self, i: u32, j: u32) -> Vec<usize> {
        let (Some(gi), Some(gj)) = (i.checked_sub(self.first.0), j.checked_sub(self.first.1))
        else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for cj in gj.saturating_sub(1)..=gj {
            for ci in gi.saturating_sub(1)..=gi {
                if ci + 1 < self.columns && cj + 1 < self.rows {
                    let cell = (cj * (self.columns - 1) + ci) as usize;
                    out.extend([2 * cell, 2 * cell + 1]);
                }
            }
        }
        out.extend(self.walls.get(&(gi, gj)).into_iter().flatten());
        out
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
