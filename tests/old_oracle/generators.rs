//! Case generators shared by the oracle suite and the reference corpus: each
//! draws, from a seeded [`Pcg32`], a shape and a ray aimed at what breaks
//! textbook code. Values are drawn in `f64` and rounded once to the
//! precision of `V`.
#![allow(dead_code)]

use rayhit::{Aabb, Plane, Ray, Scalar, Triangle, Vector};

use super::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// A point of precision `V` from `f64` coordinates (rounded once each).
pub fn v<V: Vector>(p: [f64; 3]) -> V {
    V::new(
        S::<V>::from_f64(p[0]),
        S::<V>::from_f64(p[1]),
        S::<V>::from_f64(p[2]),
    )
}

/// One box case: the box, the ray and `t_max`.
pub type BoxCase<V> = (Aabb<V>, Ray<V>, S<V>);

/// A box on a dyadic grid (multiples of 2^-6 in [-64, 64]): coordinates
/// with few significant bits, so rays built from them can pass exactly
/// through edges and corners.
pub fn grid_box(rng: &mut Pcg32) -> ([f64; 3], [f64; 3]) {
    let g = |rng: &mut Pcg32| f64::from(rng.below(8192) as i32 - 4096) / 64.0;
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for k in 0..3 {
        let (a, b) = (g(rng), g(rng));
        (lo[k], hi[k]) = if rng.one_in(8) {
            (a, a)
        } else {
            (a.min(b), a.max(b))
        };
    }
    (lo, hi)
}

/// A random valid box: centre in [-100, 100]^3, half extents 2^-4 to 2^4,
/// zero on an axis one time in eight; `scale` multiplies everything.
pub fn random_box(rng: &mut Pcg32, scale: f64, offset: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for k in 0..3 {
        let c = rng.range(-100.0, 100.0);
        let h = if rng.one_in(8) {
            0.0
        } else {
            rng.log2_range(-4.0, 4.0)
        };
        lo[k] = (c - h) * scale + offset[k];
        hi[k] = (c + h) * scale + offset[k];
    }
    (lo, hi)
}

/// The box rounded outward to precision `V` (so it stays valid).
pub fn to_box<V: Vector>(lo: [f64; 3], hi: [f64; 3]) -> Aabb<V> {
    let down = |x: f64| {
        let y = S::<V>::from_f64(x);
        if y.to_f64() > x { y.next_down() } else { y }
    };
    let up = |x: f64| {
        let y = S::<V>::from_f64(x);
        if y.to_f64() < x { y.next_up() } else { y }
    };
    Aabb::new(
        V::new(down(lo[0]), down(lo[1]), down(lo[2])),
        V::new(up(hi[0]), up(hi[1]), up(hi[2])),
    )
}

pub fn random_t_max<V: Vector>(rng: &mut Pcg32, typical: f64) -> S<V> {
    if rng.one_in(2) {
        S::<V>::INFINITY
    } else {
        S::<V>::from_f64(rng.range(0.0, 2.0 * typical))
    }
}

/// A direction: random (most), axis-parallel, or with a zero component.
pub fn random_dir(rng: &mut Pcg32) -> [f64; 3] {
    let mut d = rng.direction();
    match rng.below(8) {
        0 => {
            let k = rng.below(3) as usize;
            let s = if d[k] < 0.0 { -1.0 } else { 1.0 };
            d = [0.0; 3];
            d[k] = s;
        }
        1 => d[rng.below(3) as usize] = if rng.one_in(2) { 0.0 } else { -0.0 },
        _ => {}
    }
    let s = rng.log2_range(-4.0, 4.0);
    [d[0] * s, d[1] * s, d[2] * s]
}

/// A ray aimed at `target` from `s` direction-lengths back.
pub fn aimed<V: Vector>(target: [f64; 3], dir: [f64; 3], s: f64) -> Ray<V> {
    let d: V = v(dir);
    let o = [
        target[0] - d.x().to_f64() * s,
        target[1] - d.y().to_f64() * s,
        target[2] - d.z().to_f64() * s,
    ];
    Ray::new(v(o), d)
}

pub fn box_target(rng: &mut Pcg32, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
    let mut t = [0.0; 3];
    for k in 0..3 {
        t[k] = lo[k] + (hi[k] - lo[k]) * rng.range(-0.5, 1.5);
    }
    t
}

pub fn gen_box_uniform<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (lo, hi) = random_box(rng, 1.0, [0.0; 3]);
    let s = rng.log2_range(-4.0, 6.0);
    let ray = aimed(box_target(rng, lo, hi), random_dir(rng), s);
    (to_box(lo, hi), ray, random_t_max::<V>(rng, s))
}

/// Rays through box edges and corners, exactly: the box, the target (a
/// corner, or a point of an edge) and the ray are all on dyadic grids with
/// few enough bits that every coordinate and the origin `target - m dir`
/// are exact in `f32`, so exact arithmetic says the ray touches the edge.
pub fn gen_box_edges<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (lo, hi) = grid_box(rng);
    let mut target = [0.0; 3];
    let free = rng.below(4) as usize; // 3: a corner, else the free axis of an edge
    for k in 0..3 {
        target[k] = if k == free {
            lo[k] + (hi[k] - lo[k]) * f64::from(rng.below(5)) / 4.0
        } else if rng.one_in(2) {
            lo[k]
        } else {
            hi[k]
        };
    }
    let dir = loop {
        let d = [0, 1, 2].map(|_| f64::from(rng.below(17) as i32 - 8) / 8.0);
        if d != [0.0; 3] {
            break d;
        }
    };
    let m = f64::from(rng.below(64) + 1) / 4.0;
    let origin = [0, 1, 2].map(|k| target[k] - m * dir[k]);
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(origin), v(dir)),
        S::<V>::INFINITY,
    )
}

/// Axis-parallel rays whose origin lies exactly on a slab plane of another
/// axis (the `0 * inf = NaN` case of the slab test).
pub fn gen_box_on_slab<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (lo, hi) = grid_box(rng);
    let k = rng.below(3) as usize;
    let mut dir = [0.0; 3];
    dir[k] = if rng.one_in(2) { 1.0 } else { -1.0 };
    for (j, c) in dir.iter_mut().enumerate() {
        if j != k && rng.one_in(2) {
            *c = -0.0;
        }
    }
    let mut o = box_target(rng, lo, hi);
    let j = (k + 1 + rng.below(2) as usize) % 3;
    o[j] = if rng.one_in(2) { lo[j] } else { hi[j] };
    o[k] = rng.range(-200.0, 200.0);
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(o), v(dir)),
        random_t_max::<V>(rng, 200.0),
    )
}

/// Rays lying in a face plane: the direction's component on that axis is
/// `+0.0` or `-0.0` and the origin is on the plane.
pub fn gen_box_in_face<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (lo, hi) = grid_box(rng);
    let j = rng.below(3) as usize;
    let mut dir = random_dir(rng);
    dir[j] = if rng.one_in(2) { 0.0 } else { -0.0 };
    if dir == [0.0; 3] {
        dir[(j + 1) % 3] = 1.0;
    }
    let mut target = box_target(rng, lo, hi);
    target[j] = if rng.one_in(2) { lo[j] } else { hi[j] };
    let s = rng.log2_range(-2.0, 6.0);
    let mut ray: Ray<V> = aimed(target, dir, s);
    // Put the origin exactly on the face plane (aiming rounded nothing on
    // axis j, as dir_j is zero, but be explicit).
    let mut o = [ray.origin.x(), ray.origin.y(), ray.origin.z()];
    o[j] = S::<V>::from_f64(target[j]);
    ray.origin = V::new(o[0], o[1], o[2]);
    (Aabb::new(v(lo), v(hi)), ray, S::<V>::INFINITY)
}

/// Grazing rays: nearly parallel to a face (one direction component 2^-8
/// to 2^-24 of the others), passing near an edge.
pub fn gen_box_grazing<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (lo, hi) = random_box(rng, 1.0, [0.0; 3]);
    let j = rng.below(3) as usize;
    let mut dir = rng.direction();
    dir[j] = dir[j].signum() * rng.log2_range(-24.0, -8.0);
    let mut target = box_target(rng, lo, hi);
    target[j] = if rng.one_in(2) { lo[j] } else { hi[j] };
    let k = (j + 1) % 3;
    target[k] = if rng.one_in(2) { lo[k] } else { hi[k] };
    let s = rng.log2_range(-2.0, 6.0);
    (to_box(lo, hi), aimed(target, dir, s), S::<V>::INFINITY)
}

/// Tiny direction components: 1e-30, subnormal, `+-0.0`, mixed with
/// ordinary ones; origins near or on slab planes, one subnormal off a plane
/// at zero.
pub fn gen_box_tiny_dirs<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let (mut lo, mut hi) = grid_box(rng);
    let tiny = S::<V>::TINY.to_f64();
    let choices = [1e-30, -1e-30, 37.0 * tiny, -tiny, 0.0, -0.0, 1e-20];
    let mut dir = rng.direction();
    for c in &mut dir {
        if rng.one_in(2) {
            *c = choices[rng.below(choices.len() as u32) as usize];
        }
    }
    if dir.iter().all(|&d| d == 0.0) {
        dir[0] = 1.0;
    }
    let mut o = box_target(rng, lo, hi);
    for k in 0..3 {
        match rng.below(4) {
            0 => o[k] = lo[k],
            1 => o[k] = hi[k],
            2 => {
                // A plane at zero and an origin one subnormal away.
                lo[k] = 0.0;
                hi[k] = hi[k].max(0.0);
                o[k] = if rng.one_in(2) { -tiny } else { tiny };
            }
            _ => {}
        }
    }
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(o), v(dir)),
        random_t_max::<V>(rng, 100.0),
    )
}

/// The uniform cases moved 10^3 to 10^7 away from the origin.
pub fn gen_box_far<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let dist = 10f64.powf(rng.range(3.0, 7.0));
    let d = rng.direction();
    let offset = d.map(|x| x * dist);
    let (lo, hi) = random_box(rng, 1.0, offset);
    let s = rng.log2_range(-4.0, 6.0);
    (
        to_box(lo, hi),
        aimed(box_target(rng, lo, hi), random_dir(rng), s),
        S::<V>::INFINITY,
    )
}

/// Tiny (1e-6) and huge (1e6) boxes, everything scaled alike.
pub fn gen_box_scaled<V: Vector>(rng: &mut Pcg32) -> BoxCase<V> {
    let scale = if rng.one_in(2) { 1e-6 } else { 1e6 };
    let (lo, hi) = random_box(rng, scale, [0.0; 3]);
    let s = rng.log2_range(-4.0, 6.0);
    let dir = random_dir(rng).map(|x| x * scale);
    (
        to_box(lo, hi),
        aimed(box_target(rng, lo, hi), dir, s),
        S::<V>::INFINITY,
    )
}

pub type TriCase<V> = (Triangle<V>, Ray<V>, S<V>);

pub fn point_on(t: &[[f64; 3]; 3], u: f64, w: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| t[0][k] + u * (t[1][k] - t[0][k]) + w * (t[2][k] - t[0][k]))
}

pub fn to_tri<V: Vector>(t: [[f64; 3]; 3]) -> Triangle<V> {
    Triangle::new(v(t[0]), v(t[1]), v(t[2]))
}

/// A random triangle: centre in [-64, 64]^3 (times `scale`, plus
/// `offset`), corners 2^-3 to 2^3 away in random directions.
pub fn random_tri(rng: &mut Pcg32, scale: f64, offset: [f64; 3]) -> [[f64; 3]; 3] {
    let c = [0, 1, 2].map(|_| rng.range(-64.0, 64.0));
    [0, 1, 2].map(|_| {
        let d = rng.direction();
        let l = rng.log2_range(-3.0, 3.0);
        [0, 1, 2].map(|k| (c[k] + d[k] * l) * scale + offset[k])
    })
}

pub fn tri_target(rng: &mut Pcg32, t: &[[f64; 3]; 3]) -> [f64; 3] {
    match rng.below(8) {
        0 => {
            let s = rng.unit();
            match rng.below(3) {
                0 => point_on(t, s, 0.0),
                1 => point_on(t, 0.0, s),
                _ => point_on(t, s, 1.0 - s),
            }
        }
        1 => t[rng.below(3) as usize],
        _ => point_on(t, rng.range(-0.25, 1.0), rng.range(-0.25, 1.0)),
    }
}

pub fn gen_tri_uniform<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let t = random_tri(rng, 1.0, [0.0; 3]);
    let s = rng.log2_range(-4.0, 6.0);
    let ray = aimed(tri_target(rng, &t), random_dir(rng), s);
    (to_tri(t), ray, random_t_max::<V>(rng, s))
}

/// Rays exactly through edges and corners: dyadic corners and rays, as for
/// the box edges.
pub fn gen_tri_edges<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let g = |rng: &mut Pcg32| f64::from(rng.below(8192) as i32 - 4096) / 64.0;
    let t = [0, 1, 2].map(|_| [g(rng), g(rng), g(rng)]);
    let target = match rng.below(2) {
        0 => t[rng.below(3) as usize],
        _ => {
            let (a, b) = (rng.below(3) as usize, rng.below(3) as usize);
            let s = f64::from(rng.below(5)) / 4.0;
            [0, 1, 2].map(|k| t[a][k] + s * (t[b][k] - t[a][k]))
        }
    };
    let dir = loop {
        let d = [0, 1, 2].map(|_| f64::from(rng.below(17) as i32 - 8) / 8.0);
        if d != [0.0; 3] {
            break d;
        }
    };
    let m = f64::from(rng.below(64) + 1) / 4.0;
    let origin = [0, 1, 2].map(|k| target[k] - m * dir[k]);
    (to_tri(t), Ray::new(v(origin), v(dir)), S::<V>::INFINITY)
}

/// Long thin triangles: the third corner within 2^-4 to 2^-20 of the
/// first edge's line (relative to its length).
pub fn gen_tri_thin<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let mut t = random_tri(rng, 1.0, [0.0; 3]);
    let along = rng.unit();
    let across = rng.log2_range(-20.0, -4.0);
    let side = rng.direction();
    let e = [0, 1, 2].map(|k| t[1][k] - t[0][k]);
    let len = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
    t[2] = [0, 1, 2].map(|k| t[0][k] + along * e[k] + across * len * side[k]);
    let s = rng.log2_range(-4.0, 6.0);
    let ray = aimed(tri_target(rng, &t), random_dir(rng), s);
    (to_tri(t), ray, S::<V>::INFINITY)
}

pub fn gen_tri_far<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let dist = 10f64.powf(rng.range(3.0, 7.0));
    let offset = rng.direction().map(|x| x * dist);
    let t = random_tri(rng, 1.0, offset);
    let s = rng.log2_range(-4.0, 6.0);
    (
        to_tri(t),
        aimed(tri_target(rng, &t), random_dir(rng), s),
        S::<V>::INFINITY,
    )
}

pub fn gen_tri_scaled<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let scale = if rng.one_in(2) { 1e-6 } else { 1e6 };
    let t = random_tri(rng, scale, [0.0; 3]);
    let s = rng.log2_range(-4.0, 6.0);
    let dir = random_dir(rng).map(|x| x * scale);
    (
        to_tri(t),
        aimed(tri_target(rng, &t), dir, s),
        S::<V>::INFINITY,
    )
}

/// Grazing rays: within 2^-8 to 2^-24 radians of the triangle's plane.
pub fn gen_tri_grazing<V: Vector>(rng: &mut Pcg32) -> TriCase<V> {
    let t = random_tri(rng, 1.0, [0.0; 3]);
    let e1 = [0, 1, 2].map(|k| t[1][k] - t[0][k]);
    let e2 = [0, 1, 2].map(|k| t[2][k] - t[0][k]);
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let nl = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let d = rng.direction();
    let dn = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / nl;
    let tilt = rng.log2_range(-24.0, -8.0) * if rng.one_in(2) { 1.0 } else { -1.0 };
    let dir = [0, 1, 2].map(|k| d[k] - (dn - tilt) * n[k] / nl);
    let s = rng.log2_range(-2.0, 4.0);
    (
        to_tri(t),
        aimed(tri_target(rng, &t), dir, s),
        S::<V>::INFINITY,
    )
}

/// A plane (through a point in [-64, 64]^3, a quarter of the time 10^3 to
/// 10^7 away, given by its coefficients a quarter of the time) and a ray
/// aimed at a point of it, grazing (within 2^-8 to 2^-24 radians) a quarter
/// of the time.
pub fn gen_plane<V: Vector>(rng: &mut Pcg32) -> (Plane<V>, Ray<V>, S<V>) {
    let far = rng.one_in(4);
    let offset = if far {
        rng.direction().map(|x| x * 10f64.powf(rng.range(3.0, 7.0)))
    } else {
        [0.0; 3]
    };
    let p = [0, 1, 2].map(|k| rng.range(-64.0, 64.0) + offset[k]);
    let nrm = random_dir(rng);
    let plane = if rng.one_in(4) {
        // A x + B y + C z + D = 0 through p.
        let d = -(nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2]);
        let c = |x: f64| S::<V>::from_f64(x);
        Plane::from_coefficients(c(nrm[0]), c(nrm[1]), c(nrm[2]), c(d))
    } else {
        Plane::new(v(p), v(nrm))
    };
    let mut dir = random_dir(rng);
    if rng.one_in(4) {
        // Grazing: tilt the direction to within 2^-8..2^-24 of the plane.
        let l2 = nrm.iter().map(|x| x * x).sum::<f64>();
        let dn = dir.iter().zip(nrm).map(|(a, b)| a * b).sum::<f64>();
        let tilt = rng.log2_range(-24.0, -8.0) * l2.sqrt();
        dir = [0, 1, 2].map(|k| dir[k] - (dn - tilt) * nrm[k] / l2);
    }
    let target = [0, 1, 2].map(|k| p[k] + rng.range(-64.0, 64.0));
    let s = rng.log2_range(-4.0, 6.0);
    let ray: Ray<V> = aimed(target, dir, s);
    let t_max = random_t_max::<V>(rng, s * 2.0);
    (plane, ray, t_max)
}

/// A named generator with its seed.
pub type Generator<C> = (&'static str, u64, fn(&mut Pcg32) -> C);

/// Every box generator.
pub fn box_generators<V: Vector>() -> [Generator<BoxCase<V>>; 8] {
    [
        ("box uniform", 1, gen_box_uniform::<V>),
        ("box edges, corners", 2, gen_box_edges::<V>),
        ("box on slab plane", 3, gen_box_on_slab::<V>),
        ("box in face plane", 4, gen_box_in_face::<V>),
        ("box grazing", 5, gen_box_grazing::<V>),
        ("box tiny dir", 6, gen_box_tiny_dirs::<V>),
        ("box far 1e3..1e7", 7, gen_box_far::<V>),
        ("box 1e-6 and 1e6", 8, gen_box_scaled::<V>),
    ]
}

/// Every single-triangle generator.
pub fn triangle_generators<V: Vector>() -> [Generator<TriCase<V>>; 6] {
    [
        ("tri uniform", 11, gen_tri_uniform::<V>),
        ("tri edges, corners", 12, gen_tri_edges::<V>),
        ("tri thin", 13, gen_tri_thin::<V>),
        ("tri far 1e3..1e7", 14, gen_tri_far::<V>),
        ("tri 1e-6 and 1e6", 15, gen_tri_scaled::<V>),
        ("tri grazing", 16, gen_tri_grazing::<V>),
    ]
}
