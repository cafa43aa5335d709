//! The section `sphere`: ray `i` against sphere `i` on each sphere
//! workload, rayhit's test next to the textbook quadratic ("Ray Tracing in
//! One Weekend": `b^2 - a c`, the near root unless it is at most 0.001,
//! then the far one), its floor and `parry3d`'s ball. (`bvh` 0.13 has no
//! ray/sphere test: its `Ball` answers containment and box overlap only.)

use parry3d::query::RayCast;
use rayhit::batch::SphereBatch;
use rayhit::glam::Vec3;
use rayhit::{Intersect, IntersectLanes, Interval, PreparedRay, Ray, Sphere};
use rayhit_testkit::workloads::SphereWorkload;

use crate::harness::loops::{Orders, agree, chunked, lanes_t_sum, pairwise, t_sum};
use crate::harness::{INF, Kernel, kernel};
use crate::peers::parry_ray;

/// A sphere workload in every form its rows take.
pub struct SphereData {
    pub name: &'static str,
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub spheres: Vec<Sphere>,
    pub prepared: Vec<PreparedRay>,
    /// The rays moved into each ball's frame (parry casts against a ball
    /// at its own origin), and the balls.
    pub parry_rays: Vec<parry3d::query::Ray>,
    pub parry_balls: Vec<parry3d::shape::Ball>,
}

impl SphereData {
    pub fn new(w: SphereWorkload, shuffle: bool) -> Self {
        let local = |r: &Ray, s: &Sphere| parry_ray(&Ray::new(r.origin - s.center, r.dir));
        Self {
            name: w.name,
            order: Orders::new(w.rays.len(), shuffle),
            prepared: w.rays.iter().map(PreparedRay::new).collect(),
            parry_rays: w
                .rays
                .iter()
                .zip(&w.spheres)
                .map(|(r, s)| local(r, s))
                .collect(),
            parry_balls: w
                .spheres
                .iter()
                .map(|s| parry3d::shape::Ball::new(s.radius))
                .collect(),
            rays: w.rays,
            spheres: w.spheres,
        }
    }
}

/// The textbook test, One Weekend's `hit_sphere` with `t > 0.001`.
#[inline(always)]
pub fn textbook_sphere(ray: &Ray, s: &Sphere) -> Option<f32> {
    let oc = s.center - ray.origin;
    let a = ray.dir.length_squared();
    let h = ray.dir.dot(oc);
    let c = oc.length_squared() - s.radius * s.radius;
    let disc = h * h - a * c;
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let near = (h - root) / a;
    if near > 0.001 {
        return Some(near);
    }
    let far = (h + root) / a;
    (far > 0.001).then_some(far)
}

/// Haines et al.'s discriminant from the line's distance to the centre and
/// the stable pair of roots, nearest root above zero, with no error bound
/// (so neither the miss band nor a `t > 0` that holds exactly): the
/// published accurate form, not the guarantee.
#[inline(always)]
pub fn haines_sphere(ray: &Ray, s: &Sphere) -> Option<f32> {
    let f: Vec3 = ray.origin - s.center;
    let a = ray.dir.length_squared();
    let nd = -f.dot(ray.dir);
    let l = f + ray.dir * (nd / a);
    let disc = s.radius * s.radius - l.length_squared();
    if disc < 0.0 {
        return None;
    }
    let root = (a * disc).sqrt();
    let q = if nd >= 0.0 { nd + root } else { nd - root };
    let (t1, t2) = (q / a, (f.length_squared() - s.radius * s.radius) / q);
    let (near, far) = if t1 < t2 { (t1, t2) } else { (t2, t1) };
    if near > 0.0 {
        Some(near)
    } else {
        (far > 0.0).then_some(far)
    }
}

/// The floor: the least arithmetic that gives `Sphere::hit`'s guarantee
/// in `f32`, written out by hand: the same decisions (the discriminant as
/// `a r^2 - |f x d|^2` with its rounding band, `t > 0` from the signs of
/// `beta` and `k`), its bounds with their constants folded and without the
/// underflow terms, and no exact fallback (the rare undecided cases
/// answer `None`).
#[inline(always)]
pub fn floor_sphere(ray: &Ray, s: &Sphere) -> Option<f32> {
    const U: f32 = f32::EPSILON * 0.5;
    let g = |n: f32| n * U / (1.0 - n * U) * (1.0 + 8.0 * U);
    let d = ray.dir;
    let f = ray.origin - s.center;
    let a = d.dot(d);
    let nd = -f.dot(d);
    let ff = f.dot(f);
    let rr = s.radius * s.radius;
    let k = ff - rr;
    let c = f.cross(d);
    let cc = c.dot(c);
    let ar = a * rr;
    let x = ar - cc;
    let m = f.abs().max_element() * d.abs().element_sum();
    if x < 0.0 {
        let e = g(3.0) * m;
        let band = g(5.0) * ar + g(4.0) * cc + e * (2.0 * c.abs().element_sum() + 3.0 * e) + U * -x;
        if x < -band {
            return None;
        }
    }
    let root = x.max(0.0).sqrt();
    let (err_nd, err_k) = (g(4.0) * m, g(8.0) * (ff + rr));
    let t = if nd > err_nd {
        let q = nd + root;
        if k > err_k { k / q } else { q / a }
    } else if nd < -err_nd && k < -err_k {
        k / (nd - root)
    } else {
        return None;
    };
    (t > 0.0).then_some(t)
}

/// Pairwise sphere kernels: ray `i` against sphere `i`.
pub fn sphere_kernels<'a>(d: &'a SphereData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<bool> = (0..n)
        .map(|i| d.spheres[i].hit(&d.rays[i], INF).is_some())
        .collect();
    let textbook_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| textbook_sphere(&d.rays[i], &d.spheres[i]).is_some()),
    );
    let floor_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| floor_sphere(&d.rays[i], &d.spheres[i]).is_some()),
    );
    let haines_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| haines_sphere(&d.rays[i], &d.spheres[i]).is_some()),
    );
    let parry_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| {
            d.parry_balls[i]
                .cast_local_ray(&d.parry_rays[i], f32::MAX, false)
                .is_some()
        }),
    );
    let (w, sec) = (d.name, "sphere");
    let all = Interval::up_to(INF).expect("a valid interval");
    out.extend([
        kernel(
            sec,
            "rayhit Sphere::hit",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.spheres, |r, s| {
                t_sum(s.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Sphere::hit, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.spheres, |r, s| {
                t_sum(s.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Sphere::hit, (0, inf]",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.spheres, move |r, s| {
                t_sum(s.hit(r, all).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "textbook quadratic (One Weekend, t > 0.001)",
            w,
            n,
            Some(textbook_agree),
            pairwise(&d.order, &d.rays, &d.spheres, |r, s| {
                t_sum(textbook_sphere(r, s))
            }),
        ),
        kernel(
            sec,
            "Haines et al. (distance discriminant, stable roots), no bounds",
            w,
            n,
            Some(haines_agree),
            pairwise(&d.order, &d.rays, &d.spheres, |r, s| {
                t_sum(haines_sphere(r, s))
            }),
        ),
        kernel(
            sec,
            "floor: the guarantee's arithmetic, by hand",
            w,
            n,
            Some(floor_agree),
            pairwise(&d.order, &d.rays, &d.spheres, |r, s| {
                t_sum(floor_sphere(r, s))
            }),
        ),
        kernel(
            sec,
            "parry3d Ball::cast_local_ray",
            w,
            n,
            Some(parry_agree),
            pairwise(&d.order, &d.parry_rays, &d.parry_balls, |r, b| {
                t_sum(b.cast_local_ray(r, f32::MAX, false))
            }),
        ),
    ]);
}

/// The section `sphere x8`: a ray against a group of eight spheres (a
/// particle leaf), one sphere at a time and as one batch of eight.
pub fn sphere_group_kernels<'a>(
    rays: &'a [Ray],
    prepared: &'a [PreparedRay],
    spheres: &'a [Sphere],
    batches: &'a [SphereBatch<Vec3, 8>],
    out: &mut Vec<Kernel<'a>>,
) {
    let (w, sec, n) = ("groups", "sphere x8", spheres.len());
    out.extend([
        kernel(
            sec,
            "rayhit Sphere::hit, 8 calls",
            w,
            n,
            None,
            chunked(rays, spheres, 8, |r, s| t_sum(s.hit(r, INF).map(|h| h.t))),
        ),
        kernel(
            sec,
            "rayhit SphereBatch::hit, 8 lanes",
            w,
            n,
            None,
            chunked(rays, batches, 1, |r, b| {
                let h = b.hit(r, INF);
                lanes_t_sum(h.mask, &h.t)
            }),
        ),
        kernel(
            sec,
            "rayhit SphereBatch::hit, 8 lanes, PreparedRay",
            w,
            n,
            None,
            chunked(prepared, batches, 1, |r, b| {
                let h = b.hit(r, INF);
                lanes_t_sum(h.mask, &h.t)
            }),
        ),
        kernel(
            sec,
            "textbook quadratic (One Weekend, t > 0.001), 8 calls",
            w,
            n,
            None,
            chunked(rays, spheres, 8, |r, s| t_sum(textbook_sphere(r, s))),
        ),
    ]);
}
