//! The section `quad`: ray `i` against parallelogram `i` on each quad
//! workload: rayhit's `Quad` next to the two watertight triangles a user
//! would otherwise split it into, and the textbook test of "Ray Tracing:
//! The Next Week" (its `quad`: the plane from a stored unit normal and
//! offset, then the hit point's coordinates from a stored `w = n / (n .
//! n)`, `t > 0.001`).

use rayhit::glam::Vec3;
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

/// A quad workload in every form its rows take.
pub struct QuadData {
    pub name: &'static str,
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub prepared: Vec<PreparedRay>,
    pub quads: Vec<Quad>,
    pub halves: Vec<[Triangle; 2]>,
    pub textbook: Vec<NextWeekQuad>,
}

impl QuadData {
    pub fn new(w: QuadWorkload, shuffle: bool) -> Self {
        Self {
            name: w.name,
            order: Orders::new(w.rays.len(), shuffle),
            prepared: w.rays.iter().map(PreparedRay::new).collect(),
            halves: w.quads.iter().map(Quad::triangles).collect(),
            textbook: w.quads.iter().map(NextWeekQuad::new).collect(),
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
            "textbook quad (The Next Week, t > 0.001)",
            w,
            n,
            Some(textbook_agree),
            pairwise(&d.order, &d.rays, &d.textbook, |r, q| t_sum(q.hit(r))),
        ),
    ]);
}
