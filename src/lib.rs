//! Camera rays (pinhole, thin lens, orthographic, panoramic, from a
//! rasterizer's matrices, with ray differentials and ray cones) and
//! ray/plane, ray/box, ray/triangle, ray/quad, ray/sphere and ray/disc intersection over [`glam`] vectors,
//! with error bounds that are derived, documented and tested against exact
//! arithmetic.
//!
//! ```
//! use rayhit::{Aabb, Camera, PinholeCamera, Triangle, ray_aabb, ray_triangle, glam::Vec3};
//!
//! let cam = PinholeCamera::from_fov(
//!     Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, Vec3::Y, 60f32.to_radians(), 64, 48,
//! ).unwrap();
//! let ray = cam.pixel_ray(32, 24);
//! let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
//! let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
//! assert!((hit.t - 5.0).abs() < 1e-3);
//! let bounds = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
//! let (enter, _exit) = ray_aabb(&ray, &bounds, f32::INFINITY).unwrap();
//! assert!(enter <= hit.t);
//! ```
//!
//! # One way to ask every shape
//!
//! Every shape answers the same questions, each with one name:
//!
//! | question | method | trait |
//! | --- | --- | --- |
//! | the closest hit over a range | `hit(ray, search)` | [`Intersect`] |
//! | does anything block the ray over a range | `occluded(ray, search)` | [`Intersect`] |
//! | the hit's error bound | `hit_error(ray, &hit)` | [`Surface`] |
//! | the point a new ray leaves from | `surface_point(ray, &hit)`, then [`SurfacePoint::spawn`] or [`SurfacePoint::spawn_to`] | [`Surface`] |
//! | a BVH node's test (conservative) | `clip(ray, search)`, or `meets(ray, search)` for the hit or miss alone | [`Bounds`] |
//! | the closest hit of each of several shapes, and the any-hit answer | `hit(ray, search)`, `occluded(ray, search)` | [`IntersectLanes`] |
//!
//! What varies is passed as a value, not spelled in the name:
//!
//! - **the ray** ([`RayForm`]): a [`Ray`]; a [`PreparedRay`], its per-ray
//!   work done once for the many tests of a traversal; or a prepared ray on
//!   an instruction set chosen once ([`batch::SimdRay`]). The answer is the
//!   same bit for bit; the cost differs.
//! - **the search** ([`Search`]): a `t_max`, meaning `(0, t_max]` with
//!   `t > 0` decided conservatively (for rays spawned off a surface), or an
//!   [`Interval`] `(t_min, t_max]` with both ends decided exactly (for
//!   walking every hit in order); either with an [`EdgeRule`] (closed, or
//!   one hit per crossing of a mesh's shared edges).
//!
//! | shape | [`Intersect::Hit`] (or [`IntersectLanes::Hits`]) | [`Surface`] | [`Bounds`] |
//! | --- | --- | --- | --- |
//! | [`Triangle`] | [`TriangleHit`]: `t`, `u`, `v`, [`Side`] | [`TriangleHitError`]; the point from the barycentrics | |
//! | [`Quad`] (planar quads, parallelograms) | [`QuadHit`]: `t`, `u`, `v`, [`Side`] | [`TriangleHitError`]; the point on the triangle of the quad hit | [`Quad::bounds`], a box for your BVH |
//! | [`Plane`] | `t` | the bound on `t`; the point with the plane's exact normal | |
//! | [`Disc`] (and annuli) | [`DiscHit`]: `t`, [`Side`] | the bound on `t`; the point with the disc's exact normal | [`Disc::bounds`], a box for your BVH |
//! | [`Sphere`] | [`SphereHit`]: `t`, [`Side`] (entering or leaving the ball) | the bound on `t`; the point moved onto the sphere, its outward normal | [`Sphere::bounds`], a box for your BVH |
//! | [`Aabb`], [`ValidAabb`] | [`BoxHit`]: the interval and the entry [`BoxFace`], decided exactly | [`Aabb::surface_point`] (none from inside) | `Option<(enter, exit)>` |
//! | [`batch::TriangleBatch`] | [`batch::TriangleBatchHits`]: every lane's hit | | |
//! | [`batch::SphereBatch`] | [`batch::SphereBatchHits`]: every lane's hit | | |
//! | [`batch::AabbBatch`], [`batch::QuantizedChildren`] | | | [`batch::AabbBatchHits`]: the lanes hit, and their entries |
//!
//! The simplest calls keep a free function each: [`ray_triangle`],
//! [`ray_plane`] and [`ray_aabb`] take a [`Ray`] and a `t_max`, and are the
//! trait calls with those arguments, bit for bit.
//!
//! ```
//! use rayhit::{EdgeRule, Intersect, Interval, PreparedRay, Ray, Triangle, glam::Vec3};
//! let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
//! let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
//! let prepared = PreparedRay::new(&ray);
//! let window = Interval::new(1.0, 2.0).unwrap();
//! assert_eq!(tri.hit(&ray, f32::INFINITY).unwrap().t, 2.0);
//! assert_eq!(tri.hit(&prepared, window), tri.hit(&ray, window));
//! assert!(tri.occluded(&prepared, (window, EdgeRule::OneHit)));
//! ```
//!
//! # Which call for which job
//!
//! | job | call | why this one |
//! | --- | --- | --- |
//! | camera rays | [`Camera::ray`] of a [`CameraSample`] (or [`Camera::pixel_ray`]) on any camera: [`PinholeCamera`] and the others in [`camera`] | unit directions to a few ulps, raster conventions stated, one trait for six cameras |
//! | depth of field | [`camera::ThinLensCamera::focus`] once per film point, then [`camera::ThinLensCamera::ray_through`] per lens sample | every ray of a film point meets its focus point exactly (`ray.at(1)` is it, bit for bit); the lens centre is the pinhole ray |
//! | CAD views, previews, baking | [`camera::OrthographicCamera`] | one direction for every ray, bit for bit; origins on a plane you place by the scene |
//! | rays matching a rasterizer's pixels | [`camera::MatrixCamera::from_mat4`] with your view and projection matrices | the ray of a pixel projects back to it within a stated bound |
//! | environment maps, 360-degree captures | [`camera::EquirectangularCamera`], [`camera::EqualAreaCamera`] | with the inverse, `raster_position`, and its bound |
//! | texture filtering | [`Camera::ray_differential`], then [`Triangle::hit_differentials`] (or [`Camera::ray_cone`] and [`Triangle::cone_width`]) | each derivative with its error bound ([`Triangle::hit_differentials_error`]) |
//! | closest hit on a mesh | [`ray_triangle`], or [`Intersect::hit`] on a [`PreparedRay`] when one ray meets many triangles | watertight: no ray passes between triangles that share an edge |
//! | BVH node, binary | [`Bounds::clip`] of a [`ValidAabb`] on a [`PreparedRay`] | conservative: never misses a box the ray meets, so the leaf is always visited; a `ValidAabb` is checked once, when made |
//! | BVH node, 4 to 16 children | [`Bounds::clip`] of a [`batch::AabbBatch`] on a [`PreparedRay`] ([`Bounds::meets`] where you visit children in a fixed order or ask for any hit) | one ray against a node's children at once, the same answers bit for bit, on the widest SIMD the CPU has |
//! | compressed wide BVH node (8-bit child boxes) | [`Bounds::meets`] (or [`Bounds::clip`]) of the node read in place, [`batch::InPlace`] of a closure making its [`batch::QuantizedChildren`], on a [`PreparedRay`] | reads the node as stored, still conservative; in place, a plain call costs about what the test inlined does |
//! | leaf with several triangles | [`IntersectLanes::hit`] of a [`batch::TriangleBatch`] | 8 or 16 triangles at once, each lane the scalar test's answer |
//! | leaf of particles (spheres) | [`IntersectLanes::hit`] of a [`batch::SphereBatch`] on a [`PreparedRay`] | 8 or 16 spheres at once, each lane [`Sphere`]'s answer bit for bit, several times the speed of one call per sphere |
//! | shadow ray between two surfaces, or to a point light | [`SurfacePoint::spawn_to`], [`SurfacePoint::spawn_to_point`], then [`Intersect::occluded`] over the [`Interval`] they return | no epsilon: the segment cannot hit the surface at either end, and an occluder farther from both ends' planes than their error bounds is found |
//! | shadow / any-hit ray from a plain origin | [`Intersect::occluded`] with the light's distance as `t_max` | `t_max` is honoured conservatively |
//! | inside/outside, CSG, crossing counts | [`Intersect::hit`] with [`EdgeRule::OneHit`] | decided exactly: one hit per point where the ray crosses the surface the triangles form, at edges and corners too; zero-area fillers never hit |
//! | every hit along a ray, in order (transparency, alpha-tested foliage, volumes) | a [`Walk`]: [`Intersect::hit`] with [`EdgeRule::OneHit`] over the windows it gives, from your own traversal; nodes culled with [`Bounds::clip`] over the same windows | one report per surface crossing: both ends of every window decided exactly, so no crossing is skipped or repeated, and the windows are in exact order; the node tests never cull a box the ray crosses within a window |
//! | boxes as geometry | [`Intersect::hit`] of an [`Aabb`], then [`Aabb::surface_point`] | the face the ray enters through, decided exactly, and its normal |
//! | planes | [`ray_plane`] (or [`Intersect::hit`] of a [`Plane`]) | `t` with its error bound ([`Surface::hit_error`]) |
//! | quads (Cornell-box walls and lights, quad meshes, "The Next Week"'s `quad`) | [`Intersect::hit`] of a [`Quad`] (built with [`Quad::parallelogram`] or from four mesh corners), on a [`PreparedRay`] for many quads | watertight with the quads and triangles it shares edges with, `(u, v)` on the quad, the triangle's bounds and spawning |
//! | discs and rings (area lights, lens and camera models, clipped planes) | [`Intersect::hit`] of a [`Disc`] | the rims decided exactly: a ray through a disc's edge is never misjudged, and a disc and the ring around it leave no gap |
//! | spheres (particles, molecules, "One Weekend" scenes) | [`Intersect::hit`] of a [`Sphere`], then [`Surface::surface_point`] and [`SurfacePoint::spawn`] | no false miss at any distance (no rings on far spheres), `t` with its error bound, and no epsilon: a spawned ray never meets the sphere it left, one spawned into it finds the far side |
//! | the next ray from a hit | [`Surface::surface_point`], then [`SurfacePoint::spawn`] | the new ray cannot hit the surface it left |
//! | instances (one mesh placed many times, two-level BVH) | [`Instance`]: `object_to_world_box` for the top level, `world_to_object` once per visit, `surface_to_world` and `spawn` for the next ray, `spawn_to_through` for a shadow segment | world boxes contain the exact transformed object box; the spawned ray, mapped back, cannot hit the surface it left |
//! | when speed matters more than cracks | [`Triangle::moller_trumbore`] | the textbook fast test, not watertight |
//!
//! # Conventions
//!
//! - A [`Ray`] is `origin + t * dir` for `t >= 0`. `dir` need not be unit
//!   length; every `t` is measured in multiples of `dir`. A zero or
//!   non-finite `dir` (or origin) hits nothing.
//! - A surface ([`Plane`], [`Triangle`], [`Quad`], [`Sphere`], [`Disc`]) is hit at `0 < t <= t_max`: a hit at
//!   exactly `t = 0` is the ray's own starting surface and is not reported.
//! - A box ([`Aabb`]) is a closed solid: the result is the interval
//!   `[max(t_enter, 0), min(t_exit, t_max)]` when it is not empty, so a ray
//!   starting inside has `enter = 0`.
//! - Shapes are closed: a ray through a box face, edge or corner, or through
//!   a triangle edge or corner, hits ([`EdgeRule::OneHit`] is the
//!   deliberate exception, for meshes).
//! - Triangle hits carry barycentrics `(u, v)` with
//!   `point = (1 - u - v) * a + u * b + v * c`, each in `[0, 1]`, and the
//!   [`Side`] the ray came from; the tests are two-sided.
//! - Cameras ([`Camera`]): right-handed world, raster `(0, 0)` at the
//!   image's top-left, `x` right, `y` down, pixel `(i, j)` centred at
//!   `(i + 0.5, j + 0.5)`, `right = normalize(view x up)`; see
//!   [`PinholeCamera`].
//! - Bad input (NaN, infinities, zero vectors, zero plane normals, inverted
//!   boxes, NaN or negative `t_max`) gives `None` or an error
//!   ([`camera::CameraError`], [`instance::InstanceError`]); nothing
//!   panics and no `t` is NaN. A camera's bad parameters are errors when
//!   it is made; a NaN raster position gives a NaN ray (which every query
//!   rejects). Zero-area triangles are not invalid: they are hit where
//!   rounding leaves them a sliver, which keeps meshes that close
//!   T-junctions with them watertight (see [`Triangle`]).
//!
//! # Precision
//!
//! Every type and function is generic over the vector type: [`glam::Vec3`]
//! (`f32`, the default type parameter, so `Ray` means `Ray<Vec3>`),
//! [`glam::Vec3A`] (`f32` in a 16-byte SIMD register, as BVH crates such as
//! `obvhs` store their geometry: no conversion needed) or [`glam::DVec3`]
//! (`f64`). Every vector type of a precision gives the same answers, bit for
//! bit (the kernels do the same arithmetic on each). The `f64` types also
//! have glam-style names, `D` and the name ([`DRay`], [`DTriangle`],
//! [`camera::DThinLensCamera`], [`batch::DAabbBatch`], ...); functions and
//! methods need no second name: `ray_triangle(&ray, &tri, f64::INFINITY)`
//! takes a `DRay` and a `DTriangle`.
//!
//! The glam above is the one this crate re-exports, [`glam`] 0.34. A crate
//! on an older glam turns on that release's feature (`glam-029`,
//! `glam-030`, `glam-031`, `glam-032` or `glam-033`) and passes its own
//! `Vec3`, `Vec3A` or `DVec3` to every kernel, with the same answers bit for
//! bit; the hits come back in its own types. Import by name or with
//! [`prelude`]: a glob import of the crate root brings in `rayhit::glam`
//! too, which is ambiguous next to your own `glam`. For other math crates,
//! the `mint-05` feature adds `from_mint` constructors (see the `mint` module).
//!
//! The kernels are written once, against the sealed [`Vector`] and
//! [`Scalar`] traits, and each error bound is derived in terms of the unit
//! roundoff `u` of the precision in use (`2^-24` for `f32`, `2^-53` for
//! `f64`), with `gamma(n) = n*u / (1 - n*u)` ([`Scalar::gamma_n`]) bounding
//! `n` chained roundings; so every guarantee holds in both precisions,
//! each with its own `u`, and the test suite checks both.
//!
//! ```
//! use rayhit::{DRay, DTriangle, ray_triangle, glam::DVec3};
//! let tri = DTriangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
//! let ray = DRay::new(DVec3::new(0.25, 0.25, 1e9), -DVec3::Z);
//! assert_eq!(ray_triangle(&ray, &tri, f64::INFINITY).unwrap().t, 1e9);
//! ```
//!
//! # Watertight traversal
//!
//! The watertight triangle test keeps a ray from slipping between two
//! triangles; a BVH can still lose the ray before it reaches them. A ray
//! aimed at a shared vertex or edge passes exactly along the boundary of
//! the boxes around it, and a node test that misses such a box by one
//! rounding (as the textbook slab test does, and a test with an epsilon on
//! `t`) never visits the leaf holding the triangles: the ray goes through
//! the mesh. So a watertight traversal needs a *conservative* node test,
//! one that never misses a box exact arithmetic says the ray meets, and the
//! triangle test in the leaves; every [`Bounds`] test is conservative:
//!
//! | BVH shape | node test | leaves |
//! | --- | --- | --- |
//! | binary, boxes as [`ValidAabb`] (checked once, when built) | [`Bounds::clip`] of the box | [`Intersect::hit`] of each [`Triangle`] |
//! | wide (4 to 16 children), boxes stored as a [`batch::AabbBatch`] | [`Bounds::clip`] of the batch (its `meets` where the entries go unused) | the same, or of a [`batch::TriangleBatch`] |
//! | compressed wide (children quantized to bytes, Ylitie et al. 2017) | [`Bounds::meets`] (or `clip`) of [`batch::QuantizedChildren`], the node as stored, read in place by [`batch::InPlace`] | the same |
//!
//! Closest hit: pass the nearest hit so far as `t_max` to both tests, so
//! that farther nodes and triangles are culled. Shadow segments (from
//! [`SurfacePoint::spawn_to`] or `spawn_to_point`): pass the segment's
//! [`Interval`] to [`Bounds::meets`] and [`Intersect::occluded`] and stop
//! at the first occluder, taking a node's children in the order they are
//! stored rather than nearest first. Such a segment starts on the surface
//! it leaves, inside the boxes around that point, which rarely hold an
//! occluder; nearest first would visit them before anything else.
//!
//! For a compressed wide BVH, the node test is conservative for the boxes
//! the bytes describe; those must contain the geometry, which
//! [`batch::QuantizedChildren::quantize`] guarantees for a builder that
//! uses it.
//!
//! ```
//! use rayhit::glam::Vec3;
//! use rayhit::{Aabb, Bounds, Intersect, PreparedRay, Ray, Triangle, ValidAabb};
//!
//! /// A binary BVH node: a box and either two children or a range of triangles.
//! enum Node {
//!     Inner { bounds: ValidAabb, children: [usize; 2] },
//!     Leaf { bounds: ValidAabb, triangles: std::ops::Range<usize> },
//! }
//!
//! /// The nearest hit along `ray`: `(t, triangle index)`.
//! fn closest(nodes: &[Node], triangles: &[Triangle], ray: &Ray) -> Option<(f32, usize)> {
//!     let ray = PreparedRay::new(ray);
//!     let (mut best, mut t_max) = (None, f32::INFINITY);
//!     let mut stack = vec![0];
//!     while let Some(i) = stack.pop() {
//!         let bounds = match &nodes[i] {
//!             Node::Inner { bounds, .. } | Node::Leaf { bounds, .. } => bounds,
//!         };
//!         // Conservative: never skips a node the ray meets before `t_max`.
//!         if bounds.clip(&ray, t_max).is_none() {
//!             continue;
//!         }
//!         match &nodes[i] {
//!             Node::Inner { children, .. } => stack.extend(children),
//!             Node::Leaf { triangles: range, .. } => {
//!                 for k in range.clone() {
//!                     if let Some(hit) = triangles[k].hit(&ray, t_max) {
//!                         (best, t_max) = (Some((hit.t, k)), hit.t);
//!                     }
//!                 }
//!             }
//!         }
//!     }
//!     best
//! }
//!
//! // Two triangles sharing the edge from (1, 0, 0) to (0, 1, 0), one leaf each.
//! let tris = [
//!     Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
//!     Triangle::new(Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y),
//! ];
//! let valid = |b: Aabb| ValidAabb::new(b).expect("finite, not inverted");
//! let bounds = |t: &Triangle| valid(Aabb::new(t.a.min(t.b).min(t.c), t.a.max(t.b).max(t.c)));
//! let nodes = [
//!     Node::Inner { bounds: valid(Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))), children: [1, 2] },
//!     Node::Leaf { bounds: bounds(&tris[0]), triangles: 0..1 },
//!     Node::Leaf { bounds: bounds(&tris[1]), triangles: 1..2 },
//! ];
//! // Straight down through the middle of the shared edge: found.
//! let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), -Vec3::Z);
//! assert_eq!(closest(&nodes, &tris, &ray).map(|(t, _)| t), Some(1.0));
//! ```
//!
//! # Instances
//!
//! One mesh placed many times: an [`Instance`] holds an object-to-world
//! affine map `x -> M x + T` (from glam's `Affine3A` or `DAffine3`), its
//! inverse computed once, and bounds on that inverse's error measured from
//! the matrix itself (the residual `M A - I`), never assumed. A two-level
//! BVH uses it like this:
//!
//! - the top level stores one box per instance,
//!   [`Instance::object_to_world_box`] of the mesh's root box: it contains
//!   the exact image of the object box, so the top level never loses a ray
//!   the exact transform sends into the instance;
//! - on reaching an instance's leaf, map the ray once with
//!   [`Instance::world_to_object`], prepare it once, and traverse the
//!   mesh's own BVH with it: every triangle of the instance sees the same
//!   object ray, so the watertight guarantees hold inside the instance.
//!   `t` is shared between world and object space (the direction is mapped
//!   linearly), so the closest hit so far carries over as `t_max`;
//!   [`Instance::world_to_object_error`] bounds the difference between the
//!   two rays' points at any `t`;
//! - take the hit to the world with [`Instance::surface_to_world`] of its
//!   [`SurfacePoint`], and leave it with [`Instance::spawn`]: the new ray,
//!   mapped back into the same instance through the stored inverse, does
//!   not meet the surface it left (for a direction not within rounding of
//!   tangent). Nested instances chain the maps level by level, and
//!   [`Instance::spawn_through`] and [`instance::InstanceRayError::nested`]
//!   carry the bounds through the chain.
//!
//! Preconditions: the matrix is finite and not singular, and its computed
//! inverse is good to better than half (a condition number well below
//! `1 / u`; construction returns an [`instance::InstanceError`]
//! otherwise); every bound grows with the condition number and the
//! coordinates' magnitude. What does not hold: two *different* instances
//! meeting at a seam are not watertight with each other (each sees its own
//! rounded object ray), unless their transforms are equal.
//!
//! ```
//! use rayhit::{Aabb, Instance, Intersect, PreparedRay, Ray, Triangle, ray_aabb, glam::{Affine3A, Quat, Vec3}};
//! let mesh = [Triangle::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, -1.0))];
//! let mesh_box = Aabb::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0));
//! let copies = [
//!     Instance::from_affine3a(Affine3A::from_translation(Vec3::new(2e4, 0.0, 0.0))).unwrap(),
//!     Instance::from_affine3a(Affine3A::from_scale_rotation_translation(
//!         Vec3::splat(3.0), Quat::from_rotation_y(1.0), Vec3::new(-2e4, 5.0, 0.0))).unwrap(),
//! ];
//! let top: Vec<Aabb> = copies.iter().map(|c| c.object_to_world_box(&mesh_box).unwrap()).collect();
//! let world = Ray::new(Vec3::new(-2e4 + 0.1, 20.0, 0.2), -Vec3::Y);
//! let mut best = None;
//! let mut t_max = f32::INFINITY;
//! for (copy, bounds) in copies.iter().zip(&top) {
//!     if ray_aabb(&world, bounds, t_max).is_none() {
//!         continue;
//!     }
//!     let object = PreparedRay::new(&copy.world_to_object(&world)); // once per visit
//!     for tri in &mesh {
//!         if let Some(hit) = tri.hit(&object, t_max) {
//!             t_max = hit.t;
//!             best = Some((copy, *tri, hit));
//!         }
//!     }
//! }
//! let (copy, tri, hit) = best.unwrap();
//! assert!((hit.t - 15.0).abs() < 1e-2);
//! let here = copy.surface_to_world(&tri.surface_point_at(hit.u, hit.v));
//! let bounce = copy.spawn(&here, Vec3::new(0.2, 1.0, 0.1));
//! assert!(tri.hit(&PreparedRay::new(&copy.world_to_object(&bounce)), f32::INFINITY).is_none());
//! ```
//!
//! # Numerical guarantees
//!
//! "Exact" means what real arithmetic says about the same floating-point
//! inputs: every finite float is a rational number, and the crate's test
//! suite decides each question exactly with big rationals and holds every
//! query to its claims (the [`exact`](crate#features) module offers the
//! same answers). Each guarantee is stated, with its preconditions, where
//! the query is documented:
//!
//! | query | what it promises | stated at |
//! | --- | --- | --- |
//! | the slab test, a box's [`Bounds::clip`] | no false miss against exact arithmetic; false hits only within a few ulps of an edge or corner | [`ray_aabb`]; [`Aabb`]'s `clip` for intervals |
//! | the face-by-face box test | the reference: agrees with the slab test away from edges and corners | [`Aabb::clip_by_faces`] |
//! | a box's entry face | decided exactly; over intervals, each entry reported once | [`Aabb`]'s `hit` |
//! | the watertight triangle test | no ray passes between triangles sharing an edge; `t > 0` in exact arithmetic; `t`, `u`, `v` within their error bounds | [`ray_triangle`]; [`Triangle`]'s `hit` for intervals and the one-hit rule |
//! | a triangle hit's error bounds | finite wherever the side is certain | [`Triangle`]'s `hit_error` |
//! | Moller-Trumbore | agrees with the watertight test away from edges; not watertight | [`Triangle::moller_trumbore`] |
//! | the plane test | `t` within its bound; over intervals decided exactly | [`ray_plane`]; [`Plane`]'s `hit` and `hit_error` |
//! | batches and compressed nodes | every lane bit for bit the scalar answer | [`batch::TriangleBatch`]'s `hit`, [`batch::AabbBatch`]'s and [`batch::QuantizedChildren`]'s `clip` |
//! | spawned rays | do not hit the surface they leave | [`SurfacePoint::spawn`] |
//! | shadow segments | hit neither end; find every occluder beyond the ends' bounds | [`SurfacePoint::spawn_to`], [`SurfacePoint::spawn_to_point`] |
//! | cameras | unit directions, exact focus points, back-projection and round-trip bounds | each camera in [`camera`], and its bound functions |
//! | differentials | each camera's within its second-order term; at a hit within their bound | [`Camera::ray_differential`] of each camera, [`Triangle::hit_differentials_error`] |
//! | instances | world boxes contain the exact image; spawned rays do not re-hit through the stored inverse | [`Instance`] and its methods |
//!
//! Preconditions shared by all of them: round-to-nearest arithmetic (Rust's
//! only mode), and no intermediate overflow. For the box test, no difference
//! between a box coordinate and the origin overflows and the exact entry and
//! exit are below `MAX / 2`; for the triangle tests, coordinates relative to
//! the ray origin below `2^63` (`f32`) or `2^511` (`f64`), so that the edge
//! functions' products do not overflow, the corners' distances along the
//! ray scaled by `1 / d_z` (about `t`) times the edge functions finite (a
//! nearly parallel ray with `|d_z|` near `1/MAX` can break this), and, for
//! the `f64` exact-sign fallback, those products above `2^-969` or zero.
//!
//! The error bounds (`t`, `u`, `v`, hit points, and so the spawned-ray
//! guarantee) and the false-hit bands are relative-error arguments, like
//! pbrt-v4's: they also assume that no intermediate product or quotient
//! underflows (a result below `MIN_POSITIVE` carries an absolute error of up
//! to half a subnormal, which they do not count). That takes coordinates,
//! direction components and `t` values far below the normal range (such as
//! `t < 2^-100` or a subnormal shear factor). The slab test's "no false
//! miss" does not assume it (two subnormals of slack cover it), nor does
//! the crack-freeness of the watertight and one-hit tests, which rests on
//! computing a shared edge's functions identically, not on their accuracy.
//!
//! Exact metamorphic identities hold bit for bit: scaling the direction or
//! all positions by a power of two scales every `t` accordingly; mirroring
//! an axis and translating on a coarse grid change nothing; reversing a
//! triangle's winding swaps `u` and `v` and the side.
//!
//! # Features
//!
//! - `std` (default): float math from the standard library. Without it
//!   the crate is `no_std` and takes its float math from the `libm` crate,
//!   so `default-features = false` is all a bare-metal target needs.
//! - `libm`: does nothing (`libm` is used whenever `std` is off); kept so
//!   that builds naming it keep working.
//! - `glam-029` to `glam-033`: glam's `Vec3`, `Vec3A` and `DVec3` of that
//!   release as vector types (see "Precision").
//! - `mint-05`: `from_mint` constructors for [`Ray`], [`Aabb`], [`Triangle`]
//!   and [`Plane`] (see the `mint` module), and glam's own mint conversions.
//! - `exact`: the public `exact` module, exact answers to every query and
//!   verdicts on claimed answers (turns on `std`).
//! - `approx-05`: `approx`'s `AbsDiffEq`, `RelativeEq` and `UlpsEq` for the
//!   public types and triangle hits (see the `approx` module for what each
//!   comparison means).
//! - `proptest`: the public `strategies` module, the generators the
//!   crate's property tests use (aimed rays, boxes, triangles, planes,
//!   spheres), for
//!   testing your own kernels against this crate's.
//! - `arbitrary`: `arbitrary::Arbitrary` for [`Ray`], [`Aabb`], [`Plane`],
//!   [`Triangle`] and [`Sphere`] in both precisions, every coordinate (and
//!   radius) a raw bit pattern (NaN, infinities, subnormals and `-0.0`
//!   included), for fuzzers.
//! - `bytemuck`: `Pod` and `Zeroable` for [`Ray`], [`Aabb`], [`Triangle`],
//!   [`Plane`] and [`TriangleHitError`] over `Vec3` and `DVec3`, and checked
//!   casts to [`ValidAabb`], for GPU buffers (see the `bytemuck` module).
//! - `serde`: `Serialize` and `Deserialize` for the rays, shapes and hits,
//!   every bit kept by binary formats (see the `serde` module).

#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "std")]
extern crate std;

pub use glam;

// The modules, in the order their dependencies point: numbers, then SIMD
// lanes, then the ray and the point a ray leaves a surface from, then the
// query traits, then the shapes, then the BVH-node form and the batch
// kernels on a chosen instruction set (`node/`), then cameras and
// instances; the optional integrations (`features/`) and `exact` on top.
// CONTRIBUTING.md has the map, file by file.
mod num;
mod simd;

mod ray;
mod surface;

mod query;

mod aabb;
mod disc;
mod patch;
mod plane;
mod quad;
mod sphere;
mod triangle;

mod node;

pub mod camera;

pub mod instance;

#[cfg(feature = "approx-05")]
#[cfg_attr(docsrs, doc(cfg(feature = "approx-05")))]
#[path = "features/approx.rs"]
pub mod approx;
#[cfg(feature = "arbitrary")]
#[path = "features/arbitrary.rs"]
mod arbitrary;
#[cfg(feature = "bytemuck")]
#[cfg_attr(docsrs, doc(cfg(feature = "bytemuck")))]
#[path = "features/bytemuck.rs"]
pub mod bytemuck;
#[cfg(feature = "exact")]
#[cfg_attr(docsrs, doc(cfg(feature = "exact")))]
pub mod exact;
#[cfg(feature = "mint-05")]
#[cfg_attr(docsrs, doc(cfg(feature = "mint-05")))]
#[path = "features/mint.rs"]
pub mod mint;
#[cfg(feature = "serde")]
#[cfg_attr(docsrs, doc(cfg(feature = "serde")))]
#[path = "features/serde.rs"]
pub mod serde;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
#[path = "features/strategies.rs"]
pub mod strategies;

#[cfg(test)]
mod testing;

/// Several shapes against one ray at once, for BVH nodes and leaves: the
/// batches, a compressed wide BVH node read in place, and the choice of
/// SIMD instruction set.
///
/// A batch answers the same queries as its shapes ([`Bounds`] for boxes and
/// nodes, [`IntersectLanes`] for triangles and spheres), every lane bit for bit the
/// scalar answer, eight lanes at a time in SIMD registers. On x86-64 with `std`
/// each call runs the AVX-512 or AVX2 copy where the CPU has one (the
/// detection is cached: a load and a comparison per call, then a call into
/// the copy), so the plain call on a [`PreparedRay`] is the one to write
/// first; [`Bounds::meets`] answers in a register where a traversal needs
/// no entry distances. [`with_simd`](crate::batch::with_simd) compiles a whole traversal for
/// the chosen instruction set instead, and a ray put on it
/// ([`Simd::ray`](crate::batch::Simd::ray)) runs every batch query inline, with no call per
/// node.
///
/// ```
/// use rayhit::{Aabb, Bounds, PreparedRay, Ray, glam::Vec3};
/// use rayhit::batch::AabbBatch;
/// let boxes = [Aabb::new(Vec3::splat(1.0), Vec3::splat(2.0)), Aabb::new(Vec3::splat(-2.0), Vec3::splat(-1.0))];
/// let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::ONE));
/// let hits = batch.clip(&ray, f32::INFINITY);
/// assert_eq!(hits.mask, 0b01);
/// assert_eq!(hits.enter[0], 1.0);
/// ```
pub mod batch {
    pub use crate::aabb::{AabbBatch, AabbBatchHits};
    pub use crate::node::{InPlace, QuantizedChildren};
    pub use crate::node::{Simd, SimdRay, SimdWork, with_simd};
    pub use crate::simd::TargetSimd;
    #[cfg(rayhit_runtime_avx)]
    pub use crate::simd::{Avx2, Avx512};
    pub use crate::sphere::{SphereBatch, SphereBatchHits};
    pub use crate::triangle::{TriangleBatch, TriangleBatchHits};

    #[cfg(doc)]
    use crate::{Bounds, IntersectLanes};

    /// [`AabbBatch`] in `f64`.
    pub type DAabbBatch<const N: usize = 8> = AabbBatch<glam::DVec3, N>;
    /// [`SphereBatch`] in `f64`.
    pub type DSphereBatch<const N: usize = 8> = SphereBatch<glam::DVec3, N>;
    /// [`TriangleBatch`] in `f64`.
    pub type DTriangleBatch<const N: usize = 8> = TriangleBatch<glam::DVec3, N>;
}

/// The crate root's items, one list: the root re-exports it, and so does
/// [`prelude`].
mod root {
    pub use crate::aabb::{Aabb, BoxFace, BoxHit, ValidAabb, ray_aabb};
    pub use crate::camera::{Camera, CameraSample, DPinholeCamera, PinholeCamera};
    pub use crate::disc::{Disc, DiscHit};
    pub use crate::instance::{DInstance, Instance};
    pub use crate::num::{Scalar, Vector};
    pub use crate::patch::{Patch, PatchHit};
    pub use crate::plane::{Plane, ray_plane};
    pub use crate::quad::{Quad, QuadHit};
    pub use crate::query::{Bounds, EdgeRule, Intersect, IntersectLanes, RayForm, Search, Surface};
    pub use crate::ray::{Interval, PreparedRay, Ray, Walk};
    pub use crate::sphere::{Sphere, SphereHit};
    pub use crate::surface::SurfacePoint;
    pub use crate::triangle::{Side, Triangle, TriangleHit, TriangleHitError, ray_triangle};

    use glam::DVec3;

    /// [`Ray`] in `f64`.
    pub type DRay = Ray<DVec3>;
    /// [`PreparedRay`] in `f64`.
    pub type DPreparedRay = PreparedRay<DVec3>;
    /// [`Aabb`] in `f64`.
    pub type DAabb = Aabb<DVec3>;
    /// [`ValidAabb`] in `f64`.
    pub type DValidAabb = ValidAabb<DVec3>;
    /// [`BoxHit`] in `f64`.
    pub type DBoxHit = BoxHit<f64>;
    /// [`Patch`] in `f64`.
    pub type DPatch = Patch<DVec3>;
    /// [`PatchHit`] in `f64`.
    pub type DPatchHit = PatchHit<f64>;
    /// [`Plane`] in `f64`.
    pub type DPlane = Plane<DVec3>;
    /// [`Disc`] in `f64`.
    pub type DDisc = Disc<DVec3>;
    /// [`DiscHit`] in `f64`.
    pub type DDiscHit = DiscHit<f64>;
    /// [`Quad`] in `f64`.
    pub type DQuad = Quad<DVec3>;
    /// [`QuadHit`] in `f64`.
    pub type DQuadHit = QuadHit<f64>;
    /// [`Sphere`] in `f64`.
    pub type DSphere = Sphere<DVec3>;
    /// [`SphereHit`] in `f64`.
    pub type DSphereHit = SphereHit<f64>;
    /// [`Triangle`] in `f64`.
    pub type DTriangle = Triangle<DVec3>;
    /// [`TriangleHit`] in `f64`.
    pub type DTriangleHit = TriangleHit<f64>;
    /// [`TriangleHitError`] in `f64`.
    pub type DTriangleHitError = TriangleHitError<f64>;
    /// [`SurfacePoint`] in `f64`.
    pub type DSurfacePoint = SurfacePoint<DVec3>;
}
pub use root::*;

/// The crate root's items except the re-exported `glam` and the modules,
/// for `use rayhit::prelude::*;`: the same list, so the two never differ.
///
/// A glob import of the crate root itself (`use rayhit::*;`) brings in
/// `rayhit::glam` too, which is ambiguous (E0659) next to a crate's own
/// `glam` dependency; this module is the glob-import that is not.
///
/// ```
/// use glam::Vec3; // your own glam
/// use rayhit::prelude::*;
/// let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert!(tri.hit(&ray, f32::INFINITY).is_some());
/// assert!(ray_triangle(&ray, &tri, f32::INFINITY).is_some());
/// ```
pub mod prelude {
    pub use crate::root::*;
}

/// The README's code blocks, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

#[cfg(test)]
mod root_tests {
    /// The crate root and the prelude are one list: the root publishes
    /// `mod root` and the modules, the prelude `mod root` alone, and nothing
    /// else is re-exported at either (a `pub use` added beside them would
    /// put an item in one and not the other).
    #[test]
    fn root_and_prelude_are_one_list() {
        let src = include_str!("lib.rs");
        // Top-level lines only (the crate docs and nested items indent or
        // comment theirs).
        let top: std::vec::Vec<&str> = src.lines().filter(|l| l.starts_with("pub ")).collect();
        let uses: std::vec::Vec<&str> = top
            .iter()
            .copied()
            .filter(|l| l.starts_with("pub use"))
            .collect();
        assert_eq!(uses, ["pub use glam;", "pub use root::*;"], "{top:?}");
        let prelude = src
            .split("pub mod prelude {")
            .nth(1)
            .and_then(|rest| rest.split('}').next())
            .expect("a prelude module");
        assert_eq!(prelude.trim(), "pub use crate::root::*;");
        // The names in the list are at the root, and so in the prelude.
        use crate::prelude as p;
        let _: fn(&p::Ray, &p::Triangle, f32) -> Option<p::TriangleHit> = crate::ray_triangle;
        let _: fn(&p::Ray, &p::Plane, f32) -> Option<f32> = crate::ray_plane;
        let _: fn(&p::Ray, &p::Aabb, f32) -> Option<(f32, f32)> = crate::ray_aabb;
    }
}
