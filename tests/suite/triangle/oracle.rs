//! The triangle kernels against the exact oracle (see `common::oracle`):
//! the watertight test (`ray_triangle`), its one-hit variant and
//! Moller-Trumbore on every triangle generator of the test kit
//! (`rayhit_testkit::cases::triangles`: rays in face planes, grazing rays,
//! tiny and `-0.0` direction components, far and tiny triangles,
//! slivers), every watertight hit's `t` held to its error bound; and on
//! meshes, rays through the shared edges and vertices of a grid, an
//! octahedron, a jittered icosphere and vertex fans, also from inside
//! closed meshes: no crack, exactly one hit per crossing for the one-hit
//! variant, an odd crossing count from inside. The rest is tallied.
//!
//! `cargo test --test suite triangle::oracle::` runs 10,000 cases per
//! generator and precision; the long runs, 1,000,000 per generator:
//! `cargo test --release --test suite triangle::oracle:: -- --ignored --nocapture`.

use crate::common::oracle::{DEFAULT_CASES, Tally, f, long, precision, report};
use num_traits::Signed;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{EdgeRule, Intersect, Ray, Scalar, Surface, Triangle, Vector, ray_triangle};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::triangles::{self, TriCase};
use rayhit_testkit::cases::{aimed, v};
use rayhit_testkit::mesh as demo_mesh;
use rayhit_testkit::oracle::{self, rv};
use rayhit_testkit::source::Source;
use std::cmp::Ordering;

type S<V> = <V as Vector>::Scalar;

// -------------------------------------------------------------- triangles

/// How far the ray passes from the triangle's boundary, in ulps of the
/// largest coordinate: the distance between the ray's line and the nearest
/// edge's line (`|((p - o) x (q - o)) . d| / |d x (q - p)|`, exact Plucker
/// product over the lines' sine), or, if smaller, the distance along the ray
/// from the crossing to `t = 0` or `t_max`. This is the distance in the
/// ray's own frame, which is where the kernels round.
fn tri_gap_ulps<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: S<V>) -> f64 {
    rayhit::exact::distance_ulps(&rayhit::exact::Case::Triangle(*ray, *tri, t_max))
}

#[derive(Default)]
struct TriTallies {
    watertight: Tally,
    one_hit: Tally,
    mt: Tally,
    unbounded: usize,
    worst_t_ratio: f64,
    worst_t_ulps: f64,
}

fn run_triangles<V: Vector>(
    name: &str,
    seed: u64,
    n: usize,
    generator: fn(&mut Source) -> TriCase<V>,
) {
    let mut rng = Source::seeded(seed);
    let mut tallies = TriTallies::default();
    for i in 0..n {
        let (tri, ray, t_max) = generator(&mut rng);
        let nrm = tri.normal();
        if !(ray.is_valid() && nrm.is_finite() && nrm != V::ZERO) {
            continue;
        }
        let ex = oracle::triangle(&ray, &tri);
        let exact = ex.hits(&oracle::limit(t_max));
        let gap = || tri_gap_ulps(&ray, &tri, t_max);
        let wt = ray_triangle(&ray, &tri, t_max);
        tallies.watertight.record(wt.is_some(), exact, gap);
        tallies.one_hit.record(
            tri.hit(&ray, (t_max, EdgeRule::OneHit)).is_some(),
            exact,
            gap,
        );
        tallies
            .mt
            .record(tri.moller_trumbore(&ray, t_max).is_some(), exact, gap);
        // Every watertight hit is within its error bounds (or reports them
        // unbounded); the exact t of a reported hit is positive whenever the
        // bound is finite.
        if let Some(h) = wt {
            let err = tri.hit_error(&ray, &h);
            if err.t.is_finite() {
                let t = ex.t.as_ref().expect("a bounded hit on a parallel triangle");
                let actual = (h.t.to_f64() - f(t)).abs();
                tallies.worst_t_ratio = tallies.worst_t_ratio.max(actual / err.t.to_f64());
                tallies.worst_t_ulps = tallies
                    .worst_t_ulps
                    .max(actual / oracle::ulp::<S<V>>(h.t.to_f64()));
                assert!(
                    oracle::close(h.t, t, err.t),
                    "{name} case {i}: t {:?} exact {} bound {:?}",
                    h.t,
                    f(t),
                    err.t
                );
                assert!(
                    t.is_positive(),
                    "{name} case {i}: a hit with the exact crossing behind the origin"
                );
            } else {
                tallies.unbounded += 1;
            }
        }
    }
    report(
        precision::<V>(),
        name,
        &[
            ("watertight", &tallies.watertight),
            ("one-hit", &tallies.one_hit),
            ("MT", &tallies.mt),
        ],
    );
    println!(
        "{:>3} {name:<22} watertight t: worst error {:.2} ulps, worst error / bound {:.3}; hits with unbounded error: {}",
        precision::<V>(),
        tallies.worst_t_ulps,
        tallies.worst_t_ratio,
        tallies.unbounded
    );
}

fn all_triangles<V: Vector>(n: usize) {
    for (name, seed, generator) in triangles::generators::<V>() {
        run_triangles::<V>(name, seed, n, generator);
    }
}

// ------------------------------------------------------------------ meshes

/// A triangle mesh with shared vertices, consistent winding, and the
/// interior edges and vertices (those with a full ring of triangles).
struct Mesh {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
    closed: bool,
    convex: bool,
    /// Interior edges `(a, b)` and the two triangles sharing them.
    edges: Vec<((usize, usize), [usize; 2])>,
    /// Interior vertices and the triangles around them.
    stars: Vec<(usize, Vec<usize>)>,
    /// For every vertex, the triangles that have it.
    around: Vec<Vec<usize>>,
}

impl Mesh {
    fn new(
        vertices: Vec<[f64; 3]>,
        triangles: Vec<[usize; 3]>,
        closed: bool,
        convex: bool,
        boundary: &[bool],
    ) -> Self {
        use std::collections::BTreeMap;
        let mut by_edge: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
        for (i, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                by_edge.entry((a.min(b), a.max(b))).or_default().push(i);
            }
        }
        let edges: Vec<_> = by_edge
            .into_iter()
            .filter(|(_, ts)| ts.len() == 2)
            .map(|(e, ts)| (e, [ts[0], ts[1]]))
            .collect();
        let around: Vec<Vec<usize>> = (0..vertices.len())
            .map(|vi| {
                (0..triangles.len())
                    .filter(|&i| triangles[i].contains(&vi))
                    .collect()
            })
            .collect();
        let mut stars = Vec::new();
        for (vi, &on_boundary) in boundary.iter().enumerate() {
            if on_boundary {
                continue;
            }
            let star: Vec<usize> = (0..triangles.len())
                .filter(|&i| triangles[i].contains(&vi))
                .collect();
            if !star.is_empty() {
                stars.push((vi, star));
            }
        }
        Mesh {
            vertices,
            triangles,
            closed,
            convex,
            edges,
            stars,
            around,
        }
    }

    fn tri<V: Vector>(&self, i: usize) -> Triangle<V> {
        let [a, b, c] = self.triangles[i];
        Triangle::new(
            v(self.vertices[a]),
            v(self.vertices[b]),
            v(self.vertices[c]),
        )
    }

    fn size(&self) -> f64 {
        self.vertices
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()))
    }
}

/// A random similarity: a rotation (from a random orthonormal frame),
/// scale 2^-4..2^4 and offset in [-64, 64]^3.
fn placement(rng: &mut Source) -> impl Fn([f64; 3]) -> [f64; 3] + use<> {
    let a = rng.direction();
    let mut b = rng.direction();
    let ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    b = [0, 1, 2].map(|k| b[k] - ab * a[k]);
    let bl = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    b = b.map(|x| x / bl);
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let s = rng.log2_range(-4.0, 4.0);
    let o = [0, 1, 2].map(|_| rng.range(-64.0, 64.0));
    move |p: [f64; 3]| [0, 1, 2].map(|k| o[k] + s * (p[0] * a[k] + p[1] * b[k] + p[2] * c[k]))
}

/// An n x n grid over [-1, 1]^2 with random heights, two triangles per
/// cell, wound counter-clockwise seen from +z.
fn grid_mesh(rng: &mut Source) -> Mesh {
    let n = 8usize;
    let place = placement(rng);
    let bump = rng.range(0.0, 0.5);
    let mut vertices = Vec::new();
    let mut boundary = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (
                2.0 * i as f64 / n as f64 - 1.0,
                2.0 * j as f64 / n as f64 - 1.0,
            );
            vertices.push(place([x, y, bump * rng.range(-1.0, 1.0) / n as f64]));
            boundary.push(i == 0 || j == 0 || i == n || j == n);
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rng.one_in(2) {
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([b, c, d]);
            }
        }
    }
    Mesh::new(vertices, triangles, false, false, &boundary)
}

/// An octahedron, placed at random; closed and convex, wound outwards.
fn octahedron(rng: &mut Source) -> Mesh {
    let place = placement(rng);
    let vertices: Vec<_> = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ]
    .into_iter()
    .map(&place)
    .collect();
    let mut triangles = Vec::new();
    for sx in [0usize, 1] {
        for sy in [2usize, 3] {
            for sz in [4usize, 5] {
                // Odd number of negative axes: swap to keep the normal outwards.
                let negatives = sx + (sy - 2) + (sz - 4);
                triangles.push(if negatives % 2 == 0 {
                    [sx, sy, sz]
                } else {
                    [sx, sz, sy]
                });
            }
        }
    }
    Mesh::new(vertices, triangles, true, true, &[false; 6])
}

/// An icosahedron subdivided once (80 triangles; the demo's icosphere),
/// each vertex pushed in or out by up to 10%, placed at random: closed,
/// wound outwards, and not quite convex.
fn icosphere(rng: &mut Source) -> Mesh {
    let sphere = demo_mesh::icosphere(Vec3::ZERO, 1.0, 1);
    let place = placement(rng);
    let vertices: Vec<_> = sphere
        .positions
        .iter()
        .map(|q| {
            let q = q.as_dvec3().normalize().to_array();
            let r = 1.0 + rng.range(-0.1, 0.1);
            place(q.map(|x| x * r))
        })
        .collect();
    let triangles = sphere
        .indices
        .iter()
        .map(|t| t.map(|i| i as usize))
        .collect();
    let n = vertices.len();
    Mesh::new(vertices, triangles, true, false, &vec![false; n])
}

/// A fan of 3 to 12 triangles around one vertex: neighbours at random
/// angles and distances, heights from flat to a steep cone.
fn fan(rng: &mut Source) -> Mesh {
    let k = 3 + rng.below(10) as usize;
    let place = placement(rng);
    let mut angles: Vec<f64> = (0..k)
        .map(|_| rng.range(0.0, std::f64::consts::TAU))
        .collect();
    angles.sort_by(f64::total_cmp);
    // Keep every gap below pi so that the fan covers a disc around the centre.
    let gaps_ok = (0..k).all(|i| {
        let next = if i + 1 < k {
            angles[i + 1]
        } else {
            angles[0] + std::f64::consts::TAU
        };
        next - angles[i] < 3.0
    });
    if !gaps_ok {
        angles = (0..k)
            .map(|i| std::f64::consts::TAU * i as f64 / k as f64 + rng.range(0.0, 0.3))
            .collect();
    }
    let cone = rng.range(-1.0, 1.0) * if rng.one_in(2) { 0.0 } else { 1.0 };
    let mut vertices = vec![place([0.0, 0.0, 0.0])];
    for &a in &angles {
        let r = rng.log2_range(-1.0, 1.0);
        vertices.push(place([
            r * a.cos(),
            r * a.sin(),
            cone * r + rng.range(-0.05, 0.05),
        ]));
    }
    let triangles = (0..k).map(|i| [0, 1 + i, 1 + (i + 1) % k]).collect();
    let mut boundary = vec![true; k + 1];
    boundary[0] = false;
    Mesh::new(vertices, triangles, false, false, &boundary)
}

#[derive(Default)]
struct MeshTally {
    rays: usize,
    one_sided: usize,
    cracks_watertight: usize,
    cracks_mt: usize,
    one_hit_wrong: usize,
    one_hit_counts: [usize; 4],
    inside_rays: usize,
}

/// The sign of `dir . normal` for every triangle of a star, exactly, and
/// whether all of them face the ray the same way by a clear margin (sine of
/// the angle between ray and plane above 2^-10), so that the star projects
/// one-to-one and exactly one of its triangles must claim the crossing.
fn one_sided<V: Vector>(ray: &Ray<V>, tris: &[Triangle<V>]) -> bool {
    let mut sign = None;
    for t in tris {
        let Some(s) = facing(ray, t) else {
            return false;
        };
        if sign.is_some_and(|old| old != s) {
            return false;
        }
        sign = Some(s);
    }
    true
}

/// The side `t` faces the ray from (`Greater` where `d . n > 0`), when it
/// does by a clear margin (`sin^2 > 2^-20`, that is `(d.n)^2 > 2^-20 |d|^2
/// |n|^2`), else `None`. Decided on `Bounded` floats where their error
/// bounds allow (nearly always), else in big rationals: the exact answer
/// either way.
fn facing<V: Vector>(ray: &Ray<V>, t: &Triangle<V>) -> Option<Ordering> {
    use oracle::{Bounded, bcross, bdot, bsub, bv};
    let d = bv(ray.dir);
    let n = bcross(&bsub(&bv(t.b), &bv(t.a)), &bsub(&bv(t.c), &bv(t.a)));
    let dn = bdot(&d, &n);
    let margin = dn * dn - Bounded::exact(2f64.powi(-20)) * bdot(&d, &d) * bdot(&n, &n);
    match (margin.sign(), dn.sign()) {
        (Some(Ordering::Less | Ordering::Equal), _) => return None,
        (Some(Ordering::Greater), Some(side)) => return Some(side),
        _ => {}
    }
    let d = rv(ray.dir);
    let n = oracle::cross(
        &oracle::sub(&rv(t.b), &rv(t.a)),
        &oracle::sub(&rv(t.c), &rv(t.a)),
    );
    let dn = oracle::dot(&d, &n);
    let (dd, nn) = (oracle::dot(&d, &d), oracle::dot(&n, &n));
    (dn.clone() * &dn > oracle::dyadic(1, -20) * &dd * &nn).then(|| {
        if dn.is_positive() {
            Ordering::Greater
        } else {
            Ordering::Less
        }
    })
}

fn run_mesh<V: Vector>(name: &str, seed: u64, n: usize, build: fn(&mut Source) -> Mesh) {
    let mut rng = Source::seeded(seed);
    let mut tally = MeshTally::default();
    let mut mesh = build(&mut rng);
    for i in 0..n {
        if i % 64 == 0 {
            mesh = build(&mut rng);
        }
        let size = mesh.size();
        // A target on an interior edge or at an interior vertex, and the
        // triangles around it: for a vertex its star, for an edge the stars
        // of both ends (rounding the target can move the ray off the edge by
        // more than a sliver beside it is wide, into the next triangle).
        let (target, star): ([f64; 3], Vec<usize>) = if rng.one_in(2) && !mesh.edges.is_empty() {
            let ((a, b), _) = mesh.edges[rng.below(mesh.edges.len() as u32) as usize];
            let mut ts: Vec<usize> = mesh.around[a]
                .iter()
                .chain(&mesh.around[b])
                .copied()
                .collect();
            ts.sort_unstable();
            ts.dedup();
            let s = if rng.one_in(4) {
                0.5
            } else {
                rng.range(0.05, 0.95)
            };
            let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
            // Round the corners first, as the kernels see them.
            let (qa, qb): (V, V) = (v(pa), v(pb));
            let t = [0, 1, 2].map(|k| qa[k].to_f64() + s * (qb[k].to_f64() - qa[k].to_f64()));
            (t, ts)
        } else {
            let (vi, ts) = &mesh.stars[rng.below(mesh.stars.len() as u32) as usize];
            let q: V = v(mesh.vertices[*vi]);
            ([q.x().to_f64(), q.y().to_f64(), q.z().to_f64()], ts.clone())
        };
        // From outside or, for closed meshes, from inside half the time.
        let inside = mesh.closed && rng.one_in(2);
        let ray: Ray<V> = if inside {
            // Within 30% of the size of the centroid: inside, with a wide margin.
            let c = centroid(&mesh);
            let o = [0, 1, 2]
                .map(|k| c[k] + 0.3 * rng.range(-1.0, 1.0) * radius(&mesh, c) / 3f64.sqrt());
            let origin: V = v(o);
            let dir = [0, 1, 2].map(|k| target[k] - origin[k].to_f64());
            Ray::new(origin, v(dir))
        } else {
            let s = rng.log2_range(-2.0, 3.0) * size.max(1e-3);
            let d = rng.direction();
            aimed(target, d, s / 1.0)
        };
        if !ray.is_valid() {
            continue;
        }
        tally.rays += 1;
        let tris: Vec<Triangle<V>> = star.iter().map(|&k| mesh.tri::<V>(k)).collect();
        let inf = S::<V>::INFINITY;
        let wt = tris
            .iter()
            .filter(|t| ray_triangle(&ray, t, inf).is_some())
            .count();
        let mt = tris
            .iter()
            .filter(|t| t.moller_trumbore(&ray, inf).is_some())
            .count();
        let one = tris
            .iter()
            .filter(|t| t.hit(&ray, (inf, EdgeRule::OneHit)).is_some())
            .count();
        // The exact line crosses the star in front of the origin (checked,
        // not assumed: the target is only within rounding of the edge or
        // vertex), and the star faces the ray one way: every kernel must see
        // the crossing, and the one-hit variant exactly once.
        // (The exact check is needed only when some kernel did not answer
        // exactly one hit; it is costly, so it is skipped otherwise.)
        let answered = wt >= 1 && one == 1 && mt >= 1;
        let crossed = || answered || tris.iter().any(|t| oracle::triangle(&ray, t).hits(&None));
        if one_sided(&ray, &tris) && crossed() {
            tally.one_sided += 1;
            if wt == 0 {
                tally.cracks_watertight += 1;
            }
            if mt == 0 {
                tally.cracks_mt += 1;
            }
            if one != 1 {
                tally.one_hit_wrong += 1;
            }
            tally.one_hit_counts[one.min(3)] += 1;
            assert!(
                wt >= 1,
                "{name} ray {i}: crack: {ray:?} hits none of {tris:?}"
            );
            assert_eq!(
                one, 1,
                "{name} ray {i}: one-hit count {one} for {ray:?} through {tris:?}"
            );
        }
        // From strictly inside a closed mesh every ray hits, and the one-hit
        // variant crosses an odd number of times (exactly once if convex).
        if inside {
            tally.inside_rays += 1;
            let all: Vec<Triangle<V>> = (0..mesh.triangles.len())
                .map(|k| mesh.tri::<V>(k))
                .collect();
            let wt_all = all
                .iter()
                .filter(|t| ray_triangle(&ray, t, inf).is_some())
                .count();
            let one_all = all
                .iter()
                .filter(|t| t.hit(&ray, (inf, EdgeRule::OneHit)).is_some())
                .count();
            assert!(wt_all >= 1, "{name} ray {i}: escaped from inside: {ray:?}");
            assert!(
                one_all % 2 == 1,
                "{name} ray {i}: even crossing count {one_all} from inside: {ray:?}"
            );
            if mesh.convex {
                assert_eq!(
                    one_all, 1,
                    "{name} ray {i}: convex mesh crossed {one_all} times from inside"
                );
            }
        }
    }
    println!(
        "{:>3} {name:<22} {} rays ({} through one-sided stars, {} from inside): cracks watertight {} MT {} | one-hit != 1: {} (counts 0/1/2/3+: {:?})",
        precision::<V>(),
        tally.rays,
        tally.one_sided,
        tally.inside_rays,
        tally.cracks_watertight,
        tally.cracks_mt,
        tally.one_hit_wrong,
        tally.one_hit_counts,
    );
}

fn centroid(mesh: &Mesh) -> [f64; 3] {
    let n = mesh.vertices.len() as f64;
    [0, 1, 2].map(|k| mesh.vertices.iter().map(|p| p[k]).sum::<f64>() / n)
}

/// The distance from `c` to the nearest triangle plane: an inscribed radius
/// for a convex mesh, and a safe one for the jittered icosphere's star-shaped
/// body around its centroid.
fn radius(mesh: &Mesh, c: [f64; 3]) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, cc] = t.map(|i| mesh.vertices[i]);
            rayhit_testkit::mesh::plane_distance(a, b, cc, c).abs()
        })
        .fold(f64::INFINITY, f64::min)
}

fn all_meshes<V: Vector>(n: usize) {
    run_mesh::<V>("mesh grid", 31, n, grid_mesh);
    run_mesh::<V>("mesh octahedron", 32, n, octahedron);
    run_mesh::<V>("mesh icosphere", 33, n, icosphere);
    run_mesh::<V>("mesh vertex fan", 34, n, fan);
}

// ------------------------------------------------------------------ tests

#[test]
fn triangles_f32() {
    all_triangles::<Vec3>(case_count(DEFAULT_CASES));
}

#[test]
fn triangles_f64() {
    all_triangles::<DVec3>(case_count(DEFAULT_CASES));
}

#[test]
fn meshes_f32() {
    all_meshes::<Vec3>(case_count(DEFAULT_CASES));
}

#[test]
fn meshes_f64() {
    all_meshes::<DVec3>(case_count(DEFAULT_CASES));
}

#[test]
#[ignore = "long: cargo test --release --test suite triangle::oracle:: -- --ignored --nocapture"]
fn long_triangles() {
    long(all_triangles::<Vec3>, all_triangles::<DVec3>);
}

#[test]
#[ignore = "long: cargo test --release --test suite triangle::oracle:: -- --ignored --nocapture"]
fn long_meshes() {
    long(all_meshes::<Vec3>, all_meshes::<DVec3>);
}
