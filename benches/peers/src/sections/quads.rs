//! The section `quad`: ray `i` against parallelogram `i` on each quad
//! workload: rayhit's `Quad` next to the two watertight triangles a user
//! would otherwise split it into, and the textbook test of "Ray Tracing:
//! The Next Week" (its `quad`: the plane from a stored unit normal and
//! offset, then the hit point's coordinates from a stored `w = n / (n .
//! n)`, `t > 0.001`).

use core::hint::select_unpredictable;

use rayhit::glam::{BVec4A, Vec3, Vec4, Vec4Swizzles};
use rayhit::{Intersect, PreparedRay, Quad, Ray, Triangle};
use rayhit_testkit::workloads::QuadWorkload;

use crate::harness::loops::{Orders, agree, pairwise, t_sum};
use crate::harness::{INF, Kernel, kernel};

/// The textbook quad with what its constructor stores.
pub struct NextWeekQuad {
    q: Vec3,
    u: Vec3,
    v: Vec3,
    w: Vec3,
    normal: Vec3,
    d: f32,
}

impl NextWeekQuad {
    fn new(quad: &Quad) -> Self {
        let (q, u, v) = (quad.a, quad.b - quad.a, quad.d - quad.a);
        let n = u.cross(v);
        let normal = n.normalize();
        Self {
            q,
            u,
            v,
            w: n / n.dot(n),
            normal,
            d: normal.dot(q),
        }
    }

    /// The book's `quad::hit` over `(0.001, inf)`.
    #[inline(always)]
    fn hit(&self, ray: &Ray) -> Option<f32> {
        let denom = self.normal.dot(ray.dir);
        if denom.abs() < 1e-8 {
            return None;
        }
        let t = (self.d - self.normal.dot(ray.origin)) / denom;
        // (As the book's `interval::surrounds`; a NaN `t` fails it too.)
        if t.is_nan() || t <= 0.001 {
            return None;
        }
        let p = ray.at(t) - self.q;
        let alpha = self.w.dot(p.cross(self.v));
        let beta = self.w.dot(self.u.cross(p));
        ((0.0..=1.0).contains(&alpha) && (0.0..=1.0).contains(&beta)).then_some(t)
    }
}

/// A ray's part of the floor: the axes in the order that puts the main
/// one last, the shear and the origin in that order (what a prepared ray
/// holds).
pub struct FloorRay {
    pub k: [usize; 3],
    pub s: [f32; 3],
    pub o: [f32; 3],
}

impl FloorRay {
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir.to_array();
        let a = ray.dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let o = ray.origin.to_array();
        Self {
            k: [kx, ky, kz],
            s: [-d[kx] / d[kz], -d[ky] / d[kz], 1.0 / d[kz]],
            o: [o[kx], o[ky], o[kz]],
        }
    }

    /// Four corners in the ray's frame, a corner a lane, as the watertight
    /// triangle test computes them: the sheared `x` and `y`, and the
    /// translated depth (not yet scaled by `1 / d_z`).
    #[inline(always)]
    pub fn frame(&self, corners: [Vec3; 4]) -> (Vec4, Vec4, Vec4) {
        let [kx, ky, kz] = self.k;
        let c = corners.map(|p| p.to_array());
        let axis = |k: usize, o: f32| Vec4::new(c[0][k] - o, c[1][k] - o, c[2][k] - o, c[3][k] - o);
        let pz = axis(kz, self.o[2]);
        let x = axis(kx, self.o[0]) + self.s[0] * pz;
        let y = axis(ky, self.o[1]) + self.s[1] * pz;
        (x, y, pz)
    }
}

/// The floor: the least arithmetic that gives `Quad::hit`'s guarantee,
/// by hand, in `Quad::hit`'s form: the four corners sheared once into the
/// ray's frame (as the watertight triangle test shears them, so edges
/// shared with neighbours are computed alike), the four outer edge
/// functions and the two diagonals', both triangles finished side by side
/// in lanes (the first in lanes 0 and 1, the second in 2 and 3): which
/// covers the ray (its edge functions of one sign), its determinant's sign
/// known from the rough conditioning test, every corner ahead (`t > 0`
/// for sure), `t` from the depths, taken from the covering triangle's
/// lanes. With `OUT` the common miss (neither triangle covers the ray)
/// returns before the rest, as `Quad::hit` does; without it nothing
/// branches on the ray. No exact fallback (an undecided case answers
/// `None` or a plain answer), no `u`, `v` or side.
#[inline(always)]
pub fn floor_quad<const OUT: bool>(r: &FloorRay, q: &Quad) -> Option<f32> {
    let (x, y, pz) = r.frame([q.a, q.b, q.c, q.d]);
    // Lane i: the edge from corner i to i + 1, the diagonal from i to i + 2.
    let e = x * y.yzwx() - y * x.yzwx();
    let g = x * y.zwxy() - y * x.zwxy();
    let z = pz * r.s[2];
    // Opposite each corner: b-c, c-a, a-b; c-d, d-a, a-c.
    let e0 = Vec4::new(e.y, e.y, e.z, e.z);
    let e1 = Vec4::new(g.z, g.z, e.w, e.w);
    let e2 = Vec4::new(e.x, e.x, g.x, g.x);
    let (z0, z1, z2) = (
        Vec4::splat(z.x),
        Vec4::new(z.y, z.y, z.z, z.z),
        Vec4::new(z.z, z.z, z.w, z.w),
    );
    let (lo, hi) = (e0.min(e1).min(e2), e0.max(e1).max(e2));
    let covers = (lo.cmpge(Vec4::ZERO) | hi.cmple(Vec4::ZERO)).bitmask() & 0b0101;
    if OUT && covers == 0 {
        return None;
    }
    let det = e0 + e1 + e2;
    let t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    let k = x.abs().max(y.abs()).max(pz.abs()).max_element();
    let conditioned = det
        .abs()
        .cmpgt(Vec4::splat(200.0 * (f32::EPSILON * 0.5) * k * k));
    let ahead = z0.min(z1).min(z2).cmpgt(Vec4::ZERO);
    let t = t_scaled / det;
    let sure = ahead & conditioned & t.cmpgt(Vec4::ZERO) & t.cmple(Vec4::splat(f32::MAX));
    let hit = sure.bitmask() & covers != 0;
    let t = Vec4::select(BVec4A::splat(covers & 1 == 0), t.zwxy(), t).x;
    select_unpredictable(hit, Some(t), None)
}

/// A quad workload in every form its rows take.
pub struct QuadData {
    pub name: &'static str,
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub prepared: Vec<PreparedRay>,
    pub quads: Vec<Quad>,
    pub halves: Vec<[Triangle; 2]>,
    pub textbook: Vec<NextWeekQuad>,
    pub floor: Vec<FloorRay>,
}

impl QuadData {
    pub fn new(w: QuadWorkload, shuffle: bool) -> Self {
        Self {
            name: w.name,
            order: Orders::new(w.rays.len(), shuffle),
            prepared: w.rays.iter().map(PreparedRay::new).collect(),
            halves: w.quads.iter().map(Quad::triangles).collect(),
            textbook: w.quads.iter().map(NextWeekQuad::new).collect(),
            floor: w.rays.iter().map(FloorRay::new).collect(),
            rays: w.rays,
            quads: w.quads,
        }
    }
}

/// The nearer hit of two triangles, as a user splitting a quad writes it:
/// the second asked only up to the first's `t`.
#[inline(always)]
fn two_triangles(ray: &impl rayhit::RayForm, [first, second]: &[Triangle; 2]) -> Option<f32> {
    let near = first.hit(ray, INF).map(|h| h.t);
    let far = second.hit(ray, near.unwrap_or(INF)).map(|h| h.t);
    far.or(near)
}

/// Pairwise quad kernels: ray `i` against quad `i`.
pub fn quad_kernels<'a>(d: &'a QuadData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<bool> = (0..n)
        .map(|i| d.quads[i].hit(&d.rays[i], INF).is_some())
        .collect();
    let textbook_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| d.textbook[i].hit(&d.rays[i]).is_some()),
    );
    let floor_agree = |out: bool| {
        agree(
            ours.iter().copied(),
            (0..n).map(|i| {
                if out {
                    floor_quad::<true>(&d.floor[i], &d.quads[i]).is_some()
                } else {
                    floor_quad::<false>(&d.floor[i], &d.quads[i]).is_some()
                }
            }),
        )
    };
    let (w, sec) = (d.name, "quad");
    out.extend([
        kernel(
            sec,
            "rayhit Quad::hit",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.quads, |r, q| {
                t_sum(q.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Quad::hit, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.quads, |r, q| {
                t_sum(q.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "two watertight triangles (Triangle::hit)",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.halves, |r, h| {
                t_sum(two_triangles(r, h))
            }),
        ),
        kernel(
            sec,
            "two watertight triangles (Triangle::hit), PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.halves, |r, h| {
                t_sum(two_triangles(r, h))
            }),
        ),
        kernel(
            sec,
            "floor: the guarantee's arithmetic, by hand",
            w,
            n,
            Some(floor_agree(true)),
            pairwise(&d.order, &d.floor, &d.quads, |r, q| {
                t_sum(floor_quad::<true>(r, q))
            }),
        ),
        kernel(
            sec,
            "floor, no branch on the ray",
            w,
            n,
            Some(floor_agree(false)),
            pairwise(&d.order, &d.floor, &d.quads, |r, q| {
                t_sum(floor_quad::<false>(r, q))
            }),
        ),
        kernel(
            sec,
            "textbook quad (The Next Week, t > 0.001)",
            w,
            n,
            Some(textbook_agree),
            pairwise(&d.order, &d.rays, &d.textbook, |r, q| t_sum(q.hit(r))),
        ),
    ]);
}
