//! What the watertight test's lane forms share: a lane's answer as a
//! packed hit and back, the frame of a triangle in the ray's lanes, and the
//! ray forms the definition takes (plain or prepared).

use super::{Side, Triangle, TriangleHit};
use crate::num::{Axis, Bits, L, Lanes, Lanes8, Repr, S, Scalar, Vector};
use crate::ray::{PreparedRay, Ray, Shear};
use crate::simd::lanes_at;

/// The hit at `t` with the corners' edge functions in lanes `e`, as
/// `hit_at` computes it: `u` and `v` lanes 1 and 2 of `min(e / det, 1)`
/// (finite where `1 / det` is: each `|e_i| <= |det|`, the `e_i` sharing a
/// sign), the side from the signs of `det` and `sz = 1 / d_z` (which has
/// the sign of `d_z`, and is not zero: `|d_z| <= MAX`).
#[inline(always)]
pub(super) fn lanes_hit<F: Scalar, W: Lanes<F = F>>(
    t: F,
    e: W,
    det: F,
    inv_det: F,
    sz: F,
) -> TriangleHit<F> {
    let w = e.mul(W::splat(inv_det)).min(W::splat(F::ONE));
    let [_, u, v] = w.to_array();
    let side = if (det > F::ZERO) != (sz > F::ZERO) {
        Side::Front
    } else {
        Side::Back
    };
    TriangleHit { t, u, v, side }
}

/// A triangle test's answer as the rare paths return it: packed so that
/// it comes back in registers (see `crate::num::repr::Bits`). Returned
/// through memory, the rare paths' answer made the inlined common path
/// write its own answer through memory as well.
pub(crate) type Packed<F> = <<F as Repr>::Bits as Bits>::Packed;

/// `hit` packed: `t`, `u`, `v` and a code, 0 for a miss, 1 for a hit from
/// the front, 2 from the back.
#[inline(always)]
pub(super) fn pack<F: Scalar>(hit: Option<TriangleHit<F>>) -> Packed<F> {
    let (values, code) = match hit {
        None => ([F::ZERO; 3], 0),
        Some(h) => (
            [h.t, h.u, h.v],
            match h.side {
                Side::Front => 1,
                Side::Back => 2,
            },
        ),
    };
    F::Bits::pack(values, code)
}

/// The inverse of [`pack`], bit for bit.
#[inline(always)]
pub(super) fn unpack<F: Scalar>(packed: Packed<F>) -> Option<TriangleHit<F>> {
    let ([t, u, v], code) = F::Bits::unpack(packed);
    let side = match code {
        0 => return None,
        1 => Side::Front,
        _ => Side::Back,
    };
    Some(TriangleHit { t, u, v, side })
}

/// A ray the definition can be run on, from what a fast path was given: its
/// origin and shear (rebuilt where the fast path kept only its lanes), its
/// direction, and whether it is valid.
pub(super) trait DefinitionRay<V: Vector> {
    fn origin_and_shear(&self) -> (V, Shear<S<V>>);
    fn direction(&self) -> V;
    fn valid(&self) -> bool;
}

impl<V: Vector> DefinitionRay<V> for Ray<V> {
    #[inline(always)]
    fn origin_and_shear(&self) -> (V, Shear<S<V>>) {
        (self.origin, Shear::new(&self.dir))
    }
    #[inline(always)]
    fn direction(&self) -> V {
        self.dir
    }
    #[inline(always)]
    fn valid(&self) -> bool {
        self.is_valid()
    }
}

impl<V: Vector> DefinitionRay<V> for PreparedRay<V> {
    #[inline(always)]
    fn origin_and_shear(&self) -> (V, Shear<S<V>>) {
        (self.origin(), self.shear())
    }
    #[inline(always)]
    fn direction(&self) -> V {
        self.dir
    }
    #[inline(always)]
    fn valid(&self) -> bool {
        self.is_valid()
    }
}

/// The corners of `tri` in the frame of the ray with origin lanes
/// `origin_lanes` and shear `shear`, a corner per lane: the sheared `x` and
/// `y`, the unscaled depth `p_z`, and the edge functions.
#[inline(always)]
pub(super) fn frame_lanes<V: Vector>(
    origin_lanes: &[L<V>; 3],
    shear_lanes: &[L<V>; 3],
    axes: &[Axis; 3],
    tri: &Triangle<V>,
) -> (L<V>, L<V>, L<V>, L<V>) {
    frame_lanes_at(origin_lanes, shear_lanes, axes, [&tri.a, &tri.b, &tri.c])
}

/// [`frame_lanes`] for the triangle with corners `a, b, c`.
#[inline(always)]
fn frame_lanes_at<V: Vector>(
    origin_lanes: &[L<V>; 3],
    shear_lanes: &[L<V>; 3],
    axes: &[Axis; 3],
    [a, b, c]: [&V; 3],
) -> (L<V>, L<V>, L<V>, L<V>) {
    let [sx, sy, _] = *shear_lanes;
    // Translate, permute, shear.
    let [px, py, pz] = translated(origin_lanes, axes, [a, b, c]);
    let x = px.add(sx.mul(pz));
    let y = py.add(sy.mul(pz));
    // Edge functions: lane i is x[i+1] y[i+2] - y[i+1] x[i+2].
    let e = x.rot1().mul(y.rot2()).sub(y.rot1().mul(x.rot2()));
    (x, y, pz, e)
}

/// The corners `a, b, c` translated to the ray's origin and permuted, a
/// corner per lane: `[p_x, p_y, p_z]`, the coordinates read in the ray's
/// axis order `axes`, as [`frame_lanes`] computes them.
#[inline(always)]
pub(super) fn translated<V: Vector>(
    origin_lanes: &[L<V>; 3],
    axes: &[Axis; 3],
    [a, b, c]: [&V; 3],
) -> [L<V>; 3] {
    let corners = |k: Axis| L::<V>::new(a.get(k), b.get(k), c.get(k));
    [0, 1, 2].map(|i| corners(axes[i]).sub(origin_lanes[i]))
}

/// One corner of eight triangles in the ray's frame, as `Frame::new`
/// computes it: translated, its axes in the ray's order `k`, sheared.
#[inline(always)]
pub(super) fn sheared<W: Lanes8, const N: usize>(
    p: &[[W::F; N]; 3],
    c: usize,
    k: [usize; 3],
    o: [W; 3],
    sx: W,
    sy: W,
) -> (W, W, W)
where
    W::F: Scalar,
{
    let px = lanes_at::<W, N>(&p[k[0]], c).sub(o[0]);
    let py = lanes_at::<W, N>(&p[k[1]], c).sub(o[1]);
    let pz = lanes_at::<W, N>(&p[k[2]], c).sub(o[2]);
    (px.add(sx.mul(pz)), py.add(sy.mul(pz)), pz)
}

/// The ray's part of the lanes' frame: the axis order, the origin in it,
/// and the shear, in every lane.
pub(super) struct RayLanes<W> {
    k: [usize; 3],
    o: [W; 3],
    sx: W,
    sy: W,
}

impl<W: Lanes8> RayLanes<W>
where
    W::F: Scalar,
{
    #[inline(always)]
    pub(super) fn new<V: Vector<Scalar = W::F>>(ray: &PreparedRay<V>) -> Self {
        let sh = ray.shear();
        // The origin in the ray's axis order, from the prepared lanes
        // (indexing the origin by axis would branch on the axis).
        let [ox, oy, oz] = ray.origin_lanes.map(|l| l.x());
        Self {
            k: [sh.kx as usize, sh.ky as usize, sh.kz as usize],
            o: [W::splat(ox), W::splat(oy), W::splat(oz)],
            sx: W::splat(sh.sx),
            sy: W::splat(sh.sy),
        }
    }

    /// Chunk `c` of the batch in the ray's frame: the edge functions
    /// `e0`, `e1`, `e2` (the scalar test's, operation for operation) and
    /// the corners' unscaled depths.
    #[inline(always)]
    pub(super) fn edges<const N: usize>(
        &self,
        p: &[[[W::F; N]; 3]; 3],
        c: usize,
    ) -> ([W; 3], [W; 3]) {
        let corners = self.corners(p, c);
        let [(_, _, pz0), (_, _, pz1), (_, _, pz2)] = corners;
        (edge_functions(&corners), [pz0, pz1, pz2])
    }

    /// Chunk `c` of the batch in the ray's frame: each corner's sheared
    /// `x`, `y` and unscaled depth `p_z`.
    #[inline(always)]
    pub(super) fn corners<const N: usize>(
        &self,
        p: &[[[W::F; N]; 3]; 3],
        c: usize,
    ) -> [(W, W, W); 3] {
        let (k, o, sx, sy) = (self.k, self.o, self.sx, self.sy);
        [
            sheared::<W, N>(&p[0], c, k, o, sx, sy),
            sheared::<W, N>(&p[1], c, k, o, sx, sy),
            sheared::<W, N>(&p[2], c, k, o, sx, sy),
        ]
    }
}

/// The edge functions of three corners in the ray's frame, the scalar
/// test's operations (`Frame::new`).
#[inline(always)]
pub(super) fn edge_functions<W: Lanes8>(
    [(x0, y0, _), (x1, y1, _), (x2, y2, _)]: &[(W, W, W); 3],
) -> [W; 3] {
    let e0 = x1.mul(*y2).sub(y1.mul(*x2));
    let e1 = x2.mul(*y0).sub(y2.mul(*x0));
    let e2 = x0.mul(*y1).sub(y0.mul(*x1));
    [e0, e1, e2]
}

/// Inside test of `EdgeRule::Closed` on lanes: not both signs among the
/// edge functions. For non-NaN values "some e_i < 0" is "min e_i < 0",
/// which is cheaper; a NaN edge function leaves the lane not outside (the
/// scalar test then misses it: its `det` is NaN). Returns `outside`, and
/// the smallest and largest edge function.
#[inline(always)]
pub(super) fn outside<W: Lanes8>([e0, e1, e2]: [W; 3], lo: W) -> (W::Mask, W, W) {
    let (e_min, e_max) = (e0.min(e1.min(e2)), e0.max(e1.max(e2)));
    (W::and(e_min.lt(lo), lo.lt(e_max)), e_min, e_max)
}
