//! The patch in the ray's frame: the ray's part (its shear and origin in
//! lanes, borrowed from a plain or a prepared ray), the four corners
//! framed at once as the watertight triangle test frames a triangle's
//! (a corner a lane), the edge functions of the two diagonal triangles
//! and their closed-rule inside tests, the fold test, and the corners'
//! coordinates with what the kernel reads off them (`v` at a root, the
//! depth, the orientation).

use super::collapsed::equal_neighbours;
use super::{Patch, lerp};
use crate::num::round::max2;
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::query::RayForm;
use crate::ray::{PreparedRay, Ray, Shear};
use crate::triangle::{Frame, edge_function};

/// The patch in the ray's frame: the corners' sheared `x`, `y` and depth
/// `z` (in units of `t`), in the boundary's order `00, 10, 11, 01`.
pub(super) struct Projected<F> {
    pub(super) x: [F; 4],
    pub(super) y: [F; 4],
    pub(super) z: [F; 4],
}

impl<F: Scalar> Projected<F> {
    /// `v` for the crossing at `u`: the place of the origin on the line
    /// from `A(u)` (on the edge `v = 0`) to `B(u)` (on `v = 1`), by least
    /// squares; NaN or infinite where the segment is a point (at a
    /// collapsed edge), which every caller's range test rejects.
    #[inline(always)]
    pub(super) fn v_at(&self, u: F) -> F {
        let (x, y) = (&self.x, &self.y);
        let (ax, ay) = (lerp(x[0], x[1], u), lerp(y[0], y[1], u));
        let (bx, by) = (lerp(x[3], x[2], u), lerp(y[3], y[2], u));
        let (dx, dy) = (bx - ax, by - ay);
        -(ax * dx + ay * dy) / (dx * dx + dy * dy)
    }

    /// How far the origin is from the projected point at `(u, v)` (the
    /// larger coordinate): zero at a crossing.
    #[inline(always)]
    pub(super) fn miss_at(&self, u: F, v: F) -> F {
        let (x, y) = (&self.x, &self.y);
        let px = lerp(lerp(x[0], x[1], u), lerp(x[3], x[2], u), v);
        let py = lerp(lerp(y[0], y[1], u), lerp(y[3], y[2], u), v);
        max2(px.abs(), py.abs())
    }

    /// The depth at `(u, v)`.
    #[inline(always)]
    pub(super) fn t_at(&self, u: F, v: F) -> F {
        let z = &self.z;
        lerp(lerp(z[0], z[1], u), lerp(z[3], z[2], u), v)
    }

    /// The sign of the projected Jacobian `dq/du x dq/dv` at `(u, v)`: the
    /// orientation of the patch there, seen along the ray.
    #[inline(always)]
    pub(super) fn orientation(&self, u: F, v: F) -> F {
        let (x, y) = (&self.x, &self.y);
        self.d_du(x, v) * self.d_dv(y, u) - self.d_du(y, v) * self.d_dv(x, u)
    }

    /// `dc/du` at `v` of the bilinear values `c` (corners `00, 10, 11,
    /// 01`).
    #[inline(always)]
    pub(super) fn d_du(&self, c: &[F; 4], v: F) -> F {
        lerp(c[1] - c[0], c[2] - c[3], v)
    }

    /// `dc/dv` at `u`.
    #[inline(always)]
    pub(super) fn d_dv(&self, c: &[F; 4], u: F) -> F {
        lerp(c[3] - c[0], c[2] - c[1], u)
    }
}

/// What a plain ray's frame computes and a prepared ray holds: its
/// shear, and the origin and the shear factors in lanes.
pub(crate) struct RayParts<V: Vector> {
    shear: Shear<S<V>>,
    origin_lanes: [L<V>; 3],
    shear_lanes: [L<V>; 3],
}

impl<V: Vector> RayParts<V> {
    /// A plain ray's (three divisions).
    #[inline(always)]
    pub(crate) fn new(ray: &Ray<V>) -> Self {
        let shear = Shear::new(&ray.dir);
        Self {
            origin_lanes: shear.origin_lanes(ray.origin),
            shear_lanes: shear.lanes(),
            shear,
        }
    }
}

/// The ray's part of the patch's frame, borrowed from a plain ray's
/// [`RayParts`] or from a prepared ray (nothing copied).
pub(crate) struct RayFrame<'a, V: Vector> {
    pub(super) origin_lanes: &'a [L<V>; 3],
    pub(super) shear_lanes: &'a [L<V>; 3],
    pub(super) axes: [Axis; 3],
    /// The shear's `sz` (`1 / d_z`) and `d_z`.
    pub(crate) sz: S<V>,
    pub(super) dz: S<V>,
    source: Source<'a, V>,
}

/// Where a [`RayFrame`] comes from.
enum Source<'a, V: Vector> {
    Plain(&'a Ray<V>, &'a Shear<S<V>>),
    Prepared(&'a PreparedRay<V>),
}

impl<'a, V: Vector> RayFrame<'a, V> {
    /// The frame of a plain ray, from its parts.
    #[inline(always)]
    pub(crate) fn plain(ray: &'a Ray<V>, parts: &'a RayParts<V>) -> Self {
        // (The axes field by field: a copy of the three bytes as one
        // piece was read back wider than it was written, which stalls.)
        let Shear { kx, ky, kz, .. } = parts.shear;
        Self {
            origin_lanes: &parts.origin_lanes,
            shear_lanes: &parts.shear_lanes,
            axes: [kx, ky, kz],
            sz: parts.shear.sz,
            dz: parts.shear.dz,
            source: Source::Plain(ray, &parts.shear),
        }
    }

    /// The frame of a prepared ray, which holds it.
    #[inline(always)]
    pub(crate) fn prepared(ray: &'a PreparedRay<V>) -> Self {
        Self {
            origin_lanes: &ray.origin_lanes,
            shear_lanes: &ray.shear_lanes,
            axes: ray.axes,
            sz: ray.shear_lanes[2].x(),
            dz: ray.dir.get(ray.axes[2]),
            source: Source::Prepared(ray),
        }
    }

    /// The ray (for the rare paths).
    #[inline(always)]
    pub(super) fn ray(&self) -> Ray<V> {
        match self.source {
            Source::Plain(r, _) => *r,
            Source::Prepared(p) => p.to_ray(),
        }
    }

    /// The shear (for the rare paths), the very one `Shear::new` computes.
    #[inline(always)]
    pub(super) fn shear(&self) -> Shear<S<V>> {
        match self.source {
            Source::Plain(_, s) => *s,
            Source::Prepared(p) => p.shear(),
        }
    }
}

/// The patch in the ray's frame: its four corners framed as the
/// watertight triangle test frames a triangle's (so the values are bit for
/// bit those of every triangle with the corner), the edge functions of the
/// two triangles `p00, p10, p11` and `p00, p11, p01` (signs exact), and
/// the corners' coordinates.
pub(super) struct Framed<F> {
    /// The first triangle's edge functions, then the second's, in the
    /// triangle test's order (each opposite a corner).
    pub(super) e1: [F; 3],
    pub(super) e2: [F; 3],
    pub(super) p: Projected<F>,
    /// Whether each triangle's edge functions take both strict signs
    /// (the closed rule's miss).
    pub(super) straddles: [bool; 2],
}

/// The four corners in the ray's frame, a corner a lane in the order of
/// the boundary, `00, 10, 11, 01`: sheared `x`, `y` (as
/// `frame_lanes_at` computes them) and the depth `z` in units of `t`.
pub(crate) struct CornerLanes<V: Vector> {
    pub(crate) x: L<V>,
    pub(crate) y: L<V>,
    pub(crate) z: L<V>,
    /// The collapsed edges ([`equal_neighbours`] of the corners as
    /// given).
    pub(super) collapsed: u32,
}

impl<V: Vector> CornerLanes<V> {
    /// The patch's corners.
    #[inline(always)]
    pub(super) fn new(r: &RayFrame<V>, patch: &Patch<V>) -> Self {
        Self::of(r, |k| patch.boundary_lanes(k)).0
    }

    /// The four corners whose coordinate on axis `k` is `corners(k)`,
    /// translated, the axes in the ray's order, sheared: each corner's
    /// `x` and `y` bit for bit as the triangle test's `frame_lanes_at`
    /// computes them; and their translated depths before the shear's
    /// scaling (`z` unscaled).
    #[inline(always)]
    pub(crate) fn of(r: &RayFrame<V>, corners: impl Fn(Axis) -> L<V>) -> (Self, L<V>) {
        let [sx, sy, _] = *r.shear_lanes;
        let [ox, oy, oz] = *r.origin_lanes;
        let (kx, ky, kz) = (corners(r.axes[0]), corners(r.axes[1]), corners(r.axes[2]));
        let pz = kz.sub(oz);
        let x = kx.sub(ox).add(sx.mul(pz));
        let y = ky.sub(oy).add(sy.mul(pz));
        let lanes = Self {
            x,
            y,
            z: pz.mul(L::<V>::splat(r.sz)),
            collapsed: equal_neighbours([kx, ky, kz]),
        };
        (lanes, pz)
    }

    /// The boundary's four edge functions, lane `i` the edge from corner
    /// `i` to corner `i + 1`: each bit for bit the triangle test's for
    /// that edge and direction.
    #[inline(always)]
    pub(crate) fn edges(&self) -> L<V> {
        self.x.mul(self.y.roll4()).sub(self.y.mul(self.x.roll4()))
    }

    /// The diagonals' edge functions, lane `i` from corner `i` to corner
    /// `i + 2` (lane 0 from `00` to `11`, lane 2 back), as
    /// [`CornerLanes::edges`].
    #[inline(always)]
    pub(crate) fn diagonals(&self) -> L<V> {
        let (x2, y2) = (self.x.roll4().roll4(), self.y.roll4().roll4());
        self.x.mul(y2).sub(self.y.mul(x2))
    }

    /// Whether the projected patch may fold over itself: its Jacobian
    /// `dq/du x dq/dv` (affine in `u` and in `v`) takes both strict signs
    /// at the corners. Lane `i`, the cross product of the boundary's edge
    /// into and its edge out of the corner after corner `i` (along `00,
    /// 10, 11, 01`), is the Jacobian at that corner, bit for bit up to the
    /// sign of a zero (at `10`: `dq/du = q10 - q00`, `dq/dv = q11 - q10`;
    /// at `11`: `(q11 - q10) x (q01 - q11) = -(q01 - q11) x (q11 - q10)`;
    /// likewise at `01` and `00`).
    #[inline(always)]
    pub(super) fn may_fold(&self) -> bool {
        let (dx, dy) = (self.x.roll4().sub(self.x), self.y.roll4().sub(self.y));
        let j = dx.mul(dy.roll4()).sub(dy.mul(dx.roll4()));
        let zero = L::<V>::splat(S::<V>::ZERO);
        j.lt4(zero) != 0 && zero.lt4(j) != 0
    }
}

impl<F: Scalar> Framed<F> {
    /// From the corners' lanes ([`CornerLanes`]). The boundary's four edge
    /// functions come in one go, lane `i` the edge from corner `i` to
    /// corner `i + 1` of the boundary, and the diagonal's apart; an edge
    /// function of zero gets its exact sign, as in `Frame::new`. A shared
    /// edge's function is its neighbour's, bit for bit (negated where the
    /// neighbour runs the other way).
    #[inline(always)]
    pub(super) fn new<V: Vector<Scalar = F>>(c: &CornerLanes<V>) -> Self {
        let edges = c.edges();
        let (x, y, z) = (c.x.to_array4(), c.y.to_array4(), c.z.to_array4());
        let mut e = edges.to_array4();
        // (As lane 0 of `CornerLanes::diagonals`.)
        let mut diag = x[0] * y[2] - y[0] * x[2];
        let zero = L::<V>::splat(F::ZERO);
        let (mut neg, mut pos) = (edges.lt4(zero), zero.lt4(edges));
        // (Not both signs: zero, or NaN from overflow.)
        if neg | pos != 0b1111 || !(diag.abs() > F::ZERO) {
            for (i, e) in e.iter_mut().enumerate() {
                let j = (i + 1) % 4;
                *e = edge_function((x[i], y[i]), (x[j], y[j]));
            }
            diag = edge_function((x[0], y[0]), (x[2], y[2]));
            let bits = |f: fn(F) -> bool| (0..4).map(|i| u32::from(f(e[i])) << i).sum();
            (neg, pos) = (bits(|e| e < F::ZERO), bits(|e| e > F::ZERO));
        }
        // The triangle test's lane `i` is the edge opposite corner `i`:
        // on `00, 10, 11` the edges 10-11, 11-00 and 00-10; on `00, 11,
        // 01` the edges 11-01, 01-00 and 00-11.
        Self {
            e1: [e[1], -diag, e[0]],
            e2: [e[2], e[3], diag],
            p: Projected { x, y, z },
            straddles: diagonal_straddles(neg, pos, diag),
        }
    }
}

/// Whether each of the triangles `00, 10, 11` and `00, 11, 01` has edge
/// functions of both strict signs (the closed rule's miss), from the
/// boundary's edge functions' signs (bit `i` of `neg` and `pos`: lane `i`
/// of [`CornerLanes::edges`]) and the diagonal's edge function from `00`
/// to `11`.
#[inline(always)]
fn diagonal_straddles<F: Scalar>(neg: u32, pos: u32, diag: F) -> [bool; 2] {
    // Bits 4 and 5: the diagonal as the first triangle's edge (`11` to
    // `00`) and as the second's (`00` to `11`).
    let (dneg, dpos) = (u32::from(diag < F::ZERO), u32::from(diag > F::ZERO));
    let (neg, pos) = (neg | dpos << 4 | dneg << 5, pos | dneg << 4 | dpos << 5);
    // (`&`, not `&&`: each flag a coin toss on aimed rays, and a branch
    // apiece where `&&` made two.)
    let both = |edges: u32| (neg & edges != 0) & (pos & edges != 0);
    [both(0b01_0011), both(0b10_1100)]
}

/// The patch's two triangles' frames, as `Frame::new` makes them (the
/// same values the lanes hold; for the one-hit rule and the bounds).
#[inline(always)]
pub(super) fn frames<V: Vector>(r: &RayFrame<V>, patch: &Patch<V>) -> [Frame<S<V>>; 2] {
    let (origin, shear) = (r.ray().origin, r.shear());
    patch
        .triangles()
        .map(|tri| Frame::new(origin, &tri, &shear))
}

/// Whether a triangle of the patch covers the ray, and how it is
/// oriented there (its determinant's sign): `pos`, `neg`, or neither.
/// (Flags, not an `Option` of a sign: which triangle covers the ray and
/// from which side are coin tosses, and flags combine without branches.)
#[derive(Clone, Copy)]
pub(super) struct Cover {
    pub(super) pos: bool,
    pub(super) neg: bool,
}

impl Cover {
    /// Covers nothing.
    pub(super) const NONE: Self = Self {
        pos: false,
        neg: false,
    };

    /// A triangle that covers the ray with the edge functions `e` (all of
    /// one sign or zero, or NaN from overflow): its orientation is the
    /// sign of their sum; a triangle of zero area (the collapsed half of
    /// a degenerate patch) or with a NaN edge function covers nothing.
    #[inline(always)]
    pub(super) fn of<F: Scalar>(e: [F; 3]) -> Self {
        let det = e[0] + e[1] + e[2];
        Self {
            pos: det > F::ZERO,
            neg: det < F::ZERO,
        }
    }

    /// The closed rule's inside test on a triangle's edge functions (as
    /// the watertight test's: no two of opposite signs, a zero inside).
    #[inline(always)]
    pub(super) fn closed<F: Scalar>(e: [F; 3], straddles: bool) -> Self {
        let c = Self::of(e);
        Self {
            pos: c.pos & !straddles,
            neg: c.neg & !straddles,
        }
    }

    /// Whether it covers the ray.
    #[inline(always)]
    pub(super) fn any(self) -> bool {
        self.pos | self.neg
    }
}
