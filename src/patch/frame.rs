//! The patch in the ray's frame: the ray's part (its shear and origin in
//! lanes, from a plain or a prepared ray), the two diagonal triangles
//! framed as the watertight triangle test frames them, their closed-rule
//! inside tests, and the four corners' coordinates with what the kernel
//! reads off them (`v` at a root, the depth, the orientation).

use super::{Patch, lerp};
use crate::num::round::max2;
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::query::RayForm;
use crate::ray::{PreparedRay, Ray, Shear};
use crate::triangle::{Frame, edge_function, frame_lanes_at};

/// The patch in the ray's frame: the corners' sheared `x`, `y` and depth
/// `z` (in units of `t`), in the order `00, 10, 01, 11`.
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
        let (bx, by) = (lerp(x[2], x[3], u), lerp(y[2], y[3], u));
        let (dx, dy) = (bx - ax, by - ay);
        -(ax * dx + ay * dy) / (dx * dx + dy * dy)
    }

    /// How far the origin is from the projected point at `(u, v)` (the
    /// larger coordinate): zero at a crossing.
    #[inline(always)]
    pub(super) fn miss_at(&self, u: F, v: F) -> F {
        let (x, y) = (&self.x, &self.y);
        let px = lerp(lerp(x[0], x[1], u), lerp(x[2], x[3], u), v);
        let py = lerp(lerp(y[0], y[1], u), lerp(y[2], y[3], u), v);
        max2(px.abs(), py.abs())
    }

    /// The depth at `(u, v)`.
    #[inline(always)]
    pub(super) fn t_at(&self, u: F, v: F) -> F {
        let z = &self.z;
        lerp(lerp(z[0], z[1], u), lerp(z[2], z[3], u), v)
    }

    /// The sign of the projected Jacobian `dq/du x dq/dv` at `(u, v)`: the
    /// orientation of the patch there, seen along the ray.
    #[inline(always)]
    pub(super) fn orientation(&self, u: F, v: F) -> F {
        let (x, y) = (&self.x, &self.y);
        self.d_du(x, v) * self.d_dv(y, u) - self.d_du(y, v) * self.d_dv(x, u)
    }

    /// [`orientation`](Self::orientation) at the four corners, `(0, 0)`,
    /// `(1, 0)`, `(0, 1)`, `(1, 1)`, with the derivatives read off the
    /// edges: the same values but for the sign of a zero (a `lerp` at 0
    /// or 1 is its end).
    #[inline(always)]
    pub(super) fn corner_orientations(&self) -> [F; 4] {
        let (x, y) = (&self.x, &self.y);
        let d = |i: usize, j: usize| (x[j] - x[i], y[j] - y[i]);
        let cross = |(ax, ay): (F, F), (bx, by): (F, F)| ax * by - ay * bx;
        // dq/du along v = 0 and v = 1, dq/dv along u = 0 and u = 1.
        let (du0, du1) = (d(0, 1), d(2, 3));
        let (dv0, dv1) = (d(0, 2), d(1, 3));
        [
            cross(du0, dv0),
            cross(du0, dv1),
            cross(du1, dv0),
            cross(du1, dv1),
        ]
    }

    /// `dc/du` at `v` of the bilinear values `c` (corners `00, 10, 01,
    /// 11`).
    #[inline(always)]
    pub(super) fn d_du(&self, c: &[F; 4], v: F) -> F {
        lerp(c[1] - c[0], c[3] - c[2], v)
    }

    /// `dc/dv` at `u`.
    #[inline(always)]
    pub(super) fn d_dv(&self, c: &[F; 4], u: F) -> F {
        lerp(c[2] - c[0], c[3] - c[1], u)
    }
}

/// The ray's part of the patch's frame: its origin and shear in lanes
/// and its axis order (what a prepared ray holds), and the shear itself.
pub(super) struct RayFrame<V: Vector> {
    pub(super) origin: V,
    pub(super) dir: V,
    pub(super) shear: Shear<S<V>>,
    pub(super) origin_lanes: [L<V>; 3],
    pub(super) shear_lanes: [L<V>; 3],
    pub(super) axes: [Axis; 3],
}

impl<V: Vector> RayFrame<V> {
    /// The frame of a plain ray: its shear computed (three divisions).
    #[inline(always)]
    pub(super) fn plain(ray: &Ray<V>) -> Self {
        let shear = Shear::new(&ray.dir);
        Self {
            origin: ray.origin,
            dir: ray.dir,
            origin_lanes: shear.origin_lanes(ray.origin),
            shear_lanes: shear.lanes(),
            axes: [shear.kx, shear.ky, shear.kz],
            shear,
        }
    }

    /// The frame of a prepared ray, which holds it.
    #[inline(always)]
    pub(super) fn prepared(ray: &PreparedRay<V>) -> Self {
        let r = ray.to_ray();
        Self {
            origin: r.origin,
            dir: r.dir,
            shear: ray.shear(),
            origin_lanes: ray.origin_lanes,
            shear_lanes: ray.shear_lanes,
            axes: ray.axes,
        }
    }
}

/// The patch in the ray's frame: the two triangles `p00, p10, p11` and
/// `p00, p11, p01` (`Patch::triangles`) framed as the watertight triangle
/// test frames them (a corner a lane), their edge functions (signs exact),
/// and the four corners' coordinates.
pub(super) struct Framed<F> {
    /// The first triangle's edge functions, then the second's, in the
    /// triangle test's order (each opposite a corner).
    pub(super) e1: [F; 3],
    pub(super) e2: [F; 3],
    pub(super) p: Projected<F>,
}

/// A triangle in the ray's frame, a corner a lane (`frame_lanes_at`): the
/// sheared `x`, `y`, the unscaled depth and the edge functions.
pub(super) type Lanes4<V> = (L<V>, L<V>, L<V>, L<V>);

/// The patch's two triangles, `p00, p10, p11` and `p00, p11, p01`, in the
/// ray's frame.
#[inline(always)]
pub(super) fn frame_pair<V: Vector>(r: &RayFrame<V>, patch: &Patch<V>) -> [Lanes4<V>; 2] {
    let frame = |c: [&V; 3]| frame_lanes_at(&r.origin_lanes, &r.shear_lanes, &r.axes, c);
    [
        frame([&patch.p00, &patch.p10, &patch.p11]),
        frame([&patch.p00, &patch.p11, &patch.p01]),
    ]
}

impl<F: Scalar> Framed<F> {
    /// From the two triangles' lanes ([`frame_pair`]).
    #[inline(always)]
    pub(super) fn new<V: Vector<Scalar = F>>(r: &RayFrame<V>, pair: [Lanes4<V>; 2]) -> Self {
        let arrays = |(x, y, pz, e): Lanes4<V>| {
            let (x, y, pz) = (x.to_array(), y.to_array(), pz.to_array());
            let mut e = e.to_array();
            // An edge function of zero gets its exact sign, as in
            // `Frame::new`.
            if e.contains(&F::ZERO) {
                for (i, e) in e.iter_mut().enumerate() {
                    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                    *e = edge_function((x[j], y[j]), (x[k], y[k]));
                }
            }
            (x, y, pz, e)
        };
        let [(x1, y1, z1, e1), (x2, y2, z2, e2)] = pair.map(arrays);
        let sz = r.shear.sz;
        // Corners 00, 10, 01, 11.
        let p = Projected {
            x: [x1[0], x1[1], x2[2], x1[2]],
            y: [y1[0], y1[1], y2[2], y1[2]],
            z: [z1[0] * sz, z1[1] * sz, z2[2] * sz, z1[2] * sz],
        };
        Self { e1, e2, p }
    }
}

/// The patch's two triangles' frames, as `Frame::new` makes them (the
/// same values the lanes hold; for the one-hit rule and the bounds).
#[inline(always)]
pub(super) fn frames<V: Vector>(r: &RayFrame<V>, patch: &Patch<V>) -> [Frame<S<V>>; 2] {
    patch
        .triangles()
        .map(|tri| Frame::new(r.origin, &tri, &r.shear))
}

/// The closed rule's inside test on a triangle's edge functions (as the
/// watertight test's: no two of opposite signs, a zero inside), and the
/// triangle's orientation where it covers the ray; a triangle of zero
/// area (the collapsed half of a degenerate patch) or with a NaN edge
/// function covers nothing.
#[inline(always)]
pub(super) fn closed_cover<F: Scalar>(e: [F; 3]) -> Option<i8> {
    let zero = F::ZERO;
    let neg = (e[0] < zero) | (e[1] < zero) | (e[2] < zero);
    let pos = (e[0] > zero) | (e[1] > zero) | (e[2] > zero);
    if neg & pos {
        return None;
    }
    Some(orientation_of(e)).filter(|&s| s != 0)
}

/// The sign of a triangle's determinant from its inside test's edge
/// functions (all of one sign or zero, or NaN from overflow): `1`, `-1`
/// or `0`.
#[inline(always)]
pub(super) fn orientation_of<F: Scalar>(e: [F; 3]) -> i8 {
    let det = e[0] + e[1] + e[2];
    if det > F::ZERO {
        1
    } else if det < F::ZERO {
        -1
    } else {
        0
    }
}
