//! Closed meshes of quads, and of quads and triangles, with no crack and
//! no leak: a cube of `n x n` quads a face, a torus of non-planar quads,
//! and a cube whose faces mix one quad, four quads and two triangles, with
//! the T-junctions between them closed by zero-area triangles. Scales
//! `1e-3` to `1e3`, offsets to `1e5` (in `f32`, those where the mesh
//! stays a surface: not `1e-3` at `1e5`).
//!
//! Rays from inside, aimed at the meshes' corners, edge midpoints,
//! diagonals and faces, must each hit the mesh (a miss is a leak: the mesh
//! is closed and the origin inside it); with the one-hit rule too. On the
//! cubes, rays from outside through the same points towards a point
//! inside must hit too (a miss is a crack: the exact ray runs from outside
//! to a point well inside, so it crosses the surface). The textbook tests
//! (the "Next Week" quad and Moller-Trumbore for the triangles) are
//! counted on the same rays (on the cubes: the torus's quads are not
//! parallelograms, which the textbook test assumes). With the one-hit rule, a ray from inside a
//! cube is reported by exactly one face, whatever edge or corner it
//! leaves through.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{EdgeRule, Intersect, Patch, Quad, Ray, Scalar, Triangle, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

use super::textbook;
use crate::common::draw::{S, signed, v};
use crate::patch::reshetov;

/// What a mesh's four-sided faces are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Kind {
    /// [`Quad`]s: two triangles each.
    Quads,
    /// [`Patch`]es: bilinear patches through the same corners.
    Patches,
}

/// A closed surface of quads or patches and triangles.
pub(crate) struct Mesh<V: Vector> {
    quads: Vec<Quad<V>>,
    patches: Vec<Patch<V>>,
    triangles: Vec<Triangle<V>>,
    /// Points of the surface to aim at: corners, edge midpoints, points of
    /// the diagonals and of the faces.
    targets: Vec<V>,
    /// Points strictly inside, at least a tenth of the size from the
    /// surface.
    inside: Vec<V>,
    /// Convex: a point beyond a surface point, on the line from a point
    /// inside, is outside.
    convex: bool,
}

impl<V: Vector> Mesh<V> {
    /// Whether anything is hit at `0 < t`, with `rule`.
    fn hit(&self, ray: &Ray<V>, rule: EdgeRule) -> bool {
        let search = (S::<V>::INFINITY, rule);
        self.quads.iter().any(|q| q.hit(ray, search).is_some())
            || self.patches.iter().any(|p| p.hit(ray, search).is_some())
            || self.triangles.iter().any(|t| t.hit(ray, search).is_some())
    }

    /// How many faces (quads and triangles) `ray` hits at `0 < t`, with
    /// the one-hit rule.
    fn one_hit_count(&self, ray: &Ray<V>) -> usize {
        let search = (S::<V>::INFINITY, EdgeRule::OneHit);
        self.quads
            .iter()
            .filter(|q| q.hit(ray, search).is_some())
            .count()
            + self
                .patches
                .iter()
                .filter(|p| p.hit(ray, search).is_some())
                .count()
            + self
                .triangles
                .iter()
                .filter(|t| t.hit(ray, search).is_some())
                .count()
    }

    /// The same with the textbook tests (`t > 0`).
    fn textbook_hit(&self, ray: &Ray<V>) -> bool {
        let (zero, inf) = (S::<V>::ZERO, S::<V>::INFINITY);
        self.quads
            .iter()
            .any(|q| textbook(ray, q, zero, inf).is_some())
            || self
                .patches
                .iter()
                .any(|p| reshetov(ray, p, zero, inf).is_some())
            || self
                .triangles
                .iter()
                .any(|t| t.moller_trumbore(ray, inf).is_some())
    }
}

/// The vertex at grid position `g` (each in `0..=n`) of the cube
/// `[-1, 1]^3` scaled by `scale` around `offset`: a function of `g` alone,
/// so faces sharing a vertex share its bits.
fn grid<V: Vector>(g: [u32; 3], n: u32, scale: f64, offset: [f64; 3]) -> V {
    let c = |k: usize| offset[k] + scale * (2.0 * f64::from(g[k]) / f64::from(n) - 1.0);
    v::<V>(c(0), c(1), c(2))
}

/// The six faces of the grid cube: for each, the axis held fixed, its
/// value (`0` or `n`), and the two others in the order that winds the face
/// outwards.
fn faces() -> [(usize, bool, usize, usize); 6] {
    [
        (0, true, 1, 2),
        (0, false, 2, 1),
        (1, true, 2, 0),
        (1, false, 0, 2),
        (2, true, 0, 1),
        (2, false, 1, 0),
    ]
}

/// The grid point on face `f` at `(i, j)` of its `n x n` grid.
fn on_face(face: (usize, bool, usize, usize), i: u32, j: u32, n: u32) -> [u32; 3] {
    let (k, high, a, b) = face;
    let mut g = [0; 3];
    g[k] = if high { n } else { 0 };
    g[a] = i;
    g[b] = j;
    g
}

/// A cube of `n x n` quads (or patches) a face; with `mixed`, face 0 has
/// `2n x 2n` against the others' `n x n`, face 1 is two triangles a cell,
/// and the T-junctions along face 0's edges are closed by zero-area
/// triangles.
fn cube<V: Vector>(
    rng: &mut Pcg32,
    n: u32,
    mixed: bool,
    kind: Kind,
    scale: f64,
    offset: [f64; 3],
) -> Mesh<V> {
    // Work on a grid twice as fine, so that face 0 can use every point.
    let fine = 2 * n;
    let at = |g: [u32; 3]| grid::<V>(g, fine, scale, offset);
    let (mut quads, mut triangles, mut targets) = (Vec::new(), Vec::new(), Vec::new());
    let mut patches = Vec::new();
    for (index, face) in faces().into_iter().enumerate() {
        let step = if mixed && index == 0 { 1 } else { 2 };
        for i in (0..fine).step_by(step as usize) {
            for j in (0..fine).step_by(step as usize) {
                let p = |di: u32, dj: u32| at(on_face(face, i + di, j + dj, fine));
                let (a, b, c, d) = (p(0, 0), p(step, 0), p(step, step), p(0, step));
                if mixed && index == 1 {
                    triangles.push(Triangle::new(a, b, c));
                    triangles.push(Triangle::new(a, c, d));
                } else if kind == Kind::Patches {
                    patches.push(Patch::new(a, b, d, c));
                } else {
                    quads.push(Quad::new(a, b, c, d));
                }
                let h = step / 2;
                targets.extend([a, p(h, 0), p(h, h), p(0, h)]);
                // A point of the diagonal a-c, and one of the face.
                let w = (signed(rng) + 1.0) / 2.0;
                let lerp = |x: V, y: V, w: f64| x + (y - x) * S::<V>::from_f64(w);
                targets.push(lerp(a, c, w));
                targets.push(lerp(
                    lerp(a, b, w),
                    lerp(d, c, w),
                    (signed(rng) + 1.0) / 2.0,
                ));
            }
        }
    }
    if mixed {
        // Face 0's edges: each coarse cell edge of a neighbouring face has
        // face 0's fine point at its middle. Close each with the zero-area
        // triangle (end, middle, other end).
        let face = faces()[0];
        for i in (0..fine).step_by(2) {
            for (start, end, mid) in [
                (
                    on_face(face, i, 0, fine),
                    on_face(face, i + 2, 0, fine),
                    on_face(face, i + 1, 0, fine),
                ),
                (
                    on_face(face, i, fine, fine),
                    on_face(face, i + 2, fine, fine),
                    on_face(face, i + 1, fine, fine),
                ),
                (
                    on_face(face, 0, i, fine),
                    on_face(face, 0, i + 2, fine),
                    on_face(face, 0, i + 1, fine),
                ),
                (
                    on_face(face, fine, i, fine),
                    on_face(face, fine, i + 2, fine),
                    on_face(face, fine, i + 1, fine),
                ),
            ] {
                triangles.push(Triangle::new(at(start), at(mid), at(end)));
            }
        }
    }
    let inside = (0..8)
        .map(|_| {
            let p = [0, 1, 2].map(|k| offset[k] + 0.9 * scale * signed(rng));
            v::<V>(p[0], p[1], p[2])
        })
        .collect();
    Mesh {
        quads,
        patches,
        triangles,
        targets,
        inside,
        convex: true,
    }
}

/// A torus of `rings x sides` quads (or patches), none of them planar.
fn torus<V: Vector>(rng: &mut Pcg32, kind: Kind, scale: f64, offset: [f64; 3]) -> Mesh<V> {
    let (rings, sides) = (12u32, 8u32);
    let (major, minor) = (1.0, 0.4);
    let point = |i: u32, j: u32| {
        let (u, w) = (
            f64::from(i % rings) / f64::from(rings) * std::f64::consts::TAU,
            f64::from(j % sides) / f64::from(sides) * std::f64::consts::TAU,
        );
        // A twist makes every quad non-planar.
        let w = w + 0.3 * u;
        let r = major + minor * w.cos();
        [r * u.cos(), minor * w.sin(), r * u.sin()]
    };
    let at = |p: [f64; 3]| {
        v::<V>(
            offset[0] + scale * p[0],
            offset[1] + scale * p[1],
            offset[2] + scale * p[2],
        )
    };
    let (mut quads, mut patches, mut targets) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..rings {
        for j in 0..sides {
            let p = |di: u32, dj: u32| at(point(i + di, j + dj));
            // (Ring `rings` is ring 0, by the `% rings` above: the seam's
            // faces share ring 0's points, twisted or not.)
            let q = Quad::new(p(0, 0), p(0, 1), p(1, 1), p(1, 0));
            targets.extend([q.a, q.b, q.c]);
            targets.push(q.a + (q.b - q.a) * S::<V>::from_f64(0.5));
            let w = S::<V>::from_f64((signed(rng) + 1.0) / 2.0);
            if kind == Kind::Patches {
                let patch = Patch::new(q.a, q.b, q.d, q.c);
                let w2 = S::<V>::from_f64((signed(rng) + 1.0) / 2.0);
                targets.push(patch.point_at(w, w2));
                patches.push(patch);
            } else {
                targets.push(q.a + (q.c - q.a) * w);
                quads.push(q);
            }
        }
    }
    // Points on the tube's core circle are inside the quads' tube.
    let inside = (0..8)
        .map(|k| {
            let u = f64::from(k) / 8.0 * std::f64::consts::TAU + 0.1;
            at([major * u.cos(), 0.0, major * u.sin()])
        })
        .collect();
    Mesh {
        quads,
        patches,
        triangles: Vec::new(),
        targets,
        inside,
        convex: false,
    }
}

/// Leak and crack counts of rayhit (closed rule, one-hit rule) and of the
/// textbook tests.
#[derive(Debug, Default, Clone, Copy)]
struct Counts {
    from_inside: usize,
    leaks: usize,
    one_hit_leaks: usize,
    one_hit_repeats: usize,
    textbook_leaks: usize,
    from_outside: usize,
    cracks: usize,
    one_hit_cracks: usize,
    textbook_cracks: usize,
}

fn run<V: Vector>(mesh: &Mesh<V>, scale: f64, counts: &mut Counts) {
    for (k, &target) in mesh.targets.iter().enumerate() {
        let start = mesh.inside[k % mesh.inside.len()];
        let ray = Ray::new(start, target - start);
        counts.from_inside += 1;
        counts.leaks += usize::from(!mesh.hit(&ray, EdgeRule::Closed));
        counts.one_hit_leaks += usize::from(!mesh.hit(&ray, EdgeRule::OneHit));
        // (The textbook quad is a parallelogram test: only the cubes'
        // quads are parallelograms, so the torus is not counted for it;
        // the textbook patch test is counted everywhere.)
        if mesh.convex || !mesh.patches.is_empty() {
            counts.textbook_leaks += usize::from(!mesh.textbook_hit(&ray));
        }
        if !mesh.convex {
            continue;
        }
        // A ray from inside a convex mesh crosses it once: one face, with
        // the one-hit rule, however many share the point it leaves by.
        counts.one_hit_repeats += usize::from(mesh.one_hit_count(&ray) != 1);
        // From outside, a few sizes beyond the target on the line from
        // the point inside, back through the target towards that point.
        let out = target - start;
        let away = S::<V>::from_f64(4.0 * scale) / out.length();
        let origin = target + out * away;
        let ray = Ray::new(origin, start - origin);
        counts.from_outside += 1;
        counts.cracks += usize::from(!mesh.hit(&ray, EdgeRule::Closed));
        counts.one_hit_cracks += usize::from(!mesh.hit(&ray, EdgeRule::OneHit));
        counts.textbook_cracks += usize::from(!mesh.textbook_hit(&ray));
    }
}

/// Whether the meshes, placed, stay surfaces without overlaps in `V`'s
/// precision: the scale at least 64 ulps of the largest coordinate, so
/// that rounding moves a vertex by at most `1/128` of the scale (the
/// meshes' closest vertices are at least about `0.3` of the scale apart:
/// the cubes' grid `0.5`, the torus's rings and sides `0.31`; and the
/// origins from inside at least `0.1` of it from the surface). A mesh of
/// size `1e-3` at `1e5` in `f32` is not one: its vertices round onto a
/// grid of spacing `2^-7`, and "inside" it means nothing.
fn embedded<V: Vector>(scale: f64, offset: [f64; 3]) -> bool {
    let largest = offset.iter().fold(0.0f64, |m, x| m.max(x.abs())) + 2.0 * scale;
    scale > 64.0 * 2.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * largest
}

/// The counts over every placement (scales `1e-3` to `1e3`, offsets to
/// `1e5`, those the precision holds: [`embedded`]) of the three meshes,
/// their four-sided faces of `kind`.
fn check<V: Vector>(name: &str, kind: Kind) -> Counts {
    let mut rng = Pcg32::new(0x0057_4154 + S::<V>::UNIT_ROUNDOFF.to_f64().to_bits() % 89);
    let mut counts = Counts::default();
    // (Every scale at every offset once by default.)
    let placements = case_count(9);
    for k in 0..placements {
        let scale = [1e-3, 1.0, 1e3][k % 3];
        let reach = [0.0, 1e2, 1e5][(k / 3) % 3];
        let offset = [0, 1, 2].map(|_| reach * signed(&mut rng));
        if !embedded::<V>(scale, offset) {
            continue;
        }
        for mesh in [
            cube::<V>(&mut rng, 2, false, kind, scale, offset),
            cube::<V>(&mut rng, 2, true, kind, scale, offset),
            torus::<V>(&mut rng, kind, scale, offset),
        ] {
            run(&mesh, scale, &mut counts);
        }
    }
    println!("{name}: {counts:?}");
    counts
}

/// Both precisions' meshes with four-sided faces of `kind`: enough rays,
/// and no leak, crack or one-hit repeat.
pub(crate) fn assert_closed(kind: Kind) {
    for counts in [check::<Vec3>("f32", kind), check::<DVec3>("f64", kind)] {
        assert!(
            counts.from_inside > 1000 && counts.from_outside > 1000,
            "{counts:?}"
        );
        assert_eq!(
            (
                counts.leaks,
                counts.one_hit_leaks,
                counts.one_hit_repeats,
                counts.cracks,
                counts.one_hit_cracks
            ),
            (0, 0, 0, 0, 0),
            "{counts:?}"
        );
    }
}

#[test]
fn closed_quad_meshes_have_no_crack_and_no_leak() {
    assert_closed(Kind::Quads);
}
