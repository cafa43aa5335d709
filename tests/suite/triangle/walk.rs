//! Every hit along a ray, in order, from a sequence of interval calls, on
//! closed meshes: no skip, no repeat, and with the one-hit rule each
//! crossing of the surface once, against exact arithmetic.
//!
//! The meshes: the test kit's icosphere (convex) and torus (not convex),
//! an octahedron with a T-junction (one face split at the midpoint of an
//! edge, the crack closed by the zero-area triangle between the edge and
//! its halves), and a stack of three thin boxes (which rounding lays on
//! top of each other far away and small), each scaled by 1e-3 to 1e3 and
//! translated by up to 1e5 in the precision under test (shared corners
//! stay bit-identical). Rays start outside and are aimed at a corner, an
//! edge midpoint, a face point or the middle of the mesh.
//!
//! The sequence is collected in windows: [`Walk`]'s (from the nearest hit
//! of the rest, its `t` and error bound from `Triangle::hit_error`; every
//! hit of the window reported, sorted by `t`). This runs with
//! `Triangle::hit` over the interval on a `PreparedRay` (closed) and with
//! `EdgeRule::OneHit`; and again with tight windows, ending at the
//! nearest hit's `t` itself, so that window ends fall right at crossings
//! (the nearest triangle's `t*` is on either side of its rounded `t`;
//! where that window is empty, the walk's is taken). Checked:
//!
//! - no repeat: no triangle is reported twice;
//! - no skip: the triangles reported are those the same test reports over
//!   `(0, inf]` in one call;
//! - each reported triangle's exact crossing `t*` (exact arithmetic on the
//!   same floats, `rayhit::exact`) lies in the window it was reported in,
//!   so the windows are in exact order;
//! - against the exact crossings: every triangle whose hit or miss the
//!   exact module says is clear of the watertight tests' rounding
//!   (`triangle_clear_watertight`: the tests compared here are all
//!   watertight, so Moller-Trumbore's band is not added) is reported by
//!   the closed sequence exactly when the exact ray crosses it; the
//!   one-hit sequence reports exactly the triangles that the ray, moved
//!   off the edge lines as the rule says, crosses at `t* > 0`
//!   (`oracle::one_hit_line_hits`), so no crossing is reported twice
//!   where the placed mesh is still a surface without overlaps (at one
//!   exact `t*`, the fronts and backs alternate, as the crossings of a
//!   closed surface do: the tally's `one_hit_doubles`, against the closed
//!   rule's `closed_doubles`, its extra reports of one crossing through
//!   shared edges and corners); on rays
//!   where every triangle is clear, the one-hit count is the exact number
//!   of crossings; and on a convex mesh, a line that the exact module
//!   finds meeting it at two points, in at one and out at the other
//!   (through edges and corners included), has a one-hit count of
//!   exactly 2.
//!
//! The exact crossing of each triangle whose box the ray hits is computed
//! once per ray, for the answer, the verdict and the windows. Where
//! `surely_outside_watertight_filter` finds in floating point that the ray
//! passes the triangle by more than the test's rounding, it is a clear
//! miss (and the exact line must miss it), with no verdict to compute.
//!
//! 80 rays per mesh and precision (well under a second), times
//! `RAYHIT_CASES`; the counts and the time print with `--nocapture`. The
//! long run, about 1.36 million rays per precision (340,000 per mesh),
//! each on as many threads as `std::thread::available_parallelism` gives
//! (the two precisions run at once), took 5.8 minutes on 2 shared cores
//! (f32 253 s and f64 347 s, at once):
//!
//! ```sh
//! cargo test --release --test suite triangle::walk:: -- --ignored --nocapture
//! ```

use rayhit::exact::{self, oracle};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, EdgeRule, Intersect, Interval, PreparedRay, Ray, Scalar, Surface, Triangle, TriangleHit,
    Vector, Walk, ray_aabb,
};
use rayhit_testkit::mesh::{self, Mesh};
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// Rays per mesh and precision: 80 times `RAYHIT_CASES`.
fn rays() -> usize {
    rayhit_testkit::case_count(80)
}

/// An octahedron of radius 2 with a T-junction: the face `px, py, pz` is
/// split at `m`, the midpoint of `px, py`, and the filler `px, py, m`
/// (zero area) closes the edge against the whole face `py, px, nz`.
fn t_junction_octahedron() -> Mesh {
    let positions = vec![
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::new(-2.0, 0.0, 0.0),
        Vec3::new(0.0, -2.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::new(1.0, 1.0, 0.0),
    ];
    let (px, py, pz, nx, ny, nz, m) = (0, 1, 2, 3, 4, 5, 6);
    let indices = vec![
        [px, m, pz],
        [m, py, pz],
        [px, py, m],
        [py, nx, pz],
        [nx, ny, pz],
        [ny, px, pz],
        [py, px, nz],
        [nx, py, nz],
        [ny, nx, nz],
        [px, ny, nz],
    ];
    Mesh {
        positions,
        normals: Vec::new(),
        indices,
    }
}

/// Three thin boxes stacked along `z` (2 by 2 by 0.02, 0.2 apart), each
/// closed and wound outwards: far away and small, rounding collapses
/// their faces onto one plane.
fn thin_stack() -> Mesh {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for z in [-0.5, -0.1, 0.3] {
        let base = positions.len() as u32;
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..2 {
                    let c = |n: u32| if n == 0 { -1.0 } else { 1.0 };
                    positions.push(Vec3::new(c(i), c(j), z + 0.02 * k as f32));
                }
            }
        }
        // Corner `v(i, j, k)` is `base + i + 2j + 4k`.
        let v = |i: u32, j: u32, k: u32| base + i + 2 * j + 4 * k;
        let faces = [
            [v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)],
            [v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)],
            [v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)],
            [v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0)],
            [v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)],
            [v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)],
        ];
        for [a, b, c, d] in faces {
            indices.push([a, b, c]);
            indices.push([a, c, d]);
        }
    }
    Mesh {
        positions,
        normals: Vec::new(),
        indices,
    }
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    vec![
        ("icosphere", mesh::icosphere(Vec3::ZERO, 1.0, 1)),
        ("torus", mesh::torus(1.0, 0.4, 10, 6)),
        ("t-junction octahedron", t_junction_octahedron()),
        ("thin stack", thin_stack()),
    ]
}

fn f<V: Vector>(x: f64) -> S<V> {
    S::<V>::from_f64(x)
}

fn signed(rng: &mut Pcg32) -> f64 {
    f64::from(rng.next_u32()) / f64::from(u32::MAX) * 2.0 - 1.0
}

/// The mesh's triangles in precision `V`, scaled and translated per vertex.
fn placed<V: Vector>(m: &Mesh, scale: f64, offset: [f64; 3]) -> Vec<Triangle<V>> {
    let p: Vec<V> = m
        .positions
        .iter()
        .map(|p| {
            let c = |x: f32, o: f64| f::<V>(o) + f::<V>(f64::from(x)) * f::<V>(scale);
            V::new(c(p.x, offset[0]), c(p.y, offset[1]), c(p.z, offset[2]))
        })
        .collect();
    m.indices
        .iter()
        .map(|t| Triangle::new(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]))
        .collect()
}

/// A reported hit: its window, the triangle's index, and `t`.
type Reported<V> = (Interval<S<V>>, usize, S<V>);

type Kernel<V> = fn(&Ray<V>, &Triangle<V>, Interval<S<V>>) -> Option<TriangleHit<S<V>>>;

/// The hits of the window loop: (window, triangle, t). With `margin`, the
/// windows are [`Walk`]'s; without, each ends right at the nearest hit's
/// `t` (where that window holds it: its `t*` may be above), set by hand,
/// and the walk restarts after it.
fn windows<V: Vector>(
    ray: &Ray<V>,
    tris: &[Triangle<V>],
    kernel: Kernel<V>,
    margin: bool,
) -> (Vec<Reported<V>>, usize) {
    let inf = S::<V>::INFINITY;
    let mut walk = Walk::new(Interval::up_to(inf).unwrap());
    let mut out = Vec::new();
    let mut count = 0;
    let in_window = |window: Interval<S<V>>| -> Vec<(S<V>, usize)> {
        tris.iter()
            .enumerate()
            .filter_map(|(i, tri)| kernel(ray, tri, window).map(|h| (h.t, i)))
            .collect()
    };
    while let Some(rest) = walk.rest() {
        count += 1;
        assert!(
            count <= 2 * tris.len() + 2,
            "the windows do not advance: {ray:?}"
        );
        let nearest = tris
            .iter()
            .filter_map(|tri| kernel(ray, tri, rest).map(|h| (h, tri)))
            .min_by(|a, b| a.0.t.partial_cmp(&b.0.t).unwrap());
        let Some((hit, tri)) = nearest else { break };
        let tight = Interval::new(rest.min(), hit.t).unwrap();
        let found = if margin { Vec::new() } else { in_window(tight) };
        let (window, found) = if found.is_empty() {
            let window = walk.window(hit.t, tri.hit_error(ray, &hit).t).unwrap();
            let mut found = in_window(window);
            walk.advance(&mut found, |h| h.0);
            (window, found)
        } else {
            walk = Walk::new(Interval::new(hit.t, inf).unwrap());
            (tight, found)
        };
        assert!(
            !found.is_empty(),
            "the nearest hit is not in its own window: {ray:?}"
        );
        assert!(
            found.windows(2).all(|p| p[0].0 <= p[1].0) || !margin,
            "not in order"
        );
        out.extend(found.into_iter().map(|(t, i)| (window, i, t)));
    }
    (out, count)
}

fn prepared_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    i: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    tri.hit(&PreparedRay::new(ray), i)
}

#[derive(Default, Debug)]
struct Tally {
    rays: usize,
    /// Triangles whose box the ray hits: the exact module's work.
    boxes_hit: usize,
    /// Of those, the ones the float filter decided (a clear miss).
    filtered: usize,
    closed_hits: usize,
    one_hits: usize,
    windows: usize,
    /// Windows holding more than one triangle (ties and near-ties).
    shared_windows: usize,
    exact_checked: usize,
    clear_rays: usize,
    /// Rays through a convex mesh, in at one point and out at another.
    two_crossing_rays: usize,
    /// Reports beyond the first of one crossing (at one exact `t*`,
    /// fronts and backs beyond alternation), by the closed rule and by the
    /// one-hit rule.
    closed_doubles: usize,
    one_hit_doubles: usize,
}

impl Tally {
    fn add(mut self, o: Self) -> Self {
        self.rays += o.rays;
        self.boxes_hit += o.boxes_hit;
        self.filtered += o.filtered;
        self.closed_hits += o.closed_hits;
        self.one_hits += o.one_hits;
        self.windows += o.windows;
        self.shared_windows += o.shared_windows;
        self.exact_checked += o.exact_checked;
        self.clear_rays += o.clear_rays;
        self.two_crossing_rays += o.two_crossing_rays;
        self.closed_doubles += o.closed_doubles;
        self.one_hit_doubles += o.one_hit_doubles;
        self
    }
}

fn check_ray<V: Vector>(
    ray: &Ray<V>,
    tris: &[Triangle<V>],
    boxes: &[Aabb<V>],
    (name, embedded): (&str, bool),
    tally: &mut Tally,
) {
    let convex = name == "icosphere" || name == "t-junction octahedron";
    let inf = S::<V>::INFINITY;
    let all = Interval::up_to(inf).unwrap();
    // The exact crossings, each computed once, and whether each is clear
    // of the watertight tests' rounding. (A box the slab test misses holds
    // no exact crossing: it never misses what exact arithmetic hits. A
    // triangle the float filter finds surely outside is a clear miss: two
    // edge products of opposite signs beyond the rounding margin.)
    let mut crossings: Vec<Option<oracle::ExactTriangle>> = vec![None; tris.len()];
    let mut answers = vec![None; tris.len()];
    let mut clear = vec![true; tris.len()];
    let mut moved_crosses = vec![false; tris.len()];
    for (i, tri) in tris.iter().enumerate() {
        if ray_aabb(ray, &boxes[i], inf).is_none() {
            continue;
        }
        tally.boxes_hit += 1;
        let ex = oracle::triangle(ray, tri).unwrap();
        if oracle::surely_outside_watertight_filter(ray, tri) == Some(true) {
            tally.filtered += 1;
            assert!(
                !ex.line_hits(),
                "the filter's clear miss is crossed in exact arithmetic: {ray:?} {tri:?}"
            );
        } else {
            answers[i] = exact::ray_triangle_from_exact(ray, tri, &ex, inf);
            clear[i] = oracle::triangle_clear_watertight(ray, tri, &ex, inf);
            // The one-hit rule's exact verdict: the moved line crosses the
            // triangle (off the edge lines, the line itself), at `t* > 0`.
            let moved = if ex.signs.contains(&std::cmp::Ordering::Equal) {
                oracle::one_hit_line_hits(ray, tri) == Some(true)
            } else {
                ex.interior()
            };
            moved_crosses[i] = moved && ex.t.as_ref().is_some_and(|t| *t > oracle::int(0));
        }
        crossings[i] = Some(ex);
    }
    let crossed: Vec<bool> = answers.iter().map(Option::is_some).collect();
    // For a convex mesh: a line that meets it at exactly two points, going
    // in at one and out at the other, crosses the surface exactly twice,
    // through edges and corners too.
    let two_crossings = convex && {
        let mut ts: Vec<_> = answers
            .iter()
            .flatten()
            .map(|a| (a.t.value.clone(), a.side))
            .collect();
        ts.sort_by(|a, b| a.0.cmp(&b.0));
        ts.dedup_by(|a, b| a.0 == b.0);
        ts.len() == 2 && ts[0].1 != ts[1].1
    };
    tally.two_crossing_rays += usize::from(two_crossings);
    let all_clear = clear.iter().all(|&c| c);
    tally.clear_rays += usize::from(all_clear);
    for (one_hit, kernel, margin) in [
        (false, prepared_in::<V> as Kernel<V>, true),
        (true, one_hit_in::<V>, true),
        (false, prepared_in::<V>, false),
        (true, one_hit_in::<V>, false),
    ] {
        let (seq, count) = windows(ray, tris, kernel, margin);
        tally.windows += count;
        // No repeat.
        let mut ids: Vec<usize> = seq.iter().map(|s| s.1).collect();
        ids.sort_unstable();
        let n = ids.len();
        ids.dedup();
        assert_eq!(ids.len(), n, "a triangle reported twice: {ray:?} {seq:?}");
        // No skip: the same test over (0, inf] in one call.
        let single = if one_hit {
            one_hit_in::<V>
        } else {
            closed_in::<V>
        };
        let expected: Vec<usize> = (0..tris.len())
            .filter(|&i| single(ray, &tris[i], all).is_some())
            .collect();
        assert_eq!(ids, expected, "skipped or extra: {ray:?} {seq:?}");
        // Each exact crossing in its window: the windows are in exact order.
        for (w, i, _) in &seq {
            let ex = crossings[*i].get_or_insert_with(|| oracle::triangle(ray, &tris[*i]).unwrap());
            if let Some(t) = &ex.t {
                tally.exact_checked += 1;
                let above = oracle::r(w.min()).unwrap() < *t;
                let below = w.max() == inf || *t <= oracle::r(w.max()).unwrap();
                assert!(
                    above && below,
                    "t* = {} outside its window {w:?}: {ray:?} {:?}",
                    oracle::to_f64(t),
                    tris[*i]
                );
            }
        }
        tally.shared_windows += seq.windows(2).filter(|p| p[0].0 == p[1].0).count();
        // Reports of one crossing: at one exact `t*`, fronts and backs
        // beyond alternation. The crossings of a closed surface alternate
        // along a line, so one point can hold several (a line through a
        // saddle vertex, or touching a silhouette), fronts and backs in
        // turn, but never two more of one side than of the other; a
        // crossing reported by two triangles is.
        let doubles = {
            let mut at: Vec<_> = ids
                .iter()
                .filter_map(|&i| {
                    let side = answers[i].as_ref()?.side;
                    Some((
                        crossings[i].as_ref()?.t.clone()?,
                        side == rayhit::Side::Front,
                    ))
                })
                .collect();
            at.sort();
            at.chunk_by(|a, b| a.0 == b.0)
                .map(|group| {
                    let fronts = group.iter().filter(|g| g.1).count();
                    fronts.abs_diff(group.len() - fronts).saturating_sub(1)
                })
                .sum::<usize>()
        };
        if one_hit {
            tally.one_hits += n;
            tally.one_hit_doubles += doubles;
            // Exactly the triangles the moved line crosses: each crossing
            // of the surface once (where rounding leaves the mesh a surface
            // without overlaps, no two reports share a crossing; the stack
            // and a mesh near the precision's grid can have faces on top
            // of each other, crossed together).
            let exact: Vec<usize> = (0..tris.len()).filter(|&i| moved_crosses[i]).collect();
            assert_eq!(ids, exact, "one-hit against exact: {ray:?} {seq:?}");
            if embedded {
                assert_eq!(doubles, 0, "a crossing reported twice: {ray:?} {seq:?}");
            }
            if all_clear {
                let exact_count = crossed.iter().filter(|&&c| c).count();
                assert_eq!(
                    n, exact_count,
                    "one-hit count against exact: {ray:?} {seq:?}"
                );
            }
        } else {
            tally.closed_hits += n;
            tally.closed_doubles += doubles;
            // Against the exact crossings, where rounding cannot decide
            // otherwise.
            for i in 0..tris.len() {
                if clear[i] {
                    assert_eq!(
                        ids.contains(&i),
                        crossed[i],
                        "triangle {i} against exact: {ray:?} {:?}",
                        tris[i]
                    );
                }
            }
        }
    }
}

/// Whether the mesh, placed, surely stays a surface without overlaps:
/// not the stack, and the scale at least `2^12` ulps of the largest
/// coordinate (the meshes' closest vertices are about `0.05` of the
/// scale apart, and rounding moves a vertex by at most half an ulp, under
/// `scale / 8192`: below `1/400` of that spacing).
fn embedded<V: Vector>(name: &str, scale: f64, offset: [f64; 3]) -> bool {
    let largest = offset.iter().fold(0.0f64, |m, x| m.max(x.abs())) + 4.0 * scale;
    let ulp = S::<V>::UNIT_ROUNDOFF.to_f64() * 2.0 * largest;
    name != "thin stack" && scale > 4096.0 * ulp
}

/// The triangle's bounding box (its corners' extremes: exact).
fn bounding_box<V: Vector>(t: &Triangle<V>) -> Aabb<V> {
    let pick = |k: usize, less: bool| {
        [t.b[k], t.c[k]]
            .into_iter()
            .fold(t.a[k], |m, x| if (x < m) == less { x } else { m })
    };
    let lo = V::new(pick(0, true), pick(1, true), pick(2, true));
    let hi = V::new(pick(0, false), pick(1, false), pick(2, false));
    Aabb::new(lo, hi)
}

/// A ray from `4 scale` along the unit `dir` from the mesh's centre
/// `offset`, aimed at a point of triangle `tri`: by `kind`, its first
/// corner (0), the midpoint of its first edge (1), the point `(s / 2,
/// t / 2)` in its edges' coordinates (2), or the centre (3).
fn aimed<V: Vector>(
    tris: &[Triangle<V>],
    scale: f64,
    offset: [f64; 3],
    dir: [f64; 3],
    tri: usize,
    (kind, [s, t]): (u32, [f64; 2]),
) -> Ray<V> {
    let origin = V::new(
        f::<V>(offset[0] + 4.0 * scale * dir[0]),
        f::<V>(offset[1] + 4.0 * scale * dir[1]),
        f::<V>(offset[2] + 4.0 * scale * dir[2]),
    );
    let tri = tris[tri];
    let half = f::<V>(0.5);
    let target = match kind {
        0 => tri.a,
        1 => (tri.a + tri.b) * half,
        2 => tri.a + (tri.b - tri.a) * f::<V>(s * 0.5) + (tri.c - tri.a) * f::<V>(t * 0.5),
        _ => V::new(f::<V>(offset[0]), f::<V>(offset[1]), f::<V>(offset[2])),
    };
    Ray::new(origin, target - origin)
}

/// The rays of `rays_per_mesh` per mesh from `seed`, checked on `threads`
/// threads: each draws every placement and ray (cheap) and checks its
/// share of the placements, so the rays and the tally are the same for
/// any number of threads.
fn run<V: Vector>(seed: u64, rays_per_mesh: usize, threads: usize) -> Tally {
    std::thread::scope(|s| {
        let shares: Vec<_> = (0..threads)
            .map(|k| s.spawn(move || run_share::<V>(seed, rays_per_mesh, (k, threads))))
            .collect();
        shares
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .fold(Tally::default(), Tally::add)
    })
}

/// The placements `k`, `k + n`, `k + 2n`, ... of [`run`]'s sequence, for
/// `(k, n)` = `share`.
fn run_share<V: Vector>(seed: u64, rays_per_mesh: usize, (k, n): (usize, usize)) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let mut placement = 0;
    for (name, m) in meshes() {
        for _ in 0..rays_per_mesh.div_ceil(8) {
            let mine = placement % n == k;
            placement += 1;
            let scale = 10f64.powf(3.0 * signed(&mut rng));
            let far = if rng.below(2) == 0 { 0.0 } else { 1e5 };
            let offset = [
                far * signed(&mut rng),
                far * signed(&mut rng),
                far * signed(&mut rng),
            ];
            let tris = placed::<V>(&m, scale, offset);
            let boxes: Vec<Aabb<V>> = tris.iter().map(|t| bounding_box(t)).collect();
            for _ in 0..8 {
                let dir = loop {
                    let d = [signed(&mut rng), signed(&mut rng), signed(&mut rng)];
                    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if l > 0.1 && l <= 1.0 {
                        break d.map(|x| x / l);
                    }
                };
                let tri = rng.below(tris.len() as u32) as usize;
                let aim = (rng.below(4), [rng.unit(), rng.unit()].map(f64::from));
                let ray = aimed(&tris, scale, offset, dir, tri, aim);
                if !(mine && ray.is_valid()) {
                    continue;
                }
                tally.rays += 1;
                check_ray(
                    &ray,
                    &tris,
                    &boxes,
                    (name, embedded::<V>(name, scale, offset)),
                    &mut tally,
                );
            }
        }
    }
    tally
}

/// The threads for a long run: as many as the machine runs at once
/// (`std::thread::available_parallelism`), else 2. The rays and the tally
/// are the same for any number.
fn threads() -> usize {
    std::thread::available_parallelism().map_or(2, |n| n.get())
}

/// [`run`], timed and printed.
fn timed<V: Vector>(label: &str, seed: u64, rays_per_mesh: usize, threads: usize) -> Tally {
    let start = std::time::Instant::now();
    let t = run::<V>(seed, rays_per_mesh, threads);
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{label}: {t:?} in {secs:.1} s on {threads} thread(s), {:.3} ms per ray",
        1e3 * secs / t.rays.max(1) as f64
    );
    t
}

#[test]
fn sequences_on_closed_meshes_f32() {
    let t = timed::<Vec3>("f32", 11, rays(), 1);
    assert!(
        t.closed_hits >= t.rays && t.clear_rays > t.rays / 4,
        "{t:?}"
    );
}

#[test]
fn sequences_on_closed_meshes_f64() {
    let t = timed::<DVec3>("f64", 12, rays(), 1);
    assert!(
        t.closed_hits >= t.rays && t.clear_rays > t.rays / 4,
        "{t:?}"
    );
}

#[test]
#[ignore = "long: about 1.4 million rays per precision"]
fn sequences_on_closed_meshes_long_f32() {
    timed::<Vec3>(
        "f32 long",
        21,
        rayhit_testkit::case_count(340_000),
        threads(),
    );
}

#[test]
#[ignore = "long: about 1.4 million rays per precision"]
fn sequences_on_closed_meshes_long_f64() {
    timed::<DVec3>(
        "f64 long",
        22,
        rayhit_testkit::case_count(340_000),
        threads(),
    );
}

/// The same invariants as properties, for proptest to shrink a failure to
/// a small case: for any mesh, scale (`1e-3` to `1e3`), translation (up to
/// `1e5`), direction and aim, the window loop's sequence has no repeat and
/// no skip, each exact crossing lies in its window (so the sequence is in
/// exact order), and the one-hit count is the exact one where rounding
/// cannot decide otherwise (all in `check_ray`).
mod properties {
    use super::*;
    use proptest::prelude::*;

    fn check<V: Vector>(
        mesh: usize,
        scale: f64,
        offset: [f64; 3],
        dir: [f64; 3],
        tri: usize,
        aim: (u32, [f64; 2]),
    ) {
        let (name, m) = &meshes()[mesh];
        let tris = placed::<V>(m, scale, offset);
        let boxes: Vec<Aabb<V>> = tris.iter().map(|t| bounding_box(t)).collect();
        let l = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        let ray = aimed(
            &tris,
            scale,
            offset,
            dir.map(|x| x / l),
            tri % tris.len(),
            aim,
        );
        if ray.is_valid() {
            check_ray(
                &ray,
                &tris,
                &boxes,
                (name, embedded::<V>(name, scale, offset)),
                &mut Tally::default(),
            );
        }
    }

    fn direction() -> impl Strategy<Value = [f64; 3]> {
        [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64].prop_filter("not too short", |d| {
            d.iter().map(|x| x * x).sum::<f64>() > 0.01
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: rayhit_testkit::case_count(48).try_into().unwrap_or(u32::MAX),
            ..ProptestConfig::default()
        })]

        #[test]
        fn sequence_invariants(
            mesh in 0..4usize,
            exponent in -3.0..3.0f64,
            far in prop_oneof![Just(0.0), Just(1e5)],
            offset in [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64],
            dir in direction(),
            tri in 0..64usize,
            kind in 0..4u32,
            st in [0.0..1.0f64, 0.0..1.0f64],
            wide in any::<bool>(),
        ) {
            let (scale, offset) = (10f64.powf(exponent), offset.map(|x| x * far));
            if wide {
                check::<DVec3>(mesh, scale, offset, dir, tri, (kind, st));
            } else {
                check::<Vec3>(mesh, scale, offset, dir, tri, (kind, st));
            }
        }
    }
}

/// The closed rule over an interval, as a [`Kernel`].
fn closed_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    window: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    tri.hit(ray, window)
}

/// The one-hit rule over an interval, as a [`Kernel`].
fn one_hit_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    window: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    tri.hit(ray, (window, EdgeRule::OneHit))
}
