//! The `instances` scene: one torus mesh placed many times by
//! [`Instance`]s, turned, squashed along random axes and set down tens of
//! thousands of units from the origin (the camera too), with mirrors and
//! sunlight.
//!
//! Each copy is an [`Instance`] over one mesh in object space. The tracer
//! is two-level: the top level tests each instance's world box (from
//! [`Instance::object_to_world_box`], rounded outward, so no hit is lost
//! there) with the prepared slab test, maps the world ray into the
//! instance once per visit ([`Instance::world_to_object`]), prepares it
//! once, and tests the object mesh's BVH and triangles with that one ray.
//! The framed mirror and two stacks of rings are nested instances: an
//! instance of a group whose members are instances of a mesh; the ray is
//! mapped once per level.
//!
//! A hit is carried to the world by [`Instance::surface_to_world`], level
//! by level, innermost first: a world [`SurfacePoint`] whose error bounds
//! hold against the exact world surface. Every ray that leaves it (towards
//! the sun, towards the sky, reflected by a mirror) starts from
//! [`Instance::spawn_through`] with the instances of its path, so that,
//! mapped back into the same instances through their stored inverses as
//! the tracer does, it cannot meet the triangle it left: no acne, and no
//! epsilon, at any distance from the origin. Rays leaving the ground, a
//! world-space plane, start from [`SurfacePoint::spawn`].

use rayhit::glam::{Affine3A, EulerRot, Mat3, Quat, Vec3};
use rayhit::{
    Aabb, Bounds, Camera, CameraSample, Instance, PinholeCamera, Plane, PreparedRay, Ray, Surface,
    SurfacePoint, Triangle, TriangleHit, ray_plane,
};

use crate::mesh::{Bvh, Kernel, Mesh, torus};
use crate::renderer::{
    MAX_DEPTH, Material, OCCLUSION_RANGE, Rng, SKY_LIGHT, SUN, camera_at, facing, render_pixels,
    sky, toward_disc,
};

/// Where the scene stands: the ground, every instance and the camera are
/// placed around this point, far from the origin, where an `f32`
/// coordinate is a multiple of `2^-9` (about 0.002).
pub const CENTRE: Vec3 = Vec3::new(30_000.0, 1_200.0, -20_000.0);

/// How deep instances nest here: a group of instances inside an instance.
pub const MAX_NEST: usize = 2;

/// The index of the torus in [`InstanceScene::meshes`].
pub const TORUS: usize = 0;
/// The index of the slab (a cube in object space) in
/// [`InstanceScene::meshes`].
pub const SLAB: usize = 1;

/// A closed cube from `-1` to `1` on every axis, as twelve triangles wound
/// outwards; flat-shaded. Scaled by an instance into a thin slab.
pub fn slab() -> Mesh {
    let corner = |i: u32| {
        let s = |bit: u32| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
        Vec3::new(s(0), s(1), s(2))
    };
    let positions: Vec<Vec3> = (0..8).map(corner).collect();
    let mut indices = Vec::new();
    for axis in 0..3 {
        for side in 0..2 {
            // The face's corners in increasing index: the other two
            // coordinates (low, high) at (-, -), (+, -), (-, +), (+, +);
            // around the face that is 0, 1, 3, 2.
            let q: Vec<u32> = (0..8).filter(|i| i >> axis & 1 == side).collect();
            let mut cycle = [q[0], q[1], q[3], q[2]];
            let p = |k: usize| positions[cycle[k] as usize];
            let mut outward = Vec3::ZERO;
            outward[axis] = if side == 1 { 1.0 } else { -1.0 };
            if (p(1) - p(0)).cross(p(2) - p(0)).dot(outward) < 0.0 {
                cycle.reverse();
            }
            indices.push([cycle[0], cycle[1], cycle[2]]);
            indices.push([cycle[0], cycle[2], cycle[3]]);
        }
    }
    Mesh {
        positions,
        normals: Vec::new(),
        indices,
    }
}

/// What an instance places: a mesh, or a group of instances (nesting).
#[derive(Debug)]
pub enum Content {
    /// One of [`InstanceScene::meshes`], with its material.
    Mesh {
        /// Index in [`InstanceScene::meshes`].
        mesh: usize,
        /// Its material.
        material: Material,
    },
    /// Instances placed in this instance's object space.
    Group(Vec<Node>),
}

/// An instance: an object-to-parent map (the parent is the world, or the
/// group it belongs to) and what it places.
#[derive(Debug)]
pub struct Node {
    /// A name for messages.
    pub name: &'static str,
    /// The map from the content's space to the parent's.
    pub instance: Instance,
    /// The content's box in the parent's space, from
    /// [`Instance::object_to_world_box`]: contains the exact image of every
    /// point of the content's box.
    pub bounds: Aabb,
    /// The transpose of the stored inverse's matrix: carries a shading
    /// normal to the parent's space, as [`Instance::surface_to_world`]
    /// carries the geometric one.
    normal_matrix: Mat3,
    /// What it places.
    pub content: Content,
}

/// The smallest box around some points (min and max do not round).
fn bounds_of<'a>(points: impl IntoIterator<Item = &'a Vec3>) -> Aabb {
    let (lo, hi) = points
        .into_iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    Aabb::new(lo, hi)
}

impl Content {
    /// The content's box in its own space: the mesh's vertices' box, or
    /// the union of the members' boxes.
    pub fn bounds(&self, meshes: &[Bvh]) -> Aabb {
        match self {
            Content::Mesh { mesh, .. } => bounds_of(&meshes[*mesh].mesh.positions),
            Content::Group(members) => members
                .iter()
                .fold(Aabb::new(Vec3::INFINITY, Vec3::NEG_INFINITY), |b, m| {
                    Aabb::new(b.min.min(m.bounds.min), b.max.max(m.bounds.max))
                }),
        }
    }

    /// The lowest `y` of the content's vertices under the linear map
    /// `linear` (approximate: for setting things down on the ground).
    fn lowest(&self, linear: Affine3A, meshes: &[Bvh]) -> f32 {
        match self {
            Content::Mesh { mesh, .. } => meshes[*mesh]
                .mesh
                .positions
                .iter()
                .map(|&p| linear.transform_point3(p).y)
                .fold(f32::INFINITY, f32::min),
            Content::Group(members) => members
                .iter()
                .map(|m| {
                    let cols = m.instance.matrix_columns();
                    let own = Affine3A::from_cols(
                        cols[0].into(),
                        cols[1].into(),
                        cols[2].into(),
                        m.instance.translation().into(),
                    );
                    m.content.lowest(linear * own, meshes)
                })
                .fold(f32::INFINITY, f32::min),
        }
    }
}

impl Node {
    /// The instance of `content` by `place` (content to parent).
    ///
    /// # Panics
    ///
    /// When `place` is not invertible or its box overflows (the scene's
    /// maps are far from either).
    pub fn new(name: &'static str, place: Affine3A, content: Content, meshes: &[Bvh]) -> Self {
        let instance = Instance::from_affine3a(place).expect("an invertible placement");
        let bounds = instance
            .object_to_world_box(&content.bounds(meshes))
            .expect("a finite box");
        let (a, _) = instance.inverse();
        Self {
            name,
            instance,
            bounds,
            normal_matrix: Mat3::from_cols(a[0], a[1], a[2]).transpose(),
            content,
        }
    }

    /// `content` mapped by the matrix `linear` and set down at `(x, z)`
    /// with its lowest vertex on the parent's `y = floor`.
    fn standing(
        name: &'static str,
        content: Content,
        linear: Mat3,
        (x, floor, z): (f32, f32, f32),
        meshes: &[Bvh],
    ) -> Self {
        let low = content.lowest(Affine3A::from_mat3(linear), meshes);
        let place = Affine3A::from_mat3_translation(linear, Vec3::new(x, floor - low, z));
        Self::new(name, place, content, meshes)
    }
}

/// The matrix scaling by `scale` along the axes, then turning about `y`
/// by `angle`.
fn turned(angle: f32, scale: Vec3) -> Mat3 {
    Mat3::from_rotation_y(angle) * Mat3::from_diagonal(scale)
}

/// The instances a hit lies in, as indices: the top-level instance's in
/// [`InstanceScene::nodes`], then the member's in its group, and so on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Path {
    len: u8,
    index: [u16; MAX_NEST],
}

impl Path {
    /// The indices, outermost first.
    pub fn indices(&self) -> &[u16] {
        &self.index[..usize::from(self.len)]
    }

    /// This path followed by `k`.
    fn with(mut self, k: usize) -> Self {
        let len = usize::from(self.len);
        assert!(len < MAX_NEST, "instances nest at most {MAX_NEST} deep");
        self.index[len] = k as u16;
        self.len += 1;
        self
    }
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum On {
    /// The ground plane (world space).
    Ground,
    /// A triangle of an instanced mesh.
    Instance {
        /// The instances, outermost first.
        path: Path,
        /// The triangle's index in the mesh.
        triangle: u32,
    },
}

/// The nearest surface a ray meets.
#[derive(Clone, Copy, Debug)]
pub struct InstanceHit {
    /// Distance along the ray (world and object rays share `t`).
    pub t: f32,
    /// What was hit.
    pub on: On,
    /// The hit point in world space, with the error bounds of its point
    /// and normal against the exact world surface.
    pub surface: SurfacePoint,
    /// The unit normal used for shading, in world space.
    pub shading: Vec3,
}

/// The instances scene.
#[derive(Debug)]
pub struct InstanceScene {
    /// The camera, near [`CENTRE`].
    pub camera: PinholeCamera,
    /// The ground, through [`CENTRE`].
    pub ground: Plane,
    /// The ground's material (a checker).
    pub ground_material: Material,
    /// The meshes, in object space: [`TORUS`] and [`SLAB`].
    pub meshes: Vec<Bvh>,
    /// The top-level instances.
    pub nodes: Vec<Node>,
    /// Unit vector towards the centre of the sun.
    pub sun: Vec3,
    /// The sun's angular radius (as the tangent).
    pub sun_radius: f32,
}

/// A stack of three flat rings, each smaller ring resting on the one
/// below (their tubes touching), in the group's space with the floor at
/// `y = 0`: the content of a nested instance.
fn ring_stack(meshes: &[Bvh]) -> Content {
    let flat = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let colours = [
        Material::diffuse(0.85, 0.30, 0.20),
        Material::diffuse(0.95, 0.70, 0.20),
        Material::diffuse(0.30, 0.65, 0.30),
    ];
    // The torus's ring has radius 1 and its tube 0.35. Rings of scale
    // s0 > s1 rest on each other where their tubes' centre circles are
    // 0.35 (s0 + s1) apart: (s0 - s1) across, the rest up.
    let scales = [1.0f32, 0.7, 0.45];
    let mut height = 0.35;
    let mut members = Vec::new();
    for (k, (&s, material)) in scales.iter().zip(colours).enumerate() {
        if k > 0 {
            let prev = scales[k - 1];
            let apart: f32 = 0.35 * (prev + s);
            let across = prev - s;
            height += (apart * apart - across * across).sqrt();
        }
        let place = Affine3A::from_scale_rotation_translation(
            Vec3::splat(s),
            flat,
            Vec3::new(0.0, height, 0.0),
        );
        members.push(Node::new(
            "stacked ring",
            place,
            Content::Mesh {
                mesh: TORUS,
                material,
            },
            meshes,
        ));
    }
    Content::Group(members)
}

/// A mirror in a dark frame, standing on the group's floor `y = 0`: five
/// instances of the slab (the glass and four bars), the content of a
/// nested instance.
fn framed_mirror(meshes: &[Bvh]) -> Content {
    let bar = |name, half: Vec3, centre: Vec3, material| {
        let place = Affine3A::from_scale_rotation_translation(half, Quat::IDENTITY, centre);
        Node::new(
            name,
            place,
            Content::Mesh {
                mesh: SLAB,
                material,
            },
            meshes,
        )
    };
    let frame = Material::diffuse(0.10, 0.09, 0.08);
    let glass = Material {
        mirror: 0.85,
        ..Material::diffuse(0.85, 0.90, 0.95)
    };
    Content::Group(vec![
        bar(
            "mirror",
            Vec3::new(1.0, 1.0, 0.02),
            Vec3::new(0.0, 1.12, 0.0),
            glass,
        ),
        bar(
            "frame",
            Vec3::new(1.12, 0.06, 0.06),
            Vec3::new(0.0, 0.06, 0.0),
            frame,
        ),
        bar(
            "frame",
            Vec3::new(1.12, 0.06, 0.06),
            Vec3::new(0.0, 2.18, 0.0),
            frame,
        ),
        bar(
            "frame",
            Vec3::new(0.06, 1.0, 0.06),
            Vec3::new(-1.06, 1.12, 0.0),
            frame,
        ),
        bar(
            "frame",
            Vec3::new(0.06, 1.0, 0.06),
            Vec3::new(1.06, 1.12, 0.0),
            frame,
        ),
    ])
}

/// The instances scene for an image of `width x height` pixels: a
/// checkered ground around [`CENTRE`], a framed mirror at the back and
/// two stacks of rings (groups of instances placed by an instance), a
/// gold mirror ring, and twelve tori turned and squashed every which way,
/// in low sunlight.
pub fn instance_scene(width: u32, height: u32) -> InstanceScene {
    let eye = CENTRE + Vec3::new(0.0, 2.7, 8.0);
    let target = CENTRE + Vec3::new(0.0, 0.55, -0.6);
    let camera = camera_at(eye, target, width, height);
    let meshes = vec![Bvh::new(torus(1.0, 0.35, 32, 12)), Bvh::new(slab())];
    let (x0, y0, z0) = (CENTRE.x, CENTRE.y, CENTRE.z);
    let mut nodes = vec![
        Node::standing(
            "framed mirror",
            framed_mirror(&meshes),
            turned(-0.3, Vec3::new(1.5, 0.85, 1.0)),
            (x0 + 0.9, y0, z0 - 3.3),
            &meshes,
        ),
        Node::standing(
            "gold ring",
            Content::Mesh {
                mesh: TORUS,
                material: Material {
                    mirror: 0.85,
                    ..Material::diffuse(0.95, 0.72, 0.35)
                },
            },
            turned(0.6, Vec3::new(0.8, 0.8, 0.6)),
            (x0 - 2.4, y0, z0 - 1.6),
            &meshes,
        ),
        Node::standing(
            "ring stack",
            ring_stack(&meshes),
            turned(0.4, Vec3::new(0.75, 0.6, 0.5)),
            (x0 + 2.5, y0, z0 - 1.4),
            &meshes,
        ),
        Node::standing(
            "small ring stack",
            ring_stack(&meshes),
            turned(-0.9, Vec3::new(0.3, 0.4, 0.45)),
            (x0 - 0.6, y0, z0 - 1.9),
            &meshes,
        ),
    ];
    // Twelve tori on a jittered grid in front, each turned at random,
    // squashed along three other random axes (a rotation, a scale from 0.2
    // to 0.6 per axis, a rotation: a sheared torus), and set down.
    let palette = [
        Material::diffuse(0.80, 0.22, 0.16),
        Material::diffuse(0.20, 0.35, 0.78),
        Material::diffuse(0.22, 0.62, 0.30),
        Material::diffuse(0.85, 0.85, 0.82),
        Material::diffuse(0.60, 0.30, 0.70),
        Material::diffuse(0.90, 0.55, 0.15),
    ];
    let mut rng = Rng::new(2024);
    for k in 0..12 {
        let (column, row) = ((k % 4) as f32, (k / 4) as f32);
        let mut r = || rng.next_f32();
        let x = -3.3 + column * 2.2 + row * 0.5 + (r() - 0.5) * 0.4;
        let z = -0.2 + row * 1.5 + (r() - 0.5) * 0.4;
        let tau = std::f32::consts::TAU;
        let mut turn = || Mat3::from_euler(EulerRot::YXZ, r() * tau, r() * tau, r() * tau);
        let (first, then) = (turn(), turn());
        let mut scale = || 0.2 + r() * 0.4;
        let scale = Vec3::new(scale(), scale(), scale());
        let linear = then * Mat3::from_diagonal(scale) * first;
        nodes.push(Node::standing(
            "torus",
            Content::Mesh {
                mesh: TORUS,
                material: palette[k % palette.len()],
            },
            linear,
            (x0 + x, y0, z0 + z),
            &meshes,
        ));
    }
    InstanceScene {
        camera,
        ground: Plane::new(CENTRE, Vec3::Y),
        ground_material: Material {
            checker: Some(Vec3::new(0.36, 0.38, 0.42)),
            ..Material::diffuse(0.74, 0.72, 0.68)
        },
        meshes,
        nodes,
        sun: Vec3::new(-0.9, 0.75, 0.8).normalize(),
        sun_radius: 0.03,
    }
}

/// The best hit so far: the triangle's hit, its index, the path to it.
type Found = Option<(TriangleHit, u32, Path)>;

impl InstanceScene {
    /// The instances along `path`, outermost first (the first `len` of
    /// the array; the rest repeat the first).
    ///
    /// # Panics
    ///
    /// When `path` does not lead through groups of this scene.
    pub fn chain(&self, path: &Path) -> ([&Node; MAX_NEST], usize) {
        let indices = path.indices();
        let mut nodes = [&self.nodes[usize::from(indices[0])]; MAX_NEST];
        for (k, &i) in indices.iter().enumerate().skip(1) {
            let Content::Group(members) = &nodes[k - 1].content else {
                panic!("a path through a mesh")
            };
            nodes[k] = &members[usize::from(i)];
        }
        (nodes, indices.len())
    }

    /// Every path from the top level to a mesh, in traversal order.
    pub fn paths(&self) -> Vec<Path> {
        fn walk(nodes: &[Node], path: Path, out: &mut Vec<Path>) {
            for (k, node) in nodes.iter().enumerate() {
                match &node.content {
                    Content::Mesh { .. } => out.push(path.with(k)),
                    Content::Group(members) => walk(members, path.with(k), out),
                }
            }
        }
        let mut out = Vec::new();
        walk(&self.nodes, Path::default(), &mut out);
        out
    }

    /// The mesh and material at the end of `path`.
    ///
    /// # Panics
    ///
    /// When `path` does not lead to a mesh of this scene.
    pub fn leaf(&self, path: &Path) -> (&Bvh, &Material) {
        let (nodes, len) = self.chain(path);
        match &nodes[len - 1].content {
            Content::Mesh { mesh, material } => (&self.meshes[*mesh], material),
            Content::Group(_) => panic!("a path ending at a group"),
        }
    }

    /// The material of what was hit.
    pub fn material(&self, on: &On) -> &Material {
        match on {
            On::Ground => &self.ground_material,
            On::Instance { path, .. } => self.leaf(path).1,
        }
    }

    /// The object-space triangle a hit lies on (`None` for the ground).
    pub fn triangle(&self, on: &On) -> Option<Triangle> {
        match on {
            On::Ground => None,
            On::Instance { path, triangle } => {
                Some(self.leaf(path).0.mesh.triangle(*triangle as usize))
            }
        }
    }

    /// A world ray in the object space at the end of `path`, as the
    /// tracer maps it: [`Instance::world_to_object`] once per level,
    /// outermost first.
    pub fn object_ray(&self, path: &Path, ray: &Ray) -> Ray {
        let (nodes, len) = self.chain(path);
        nodes[..len]
            .iter()
            .fold(*ray, |r, node| node.instance.world_to_object(&r))
    }

    /// The nearest hit of `ray` at `0 < t <= t_max`.
    pub fn nearest(&self, ray: &Ray, t_max: f32) -> Option<InstanceHit> {
        let mut t_max = t_max;
        let ground = ray_plane(ray, &self.ground, t_max);
        if let Some(t) = ground {
            t_max = t;
        }
        let mut found = None;
        self.visit(
            &self.nodes,
            ray,
            &PreparedRay::new(ray),
            &mut t_max,
            Path::default(),
            false,
            &mut found,
        );
        match found {
            Some((hit, triangle, path)) => Some(self.instance_hit(ray, &hit, triangle, path)),
            None => ground.map(|t| InstanceHit {
                t,
                on: On::Ground,
                surface: self.ground.surface_point(ray, &t),
                shading: self.ground.normal.normalize(),
            }),
        }
    }

    /// True when anything lies on `ray` at `0 < t <= t_max`.
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        if ray_plane(ray, &self.ground, t_max).is_some() {
            return true;
        }
        let mut t_max = t_max;
        self.visit(
            &self.nodes,
            ray,
            &PreparedRay::new(ray),
            &mut t_max,
            Path::default(),
            true,
            &mut None,
        )
    }

    /// The two-level traversal: for each instance of `nodes` whose box
    /// `ray` (in the parent's space) meets within `t_max`, the ray mapped
    /// into the instance once and prepared once, then the mesh's BVH, or
    /// the group's members, tested with that one ray. Keeps the nearest
    /// hit in `found`, shrinking `t_max`; with `any`, stops at the first
    /// and returns `true`.
    #[allow(clippy::too_many_arguments)]
    fn visit(
        &self,
        nodes: &[Node],
        ray: &Ray,
        prepared: &PreparedRay,
        t_max: &mut f32,
        path: Path,
        any: bool,
        found: &mut Found,
    ) -> bool {
        for (k, node) in nodes.iter().enumerate() {
            if node.bounds.clip(prepared, *t_max).is_none() {
                continue;
            }
            let object = node.instance.world_to_object(ray);
            let object_prepared = PreparedRay::new(&object);
            let here = path.with(k);
            let stop = match &node.content {
                Content::Mesh { mesh, .. } => {
                    match self.meshes[*mesh].intersect(
                        &object,
                        &object_prepared,
                        *t_max,
                        Kernel::Watertight,
                        any,
                    ) {
                        Some((hit, triangle)) => {
                            // Object and world rays share `t`.
                            *t_max = hit.t;
                            *found = Some((hit, triangle, here));
                            any
                        }
                        None => false,
                    }
                }
                Content::Group(members) => {
                    self.visit(members, &object, &object_prepared, t_max, here, any, found)
                }
            };
            if stop {
                return true;
            }
        }
        false
    }

    /// The world hit of an object-space triangle hit: the surface point
    /// carried out level by level, innermost first, by
    /// [`Instance::surface_to_world`], and the shading normal by each
    /// level's inverse transpose.
    fn instance_hit(&self, ray: &Ray, hit: &TriangleHit, triangle: u32, path: Path) -> InstanceHit {
        let (nodes, len) = self.chain(&path);
        let (bvh, _) = self.leaf(&path);
        let tri = bvh.mesh.triangle(triangle as usize);
        let object = tri.surface_point_at(hit.u, hit.v);
        let surface = nodes[..len]
            .iter()
            .rev()
            .fold(object, |p, node| node.instance.surface_to_world(&p));
        let shading = bvh
            .mesh
            .shading_normal(triangle as usize, hit.u, hit.v)
            .map(|n| {
                nodes[..len]
                    .iter()
                    .rev()
                    .fold(n, |n, node| node.normal_matrix * n)
            })
            .and_then(Vec3::try_normalize)
            .or_else(|| surface.normal.try_normalize())
            .unwrap_or(-ray.dir.normalize());
        InstanceHit {
            t: hit.t,
            on: On::Instance { path, triangle },
            surface,
            shading,
        }
    }

    /// A ray leaving `hit` along `dir`: from an instance,
    /// [`Instance::spawn_through`] with the instances of its path, so that
    /// the ray mapped back into them cannot meet the triangle it left;
    /// from the ground, [`SurfacePoint::spawn`].
    pub fn spawn(&self, hit: &InstanceHit, dir: Vec3) -> Ray {
        match &hit.on {
            On::Ground => hit.surface.spawn(dir),
            On::Instance { path, .. } => {
                let (nodes, len) = self.chain(path);
                let instances = nodes.map(|n| &n.instance);
                Instance::spawn_through(&instances[..len], &hit.surface, dir)
            }
        }
    }

    /// The light arriving along `ray` (reversed); `rays` counts every ray
    /// traced, this one included.
    pub fn radiance(&self, ray: &Ray, depth: u32, rng: &mut Rng, rays: &mut u64) -> Vec3 {
        *rays += 1;
        match self.nearest(ray, f32::INFINITY) {
            Some(hit) => self.shade(ray, &hit, depth, rng, rays),
            None => sky(ray.dir),
        }
    }

    /// The light leaving `hit` back along `ray`: sunlight unless the sun
    /// is blocked, skylight unless a random direction towards the sky is
    /// blocked nearby, and a mirror reflection; every ray from
    /// [`InstanceScene::spawn`].
    pub fn shade(
        &self,
        ray: &Ray,
        hit: &InstanceHit,
        depth: u32,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> Vec3 {
        let material = self.material(&hit.on);
        let (geometric, shading) = facing(ray, hit.surface.normal, hit.shading);
        let mut light = Vec3::ZERO;

        // The sun: a random point of its disc, for soft shadows.
        let to_sun = toward_disc(self.sun, self.sun_radius, rng);
        let cos = shading.dot(to_sun);
        if cos > 0.0 && geometric.dot(to_sun) > 0.0 {
            *rays += 1;
            if !self.occluded(&self.spawn(hit, to_sun), f32::INFINITY) {
                light += SUN * cos;
            }
        }

        // The sky: one cosine-distributed direction, unless something
        // nearby is in the way.
        let (x, y) = rng.disc();
        let (t1, t2) = shading.any_orthonormal_pair();
        let dir = t1 * x + t2 * y + shading * (1.0 - x * x - y * y).max(0.0).sqrt();
        if dir.dot(geometric) > 0.0 {
            *rays += 1;
            if !self.occluded(&self.spawn(hit, dir), OCCLUSION_RANGE) {
                light += SKY_LIGHT;
            }
        }

        let mut colour = material.albedo_at(hit.surface.point) * light;
        if material.mirror > 0.0 && depth < MAX_DEPTH {
            let mut dir = ray.dir.reflect(shading);
            if dir.dot(geometric) <= 0.0 {
                dir = ray.dir.reflect(geometric);
            }
            let reflected = self.radiance(&self.spawn(hit, dir), depth + 1, rng, rays);
            colour = colour.lerp(reflected * material.albedo, material.mirror);
        }
        colour
    }
}

/// A rendered image of the instances scene.
#[derive(Clone, Debug)]
pub struct InstanceImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear colours, row by row from the top.
    pub pixels: Vec<Vec3>,
    /// What the ray through each pixel's centre hit first, row by row.
    pub seen: Vec<Option<On>>,
}

/// Renders the instances scene with `samples` rays per pixel (the first
/// through the pixel's centre, the others at random points of the pixel)
/// on all cores, calling `row_done` after each row. Returns the image and
/// the number of rays traced.
pub fn render_instances(
    scene: &InstanceScene,
    samples: u32,
    row_done: &(dyn Fn() + Sync),
) -> (InstanceImage, u64) {
    let camera = &scene.camera;
    let (width, height) = (camera.width(), camera.height());
    let (pixels, seen, [rays, _]) = render_pixels(
        (width, height),
        samples,
        row_done,
        |x, y, _, rng, counts| {
            let ray = camera.ray(CameraSample::new(x, y));
            let hit = scene.nearest(&ray, f32::INFINITY);
            let colour = match hit {
                Some(hit) => scene.shade(&ray, &hit, 0, rng, &mut counts[0]),
                None => sky(ray.dir),
            };
            (colour, hit.map(|h| h.on))
        },
    );
    let image = InstanceImage {
        width,
        height,
        pixels,
        seen,
    };
    (image, rays)
}
