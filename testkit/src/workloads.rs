//! Fixed-seed workloads shared by the kernel benches (`benches/kernels.rs`)
//! and the peers table (`benches/peers`), so that both time the same data.
//!
//! Every workload is a list of ray/shape pairs (4096 of them unless said
//! otherwise) drawn from a small PCG generator with a fixed seed, and is
//! named by how its rays relate to its shapes, which sets the hit rate:
//!
//! - `random`: origins and shapes scattered in a cube, directions uniform
//!   on the sphere: few hits;
//! - `aimed`: each ray aimed at a point near its shape: about half hit;
//! - `axis`: aimed, but every direction along a coordinate axis (zero
//!   components, infinite reciprocals), and a quarter of the rays lie in a
//!   face plane of their box (the slab test's `0 * inf` case);
//! - `camera`: the primary rays of a 64x64 pinhole camera over a 16x16
//!   grid of shapes, each pixel paired with the shape in front of it:
//!   coherent rays whose neighbours behave alike;
//! - `groups`: 512 rays, each against a group of 8 nearby shapes it is
//!   aimed into (a BVH node's children or a leaf's triangles).
//!
//! All of it is `f32`.

use rayhit::glam::Vec3;
use rayhit::{Aabb, Camera, Patch, PinholeCamera, Plane, Quad, Ray, Sphere, Triangle};

/// Pairs per workload.
pub const PAIRS: usize = 4096;
/// Shapes per group in the `groups` workloads.
pub const GROUP: usize = 8;

use crate::rng::Pcg32;

/// A named list of ray/box pairs.
#[derive(Clone, Debug)]
pub struct BoxWorkload {
    /// How the rays relate to the boxes (see the module docs).
    pub name: &'static str,
    /// The rays, one per pair.
    pub rays: Vec<Ray>,
    /// The boxes, one per pair.
    pub boxes: Vec<Aabb>,
}

/// A named list of ray/triangle pairs.
#[derive(Clone, Debug)]
pub struct TriangleWorkload {
    /// How the rays relate to the triangles (see the module docs).
    pub name: &'static str,
    /// The rays, one per pair.
    pub rays: Vec<Ray>,
    /// The triangles, one per pair.
    pub triangles: Vec<Triangle>,
}

/// A named list of ray/sphere pairs.
#[derive(Clone, Debug)]
pub struct SphereWorkload {
    /// How the rays relate to the spheres (see the module docs).
    pub name: &'static str,
    /// The rays, one per pair.
    pub rays: Vec<Ray>,
    /// The spheres, one per pair.
    pub spheres: Vec<Sphere>,
}

/// A named list of ray/quad pairs.
#[derive(Clone, Debug)]
pub struct QuadWorkload {
    /// How the rays relate to the quads (see the module docs).
    pub name: &'static str,
    /// The rays, one per pair.
    pub rays: Vec<Ray>,
    /// The quads (parallelograms), one per pair.
    pub quads: Vec<Quad>,
}

/// A `patch` workload: ray `i` against patch `i`.
#[derive(Clone, Debug)]
pub struct PatchWorkload {
    /// How the rays relate to the patches (see the module docs).
    pub name: &'static str,
    /// The rays, one per pair.
    pub rays: Vec<Ray>,
    /// The patches, one per pair.
    pub patches: Vec<Patch>,
}

/// `groups` workloads: ray `i` against shapes `GROUP * i .. GROUP * (i + 1)`.
#[derive(Clone, Debug)]
pub struct BoxGroups {
    /// The rays.
    pub rays: Vec<Ray>,
    /// `GROUP` boxes per ray.
    pub boxes: Vec<Aabb>,
}

/// See [`BoxGroups`].
#[derive(Clone, Debug)]
pub struct TriangleGroups {
    /// The rays.
    pub rays: Vec<Ray>,
    /// `GROUP` triangles per ray.
    pub triangles: Vec<Triangle>,
}

fn random_box(rng: &mut Pcg32, spread: f32) -> Aabb {
    let c = rng.cube(spread);
    let h = Vec3::new(
        rng.range(0.25, 1.0),
        rng.range(0.25, 1.0),
        rng.range(0.25, 1.0),
    );
    Aabb::new(c - h, c + h)
}

fn random_triangle(rng: &mut Pcg32, spread: f32) -> Triangle {
    let c = rng.cube(spread);
    let mut corner = || c + rng.sphere() * rng.range(0.5, 2.0);
    Triangle::new(corner(), corner(), corner())
}

/// A ray that passes through `target` after running `4..16` along a random
/// unit direction.
fn through(rng: &mut Pcg32, target: Vec3, dir: Vec3) -> Ray {
    Ray::new(target - dir * rng.range(4.0, 16.0), dir)
}

/// A point in `b` grown about its centre by `grow` on each axis.
fn near_box(rng: &mut Pcg32, b: &Aabb, grow: f32) -> Vec3 {
    let c = (b.min + b.max) * 0.5;
    let h = (b.max - b.min) * 0.5;
    c + h * rng.cube(grow)
}

/// `a + u (b - a) + v (c - a)` with `u, v` uniform in `[-0.15, 0.85)`:
/// inside the triangle a little under half of the time.
fn near_triangle(rng: &mut Pcg32, t: &Triangle) -> Vec3 {
    let (u, v) = (rng.range(-0.15, 0.85), rng.range(-0.15, 0.85));
    t.a + (t.b - t.a) * u + (t.c - t.a) * v
}

/// The 64x64 camera of the `camera` workloads: at `z = 12` looking down
/// `-z` at the 16x16 grid of shapes in the plane `z = 0`.
pub fn camera() -> PinholeCamera {
    PinholeCamera::from_fov(
        Vec3::new(0.0, 0.0, 12.0),
        -Vec3::Z,
        Vec3::Y,
        60f32.to_radians(),
        64,
        64,
    )
    .expect("a valid camera")
}

/// The centre of grid cell `(i, j)` of the 16x16 grid that fills the
/// camera's view at `z = 0`, and the cell size.
fn grid_cell(i: u32, j: u32) -> (Vec3, f32) {
    // Half the view at distance 12 with a 60 degree field: 12 tan 30.
    let half = 12.0 * (30f32.to_radians()).tan();
    let cell = 2.0 * half / 16.0;
    let x = -half + (i as f32 + 0.5) * cell;
    let y = half - (j as f32 + 0.5) * cell;
    (Vec3::new(x, y, 0.0), cell)
}

/// The camera workloads' pixels: each `(pixel ray, grid cell)` pair.
fn camera_pairs() -> impl Iterator<Item = (Ray, Vec3, f32)> {
    let cam = camera();
    (0..64u32).flat_map(move |j| {
        (0..64u32).map(move |i| {
            let (c, cell) = grid_cell(i / 4, j / 4);
            (cam.pixel_ray(i, j), c, cell)
        })
    })
}

/// The four box workloads.
pub fn box_workloads() -> Vec<BoxWorkload> {
    let mut out = Vec::new();

    let mut rng = Pcg32::with_stream(1, 1);
    let (mut rays, mut boxes) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        boxes.push(random_box(&mut rng, 4.0));
        rays.push(Ray::new(rng.cube(4.0), rng.sphere()));
    }
    out.push(BoxWorkload {
        name: "random",
        rays,
        boxes,
    });

    let mut rng = Pcg32::with_stream(2, 1);
    let (mut rays, mut boxes) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        let b = random_box(&mut rng, 8.0);
        let target = near_box(&mut rng, &b, 1.7);
        let dir = rng.sphere();
        rays.push(through(&mut rng, target, dir));
        boxes.push(b);
    }
    out.push(BoxWorkload {
        name: "aimed",
        rays,
        boxes,
    });

    let mut rng = Pcg32::with_stream(3, 1);
    let (mut rays, mut boxes) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        // Boxes on a grid of quarter units, so that snapping an origin
        // coordinate to a face is exact.
        let q = |x: f32| (x * 4.0).round() * 0.25;
        let b = random_box(&mut rng, 8.0);
        let b = Aabb::new(b.min.map(q), b.max.map(q));
        let dir = rng.axis();
        let mut target = near_box(&mut rng, &b, 1.45);
        if rng.below(4) == 0 {
            // In a face plane of an axis the ray does not move along.
            let k = (dir.abs().max_position() + 1 + rng.below(2) as usize) % 3;
            target[k] = if rng.below(2) == 0 {
                b.min[k]
            } else {
                b.max[k]
            };
        }
        rays.push(through(&mut rng, target, dir));
        boxes.push(b);
    }
    out.push(BoxWorkload {
        name: "axis",
        rays,
        boxes,
    });

    let (mut rays, mut boxes) = (Vec::new(), Vec::new());
    for (ray, c, cell) in camera_pairs() {
        let h = Vec3::new(0.3 * cell, 0.3 * cell, 0.5);
        rays.push(ray);
        boxes.push(Aabb::new(c - h, c + h));
    }
    out.push(BoxWorkload {
        name: "camera",
        rays,
        boxes,
    });
    out
}

/// The four triangle workloads. Triangles face every way, so about half of
/// the hits are on the back side.
pub fn triangle_workloads() -> Vec<TriangleWorkload> {
    let mut out = Vec::new();

    let mut rng = Pcg32::with_stream(11, 2);
    let (mut rays, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        triangles.push(random_triangle(&mut rng, 3.0));
        rays.push(Ray::new(rng.cube(3.0), rng.sphere()));
    }
    out.push(TriangleWorkload {
        name: "random",
        rays,
        triangles,
    });

    let mut rng = Pcg32::with_stream(12, 2);
    let (mut rays, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        let t = random_triangle(&mut rng, 8.0);
        let target = near_triangle(&mut rng, &t);
        let dir = rng.sphere();
        rays.push(through(&mut rng, target, dir));
        triangles.push(t);
    }
    out.push(TriangleWorkload {
        name: "aimed",
        rays,
        triangles,
    });

    let mut rng = Pcg32::with_stream(13, 2);
    let (mut rays, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        let t = random_triangle(&mut rng, 8.0);
        let target = near_triangle(&mut rng, &t);
        let dir = rng.axis();
        rays.push(through(&mut rng, target, dir));
        triangles.push(t);
    }
    out.push(TriangleWorkload {
        name: "axis",
        rays,
        triangles,
    });

    let mut rng = Pcg32::with_stream(14, 2);
    let (mut rays, mut triangles) = (Vec::new(), Vec::new());
    // One triangle per cell, its winding flipped in every other cell.
    let mut cells = Vec::new();
    for cj in 0..16u32 {
        for ci in 0..16u32 {
            let (c, cell) = grid_cell(ci, cj);
            let mut corner = |a: f32| {
                let r = cell * rng.range(0.35, 0.6);
                c + Vec3::new(r * a.cos(), r * a.sin(), rng.range(-0.3, 0.3))
            };
            let (a, b, d) = (corner(0.3), corner(2.4), corner(4.4));
            cells.push(if (ci + cj) % 2 == 0 {
                Triangle::new(a, b, d)
            } else {
                Triangle::new(a, d, b)
            });
        }
    }
    for (k, (ray, _, _)) in camera_pairs().enumerate() {
        let (i, j) = (k as u32 % 64, k as u32 / 64);
        rays.push(ray);
        triangles.push(cells[((j / 4) * 16 + i / 4) as usize]);
    }
    out.push(TriangleWorkload {
        name: "camera",
        rays,
        triangles,
    });
    out
}

/// The three sphere workloads: `random`, `aimed` (at a point of the ball
/// grown by a fifth: most hit, some graze or miss) and `camera` (one
/// sphere per grid cell, radius 0.35 to 0.6 of the cell).
pub fn sphere_workloads() -> Vec<SphereWorkload> {
    let mut out = Vec::new();
    let mut rng = Pcg32::with_stream(15, 2);
    let (mut rays, mut spheres) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        spheres.push(Sphere::new(rng.cube(3.0), rng.range(0.1, 1.0)));
        rays.push(Ray::new(rng.cube(3.0), rng.sphere()));
    }
    out.push(SphereWorkload {
        name: "random",
        rays,
        spheres,
    });

    let mut rng = Pcg32::with_stream(16, 2);
    let (mut rays, mut spheres) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        let s = Sphere::new(rng.cube(8.0), rng.range(0.1, 2.0));
        let target = s.center + rng.sphere() * (s.radius * 1.2 * rng.unit());
        let dir = rng.sphere();
        rays.push(through(&mut rng, target, dir));
        spheres.push(s);
    }
    out.push(SphereWorkload {
        name: "aimed",
        rays,
        spheres,
    });

    let (mut rays, mut spheres) = (Vec::new(), Vec::new());
    let mut rng = Pcg32::with_stream(17, 2);
    let cells: Vec<Sphere> = (0..256u32)
        .map(|k| {
            let (c, cell) = grid_cell(k % 16, k / 16);
            Sphere::new(c, cell * rng.range(0.35, 0.6))
        })
        .collect();
    for (k, (ray, _, _)) in camera_pairs().enumerate() {
        let (i, j) = (k as u32 % 64, k as u32 / 64);
        rays.push(ray);
        spheres.push(cells[((j / 4) * 16 + i / 4) as usize]);
    }
    out.push(SphereWorkload {
        name: "camera",
        rays,
        spheres,
    });
    out
}

/// The three quad workloads, every quad a parallelogram
/// ([`Quad::parallelogram`]): `random`, `aimed` (at a point of the
/// parallelogram grown by a fifth on each side: most hit) and `camera`
/// (one square per grid cell, turned and tilted, 0.5 to 0.9 of the cell).
pub fn quad_workloads() -> Vec<QuadWorkload> {
    let mut out = Vec::new();
    let random_quad = |rng: &mut Pcg32, spread: f32, size: f32| {
        Quad::parallelogram(
            rng.cube(spread),
            rng.sphere() * rng.range(0.2, size),
            rng.sphere() * rng.range(0.2, size),
        )
    };
    let mut rng = Pcg32::with_stream(18, 2);
    let (mut rays, mut quads) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        quads.push(random_quad(&mut rng, 3.0, 2.0));
        rays.push(Ray::new(rng.cube(3.0), rng.sphere()));
    }
    out.push(QuadWorkload {
        name: "random",
        rays,
        quads,
    });

    let mut rng = Pcg32::with_stream(19, 2);
    let (mut rays, mut quads) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS {
        let q = random_quad(&mut rng, 8.0, 3.0);
        let (u, v) = (rng.range(-0.2, 1.2), rng.range(-0.2, 1.2));
        let target = q.a + (q.b - q.a) * u + (q.d - q.a) * v;
        let dir = rng.sphere();
        rays.push(through(&mut rng, target, dir));
        quads.push(q);
    }
    out.push(QuadWorkload {
        name: "aimed",
        rays,
        quads,
    });

    let mut rng = Pcg32::with_stream(20, 2);
    let cells: Vec<Quad> = (0..256u32)
        .map(|k| {
            let (c, cell) = grid_cell(k % 16, k / 16);
            let side = cell * rng.range(0.5, 0.9);
            let turn = rng.range(0.0, 1.5);
            let tilt = rng.range(-0.5, 0.5);
            let eu = Vec3::new(turn.cos(), turn.sin(), tilt) * side;
            let ev = Vec3::new(-turn.sin(), turn.cos(), -tilt) * side;
            Quad::parallelogram(c - (eu + ev) * 0.5, eu, ev)
        })
        .collect();
    let (mut rays, mut quads) = (Vec::new(), Vec::new());
    for (k, (ray, _, _)) in camera_pairs().enumerate() {
        let (i, j) = (k as u32 % 64, k as u32 / 64);
        rays.push(ray);
        quads.push(cells[((j / 4) * 16 + i / 4) as usize]);
    }
    out.push(QuadWorkload {
        name: "camera",
        rays,
        quads,
    });
    out
}

/// 512 rays, each aimed into a group of 8 boxes around one centre (a BVH
/// node's children).
pub fn box_groups() -> BoxGroups {
    let mut rng = Pcg32::with_stream(21, 3);
    let (mut rays, mut boxes) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS / GROUP {
        let c = rng.cube(8.0);
        for _ in 0..GROUP {
            let b = random_box(&mut rng, 1.5);
            boxes.push(Aabb::new(b.min + c, b.max + c));
        }
        let dir = rng.sphere();
        let target = c + rng.cube(1.5);
        rays.push(through(&mut rng, target, dir));
    }
    BoxGroups { rays, boxes }
}

/// 512 rays, each aimed into a group of 8 triangles around one centre (a
/// BVH leaf).
pub fn triangle_groups() -> TriangleGroups {
    let mut rng = Pcg32::with_stream(22, 3);
    let (mut rays, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS / GROUP {
        let c = rng.cube(8.0);
        for _ in 0..GROUP {
            let t = random_triangle(&mut rng, 1.0);
            triangles.push(Triangle::new(t.a + c, t.b + c, t.c + c));
        }
        let dir = rng.sphere();
        let target = c + rng.cube(1.0);
        rays.push(through(&mut rng, target, dir));
    }
    TriangleGroups { rays, triangles }
}

/// 512 rays, each aimed into a group of 8 spheres around one centre (a
/// leaf of particles): `GROUP` spheres per ray, in `spheres`.
pub fn sphere_groups() -> SphereWorkload {
    let mut rng = Pcg32::with_stream(23, 3);
    let (mut rays, mut spheres) = (Vec::new(), Vec::new());
    for _ in 0..PAIRS / GROUP {
        let c = rng.cube(8.0);
        for _ in 0..GROUP {
            spheres.push(Sphere::new(c + rng.cube(1.0), rng.range(0.1, 0.5)));
        }
        let dir = rng.sphere();
        let target = c + rng.cube(1.0);
        rays.push(through(&mut rng, target, dir));
    }
    SphereWorkload {
        name: "groups",
        rays,
        spheres,
    }
}

/// 1024 boxes scattered over a cube of side 16 (a BVH's nodes) and 64 rays
/// aimed at random ones among them: the `one ray against N boxes` sweep
/// takes the first `N`.
pub fn box_sweep() -> (Vec<Ray>, Vec<Aabb>) {
    let mut rng = Pcg32::with_stream(31, 4);
    let boxes: Vec<Aabb> = (0..1024).map(|_| random_box(&mut rng, 8.0)).collect();
    let rays = (0..64)
        .map(|_| {
            let b = boxes[rng.below(8) as usize];
            let target = near_box(&mut rng, &b, 1.0);
            let dir = rng.sphere();
            through(&mut rng, target, dir)
        })
        .collect();
    (rays, boxes)
}

/// 1024 triangles in a cube of side 4 (a BVH leaf's worth of a dense mesh,
/// and more) and 64 rays aimed at the first 8.
pub fn triangle_sweep() -> (Vec<Ray>, Vec<Triangle>) {
    let mut rng = Pcg32::with_stream(32, 4);
    let triangles: Vec<Triangle> = (0..1024).map(|_| random_triangle(&mut rng, 2.0)).collect();
    let rays = (0..64)
        .map(|_| {
            let t = triangles[rng.below(8) as usize];
            let target = near_triangle(&mut rng, &t);
            let dir = rng.sphere();
            through(&mut rng, target, dir)
        })
        .collect();
    (rays, triangles)
}

/// 4096 ray/plane pairs: planes through points in the cube with random
/// normals, rays from points in the cube in random directions (half of
/// them cross their plane ahead).
pub fn plane_pairs() -> (Vec<Ray>, Vec<Plane>) {
    let mut rng = Pcg32::with_stream(41, 5);
    let planes = (0..PAIRS)
        .map(|_| Plane::new(rng.cube(8.0), rng.sphere()))
        .collect();
    let rays = (0..PAIRS)
        .map(|_| Ray::new(rng.cube(8.0), rng.sphere()))
        .collect();
    (rays, planes)
}

/// The fraction of `flags` that are set.
pub fn rate(flags: impl IntoIterator<Item = bool>) -> f64 {
    let (mut n, mut k) = (0usize, 0usize);
    for f in flags {
        n += 1;
        k += usize::from(f);
    }
    k as f64 / n.max(1) as f64
}

/// The `patch` workloads: the `quad` workloads' parallelograms, each
/// twisted into a bilinear patch by lifting its corner `c` off the plane
/// by up to 0.3 of the longer edge either way (so no patch is planar);
/// `random` and `camera` keep the quads' rays, `aimed` aims each ray at a
/// point `P(u, v)` of its patch, `u`, `v` uniform in `[-0.2, 1.2)` (a hit
/// a little over half of the time).
pub fn patch_workloads() -> Vec<PatchWorkload> {
    let mut rng = Pcg32::with_stream(21, 2);
    quad_workloads()
        .into_iter()
        .map(|w| {
            let patches: Vec<Patch> = w
                .quads
                .iter()
                .map(|q| {
                    let (eu, ev) = (q.b - q.a, q.d - q.a);
                    let lift = eu.cross(ev).normalize_or_zero()
                        * eu.length().max(ev.length())
                        * rng.range(-0.3, 0.3);
                    Patch::new(q.a, q.b, q.d, q.c + lift)
                })
                .collect();
            let rays = if w.name == "aimed" {
                patches
                    .iter()
                    .map(|p| {
                        let (u, v) = (rng.range(-0.2, 1.2), rng.range(-0.2, 1.2));
                        let dir = rng.sphere();
                        through(&mut rng, p.point_at(u, v), dir)
                    })
                    .collect()
            } else {
                w.rays
            };
            PatchWorkload {
                name: w.name,
                rays,
                patches,
            }
        })
        .collect()
}
