//! The watertight test on a batch over an interval: the kernel of
//! [`TriangleBatch`]'s `hit` and `occluded` with an [`Interval`], each
//! lane bit for bit the scalar interval test's answer (the corners'
//! depths decide most lanes; the rest go to the scalar test).

use core::marker::PhantomData;

use super::batch::{TriangleBatch, TriangleBatchHits, scalar_lanes};
use super::conditioning::edge_signs_known;
use super::definition::EdgeRule;
use super::interval::{DepthWindow, watertight_in};
use super::lanes::{RayLanes, edge_functions, outside};
use crate::num::{Bits, Lanes8, Repr, S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay};
use crate::simd::{Isa, Kernel, check_lanes, lanes_at, put};

/// `ray_triangle_batch_in` (`ANY = false`) and its any-hit form
/// (`ANY = true`) as a kernel: the answer
/// of every lane the corners' depths decide, and the scalar interval test
/// for the lanes they leave. With `ANY`, it returns at the first lane hit,
/// with only `mask` set.
pub(crate) struct TriangleBatchInKernel<V, const N: usize, const ANY: bool>(PhantomData<V>);

impl<V: Vector, const N: usize, const ANY: bool> Kernel for TriangleBatchInKernel<V, N, ANY> {
    type Ray = PreparedRay<V>;
    type Shapes = TriangleBatch<V, N>;
    type Limit = Interval<S<V>>;
    type Output = TriangleBatchHits<S<V>, N>;
    /// As for [`TriangleBatchKernel`].
    const AVX512: bool = false;

    #[inline(always)]
    fn run<I: Isa>(
        _: I,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        interval: Interval<S<V>>,
    ) -> Self::Output {
        triangle_batch_in_body::<I::W<S<V>>, V, N, ANY>(ray, batch, interval)
    }
}

/// The body of [`TriangleBatchInKernel`] with the eight-lane type `W`: per
/// lane, the scalar interval test's shortcut (`watertight_in_lanes`: the
/// inside test, then, where every edge function's sign is surely exact,
/// the corners' depths against the interval's ends), on the same values
/// with the same operations, so the same answer, bit for bit (the
/// depths' conditions through their smallest and largest, as
/// `corner_verdict` notes).
#[inline(always)]
fn triangle_batch_in_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize, const ANY: bool>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    interval: Interval<S<V>>,
) -> TriangleBatchHits<S<V>, N> {
    const { check_lanes::<N>() };
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    let mut out = TriangleBatchHits::none();
    if !ray.is_valid() {
        return out;
    }
    let sh = ray.shear();
    let window = DepthWindow::new(interval, sh.sz);
    if !window.usable {
        // Every lane to the scalar test (a direction near the ends of the
        // float range).
        return slow_lanes_in(ray, batch, interval, batch.used, ANY, out);
    }
    let frame = RayLanes::<W>::new(ray);
    let splat = W::splat;
    let (lo, ones, sz) = (splat(zero), splat(one), splat(sh.sz));
    let (down, up) = DepthWindow::<S<V>>::factors();
    let (down, up) = (splat(down), splat(up));
    let (t_lo, t_hi) = (splat(window.lo), splat(window.hi));
    let (t_lo_normal, t_hi_normal) = (splat(window.lo_normal), splat(window.hi_normal));
    let normal = splat(S::<V>::MIN_POSITIVE);
    let neg_normal = lo.sub(normal);
    let (mut hit, mut slow, mut front) = (0, 0, 0);
    let all = lo.le(lo);
    for c in 0..N.div_ceil(8) {
        // Lanes past N hold NaN, and are not in `batch.used`.
        let corners = frame.corners(&batch.p, c);
        let [e0, e1, e2] = edge_functions(&corners);
        let (outside, e_min, e_max) = outside([e0, e1, e2], lo);
        let inside = W::and_not(all, outside);
        if W::bits(inside) == 0 {
            // (As in `triangle_batch_body`.)
            if N <= 8 {
                return out;
            }
            continue;
        }
        let [(x0, y0, pz0), (_, _, pz1), (_, _, pz2)] = corners;
        // Inside, the edge functions share a sign, so the smallest |e_i|
        // is e_min where they are positive and -e_max where negative.
        let min_abs_e = e_min.max(lo.sub(e_max));
        let det = e0.add(e1).add(e2);
        // (`det - det` is zero exactly when `det` is finite.)
        let finite = det.sub(det).eq(lo);
        let reach = lanes_at::<W, N>(&batch.reach, c);
        let signs_known = edge_signs_known(min_abs_e, (x0, y0, pz0), reach);
        let known = W::and(W::and(signs_known, finite), inside);
        let (z0, z1, z2) = (pz0.mul(sz), pz1.mul(sz), pz2.mul(sz));
        let (z_min, z_max) = (z0.min(z1.min(z2)), z0.max(z1.max(z2)));
        let (low, high) = (z_min.mul(down), z_max.mul(up));
        let accept = W::and(t_lo_normal.lt(low), high.le(t_hi));
        let reject = W::or(
            W::or(t_hi_normal.lt(low), z_max.le(neg_normal)),
            W::and(normal.le(z_min), high.le(t_lo)),
        );
        let hit_c = W::and(known, accept);
        let shift = 8 * c;
        slow |= W::bits(W::and_not(inside, W::and(known, W::or(accept, reject)))) << shift;
        hit |= W::bits(hit_c) << shift;
        if W::bits(hit_c) & (batch.used >> shift) == 0 {
            // (Most chunks with a lane inside have no lane hit: for random
            // rays, half the triangles the line crosses are behind.)
            continue;
        }
        if ANY {
            out.mask = hit & batch.used;
            return out;
        }
        let inv_det = ones.div(det);
        let t = e0.mul(z0).add(e1.mul(z1)).add(e2.mul(z2)).mul(inv_det);
        // `bring_into`: `t` above `t_min`, at most `t_max` (the float
        // above `t_min` computed here, for chunks with a hit only).
        let above_lo = splat(<S<V> as Repr>::Bits::successor(window.lo));
        let t = W::select(t_lo.lt(t), t, above_lo).min(t_hi);
        let u = e1.mul(inv_det).min(ones);
        let v = e2.mul(inv_det).min(ones);
        front |= W::bits(lo.lt(det)) << shift;
        put(&mut out.t, c, W::select(hit_c, t, splat(S::<V>::INFINITY)));
        put(&mut out.u, c, W::select(hit_c, u, lo));
        put(&mut out.v, c, W::select(hit_c, v, lo));
    }
    let hit = hit & batch.used;
    out.mask = hit;
    // A hit is from the front when the sign of its determinant differs
    // from that of the ray's main component (see `watertight_definition`).
    out.front = if sh.dz > zero {
        !front & hit
    } else {
        front & hit
    };
    let slow = slow & batch.used;
    if slow != 0 {
        out = slow_lanes_in(ray, batch, interval, slow, ANY, out);
    }
    out
}

/// The lanes in `slow` of a batch answer from the scalar interval test
/// ([`Triangle`'s `hit` over an interval](crate::Triangle#method.hit)), bit
/// for bit; with `any`, it stops at the first hit. Out of line (such lanes
/// are rare).
#[cold]
#[inline(never)]
fn slow_lanes_in<V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    interval: Interval<S<V>>,
    slow: u32,
    any: bool,
    out: TriangleBatchHits<S<V>, N>,
) -> TriangleBatchHits<S<V>, N> {
    let (origin, shear) = (ray.origin(), ray.shear());
    scalar_lanes(batch, slow, any, out, |tri| {
        watertight_in(origin, ray.dir, &shear, tri, interval, EdgeRule::Closed)
    })
}
