//! Triangle meshes built procedurally (icosphere, torus, a closed shell) and
//! a bounding volume hierarchy that finds a ray's hits among them.
//!
//! The hierarchy is the plainest kind: split the triangles at the median
//! centroid along the widest axis until at most `LEAF_SIZE` remain. Every
//! node's box is tested with the crate's prepared slab test, which never
//! misses a box that exact arithmetic says the ray meets, so a triangle is
//! never skipped because its box was rounded away; the root box is the
//! mesh's bounding box, tested before any triangle. The interval forms
//! (`occluded_in`, `nearest_one_hit_in`, `one_hits_in`) search `(t_min,
//! t_max]` with the crate's interval kernels, for shadow segments and for
//! walking every crossing along a ray.

use std::collections::HashMap;

use rayhit::glam::{DVec3, Mat3, Vec3};
use rayhit::{
    Aabb, Bounds, EdgeRule, Intersect, Interval, PreparedRay, Ray, Triangle, TriangleHit,
    ray_triangle,
};

/// Which ray/triangle kernel a mesh is intersected with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// `ray_triangle`: watertight.
    Watertight,
    /// `Triangle::moller_trumbore`: Moller-Trumbore, not watertight.
    MollerTrumbore,
}

impl Kernel {
    /// Both kernels, watertight first.
    pub const ALL: [Kernel; 2] = [Kernel::Watertight, Kernel::MollerTrumbore];

    /// The crate function this kernel calls.
    pub fn name(self) -> &'static str {
        match self {
            Kernel::Watertight => "ray_triangle (watertight)",
            Kernel::MollerTrumbore => "moller_trumbore (Moller-Trumbore)",
        }
    }

    /// The hit of `ray` with `tri` at `0 < t <= t_max`, if any.
    #[inline]
    pub fn intersect(self, ray: &Ray, tri: &Triangle, t_max: f32) -> Option<TriangleHit> {
        match self {
            Kernel::Watertight => ray_triangle(ray, tri, t_max),
            Kernel::MollerTrumbore => tri.moller_trumbore(ray, t_max),
        }
    }
}

/// An indexed triangle mesh. Triangles that share an edge share the vertex
/// indices, so their corners are bit-identical: what the watertight
/// guarantee asks for.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit shading normals, one per vertex; empty for flat shading.
    pub normals: Vec<Vec3>,
    /// Triangles as vertex indices, wound counter-clockwise seen from
    /// outside (the geometric normal points out).
    pub indices: Vec<[u32; 3]>,
}

impl Mesh {
    /// Triangle `i` as the crate's `Triangle`.
    pub fn triangle(&self, i: usize) -> Triangle {
        let [a, b, c] = self.indices[i].map(|k| self.positions[k as usize]);
        Triangle::new(a, b, c)
    }

    /// The unit shading normal at barycentrics `(u, v)` of triangle `i`, or
    /// `None` when the mesh is flat-shaded.
    pub fn shading_normal(&self, i: usize, u: f32, v: f32) -> Option<Vec3> {
        if self.normals.is_empty() {
            return None;
        }
        let [a, b, c] = self.indices[i].map(|k| self.normals[k as usize]);
        Some((a * (1.0 - u - v) + b * u + c * v).normalize())
    }

    /// Moves every vertex by `rotation` and then `offset`.
    pub fn transformed(mut self, rotation: Mat3, offset: Vec3) -> Self {
        for p in &mut self.positions {
            *p = rotation * *p + offset;
        }
        for n in &mut self.normals {
            *n = (rotation * *n).normalize();
        }
        self
    }
}

/// The icosahedron's twelve corners, `(0, +-1, +-g)` and their cyclic
/// permutations with `g` the golden ratio, coded per coordinate as 0, `+-1`
/// (for `+-1`) or `+-2` (for `+-g`), so that each user builds them in its
/// own precision: see [`icosahedron_corner`].
pub const ICOSAHEDRON_CORNERS: [[i8; 3]; 12] = [
    [-1, 2, 0],
    [1, 2, 0],
    [-1, -2, 0],
    [1, -2, 0],
    [0, -1, 2],
    [0, 1, 2],
    [0, -1, -2],
    [0, 1, -2],
    [2, 0, -1],
    [2, 0, 1],
    [-2, 0, -1],
    [-2, 0, 1],
];

/// The icosahedron's twenty faces, wound outward.
pub const ICOSAHEDRON_FACES: [[u32; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// Corner `code` of [`ICOSAHEDRON_CORNERS`] with the golden ratio `g` of
/// the caller's precision (`+-1` and `+-g` exactly, as literals would be).
pub fn icosahedron_corner<F>(code: [i8; 3], g: F) -> [F; 3]
where
    F: Copy + From<i8> + core::ops::Mul<Output = F>,
{
    code.map(|k| match k.abs() {
        2 => g * F::from(k.signum()),
        _ => F::from(k),
    })
}

/// Splits every face of `faces` into four, `levels` times: one new vertex
/// per edge, made by `midpoint` from the edge's two ends, pushed onto
/// `vertices` and shared by the two faces beside the edge. Each face
/// `[a, b, c]` becomes `[a, ab, ca]`, `[b, bc, ab]`, `[c, ca, bc]`,
/// `[ab, bc, ca]`, so the winding is kept.
pub fn subdivide<P>(
    vertices: &mut Vec<P>,
    mut faces: Vec<[u32; 3]>,
    levels: u32,
    midpoint: impl Fn(&P, &P) -> P,
) -> Vec<[u32; 3]> {
    for _ in 0..levels {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut between = |a: u32, b: u32| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let m = midpoint(&vertices[a as usize], &vertices[b as usize]);
                vertices.push(m);
                (vertices.len() - 1) as u32
            })
        };
        faces = faces
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (between(a, b), between(b, c), between(c, a));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    faces
}

/// A sphere of `radius` around `centre`: the icosahedron with each face
/// split into four `subdivisions` times (`20 * 4^subdivisions` triangles),
/// vertices pushed out to the sphere.
pub fn icosphere(centre: Vec3, radius: f32, subdivisions: u32) -> Mesh {
    let g = (1.0 + 5f32.sqrt()) / 2.0;
    let mut dirs: Vec<Vec3> = ICOSAHEDRON_CORNERS
        .iter()
        .map(|&code| Vec3::from_array(icosahedron_corner(code, g)).normalize())
        .collect();
    let faces = subdivide(
        &mut dirs,
        ICOSAHEDRON_FACES.to_vec(),
        subdivisions,
        |a, b| (*a + *b).normalize(),
    );
    Mesh {
        positions: dirs.iter().map(|&d| centre + d * radius).collect(),
        normals: dirs,
        indices: faces,
    }
}

/// A torus around the local `z` axis through the origin: the tube of radius
/// `minor` swept along the circle of radius `major`, `rings` segments around
/// the circle and `sides` around the tube (`2 * rings * sides` triangles).
pub fn torus(major: f32, minor: f32, rings: u32, sides: u32) -> Mesh {
    let mut mesh = Mesh::default();
    for i in 0..rings {
        let theta = i as f32 / rings as f32 * std::f32::consts::TAU;
        for j in 0..sides {
            let phi = j as f32 / sides as f32 * std::f32::consts::TAU;
            let n = Vec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin());
            let ring = Vec3::new(theta.cos(), theta.sin(), 0.0) * major;
            mesh.positions.push(ring + n * minor);
            mesh.normals.push(n);
        }
    }
    let index = |i: u32, j: u32| (i % rings) * sides + (j % sides);
    for i in 0..rings {
        for j in 0..sides {
            // Around the ring, then around the tube: their cross product
            // points out of the tube.
            let (a, b) = (index(i, j), index(i + 1, j));
            let (c, d) = (index(i + 1, j + 1), index(i, j + 1));
            mesh.indices.push([a, b, c]);
            mesh.indices.push([a, c, d]);
        }
    }
    mesh
}

/// A closed shell between two surfaces seen through a grid of rays from the
/// origin: `directions` holds `columns x rows` ray directions, row by row,
/// and each gets a vertex at `near * dir` on the front surface and at
/// `far * dir` on the back surface. The two surfaces are cut into triangles
/// along the grid and joined by walls along its border. Flat-shaded. With
/// `near` and `far` powers of two the vertices are exact: they lie exactly
/// on the rays `t * dir`.
pub fn shell(directions: &[Vec3], columns: u32, rows: u32, near: f32, far: f32) -> Mesh {
    assert!(columns >= 2 && rows >= 2 && directions.len() == (columns * rows) as usize);
    let mut mesh = Mesh::default();
    mesh.positions.extend(directions.iter().map(|&d| d * near));
    mesh.positions.extend(directions.iter().map(|&d| d * far));
    let front = |i: u32, j: u32| j * columns + i;
    let back = |i: u32, j: u32| columns * rows + j * columns + i;
    for j in 0..rows - 1 {
        for i in 0..columns - 1 {
            let (f00, f10, f11, f01) = (
                front(i, j),
                front(i + 1, j),
                front(i + 1, j + 1),
                front(i, j + 1),
            );
            let (b00, b10, b11, b01) = (
                back(i, j),
                back(i + 1, j),
                back(i + 1, j + 1),
                back(i, j + 1),
            );
            mesh.indices.extend([[f00, f10, f11], [f00, f11, f01]]);
            mesh.indices.extend([[b00, b11, b10], [b00, b01, b11]]);
        }
    }
    // The border of the grid, in the order the front surface's triangles
    // run along it (left to right along the first row, down the last
    // column, back along the last row, up the first column); each wall
    // quad runs the other way, so every edge is used once in each
    // direction.
    let mut border: Vec<(u32, u32)> = Vec::new();
    border.extend((0..columns - 1).map(|i| (i, 0)));
    border.extend((0..rows - 1).map(|j| (columns - 1, j)));
    border.extend((1..columns).rev().map(|i| (i, rows - 1)));
    border.extend((1..rows).rev().map(|j| (0, j)));
    for (k, &(i, j)) in border.iter().enumerate() {
        let (ni, nj) = border[(k + 1) % border.len()];
        let (fa, fb, ba, bb) = (front(i, j), front(ni, nj), back(i, j), back(ni, nj));
        mesh.indices.extend([[fb, fa, ba], [fb, ba, bb]]);
    }
    // Which way the whole is wound depends on the grid's handedness: make
    // the normals point out (positive signed volume).
    if signed_volume(&mesh) < 0.0 {
        for tri in &mut mesh.indices {
            tri.swap(1, 2);
        }
    }
    mesh
}

/// The signed distance of `p` from the plane of the triangle `a, b, c`,
/// in `f64`: positive on the side its normal `(b - a) x (c - a)` points to.
pub fn plane_distance(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> f64 {
    let [a, b, c, p] = [a, b, c, p].map(DVec3::from);
    let n = (b - a).cross(c - a);
    (p - a).dot(n) / n.length()
}

/// Six times the signed volume enclosed by a closed mesh: positive when its
/// normals point out.
pub fn signed_volume(mesh: &Mesh) -> f64 {
    mesh.indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| mesh.positions[k as usize].as_dvec3());
            a.dot(b.cross(c))
        })
        .sum()
}

/// Triangles per leaf, at most.
const LEAF_SIZE: usize = 4;

/// One node of the hierarchy. The first child of an interior node follows
/// it in the array.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: the first of its triangles in `Bvh::triangles`; interior: the
    /// index of the second child.
    index: u32,
    /// Leaf: how many triangles; interior: 0.
    count: u32,
}

/// A mesh with its bounding volume hierarchy.
#[derive(Clone, Debug)]
pub struct Bvh {
    /// The mesh, for normals.
    pub mesh: Mesh,
    nodes: Vec<Node>,
    /// The triangles in leaf order, each with its index in the mesh.
    triangles: Vec<(Triangle, u32)>,
}

/// The smallest box around the points.
fn bounds_of(points: impl IntoIterator<Item = Vec3>) -> Aabb {
    let (lo, hi) = points
        .into_iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    Aabb::new(lo, hi)
}

impl Bvh {
    /// Builds the hierarchy over `mesh`. Boxes are unions of the exact
    /// corner coordinates (min and max do not round), so each contains its
    /// triangles exactly.
    pub fn new(mesh: Mesh) -> Self {
        let mut bvh = Bvh {
            nodes: Vec::new(),
            triangles: Vec::with_capacity(mesh.indices.len()),
            mesh,
        };
        let mut items: Vec<u32> = (0..bvh.mesh.indices.len() as u32).collect();
        let centroids: Vec<Vec3> = (0..items.len())
            .map(|i| {
                let t = bvh.mesh.triangle(i);
                (t.a + t.b + t.c) / 3.0
            })
            .collect();
        if !items.is_empty() {
            bvh.build(&mut items, &centroids);
        }
        bvh
    }

    fn build(&mut self, items: &mut [u32], centroids: &[Vec3]) -> u32 {
        let mesh = &self.mesh;
        let bounds = bounds_of(items.iter().flat_map(|&i| {
            let t = mesh.triangle(i as usize);
            [t.a, t.b, t.c]
        }));
        let at = self.nodes.len();
        self.nodes.push(Node {
            bounds,
            index: 0,
            count: 0,
        });
        if items.len() <= LEAF_SIZE {
            self.nodes[at].index = self.triangles.len() as u32;
            self.nodes[at].count = items.len() as u32;
            for &i in items.iter() {
                self.triangles.push((self.mesh.triangle(i as usize), i));
            }
        } else {
            // Median split along the axis where the centroids spread most.
            let spread = bounds_of(items.iter().map(|&i| centroids[i as usize]));
            let axis = (spread.max - spread.min).max_position();
            let mid = items.len() / 2;
            items.select_nth_unstable_by(mid, |&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            });
            let (left, right) = items.split_at_mut(mid);
            self.build(left, centroids);
            self.nodes[at].index = self.build(right, centroids);
        }
        at as u32
    }

    /// The nearest hit at `0 < t <= t_max` with the triangle's index in the
    /// mesh; with `any`, the first hit found instead (for shadow rays).
    /// `ray` is the ray and `prepared` the same ray prepared for the box
    /// tests.
    pub fn intersect(
        &self,
        ray: &Ray,
        prepared: &PreparedRay,
        mut t_max: f32,
        kernel: Kernel,
        any: bool,
    ) -> Option<(TriangleHit, u32)> {
        let root = self.nodes.first()?;
        root.bounds.clip(prepared, t_max)?;
        let mut best = None;
        // A median split halves the triangles at each level, so the depth
        // is about log2(triangles / LEAF_SIZE); 64 levels is ample.
        let mut stack = [0u32; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let node = &self.nodes[stack[len] as usize];
            if node.count > 0 {
                let first = node.index as usize;
                for (tri, id) in &self.triangles[first..first + node.count as usize] {
                    if let Some(hit) = kernel.intersect(ray, tri, t_max) {
                        t_max = hit.t;
                        best = Some((hit, *id));
                        if any {
                            return best;
                        }
                    }
                }
                continue;
            }
            let (left, right) = (stack[len] + 1, node.index);
            let enter = |i: u32| {
                self.nodes[i as usize]
                    .bounds
                    .clip(prepared, t_max)
                    .map(|(e, _)| e)
            };
            // Push the farther child first so that the nearer is visited
            // first and shrinks `t_max` for the other.
            len = push_children(&mut stack, len, (left, enter(left)), (right, enter(right)));
        }
        best
    }

    /// Whether any triangle blocks the ray within `interval` (for a shadow
    /// segment from `SurfacePoint::spawn_to`, `(0, 1]`): nodes by
    /// `Aabb::clip` over the interval, which never misses a box exact
    /// arithmetic puts in it, triangles by `Triangle::occluded`, which
    /// decides both ends exactly; stops at the first triangle found.
    pub fn occluded_in(&self, prepared: &PreparedRay, interval: Interval<f32>) -> bool {
        let mut window = interval;
        self.visit_in(prepared, &mut window, &mut |tri, _, window| {
            tri.occluded(prepared, *window)
        })
    }

    /// The nearest crossing within `interval` by `Triangle::hit` with
    /// `EdgeRule::OneHit` (each crossing of a closed, consistently wound
    /// mesh belongs to exactly one triangle, even through a shared edge or
    /// corner), with the triangle's index in the mesh. `prepared` is `ray`
    /// prepared.
    pub fn nearest_one_hit_in(
        &self,
        ray: &Ray,
        prepared: &PreparedRay,
        interval: Interval<f32>,
    ) -> Option<(TriangleHit, u32)> {
        let mut best = None;
        let mut window = interval;
        self.visit_in(prepared, &mut window, &mut |tri, id, window| {
            if let Some(hit) = tri.hit(ray, (*window, EdgeRule::OneHit)) {
                // The hit's `t` is in the window, above its lower end, so
                // the shrunk window is valid; any nearer crossing is in it.
                if let Some(nearer) = Interval::new(window.min(), hit.t) {
                    *window = nearer;
                }
                best = Some((hit, id));
            }
            false
        });
        best
    }

    /// Every crossing within `interval` by `Triangle::hit` with
    /// `EdgeRule::OneHit`, with the triangles' indices in the mesh, in no
    /// particular order, added to `out`.
    pub fn one_hits_in(
        &self,
        ray: &Ray,
        prepared: &PreparedRay,
        interval: Interval<f32>,
        out: &mut Vec<(TriangleHit, u32)>,
    ) {
        let mut window = interval;
        self.visit_in(prepared, &mut window, &mut |tri, id, window| {
            if let Some(hit) = tri.hit(ray, (*window, EdgeRule::OneHit)) {
                out.push((hit, id));
            }
            false
        });
    }

    /// Calls `visit` on each triangle of the leaves whose boxes the ray
    /// meets within `window` (nearer boxes first), which `visit` may
    /// shrink; stops and returns `true` as soon as `visit` does.
    fn visit_in(
        &self,
        prepared: &PreparedRay,
        window: &mut Interval<f32>,
        visit: &mut dyn FnMut(&Triangle, u32, &mut Interval<f32>) -> bool,
    ) -> bool {
        let Some(root) = self.nodes.first() else {
            return false;
        };
        if root.bounds.clip(prepared, *window).is_none() {
            return false;
        }
        let mut stack = [0u32; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let node = &self.nodes[stack[len] as usize];
            if node.count > 0 {
                let first = node.index as usize;
                for (tri, id) in &self.triangles[first..first + node.count as usize] {
                    if visit(tri, *id, window) {
                        return true;
                    }
                }
                continue;
            }
            let (left, right) = (stack[len] + 1, node.index);
            let enter = |i: u32| {
                self.nodes[i as usize]
                    .bounds
                    .clip(prepared, *window)
                    .map(|(e, _)| e)
            };
            len = push_children(&mut stack, len, (left, enter(left)), (right, enter(right)));
        }
        false
    }
}

/// Pushes the children a ray enters (`Some` entry distance) onto a
/// traversal stack holding `len` nodes, the farther first so that the
/// nearer is visited first; returns the new length.
fn push_children<F: PartialOrd>(
    stack: &mut [u32; 64],
    len: usize,
    (left, l): (u32, Option<F>),
    (right, r): (u32, Option<F>),
) -> usize {
    match (l, r) {
        (Some(l), Some(r)) => {
            let (near, far) = if l <= r { (left, right) } else { (right, left) };
            stack[len] = far;
            stack[len + 1] = near;
            len + 2
        }
        (Some(_), None) => {
            stack[len] = left;
            len + 1
        }
        (None, Some(_)) => {
            stack[len] = right;
            len + 1
        }
        (None, None) => len,
    }
}
