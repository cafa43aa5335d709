//! `SurfacePoint::spawn_to` and `spawn_to_point`, the shadow-ray segment
//! between two surfaces (or to a point light), held to exact arithmetic in
//! both precisions.
//!
//! Scenes: a closed mesh from the test kit (an icosphere, or a torus),
//! a plane and a box, scaled by `1e-3` to `1e3` and translated by nothing
//! or by `1e4` to `1e5`, rounded once to the precision. Ends are real
//! hits of random rays: `Triangle::surface_point` (aimed at a face, an
//! edge or a corner of a mesh triangle), `Plane::surface_point`,
//! `Aabb::surface_point`.
//! Segments join two ends (for a quarter of the mesh ends, the other end
//! is on the same triangle or one sharing a corner with it), or an end
//! and a point light anywhere around it.
//!
//! - *Neither end is hit* (every segment returned): the exact crossing of
//!   the returned ray with the start surface's exact plane is at `t < 0`
//!   and with the target's at `t > 1`, in big rationals; and the interval
//!   kernels (`Triangle::hit`, `Plane::hit`, `Aabb::hit`'s entry face,
//!   over the returned interval) report neither end's surface.
//!   Self-hits are counted and must be zero. The mesh triangles sharing
//!   a corner with an end's triangle lie in other planes, which guarantee
//!   1 does not cover: a hit on one must be explained, by the segment
//!   between the points crossing its plane, or by an end lying within
//!   its move plus its error bound of that plane (the band guarantee 2
//!   leaves open); the counts of each print.
//! - *Occluders are found*: with `B_o` and `B_e` the exact moves of the
//!   ends (the documented bounds), a plane and a big triangle whose plane
//!   is just beyond `B_o` from the start point (or `B_e` from the target),
//!   crossing the segment, and a plane and a triangle through the
//!   midpoint; wherever exact arithmetic confirms the documented
//!   precondition (the ends on opposite sides, farther than `B_o` and
//!   `B_e` from the plane; for a triangle, from its own plane, its corners
//!   being rounded), `Plane::hit` and `Triangle::occluded` must
//!   report them. "Just beyond" is `B (1 + 2^-8)` snapped outward to
//!   the float grid for planes, and `B (1 + 2^-6)` plus the corners'
//!   rounding for triangles; the distances reached, in units of `B`, are
//!   printed.
//! - *Close ends*: point lights at `2^-4` to `2^8` times the start's error
//!   bound from it: whatever is returned is exactly clear of the start
//!   plane.
//! - *Bad input*: NaN and infinities in every field, coincident ends,
//!   overflowing differences, random bit patterns: `None` or a valid ray
//!   with `(0, 1]`, never a panic.
//!
//! 8000 segments per precision (about four seconds in the test profile;
//! counts print with `--nocapture`), times `RAYHIT_CASES`.
//! The long run, a million segments per precision (occluders on every
//! tenth), the two precisions on two threads: about five minutes on this
//! 2-core machine (50,000 per precision took 15 s in the test profile,
//! opt-level 2; not measured at a million):
//!
//! ```sh
//! cargo test --release -p rayhit --test suite surface::spawn_to:: -- --ignored --nocapture
//! ```

use crate::common::draw::signed;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, BoxFace, Intersect, Interval, Plane, Ray, Scalar, Surface as _, SurfacePoint, Triangle,
    Vector, ray_plane, ray_triangle,
};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::{c, v};
use rayhit_testkit::mesh;
use rayhit_testkit::oracle::{R, R3, cross, dot, rv, sub, to_f64};
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

// ------------------------------------------------------------ f64 helpers

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn fdot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn fcross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn lin(a: [f64; 3], s: f64, b: [f64; 3]) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = norm(a);
    a.map(|x| x / l)
}

fn random_unit(rng: &mut Pcg32) -> [f64; 3] {
    loop {
        let a = [signed(rng), signed(rng), signed(rng)];
        let l = norm(a);
        if l > 0.1 && l <= 1.0 {
            return a.map(|x| x / l);
        }
    }
}

/// Two unit vectors orthogonal to the unit `n` and to each other.
fn tangents(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = unit(fcross(n, helper));
    (t1, fcross(n, t1))
}

fn exact_norm2(a: &R3) -> R {
    dot(a, a)
}

fn rat(x: f64) -> R {
    R::from_float(x).expect("finite")
}

// ----------------------------------------------------------------- scenes

/// A surface an end lies on.
#[derive(Clone, Copy, Debug)]
enum Surface<V: Vector> {
    Tri(Triangle<V>),
    Plane(Plane<V>),
    Face(Aabb<V>, BoxFace),
}

impl<V: Vector> Surface<V> {
    /// The exact plane: a point on it and a normal.
    fn exact_plane(&self) -> (R3, R3) {
        match self {
            Surface::Tri(t) => {
                let (a, b, c) = (rv(t.a), rv(t.b), rv(t.c));
                let n = cross(&sub(&b, &a), &sub(&c, &a));
                (a, n)
            }
            Surface::Plane(p) => (rv(p.point), rv(p.normal)),
            Surface::Face(b, f) => {
                let (point, normal) = face_plane(b, *f);
                (rv(point), rv(normal))
            }
        }
    }

    /// Whether the interval kernels report this surface on the segment.
    fn reported(&self, ray: &Ray<V>, interval: Interval<S<V>>) -> bool {
        match self {
            Surface::Tri(t) => t.hit(ray, interval).is_some(),
            Surface::Plane(p) => p.hit(ray, interval).is_some(),
            Surface::Face(b, f) => {
                let (point, normal) = face_plane(b, *f);
                b.hit(ray, interval).is_some_and(|h| h.face == Some(*f))
                    || Plane::new(point, normal).hit(ray, interval).is_some()
            }
        }
    }
}

/// A point of a box face's plane and its outward normal.
fn face_plane<V: Vector>(b: &Aabb<V>, f: BoxFace) -> (V, V) {
    let k = f.axis();
    let at = f.plane(b);
    let point = V::new(
        if k == 0 { at } else { b.min.x() },
        if k == 1 { at } else { b.min.y() },
        if k == 2 { at } else { b.min.z() },
    );
    (point, f.normal())
}

#[derive(Clone, Copy, Debug)]
struct End<V: Vector> {
    sp: SurfacePoint<V>,
    surface: Surface<V>,
    /// The mesh triangle the end is on.
    tri: Option<usize>,
}

/// The kit's closed meshes in precision `V`: triangles and, per triangle,
/// the others sharing a corner with it.
struct Solid {
    positions: Vec<[f64; 3]>,
    faces: Vec<[usize; 3]>,
    neighbours: Vec<Vec<usize>>,
}

impl Solid {
    fn new(torus: bool) -> Self {
        let m = if torus {
            mesh::torus(1.0, 0.4, 16, 8)
        } else {
            mesh::icosphere(Vec3::ZERO, 1.0, 2)
        };
        let positions: Vec<[f64; 3]> = m
            .positions
            .iter()
            .map(|p| [f64::from(p.x), f64::from(p.y), f64::from(p.z)])
            .collect();
        let faces: Vec<[usize; 3]> = m.indices.iter().map(|t| t.map(|k| k as usize)).collect();
        let neighbours = (0..faces.len())
            .map(|i| {
                (0..faces.len())
                    .filter(|&j| j != i && faces[j].iter().any(|k| faces[i].contains(k)))
                    .collect()
            })
            .collect();
        Solid {
            positions,
            faces,
            neighbours,
        }
    }
}

struct Scene<V: Vector> {
    tris: Vec<Triangle<V>>,
    plane: Plane<V>,
    aabb: Aabb<V>,
    scale: f64,
    centre: [f64; 3],
}

fn scene<V: Vector>(rng: &mut Pcg32, solid: &Solid) -> Scene<V> {
    let scale = 10f64.powf(3.0 * signed(rng));
    let far = match rng.below(3) {
        0 => 0.0,
        _ => 10f64.powf(4.0 + signed(rng).abs()),
    };
    let centre = random_unit(rng).map(|x| x * far);
    let place = |p: [f64; 3]| v::<V>(lin(centre, scale, p));
    let corners: Vec<V> = solid.positions.iter().map(|&p| place(p)).collect();
    let tris = solid
        .faces
        .iter()
        .map(|f| Triangle::new(corners[f[0]], corners[f[1]], corners[f[2]]))
        .collect();
    let plane = Plane::new(
        place([signed(rng), signed(rng), signed(rng)]),
        v::<V>(random_unit(rng)),
    );
    let lo = [0, 1, 2].map(|_| -0.3 - signed(rng).abs());
    let hi = [0, 1, 2].map(|_| 0.3 + signed(rng).abs());
    let aabb = Aabb::new(place(lo), place(hi));
    Scene {
        tris,
        plane,
        aabb,
        scale,
        centre,
    }
}

/// A point of the triangle `tri` (interior, edge or corner).
fn on_triangle_f64(rng: &mut Pcg32, corners: [[f64; 3]; 3]) -> [f64; 3] {
    let (mut s, mut t) = (0.5 * (signed(rng) + 1.0), 0.5 * (signed(rng) + 1.0));
    if s + t > 1.0 {
        (s, t) = (1.0 - s, 1.0 - t);
    }
    match rng.below(6) {
        0 => corners[rng.below(3) as usize],
        1 => lin(
            corners[0],
            s,
            [0, 1, 2].map(|k| corners[1][k] - corners[0][k]),
        ),
        _ => {
            let ab = [0, 1, 2].map(|k| corners[1][k] - corners[0][k]);
            let ac = [0, 1, 2].map(|k| corners[2][k] - corners[0][k]);
            lin(lin(corners[0], s, ab), t, ac)
        }
    }
}

/// A ray aimed at `target` from a point `0.3` to `3.3` times `scale` away
/// from it along the direction `from` draws (after the distance).
fn aimed<V: Vector>(
    rng: &mut Pcg32,
    scale: f64,
    target: [f64; 3],
    from: impl FnOnce(&mut Pcg32) -> [f64; 3],
) -> Ray<V> {
    let distance = scale * (0.3 + 3.0 * signed(rng).abs());
    let origin = v::<V>(lin(target, distance, from(rng)));
    Ray::new(origin, v::<V>(target) - origin)
}

/// An end on the mesh triangle `i`, from a ray aimed at it.
fn end_on_triangle<V: Vector>(rng: &mut Pcg32, sc: &Scene<V>, i: usize) -> Option<End<V>> {
    let tri = sc.tris[i];
    let target = on_triangle_f64(rng, [c(tri.a), c(tri.b), c(tri.c)]);
    let ray = aimed::<V>(rng, sc.scale, target, random_unit);
    let hit = ray_triangle(&ray, &tri, S::<V>::INFINITY)?;
    Some(End {
        sp: tri.surface_point(&ray, &hit),
        surface: Surface::Tri(tri),
        tri: Some(i),
    })
}

fn end_on<V: Vector>(rng: &mut Pcg32, sc: &Scene<V>) -> Option<End<V>> {
    match rng.below(4) {
        0 | 1 => {
            let i = rng.below(sc.tris.len() as u32) as usize;
            end_on_triangle(rng, sc, i)
        }
        2 => {
            let pl = sc.plane;
            let n = unit(c(pl.normal));
            let (t1, t2) = tangents(n);
            let target = lin(
                lin(c(pl.point), sc.scale * signed(rng), t1),
                sc.scale * signed(rng),
                t2,
            );
            let ray = aimed::<V>(rng, sc.scale, target, random_unit);
            let t = ray_plane(&ray, &pl, S::<V>::INFINITY)?;
            Some(End {
                sp: pl.surface_point(&ray, &t),
                surface: Surface::Plane(pl),
                tri: None,
            })
        }
        _ => {
            let b = sc.aabb;
            let face = BoxFace::new(rng.below(3) as usize, rng.below(2) == 1)?;
            let k = face.axis();
            let (lo, hi) = (c(b.min), c(b.max));
            let mut target = [0, 1, 2].map(|j| lo[j] + (hi[j] - lo[j]) * 0.5 * (signed(rng) + 1.0));
            target[k] = face.plane(&b).to_f64();
            let n = c(face.normal::<V>());
            let out = lin(n, 0.8, random_unit(rng));
            if fdot(out, n) <= 0.05 {
                return None;
            }
            let ray = aimed::<V>(rng, sc.scale, target, |_| out);
            let hit = b.hit(&ray, S::<V>::INFINITY)?;
            let f = hit.face?;
            Some(End {
                sp: b.surface_point(&ray, &hit)?,
                surface: Surface::Face(b, f),
                tri: None,
            })
        }
    }
}

// ------------------------------------------------------------------ checks

#[derive(Default, Debug)]
struct Tally {
    segments: usize,
    returned: usize,
    /// Per kind of target: returned out of tried.
    lights: usize,
    lights_returned: usize,
    /// Exact crossings on the wrong side of an end (must be zero).
    exact_start: usize,
    exact_end: usize,
    /// Interval kernels reporting an end's surface (must be zero).
    self_start: usize,
    self_end: usize,
    /// Segments from or to a mesh end, and the ones hitting a triangle that
    /// shares a corner with the end's (not covered by the guarantee).
    mesh_ends: usize,
    neighbour_hits: usize,
    /// Of the neighbours hit: crossed by the segment between the points,
    /// or with an end within its move and error bound of its plane.
    neighbour_crossing: usize,
    neighbour_near: usize,
    occluders_placed: usize,
    occluders_found: usize,
    /// Occluders the documented precondition did not hold for after
    /// rounding (not asserted), and segments too short for any.
    occluders_skipped: usize,
    midpoint_placed: usize,
    midpoint_found: usize,
    /// The distance reached, in units of the bound: the smallest and the
    /// largest, and their sum for the mean.
    ratio_min: f64,
    ratio_max: f64,
    ratio_sum: f64,
    ratio_count: usize,
    /// The moves against the points' error bounds: `B_o / |e_p|` and
    /// `B_e / (|e_q| + u |q - p|)`, their largest.
    start_move_max: f64,
    end_move_max: f64,
    misses: Vec<String>,
}

impl Tally {
    fn ratio(&mut self, x: f64) {
        if self.ratio_min == 0.0 || x < self.ratio_min {
            self.ratio_min = x;
        }
        self.ratio_max = self.ratio_max.max(x);
        self.ratio_sum += x;
        self.ratio_count += 1;
    }
}

/// The exact crossing `t` of the ray with a plane (point, normal), or
/// `None` when parallel.
fn crossing_t(o: &R3, d: &R3, plane: &(R3, R3)) -> Option<R> {
    let den = dot(d, &plane.1);
    if den == R::from_integer(0.into()) {
        return None;
    }
    Some(dot(&sub(&plane.0, o), &plane.1) / den)
}

/// The checks of one returned segment from `a` to `b` (a surface end) or
/// to `light`.
#[allow(clippy::too_many_arguments)]
fn check<V: Vector>(
    rng: &mut Pcg32,
    sc: &Scene<V>,
    solid: &Solid,
    a: &End<V>,
    b: Option<&End<V>>,
    light: V,
    occluders: bool,
    tally: &mut Tally,
) {
    tally.segments += 1;
    if b.is_none() {
        tally.lights += 1;
    }
    let got = match b {
        Some(b) => a.sp.spawn_to(&b.sp),
        None => a.sp.spawn_to_point(light),
    };
    let Some((ray, interval)) = got else {
        return;
    };
    tally.returned += 1;
    if b.is_none() {
        tally.lights_returned += 1;
    }
    assert_eq!(interval, Interval::up_to(S::<V>::ONE).unwrap());
    assert!(ray.is_valid(), "{ray:?}");
    let (o, d) = (rv(ray.origin), rv(ray.dir));
    let zero = R::from_integer(0.into());
    let one = R::from_integer(1.into());
    // Guarantee 1, exactly.
    let start_t = crossing_t(&o, &d, &a.surface.exact_plane());
    if start_t.as_ref().is_none_or(|t| *t >= zero) {
        tally.exact_start += 1;
        tally.misses.push(format!(
            "start crossing {:?}: {a:?} -> {b:?} / {light:?}: {ray:?}",
            start_t.map(|t| to_f64(&t))
        ));
    }
    if a.surface.reported(&ray, interval) {
        tally.self_start += 1;
        tally.misses.push(format!(
            "start reported: {a:?} -> {b:?} / {light:?}: {ray:?}"
        ));
    }
    if let Some(b) = b {
        let end_t = crossing_t(&o, &d, &b.surface.exact_plane());
        if end_t.as_ref().is_none_or(|t| *t <= one) {
            tally.exact_end += 1;
            tally.misses.push(format!(
                "end crossing {:?}: {a:?} -> {b:?}: {ray:?}",
                end_t.map(|t| to_f64(&t))
            ));
        }
        if b.surface.reported(&ray, interval) {
            tally.self_end += 1;
            tally
                .misses
                .push(format!("end reported: {a:?} -> {b:?}: {ray:?}"));
        }
    }
    // The moves of the ends.
    let p = a.sp.point;
    let q = b.map_or(light, |b| b.sp.point);
    let (pr, qr) = (rv(p), rv(q));
    let e = [0, 1, 2].map(|k| &o[k] + &d[k]);
    let bo2 = exact_norm2(&sub(&o, &pr));
    let be2 = exact_norm2(&sub(&e, &qr));
    let (bo, be) = (to_f64(&bo2).sqrt(), to_f64(&be2).sqrt());
    // Triangles sharing a corner with an end's triangle: other planes
    // through or near the end, which guarantee 1 does not cover. A hit must
    // be explained: the segment between the points crosses that plane
    // (`p` and `q` strictly on opposite sides), or an end lies within its
    // move plus its error bound of it (the band guarantee 2 leaves open).
    for end in [Some(a), b].into_iter().flatten() {
        if let Some(i) = end.tri {
            tally.mesh_ends += 1;
            let mut hit = false;
            for &j in &solid.neighbours[i] {
                let tri = sc.tris[j];
                if tri.hit(&ray, interval).is_none() {
                    continue;
                }
                hit = true;
                let plane = Surface::Tri(tri).exact_plane();
                let hp = dot(&sub(&pr, &plane.0), &plane.1);
                let hq = dot(&sub(&qr, &plane.0), &plane.1);
                let n2 = to_f64(&exact_norm2(&plane.1));
                let crosses = (hp > zero && hq < zero) || (hp < zero && hq > zero);
                let near = |h: &R, bound: f64| to_f64(h).abs() <= bound * n2.sqrt();
                let ep = norm(c(a.sp.point_error));
                let eq = b.map_or(0.0, |b| norm(c(b.sp.point_error)));
                if crosses {
                    tally.neighbour_crossing += 1;
                } else if near(&hp, bo + ep) || near(&hq, be + eq) {
                    tally.neighbour_near += 1;
                } else {
                    tally.misses.push(format!(
                        "unexplained neighbour hit {tri:?}: {a:?} -> {b:?}: {ray:?}"
                    ));
                }
            }
            tally.neighbour_hits += usize::from(hit);
        }
    }
    // The moves, against the points' own error bounds.
    let u = S::<V>::UNIT_ROUNDOFF.to_f64();
    let len = norm([0, 1, 2].map(|k| c(q)[k] - c(p)[k]));
    // Against the documented sizes: the error bound plus a few ulps of
    // the point, and for the end the rounding of `dir`.
    let ulps = |x: V| 4.0 * u * norm(c(x));
    tally.start_move_max = tally
        .start_move_max
        .max(bo / (norm(c(a.sp.point_error)) + ulps(p)));
    let eq = b.map_or(0.0, |b| norm(c(b.sp.point_error)) + ulps(q));
    tally.end_move_max = tally.end_move_max.max(be / (eq + u * len));
    if occluders {
        place_occluders(rng, &ray, interval, p, q, (&bo2, &be2), (bo, be), tally);
    }
}

/// Occluders just beyond the moves from each end, and through the
/// midpoint; each must be reported wherever exact arithmetic confirms the
/// documented precondition.
#[allow(clippy::too_many_arguments)]
fn place_occluders<V: Vector>(
    rng: &mut Pcg32,
    ray: &Ray<V>,
    interval: Interval<S<V>>,
    p: V,
    q: V,
    (bo2, be2): (&R, &R),
    (bo, be): (f64, f64),
    tally: &mut Tally,
) {
    let (pf, qf) = (c(p), c(q));
    let (pr, qr) = (rv(p), rv(q));
    let w = [0, 1, 2].map(|k| qf[k] - pf[k]);
    let len = norm(w);
    if !(len > 8.0 * (bo + be)) {
        tally.occluders_skipped += 1;
        return;
    }
    let wu = unit(w);
    // The ends' largest coordinate: the scale of the corners' rounding.
    let big = pf.iter().chain(&qf).fold(0.0f64, |m, x| m.max(x.abs()));
    let eps_plane = rat(1.0 + 1.0 / 256.0);
    // The exact precondition for a plane through `at` with normal `n`: `p`
    // on the negative side farther than `B_o (1 + eps)`, `q` on the
    // positive side farther than `B_e`.
    let clear = |at: &R3, n: &R3, eps: &R| -> bool {
        let hp = dot(&sub(at, &pr), n);
        let hq = dot(&sub(&qr, at), n);
        let n2 = exact_norm2(n);
        hp > R::from_integer(0.into())
            && hq > R::from_integer(0.into())
            && &hp * &hp > bo2 * &n2 * eps * eps
            && &hq * &hq > be2 * &n2
    };
    let clear_end = |at: &R3, n: &R3, eps: &R| -> bool {
        let hp = dot(&sub(at, &pr), n);
        let hq = dot(&sub(&qr, at), n);
        let n2 = exact_norm2(n);
        hp > R::from_integer(0.into())
            && hq > R::from_integer(0.into())
            && &hp * &hp > bo2 * &n2
            && &hq * &hq > be2 * &n2 * eps * eps
    };
    for near_start in [true, false] {
        // A normal within 60 degrees of the segment.
        let tilt = random_unit(rng);
        let n = unit(lin(wu, 1.6 * signed(rng).abs(), tilt));
        let n = if fdot(n, wu) < 0.5 { wu } else { n };
        let nv: V = v(n);
        let nr = rv(nv);
        let nf = c(nv);
        let b = if near_start { bo } else { be };
        // The plane: through `p` (or `q`) moved along the largest axis of
        // the normal, snapped outward until exactly beyond the bound.
        let j = (0..3)
            .max_by(|&x, &y| nf[x].abs().total_cmp(&nf[y].abs()))
            .unwrap();
        let towards = if near_start { 1.0 } else { -1.0 } * nf[j].signum();
        let base = if near_start { pf } else { qf };
        let mut at = base;
        at[j] += towards * b * (1.0 + 1.0 / 256.0) * norm(nf) / nf[j].abs();
        let mut atv: V = v(at);
        let mut placed = false;
        for _ in 0..64 {
            let ar = rv(atv);
            let ok = if near_start {
                clear(&ar, &nr, &eps_plane)
            } else {
                clear_end(&ar, &nr, &eps_plane)
            };
            if ok {
                placed = true;
                break;
            }
            let mut x = c(atv);
            let step = S::<V>::from_f64(x[j]);
            x[j] = if towards > 0.0 {
                step.next_up().to_f64()
            } else {
                step.next_down().to_f64()
            };
            atv = v(x);
        }
        // Room on the other side is not guaranteed for short segments.
        if !placed {
            tally.occluders_skipped += 1;
        } else {
            let ar = rv(atv);
            let h = if near_start {
                dot(&sub(&ar, &pr), &nr)
            } else {
                dot(&sub(&qr, &ar), &nr)
            };
            if b > 0.0 {
                tally.ratio(to_f64(&h) / (b * norm(nf)));
            }
            tally.occluders_placed += 1;
            let plane = Plane::new(atv, nv);
            if plane.hit(ray, interval).is_some() {
                tally.occluders_found += 1;
            } else {
                tally
                    .misses
                    .push(format!("plane occluder missed: {plane:?} {ray:?}"));
            }
        }
        // The triangle: its plane `B (1 + 2^-6)` plus the corners'
        // rounding from the end, centred where `[p, q]` crosses it, its
        // size many times the documented edge margin.
        let margin_b = bo.max(be);
        let nu = unit(nf);
        let want = b * (1.0 + 1.0 / 64.0);
        let (hp, hq) = if near_start {
            (want, fdot(wu, nu) * len - want)
        } else {
            (fdot(wu, nu) * len - want, want)
        };
        if !(hq > 0.0 && hp > 0.0) {
            tally.occluders_skipped += 1;
            continue;
        }
        let edge = margin_b * (1.0 + len / (hp + hq - bo - be).max(f64::MIN_POSITIVE));
        let radius = 16.0 * edge + 64.0 * 2.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * big;
        let grid = 2.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * (big + radius);
        let dist = want + 2.0 * grid;
        let (hp, hq) = if near_start {
            (dist, fdot(wu, nu) * len - dist)
        } else {
            (fdot(wu, nu) * len - dist, dist)
        };
        if !(hq > 0.0 && hp > 0.0) {
            tally.occluders_skipped += 1;
            continue;
        }
        let x0 = lin(pf, hp / (hp + hq), w);
        let (t1, t2) = tangents(nu);
        let corner = |a: f64| {
            let (s, t) = (a.cos(), a.sin());
            v::<V>(lin(lin(x0, radius * s, t1), radius * t, t2))
        };
        let third = std::f64::consts::TAU / 3.0;
        let tri = Triangle::new(corner(0.0), corner(third), corner(2.0 * third));
        let (ta, tb, tc) = (rv(tri.a), rv(tri.b), rv(tri.c));
        let tn = cross(&sub(&tb, &ta), &sub(&tc, &ta));
        let ok = if near_start {
            clear(&ta, &tn, &rat(1.0))
        } else {
            clear_end(&ta, &tn, &rat(1.0))
        } || {
            // Wound the other way: the same plane with the normal flipped.
            let flipped = tn.clone().map(|x| -x);
            if near_start {
                clear(&ta, &flipped, &rat(1.0))
            } else {
                clear_end(&ta, &flipped, &rat(1.0))
            }
        };
        if !ok {
            tally.occluders_skipped += 1;
            continue;
        }
        tally.occluders_placed += 1;
        if b > 0.0 {
            let h = if near_start {
                dot(&sub(&ta, &pr), &tn)
            } else {
                dot(&sub(&qr, &ta), &tn)
            };
            tally.ratio(to_f64(&h).abs() / (b * to_f64(&exact_norm2(&tn)).sqrt()));
        }
        if tri.occluded(ray, interval) {
            tally.occluders_found += 1;
        } else {
            tally
                .misses
                .push(format!("triangle occluder missed: {tri:?} {ray:?}"));
        }
    }
    // Through the midpoint, any normal at least 20 degrees off the plane
    // containing the segment.
    let n = loop {
        let n = random_unit(rng);
        if fdot(n, wu).abs() > 0.35 {
            break if fdot(n, wu) > 0.0 { n } else { n.map(|x| -x) };
        }
    };
    let nv: V = v(n);
    let nr = rv(nv);
    let mid: V = v(lin(pf, 0.5, w));
    if clear(&rv(mid), &nr, &rat(1.0)) {
        let plane = Plane::new(mid, nv);
        let (t1, t2) = tangents(unit(c(nv)));
        // Large next to the corners' rounding too (`2u` of the largest
        // coordinate): far from the origin, a triangle a few segment
        // lengths wide is tilted out of the plane by rounding its corners,
        // and its own plane is what the precondition is about.
        let radius = 4.0 * len + 128.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * big;
        let corner = |a: f64| {
            let (s, t) = (a.cos(), a.sin());
            v::<V>(lin(lin(c(mid), radius * s, t1), radius * t, t2))
        };
        let third = std::f64::consts::TAU / 3.0;
        let tri = Triangle::new(corner(0.0), corner(third), corner(2.0 * third));
        let (ta, tb, tc) = (rv(tri.a), rv(tri.b), rv(tri.c));
        let tn = cross(&sub(&tb, &ta), &sub(&tc, &ta));
        let flipped = tn.clone().map(|x| -x);
        if !(clear(&ta, &tn, &rat(1.0)) || clear(&ta, &flipped, &rat(1.0))) {
            tally.occluders_skipped += 1;
            return;
        }
        tally.midpoint_placed += 1;
        let found = plane.hit(ray, interval).is_some() && tri.occluded(ray, interval);
        if found {
            tally.midpoint_found += 1;
        } else {
            tally.misses.push(format!(
                "midpoint occluder missed: {plane:?} {tri:?} {ray:?}"
            ));
        }
    } else {
        tally.occluders_skipped += 1;
    }
}

fn run<V: Vector>(seed: u64, n: usize, occluder_every: usize) -> Tally {
    let mut rng = Pcg32::new(seed);
    let solids = [Solid::new(false), Solid::new(true)];
    let mut tally = Tally::default();
    let mut sc = scene::<V>(&mut rng, &solids[0]);
    let mut which = 0;
    let mut k = 0;
    while tally.segments < n {
        if k % 16 == 0 {
            which = rng.below(2) as usize;
            sc = scene::<V>(&mut rng, &solids[which]);
        }
        k += 1;
        let solid = &solids[which];
        let Some(a) = end_on(&mut rng, &sc) else {
            continue;
        };
        let occluders = occluder_every > 0 && k % occluder_every == 0;
        match rng.below(4) {
            // A point light around the start, up to a few scene sizes away.
            0 => {
                let at = lin(
                    c(a.sp.point),
                    sc.scale * 4.0 * signed(&mut rng).abs(),
                    random_unit(&mut rng),
                );
                check(
                    &mut rng,
                    &sc,
                    solid,
                    &a,
                    None,
                    v::<V>(at),
                    occluders,
                    &mut tally,
                );
            }
            // Two ends on one triangle or on triangles sharing a corner.
            1 if a.tri.is_some() => {
                let i = a.tri.unwrap();
                let near = &solid.neighbours[i];
                let j = match rng.below(4) {
                    0 => i,
                    _ => near[rng.below(near.len() as u32) as usize],
                };
                if let Some(b) = end_on_triangle(&mut rng, &sc, j) {
                    check(
                        &mut rng,
                        &sc,
                        solid,
                        &a,
                        Some(&b),
                        V::ZERO,
                        occluders,
                        &mut tally,
                    );
                }
            }
            _ => {
                if let Some(b) = end_on(&mut rng, &sc) {
                    check(
                        &mut rng,
                        &sc,
                        solid,
                        &a,
                        Some(&b),
                        V::ZERO,
                        occluders,
                        &mut tally,
                    );
                }
            }
        }
        let _ = sc.centre;
    }
    tally
}

fn report_and_assert(name: &str, t: &Tally) {
    println!(
        "{name}: {} segments ({} to point lights), {} returned ({} to lights); \
         exact wrong side: start {} end {}; kernels' self-hits: start {} end {}; \
         mesh ends {} with a neighbour hit {} (crossing {}, near an end {}); occluders placed {} found {}, \
         midpoint placed {} found {}, skipped {}; distance / bound min {:.4} mean {:.4} \
         max {:.4}; largest B_o/|e_p| {:.3}, B_e/(|e_q| + u|q - p|) {:.3}",
        t.segments,
        t.lights,
        t.returned,
        t.lights_returned,
        t.exact_start,
        t.exact_end,
        t.self_start,
        t.self_end,
        t.mesh_ends,
        t.neighbour_hits,
        t.neighbour_crossing,
        t.neighbour_near,
        t.occluders_placed,
        t.occluders_found,
        t.midpoint_placed,
        t.midpoint_found,
        t.occluders_skipped,
        t.ratio_min,
        t.ratio_sum / t.ratio_count.max(1) as f64,
        t.ratio_max,
        t.start_move_max,
        t.end_move_max,
    );
    for m in t.misses.iter().take(5) {
        println!("  {m}");
    }
    assert!(
        t.misses.is_empty(),
        "{name}: {} failures, first: {:?}",
        t.misses.len(),
        t.misses.first()
    );
    // Enough of every kind was exercised.
    assert!(
        t.returned * 2 > t.segments,
        "{name}: too few segments returned"
    );
    assert!(t.lights_returned * 2 > t.lights, "{name}: too few lights");
    assert!(t.occluders_placed > 0 && t.midpoint_placed > 0);
}

#[test]
fn segments_f32() {
    let t = run::<Vec3>(0x5ba3_0001, case_count(8000), 3);
    report_and_assert("f32", &t);
}

#[test]
fn segments_f64() {
    let t = run::<DVec3>(0x5ba3_0002, case_count(8000), 3);
    report_and_assert("f64", &t);
}

#[test]
#[ignore = "long run: a million segments per precision"]
fn segments_long() {
    let n = case_count(1_000_000);
    std::thread::scope(|s| {
        let a = s.spawn(|| run::<Vec3>(0x5ba3_1001, n, 10));
        let b = s.spawn(|| run::<DVec3>(0x5ba3_1002, n, 10));
        report_and_assert("f32 long", &a.join().unwrap());
        report_and_assert("f64 long", &b.join().unwrap());
    });
}

// ------------------------------------------------------------- close ends

/// Point lights at `2^-4` to `2^8` times the start's error bound from it,
/// in every direction: whatever comes back is exactly clear of the start
/// plane, and lights well beyond the bound (and not near the plane) do
/// come back.
fn close_lights<V: Vector>(seed: u64) {
    let mut rng = Pcg32::new(seed);
    let solid = Solid::new(false);
    let (mut tried, mut returned, mut far_clear, mut far_returned) = (0, 0, 0, 0);
    for k in 0..case_count(1500) {
        let sc = scene::<V>(&mut rng, &solid);
        let Some(a) = end_on(&mut rng, &sc) else {
            continue;
        };
        let u = S::<V>::UNIT_ROUNDOFF.to_f64();
        let bound = norm(c(a.sp.point_error)) + 4.0 * u * norm(c(a.sp.point));
        let power = (k % 13) as i32 - 4;
        let dir = random_unit(&mut rng);
        let light: V = v(lin(c(a.sp.point), bound * 2f64.powi(power), dir));
        tried += 1;
        // Far from the plane in units of the bound, and steep: returned.
        let n = unit(c(a.sp.normal));
        let far = power >= 6 && fdot(n, dir).abs() > 0.5;
        far_clear += usize::from(far);
        let Some((ray, _)) = a.sp.spawn_to_point(light) else {
            continue;
        };
        returned += 1;
        far_returned += usize::from(far);
        let (o, d) = (rv(ray.origin), rv(ray.dir));
        let t = crossing_t(&o, &d, &a.surface.exact_plane());
        assert!(
            t.is_some_and(|t| t < R::from_integer(0.into())),
            "{a:?} {light:?} {ray:?}"
        );
    }
    println!(
        "close lights {}: {tried} tried, {returned} returned, far and steep {far_clear}, of them returned {far_returned}",
        std::any::type_name::<V>()
    );
    assert!(returned > 0 && far_returned == far_clear);
}

#[test]
fn close_lights_f32() {
    close_lights::<Vec3>(0x5ba3_0003);
}

#[test]
fn close_lights_f64() {
    close_lights::<DVec3>(0x5ba3_0004);
}

// --------------------------------------------------------------- bad input

fn bad_input<V: Vector>() {
    let tri = Triangle::new(
        v::<V>([-1.0, 0.0, -1.0]),
        v::<V>([0.0, 0.0, 1.0]),
        v::<V>([1.0, 0.0, -1.0]),
    );
    let ray = Ray::new(v::<V>([0.1, 2.0, 0.0]), v::<V>([0.0, -1.0, -0.1]));
    let hit = ray_triangle(&ray, &tri, S::<V>::INFINITY).unwrap();
    let good = tri.surface_point(&ray, &hit);
    let above = SurfacePoint {
        point: v::<V>([0.3, 2.0, 0.1]),
        point_error: V::ZERO,
        normal: v::<V>([0.0, -1.0, 0.0]),
        normal_error: V::ZERO,
    };
    let light = v::<V>([0.2, 3.0, 0.4]);
    assert!(good.spawn_to(&above).is_some());
    assert!(good.spawn_to_point(light).is_some());
    let specials = [S::<V>::NAN, S::<V>::INFINITY, -S::<V>::INFINITY];
    let with = |x: V, k: usize, s: S<V>| {
        V::new(
            if k == 0 { s } else { x.x() },
            if k == 1 { s } else { x.y() },
            if k == 2 { s } else { x.z() },
        )
    };
    for s in specials {
        for k in 0..3 {
            for field in 0..4 {
                let mut bad = good;
                match field {
                    0 => bad.point = with(bad.point, k, s),
                    1 => bad.point_error = with(bad.point_error, k, s),
                    2 => bad.normal = with(bad.normal, k, s),
                    _ => bad.normal_error = with(bad.normal_error, k, s),
                }
                assert!(bad.spawn_to(&above).is_none(), "{bad:?}");
                assert!(above.spawn_to(&bad).is_none(), "{bad:?}");
                assert!(bad.spawn_to_point(light).is_none(), "{bad:?}");
            }
            assert!(good.spawn_to_point(with(light, k, s)).is_none());
        }
    }
    // Coincident ends; a zero normal at either end.
    assert!(good.spawn_to(&good).is_none());
    assert!(good.spawn_to_point(good.point).is_none());
    let flat = SurfacePoint {
        normal: V::ZERO,
        ..above
    };
    assert!(good.spawn_to(&flat).is_none() && flat.spawn_to(&good).is_none());
    assert!(flat.spawn_to_point(light).is_none());
    // Differences that overflow.
    let max = S::<V>::MAX;
    let huge = SurfacePoint {
        point: V::new(max, max, max),
        ..above
    };
    let tiny = SurfacePoint {
        point: V::new(-max, -max, -max),
        normal: v::<V>([0.0, 1.0, 0.0]),
        ..above
    };
    for (x, y) in [(&huge, &tiny), (&tiny, &huge)] {
        if let Some((r, i)) = x.spawn_to(y) {
            assert!(r.is_valid() && i == Interval::up_to(S::<V>::ONE).unwrap());
        }
    }
    assert!(huge.spawn_to_point(V::new(-max, -max, -max)).is_none());
    // Random bit patterns: `None` or a valid ray, never a panic.
    let mut rng = Pcg32::new(0x5ba3_0005);
    let any = |rng: &mut Pcg32| {
        let bits = (u64::from(rng.next_u32()) << 32) | u64::from(rng.next_u32());
        let x = if S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10 {
            f64::from_bits(bits)
        } else {
            f64::from(f32::from_bits(bits as u32))
        };
        S::<V>::from_f64(x)
    };
    let vec = |rng: &mut Pcg32| V::new(any(rng), any(rng), any(rng));
    for _ in 0..case_count(20_000) {
        let x = SurfacePoint {
            point: vec(&mut rng),
            point_error: vec(&mut rng),
            normal: vec(&mut rng),
            normal_error: vec(&mut rng),
        };
        let y = SurfacePoint {
            point: vec(&mut rng),
            ..above
        };
        for got in [
            x.spawn_to(&y),
            y.spawn_to(&x),
            x.spawn_to_point(vec(&mut rng)),
        ]
        .into_iter()
        .flatten()
        {
            assert!(got.0.is_valid() && got.1 == Interval::up_to(S::<V>::ONE).unwrap());
        }
    }
}

#[test]
fn bad_input_f32() {
    bad_input::<Vec3>();
}

#[test]
fn bad_input_f64() {
    bad_input::<DVec3>();
}
