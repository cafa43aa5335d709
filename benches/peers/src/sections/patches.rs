//! The section `patch`: ray `i` against bilinear patch `i` on each patch
//! workload (the quad workloads' parallelograms, twisted): rayhit's
//! `Patch` next to the textbook test, Reshetov's formulas ("Cool
//! Patches", Ray Tracing Gems ch. 8, 2019, as the test kit writes them
//! once: the quadratic in `u` from three triple products, then `v` and
//! `t` from two more, `t > 0`), the floor (`floor_patch`: the decisions
//! `Patch::hit` makes, by hand) and the `Quad` of the same corners (two
//! watertight triangles, for scale: not the same surface).

use rayhit::glam::{Vec4, Vec4Swizzles};
use rayhit::{Intersect, Patch, PreparedRay, Quad, Ray};
use rayhit_testkit::textbook::reshetov;
use rayhit_testkit::workloads::PatchWorkload;

use crate::harness::loops::{Orders, agree, pairwise, t_sum};
use crate::harness::{INF, Kernel, kernel};
use crate::sections::quads::FloorRay;

/// `lerp(a, b, w)` as the kernel writes it.
#[inline(always)]
fn lerp(a: f32, b: f32, w: f32) -> f32 {
    (1.0 - w) * a + w * b
}

/// The floor: the least arithmetic that makes `Patch::hit`'s decisions,
/// by hand, in `f32` on a prepared ray's frame: the four corners sheared
/// once into the ray's frame (as the watertight triangle test shears
/// them), out where none is in front; the boundary's four edge functions
/// and the diagonal's, each triangle's inside test on them, and the
/// winding number from the two; with a winding of zero, out where both
/// triangles straddle and the corners lie on one side of an axis, or where
/// the corners' Jacobians have one sign (no fold); the quadratic's
/// coefficients scaled by a power of two, its discriminant and roots, `v`
/// and `t` at each root in the square, the nearer. Left out: the
/// certificate (a fold's crossings and crossings with a corner behind the
/// origin are taken as computed, `t > 0` on the computed `t`), the exact
/// sign of an edge function that rounds to zero, the collapsed-edge and
/// finiteness checks, the one-hit rule, `u`, `v` and the side.
#[inline(always)]
pub fn floor_patch(r: &FloorRay, p: &Patch) -> Option<f32> {
    // The boundary's order: 00, 10, 11, 01.
    let (x, y, pz) = r.frame([p.p00, p.p10, p.p11, p.p01]);
    let z = pz * r.s[2];
    if z.cmpgt(Vec4::ZERO).bitmask() == 0 {
        return None;
    }
    // 00->10, 10->11, 11->01, 01->00; and 00->11.
    let e = x * y.yzwx() - y * x.yzwx();
    let d = x.x * y.z - y.x * x.z;
    let cover = |a: f32, b: f32, c: f32| {
        let straddles = a.min(b).min(c) < 0.0 && a.max(b).max(c) > 0.0;
        let det = a + b + c;
        (
            straddles,
            if straddles || det == 0.0 {
                0
            } else if det > 0.0 {
                1
            } else {
                -1
            },
        )
    };
    let ((out1, w1), (out2, w2)) = (cover(e.y, -d, e.x), cover(e.z, e.w, d));
    let single = (w1 != 0 || w2 != 0) && (w1 == 0 || w2 == 0 || w1 == w2);
    if !single {
        let side = |a: Vec4| {
            a.cmpgt(Vec4::ZERO).bitmask() == 0b1111 || a.cmplt(Vec4::ZERO).bitmask() == 0b1111
        };
        if out1 && out2 && (side(x) || side(y)) {
            return None;
        }
        let (dx, dy) = (x.yzwx() - x, y.yzwx() - y);
        let j = dx * dy.yzwx() - dy * dx.yzwx();
        if !(j.min_element() < 0.0 && j.max_element() > 0.0) {
            return None;
        }
    }
    let (b0, b2) = (-e.w, e.y);
    let b1 = (d + (x.y * y.w - y.y * x.w)) * 0.5;
    let m = b0.abs().max(b1.abs()).max(b2.abs());
    let scale = f32::from_bits((254 << 23) - (m.min(2f32.powi(125)).to_bits() & 0x7f80_0000));
    let (b0, b1, b2) = (b0 * scale, b1 * scale, b2 * scale);
    let disc = b1 * b1 - b0 * b2;
    let disc = if single {
        disc.max(0.0)
    } else if disc >= 0.0 {
        disc
    } else {
        return None;
    };
    let (a, b) = ((b0 + b2) - (b1 + b1), b1 - b0);
    let root = disc.sqrt();
    let q = -(b + if b < 0.0 { -root } else { root });
    let place = |u: f32| {
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let (ax, ay) = (lerp(x.x, x.y, u), lerp(y.x, y.y, u));
        let (dx, dy) = (lerp(x.w, x.z, u) - ax, lerp(y.w, y.z, u) - ay);
        let v = -(ax * dx + ay * dy) / (dx * dx + dy * dy);
        if !(0.0..=1.0).contains(&v) {
            return None;
        }
        let t = lerp(lerp(z.x, z.y, u), lerp(z.w, z.z, u), v);
        (t > 0.0 && t <= f32::MAX).then_some(t)
    };
    let near = place(b0 / q);
    if single && near.is_some() {
        return near;
    }
    match (near, place(q / a)) {
        (Some(n), Some(f)) => Some(n.min(f)),
        (n, f) => n.or(f),
    }
}

/// A patch workload in every form its rows take.
pub struct PatchData {
    pub name: &'static str,
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub prepared: Vec<PreparedRay>,
    pub floor: Vec<FloorRay>,
    pub patches: Vec<Patch>,
    pub quads: Vec<Quad>,
}

impl PatchData {
    pub fn new(w: PatchWorkload, shuffle: bool) -> Self {
        Self {
            name: w.name,
            order: Orders::new(w.rays.len(), shuffle),
            prepared: w.rays.iter().map(PreparedRay::new).collect(),
            floor: w.rays.iter().map(FloorRay::new).collect(),
            quads: w
                .patches
                .iter()
                .map(|p| Quad::new(p.p00, p.p10, p.p11, p.p01))
                .collect(),
            rays: w.rays,
            patches: w.patches,
        }
    }
}

/// Pairwise patch kernels: ray `i` against patch `i`.
pub fn patch_kernels<'a>(d: &'a PatchData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<bool> = (0..n)
        .map(|i| d.patches[i].hit(&d.rays[i], INF).is_some())
        .collect();
    let textbook_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| reshetov(&d.rays[i], &d.patches[i], 0.0, INF).is_some()),
    );
    let floor_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| floor_patch(&d.floor[i], &d.patches[i]).is_some()),
    );
    let (w, sec) = (d.name, "patch");
    out.extend([
        kernel(
            sec,
            "rayhit Patch::hit",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.patches, |r, p| {
                t_sum(p.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Patch::hit, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.patches, |r, p| {
                t_sum(p.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "textbook patch (Reshetov, t > 0)",
            w,
            n,
            Some(textbook_agree),
            pairwise(&d.order, &d.rays, &d.patches, |r, p| {
                t_sum(reshetov(r, p, 0.0, INF).map(|h| h.0))
            }),
        ),
        kernel(
            sec,
            "floor: the decisions by hand, no certificate",
            w,
            n,
            Some(floor_agree),
            pairwise(&d.order, &d.floor, &d.patches, |r, p| {
                t_sum(floor_patch(r, p))
            }),
        ),
        kernel(
            sec,
            "rayhit Quad::hit on the same corners",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.quads, |r, q| {
                t_sum(q.hit(r, INF).map(|h| h.t))
            }),
        ),
    ]);
}
