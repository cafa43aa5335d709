//! Camera rays (pinhole, thin lens, orthographic, panoramic, from a
//! rasterizer's matrices, with ray differentials and ray cones) and
//! ray/plane, ray/box and ray/triangle intersection, as small pure functions
//! over [`glam`] vectors, with error bounds that are derived, documented and
//! tested against exact arithmetic.
//!
//! ```
//! use rayhit::{Aabb, PinholeCamera, Triangle, ray_aabb, ray_triangle, glam::Vec3};
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
//! # Conventions
//!
//! - A [`Ray`] is `origin + t * dir` for `t >= 0`. `dir` need not be unit
//!   length; every `t` is measured in multiples of `dir`. A zero or
//!   non-finite `dir` (or origin) hits nothing.
//! - A surface ([`Plane`], [`Triangle`]) is hit at `0 < t <= t_max`: a hit at
//!   exactly `t = 0` is the ray's own starting surface and is not reported.
//! - A box ([`Aabb`]) is a closed solid: the result is the interval
//!   `[max(t_enter, 0), min(t_exit, t_max)]` when it is not empty, so a ray
//!   starting inside has `enter = 0`.
//! - Shapes are closed: a ray through a box face, edge or corner, or through
//!   a triangle edge or corner, hits ([`ray_triangle_one_hit`] is the
//!   deliberate exception, for meshes).
//! - Triangle hits carry barycentrics `(u, v)` with
//!   `point = (1 - u - v) * a + u * b + v * c`, each in `[0, 1]`, and the
//!   [`Side`] the ray came from; the tests are two-sided.
//! - Cameras: right-handed world, raster `(0, 0)` at the image's top-left,
//!   `x` right, `y` down, pixel `(i, j)` centred at `(i + 0.5, j + 0.5)`,
//!   `right = normalize(view x up)`; see [`PinholeCamera`]. Every camera
//!   ([`PinholeCamera`], [`ThinLensCamera`], [`OrthographicCamera`],
//!   [`MatrixCamera`], [`EquirectangularCamera`], [`EqualAreaCamera`])
//!   gives the ray of a raster position, the ray with its differentials
//!   ([`RayDifferential`]: per pixel in `x` and `y`) and its ray cone
//!   ([`RayCone`]); [`triangle_hit_differentials`] carries the differentials
//!   to a hit, for texture filtering.
//! - Bad input (NaN, infinities, zero vectors, zero plane normals, inverted
//!   boxes, NaN or negative `t_max`) gives `None` or a [`CameraError`];
//!   nothing panics and no `t` is NaN. Zero-area triangles are hit where
//!   rounding leaves them a sliver (see [`Triangle`]).
//!
//! # Precision
//!
//! Every type and function is generic over the vector type: [`glam::Vec3`]
//! (`f32`, the default type parameter, so `Ray` means `Ray<Vec3>`),
//! [`glam::Vec3A`] (`f32` in a 16-byte SIMD register, as BVH crates such as
//! `obvhs` store their geometry: no conversion needed) or [`glam::DVec3`]
//! (`f64`). Every vector type of a precision gives the same answers, bit for
//! bit (the kernels do the same arithmetic on each). The `f64` types also
//! have glam-style names:
//! [`DRay`], [`DAabb`], [`DValidAabb`], [`DPreparedRay`], [`DAabbBatch`],
//! [`DTriangleBatch`], [`DPlane`], [`DTriangle`], [`DTriangleHit`],
//! [`DTriangleHitError`], [`DPinholeCamera`], [`DThinLensCamera`],
//! [`DOrthographicCamera`], [`DMatrixCamera`], [`DEquirectangularCamera`],
//! [`DEqualAreaCamera`], [`DRayDifferential`], [`DHitDifferentials`],
//! [`DSurfacePoint`]. Functions
//! need no second name: `ray_triangle(&ray, &tri, f64::INFINITY)` takes a
//! `DRay` and a `DTriangle`.
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
//! `n` chained roundings; so every guarantee below holds in both precisions,
//! each with its own `u`, and the test suite checks both.
//!
//! ```
//! use rayhit::{DRay, DTriangle, ray_triangle, glam::DVec3};
//! let tri = DTriangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
//! let ray = DRay::new(DVec3::new(0.25, 0.25, 1e9), -DVec3::Z);
//! assert_eq!(ray_triangle(&ray, &tri, f64::INFINITY).unwrap().t, 1e9);
//! ```
//!
//! # Batches
//!
//! For the inner loops of BVH traversal, [`PreparedRay`] carries everything
//! per ray that the box and triangle tests need, and the batch kernels test
//! one prepared ray against up to 32 shapes stored structure-of-arrays
//! ([`AabbBatch`] with [`ray_aabb_batch`], [`TriangleBatch`] with
//! [`ray_triangle_batch`]; 8 or 16 lanes are the useful sizes), returning a
//! hit mask and per-lane distances. They work on eight lanes at a time in
//! SIMD registers (SSE2 by default; AVX2 where the build or the CPU has it:
//! with `std` on x86-64 an AVX2 copy is picked at run time; NEON on
//! aarch64), in both
//! precisions, and each lane's answer is bit for bit the scalar kernel's.
//! [`with_simd`] makes that choice once for a whole traversal instead of
//! once per batch, and also uses an AVX-512 copy of the box kernels on CPUs
//! that have it.
//!
//! ```
//! use rayhit::{Aabb, AabbBatch, PreparedRay, Ray, ray_aabb_batch, glam::Vec3};
//! let boxes = [Aabb::new(Vec3::splat(1.0), Vec3::splat(2.0)), Aabb::new(Vec3::splat(-2.0), Vec3::splat(-1.0))];
//! let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
//! let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::ONE));
//! let hits = ray_aabb_batch(&ray, &batch, f32::INFINITY);
//! assert_eq!(hits.mask, 0b01);
//! assert_eq!(hits.enter[0], 1.0);
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
//! triangle test in the leaves; all the crate's box tests are conservative:
//!
//! | BVH shape | node test | leaves |
//! | --- | --- | --- |
//! | binary, boxes as [`ValidAabb`] (checked once, when built) | [`ray_aabb_prepared`] | [`ray_triangle_prepared`] |
//! | wide (4 to 16 children), boxes stored as an [`AabbBatch`] | [`ray_aabb_batch`] | [`ray_triangle_batch`] or [`ray_triangle_prepared`] |
//! | compressed wide (children quantized to bytes, Ylitie et al. 2017) | [`ray_quantized_children`] on the node as stored | the same |
//!
//! Closest hit: pass the nearest hit so far as `t_max` to both tests, so
//! that farther nodes and triangles are culled. For a compressed wide BVH,
//! the node test is conservative for the boxes the bytes describe; those
//! must contain the geometry, which [`quantize_bounds`] guarantees for a
//! builder that uses it.
//!
//! ```
//! use rayhit::glam::Vec3;
//! use rayhit::{
//!     Aabb, PreparedRay, Ray, Triangle, ValidAabb, ray_aabb_prepared, ray_triangle_prepared,
//! };
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
//!         if ray_aabb_prepared(&ray, bounds, t_max).is_none() {
//!             continue;
//!         }
//!         match &nodes[i] {
//!             Node::Inner { children, .. } => stack.extend(children),
//!             Node::Leaf { triangles: range, .. } => {
//!                 for k in range.clone() {
//!                     if let Some(hit) = ray_triangle_prepared(&ray, &triangles[k], t_max) {
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
//!   [`Instance::spawn_through`] and [`InstanceRayError::nested`] carry the
//!   bounds through the chain.
//!
//! Preconditions: the matrix is finite and not singular, and its computed
//! inverse is good to better than half (a condition number well below
//! `1 / u`; construction returns an [`InstanceError`] otherwise); every
//! bound grows with the condition number and the coordinates' magnitude.
//! What does not hold: two *different* instances meeting at a seam are not
//! watertight with each other (each sees its own rounded object ray), unless
//! their transforms are equal.
//!
//! ```
//! use rayhit::{Aabb, Instance, PreparedRay, Ray, SurfacePoint, Triangle, ray_aabb, ray_triangle_prepared, glam::{Affine3A, Quat, Vec3}};
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
//!         if let Some(hit) = ray_triangle_prepared(&object, tri, t_max) {
//!             t_max = hit.t;
//!             best = Some((copy, *tri, hit));
//!         }
//!     }
//! }
//! let (copy, tri, hit) = best.unwrap();
//! assert!((hit.t - 15.0).abs() < 1e-2);
//! let here = copy.surface_to_world(&SurfacePoint::on_triangle(&tri, &hit));
//! let bounce = copy.spawn(&here, Vec3::new(0.2, 1.0, 0.1));
//! assert!(ray_triangle_prepared(&PreparedRay::new(&copy.world_to_object(&bounce)), &tri, f32::INFINITY).is_none());
//! ```
//!
//! # Numerical guarantees
//!
//! "Exact" means what real arithmetic says about the same floating-point
//! inputs: every finite float is a rational number, and the crate's test
//! suite decides each question exactly with big rationals and holds every
//! kernel to the claims below (`tests/suite/oracle.rs`, `tests/suite/properties.rs`).
//! `u` is the unit roundoff of the precision in use.
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
//! - **Slab test** ([`ray_aabb`], [`ray_aabb_prepared`]). No false miss: if
//!   the closed box meets the ray on `[0, t_max]` exactly, the test reports
//!   it, for every input including axis-parallel rays, rays lying in a face
//!   plane, zero-thickness boxes, `-0.0` direction components and components
//!   so small that their reciprocal overflows. The reported exit is at least
//!   the exact exit. False hits only within a factor `1 + 16u` (plus four
//!   subnormals) of the boundary: the ray passes within a few ulps of an
//!   edge (`1 + 40u` where a direction component above `2^126` in `f32`,
//!   `2^1022` in `f64`, has a subnormal reciprocal).
//! - **Naive box test** ([`ray_aabb_naive`]). The reference: agrees with the
//!   slab test on hit or miss wherever the exact interval is not within
//!   `32u` (relative) of empty, with distances within two roundings; never
//!   hits where the slab test misses.
//! - **Watertight triangle test** ([`ray_triangle`]). A ray through an edge
//!   or corner shared by triangles of a mesh (bit-identical corners,
//!   consistent winding, locally a surface seen from one side) hits at least
//!   one of them. Every reported hit has `t > 0` and lies in front of the
//!   origin in exact arithmetic (all corners in front, or the numerator or
//!   `t` above its error bound). `t`, `u`, `v` are within
//!   [`ray_triangle_error_bounds`], which is finite unless the exact
//!   determinant's sign is unknown (a ray within rounding of parallel, or a
//!   sliver seen edge-on).
//! - **One-hit variant** ([`ray_triangle_one_hit`]). The same, and exactly
//!   one hit where the ray crosses such a mesh at a shared edge or corner; a
//!   closed mesh is crossed an odd number of times by a ray from strictly
//!   inside. A lone triangle's edges and corners hit only on one side of a
//!   fixed tie-break.
//! - **Intervals** ([`ray_triangle_in`], [`ray_triangle_prepared_in`],
//!   [`ray_triangle_one_hit_in`], [`ray_triangle_occluded`]). The inside
//!   tests above over an [`Interval`] `(t_min, t_max]`, with both ends
//!   decided exactly against the exact crossing `t*` (the line's crossing
//!   with the triangle's plane, from the input floats; the reported `t`
//!   itself where that is undefined, for zero-area triangles): consecutive
//!   intervals `(t0, t1]`, `(t1, t2]`, ... report each hit triangle in
//!   exactly one of them, so every hit along a ray can be walked in order
//!   with no skip and no repeat, and the one-hit form counts each crossing
//!   of a closed mesh once over the whole walk. Exact for `f32`; for `f64`
//!   under a range precondition on the coordinate differences (see
//!   [`ray_triangle_in`]). With `(0, t_max]` the hit is [`ray_triangle`]'s,
//!   bit for bit, wherever `t*` is farther than its error bound from both
//!   ends.
//! - **Plane and box intervals** ([`ray_plane_in`], [`ray_aabb_in`],
//!   [`ray_aabb_prepared_in`], [`ray_aabb_face_in`],
//!   [`ray_aabb_prepared_face_in`]). The plane's crossing `t*` decided
//!   exactly against `(t_min, t_max]`, rays within rounding of parallel
//!   included (no crossing only where `dir . normal` is exactly zero), so
//!   consecutive intervals report a plane exactly once; `t` is
//!   [`ray_plane`]'s quotient brought into the interval. The slab test over
//!   an interval: no false miss when the exact segment inside the closed
//!   box meets `[t_min, t_max]`, `t_min <= enter <= exit <= t_max`, and
//!   with `(0, t_max]` [`ray_aabb`]'s answer bit for bit. The entry face
//!   over an interval is reported only when the exact entry distance is
//!   in `(t_min, t_max]`, decided exactly: consecutive intervals report a
//!   box's entry once. Exact for `f32`; for `f64` under the range
//!   preconditions their documentation states.
//! - **Moller-Trumbore** ([`ray_triangle_mt`]). Agrees with the watertight
//!   test away from edges; not watertight (rays through shared edges can
//!   miss both triangles, and do, at a measurable rate); rejects rays whose
//!   determinant is within its own rounding error bound.
//! - **Batches** ([`ray_aabb_batch`], [`ray_triangle_batch`],
//!   [`ray_triangle_prepared`]). Bit for bit the answers of
//!   [`ray_aabb_prepared`] and [`ray_triangle`] on each lane's shape, so
//!   every guarantee above holds per lane; over an interval,
//!   [`ray_aabb_batch_in`] is [`ray_aabb_prepared_in`] on each lane's box,
//!   and [`ray_triangle_batch_in`] (with its any-hit form
//!   [`ray_triangle_batch_occluded`]) is [`ray_triangle_prepared_in`] on each
//!   lane's triangle, bit for bit.
//! - **Compressed wide nodes** ([`ray_quantized_children`],
//!   [`ray_quantized_children_in`]). Every child box is decoded rounded
//!   outward, so that it contains the exact quantized box, and tested as
//!   [`ray_aabb_batch`] (or [`ray_aabb_batch_in`]) tests it: no false
//!   miss against exact arithmetic on the quantized boxes.
//! - **Plane** ([`ray_plane`]). `t` within [`ray_plane_t_error`], always
//!   finite for a reported hit; rays within rounding of parallel (the sign
//!   of `dir . normal` not certain) are not reported.
//! - **Spawned rays** ([`offset_ray_origin`]). The offset origin lies
//!   strictly on the far side of the exact plane of the surface it leaves,
//!   given bounds on the hit point's and the normal's errors
//!   ([`triangle_hit_point`], [`Triangle::normal_with_error`],
//!   [`ray_plane_hit_point`]); a ray spawned from it in a direction not
//!   within rounding of tangent (the sign of `dir . normal` known despite
//!   its rounding and the normal's error) does not hit that surface again.
//! - **Shadow segments** ([`SurfacePoint::spawn_to`],
//!   [`SurfacePoint::spawn_to_point`]). A ray and the interval `(0, 1]`
//!   from one surface point to another (or to a point light): the exact
//!   segment crosses the start surface's plane at `t < 0` and the
//!   target's at `t > 1`, checked, not assumed (`None` where it cannot be
//!   shown: within rounding of tangent, coincident ends, no usable
//!   normal); every plane with the two points on opposite sides, farther
//!   from it than the ends' moves (about their error bounds), is crossed
//!   inside the interval.
//! - **Camera** ([`PinholeCamera`]). Unit directions within `gamma(6)`; the
//!   centre pixel of an odd-sized image looks along the view direction to a
//!   few ulps; agrees with glam's view and projection matrices.
//! - **Thin lens** ([`ThinLensCamera`]). The rays of one film point meet at
//!   its focus point exactly: `origin + dir` is the focus point in exact
//!   arithmetic and `ray.at(1)` is it bit for bit (lens samples in `[0,
//!   1]^2`, coordinates below `MAX / 8`); the focus point within `gamma(6)`
//!   of `|eye_i| + k |p_i|`'s magnitudes plus two ulps of the grid, of the
//!   exact `eye + (focal_distance / focal_length) p`; the lens centre (and
//!   a zero radius) gives the pinhole ray bit for bit.
//! - **Orthographic** ([`OrthographicCamera`]). One direction for every ray,
//!   bit for bit; each origin within `gamma(4)` of its magnitudes of the
//!   exact point of the plane through the given centre (no far position is
//!   ever added).
//! - **From matrices** ([`MatrixCamera`]). In exact arithmetic on the
//!   matrices given, a pixel's ray projects back to the pixel within the
//!   bound its documentation states (about `10 u` of the image size for a
//!   well-conditioned camera); singular (within rounding) and non-finite
//!   matrices are errors.
//! - **Panoramic** ([`EquirectangularCamera`], [`EqualAreaCamera`]). Unit
//!   directions within `4 u`; the inverse (`raster_position`) returns
//!   the raster position within a derived bound (equirectangular, in `f32`,
//!   about `w (40 u / cos(lat) + 15 u)` pixels across, growing towards the
//!   poles, and `107 u h` down; equal area `225 u` of the image size); the
//!   equal-area differentials span a pixel's solid angle, `4 pi / (width
//!   height)`.
//! - **Differentials** ([`RayDifferential`], [`triangle_hit_differentials`]).
//!   Each camera's are the derivatives of its rays, within its stated
//!   second-order term of the difference of neighbouring pixels' rays; at a
//!   triangle hit, every derivative within
//!   [`triangle_hit_differentials_error`] of the exact transfer.
//! - **Exact metamorphic identities**, bit for bit: scaling the direction or
//!   all positions by a power of two scales every `t` accordingly; mirroring
//!   an axis and translating on a coarse grid change nothing; reversing a
//!   triangle's winding swaps `u` and `v` and the side.
//!
//! Invalid input (NaN, infinities, zero direction, inverted box, NaN or
//! negative `t_max`) gives `None` or a [`CameraError`]: never a panic, never
//! a NaN or negative `t`. A camera's bad parameters are errors when it is
//! made; a NaN raster position gives a NaN ray (which every kernel
//! rejects), and positions outside the image give finite rays (each
//! camera says which). Zero-area triangles are not invalid: they can be
//! hit where rounding leaves them a sliver, which keeps meshes that close
//! T-junctions with them watertight (see [`Triangle`]).
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
//! - `exact`: the public `exact` module, exact answers to every kernel's
//!   question and verdicts on claimed answers (turns on `std`).
//! - `approx-05`: `approx`'s `AbsDiffEq`, `RelativeEq` and `UlpsEq` for the
//!   public types and triangle hits (see the `approx` module for what each
//!   comparison means).
//! - `proptest`: the public `strategies` module, the generators the
//!   crate's property tests use (aimed rays, boxes, triangles, planes), for
//!   testing your own kernels against this crate's.
//! - `arbitrary`: `arbitrary::Arbitrary` for [`Ray`], [`Aabb`], [`Plane`] and
//!   [`Triangle`] in both precisions, every coordinate a raw bit pattern (NaN,
//!   infinities, subnormals and `-0.0` included), for fuzzers.
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
// lanes, then the ray, then the shapes, then the BVH-node form and the
// batch kernels on a chosen instruction set, then surface points and
// cameras; the interop modules and `exact` on top. CONTRIBUTING.md has the
// map, file by file.
mod num;
mod simd;

mod ray;

mod aabb;
mod plane;
mod triangle;

mod quantized;
mod with_simd;

mod camera;
mod surface;

mod instance;

#[cfg(feature = "approx-05")]
#[cfg_attr(docsrs, doc(cfg(feature = "approx-05")))]
pub mod approx;
#[cfg(feature = "arbitrary")]
mod arbitrary;
#[cfg(feature = "bytemuck")]
#[cfg_attr(docsrs, doc(cfg(feature = "bytemuck")))]
pub mod bytemuck;
#[cfg(feature = "exact")]
#[cfg_attr(docsrs, doc(cfg(feature = "exact")))]
pub mod exact;
#[cfg(feature = "mint-05")]
#[cfg_attr(docsrs, doc(cfg(feature = "mint-05")))]
pub mod mint;
#[cfg(feature = "serde")]
#[cfg_attr(docsrs, doc(cfg(feature = "serde")))]
pub mod serde;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

#[cfg(test)]
mod testing;

pub use aabb::{
    Aabb, AabbBatch, AabbBatchHits, BoxFace, BoxHit, SlabBox, ValidAabb, aabb_entry_face, ray_aabb,
    ray_aabb_batch, ray_aabb_batch_in, ray_aabb_face, ray_aabb_face_in, ray_aabb_in,
    ray_aabb_naive, ray_aabb_prepared, ray_aabb_prepared_face, ray_aabb_prepared_face_in,
    ray_aabb_prepared_in,
};
pub use camera::{
    CameraError, ClipSpace, Columns, EqualAreaCamera, EquirectangularCamera, FocusPoint,
    HitDifferentials, MatrixCamera, OrthographicCamera, PinholeCamera, RayCone, RayDifferential,
    ThinLensCamera, triangle_cone_width, triangle_hit_differentials,
    triangle_hit_differentials_error,
};
pub use instance::{Instance, InstanceError, InstanceRayError};
pub use num::{Scalar, Vector};
pub use plane::{Plane, ray_plane, ray_plane_hit_point, ray_plane_in, ray_plane_t_error};
pub use quantized::{
    QuantizedChildren, quantize_bounds, ray_quantized_children, ray_quantized_children_in,
};
pub use ray::{Interval, PreparedRay, Ray};
pub use simd::TargetSimd;
#[cfg(rayhit_runtime_avx)]
pub use simd::{Avx2, Avx512};
pub use surface::{SurfacePoint, offset_ray_origin};
pub use triangle::{
    Side, Triangle, TriangleBatch, TriangleBatchHits, TriangleHit, TriangleHitError, ray_triangle,
    ray_triangle_batch, ray_triangle_batch_in, ray_triangle_batch_occluded,
    ray_triangle_error_bounds, ray_triangle_in, ray_triangle_mt, ray_triangle_occluded,
    ray_triangle_one_hit, ray_triangle_one_hit_in, ray_triangle_prepared, ray_triangle_prepared_in,
    ray_triangle_prepared_occluded, triangle_hit_point,
};
pub use with_simd::{Simd, SimdWork, with_simd};

/// `f64` names, glam-style (see the crate docs, "Precision").
mod f64_names {
    use glam::DVec3;

    /// [`Ray`](crate::Ray) in `f64`.
    pub type DRay = crate::Ray<DVec3>;
    /// [`Aabb`](crate::Aabb) in `f64`.
    pub type DAabb = crate::Aabb<DVec3>;
    /// [`ValidAabb`](crate::ValidAabb) in `f64`.
    pub type DValidAabb = crate::ValidAabb<DVec3>;
    /// [`PreparedRay`](crate::PreparedRay) in `f64`.
    pub type DPreparedRay = crate::PreparedRay<DVec3>;
    /// [`Plane`](crate::Plane) in `f64`.
    pub type DPlane = crate::Plane<DVec3>;
    /// [`Triangle`](crate::Triangle) in `f64`.
    pub type DTriangle = crate::Triangle<DVec3>;
    /// [`TriangleHit`](crate::TriangleHit) in `f64`.
    pub type DTriangleHit = crate::TriangleHit<f64>;
    /// [`TriangleHitError`](crate::TriangleHitError) in `f64`.
    pub type DTriangleHitError = crate::TriangleHitError<f64>;
    /// [`AabbBatch`](crate::AabbBatch) in `f64`.
    pub type DAabbBatch<const N: usize = 8> = crate::AabbBatch<DVec3, N>;
    /// [`TriangleBatch`](crate::TriangleBatch) in `f64`.
    pub type DTriangleBatch<const N: usize = 8> = crate::TriangleBatch<DVec3, N>;
    /// [`PinholeCamera`](crate::PinholeCamera) in `f64`.
    pub type DPinholeCamera = crate::PinholeCamera<DVec3>;
    /// [`ThinLensCamera`](crate::ThinLensCamera) in `f64`.
    pub type DThinLensCamera = crate::ThinLensCamera<DVec3>;
    /// [`OrthographicCamera`](crate::OrthographicCamera) in `f64`.
    pub type DOrthographicCamera = crate::OrthographicCamera<DVec3>;
    /// [`MatrixCamera`](crate::MatrixCamera) in `f64`.
    pub type DMatrixCamera = crate::MatrixCamera<DVec3>;
    /// [`EquirectangularCamera`](crate::EquirectangularCamera) in `f64`.
    pub type DEquirectangularCamera = crate::EquirectangularCamera<DVec3>;
    /// [`EqualAreaCamera`](crate::EqualAreaCamera) in `f64`.
    pub type DEqualAreaCamera = crate::EqualAreaCamera<DVec3>;
    /// [`RayDifferential`](crate::RayDifferential) in `f64`.
    pub type DRayDifferential = crate::RayDifferential<DVec3>;
    /// [`HitDifferentials`](crate::HitDifferentials) in `f64`.
    pub type DHitDifferentials = crate::HitDifferentials<DVec3>;
    /// [`SurfacePoint`](crate::SurfacePoint) in `f64`.
    pub type DSurfacePoint = crate::SurfacePoint<DVec3>;
    /// [`Instance`](crate::Instance) in `f64`.
    pub type DInstance = crate::Instance<DVec3>;
}
pub use f64_names::*;

/// Every type, trait and function of the crate root except the re-exported
/// `glam`, for `use rayhit::prelude::*;`.
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
/// assert!(ray_triangle(&ray, &tri, f32::INFINITY).is_some());
/// ```
pub mod prelude {
    pub use crate::{
        Aabb, AabbBatch, AabbBatchHits, BoxFace, BoxHit, CameraError, ClipSpace, Columns, DAabb,
        DAabbBatch, DEqualAreaCamera, DEquirectangularCamera, DHitDifferentials, DInstance,
        DMatrixCamera, DOrthographicCamera, DPinholeCamera, DPlane, DPreparedRay, DRay,
        DRayDifferential, DSurfacePoint, DThinLensCamera, DTriangle, DTriangleBatch, DTriangleHit,
        DTriangleHitError, DValidAabb, EqualAreaCamera, EquirectangularCamera, FocusPoint,
        HitDifferentials, Interval, MatrixCamera, OrthographicCamera, PinholeCamera, Plane,
        PreparedRay, QuantizedChildren, Ray, RayCone, RayDifferential, Scalar, Side, Simd,
        SimdWork, SlabBox, SurfacePoint, TargetSimd, ThinLensCamera, Triangle, TriangleBatch,
        TriangleBatchHits, TriangleHit, TriangleHitError, ValidAabb, Vector, aabb_entry_face,
        offset_ray_origin, quantize_bounds, ray_aabb, ray_aabb_batch, ray_aabb_batch_in,
        ray_aabb_face, ray_aabb_face_in, ray_aabb_in, ray_aabb_naive, ray_aabb_prepared,
        ray_aabb_prepared_face, ray_aabb_prepared_face_in, ray_aabb_prepared_in, ray_plane,
        ray_plane_hit_point, ray_plane_in, ray_plane_t_error, ray_quantized_children,
        ray_quantized_children_in, ray_triangle, ray_triangle_batch, ray_triangle_error_bounds,
        ray_triangle_in, ray_triangle_mt, ray_triangle_occluded, ray_triangle_one_hit,
        ray_triangle_one_hit_in, ray_triangle_prepared, ray_triangle_prepared_in,
        ray_triangle_prepared_occluded, triangle_cone_width, triangle_hit_differentials,
        triangle_hit_differentials_error, triangle_hit_point, with_simd,
    };
    #[cfg(rayhit_runtime_avx)]
    pub use crate::{Avx2, Avx512};
}

/// The README's code blocks, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
