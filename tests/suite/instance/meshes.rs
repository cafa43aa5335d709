//! Closed meshes placed by instances neither crack nor leak.
//!
//! Two closed, consistently wound meshes from the test kit (an icosphere,
//! convex, and a torus, not convex) are placed in the world by transforms
//! from `rayhit::strategies::transform` and by nested pairs of them. Each
//! world ray is mapped into object space once (`Instance::world_to_object`,
//! level by level for a nested pair), prepared once, and traced against
//! every triangle of the mesh with the watertight test (`Triangle::hit`
//! with the `PreparedRay`) and the one-hit test (`Triangle::hit` with
//! `EdgeRule::OneHit`), as a renderer traces an instance.
//!
//! What is expected comes from the geometry, not from the code: a straight
//! ray from outside a closed surface crosses it an even number of times,
//! and at least twice when it passes through the inside; a ray from inside
//! crosses it an odd number of times. The one-hit test reports each
//! crossing once, so its count must have that parity; the watertight test
//! reports each crossing at least once. Three kinds of ray:
//!
//! - *through*: from outside, aimed at a vertex, an edge or a face point of
//!   the mesh (mapped into the world) and on through a point well inside;
//!   one-hit count even and at least 2 (exactly 2 for the convex mesh),
//!   watertight count at least 2. Fewer is a crack;
//! - *from inside*: from an interior point mapped exactly through the
//!   instance and rounded, towards a vertex, an edge point or anywhere;
//!   one-hit count odd (exactly 1 for the convex mesh), watertight count at
//!   least 1. Otherwise the ray leaked out;
//! - *any line*: from outside towards a vertex, an edge point or a point
//!   near the silhouette, grazing or missing; one-hit count even.
//!
//! Inside and outside are decided in exact arithmetic on the floats the
//! kernels see: the world ray's origin (and, for *through* rays, the point
//! that must be inside) is mapped back by the exact inverse of the exact
//! transform, and must be inside or outside by a wide margin in object
//! units, wider than the distance between the object ray and the exact
//! preimage of the world ray that `world_to_object_error` allows (mapped
//! back by the exact inverse too). Rays that do not meet those
//! preconditions (a tiny mesh far from the origin in `f32`, where rounding
//! the world origin moves it by more than the mesh's size) are skipped and
//! counted.
//!
//! 60 transforms per precision (a few seconds; each transform places both
//! meshes alone and inside a second instance, with 16 rays each), times
//! `RAYHIT_CASES`. Counts print with `--nocapture`. The long run, 20,000 transforms (about 2.5 million rays
//! per precision):
//!
//! ```sh
//! cargo test --release -p rayhit --test suite instance::meshes:: -- --ignored --nocapture
//! ```

use rayhit::exact::{self, AffineMap};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    EdgeRule, Instance, Intersect, PreparedRay, Ray, Scalar, Triangle, Vector,
    instance::InstanceRayError,
};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::{c, v};
use rayhit_testkit::mesh;
use rayhit_testkit::oracle::{R3, r, rv, to_f64};
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

fn norm(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

fn lerp(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]))
}

// ------------------------------------------------------------- the meshes

#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    /// The icosphere of radius 1 around the origin: every face plane is at
    /// least `0.9` from the origin (checked when built), so a point within
    /// `INSIDE_SPHERE` of the origin is inside by more than `0.3`.
    Sphere,
    /// The torus around the `z` axis, tube radius `TUBE` around the circle
    /// of radius 1 in the `z = 0` plane: every point of every triangle is
    /// at least `0.33` from that circle (checked when built), so a point
    /// within `INSIDE_TUBE` of it is inside by more than `0.08`.
    Torus,
}

const INSIDE_SPHERE: f64 = 0.6;
const TUBE: f32 = 0.4;
const INSIDE_TUBE: f64 = 0.25;

/// A closed mesh in precision `V`, with what the test needs to know about
/// its inside.
struct Solid<V> {
    shape: Shape,
    positions: Vec<V>,
    faces: Vec<[usize; 3]>,
    tris: Vec<Triangle<V>>,
    /// The largest distance of a vertex from the origin: every point of
    /// the mesh is within it, so a point `1.05` times farther is outside.
    outer: f64,
}

impl<V: Vector> Solid<V> {
    fn new(shape: Shape) -> Self {
        let m = match shape {
            Shape::Sphere => mesh::icosphere(Vec3::ZERO, 1.0, 2),
            Shape::Torus => mesh::torus(1.0, TUBE, 24, 12),
        };
        assert!(
            mesh::signed_volume(&m) > 0.0,
            "{shape:?}: wound inward, or not closed"
        );
        // The kit's `f32` vertices, exactly, in `V`.
        let positions: Vec<V> = m
            .positions
            .iter()
            .map(|p| v([f64::from(p.x), f64::from(p.y), f64::from(p.z)]))
            .collect();
        let faces: Vec<[usize; 3]> = m.indices.iter().map(|t| t.map(|k| k as usize)).collect();
        let tris: Vec<Triangle<V>> = faces
            .iter()
            .map(|f| Triangle::new(positions[f[0]], positions[f[1]], positions[f[2]]))
            .collect();
        let outer = positions.iter().map(|&p| norm(c(p))).fold(0.0, f64::max);
        let solid = Solid {
            shape,
            positions,
            faces,
            tris,
            outer,
        };
        solid.check_inside_margin();
        solid
    }

    /// Checks the margins the `Shape` docs state (the test's
    /// preconditions; `f64` rounding is far below the margins).
    fn check_inside_margin(&self) {
        for f in &self.faces {
            let [a, b, cc] = f.map(|k| c(self.positions[k]));
            match self.shape {
                Shape::Sphere => {
                    // The distance of the face's plane from the origin (on
                    // the side its outward normal points away from).
                    let d = -rayhit_testkit::mesh::plane_distance(a, b, cc, [0.0; 3]);
                    assert!(d > 0.9, "a sphere face at {d} from the centre");
                }
                Shape::Torus => {
                    // The distance from the circle is 1-Lipschitz: its
                    // minimum over the triangle is at least its minimum
                    // over a grid of spacing h minus h times the longest
                    // edge.
                    let n = 16;
                    let longest = [(a, b), (b, cc), (cc, a)]
                        .iter()
                        .map(|(p, q)| norm([0, 1, 2].map(|k| q[k] - p[k])))
                        .fold(0.0, f64::max);
                    let mut least = f64::INFINITY;
                    for i in 0..=n {
                        for j in 0..=n - i {
                            let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
                            let p =
                                [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]) + t * (cc[k] - a[k]));
                            least = least.min(tube_distance(p));
                        }
                    }
                    let bound = least - longest / n as f64;
                    assert!(bound > 0.33, "a torus triangle {bound} from the circle");
                }
            }
        }
    }

    /// Inside by the margin of the `Shape` docs.
    fn inside(&self, x: [f64; 3]) -> bool {
        match self.shape {
            Shape::Sphere => norm(x) < INSIDE_SPHERE,
            Shape::Torus => tube_distance(x) < INSIDE_TUBE,
        }
    }

    /// Outside by at least `0.05` of the mesh's size.
    fn outside(&self, x: [f64; 3]) -> bool {
        norm(x) > 1.05 * self.outer
    }

    /// A point well inside (within `0.5` of the centre, or `0.2` of the
    /// torus's circle).
    fn interior_point(&self, src: &mut Source) -> [f64; 3] {
        let d = src.direction();
        match self.shape {
            Shape::Sphere => d.map(|x| x * 0.5 * src.unit()),
            Shape::Torus => {
                let a = src.range(0.0, std::f64::consts::TAU);
                let s = 0.2 * src.unit();
                [a.cos() + d[0] * s, a.sin() + d[1] * s, d[2] * s]
            }
        }
    }

    /// A point of the mesh where cracks open: a vertex, a point of an edge
    /// (its middle one time in four) or, one time in four, a point inside
    /// a face. Computed in `f64` from the corners.
    fn surface_point(&self, src: &mut Source) -> [f64; 3] {
        let f = self.faces[src.index(self.faces.len())];
        let [a, b, cc] = f.map(|k| c(self.positions[k]));
        match src.below(4) {
            0 => [a, b, cc][src.index(3)],
            1 | 2 => {
                let s = if src.one_in(4) {
                    0.5
                } else {
                    src.range(0.02, 0.98)
                };
                let (p, q) = [(a, b), (b, cc), (cc, a)][src.index(3)];
                lerp(p, q, s)
            }
            _ => {
                let (s, t) = (src.unit(), src.unit());
                let (s, t) = if s + t > 1.0 {
                    (1.0 - s, 1.0 - t)
                } else {
                    (s, t)
                };
                [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]) + t * (cc[k] - a[k]))
            }
        }
    }
}

/// The distance from `x` to the circle of radius 1 around the `z` axis in
/// the `z = 0` plane.
fn tube_distance(x: [f64; 3]) -> f64 {
    let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
    ((rho - 1.0) * (rho - 1.0) + x[2] * x[2]).sqrt()
}

// ----------------------------------------------------------- placements

/// One placement of a mesh: the instances from the world inwards, the
/// exact object-to-world map of the whole path and its inverse, and `f64`
/// copies for aiming (never for judging).
struct Placement<V: Vector> {
    path: Vec<Instance<V>>,
    to_world: AffineMap,
    to_object: AffineMap,
    /// `|M^-1|` of the whole path, rounded up a little, for carrying the
    /// world-space ray bound into object space.
    inv_abs: [[f64; 3]; 3],
    aim_m: [[f64; 3]; 3],
    aim_t: [f64; 3],
}

impl<V: Vector> Placement<V> {
    fn new(path: Vec<Instance<V>>) -> Self {
        let levels: Vec<&Instance<V>> = path.iter().collect();
        let to_world = AffineMap::of_path(&levels).expect("a path of one or two instances");
        let to_object = to_world
            .inverse()
            .expect("the transforms drawn are not singular");
        let inv_abs = to_object
            .matrix
            .clone()
            .map(|row| row.map(|x| to_f64(&x).abs() * (1.0 + 1e-12)));
        let aim_m = to_world.matrix.clone().map(|row| row.map(|x| to_f64(&x)));
        let aim_t = to_world.translation.clone().map(|x| to_f64(&x));
        Placement {
            path,
            to_world,
            to_object,
            inv_abs,
            aim_m,
            aim_t,
        }
    }

    /// The world point of an object point, in `f64`, for aiming.
    fn aim(&self, x: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|i| (0..3).map(|j| self.aim_m[i][j] * x[j]).sum::<f64>() + self.aim_t[i])
    }

    /// The exact preimage of a world point, as `f64` (for the margins).
    fn preimage(&self, x: &R3) -> [f64; 3] {
        self.to_object.apply(x).map(|y| to_f64(&y))
    }

    /// The object ray, mapped level by level as a renderer does, and the
    /// world-space bound relating it to `world`.
    fn object_ray(&self, world: &Ray<V>) -> (Ray<V>, InstanceRayError<V>) {
        let mut ray = self.path[0].world_to_object(world);
        let mut err = self.path[0].world_to_object_error(world);
        for lvl in 1..self.path.len() {
            let inner = self.path[lvl].world_to_object_error(&ray);
            err = InstanceRayError::nested(&self.path[lvl - 1], &err, &inner);
            ray = self.path[lvl].world_to_object(&ray);
        }
        (ray, err)
    }

    /// The largest component of `|M^-1| e`: how far, in object units, a
    /// world-space error `e` can move a point.
    fn object_distance(&self, e: V) -> f64 {
        (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| self.inv_abs[i][j] * e[j].to_f64())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max)
            * (1.0 + 1e-12)
    }
}

// ----------------------------------------------------------------- rays

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Through,
    FromInside,
    AnyLine,
}

/// Counts for one mesh.
#[derive(Default, Debug)]
struct Tally {
    /// Rays checked, per kind.
    through: usize,
    inside: usize,
    any_line: usize,
    /// Rays whose preconditions did not hold (skipped).
    skipped: usize,
    /// A ray through the inside with fewer than two crossings or an odd
    /// count, or a ray from outside with an odd count.
    cracks: usize,
    /// A ray from inside with no watertight hit or an even one-hit count.
    leaks: usize,
    /// One-hit counts of the rays checked: 0, 1, 2, 3, 4 or more.
    counts: [usize; 5],
    /// The first failures, for the message.
    first: Vec<String>,
}

/// Traces `ray` (a world ray) through the placement against every
/// triangle and checks the count against `kind`'s expectation. `probe` is
/// the object-space parameter (in units of the world direction) of a point
/// that must be inside (`Through` only).
fn check_ray<V: Vector>(
    solid: &Solid<V>,
    place: &Placement<V>,
    world: Ray<V>,
    kind: Kind,
    probe: S<V>,
    tally: &mut Tally,
) {
    if !world.is_valid() {
        tally.skipped += 1;
        return;
    }
    // The exact world ray's origin and probe point, in object space.
    let (o, d) = (rv(world.origin), rv(world.dir));
    let x0 = place.preimage(&o);
    let pr = r(probe);
    let x1 = place.preimage(&[0, 1, 2].map(|k| &o[k] + &pr * &d[k]));
    // The object ray, mapped once, and how far it may be from the exact
    // preimage of the world ray (object units) at 0 and at the probe.
    let (object, err) = place.object_ray(&world);
    let slack = place
        .object_distance(err.at(S::<V>::ZERO))
        .max(place.object_distance(err.at(probe)));
    let ok = slack < 0.02
        && object.is_valid()
        && match kind {
            Kind::Through => solid.outside(x0) && solid.inside(x1),
            Kind::FromInside => solid.inside(x0),
            Kind::AnyLine => solid.outside(x0),
        };
    if !ok {
        tally.skipped += 1;
        return;
    }
    // Prepared once, every triangle tested with the one object ray.
    let prepared = PreparedRay::new(&object);
    let inf = S::<V>::INFINITY;
    let closed = solid
        .tris
        .iter()
        .filter(|t| t.hit(&prepared, inf).is_some())
        .count();
    let one = solid
        .tris
        .iter()
        .filter(|t| t.hit(&object, (inf, EdgeRule::OneHit)).is_some())
        .count();
    tally.counts[one.min(4)] += 1;
    let convex = solid.shape == Shape::Sphere;
    let (crack, leak) = match kind {
        Kind::Through => {
            tally.through += 1;
            let bad = one % 2 == 1 || one < 2 || closed < 2 || (convex && one != 2);
            (bad, false)
        }
        Kind::FromInside => {
            tally.inside += 1;
            (false, one % 2 == 0 || closed == 0 || (convex && one != 1))
        }
        Kind::AnyLine => {
            tally.any_line += 1;
            (one % 2 == 1, false)
        }
    };
    tally.cracks += usize::from(crack);
    tally.leaks += usize::from(leak);
    if (crack || leak) && tally.first.len() < 5 {
        tally.first.push(format!(
            "{kind:?} {:?}: one-hit {one}, watertight {closed}; world {world:?}, object {object:?}, path {:?}",
            solid.shape,
            place.path.iter().map(Instance::matrix_columns).collect::<Vec<_>>()
        ));
    }
}

/// The rays of one placement of one mesh.
fn rays<V: Vector>(solid: &Solid<V>, place: &Placement<V>, src: &mut Source, tally: &mut Tally) {
    let one = S::<V>::ONE;
    for k in 0..16 {
        match k % 4 {
            // Through: from outside at a surface point `e` and on through
            // an interior point `p`: the origin `e + s (e - p)`, the probe
            // (where `p` is) at `1 + 1/s` times the way to `e`. Far enough
            // out to be outside the bounding sphere: `s |e - p|` at least
            // 2.5 times its radius.
            0 | 1 => {
                let (e, p) = (solid.surface_point(src), solid.interior_point(src));
                let ep = [0, 1, 2].map(|k| e[k] - p[k]);
                let s = solid.outer * src.range(2.5, 8.0) / norm(ep);
                let origin = [0, 1, 2].map(|k| e[k] + s * ep[k]);
                let world = aimed_ray(place, origin, e);
                let probe = S::<V>::from_f64(1.0 + 1.0 / s);
                check_ray(solid, place, world, Kind::Through, probe, tally);
            }
            // From inside: the interior point mapped exactly and rounded,
            // towards a surface point or anywhere.
            2 => {
                let p: V = v(solid.interior_point(src));
                let image = exact::instance_point(&place.to_world, p).expect("finite");
                let origin = V::new(image[0].rounded, image[1].rounded, image[2].rounded);
                let to = if src.one_in(4) {
                    let d = src.direction();
                    place.aim([0, 1, 2].map(|k| c(p)[k] + d[k]))
                } else {
                    place.aim(solid.surface_point(src))
                };
                let dir = v([0, 1, 2].map(|k| to[k] - c(origin)[k]));
                check_ray(
                    solid,
                    place,
                    Ray::new(origin, dir),
                    Kind::FromInside,
                    one,
                    tally,
                );
            }
            // Any line from outside: at a surface point (through it, or
            // grazing at the silhouette), or at a point near the mesh.
            _ => {
                let dist = solid.outer * src.range(1.5, 6.0);
                let origin = src.direction().map(|x| x * dist);
                let target = if src.one_in(4) {
                    src.direction()
                        .map(|x| x * solid.outer * src.range(0.8, 1.2))
                } else {
                    solid.surface_point(src)
                };
                let world = aimed_ray(place, origin, target);
                check_ray(solid, place, world, Kind::AnyLine, one, tally);
            }
        }
    }
}

/// The world ray from the image of `from` towards the image of `to`
/// (object points), both mapped in `f64` and rounded: only an aim, the
/// checks use the exact preimage of the rounded ray.
fn aimed_ray<V: Vector>(place: &Placement<V>, from: [f64; 3], to: [f64; 3]) -> Ray<V> {
    let origin: V = v(place.aim(from));
    let to = place.aim(to);
    Ray::new(origin, v([0, 1, 2].map(|k| to[k] - c(origin)[k])))
}

fn run<V: Vector>(name: &str, seed: u64, n: usize) {
    let solids = [
        Solid::<V>::new(Shape::Sphere),
        Solid::<V>::new(Shape::Torus),
    ];
    let mut tallies = [Tally::default(), Tally::default()];
    let mut src = Source::seeded(seed);
    let draw = |src: &mut Source| {
        let (cols, t) = src.draw(&rayhit::strategies::transform::<V>())?;
        Instance::new(cols, t).ok()
    };
    let mut placed = 0;
    for _ in 0..n {
        let (Some(outer), Some(inner)) = (draw(&mut src), draw(&mut src)) else {
            continue;
        };
        for path in [vec![outer], vec![outer, inner]] {
            let place = Placement::new(path);
            placed += 1;
            for (solid, tally) in solids.iter().zip(&mut tallies) {
                rays(solid, &place, &mut src, tally);
            }
        }
    }
    for (solid, t) in solids.iter().zip(&tallies) {
        eprintln!(
            "{name} {:?} ({} triangles), {placed} placements: {} rays through the inside, {} from inside, \
             {} other lines from outside checked ({} skipped: preconditions); \
             cracks {}, leaks {}; one-hit counts 0/1/2/3/4+: {:?}",
            solid.shape,
            solid.tris.len(),
            t.through,
            t.inside,
            t.any_line,
            t.skipped,
            t.cracks,
            t.leaks,
            t.counts
        );
    }
    for (solid, t) in solids.iter().zip(&tallies) {
        // Enough rays of each kind passed the preconditions to mean
        // something (most do; f32 placements of tiny meshes far away do
        // not).
        assert!(
            t.through > 4 * n && t.inside > 2 * n && t.any_line > 2 * n,
            "{name} {:?}: too few rays checked: {t:?}",
            solid.shape
        );
        assert!(
            t.cracks == 0 && t.leaks == 0,
            "{name} {:?}: {} cracks, {} leaks; first: {:#?}",
            solid.shape,
            t.cracks,
            t.leaks,
            t.first
        );
    }
}

#[test]
fn instanced_meshes_are_closed_f32() {
    run::<Vec3>("f32", 0x3e54_0001, case_count(60));
}

#[test]
fn instanced_meshes_are_closed_f64() {
    run::<DVec3>("f64", 0x3e54_0002, case_count(60));
}

#[test]
#[ignore = "long: about 2.5 million rays per precision"]
fn instanced_meshes_are_closed_long_f32() {
    run::<Vec3>("f32", 0x3e54_1001, case_count(20_000));
}

#[test]
#[ignore = "long: about 2.5 million rays per precision"]
fn instanced_meshes_are_closed_long_f64() {
    run::<DVec3>("f64", 0x3e54_1002, case_count(20_000));
}
