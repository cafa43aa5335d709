//! rayhit inside a real compressed wide BVH: obvhs's CWBVH (Ylitie et al.
//! 2017) over closed meshes, traversed with obvhs's own traversal order
//! (closest hit) or an any-hit walk written here (shadow segments), and
//! either obvhs's node and triangle tests or rayhit's
//! (`QuantizedChildren::clip` on the node as obvhs stores it, and the
//! triangles' `hit` in the leaves).
//!
//! The meshes have shared vertices and every coordinate on a grid of
//! `2^-14`, so that a vertex or an edge midpoint minus a grid point is
//! exact: a ray built as `origin + 1 * (target - origin)` passes exactly
//! through its target, where only rounding decides which triangles around
//! it report the hit.

use std::time::Duration;

// The icosahedron and its subdivision, shared with the tests and the demo.
use rayhit_testkit::mesh;
use rayhit_testkit::rng::Pcg32;

use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::node::{CwBvhNode, extract_byte64};
use obvhs::ray::Ray as ObRay;
use obvhs::triangle::Triangle as ObTriangle;
use obvhs::{BvhBuildParams, traverse};
use rayhit::batch::{InPlace, QuantizedChildren, Simd, SimdWork, with_simd};
use rayhit::glam::{UVec2, Vec3, Vec3A};
use rayhit::{Bounds, Intersect, Interval, PreparedRay, Ray, RayForm, Search, Triangle};

/// A closed mesh: vertices and index triples, consistently wound, every
/// edge shared by exactly two triangles.
pub struct Mesh {
    pub name: &'static str,
    pub vertices: Vec<Vec3>,
    pub faces: Vec<[u32; 3]>,
    /// Where [`LeakRays`] finds points inside the solid.
    pub interior: Interior,
}

/// How to find a point inside a mesh's solid near a point of its surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Interior {
    /// A solid around the core circle of this radius about `z` (a torus):
    /// points near that circle.
    CoreCircle(f64),
    /// A solid that contains the segment from the origin to every point of
    /// its surface (a sphere): points on that segment.
    StarFromOrigin,
    /// Any closed mesh: a point a short step from the surface along the
    /// vertex normal, to either side, kept where an exact count of the
    /// mesh's crossings by a ray from it is odd ([`Crossings`]).
    Tested,
}

/// The Stanford bunny as the npm package `bunny` 1.0.1 has it (public
/// domain; see the file's header).
const BUNNY: &str = include_str!("../data/bunny.txt");

/// `x` on the grid of `2^-14`.
fn snap(x: f64) -> f32 {
    ((x * 16384.0).round() / 16384.0) as f32
}

fn snap3(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(snap(x), snap(y), snap(z))
}

impl Mesh {
    /// A torus around `z` (radii 2 and 0.7), `nu` by `nv` quads, each split
    /// into two triangles.
    pub fn torus(nu: u32, nv: u32) -> Self {
        let mut vertices = Vec::new();
        for i in 0..nu {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
            for j in 0..nv {
                let b = std::f64::consts::TAU * f64::from(j) / f64::from(nv);
                let rr = 2.0 + 0.7 * b.cos();
                vertices.push(snap3(rr * a.cos(), rr * a.sin(), 0.7 * b.sin()));
            }
        }
        let at = |i: u32, j: u32| (i % nu) * nv + (j % nv);
        let mut faces = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                faces.push([p, q, r]);
                faces.push([p, r, s]);
            }
        }
        Mesh {
            name: "torus",
            vertices,
            faces,
            interior: Interior::CoreCircle(2.0),
        }
    }

    /// An icosphere of radius 1.5, `levels` times subdivided (20 4^levels
    /// triangles).
    pub fn icosphere(levels: u32) -> Self {
        let g = (1.0 + 5f64.sqrt()) / 2.0;
        let mut v: Vec<[f64; 3]> = mesh::ICOSAHEDRON_CORNERS
            .iter()
            .map(|&code| mesh::icosahedron_corner(code, g))
            .collect();
        let faces = mesh::subdivide(&mut v, mesh::ICOSAHEDRON_FACES.to_vec(), levels, |p, q| {
            [
                (p[0] + q[0]) / 2.0,
                (p[1] + q[1]) / 2.0,
                (p[2] + q[2]) / 2.0,
            ]
        });
        let vertices = v
            .iter()
            .map(|p| {
                let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() / 1.5;
                snap3(p[0] / l, p[1] / l, p[2] / l)
            })
            .collect();
        Mesh {
            name: "icosphere",
            vertices,
            faces,
            interior: Interior::StarFromOrigin,
        }
    }

    /// The Stanford bunny (3674 triangles, coordinates within about 10 of
    /// the origin) on the grid, each triangle split `levels` times into
    /// four by its edges' midpoints (flat: the surface does not change,
    /// and the midpoints are exact on a grid twice as fine per level).
    pub fn bunny(levels: u32) -> Self {
        let mut v: Vec<[f64; 3]> = Vec::new();
        let mut faces = Vec::new();
        for line in BUNNY.lines() {
            let mut words = line.split_whitespace();
            let kind = words.next();
            let mut num = || words.next().expect("three numbers").parse::<f64>();
            match kind {
                Some("v") => {
                    let [x, y, z] = [num(), num(), num()].map(|n| n.expect("a coordinate"));
                    v.push([f64::from(snap(x)), f64::from(snap(y)), f64::from(snap(z))]);
                }
                Some("f") => {
                    faces.push([num(), num(), num()].map(|n| n.expect("an index") as u32));
                }
                _ => {}
            }
        }
        let faces = mesh::subdivide(&mut v, faces, levels, |p, q| {
            [
                (p[0] + q[0]) / 2.0,
                (p[1] + q[1]) / 2.0,
                (p[2] + q[2]) / 2.0,
            ]
        });
        Mesh {
            name: match levels {
                0 => "bunny",
                1 => "bunny x4",
                2 => "bunny x16",
                _ => "bunny, subdivided",
            },
            // Exact: every coordinate is on a grid of 2^-16 or finer and
            // below 16 in size.
            vertices: v
                .iter()
                .map(|p| Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32))
                .collect(),
            faces,
            interior: Interior::Tested,
        }
    }

    /// The smallest box around the vertices.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.vertices
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    pub fn triangles(&self) -> Vec<Triangle> {
        self.faces
            .iter()
            .map(|f| {
                let p = |i: usize| self.vertices[f[i] as usize];
                Triangle::new(p(0), p(1), p(2))
            })
            .collect()
    }

    /// The triangles' normals in exact arithmetic (the grid coordinates
    /// make every product and difference exact in `f64`).
    fn normal(&self, f: [u32; 3]) -> [f64; 3] {
        let p = |i: usize| self.vertices[f[i] as usize].as_dvec3();
        let (a, b, c) = (p(0), p(1), p(2));
        (b - a).cross(c - a).to_array()
    }
}

/// Rays aimed exactly at vertices and edge midpoints of a mesh.
pub struct LeakRays {
    /// From inside the solid: each must hit something.
    pub inside: Vec<Ray>,
    /// From outside, at vertices where every triangle around the target
    /// faces the ray: each must hit at `t <= 1`.
    pub outside: Vec<Ray>,
}

impl LeakRays {
    /// `count` rays of each kind, from the mesh's vertices and edge midpoints.
    pub fn new(mesh: &Mesh, count: usize, seed: u64) -> Self {
        let mut rng = Pcg32::new(seed);
        // Every vertex's star (the faces around it).
        let mut star: Vec<Vec<u32>> = vec![Vec::new(); mesh.vertices.len()];
        for (i, f) in mesh.faces.iter().enumerate() {
            for &v in f {
                star[v as usize].push(i as u32);
            }
        }
        let crossings = (mesh.interior == Interior::Tested).then(|| Crossings::new(mesh));
        let (lo, hi) = mesh.bounds();
        let size = f64::from((hi - lo).length());
        let vertex_normal = |v: u32| {
            let n = star[v as usize]
                .iter()
                .map(|&i| mesh.normal(mesh.faces[i as usize]))
                .fold([0.0; 3], |s, n| [s[0] + n[0], s[1] + n[1], s[2] + n[2]]);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            [n[0] / len, n[1] / len, n[2] / len]
        };
        // A point inside the solid near the target (a vertex `v` or the
        // midpoint of the edge from `v`), on the grid; `None` where the
        // tested kind found none.
        let interior = |target: Vec3, v: u32, rng: &mut Pcg32| -> Option<Vec3> {
            let t = target.as_dvec3();
            match mesh.interior {
                Interior::CoreCircle(radius) => {
                    let a = t.y.atan2(t.x);
                    let j = f64::from(rng.unit()) * 0.2 - 0.1;
                    Some(snap3(radius * a.cos() + j, radius * a.sin() - j, j))
                }
                Interior::StarFromOrigin => {
                    let s = 0.2 + 0.5 * f64::from(rng.unit());
                    Some(snap3(t.x * s, t.y * s, t.z * s))
                }
                Interior::Tested => {
                    let n = vertex_normal(v);
                    let step = size * (0.002 + 0.02 * f64::from(rng.unit()));
                    [step, -step].into_iter().find_map(|s| {
                        let p = snap3(t.x + s * n[0], t.y + s * n[1], t.z + s * n[2]);
                        crossings.as_ref().is_some_and(|c| c.inside(p)).then_some(p)
                    })
                }
            }
        };
        let mut inside = Vec::with_capacity(count);
        let mut outside = Vec::with_capacity(count);
        while inside.len() < count || outside.len() < count {
            let f = mesh.faces[rng.below(mesh.faces.len() as u32) as usize];
            let a = mesh.vertices[f[0] as usize];
            let b = mesh.vertices[f[1] as usize];
            // A vertex, or the midpoint of an edge (exact on the grid).
            let target = if rng.below(2) == 0 { a } else { (a + b) * 0.5 };
            if inside.len() < count
                && let Some(o) = interior(target, f[0], &mut rng)
            {
                inside.push(Ray::new(o, target - o));
            }
            if outside.len() < count && target == a {
                // From a point well outside along the vertex normal, only
                // where every triangle around the vertex faces the ray.
                let n = star[f[0] as usize]
                    .iter()
                    .map(|&i| mesh.normal(mesh.faces[i as usize]))
                    .fold([0.0; 3], |s, n| [s[0] + n[0], s[1] + n[1], s[2] + n[2]]);
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                let j = |rng: &mut Pcg32| 0.3 * (f64::from(rng.unit()) - 0.5);
                let t = target.as_dvec3();
                let o = snap3(
                    t.x + n[0] / len + j(&mut rng),
                    t.y + n[1] / len + j(&mut rng),
                    t.z + n[2] / len + j(&mut rng),
                );
                let d = target - o;
                let faces_ray = star[f[0] as usize].iter().all(|&i| {
                    let n = mesh.normal(mesh.faces[i as usize]);
                    let dd = d.as_dvec3();
                    n[0] * dd.x + n[1] * dd.y + n[2] * dd.z < 0.0
                });
                if faces_ray {
                    outside.push(Ray::new(o, d));
                }
            }
        }
        LeakRays { inside, outside }
    }
}

/// An exact point-in-solid test for a closed mesh: the parity of the
/// crossings of the ray from the point along `+x`, each counted once by
/// rayhit's one-hit rule (`Triangle::hit` with `EdgeRule::OneHit` over
/// `(0, inf]`, exact even through edges and vertices). The triangles are
/// sorted into a grid of cells over `y` and `z` (each into every cell its
/// closed box covers), so that a point tests only its cell's.
pub struct Crossings {
    /// The mesh's triangles.
    tris: Vec<Triangle>,
    /// Per cell (`y` major), the triangles whose closed box covers it.
    cells: Vec<Vec<u32>>,
    /// The grid's low corner in `y` and `z`.
    lo: [f32; 2],
    /// Cells per unit length in `y` and `z`.
    scale: [f32; 2],
}

/// Cells per side of [`Crossings`]'s grid.
const CELLS: usize = 64;

impl Crossings {
    /// Sorts the mesh's triangles into the grid.
    pub fn new(mesh: &Mesh) -> Self {
        let (lo, hi) = mesh.bounds();
        let lo = [lo.y, lo.z];
        let scale = [
            CELLS as f32 / (hi.y - lo[0]).max(f32::MIN_POSITIVE),
            CELLS as f32 / (hi.z - lo[1]).max(f32::MIN_POSITIVE),
        ];
        let mut c = Crossings {
            tris: mesh.triangles(),
            cells: vec![Vec::new(); CELLS * CELLS],
            lo,
            scale,
        };
        for (i, t) in c.tris.iter().enumerate() {
            let (a, b) = (t.a.min(t.b).min(t.c), t.a.max(t.b).max(t.c));
            let (y0, z0) = c.cell(a.y, a.z);
            let (y1, z1) = c.cell(b.y, b.z);
            for y in y0..=y1 {
                for z in z0..=z1 {
                    c.cells[y * CELLS + z].push(i as u32);
                }
            }
        }
        c
    }

    /// The cell of `(y, z)`: monotone in each coordinate (rounding and
    /// clamping keep order), so a point inside a closed box is in one of
    /// the cells the box was put in.
    fn cell(&self, y: f32, z: f32) -> (usize, usize) {
        let at = |x: f32, k: usize| {
            (((x - self.lo[k]) * self.scale[k]).floor().max(0.0) as usize).min(CELLS - 1)
        };
        (at(y, 0), at(z, 1))
    }

    /// Whether `p` is inside the solid (for `p` on no triangle).
    pub fn inside(&self, p: Vec3) -> bool {
        let ray = PreparedRay::new(&Ray::new(p, Vec3::X));
        let (y, z) = self.cell(p.y, p.z);
        let search = (
            rayhit::Interval::up_to(f32::INFINITY).expect("a range"),
            rayhit::EdgeRule::OneHit,
        );
        let n = self.cells[y * CELLS + z]
            .iter()
            .filter(|&&i| self.tris[i as usize].hit(&ray, search).is_some())
            .count();
        n % 2 == 1
    }
}

/// Entries on [`Scene::rayhit_occluded_with`]'s stack at most: seven a
/// level ([`Scene::new`] checks the tree's depth against it).
const ANY_STACK: usize = 128;

/// The nodes an any-hit walk has still to visit, depth first: of the
/// children a node passes on, the first is visited next and the others
/// wait on a stack of `N` node indices (the caller bounds the depth).
pub struct Pending<const N: usize> {
    next: Option<u32>,
    stack: [u32; N],
    top: usize,
}

impl<const N: usize> Default for Pending<N> {
    /// Nothing to visit.
    #[inline(always)]
    fn default() -> Self {
        Pending {
            next: None,
            stack: [0; N],
            top: 0,
        }
    }
}

impl<const N: usize> Pending<N> {
    /// A node to visit: the next one if none is, else kept on the stack.
    #[inline(always)]
    pub fn push(&mut self, node: u32) {
        if self.next.is_none() {
            self.next = Some(node);
        } else {
            self.stack[self.top] = node;
            self.top += 1;
        }
    }

    /// The node to visit now, `None` when the walk is over.
    #[inline(always)]
    pub fn pop(&mut self) -> Option<u32> {
        self.next.take().or_else(|| {
            self.top = self.top.checked_sub(1)?;
            Some(self.stack[self.top])
        })
    }
}

/// A mesh's CWBVH, built by obvhs, and its triangles in both crates' types.
pub struct Scene {
    pub bvh: CwBvh,
    pub ob_tris: Vec<ObTriangle>,
    pub tris: Vec<Triangle>,
}

/// Per child of every node, the exact bounds of the geometry under it
/// (the union of its triangles' corners), computed bottom-up.
fn child_bounds(bvh: &CwBvh, tris: &[Triangle]) -> Vec<[(Vec3, Vec3); 8]> {
    fn node_bounds(
        bvh: &CwBvh,
        tris: &[Triangle],
        i: usize,
        out: &mut Vec<[(Vec3, Vec3); 8]>,
    ) -> (Vec3, Vec3) {
        let node = &bvh.nodes[i];
        let mut all = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for c in 0..8 {
            if node.is_child_empty(c) {
                continue;
            }
            let b = if node.is_leaf(c) {
                let (start, count) = node.child_primitives(c);
                (start..start + count).fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                    let t = &tris[bvh.primitive_indices[p as usize] as usize];
                    (lo.min(t.a).min(t.b).min(t.c), hi.max(t.a).max(t.b).max(t.c))
                })
            } else {
                node_bounds(bvh, tris, node.child_node_index(c) as usize, out)
            };
            out[i][c] = b;
            all = (all.0.min(b.0), all.1.max(b.1));
        }
        all
    }
    let mut out = vec![[(Vec3::ZERO, Vec3::ZERO); 8]; bvh.nodes.len()];
    if !bvh.nodes.is_empty() {
        node_bounds(bvh, tris, 0, &mut out);
    }
    out
}

/// The node as rayhit reads it: references into obvhs's own arrays.
#[inline(always)]
pub fn children(node: &CwBvhNode) -> QuantizedChildren<'_> {
    QuantizedChildren {
        origin: node.p,
        exponents: node.e,
        min: [&node.child_min_x, &node.child_min_y, &node.child_min_z],
        max: [&node.child_max_x, &node.child_max_y, &node.child_max_z],
    }
}

/// `tris` as obvhs's triangles.
pub fn ob_triangles(tris: &[Triangle]) -> Vec<ObTriangle> {
    tris.iter()
        .map(|t| ObTriangle {
            v0: t.a.into(),
            v1: t.b.into(),
            v2: t.c.into(),
        })
        .collect()
}

impl Scene {
    pub fn new(mesh: &Mesh) -> Self {
        let tris = mesh.triangles();
        let ob_tris = ob_triangles(&tris);
        let bvh = build_cwbvh_from_tris(
            &ob_tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        fn depth(bvh: &CwBvh, i: usize) -> usize {
            let node = &bvh.nodes[i];
            (0..8)
                .filter(|&c| !node.is_child_empty(c) && !node.is_leaf(c))
                .map(|c| 1 + depth(bvh, node.child_node_index(c) as usize))
                .max()
                .unwrap_or(0)
        }
        assert!(
            bvh.nodes.is_empty() || 7 * (depth(&bvh, 0) + 1) <= ANY_STACK,
            "tree too deep"
        );
        Scene { bvh, ob_tris, tris }
    }

    /// How many occupied child boxes, decoded as rayhit decodes them, do not
    /// contain the geometry under them; and, with `fix`, rewrites those
    /// bytes in place with `QuantizedChildren::quantize` (the nodes stay
    /// obvhs's).
    pub fn check_quantization(&mut self, fix: bool) -> (usize, usize) {
        let bounds = child_bounds(&self.bvh, &self.tris);
        let (mut occupied, mut bad) = (0, 0);
        for (node, b) in self.bvh.nodes.iter_mut().zip(&bounds) {
            for c in 0..8 {
                if node.is_child_empty(c) {
                    continue;
                }
                occupied += 1;
                let (lo, hi) = b[c];
                let decoded = children(node).child_box(c).expect("valid node");
                if decoded.min.cmple(lo).all() && decoded.max.cmpge(hi).all() {
                    continue;
                }
                bad += 1;
                if fix {
                    let rows = [
                        (&mut node.child_min_x, &mut node.child_max_x),
                        (&mut node.child_min_y, &mut node.child_max_y),
                        (&mut node.child_min_z, &mut node.child_max_z),
                    ];
                    for (k, (min, max)) in rows.into_iter().enumerate() {
                        let (q0, q1) =
                            QuantizedChildren::quantize(node.p[k], node.e[k], lo[k], hi[k])
                                .expect("the node's box contains its children's");
                        min[c] = q0;
                        max[c] = q1;
                    }
                }
            }
        }
        (occupied, bad)
    }

    /// Closest hit with obvhs's node test and obvhs's triangle test.
    pub fn obvhs_closest(&self, ray: &Ray) -> f32 {
        let ob = ObRay::new_inf(ray.origin.into(), ray.dir.into());
        let mut hit = obvhs::ray::RayHit::none();
        self.bvh.ray_traverse(ob, &mut hit, |r, id| {
            self.ob_tris[self.bvh.primitive_indices[id] as usize].intersect(r)
        });
        hit.t
    }

    /// As [`Scene::obvhs_closest`], on obvhs's ray as given (its `tmin`
    /// and `tmax` kept).
    pub fn obvhs_closest_ob(&self, ray: &ObRay) -> f32 {
        let mut hit = obvhs::ray::RayHit::none();
        self.bvh.ray_traverse(*ray, &mut hit, |r, id| {
            self.ob_tris[self.bvh.primitive_indices[id] as usize].intersect(r)
        });
        hit.t
    }

    /// Closest hit with obvhs's node test and rayhit's triangle test.
    pub fn obvhs_nodes_rayhit_triangles(&self, ray: &Ray) -> f32 {
        let p = PreparedRay::new(ray);
        let ob = ObRay::new_inf(ray.origin.into(), ray.dir.into());
        let mut hit = obvhs::ray::RayHit::none();
        self.bvh.ray_traverse(ob, &mut hit, |r, id| {
            let t = &self.tris[self.bvh.primitive_indices[id] as usize];
            t.hit(&p, r.tmax).map_or(f32::INFINITY, |h| h.t)
        });
        hit.t
    }

    /// Closest hit with rayhit's node and triangle tests, in obvhs's
    /// traversal order (its `traverse!` with rayhit's kernels plugged in),
    /// the node test on the instruction set `simd` (chosen once, by
    /// `with_simd`).
    #[inline(always)]
    pub fn rayhit_closest<I: Simd>(&self, simd: I, ray: &PreparedRay, dir: Vec3A) -> f32 {
        self.rayhit_closest_on(&simd.ray(ray), ray, dir)
    }

    /// Closest hit with rayhit's node and triangle tests in obvhs's
    /// traversal order, the node test on `node_ray`: the prepared ray
    /// itself (plain calls, which pick the node test's instruction set per
    /// call) or its form on an instruction set from `with_simd`. The
    /// triangles take the prepared ray. `dir` is the ray's direction
    /// (obvhs orders the children by its octant).
    #[inline(always)]
    pub fn rayhit_closest_on<R: RayForm>(
        &self,
        node_ray: &R,
        ray: &PreparedRay,
        dir: Vec3A,
    ) -> f32 {
        // (The node read in place: see `InPlace`.)
        self.rayhit_closest_with(ray, dir, |node, t_max| {
            InPlace(|| children(node)).meets(node_ray, t_max)
        })
    }

    /// [`Scene::rayhit_closest_on`] with the node test `meets` (the
    /// children hit within `(0, t_max]`, one bit each).
    #[inline(always)]
    pub fn rayhit_closest_with(
        &self,
        ray: &PreparedRay,
        dir: Vec3A,
        meets: impl Fn(&CwBvhNode, f32) -> u32,
    ) -> f32 {
        self.closest_by(
            dir,
            meets,
            #[inline(always)]
            |i, t_max| self.tris[i].hit(ray, t_max).map(|hit| hit.t),
        )
    }

    /// [`Scene::rayhit_closest_with`] with the triangle test `hit` (the
    /// triangle's index in `tris` and `ob_tris`, and `t_max`: the hit's
    /// `t` within `(0, t_max]`, if any): the floor rows' leaves.
    #[inline(always)]
    pub fn closest_by(
        &self,
        dir: Vec3A,
        meets: impl Fn(&CwBvhNode, f32) -> u32,
        mut hit: impl FnMut(usize, f32) -> Option<f32>,
    ) -> f32 {
        let bvh = &self.bvh;
        let mut t_max = f32::INFINITY;
        let mut state = bvh.new_traversal(dir);
        let mut node;
        traverse!(
            bvh,
            node,
            state,
            hit_mask(node, meets(node, t_max), state.oct_inv4),
            {
                let i = bvh.primitive_indices[state.primitive_id as usize] as usize;
                if let Some(t) = hit(i, t_max) {
                    t_max = t;
                }
            }
        );
        t_max
    }

    /// Whether anything blocks the segment `segment` of the ray, with
    /// rayhit's node test over the same interval and `Triangle::occluded`
    /// in the leaves, stopping at the first occluder (as obvhs's
    /// `ray_traverse_miss` stops), by the walk of
    /// [`Scene::rayhit_occluded_with`]. `node_ray` as for
    /// [`Scene::rayhit_closest_on`].
    #[inline(always)]
    pub fn rayhit_occluded_on<R: RayForm>(
        &self,
        node_ray: &R,
        ray: &PreparedRay,
        segment: Interval<f32>,
    ) -> bool {
        self.rayhit_occluded_with(ray, segment, |node| {
            InPlace(|| children(node)).meets(node_ray, segment)
        })
    }

    /// [`Scene::rayhit_occluded_on`] with the node test `meets` (the
    /// children hit within the segment, one bit each): an any-hit walk
    /// written here rather than obvhs's ordered one. A node's children the
    /// segment meets are taken in their stored order: a leaf child's
    /// triangles tested at once, the first inner child visited next and
    /// the others kept on a stack of node indices. Any occluder ends the
    /// walk, so no order is worth its cost, and the walk reads obvhs's
    /// nodes directly, without the hit mask its ordered traversal needs.
    #[inline(always)]
    pub fn rayhit_occluded_with(
        &self,
        ray: &PreparedRay,
        segment: Interval<f32>,
        meets: impl Fn(&CwBvhNode) -> u32,
    ) -> bool {
        let bvh = &self.bvh;
        if bvh.nodes.is_empty() {
            return false;
        }
        // At most seven entries a level (checked when the scene is built).
        let mut pending = Pending::<ANY_STACK>::default();
        let mut at = 0usize;
        loop {
            let node = &bvh.nodes[at];
            let mut hits = meets(node);
            while hits != 0 {
                let c = hits.trailing_zeros() as usize;
                hits &= hits - 1;
                if node.is_child_empty(c) {
                    continue;
                }
                if node.is_leaf(c) {
                    let (start, count) = node.child_primitives(c);
                    for p in start..start + count {
                        let t = &self.tris[bvh.primitive_indices[p as usize] as usize];
                        if t.occluded(ray, segment) {
                            return true;
                        }
                    }
                } else {
                    pending.push(node.child_node_index(c));
                }
            }
            match pending.pop() {
                Some(next) => at = next as usize,
                None => return false,
            }
        }
    }

    /// Whether anything blocks the ray within `(0, t_max]`, by obvhs's
    /// own any-hit traversal (`CwBvh::ray_traverse_miss`) and triangle
    /// test.
    pub fn obvhs_occluded(&self, ray: &ObRay) -> bool {
        !self.bvh.ray_traverse_miss(*ray, |r, id| {
            self.ob_tris[self.bvh.primitive_indices[id] as usize].intersect(r)
        })
    }
}

/// The floor of a plain call per node: a function compiled with AVX-512
/// (256-bit forms) that takes obvhs's node by one reference and runs
/// rayhit's node test inlined there (`with_simd` inside, which picks its
/// AVX-512 arm), called once per node from the traversal compiled for the
/// default target. Against the plain `InPlace(..).meets` call it leaves
/// out only the instruction-set choice at the call (made inside instead);
/// the call and the kernel stay.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub struct NodeFloor(crate::avx512::Avx512);

#[cfg(target_arch = "x86_64")]
impl NodeFloor {
    /// `Some` where the CPU has AVX2, AVX-512F and AVX-512VL.
    pub fn detect() -> Option<Self> {
        crate::avx512::Avx512::detect().map(NodeFloor)
    }

    /// The children of `node` the ray meets within `search`.
    #[inline(always)]
    pub fn meets(self, node: &CwBvhNode, ray: &PreparedRay, search: impl Into<Search>) -> u32 {
        // SAFETY: the CPU has the features the function is compiled with;
        // a `NodeFloor` holds an `Avx512`, which only detecting them makes.
        unsafe { node_meets_avx512(node, ray, search.into()) }
    }
}

/// [`NodeFloor::meets`]'s function: `with_simd` inside a function with
/// AVX-512 enabled, so that its AVX-512 arm is inlined here.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512vl")]
#[inline(never)]
fn node_meets_avx512(node: &CwBvhNode, ray: &PreparedRay, search: Search) -> u32 {
    struct One<'a>(&'a CwBvhNode, &'a PreparedRay, Search);
    impl SimdWork for One<'_> {
        type Output = u32;
        #[inline(always)]
        fn run<I: Simd>(self, simd: I) -> u32 {
            children(self.0).meets(&simd.ray(self.1), self.2)
        }
    }
    with_simd(One(node, ray, search))
}

/// obvhs's hit mask from rayhit's mask of the children hit: each hit
/// child's bits (one for an inner node, the unary primitive count for a
/// leaf) at its index, as obvhs's own node test builds it.
#[inline(always)]
fn hit_mask(node: &CwBvhNode, hits: u32, oct_inv4: u32) -> u32 {
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
    // (Over all eight children, as obvhs does, rather than over the hit
    // ones: no branch on how many there are.)
    let mut mask = 0u32;
    for c in 0..8 {
        if hits & (1 << c) != 0 {
            mask |= extract_byte64(child_bits8, c) << extract_byte64(bit_index8, c);
        }
    }
    mask
}

/// Every ray of a list through the rayhit pipeline, as `SimdWork`: each
/// prepared ray with its direction (obvhs's traversal order comes from the
/// direction's octant).
#[derive(Clone, Copy)]
pub struct RayhitPipeline<'a> {
    pub scene: &'a Scene,
    pub rays: &'a [(PreparedRay, Vec3A)],
}

impl SimdWork for RayhitPipeline<'_> {
    type Output = u64;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> u64 {
        let mut c = 0u64;
        for (r, d) in self.rays {
            c = c.wrapping_add(u64::from(self.scene.rayhit_closest(simd, r, *d).to_bits()));
        }
        c
    }
}

/// The counts of one pipeline on one mesh's leak rays.
#[derive(Debug, Default, Clone, Copy)]
pub struct Leaks {
    /// Rays from inside that hit nothing.
    pub inside_missed: usize,
    /// Rays from outside whose closest hit is not at or before the target
    /// (beyond `t = 1` by more than rounding, or none).
    pub passed_through: usize,
}

/// Counts leaks of a pipeline given as "closest hit `t` of a ray".
///
/// The target is at `t = 1` exactly; a closest hit computed within rounding
/// of it (a few ulps above 1; `1 + 2^-16` is far beyond that and far below
/// the next surface) is at the target.
pub fn count_leaks(rays: &LeakRays, closest: impl Fn(&Ray) -> f32) -> Leaks {
    let at_target = 1.0 + f32::powi(2.0, -16);
    Leaks {
        inside_missed: rays
            .inside
            .iter()
            .filter(|r| {
                let t = closest(r);
                t.is_nan() || t == f32::INFINITY
            })
            .count(),
        passed_through: rays
            .outside
            .iter()
            .filter(|r| {
                let t = closest(r);
                t.is_nan() || t > at_target
            })
            .count(),
    }
}

/// rayhit's pipeline for one ray, with the instruction set `with_simd`
/// picks.
pub fn rayhit_one(scene: &Scene, ray: &Ray) -> f32 {
    struct One<'a>(&'a Scene, PreparedRay, Vec3A);
    impl SimdWork for One<'_> {
        type Output = f32;
        #[inline(always)]
        fn run<I: Simd>(self, simd: I) -> f32 {
            self.0.rayhit_closest(simd, &self.1, self.2)
        }
    }
    with_simd(One(scene, PreparedRay::new(ray), ray.dir.into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Through obvhs's CWBVH, rayhit's node and triangle tests let no ray
    /// through a closed mesh, on rays aimed exactly at vertices and edge
    /// midpoints, where obvhs's own kernels (and obvhs's node test with
    /// rayhit's triangle test) do.
    #[test]
    fn rayhit_kernels_do_not_leak_through_a_cwbvh() {
        for mesh in [Mesh::torus(120, 90), Mesh::icosphere(4)] {
            let rays = LeakRays::new(&mesh, 20_000, 3);
            let mut scene = Scene::new(&mesh);
            let (children, _) = scene.check_quantization(true);
            assert!(children > 1000);
            let ours = count_leaks(&rays, |r| rayhit_one(&scene, r));
            assert_eq!(
                (ours.inside_missed, ours.passed_through),
                (0, 0),
                "{}",
                mesh.name
            );
            let theirs = count_leaks(&rays, |r| scene.obvhs_closest(r));
            assert!(
                theirs.inside_missed + theirs.passed_through > 0,
                "{}: {theirs:?}",
                mesh.name
            );
            // Their node test alone, with the watertight triangle test.
            let mixed = count_leaks(&rays, |r| scene.obvhs_nodes_rayhit_triangles(r));
            println!(
                "{}: obvhs {theirs:?}, obvhs nodes + Triangle::hit {mixed:?}, rayhit {ours:?}",
                mesh.name
            );
        }
    }
}
