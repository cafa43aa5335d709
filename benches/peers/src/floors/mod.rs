//! The kernels rayhit is measured against that are written here rather
//! than taken from another crate: the textbook tests as they are usually
//! written ("textbook") and the floors, each a textbook test plus only the
//! operations rayhit's guarantees need beyond it ("floor"). This file
//! holds the scalar box and triangle tests; `batch` the eight-lane
//! triangle floors in AVX2, `boxes8` the floor of a plain call into an
//! eight-box batch, `camera` the cameras' references and
//! `instance` the floor of the hit's mapping to the world.

use rayhit::glam::{Vec3, Vec3A, Vec3Swizzles, Vec4, Vec4Swizzles};
use rayhit::{Aabb, Ray, Triangle};

use crate::harness::INF;

#[cfg(target_arch = "x86_64")]
pub mod batch;
#[cfg(target_arch = "x86_64")]
pub mod boxes8;
pub mod camera;
pub mod instance;

/// A ray as the textbook slab test stores it: origin and `1 / dir`.
#[derive(Clone, Copy)]
pub struct PlainRay {
    origin: Vec3,
    inv: Vec3,
}

impl PlainRay {
    pub fn new(r: &Ray) -> Self {
        Self {
            origin: r.origin,
            inv: r.dir.recip(),
        }
    }
}

/// `if a > b { a } else { b }` when `MAX`, else `if a < b { a } else { b }`,
/// as one `maxss` or `minss` on x86-64. (Written as that `if`, the slab
/// test's selects were vectorized two axes at a time and compiled to
/// branches on the comparisons' mask, which the order of the rays then
/// made or broke; the instruction keeps the test branchless.)
#[inline(always)]
fn min_max_ss<const MAX: bool>(a: f32, b: f32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE is part of every x86-64 target, and these intrinsics
    // only compute on registers (no memory access).
    unsafe {
        use std::arch::x86_64::{_mm_cvtss_f32, _mm_max_ss, _mm_min_ss, _mm_set_ss};
        let (a, b) = (_mm_set_ss(a), _mm_set_ss(b));
        _mm_cvtss_f32(if MAX {
            _mm_max_ss(a, b)
        } else {
            _mm_min_ss(a, b)
        })
    }
    #[cfg(not(target_arch = "x86_64"))]
    if (MAX && a > b) || (!MAX && a < b) {
        a
    } else {
        b
    }
}

/// The plain branchless `f32` slab test the way it is usually written
/// (Williams et al. 2005 without the sign table; Barnes 2022's loop), with
/// each `min`/`max` a single comparison so that it compiles to one
/// `minss`/`maxss`: not conservative, and a ray in a face plane can miss.
#[inline]
pub fn plain_slab(r: &PlainRay, b: &Aabb) -> bool {
    let (mut lo, mut hi) = (0.0f32, INF);
    for k in 0..3 {
        let t1 = (b.min[k] - r.origin[k]) * r.inv[k];
        let t2 = (b.max[k] - r.origin[k]) * r.inv[k];
        let (min, max) = (min_max_ss::<false>, min_max_ss::<true>);
        let (near, far) = (min(t1, t2), max(t1, t2));
        lo = max(near, lo);
        hi = min(far, hi);
    }
    lo <= hi
}

/// `rayhit`'s widening of the exit, `(1 + 2 gamma(4))` rounded up, and
/// its slack of two subnormals (see `aabb/definition.rs`).
/// A constant, so that no floor computes it per call.
pub const WIDENING: (f32, f32) = {
    let eps = f32::EPSILON / 2.0;
    let gamma4 = 4.0 * eps / (1.0 - 4.0 * eps);
    ((1.0 + 2.0 * gamma4).next_up(), 2.0 * f32::from_bits(1))
};

/// A ray as the floor of a binary BVH's box test reads it: origin and
/// `1 / dir`, four lanes each.
#[derive(Clone, Copy)]
pub struct FloorBoxRay {
    origin: Vec3A,
    inv: Vec3A,
}

impl FloorBoxRay {
    pub fn new(r: &Ray) -> Self {
        Self {
            origin: r.origin.into(),
            inv: Vec3A::from(r.dir).recip(),
        }
    }
}

/// The floor of a binary BVH's box test by plain call, inlined: the
/// textbook slab test on lanes (`min`/`max` of the two planes' distances
/// per axis, the largest near and smallest far over the axes, folded into
/// `[lo, hi]`) plus the one operation the guarantee adds for rays with no
/// zero direction component, the exit's widening (`rayhit`'s constants).
/// The entry, or `None`. Left out against `ValidAabb::clip`: the NaN-safe
/// fold for an origin on a slab plane of an axis the ray does not move
/// along, the check of `t_max`, the entry's bound `MAX`, and the reported
/// ends kept within the range.
#[inline(always)]
pub fn floor_box_enter(r: &FloorBoxRay, b: &Aabb, lo: f32, hi: f32) -> Option<f32> {
    let (w, slack) = WIDENING;
    let t0 = (Vec3A::from(b.min) - r.origin) * r.inv;
    let t1 = (Vec3A::from(b.max) - r.origin) * r.inv;
    let near = t0.min(t1).max_element().max(lo);
    let far = t0.max(t1).min_element().min(hi);
    (near <= far * w + slack).then_some(near)
}

/// The axis of `d`'s largest magnitude component, the watertight test's
/// `kz` (Woop, Benthin and Wald, JCGT 2013): x if `|d_x|` is larger than
/// both others, else y if larger than `|d_z|`, else z.
#[inline(always)]
fn main_axis(d: Vec3) -> usize {
    let a = d.abs();
    if a.x > a.y {
        if a.x > a.z { 0 } else { 2 }
    } else if a.y > a.z {
        1
    } else {
        2
    }
}

/// The textbook two-sided Moller-Trumbore (Moller and Trumbore, JGT 1997)
/// with an absolute epsilon on the determinant, as it is usually written:
/// not watertight.
#[inline]
pub fn textbook_mt(r: &Ray, tri: &Triangle) -> Option<f32> {
    const EPS: f32 = f32::EPSILON;
    let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
    let p = r.dir.cross(e2);
    let det = e1.dot(p);
    if det > -EPS && det < EPS {
        return None;
    }
    let inv = 1.0 / det;
    let s = r.origin - tri.a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = r.dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > EPS).then_some(t)
}

/// The floor for `Triangle::moller_trumbore`: [`textbook_mt`] with only
/// the operations `Triangle::moller_trumbore`'s guarantees need beyond it,
/// written as the textbook writes the rest (glam's `Vec3`): no epsilon,
/// but a hit needs the determinant's sign certain (`|det|` above its
/// rounding bound, `gamma(7) sum |e1_i| (|d_j e2_k| + |d_k e2_j|)`, stepped
/// up for its own rounding, as `Triangle::moller_trumbore` derives it);
/// `0 < t <= t_max` and finite. Invalid input needs nothing more, as in
/// `Triangle::moller_trumbore`: NaN or infinite values fail the range
/// tests. The bound is tested last, where only hits pay for it.
#[inline]
pub fn floor_mt(r: &Ray, tri: &Triangle, t_max: f32) -> Option<f32> {
    let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
    let d = r.dir;
    let (m1, m2) = (d.yzx() * e2.zxy(), d.zxy() * e2.yzx());
    let p = m1 - m2;
    let det = e1.dot(p);
    let inv = 1.0 / det;
    let s = r.origin - tri.a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    if !(t > 0.0 && t <= f32::MAX.min(t_max)) {
        return None;
    }
    // gamma(7) and the step up of `bound_up(_, 7)`, (1 + gamma(8)) rounded
    // up, as constants.
    const U: f32 = f32::EPSILON * 0.5;
    const GAMMA_7: f32 = (7.0 * U / (1.0 - 7.0 * U)).next_up();
    const STEP: f32 = (1.0 + (8.0 * U / (1.0 - 8.0 * U)).next_up()).next_up();
    let bound = GAMMA_7 * e1.abs().dot(m1.abs() + m2.abs()) * STEP;
    (det.abs() > bound).then_some(t)
}

/// The watertight test of Woop, Benthin and Wald (JCGT 2013) as the paper
/// lays it out, with the ray's shear computed per call (as `ray_triangle`
/// must): permute so the ray runs along its largest axis, shear, three 2-D
/// edge functions with the sign test, then `t` from the scaled depths
/// times the reciprocal of the determinant (the paper's arithmetic: the
/// same reciprocal scales the edge functions into the barycentrics),
/// two-sided, no exact-sign fallback, no conservative `t > 0` tests, no
/// input checks. The floor against which `ray_triangle` is measured: the
/// operations the watertight guarantee needs beyond Moller-Trumbore.
#[inline]
pub fn textbook_watertight(r: &Ray, tri: &Triangle) -> Option<f32> {
    let d = r.dir;
    let kz = main_axis(d);
    let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
    // (Indexing arrays, not the vectors: glam's `Index` is a `match`, which
    // compiles to a jump on the axis, mispredicted whenever the ray's main
    // axis changes.)
    let (dv, ov): (&[f32; 3], &[f32; 3]) = (r.dir.as_ref(), r.origin.as_ref());
    let (sx, sy, sz) = (-dv[kx] / dv[kz], -dv[ky] / dv[kz], 1.0 / dv[kz]);
    let corner = |p: Vec3| {
        let p: &[f32; 3] = p.as_ref();
        let q = |k: usize| p[k] - ov[k];
        (q(kx) + sx * q(kz), q(ky) + sy * q(kz), q(kz) * sz)
    };
    let (ax, ay, az) = corner(tri.a);
    let (bx, by, bz) = corner(tri.b);
    let (cx, cy, cz) = corner(tri.c);
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    // (The paper's arithmetic: one reciprocal of the determinant, which
    // also scales the edge functions into the barycentrics.)
    let t = (u * az + v * bz + w * cz) * (1.0 / det);
    (t > 0.0).then_some(t)
}

/// The floor with the guarantee: [`textbook_watertight`] plus only the
/// operations `ray_triangle`'s guarantees need beyond it, each as cheap as
/// it can be written: the ray's validity (finite, non-zero direction) and
/// `t_max`; an edge function of exactly zero leaves for an exact
/// recomputation; `t > 0` is decided on the corners' depths (all in front:
/// sure; none: no hit) and anything else leaves for the full decision; a
/// hit must pass the cheap test that the determinant's sign is known
/// (`|det| > 200 u k^2`, `k` the largest sheared coordinate or depth);
/// `t` must be finite (`t <= MAX`, one comparison with `t_max`'s). The
/// rare paths are stubs out of line (`rare`): what is measured is the
/// common path. `t` only, like the textbook test. (Its frame is written out
/// again rather than shared with [`textbook_watertight`]: a shared helper
/// cost this floor 10 instructions per test under callgrind, which would
/// flatter `ray_triangle` against it.)
#[inline]
pub fn floor_watertight(r: &Ray, tri: &Triangle, t_max: f32) -> Option<f32> {
    #[cold]
    #[inline(never)]
    fn rare() -> Option<f32> {
        std::hint::black_box(None)
    }
    let (o, d) = (r.origin, r.dir);
    if !(o.is_finite() && d.is_finite() && d != Vec3::ZERO && t_max >= 0.0) {
        return None;
    }
    let kz = main_axis(d);
    let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
    // (Indexing arrays, not the vectors: glam's `Index` is a `match`, which
    // compiles to a jump on the axis, mispredicted whenever the ray's main
    // axis changes.)
    let (dv, ov): (&[f32; 3], &[f32; 3]) = (r.dir.as_ref(), r.origin.as_ref());
    let (sx, sy, sz) = (-dv[kx] / dv[kz], -dv[ky] / dv[kz], 1.0 / dv[kz]);
    let corner = |p: Vec3| {
        let p: &[f32; 3] = p.as_ref();
        let q = |k: usize| p[k] - ov[k];
        (q(kx) + sx * q(kz), q(ky) + sy * q(kz), q(kz))
    };
    let (ax, ay, apz) = corner(tri.a);
    let (bx, by, bpz) = corner(tri.b);
    let (cx, cy, cpz) = corner(tri.c);
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    if u == 0.0 || v == 0.0 || w == 0.0 {
        return rare();
    }
    let det = u + v + w;
    let (az, bz, cz) = (apz * sz, bpz * sz, cpz * sz);
    let t_scaled = u * az + v * bz + w * cz;
    let ahead = az > 0.0 && bz > 0.0 && cz > 0.0;
    let in_range = if det > 0.0 {
        t_scaled > 0.0 && t_scaled <= t_max * det
    } else {
        t_scaled < 0.0 && t_scaled >= t_max * det
    };
    if !in_range {
        return if az > 0.0 || bz > 0.0 || cz > 0.0 {
            rare()
        } else {
            None
        };
    }
    let k = ax.abs().max(ay.abs()).max(apz.abs());
    let k = k.max(bx.abs().max(by.abs()).max(bpz.abs()));
    let k = k.max(cx.abs().max(cy.abs()).max(cpz.abs()));
    if !(ahead && det.abs() > k * k * (200.0 * f32::EPSILON * 0.5)) {
        return rare();
    }
    let t = t_scaled * (1.0 / det);
    (t > 0.0 && t <= t_max.min(f32::MAX)).then_some(t)
}

/// A ray as the watertight test of Woop, Benthin and Wald (JCGT 2013)
/// prepares it once: the axis order (the largest `|d|` component last, the
/// other two following it cyclically), the shear factors and the origin in
/// that order, each in every lane, and whether the ray is valid (finite,
/// non-zero direction).
#[derive(Clone, Copy)]
pub struct FloorRay {
    k: [usize; 3],
    s: [Vec4; 3],
    origin: [Vec4; 3],
    dz: f32,
    valid: bool,
}

impl FloorRay {
    pub fn new(r: &Ray) -> Self {
        let (o, d) = (r.origin, r.dir);
        let kz = main_axis(d);
        let k = [(kz + 1) % 3, (kz + 2) % 3, kz];
        let s = [-d[k[0]] / d[kz], -d[k[1]] / d[kz], 1.0 / d[kz]];
        Self {
            k,
            s: s.map(Vec4::splat),
            origin: k.map(|i| Vec4::splat(o[i])),
            dz: d[kz],
            valid: o.is_finite() && d.is_finite() && d != Vec3::ZERO,
        }
    }
}

/// The floor for `Triangle::hit` on a `PreparedRay`: the textbook
/// watertight test with the ray's shear prepared once ([`FloorRay`]), as a
/// BVH traversal uses it, written the fastest way found for this core: the
/// three corners in the lanes of one SSE register (`glam::Vec4`), so that
/// translating, shearing and the three edge functions are a handful of
/// instructions each, and the sign test is two comparisons of the register.
/// With `CHECKS`, only the operations the prepared `Triangle::hit`'s
/// guarantees need beyond it: the ray's validity and `t_max`; an edge
/// function of exactly zero leaves for an exact recomputation; `t > 0`
/// decided on the corners' depths (all in front: sure; none: no hit; else
/// the full decision); the cheap test that the determinant's sign is known
/// (`|det| > 200 u k^2`); a finite `t`. `t` is the scaled depth times the
/// reciprocal of the determinant, as in the paper. The rare paths are stubs
/// out of line. `t` and the side, of which the rows keep `t` only, like the
/// other floors: returning the side as well compiled the checked form to 5
/// fewer instructions per aimed test under callgrind (122 against 127), and
/// a floor should be the fastest form.
#[inline]
pub fn floor_watertight_prepared<const CHECKS: bool>(
    r: &FloorRay,
    tri: &Triangle,
    t_max: f32,
) -> Option<(f32, bool)> {
    #[cold]
    #[inline(never)]
    fn rare() -> Option<(f32, bool)> {
        std::hint::black_box(None)
    }
    if CHECKS && !(r.valid && t_max >= 0.0) {
        return None;
    }
    // (Indexing the arrays, not the vectors: glam's `Index` is a `match`,
    // which compiled to a jump on the axis, mispredicted whenever the
    // ray's main axis changes.)
    let (a, b, c): (&[f32; 3], &[f32; 3], &[f32; 3]) =
        (tri.a.as_ref(), tri.b.as_ref(), tri.c.as_ref());
    let corners = |k: usize| Vec4::new(a[k], b[k], c[k], 0.0);
    let [kx, ky, kz] = r.k;
    let [ox, oy, oz] = r.origin;
    let [sx, sy, sz] = r.s;
    let pz = corners(kz) - oz;
    let x = corners(kx) - ox + sx * pz;
    let y = corners(ky) - oy + sy * pz;
    // Lane i: x[i+1] y[i+2] - y[i+1] x[i+2]; lane 3 is 0.
    let e = x.yzxw() * y.zxyw() - y.yzxw() * x.zxyw();
    if e.cmplt(Vec4::ZERO).any() && e.cmpgt(Vec4::ZERO).any() {
        return None;
    }
    if CHECKS && e.cmpeq(Vec4::ZERO).bitmask() & 0b111 != 0 {
        return rare();
    }
    let det = e.x + e.y + e.z;
    let z = pz * sz;
    let t_scaled = e.dot(z);
    let in_range = if det > 0.0 {
        t_scaled > 0.0 && t_scaled <= t_max * det
    } else if det < 0.0 {
        t_scaled < 0.0 && t_scaled >= t_max * det
    } else {
        false
    };
    let ahead = z.cmpgt(Vec4::ZERO).bitmask() & 0b111;
    if !in_range {
        return if CHECKS && ahead != 0 { rare() } else { None };
    }
    if CHECKS {
        let k = x.abs().max(y.abs()).max(pz.abs());
        let bound = Vec4::splat(200.0 * f32::EPSILON * 0.5);
        let conditioned = (k * k * bound).cmplt(Vec4::splat(det.abs())).bitmask() & 0b111;
        if !(ahead == 0b111 && conditioned == 0b111) {
            return rare();
        }
    }
    let t = t_scaled * (1.0 / det);
    let t_limit = if CHECKS { t_max.min(f32::MAX) } else { t_max };
    (t > 0.0 && t <= t_limit).then_some((t, (det > 0.0) != (r.dz > 0.0)))
}
