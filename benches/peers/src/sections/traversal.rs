//! The section `traversal`: whole traversals per ray, rayhit's kernels
//! called the way a renderer author first writes them (plain calls on a
//! `PreparedRay`) against obvhs's own traversals with its own tests, on
//! the same trees: obvhs's compressed wide BVH (`rayhit_peers::cwbvh`) and
//! its binary BVH (`rayhit_peers::traversal`).
//!
//! Rows, per mesh and workload (time per ray; 1000 / ns is Mrays/s):
//!
//! - `rayhit CWBVH, plain calls`: obvhs's CWBVH in obvhs's order
//!   (`traverse!`), the node test `QuantizedChildren::clip` on the prepared
//!   ray, `Triangle::hit` in the leaves; on `shadow`, an any-hit walk of
//!   the same nodes written here (`Scene::rayhit_occluded_with`: children
//!   in stored order, `QuantizedChildren::meets`, `Triangle::occluded`);
//!   no `with_simd` anywhere;
//! - `rayhit CWBVH, with_simd`: the same traversal with the node test on
//!   the instruction set `with_simd` chose once for the whole pass;
//! - `obvhs CwBvh, its own tests`: `CwBvh::ray_traverse` (closest) or
//!   `ray_traverse_miss` (any hit) with obvhs's triangle test;
//! - `rayhit BVH2, plain calls`: obvhs's binary BVH walked by the stack
//!   traversals of `rayhit_peers::traversal`: nearer first with
//!   `ValidAabb::clip` and `Triangle::hit`, or, on `shadow`, any hit with
//!   `ValidAabb::meets` and `Triangle::occluded`;
//! - [`BVH2_FLOOR`]: the same walk with the box test's floor
//!   (`floors::floor_box_enter`, inlined);
//! - `obvhs Bvh2, its own tests`: `Bvh2::ray_traverse` or
//!   `ray_traverse_miss` with obvhs's triangle test;
//! - on the closest-hit workloads, [`LEAF_FLOORS`]: rayhit's two
//!   traversals with the textbook watertight test (no guarantee's checks)
//!   or obvhs's triangle test in the leaves, which separate the triangle
//!   test's cost from the walk's;
//! - on the shadow workloads only, [`OFFSET`]: rayhit's two plain-call
//!   traversals over obvhs's offset segments, which separates the cost of
//!   the epsilon-free start from the kernels'.
//!
//! Workloads: `camera` (128 x 128 pinhole rays in scanline order),
//! `incoherent` (as many rays between random points around the mesh and
//! in its box), `inside` (secondary rays from inside the solid in random
//! directions, from the interior points of `LeakRays::inside`), `inside,
//! aimed at vertices and edges` (`LeakRays::inside` itself: every ray
//! through a vertex or an edge midpoint exactly, the leak test's rays,
//! where every hit is on an edge), `shadow` (any-hit segments from
//! the camera rays' hits to a point light: rayhit's epsilon-free
//! `spawn_to_point` segment over its interval for rayhit's rows, the
//! `point + 1e-4 n`, `t_max = 1 - 1e-4` segment for obvhs's), and
//! `shadow, lit side` (those of them with the light on the eye's side of
//! the surface: the ones a renderer traces for an opaque surface). The
//! agreement column is hit or miss (occluded or not on `shadow`) against
//! `rayhit CWBVH, plain calls`; the counts are printed after the table
//! ([`print_counts`]), and `--traversal-leaks` prints the leak table.

use rayhit::batch::{InPlace, Simd, SimdWork, with_simd};
use rayhit::glam::Vec3A;
use rayhit::{Bounds, Interval, PreparedRay, Ray, RayForm, ValidAabb};
use rayhit_peers::cwbvh::{self, LeakRays, Mesh, count_leaks};
use rayhit_peers::traversal::{
    Bvh2Scene, EPS, Reach, ShadowRays, camera_rays, inside_random_rays, ob_hit, ob_ray, random_rays,
};

use crate::floors::{FloorBoxRay, FloorRay, floor_box_enter, floor_watertight_prepared};
use crate::harness::loops::agree;
use crate::harness::{Kernel, kernel};
use crate::sections::cwbvh::print_leak_row;

/// The section's name in the table.
pub const SECTION: &str = "traversal";

/// The rows' names, in the table's order: rayhit's CWBVH rows, obvhs's
/// CWBVH, rayhit's binary BVH, obvhs's binary BVH.
pub const ROWS: [&str; 5] = [
    "rayhit CWBVH, plain calls",
    "rayhit CWBVH, with_simd",
    "obvhs CwBvh, its own tests",
    "rayhit BVH2, plain calls",
    "obvhs Bvh2, its own tests",
];

/// The floor row of a plain call per node (`cwbvh::NodeFloor`): the
/// CWBVH traversal of the first row with the node passed to an AVX-512
/// function by one reference, rayhit's node test inlined there.
pub const FLOOR: &str =
    "floor: CWBVH, a call per node into the AVX-512 node test, the node by reference";

/// The floor row of the binary BVH's box test: the traversal of `rayhit
/// BVH2, plain calls` with `floors::floor_box_enter` (the textbook slab
/// test and the exit's widening, inlined) in place of `ValidAabb::clip`.
pub const BVH2_FLOOR: &str = "floor: BVH2, the same walk, a slab test with only the widening";

/// The floor rows of the leaves' test, on the closest-hit workloads: the
/// traversals of `rayhit CWBVH, plain calls` and `rayhit BVH2, plain
/// calls` with, in the leaves, the textbook watertight test on a ray
/// prepared once (`floors::floor_watertight_prepared` without its checks:
/// no exact sign, no conservative `t > 0`) and obvhs's own triangle test
/// (not watertight). Against the plain rows, they separate the triangle
/// test's cost from the walk's and the node test's.
pub const LEAF_FLOORS: [&str; 4] = [
    "floor: CWBVH, the same traversal, the textbook watertight test in the leaves",
    "floor: CWBVH, the same traversal, obvhs's triangle test in the leaves",
    "floor: BVH2, the same walk, the textbook watertight test in the leaves",
    "floor: BVH2, the same walk, obvhs's triangle test in the leaves",
];

/// The distance, as a fraction of the mesh's size (its box's diagonal),
/// within which [`print_counts`] counts an offset segment's first hit as
/// the surface it leaves.
const NEAR: f32 = 1e-3;

/// The rows of `shadow` that trace obvhs's segments (origin `point + EPS
/// n`, over `(0, 1 - EPS]`) with rayhit's plain-call traversals: the
/// kernels' cost on the same segments as obvhs's rows, without the
/// epsilon-free start.
pub const OFFSET: [&str; 2] = [
    "rayhit CWBVH, plain calls, obvhs's offset segments",
    "rayhit BVH2, plain calls, obvhs's offset segments",
];

/// One ray set: rayhit's rays (prepared, with the direction obvhs's order
/// reads), their intervals on `shadow`, and obvhs's rays.
struct Workload {
    /// `camera`, `incoherent`, `inside`, `inside, aimed ...`, `shadow` or
    /// `shadow, lit side`.
    name: &'static str,
    /// rayhit's rays, prepared, with their directions.
    rays: Vec<(PreparedRay, Vec3A)>,
    /// Empty for the closest-hit sets; on `shadow`, each ray's segment.
    segments: Vec<Interval<f32>>,
    /// obvhs's rays (on `shadow`, the offset segments over `(0, 1 - EPS]`).
    ob: Vec<obvhs::ray::Ray>,
    /// Shadow hit points without a segment (counted as blocked).
    grazing: usize,
    /// On the shadow sets: of the segments with the light behind the
    /// surface, how many there are, and how many obvhs's offset segments
    /// have their first hit within `NEAR` of the mesh's size from their
    /// start (the surface they leave, crossed again: the origin `point +
    /// EPS n` is on the eye's side, the light on the other).
    unlit: (usize, usize),
    /// The rays as the binary BVH's floor row reads them.
    floor: Vec<FloorBoxRay>,
    /// The rays as the textbook watertight floor reads them.
    watertight: Vec<FloorRay>,
    /// Empty but on `shadow`: obvhs's offset segments as rayhit's rays,
    /// each over `(0, 1 - EPS]`.
    offset: Vec<PreparedRay>,
}

/// One mesh's trees and ray sets, and each row's answer per ray (hit or
/// occluded), for the agreement column and the counts.
pub struct TraversalData {
    /// The mesh's name.
    name: &'static str,
    /// The mesh's triangle count.
    triangles: usize,
    /// obvhs's CWBVH as built, for obvhs's traversal.
    obvhs: cwbvh::Scene,
    /// The same with the child boxes rayhit's decoding does not contain
    /// re-quantized (`Scene::check_quantization`), for rayhit's.
    fixed: cwbvh::Scene,
    /// obvhs's binary BVH, for both binary rows.
    bvh2: Bvh2Scene,
    /// The closest-hit workloads, then the two shadow sets.
    workloads: Vec<Workload>,
    /// Per workload, per row of [`ROWS`], per ray: hit (or occluded).
    answers: Vec<[Vec<bool>; 5]>,
}

/// One ray of a workload through rayhit's CWBVH traversal, the node test
/// on `node_ray`: the closest hit's `t` bits, or 1 where occluded.
#[inline(always)]
fn cw_one(s: &cwbvh::Scene, w: &Workload, i: usize, node_ray: &impl RayForm) -> u64 {
    if w.segments.is_empty() {
        cw_one_of::<false>(s, w, i, node_ray)
    } else {
        cw_one_of::<true>(s, w, i, node_ray)
    }
}

/// [`cw_one`] for a workload known to be `SHADOW` or not, so that a timed
/// loop holds one traversal, closest or any hit, as a renderer's does
/// (with both in one loop, the compiler's choices for the pair made the
/// closest-hit rows by plain calls up to twice as slow as the same
/// traversal on its own).
#[inline(always)]
fn cw_one_of<const SHADOW: bool>(
    s: &cwbvh::Scene,
    w: &Workload,
    i: usize,
    node_ray: &impl RayForm,
) -> u64 {
    let (p, d) = &w.rays[i];
    if SHADOW {
        u64::from(s.rayhit_occluded_on(node_ray, p, w.segments[i]))
    } else {
        u64::from(s.rayhit_closest_on(node_ray, p, *d).to_bits())
    }
}

/// The wrapping sum of `f` over `0..n`: a row's checksum over its rays.
fn sum(n: usize, f: impl Fn(usize) -> u64) -> u64 {
    (0..n).map(f).fold(0, u64::wrapping_add)
}

/// A workload through rayhit's CWBVH with the node test on the
/// instruction set `with_simd` picks once for the pass; any hit where
/// `SHADOW`, else closest hit.
#[derive(Clone, Copy)]
struct CwSimd<'a, const SHADOW: bool>(&'a cwbvh::Scene, &'a Workload);

impl<const SHADOW: bool> SimdWork for CwSimd<'_, SHADOW> {
    type Output = u64;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> u64 {
        let CwSimd(s, w) = self;
        sum(w.rays.len(), |i| {
            cw_one_of::<SHADOW>(s, w, i, &simd.ray(&w.rays[i].0))
        })
    }
}

/// As [`CwSimd`], each ray's answer.
#[derive(Clone, Copy)]
struct CwSimdEach<'a>(&'a cwbvh::Scene, &'a Workload);

impl SimdWork for CwSimdEach<'_> {
    type Output = Vec<u64>;
    fn run<I: Simd>(self, simd: I) -> Vec<u64> {
        let CwSimdEach(s, w) = self;
        (0..w.rays.len())
            .map(|i| cw_one(s, w, i, &simd.ray(&w.rays[i].0)))
            .collect()
    }
}

impl TraversalData {
    /// Builds the trees and the ray sets, and runs every row once for its
    /// answers.
    pub fn new(mesh: &Mesh) -> Self {
        let obvhs = cwbvh::Scene::new(mesh);
        let mut fixed = cwbvh::Scene::new(mesh);
        fixed.check_quantization(true);
        let bvh2 = Bvh2Scene::new(mesh);
        let camera = camera_rays(mesh, 128);
        let closest = |name, rays: &[Ray]| Workload {
            name,
            rays: rays
                .iter()
                .map(|r| (PreparedRay::new(r), r.dir.into()))
                .collect(),
            segments: Vec::new(),
            ob: rays.iter().map(|r| ob_ray(r, f32::INFINITY)).collect(),
            grazing: 0,
            unlit: (0, 0),
            floor: rays.iter().map(FloorBoxRay::new).collect(),
            watertight: rays.iter().map(FloorRay::new).collect(),
            offset: Vec::new(),
        };
        let shadow = ShadowRays::new(&bvh2, mesh, &camera);
        let aimed = LeakRays::new(mesh, 4096, 7).inside;
        let mut workloads = vec![
            closest("camera", &camera),
            closest("incoherent", &random_rays(mesh, camera.len(), 11)),
            closest("inside", &inside_random_rays(&aimed, 13)),
            closest("inside, aimed at vertices and edges", &aimed),
        ];
        // Every segment, and those a renderer traces for an opaque
        // surface (the light on the eye's side).
        let (lo, hi) = mesh.bounds();
        let near = NEAR * (hi - lo).length();
        let segments = |name, keep: &dyn Fn(usize) -> bool, grazing| {
            let kept: Vec<usize> = (0..shadow.rayhit.len()).filter(|&i| keep(i)).collect();
            let rayhit = || kept.iter().map(|&i| &shadow.rayhit[i]);
            let eps = || kept.iter().map(|&i| &shadow.eps[i]);
            let unlit: Vec<&Ray> = kept
                .iter()
                .filter(|&&i| !shadow.lit[i])
                .map(|&i| &shadow.eps[i])
                .collect();
            let first_hit = |r: &Ray| bvh2.obvhs_closest(&ob_ray(r, 1.0 - EPS)) * r.dir.length();
            Workload {
                unlit: (
                    unlit.len(),
                    unlit.iter().filter(|r| first_hit(r) < near).count(),
                ),
                name,
                rays: rayhit()
                    .map(|(r, _)| (PreparedRay::new(r), r.dir.into()))
                    .collect(),
                segments: rayhit().map(|&(_, s)| s).collect(),
                ob: eps().map(|r| ob_ray(r, 1.0 - EPS)).collect(),
                grazing,
                floor: rayhit().map(|(r, _)| FloorBoxRay::new(r)).collect(),
                watertight: Vec::new(),
                offset: eps().map(PreparedRay::new).collect(),
            }
        };
        workloads.push(segments("shadow", &|_| true, shadow.grazing));
        workloads.push(segments("shadow, lit side", &|i| shadow.lit[i], 0));
        let mut d = TraversalData {
            name: mesh.name,
            triangles: mesh.faces.len(),
            obvhs,
            fixed,
            bvh2,
            workloads,
            answers: Vec::new(),
        };
        d.answers = (0..d.workloads.len())
            .map(|k| std::array::from_fn(|row| d.answers_of(k, row)))
            .collect();
        d
    }

    /// Row `row`'s answer per ray of workload `k`: hit (closest) or
    /// occluded (shadow).
    fn answers_of(&self, k: usize, row: usize) -> Vec<bool> {
        let w = &self.workloads[k];
        let shadow = !w.segments.is_empty();
        let hit = |x: u64| {
            if shadow {
                x == 1
            } else {
                x != f32::INFINITY.to_bits().into()
            }
        };
        let simd = if row == 1 {
            with_simd(CwSimdEach(&self.fixed, w))
        } else {
            Vec::new()
        };
        (0..w.rays.len())
            .map(|i| {
                let (p, _) = &w.rays[i];
                match row {
                    0 => hit(cw_one(&self.fixed, w, i, p)),
                    1 => hit(simd[i]),
                    2 if shadow => self.obvhs.obvhs_occluded(&w.ob[i]),
                    2 => self.obvhs.obvhs_closest_ob(&w.ob[i]) < f32::INFINITY,
                    3 if shadow => self.bvh2.rayhit_occluded(p, w.segments[i]),
                    3 => self.bvh2.rayhit_closest(p).is_some(),
                    _ if shadow => self.bvh2.obvhs_occluded(&w.ob[i]),
                    _ => self.bvh2.obvhs_closest(&w.ob[i]) < f32::INFINITY,
                }
            })
            .collect()
    }
}

/// The section's rows for one mesh: every workload, every row of
/// [`ROWS`].
pub fn traversal_kernels<'a>(d: &'a TraversalData, out: &mut Vec<Kernel<'a>>) {
    for (k, w) in d.workloads.iter().enumerate() {
        let name = format!("{}, {}", d.name, w.name);
        let n = w.rays.len();
        let ours = &d.answers[k][0];
        let agreement = |row: usize| {
            Some(agree(
                ours.iter().copied(),
                d.answers[k][row].iter().copied(),
            ))
        };
        let shadow = !w.segments.is_empty();
        let (fixed, bvh2, obvhs) = (&d.fixed, &d.bvh2, &d.obvhs);
        out.push(one_of(
            (&name, n, shadow),
            ROWS[0],
            None,
            move |i| cw_one_of::<false>(fixed, w, i, &w.rays[i].0),
            move |i| cw_one_of::<true>(fixed, w, i, &w.rays[i].0),
        ));
        out.push(if shadow {
            kernel(SECTION, ROWS[1], &name, n, None, move || {
                with_simd(CwSimd::<true>(fixed, w))
            })
        } else {
            kernel(SECTION, ROWS[1], &name, n, None, move || {
                with_simd(CwSimd::<false>(fixed, w))
            })
        });
        #[cfg(target_arch = "x86_64")]
        if let Some(floor) = cwbvh::NodeFloor::detect() {
            let closest = move |i: usize| {
                let (p, d) = &w.rays[i];
                let t = fixed.rayhit_closest_with(p, *d, |node, t| floor.meets(node, p, t));
                u64::from(t.to_bits())
            };
            let occluded = move |i: usize| {
                let ((p, _), seg) = (&w.rays[i], w.segments[i]);
                u64::from(fixed.rayhit_occluded_with(p, seg, |node| floor.meets(node, p, seg)))
            };
            let floor_agrees = agree(
                ours.iter().copied(),
                (0..n).map(|i| {
                    if shadow {
                        occluded(i) == 1
                    } else {
                        closest(i) != u64::from(f32::INFINITY.to_bits())
                    }
                }),
            );
            out.push(one_of(
                (&name, n, shadow),
                FLOOR,
                Some(floor_agrees),
                closest,
                occluded,
            ));
        }
        out.push(one_of(
            (&name, n, shadow),
            ROWS[2],
            agreement(2),
            move |i| u64::from(obvhs.obvhs_closest_ob(&w.ob[i]).to_bits()),
            move |i| u64::from(obvhs.obvhs_occluded(&w.ob[i])),
        ));
        out.push(one_of(
            (&name, n, shadow),
            ROWS[3],
            agreement(3),
            move |i| {
                bvh2.rayhit_closest(&w.rays[i].0)
                    .map_or(u64::MAX, |(_, h)| u64::from(h.t.to_bits()))
            },
            move |i| u64::from(bvh2.rayhit_occluded(&w.rays[i].0, w.segments[i])),
        ));
        let enter = move |i: usize, b: &ValidAabb, r: Reach| {
            floor_box_enter(&w.floor[i], b.aabb(), r.lo, r.hi)
        };
        let floor_closest = move |i: usize| {
            bvh2.closest_with(&w.rays[i].0, |b, r| enter(i, b, r))
                .map_or(u64::MAX, |(_, h)| u64::from(h.t.to_bits()))
        };
        let floor_occluded = move |i: usize| {
            let meets = |b: &ValidAabb, r: Reach| enter(i, b, r).is_some();
            u64::from(bvh2.occluded_with(&w.rays[i].0, w.segments[i], meets))
        };
        let floor_agrees = agree(
            d.answers[k][3].iter().copied(),
            (0..n).map(|i| {
                if shadow {
                    floor_occluded(i) == 1
                } else {
                    floor_closest(i) != u64::MAX
                }
            }),
        );
        out.push(one_of(
            (&name, n, shadow),
            BVH2_FLOOR,
            Some(floor_agrees),
            floor_closest,
            floor_occluded,
        ));
        if !shadow {
            leaf_floors(d, k, &name, out);
        }
        if shadow {
            // rayhit's kernels on obvhs's segments: what the epsilon-free
            // start costs, apart from the kernels.
            let offset = Interval::new(0.0, 1.0 - EPS).expect("0 < 1 - EPS");
            let on = |i: usize| &w.offset[i];
            out.push(kernel(SECTION, OFFSET[0], &name, n, None, move || {
                sum(n, |i| {
                    u64::from(fixed.rayhit_occluded_on(on(i), on(i), offset))
                })
            }));
            out.push(kernel(SECTION, OFFSET[1], &name, n, None, move || {
                sum(n, |i| u64::from(bvh2.rayhit_occluded(on(i), offset)))
            }));
        }
        out.push(one_of(
            (&name, n, shadow),
            ROWS[4],
            agreement(4),
            move |i| u64::from(bvh2.obvhs_closest(&w.ob[i]).to_bits()),
            move |i| u64::from(bvh2.obvhs_occluded(&w.ob[i])),
        ));
    }
}

/// The rows of [`LEAF_FLOORS`] on the closest-hit workload `k`, each
/// with its agreement (hit or miss) against `rayhit CWBVH, plain calls`.
fn leaf_floors<'a>(d: &'a TraversalData, k: usize, name: &str, out: &mut Vec<Kernel<'a>>) {
    let w = &d.workloads[k];
    let n = w.rays.len();
    let (fixed, bvh2) = (&d.fixed, &d.bvh2);
    let watertight = move |i: usize, t: &rayhit::Triangle, t_max: f32| {
        floor_watertight_prepared::<false>(&w.watertight[i], t, t_max).map(|(t, _)| t)
    };
    let meets = move |i: usize| {
        #[inline(always)]
        move |node: &_, t: f32| InPlace(|| cwbvh::children(node)).meets(&w.rays[i].0, t)
    };
    let agreement = |closest: &dyn Fn(usize) -> f32| {
        agree(
            d.answers[k][0].iter().copied(),
            (0..n).map(|i| closest(i) != f32::INFINITY),
        )
    };
    let cw_watertight = move |i: usize| {
        fixed.closest_by(
            w.rays[i].1,
            meets(i),
            #[inline(always)]
            |j, t_max| watertight(i, &fixed.tris[j], t_max),
        )
    };
    let cw_obvhs = move |i: usize| {
        fixed.closest_by(
            w.rays[i].1,
            meets(i),
            #[inline(always)]
            |j, t_max| ob_hit(&fixed.ob_tris[j], &w.ob[i], t_max),
        )
    };
    let bvh2_watertight = move |i: usize| {
        bvh2.closest_by(
            &w.rays[i].0,
            #[inline(always)]
            |t, _, t_max| watertight(i, t, t_max),
        )
    };
    let bvh2_obvhs = move |i: usize| {
        bvh2.closest_by(
            &w.rays[i].0,
            #[inline(always)]
            |_, j, t_max| bvh2.obvhs_triangle(j, &w.ob[i], t_max),
        )
    };
    let rows = [
        agreement(&cw_watertight),
        agreement(&cw_obvhs),
        agreement(&bvh2_watertight),
        agreement(&bvh2_obvhs),
    ];
    let row = |r: usize| (name, n, LEAF_FLOORS[r], rows[r]);
    out.push(floor_row(row(0), cw_watertight));
    out.push(floor_row(row(1), cw_obvhs));
    out.push(floor_row(row(2), bvh2_watertight));
    out.push(floor_row(row(3), bvh2_obvhs));
}

/// A timed row of closest hits `closest` (each ray's `t`, infinite for
/// none) over `n` rays, with its agreement.
fn floor_row<'a>(
    (name, n, label, agreement): (&str, usize, &str, f64),
    closest: impl Fn(usize) -> f32 + 'a,
) -> Kernel<'a> {
    kernel(SECTION, label, name, n, Some(agreement), move || {
        sum(n, |i| u64::from(closest(i).to_bits()))
    })
}

/// A row of the section on workload `name` of `n` rays: `occluded` over
/// every ray on `shadow`, else `closest`. Only the one chosen goes into
/// the timed closure, so that each row's timed code is one traversal
/// loop, as a renderer's is (see [`cw_one_of`]).
fn one_of<'a>(
    (name, n, shadow): (&str, usize, bool),
    label: &str,
    agreement: Option<f64>,
    closest: impl Fn(usize) -> u64 + 'a,
    occluded: impl Fn(usize) -> u64 + 'a,
) -> Kernel<'a> {
    if shadow {
        kernel(SECTION, label, name, n, agreement, move || {
            sum(n, &occluded)
        })
    } else {
        kernel(SECTION, label, name, n, agreement, move || sum(n, &closest))
    }
}

/// After the table: per mesh and workload, how many rays each row saw hit
/// (on `inside`, also how many hit nothing: each one a leak; on `shadow`,
/// how many segments were occluded).
pub fn print_counts(data: &[TraversalData]) {
    println!();
    println!(
        "Traversal counts (hits, or occluded segments on `shadow`; on `inside` every miss is a ray that leaked out of a closed mesh):"
    );
    println!();
    print!("| mesh | triangles | workload | rays |");
    for r in ROWS {
        print!(" {r} |");
    }
    println!();
    println!(
        "| --- | ---: | --- | ---: |{}",
        " ---: |".repeat(ROWS.len())
    );
    for d in data {
        for (w, answers) in d.workloads.iter().zip(&d.answers) {
            print!(
                "| {} | {} | {} | {} |",
                d.name,
                d.triangles,
                w.name,
                w.rays.len()
            );
            for a in answers {
                let hits = a.iter().filter(|&&h| h).count();
                if w.name.starts_with("inside") {
                    print!(" {hits} ({} missed) |", a.len() - hits);
                } else {
                    print!(" {hits} |");
                }
            }
            println!();
            if w.grazing > 0 {
                println!(
                    "| | | ({} hit points had no rayhit segment: light within rounding of the plane) | | | | | | |",
                    w.grazing
                );
            }
        }
    }
    println!();
    println!(
        "Shadow segments with the light behind the surface (all occluded on a closed mesh), and how many of obvhs's offset segments among them have their first hit within {NEAR} of the mesh's size from their start: the surface they leave, crossed again."
    );
    println!();
    println!(
        "| mesh | workload | light behind the surface | obvhs's segment blocked next to its start |"
    );
    println!("| --- | --- | ---: | ---: |");
    for d in data {
        for w in d.workloads.iter().filter(|w| w.unlit.0 > 0) {
            println!(
                "| {} | {} | {} | {} |",
                d.name, w.name, w.unlit.0, w.unlit.1
            );
        }
    }
}

/// `--traversal-leaks`: per mesh, `count` rays from inside and from
/// outside aimed exactly at vertices and edge midpoints, through every
/// row's pipeline: how many inside rays hit nothing, and how many outside
/// rays passed their target.
pub fn print_traversal_leaks(meshes: &[&Mesh], count: usize) {
    println!(
        "| mesh | triangles | rays from inside | rays from outside | pipeline | inside rays that hit nothing | outside rays past their target |"
    );
    println!("| --- | ---: | ---: | ---: | --- | ---: | ---: |");
    for mesh in meshes {
        let rays = LeakRays::new(mesh, count, 7);
        let obvhs = cwbvh::Scene::new(mesh);
        let mut fixed = cwbvh::Scene::new(mesh);
        fixed.check_quantization(true);
        let bvh2 = Bvh2Scene::new(mesh);
        let row = |name: &str, closest: &dyn Fn(&Ray) -> f32| {
            print_leak_row(mesh, &rays, name, count_leaks(&rays, closest));
        };
        row(ROWS[0], &|r| {
            let p = PreparedRay::new(r);
            fixed.rayhit_closest_on(&p, &p, r.dir.into())
        });
        row(ROWS[1], &|r| cwbvh::rayhit_one(&fixed, r));
        row(ROWS[2], &|r| obvhs.obvhs_closest(r));
        row(ROWS[3], &|r| {
            bvh2.rayhit_closest(&PreparedRay::new(r))
                .map_or(f32::INFINITY, |(_, h)| h.t)
        });
        row(ROWS[4], &|r| bvh2.obvhs_closest(&ob_ray(r, f32::INFINITY)));
    }
}
