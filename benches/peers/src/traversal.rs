//! Whole traversals for the section `traversal`: a binary BVH built by
//! obvhs (`obvhs::bvh2::Bvh2`) walked by a plain stack traversal written
//! here with rayhit's box and triangle tests, next to obvhs's own walk of
//! the same tree; and the ray sets the section times (a camera, random
//! rays, shadow segments). The compressed wide BVH's traversals are in
//! [`crate::cwbvh`].
//!
//! The traversals here are the ones a renderer author writes first. The
//! closest hit: test both children of an inner node with `ValidAabb::clip`
//! (the node boxes checked once, when the tree is copied), go to the
//! nearer, keep the farther on a stack with its entry distance, and test
//! the triangles of a leaf with `Triangle::hit`, shrinking `t_max`; the
//! order follows obvhs's `Bvh2::ray_traverse_dynamic` (children tested in
//! pairs, nearer first). Any hit over a fixed interval: `ValidAabb::meets`
//! on both children in their stored order, a leaf's triangles tested with
//! `Triangle::occluded` at once, the first occluder ending the walk. The
//! code is written here.

use std::time::Duration;

use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::ray::{Ray as ObRay, RayHit};
use obvhs::triangle::Triangle as ObTriangle;
use rayhit::glam::Vec3;
use rayhit::{
    Aabb, Bounds, Intersect, Interval, PreparedRay, Ray, Search, Triangle, TriangleHit, ValidAabb,
};
use rayhit_testkit::rng::Pcg32;

use crate::cwbvh::{Mesh, Pending, ob_triangles};

/// Entries on the traversal stack at most (the tree's depth is checked
/// against it when the tree is built).
const STACK: usize = 64;

/// A node of the binary tree as the traversal here reads it: the box as
/// rayhit's `ValidAabb` (checked once, so the box test does not check it
/// per call), and either two children (`count == 0`, at `first` and
/// `first + 1`) or `count` triangles from `first`. 32 bytes, as obvhs's
/// node is.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: ValidAabb,
    count: u32,
    first: u32,
}

/// A mesh's binary BVH built by obvhs (its `medium_build`, up to eight
/// triangles a leaf), with the triangles in the tree's order in both
/// crates' types, and the nodes copied into rayhit's boxes.
pub struct Bvh2Scene {
    /// obvhs's tree, for obvhs's own traversal.
    pub bvh: Bvh2,
    /// The triangles in the tree's order (leaf `first..first + count`).
    pub ob_tris: Vec<ObTriangle>,
    /// The same triangles as rayhit's.
    pub tris: Vec<Triangle>,
    /// obvhs's nodes with rayhit's boxes, in obvhs's order.
    nodes: Vec<Node>,
}

/// The range a traversal tests the boxes over now: rayhit's search, and
/// its ends for box tests written without rayhit (the floor row).
#[derive(Clone, Copy, Debug)]
pub struct Reach {
    /// A `t_max` or an interval.
    pub search: Search<f32>,
    /// The lower end (zero for a `t_max`).
    pub lo: f32,
    /// The upper end.
    pub hi: f32,
}

/// What a traversal asks of the tree: the range the boxes are tested
/// over, and the leaves' test.
trait Query {
    /// The range the boxes are clipped to now (a `t_max` or an interval).
    fn reach(&self) -> Reach;
    /// Entries beyond this distance need not be visited.
    fn far(&self) -> f32;
    /// Tests the triangles `tris`, numbered from `first`; `true` ends the
    /// traversal.
    fn leaf(&mut self, ray: &PreparedRay, tris: &[Triangle], first: u32) -> bool;
}

/// The closest hit: `t_max` shrinks to each hit the triangle test `hit`
/// finds (given the triangle, its index and `t_max`, the hit's `t` within
/// `(0, t_max]`).
struct Closest<H> {
    /// The nearest hit's `t` so far (infinite before one).
    t_max: f32,
    /// The triangle test.
    hit: H,
}

impl<H: FnMut(&Triangle, u32, f32) -> Option<f32>> Query for Closest<H> {
    #[inline(always)]
    fn reach(&self) -> Reach {
        Reach {
            search: self.t_max.into(),
            lo: 0.0,
            hi: self.t_max,
        }
    }
    #[inline(always)]
    fn far(&self) -> f32 {
        self.t_max
    }
    #[inline(always)]
    fn leaf(&mut self, _: &PreparedRay, tris: &[Triangle], first: u32) -> bool {
        for (i, t) in tris.iter().enumerate() {
            if let Some(t) = (self.hit)(t, first + i as u32, self.t_max) {
                self.t_max = t;
            }
        }
        false
    }
}

/// Any hit within a fixed interval: the first occluder ends the walk.
struct Occluded {
    /// The segment's range along the ray.
    segment: Interval<f32>,
    /// Whether an occluder was found.
    blocked: bool,
}

impl Query for Occluded {
    #[inline(always)]
    fn reach(&self) -> Reach {
        Reach {
            search: self.segment.into(),
            lo: self.segment.min(),
            hi: self.segment.max(),
        }
    }
    #[inline(always)]
    fn far(&self) -> f32 {
        self.segment.max()
    }
    #[inline(always)]
    fn leaf(&mut self, ray: &PreparedRay, tris: &[Triangle], _first: u32) -> bool {
        self.blocked = tris.iter().any(|t| t.occluded(ray, self.segment));
        self.blocked
    }
}

impl Bvh2Scene {
    /// Builds the tree over the mesh's triangles with obvhs and copies it;
    /// panics unless every box contains what is under it.
    pub fn new(mesh: &Mesh) -> Self {
        let original = mesh.triangles();
        let ob_original = ob_triangles(&original);
        let bvh = build_bvh2_from_tris(
            &ob_original,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let order = |i: &u32| *i as usize;
        let tris: Vec<Triangle> = bvh
            .primitive_indices
            .iter()
            .map(|i| original[order(i)])
            .collect();
        let ob_tris = bvh
            .primitive_indices
            .iter()
            .map(|i| ob_original[order(i)])
            .collect();
        let nodes: Vec<Node> = bvh
            .nodes
            .iter()
            .map(|n| Node {
                bounds: ValidAabb::new(Aabb::new(n.aabb().min.into(), n.aabb().max.into()))
                    .expect("obvhs's boxes are finite, min <= max"),
                count: n.prim_count,
                first: n.first_index,
            })
            .collect();
        let scene = Bvh2Scene {
            bvh,
            ob_tris,
            tris,
            nodes,
        };
        assert!(scene.depth_and_containment(0, 0) <= STACK, "tree too deep");
        scene
    }

    /// The depth below node `i`; panics unless every node's box contains
    /// its triangles' corners (obvhs's boxes are unions of the corners'
    /// min and max, exact, so they do).
    fn depth_and_containment(&self, i: usize, depth: usize) -> usize {
        let n = self.nodes[i];
        let b = n.bounds.aabb();
        let inside = |p: Vec3| b.min.cmple(p).all() && b.max.cmpge(p).all();
        if n.count > 0 {
            let tris = &self.tris[n.first as usize..(n.first + n.count) as usize];
            assert!(
                tris.iter()
                    .all(|t| inside(t.a) && inside(t.b) && inside(t.c))
            );
            return depth;
        }
        (0..2)
            .map(|k| {
                let c = self.nodes[n.first as usize + k].bounds.aabb();
                assert!(inside(c.min) && inside(c.max));
                self.depth_and_containment(n.first as usize + k, depth + 1)
            })
            .max()
            .unwrap_or(depth)
    }

    /// The traversal: both children of an inner node tested with `enter`
    /// (the box, the query's current range: the entry distance, or `None`
    /// for a miss), the nearer visited first, the farther kept on the stack
    /// with its entry and skipped when popped beyond the query's `far`.
    #[inline(always)]
    fn walk(
        &self,
        ray: &PreparedRay,
        q: &mut impl Query,
        enter: impl Fn(&ValidAabb, Reach) -> Option<f32>,
    ) {
        let nodes = &self.nodes[..];
        if nodes.is_empty() || enter(&nodes[0].bounds, q.reach()).is_none() {
            return;
        }
        let mut stack = [(0u32, 0f32); STACK];
        let mut top = 0;
        let mut at = 0usize;
        loop {
            let n = nodes[at];
            if n.count > 0 {
                let tris = &self.tris[n.first as usize..(n.first + n.count) as usize];
                if q.leaf(ray, tris, n.first) {
                    return;
                }
            } else {
                let (a, b) = (n.first as usize, n.first as usize + 1);
                let reach = q.reach();
                match (
                    enter(&nodes[a].bounds, reach),
                    enter(&nodes[b].bounds, reach),
                ) {
                    (Some(ea), Some(eb)) => {
                        let (near, far, enter) = if ea <= eb { (a, b, eb) } else { (b, a, ea) };
                        stack[top] = (far as u32, enter);
                        top += 1;
                        at = near;
                        continue;
                    }
                    (Some(_), None) => {
                        at = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        at = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next node whose entry is still within reach.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (next, enter) = stack[top];
                if enter <= q.far() {
                    at = next as usize;
                    break;
                }
            }
        }
    }

    /// The any-hit traversal: both children of an inner node tested with
    /// `meets` over the query's range, in the order they are stored (any
    /// occluder ends the walk, so no order is worth its cost), a leaf
    /// child's triangles tested at once, an inner child visited next or
    /// kept on a stack of node indices.
    #[inline(always)]
    fn walk_any(
        &self,
        ray: &PreparedRay,
        q: &mut impl Query,
        meets: impl Fn(&ValidAabb, Reach) -> bool,
    ) {
        let nodes = &self.nodes[..];
        let Some(root) = nodes.first() else { return };
        if !meets(&root.bounds, q.reach()) {
            return;
        }
        if root.count > 0 {
            let tris = &self.tris[root.first as usize..(root.first + root.count) as usize];
            q.leaf(ray, tris, root.first);
            return;
        }
        let mut pending = Pending::<STACK>::default();
        let mut at = root.first as usize;
        loop {
            let reach = q.reach();
            for c in &nodes[at..at + 2] {
                if !meets(&c.bounds, reach) {
                    continue;
                }
                if c.count > 0 {
                    let tris = &self.tris[c.first as usize..(c.first + c.count) as usize];
                    if q.leaf(ray, tris, c.first) {
                        return;
                    }
                } else {
                    pending.push(c.first);
                }
            }
            match pending.pop() {
                Some(next) => at = next as usize,
                None => return,
            }
        }
    }

    /// Closest hit by the traversal here with rayhit's `ValidAabb::clip`
    /// and `Triangle::hit`, plain calls on the prepared ray: the triangle
    /// (in the tree's order) and the hit.
    #[inline(always)]
    pub fn rayhit_closest(&self, ray: &PreparedRay) -> Option<(u32, TriangleHit)> {
        self.closest_with(ray, clip_entry(ray))
    }

    /// [`Bvh2Scene::rayhit_closest`] with the box test `enter`.
    #[inline(always)]
    pub fn closest_with(
        &self,
        ray: &PreparedRay,
        enter: impl Fn(&ValidAabb, Reach) -> Option<f32>,
    ) -> Option<(u32, TriangleHit)> {
        let mut best = None;
        self.closest_walk(
            ray,
            enter,
            #[inline(always)]
            |t, i, t_max| {
                let hit = t.hit(ray, t_max)?;
                best = Some((i, hit));
                Some(hit.t)
            },
        );
        best
    }

    /// The closest hit's `t` (infinite for none) by the traversal of
    /// [`Bvh2Scene::rayhit_closest`] with the triangle test `hit` (the
    /// triangle, its index in `ob_tris`, `t_max`: the hit's `t` within
    /// `(0, t_max]`): the floor rows.
    #[inline(always)]
    pub fn closest_by(
        &self,
        ray: &PreparedRay,
        hit: impl FnMut(&Triangle, u32, f32) -> Option<f32>,
    ) -> f32 {
        self.closest_walk(ray, clip_entry(ray), hit)
    }

    /// The closest-hit walk with the box test `enter` and the triangle
    /// test `hit`: the nearest hit's `t`.
    #[inline(always)]
    fn closest_walk(
        &self,
        ray: &PreparedRay,
        enter: impl Fn(&ValidAabb, Reach) -> Option<f32>,
        hit: impl FnMut(&Triangle, u32, f32) -> Option<f32>,
    ) -> f32 {
        let mut q = Closest {
            t_max: f32::INFINITY,
            hit,
        };
        self.walk(ray, &mut q, enter);
        q.t_max
    }

    /// obvhs's triangle `i` (in the tree's order) by [`ob_hit`].
    #[inline(always)]
    pub fn obvhs_triangle(&self, i: u32, ray: &ObRay, t_max: f32) -> Option<f32> {
        ob_hit(&self.ob_tris[i as usize], ray, t_max)
    }

    /// Whether anything blocks `segment` of the ray, by the any-hit
    /// traversal here with `ValidAabb::meets` over the interval and
    /// `Triangle::occluded`, stopping at the first occluder.
    #[inline(always)]
    pub fn rayhit_occluded(&self, ray: &PreparedRay, segment: Interval<f32>) -> bool {
        self.occluded_with(ray, segment, |b, r| b.meets(ray, r.search))
    }

    /// [`Bvh2Scene::rayhit_occluded`] with the box test `meets`.
    #[inline(always)]
    pub fn occluded_with(
        &self,
        ray: &PreparedRay,
        segment: Interval<f32>,
        meets: impl Fn(&ValidAabb, Reach) -> bool,
    ) -> bool {
        let mut q = Occluded {
            segment,
            blocked: false,
        };
        self.walk_any(ray, &mut q, meets);
        q.blocked
    }

    /// Closest hit by obvhs's own traversal (`Bvh2::ray_traverse`) and
    /// triangle test: the `t` (infinite for none).
    pub fn obvhs_closest(&self, ray: &ObRay) -> f32 {
        let mut hit = RayHit::none();
        self.bvh
            .ray_traverse(*ray, &mut hit, |r, i| self.ob_tris[i].intersect(r));
        hit.t
    }

    /// Whether anything blocks the ray within its `tmin..=tmax`, by obvhs's
    /// own any-hit traversal (`Bvh2::ray_traverse_miss`) and triangle
    /// test.
    pub fn obvhs_occluded(&self, ray: &ObRay) -> bool {
        !self
            .bvh
            .ray_traverse_miss(*ray, |r, i| self.ob_tris[i].intersect(r))
    }
}

/// A pinhole camera's rays at a mesh from outside, row by row: `side` by
/// `side` pixels, from a point 2.5 times the bounding sphere's radius from
/// its centre, the view half as wide as the sphere's silhouette (so that
/// most rays hit the mesh).
pub fn camera_rays(mesh: &Mesh, side: u32) -> Vec<Ray> {
    let (lo, hi) = mesh.bounds();
    let (centre, radius) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
    let back = Vec3::new(0.45, 0.35, 0.8).normalize();
    let eye = centre + back * (2.5 * radius);
    let forward = -back;
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // The tangent of half the view angle: half the sphere's (the mesh
    // fills less than its bounding sphere).
    let half = 0.5 * radius / (2.5 * radius);
    let mut rays = Vec::with_capacity((side * side) as usize);
    for y in 0..side {
        for x in 0..side {
            let sx = ((x as f32 + 0.5) / side as f32 * 2.0 - 1.0) * half;
            let sy = (1.0 - (y as f32 + 0.5) / side as f32 * 2.0) * half;
            rays.push(Ray::new(eye, forward + sx * right + sy * up));
        }
    }
    rays
}

/// `count` rays from random points on the sphere of twice the bounding
/// sphere's radius towards random points of the bounding box, in the
/// order drawn.
pub fn random_rays(mesh: &Mesh, count: usize, seed: u64) -> Vec<Ray> {
    let (lo, hi) = mesh.bounds();
    let (centre, radius) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
    let mut rng = Pcg32::new(seed);
    (0..count)
        .map(|_| {
            let dir = loop {
                let d = Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                );
                if (0.01..=1.0).contains(&d.length_squared()) {
                    break d.normalize();
                }
            };
            let origin = centre + dir * (2.0 * radius);
            let target = lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
            Ray::new(origin, target - origin)
        })
        .collect()
}

/// Rays from inside the solid in random directions (secondary rays, as a
/// path tracer's inside a closed mesh are): the origins of `inside` (the
/// leak rays' interior points), each with a direction uniform on the
/// sphere. Every one must hit the mesh.
pub fn inside_random_rays(inside: &[Ray], seed: u64) -> Vec<Ray> {
    let mut rng = Pcg32::new(seed);
    inside
        .iter()
        .map(|r| Ray::new(r.origin, rng.sphere()))
        .collect()
}

/// Shadow segments from the points where `rays` first hit the mesh
/// (rayhit's closest hit through `scene`) to a point light outside it.
pub struct ShadowRays {
    /// rayhit's segments: `SurfacePoint::spawn_to_point` from the hit's
    /// surface point (an origin moved off the surface by its error bound,
    /// no epsilon), traced over the interval it returns.
    pub rayhit: Vec<(Ray, Interval<f32>)>,
    /// The same segments the usual way: origin `point + EPS n` (the unit
    /// normal turned towards the eye), direction `light - origin`, over
    /// `(0, 1 - EPS]`.
    pub eps: Vec<Ray>,
    /// Hit points where `spawn_to_point` gave no segment (the light within
    /// rounding of the surface's plane): counted as blocked, not traced.
    pub grazing: usize,
    /// Per segment, whether the light is on the eye's side of the surface
    /// (`n . (light - point) > 0`, `n` turned towards the eye): the
    /// segments a renderer traces for an opaque surface, whose reflection
    /// is zero where the light is behind it.
    pub lit: Vec<bool>,
}

/// The offset and the end of the segments [`ShadowRays::eps`] holds.
pub const EPS: f32 = 1e-4;

impl ShadowRays {
    /// The segments from the hits of `rays` (the first hit of each, by
    /// rayhit's traversal of `scene`) to a light at three times the
    /// bounding sphere's radius from its centre, up and to the side.
    pub fn new(scene: &Bvh2Scene, mesh: &Mesh, rays: &[Ray]) -> Self {
        let (lo, hi) = mesh.bounds();
        let (centre, radius) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
        let light = centre + Vec3::new(-0.6, 0.7, 0.4).normalize() * (3.0 * radius);
        let mut out = ShadowRays {
            rayhit: Vec::new(),
            eps: Vec::new(),
            grazing: 0,
            lit: Vec::new(),
        };
        for r in rays {
            let Some((i, hit)) = scene.rayhit_closest(&PreparedRay::new(r)) else {
                continue;
            };
            let tri = &scene.tris[i as usize];
            let surface = rayhit::Surface::surface_point(tri, r, &hit);
            let Some(segment) = surface.spawn_to_point(light) else {
                out.grazing += 1;
                continue;
            };
            out.rayhit.push(segment);
            let n = surface.normal.normalize();
            let n = if n.dot(r.dir) > 0.0 { -n } else { n };
            let origin = surface.point + EPS * n;
            out.eps.push(Ray::new(origin, light - origin));
            out.lit.push(n.dot(light - surface.point) > 0.0);
        }
        out
    }
}

/// The closest-hit walk's box test: `ValidAabb::clip` on `ray` over the
/// query's range, its entry distance.
#[inline(always)]
fn clip_entry(ray: &PreparedRay) -> impl Fn(&ValidAabb, Reach) -> Option<f32> + '_ {
    |b, r| b.clip(ray, r.search).map(|(enter, _)| enter)
}

/// obvhs's triangle test on `ray` with its `tmax` set to `t_max` (obvhs
/// tests `tmin <= t <= tmax`): the hit's `t`, if any.
#[inline(always)]
pub fn ob_hit(tri: &ObTriangle, ray: &ObRay, t_max: f32) -> Option<f32> {
    let t = tri.intersect(&ObRay {
        tmax: t_max,
        ..*ray
    });
    (t != f32::INFINITY).then_some(t)
}

/// obvhs's ray for `r` over `(0, t_max]` (obvhs tests `tmin <= t <=
/// tmax`).
pub fn ob_ray(r: &Ray, t_max: f32) -> ObRay {
    ObRay::new(r.origin.into(), r.dir.into(), 0.0, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cwbvh::{LeakRays, Scene, count_leaks};

    /// rayhit's plain-call traversals (the compressed wide BVH with
    /// `QuantizedChildren::clip` on the prepared ray, and the binary BVH
    /// with `Aabb::clip`) let no ray from inside the torus or the bunny
    /// escape, on rays aimed exactly at vertices and edge midpoints.
    #[test]
    fn plain_call_traversals_do_not_leak() {
        for mesh in [Mesh::torus(120, 90), Mesh::bunny(0)] {
            let rays = LeakRays::new(&mesh, 10_000, 5);
            let mut cw = Scene::new(&mesh);
            cw.check_quantization(true);
            let bvh2 = Bvh2Scene::new(&mesh);
            let wide = count_leaks(&rays, |r| {
                let p = PreparedRay::new(r);
                cw.rayhit_closest_on(&p, &p, r.dir.into())
            });
            let binary = count_leaks(&rays, |r| {
                bvh2.rayhit_closest(&PreparedRay::new(r))
                    .map_or(f32::INFINITY, |(_, h)| h.t)
            });
            for l in [wide, binary] {
                assert_eq!((l.inside_missed, l.passed_through), (0, 0), "{}", mesh.name);
            }
            // The same rays against obvhs's binary traversal, for the record.
            let theirs = count_leaks(&rays, |r| bvh2.obvhs_closest(&ob_ray(r, f32::INFINITY)));
            println!("{}: obvhs Bvh2 {theirs:?}", mesh.name);
        }
    }

    /// The any-hit walks over shadow segments (of the binary tree and of
    /// the compressed wide one) answer as testing every triangle of the
    /// mesh does, and so does the binary closest-hit walk as the nearest
    /// of all triangles' hits, on a small torus and the bunny.
    #[test]
    fn walks_answer_as_every_triangle() {
        for mesh in [Mesh::torus(60, 40), Mesh::bunny(0)] {
            let scene = Bvh2Scene::new(&mesh);
            let mut wide = Scene::new(&mesh);
            wide.check_quantization(true);
            let camera = camera_rays(&mesh, 24);
            let shadow = ShadowRays::new(&scene, &mesh, &camera);
            assert!(shadow.rayhit.len() > 100, "{}", mesh.name);
            let mut blocked = 0;
            for (r, segment) in &shadow.rayhit {
                let p = PreparedRay::new(r);
                let all = scene.tris.iter().any(|t| t.occluded(&p, *segment));
                assert_eq!(scene.rayhit_occluded(&p, *segment), all, "{r:?}");
                let walked = wide.rayhit_occluded_on(&p, &p, *segment);
                assert_eq!(walked, all, "{r:?}");
                blocked += usize::from(all);
            }
            assert!(blocked > 0, "{}", mesh.name);
            for r in &camera {
                let p = PreparedRay::new(r);
                let nearest = scene
                    .tris
                    .iter()
                    .filter_map(|t| t.hit(&p, f32::INFINITY))
                    .map(|h| h.t)
                    .min_by(f32::total_cmp);
                let walked = scene.rayhit_closest(&p).map(|(_, h)| h.t);
                assert_eq!(walked, nearest, "{r:?}");
            }
        }
    }

    /// On a convex closed mesh (the icosphere), a shadow segment is
    /// occluded exactly where the light is behind the surface: `lit`
    /// marks the segments the binary walk finds unoccluded, and both
    /// kinds occur.
    #[test]
    fn lit_segments_are_the_unoccluded_ones_on_a_convex_mesh() {
        let mesh = Mesh::icosphere(3);
        let scene = Bvh2Scene::new(&mesh);
        let shadow = ShadowRays::new(&scene, &mesh, &camera_rays(&mesh, 32));
        let lit = shadow.lit.iter().filter(|&&l| l).count();
        assert!(lit > 100 && shadow.lit.len() - lit > 100, "{lit}");
        for ((r, segment), &lit) in shadow.rayhit.iter().zip(&shadow.lit) {
            assert_eq!(scene.rayhit_occluded(&PreparedRay::new(r), *segment), !lit);
        }
    }

    /// Every bunny inside point the exact crossing count accepts is
    /// inside by a second count along another axis.
    #[test]
    fn crossing_counts_agree_across_directions() {
        let mesh = Mesh::bunny(0);
        let rays = LeakRays::new(&mesh, 500, 9);
        let tris = mesh.triangles();
        for r in &rays.inside {
            let down = PreparedRay::new(&Ray::new(r.origin, -Vec3::Y));
            let search = (
                Interval::up_to(f32::INFINITY).unwrap(),
                rayhit::EdgeRule::OneHit,
            );
            let n = tris
                .iter()
                .filter(|t| t.hit(&down, search).is_some())
                .count();
            assert_eq!(n % 2, 1, "{:?}", r.origin);
        }
    }
}
