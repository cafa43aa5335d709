//! Triangles: the watertight test (closed, and a one-hit-per-crossing
//! variant for meshes) and Moller-Trumbore.

use glam::Vec3;

use crate::aabb::PreparedRay;
use crate::lanes::{Axis, Lanes};
use crate::ray::{Ray, t_max_ok};
use crate::real::{L, S, Scalar, Vector, bound_up, max2, min2, scale_to_one};

/// The triangle with corners `a`, `b`, `c`.
///
/// The winding `a -> b -> c` defines the geometric normal
/// `(b - a) x (c - a)` (right-handed: counter-clockwise seen from the side it
/// points to) and so which side of a hit is [`Side::Front`]. The tests are
/// two-sided and report the side. A triangle with a NaN or infinite
/// coordinate is hit by nothing.
///
/// **Zero-area triangles** (corners collinear or coincident, exactly:
/// [`Triangle::is_degenerate`]) can be hit, on purpose. The watertight tests
/// hit one where, in the ray's sheared frame, its rounded corners enclose the
/// ray: rounding gives the segment a sliver of area there. Meshes close
/// T-junctions (a vertex on another triangle's edge, filled with the
/// zero-area triangle between that edge and the two halves) and collapsed
/// edges with such triangles, and in the rounded frame the filler is exactly
/// the sliver between the neighbours' edges; dropping it would open a crack
/// just there. A hit on one has `u`, `v` in range, the side of its rounded
/// determinant, and the `t` where the ray passes the segment, within the
/// finite bound [`ray_triangle_error_bounds`] gives; its normal is zero or
/// meaningless, so shade it with a neighbour's. [`SurfacePoint::on_triangle`] and
/// [`SurfacePoint::spawn`] stay finite: with a zero normal the spawned
/// ray starts at the hit point itself. Use [`Triangle::is_degenerate`] to
/// drop such triangles when loading a mesh that does not need them.
///
/// [`SurfacePoint::on_triangle`]: crate::SurfacePoint::on_triangle
/// [`SurfacePoint::spawn`]: crate::SurfacePoint::spawn
///
/// ```
/// use rayhit::{Triangle, glam::Vec3};
/// let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(t.normal(), Vec3::Z);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Triangle<V = Vec3> {
    /// First corner; barycentric weight `1 - u - v`.
    pub a: V,
    /// Second corner; barycentric weight `u`.
    pub b: V,
    /// Third corner; barycentric weight `v`.
    pub c: V,
}

impl<V: Vector> Triangle<V> {
    /// The triangle `a, b, c`. Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(a: V, b: V, c: V) -> Self {
        Self { a, b, c }
    }

    /// The geometric normal `(b - a) x (c - a)`, not normalised (its length
    /// is twice the area), rounded.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> V {
        (self.b - self.a).cross(self.c - self.a)
    }

    /// The geometric normal [`Triangle::normal`] and a per-component bound on
    /// its difference from the exact `(b - a) x (c - a)`.
    ///
    /// Each monomial `e1_j e2_k` of a component carries four roundings (two
    /// edge subtractions, the product, the difference), so the error is at
    /// most `gamma(4) (|e1_j e2_k| + |e1_k e2_j|)`, and `gamma(6)` with the
    /// computed edges; evaluating that adds three roundings. For a sliver
    /// triangle the bound can be as large as the normal itself: its
    /// direction is then not known, and [`offset_ray_origin`](crate::offset_ray_origin)
    /// offsets accordingly.
    #[inline]
    #[must_use]
    pub fn normal_with_error(&self) -> (V, V) {
        let (e1, e2) = (self.b - self.a, self.c - self.a);
        let g6 = S::<V>::gamma_n(6);
        let m = |j: usize, k: usize| (e1[j] * e2[k]).abs() + (e1[k] * e2[j]).abs();
        let err = V::new(m(1, 2), m(2, 0), m(0, 1)) * g6;
        let err = V::new(
            bound_up(err.x(), 3),
            bound_up(err.y(), 3),
            bound_up(err.z(), 3),
        );
        (e1.cross(e2), err)
    }

    /// True when the corners are collinear or coincide, in exact arithmetic:
    /// `(b - a) x (c - a)` is exactly zero. No tolerance: a triangle with
    /// the smallest area the coordinates allow is not degenerate.
    ///
    /// For loading meshes: the watertight tests still hit such a triangle
    /// where its rounded corners enclose the ray (see [`Triangle`]); drop
    /// it only where the mesh does not rely on it to stay closed.
    ///
    /// Exact: the rounded cross product decides when a component clearly
    /// exceeds its rounding error (almost always: a few dozen operations);
    /// otherwise each difference is split into its rounded value and exact
    /// error (Knuth's two-sum) and each component's sign is computed exactly
    /// from the sixteen products (Shewchuk's expansions; a few hundred
    /// operations). For `f64`, exact as long as no product of two
    /// coordinate differences, scaled to the largest, underflows (the
    /// differences within a factor `2^900` of each other).
    ///
    /// ```
    /// use rayhit::{Triangle, glam::Vec3};
    /// // c - a = 2 (b - a): collinear, exactly.
    /// let line = Triangle::new(Vec3::new(6.0, -5.0, 2.0), Vec3::new(4.0, -2.0, 5.0), Vec3::new(2.0, 1.0, 8.0));
    /// assert!(line.is_degenerate());
    /// // Off the line by one ulp: not degenerate.
    /// let sliver = Triangle::new(line.a, line.b, Vec3::new(2.0, 1.0, 8.0f32.next_up()));
    /// assert!(!sliver.is_degenerate());
    /// assert!(Triangle::new(Vec3::ONE, Vec3::ONE, Vec3::ONE).is_degenerate());
    /// ```
    #[must_use]
    pub fn is_degenerate(&self) -> bool {
        let (n, err) = self.normal_with_error();
        if n.abs().x() > err.x() || n.abs().y() > err.y() || n.abs().z() > err.z() {
            return false;
        }
        // Exact differences: b - a = s1 + e1, c - a = s2 + e2.
        let split = |p: V, q: V| {
            let d = |k: usize| S::<V>::two_diff(p[k], q[k]);
            [d(0), d(1), d(2)]
        };
        let (u, v) = (split(self.b, self.a), split(self.c, self.a));
        // Scale each difference vector's parts by a common power of two
        // first (exact), so that tiny or huge coordinates neither underflow
        // nor overflow the products.
        let scale = |w: [(S<V>, S<V>); 3]| {
            let m = w.iter().fold(0.0f64, |m, (s, _)| m.max(s.to_f64().abs()));
            if m == 0.0 {
                return w.map(|(s, e)| (s.to_f64(), e.to_f64()));
            }
            w.map(|(s, e)| (scale_to_one(s.to_f64(), m), scale_to_one(e.to_f64(), m)))
        };
        let (u, v) = (scale(u), scale(v));
        // Component k of u x v: u_j v_l - u_l v_j, (j, l) = (k + 1, k + 2).
        (0..3).all(|k| {
            let (j, l) = ((k + 1) % 3, (k + 2) % 3);
            let ((uj, ej), (ul, el)) = (u[j], u[l]);
            let ((vj, fj), (vl, fl)) = (v[j], v[l]);
            let terms = [
                (uj, vl),
                (uj, fl),
                (ej, vl),
                (ej, fl),
                (-ul, vj),
                (-ul, fj),
                (-el, vj),
                (-el, fj),
            ];
            f64::sum_of_products_sign(&terms) == core::cmp::Ordering::Equal
        })
    }

    /// The same triangle with the opposite winding (`a, c, b`): the normal
    /// flips, `u` and `v` swap, and front and back swap.
    #[inline]
    #[must_use]
    pub fn flipped(&self) -> Self {
        Self {
            a: self.a,
            b: self.c,
            c: self.b,
        }
    }
}

/// Which side of a triangle a ray arrived from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// Against the geometric normal (`dir . normal < 0`): the side the normal
    /// points to, where the winding looks counter-clockwise.
    Front,
    /// Along the geometric normal (`dir . normal > 0`).
    Back,
}

/// A ray/triangle hit.
///
/// The hit point is `(1 - u - v) * a + u * b + v * c = origin + t * dir`;
/// `t` is in units of the ray's `dir`, `0 < t <= t_max`; `u` and `v` are each
/// in `[0, 1]` (their sum can exceed 1 by a rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// Barycentric weight of corner `b`.
    pub u: F,
    /// Barycentric weight of corner `c`.
    pub v: F,
    /// The side the ray arrived from: the sign of the computed determinant
    /// (`dir . normal`), which is the exact sign whenever
    /// [`ray_triangle_error_bounds`] for the hit is finite (it is infinite
    /// exactly when that sign is not certain: a ray within rounding of
    /// parallel, or a sliver seen edge-on).
    pub side: Side,
}

/// The per-ray part of the watertight test: which axis the ray mostly runs
/// along, and the shear that maps its direction to `+z`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shear<F: Scalar> {
    /// The axis of the direction's largest magnitude component; `kx, ky`
    /// follow it cyclically, so the permutation keeps the handedness.
    pub(crate) kx: Axis,
    pub(crate) ky: Axis,
    pub(crate) kz: Axis,
    /// `-d_x / d_z` and `-d_y / d_z` in the permuted frame: `|s_x|, |s_y| <= 1`.
    pub(crate) sx: F,
    pub(crate) sy: F,
    /// `1 / d_z`.
    pub(crate) sz: F,
    /// `d_z` itself, for the side of a hit.
    pub(crate) dz: F,
}

impl<F: Scalar> PartialEq for Shear<F> {
    fn eq(&self, o: &Self) -> bool {
        (self.kz, self.sx, self.sy, self.sz, self.dz) == (o.kz, o.sx, o.sy, o.sz, o.dz)
    }
}

/// The index of the ray's main axis from the magnitudes of its direction's
/// components: x if `|d_x| > |d_y|` and `|d_x| > |d_z|`, else y if
/// `|d_y| > |d_z|`, else z. Written as selects rather than branches (the
/// direction of the next ray is not predictable).
#[inline(always)]
fn largest_axis<F: Scalar>(a: [F; 3]) -> usize {
    let x_wins = a[0] > a[1];
    let larger = if x_wins { a[0] } else { a[1] };
    if larger > a[2] {
        usize::from(!x_wins)
    } else {
        2
    }
}

impl<F: Scalar> Shear<F> {
    #[inline(always)]
    pub(crate) fn new<V: Vector<Scalar = F>>(dir: &V) -> Self {
        let a = dir.abs();
        let k = largest_axis([a.x(), a.y(), a.z()]);
        let (kz, kx, ky) = (
            Axis::from_index(k),
            Axis::from_index(if k == 2 { 0 } else { k + 1 }),
            Axis::from_index(if k == 0 { 2 } else { k - 1 }),
        );
        let (dx, dy, dz) = (dir.get(kx), dir.get(ky), dir.get(kz));
        // Three quotients, each rounded once, in one division of lanes.
        let q = F::Lanes::new(-dx, -dy, F::ONE).div(F::Lanes::splat(dz));
        let [sx, sy, sz] = q.to_array();
        Self {
            kx,
            ky,
            kz,
            sx,
            sy,
            sz,
            dz,
        }
    }

    /// `sx`, `sy`, `sz`, each in every lane: what the lanes form of the
    /// test multiplies by.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> [F::Lanes; 3] {
        [
            F::Lanes::splat(self.sx),
            F::Lanes::splat(self.sy),
            F::Lanes::splat(self.sz),
        ]
    }

    /// `(v[kx], v[ky], v[kz])`.
    #[inline(always)]
    pub(crate) fn permute<V: Vector<Scalar = F>>(&self, v: V) -> (F, F, F) {
        (v.get(self.kx), v.get(self.ky), v.get(self.kz))
    }

    /// `origin[kx]`, `origin[ky]`, `origin[kz]`, each in every lane: what
    /// the lanes form of the test subtracts from the corners.
    #[inline(always)]
    pub(crate) fn origin_lanes<V: Vector<Scalar = F>>(&self, origin: V) -> [F::Lanes; 3] {
        let (x, y, z) = self.permute(origin);
        [F::Lanes::splat(x), F::Lanes::splat(y), F::Lanes::splat(z)]
    }
}

/// The triangle in the ray's frame: translated to the ray origin, permuted,
/// and sheared in `x, y`; the ray is the `+z` axis.
#[derive(Clone, Copy, Debug)]
struct Frame<F> {
    /// Sheared `x` and `y` of the three corners.
    x: [F; 3],
    y: [F; 3],
    /// Translated, permuted, unsheared coordinates (for the error bounds).
    px: [F; 3],
    py: [F; 3],
    pz: [F; 3],
    /// Edge functions: `e[i]` is the 2-D cross product of the two corners
    /// other than `i` (in order `i+1, i+2`), with its sign exact.
    e: [F; 3],
}

impl<F: Scalar> Frame<F> {
    /// The corners' depths along the ray in units of `t`: `p_z / d_z`,
    /// computed as `p_z fl(1 / d_z)`.
    #[inline(always)]
    fn scaled_z(&self, shear: &Shear<F>) -> [F; 3] {
        self.pz.map(|p| p * shear.sz)
    }

    #[inline(always)]
    fn new<V: Vector<Scalar = F>>(origin: V, tri: &Triangle<V>, shear: &Shear<F>) -> Self {
        let mut f = Frame {
            x: [F::ZERO; 3],
            y: [F::ZERO; 3],
            px: [F::ZERO; 3],
            py: [F::ZERO; 3],
            pz: [F::ZERO; 3],
            e: [F::ZERO; 3],
        };
        for (i, p) in [tri.a, tri.b, tri.c].into_iter().enumerate() {
            // Translate, permute, shear.
            let (px, py, pz) = shear.permute(p - origin);
            f.px[i] = px;
            f.py[i] = py;
            f.pz[i] = pz;
            f.x[i] = px + shear.sx * pz;
            f.y[i] = py + shear.sy * pz;
        }
        // Edge functions. Rounding is monotone, so fl(fl(ab) - fl(cd)) has
        // the sign of ab - cd or is zero; only a zero needs the exact
        // recomputation (Woop, Benthin and Wald, JCGT 2013, section 3).
        for i in 0..3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let e = f.x[j] * f.y[k] - f.y[j] * f.x[k];
            f.e[i] = if e == F::ZERO {
                F::diff_of_products_exact_sign(f.x[j], f.y[k], f.y[j], f.x[k])
            } else {
                e
            };
        }
        f
    }

    /// The one-hit tie-break for edge `i` (from corner `i+1` to `i+2`) when
    /// its edge function is exactly zero: the sign the edge function takes
    /// once the ray is moved by an infinitesimal `(eps1, eps2)` with
    /// `0 < eps2 << eps1`. Some(true) positive, Some(false) negative, None
    /// for an edge of zero length in the sheared plane.
    ///
    /// For the edge `P -> Q` and a point `X`, the edge function is
    /// `(P - X) x (Q - X) = P x Q - X_x D_y + X_y D_x` with `D = Q - P`. With
    /// `P x Q = 0` and `X = (eps1, eps2)` its sign is that of `-D_y`, or of
    /// `D_x` when `D_y = 0`. Only comparisons are needed, so it is exact.
    #[inline(always)]
    fn tie_break(&self, i: usize) -> Option<bool> {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let (py, qy) = (self.y[j], self.y[k]);
        let (px, qx) = (self.x[j], self.x[k]);
        if py != qy {
            Some(py > qy)
        } else if px != qx {
            Some(qx > px)
        } else {
            None
        }
    }
}

/// Which edge rule the watertight core applies to an edge function of
/// exactly zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum EdgeRule {
    /// Zero counts as inside: edges and corners belong to every triangle
    /// that has them.
    Closed,
    /// Zero is decided by the symbolic perturbation in `Frame::tie_break`:
    /// each edge or corner point belongs to exactly one triangle of a
    /// consistently wound mesh.
    OneHit,
}

/// The watertight test shared by [`ray_triangle`] and
/// [`ray_triangle_one_hit`].
#[inline(always)]
fn watertight<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    if !(ray.is_valid() && t_max_ok(t_max)) {
        return None;
    }
    match rule {
        EdgeRule::Closed => watertight_every_axis(ray, tri, t_max),
        EdgeRule::OneHit => watertight_sheared(ray.origin, &Shear::new(&ray.dir), tri, t_max, rule),
    }
}

/// The closed watertight test for a valid ray (not prepared) and a
/// `t_max >= 0`, computed for all three choices of the ray's main axis at
/// once, lane `k` being the test in the frame with `kz = k`, and decided
/// on the lane of the ray's actual main axis.
///
/// Lane `k` runs exactly the operations of [`watertight_sheared`] with
/// `kz = k` (the shear factors `-d[k+1] / d[k]`, `-d[k+2] / d[k]` and
/// `1 / d[k]`, each one division; the corners translated in their natural
/// axis order, so that `p[k+1]`, `p[k+2]`, `p[k]` are the permuted `px`,
/// `py`, `pz`), so on the chosen lane its values are the definition's,
/// bit for bit. Nothing waits for the choice of the axis: on one ray
/// against one triangle, that shortens the chain of dependent operations
/// (the ray's shear is not known in advance) more than the two other
/// lanes cost. The rare cases go to [`watertight_sheared`], as in
/// [`watertight_lanes`].
#[inline(always)]
fn watertight_every_axis<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    let splat = L::<V>::splat;
    let lanes = |v: V| L::<V>::new(v.x(), v.y(), v.z());
    let (zero, one) = (splat(S::<V>::ZERO), splat(S::<V>::ONE));
    let (o, d) = (lanes(ray.origin), lanes(ray.dir));
    let kz = largest_axis(d.abs().to_array());
    let bit = 1 << kz;
    let slow = || S::<V>::unpack_hit(per_call_slow(ray, tri, t_max));
    // The three candidate shears: lane k holds -d[k+1] / d[k],
    // -d[k+2] / d[k] and 1 / d[k].
    let sx = d.rot1().neg().div(d);
    let sy = d.rot2().neg().div(d);
    let sz = one.div(d);
    // Translate; then lane k of `x` is p[k+1] + sx[k] p[k], and so on.
    let p = [
        lanes(tri.a).sub(o),
        lanes(tri.b).sub(o),
        lanes(tri.c).sub(o),
    ];
    let x = p.map(|p| p.rot1().add(sx.mul(p)));
    let y = p.map(|p| p.rot2().add(sy.mul(p)));
    let z = p.map(|p| p.mul(sz));
    let edge = |j: usize, k: usize| x[j].mul(y[k]).sub(y[j].mul(x[k]));
    let (e0, e1, e2) = (edge(1, 2), edge(2, 0), edge(0, 1));
    // Both signs among the edge functions: outside. (For values that are
    // not NaN, "some e_i < 0" is "min e_i < 0"; a NaN edge function, from
    // overflow, makes `det` NaN and fails the range test below, whatever
    // this says, as in the definition.)
    let neg = e0.min(e1).min(e2).lt(zero);
    let pos = zero.lt(e0.max(e1).max(e2));
    if neg & pos & bit != 0 {
        return None;
    }
    if (e0.eq(zero) | e1.eq(zero) | e2.eq(zero)) & bit != 0 {
        return slow();
    }
    let det = e0.add(e1).add(e2);
    let t_scaled = e0.mul(z[0]).add(e1.mul(z[1])).add(e2.mul(z[2]));
    let limit = splat(t_max).mul(det);
    let ahead_range = zero.lt(det) & zero.lt(t_scaled) & t_scaled.le(limit);
    let behind_range = det.lt(zero) & t_scaled.lt(zero) & limit.le(t_scaled);
    // A plain miss stands where no corner is in front of the origin or the
    // determinant is well conditioned (see `watertight_lanes`). (Lane k is
    // the frame with kz = k, so the maxima over the corners are lane-wise
    // here.)
    let front = [0, 1, 2].map(|c| zero.lt(z[c]));
    let ahead = front[0] & front[1] & front[2] & bit != 0;
    let conditioned = || {
        let m = (0..3)
            .map(|c| x[c].abs().max(y[c].abs()))
            .fold(zero, |a, b| a.max(b));
        let w = d.abs().mul(z[0].abs().max(z[1].abs()).max(z[2].abs()));
        roughly_conditioned(det, m.max(w)) & bit != 0
            || well_conditioned_lanes(det, m, w) & bit != 0
    };
    // (Most misses are decided before the division.)
    let plain = if (ahead_range | behind_range) & bit != 0 {
        let inv_det = one.div(det);
        let t = t_scaled.mul(inv_det);
        // (`t > 0` makes `is_finite` the same as `t <= MAX`.)
        let big = splat(S::<V>::MAX);
        let t_ok = zero.lt(t) & t.le(splat(t_max)) & t.le(big);
        (t_ok & bit != 0).then_some((t, inv_det))
    } else {
        None
    };
    let Some((t, inv_det)) = plain else {
        return if (front[0] | front[1] | front[2]) & bit == 0 || conditioned() {
            None
        } else {
            slow()
        };
    };
    // The first sufficient test for t > 0 (see `watertight_sheared`), and
    // a well-conditioned determinant (see `watertight_lanes`).
    if !(ahead && conditioned()) {
        return slow();
    }
    // u and v, finite here (see `watertight_lanes`).
    let u = e1.mul(inv_det).min(one);
    let v = e2.mul(inv_det).min(one);
    let pick = |w: L<V>| -> S<V> { Lanes::to_array(w)[kz] };
    let det = pick(det);
    let side = if (det > S::<V>::ZERO) != (pick(d) > S::<V>::ZERO) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleHit {
        t: pick(t),
        u: pick(u),
        v: pick(v),
        side,
    })
}

/// The closed watertight test for a prepared ray and a `t_max >= 0`, with
/// the three corners in the lanes of one register: the same operations as
/// [`watertight_sheared`], lane by lane, so the same bits. The rare cases
/// go to [`watertight_sheared`] itself: an edge function that rounds to
/// zero (its sign must be recomputed exactly), a crossing for which the
/// cheapest sufficient test for `t > 0` (every corner in front of the
/// origin) fails or whose determinant's sign is not surely known, and a
/// plain miss that only the definition can settle.
///
/// An invalid ray needs no test of its own: its origin lanes are NaN
/// (`PreparedRay::new`), so every sheared coordinate, edge function and
/// depth is NaN, and every comparison below is false: no two edge
/// functions of opposite signs, none zero, the determinant out of range,
/// no corner in front. That is a plain miss with no corner in front, so
/// `None`, and no rare path is taken.
#[inline(always)]
pub(crate) fn watertight_lanes<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    // (The definition is called with what this function was given, so that
    // no closure's environment is built on the common paths.)
    let slow = || S::<V>::unpack_hit(prepared_slow(ray, tri, t_max));
    let (x, y, pz, e) = frame_lanes(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, tri);
    let lanes_zero = L::<V>::splat(zero);
    let (neg, pos) = (e.lt(lanes_zero), lanes_zero.lt(e));
    if neg != 0 && pos != 0 {
        // Outside, whatever the exact sign of an edge function of zero.
        return None;
    }
    if e.eq(lanes_zero) != 0 {
        return slow();
    }
    let det = e.sum3();
    let sz = ray.shear_lanes[2];
    let z = pz.mul(sz);
    let t_scaled = e.mul(z).sum3();
    let in_range = if det > zero {
        t_scaled > zero && t_scaled <= t_max * det
    } else if det < zero {
        t_scaled < zero && t_scaled >= t_max * det
    } else {
        false
    };
    // The definition's answer to a plain miss is a miss too, except for a
    // zero-area triangle whose determinant's sign is unknown, when it takes
    // `t` from the segment: so a miss stands where no corner is in front of
    // the origin (the depths' signs are exact: see `watertight_sheared`),
    // or where the determinant is well conditioned
    // (`corners_conditioned`); otherwise the definition decides. (Decided
    // before the division, which most misses need not pay for.)
    let ahead = lanes_zero.lt(z);
    if !in_range {
        return if ahead == 0 {
            None
        } else {
            S::<V>::unpack_hit(plain_miss_lanes(ray, tri, t_max))
        };
    }
    // The first sufficient test for t > 0 (every corner in front), and a
    // well-conditioned determinant; else the definition decides. (Before
    // the division, so that no branch waits for it; the definition's tests
    // are pure functions of the same values, so their order changes no
    // answer.)
    if !(ahead == 0b111 && corners_conditioned(x, y, pz, det)) {
        return slow();
    }
    let inv_det = one / det;
    let t = t_scaled * inv_det;
    // A plain miss with a well-conditioned determinant, as above. (`t > 0`
    // makes `is_finite` the same as `t <= MAX`, so the two upper limits are
    // one comparison.)
    if !(t > zero && t <= min2(S::<V>::MAX, t_max)) {
        return None;
    }
    // u and v: lanes 1 and 2 of `min(e * inv_det, 1)`, finite here: each
    // `|e_i| <= |det|` (the `e_i` share a sign), and `1 / det` is finite
    // (else `t` would be infinite).
    let w = e.mul(L::<V>::splat(inv_det)).min(L::<V>::splat(one));
    let [_, u, v] = w.to_array();
    // (`sz = 1 / d_z` has the sign of `d_z`, and is not zero: `|d_z| <=
    // MAX`.)
    let side = if (det > zero) != (sz.x() > zero) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleHit { t, u, v, side })
}

/// A triangle test's answer as the rare paths return it (see
/// [`Scalar::PackedHit`]).
type PackedHit<V> = <S<V> as Scalar>::PackedHit;

/// [`watertight_sheared`] with the closed rule for a prepared ray, out of
/// the hot path.
#[cold]
#[inline(never)]
fn prepared_slow<V: Vector>(ray: &PreparedRay<V>, tri: &Triangle<V>, t_max: S<V>) -> PackedHit<V> {
    S::<V>::pack_hit(watertight_sheared(
        ray.origin(),
        &ray.shear(),
        tri,
        t_max,
        EdgeRule::Closed,
    ))
}

/// [`watertight_sheared`] with the closed rule for a ray not prepared, out
/// of the hot path.
#[cold]
#[inline(never)]
fn per_call_slow<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: S<V>) -> PackedHit<V> {
    S::<V>::pack_hit(watertight_sheared(
        ray.origin,
        &Shear::new(&ray.dir),
        tri,
        t_max,
        EdgeRule::Closed,
    ))
}

/// The watertight test for a valid ray, given its origin and shear, and a
/// `t_max >= 0`. [`ray_triangle`], [`ray_triangle_prepared`] and the
/// triangle batches' undecided lanes all come here.
#[inline(always)]
pub(crate) fn watertight_sheared<V: Vector>(
    origin: V,
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
    t_max: S<V>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let zero = S::<V>::ZERO;
    let shear = *shear;
    let f = Frame::new(origin, tri, &shear);
    let [e0, e1, e2] = f.e;

    // Inside test in the sheared plane.
    let inside = match rule {
        EdgeRule::Closed => {
            let any_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
            let any_pos = (e0 > zero) | (e1 > zero) | (e2 > zero);
            // NaN edge functions (overflow) fail both tests below instead.
            !(any_neg & any_pos)
        }
        EdgeRule::OneHit => {
            let sign = |i: usize, e: S<V>| {
                if e > zero {
                    Some(true)
                } else if e < zero {
                    Some(false)
                } else if e == zero {
                    f.tie_break(i)
                } else {
                    None
                }
            };
            match (sign(0, e0), sign(1, e1), sign(2, e2)) {
                (Some(a), Some(b), Some(c)) => a == b && b == c,
                _ => false,
            }
        }
    };
    if !inside {
        return None;
    }
    let det = e0 + e1 + e2;

    // Distance: interpolate the scaled z with the edge functions, and compare
    // against t_max * det before paying for the division.
    let z = f.scaled_z(&shear);
    let t_scaled = e0 * z[0] + e1 * z[1] + e2 * z[2];
    let in_range = if det > zero {
        t_scaled > zero && t_scaled <= t_max * det
    } else if det < zero {
        t_scaled < zero && t_scaled >= t_max * det
    } else {
        false // zero area in the sheared plane, or NaN
    };
    let inv_det = S::<V>::ONE / det;
    let plain = t_scaled * inv_det;
    let plain_ok = in_range && plain > zero && plain <= t_max && plain.is_finite();
    // t > 0 decided conservatively, by any of three sufficient tests, in
    // order of cost:
    // - every corner lies in front of the origin in exact arithmetic
    //   (z_i > 0: the sign of z_i = fl(fl(c_z - o_z) fl(1 / d_z)) is exact,
    //   as a rounded difference is zero only when the operands are equal
    //   and rounding keeps signs; an underflow to zero only makes the test
    //   fail): any crossing of the triangle is a convex combination of
    //   them, so it is in front too, however thin the triangle looks from
    //   the ray (this keeps small triangles far away, where the next two are
    //   too pessimistic, and a crack would open if they were the only ones);
    // - the scaled distance exceeds its rounding error bound (pbrt-v4's
    //   test): the exact numerator has the sign of det;
    // - where the determinant is well conditioned, t exceeds its own error
    //   bound: the exact crossing is at t > 0.
    // The first test needs no bound, so the other bounds are computed only
    // when it fails (they are pure functions of the same
    // values, so the order changes no answer). No corner in front of the
    // origin (every z_i <= 0, or NaN) likewise means no hit: every crossing
    // is at t <= 0.
    let ahead = z[0] > zero && z[1] > zero && z[2] > zero;
    let behind = !(z[0] > zero || z[1] > zero || z[2] > zero);
    let (m, w) = (max2(max3(&f.x), max3(&f.y)), max3(&f.pz));
    let t = if plain_ok && ahead && well_conditioned(det, m, w) {
        // (The common case, and the fast paths' answer: the full test
        // below would give the same, as the determinant's sign is known.)
        plain
    } else if behind {
        return None;
    } else {
        let bounds = ErrorBounds::new(&f, &z, &shear);
        match HitCondition::new(&bounds, det) {
            Some(c) => {
                let sure = ahead
                    || t_scaled.abs() > bounds.t_scaled
                    || plain > c.t_error(&bounds, &z, plain);
                if !(plain_ok && sure) {
                    return None;
                }
                plain
            }
            None if det != zero && tri.is_degenerate() => {
                // A triangle of zero area (its corners exactly collinear)
                // that rounding leaves a sliver in the ray's frame: `plain`
                // weighs the corners' depths almost arbitrarily, its sign
                // included. The depth of the longest edge's point nearest
                // the ray is well conditioned, and is where the ray passes
                // the segment; the hit stands where that is surely in front
                // (as it is when every corner is).
                let (t, bound) = longest_edge_t(&f, &z, &bounds)?;
                if !((ahead || t > bound) && t > zero && t <= t_max) {
                    return None;
                }
                t
            }
            // Otherwise (a ray within rounding of parallel to the triangle,
            // or a sliver far away), only where every corner is in front.
            None if plain_ok && ahead => plain,
            None => return None,
        }
    };
    // Each e_i / det is in [0, 1] exactly (all e_i share det's sign, and
    // |det| >= |e_i|); the rounded reciprocal can push it one ulp past 1.
    let one = S::<V>::ONE;
    let u = min2(e1 * inv_det, one);
    let v = min2(e2 * inv_det, one);
    if !(u.is_finite() && v.is_finite()) {
        return None;
    }
    // In the frame before the z scaling (orientation preserving: a cyclic
    // permutation and a shear), the ray runs along +z with speed d_z and
    // det is the z component of the normal; dir . normal = d_z * det.
    let side = if (det > zero) != (shear.dz > zero) {
        Side::Front
    } else {
        Side::Back
    };
    Some(TriangleHit { t, u, v, side })
}

/// Rounding error bounds of the watertight test's intermediate values, all
/// absolute, in terms of the computed quantities.
///
/// Notation: `u` the unit roundoff, `gamma(n) = n*u/(1 - n*u)`; `P` the exact
/// translated, permuted corners and `p` their computed values (one rounding
/// each); `X, Y, Z` the exact sheared and scaled coordinates, `x, y, z` the
/// computed ones; `E_i`, `e_i` the exact and computed edge functions. The
/// structure follows pbrt-v4 (`IntersectTriangle`; Pharr, Jakob and
/// Humphreys, "Physically Based Rendering", 4th ed., section 6.8.4), with
/// the shear error measured by the actual shear factor and the result, so
/// that it holds for a direction of any length, vanishes for an
/// axis-parallel ray and stays small where the shear cancels the
/// translation; second-order terms are kept.
#[derive(Clone, Copy, Debug)]
struct ErrorBounds<F> {
    /// Bound on `|e_i - E_i|`.
    e: F,
    /// Bound on `|z_i - Z_i|`.
    z: F,
    /// Bound on `|t_scaled - sum E_i Z_i|`.
    t_scaled: F,
    /// `max |z_i|`.
    max_z: F,
    /// Bound on `|x_i - X_i|` and `|y_i - Y_i|`.
    xy: F,
}

impl<F: Scalar> ErrorBounds<F> {
    #[inline(always)]
    fn new(f: &Frame<F>, z: &[F; 3], shear: &Shear<F>) -> Self {
        let (mx, my) = (max3(&f.x), max3(&f.y));
        let (mpx, mpy, mpz) = (max3(&f.px), max3(&f.py), max3(&f.pz));
        let me = max3(&f.e);
        // Shear: with p = P(1 + d1) (translation), s_x = S_x (1 + d3),
        // m = fl(s_x p_z) = S_x P_z (1 + theta_3) and x = fl(p_x + m) =
        // (p_x + m)(1 + d5):
        //   x - X = P_x d1 + S_x P_z theta_3 + (p_x + m) d5,
        // so |x - X| <= u|P_x| + gamma(3)|S_x P_z| + u|x|/(1 - u)
        //            <= gamma(1)(|p_x| + |x|) + gamma(4)|s_x p_z|
        // (|P_x| <= |p_x|/(1 - u), |S_x P_z| <= |m|/(1 - gamma(3))). The last
        // rounding is relative to the result, which is small exactly when
        // the shear cancels the translation. (3 roundings to evaluate.)
        let dx = bound_up(
            F::gamma_n(1) * (mpx + mx) + F::gamma_n(4) * shear.sx.abs() * mpz,
            3,
        );
        let dy = bound_up(
            F::gamma_n(1) * (mpy + my) + F::gamma_n(4) * shear.sy.abs() * mpz,
            3,
        );
        let (mz, dz) = z_error(z);
        // Edge function e_0 = fl(fl(x1 y2) - fl(y1 x2)) (or the exact-sign
        // recomputation, which is closer): rounding adds gamma(2)(|x1 y2| +
        // |y1 x2|) <= 2 gamma(2) mx my, and x1 y2 - X1 Y2 =
        // x1 (y2 - Y2) + (x1 - X1) Y2 adds mx dy + dx (my + dy), twice.
        // (At most 5 roundings on a path from dx, dy.)
        let two = F::TWO;
        let de = bound_up(
            two * (F::gamma_n(2) * mx * my + mx * dy + my * dx + dx * dy),
            5,
        );
        // t_scaled = fl(sum e_i z_i): rounding adds gamma(3) sum |e_i z_i|;
        // replacing e, z by E, Z adds sum |e_i| dz + de (|z_i| + dz).
        // (At most 5 roundings on a path from de, dz.)
        let three = F::from_u32(3);
        let dt = bound_up(
            three * (F::gamma_n(3) * me * mz + me * dz + de * (mz + dz)),
            5,
        );
        Self {
            e: de,
            z: dz,
            t_scaled: dt,
            max_z: mz,
            xy: max2(dx, dy),
        }
    }
}

/// `max |v_i|`, in the order every caller uses (so NaN propagates alike).
#[inline(always)]
pub(crate) fn max3<F: Scalar>(v: &[F; 3]) -> F {
    max2(v[0].abs(), max2(v[1].abs(), v[2].abs()))
}

/// A sufficient condition for the determinant's sign to be known (for
/// [`HitCondition::new`] to be `Some`), from `m`, the largest `|x_i|` and
/// `|y_i|` of the corners, and `w = max |p_z,i|`, their largest depth before
/// scaling (or `|d_z| max |z_i|`, which differs from it by at most `2u`
/// relative, well within the margin below):
/// `|det| > u (64 m (m + 2w) + 256 u (m + w)^2)`. For a hit, `m` is about
/// the triangle's size and `w` its distance, so the test asks for
/// `det`, about the squared size, to exceed about `128 u` times size times
/// distance: only slivers seen edge-on fail it.
///
/// Why: `|s_x|, |s_y| <= 1`, so each
/// shear product `|s_x p_z|` is at most about `w`, and each `|p_x|`,
/// `|p_y|` at most about `m + w`. Then [`ErrorBounds`] gives `dx, dy <=
/// u (2m + 5w)` and `de <= u (12 m^2 + 20 m w) + 2 u^2 (2m + 5w)^2`
/// (to first order in the `(1 + k u)` factors), so `4 de`, at most
/// `u (48 m^2 + 80 m w) + 200 u^2 (m + w)^2`, is below the threshold by a
/// factor of at least 1.28, which covers those factors and the few
/// roundings of the threshold itself; then the lower bound of
/// [`HitCondition`] is positive. NaN or infinite input fails it.
#[inline(always)]
fn well_conditioned<F: Scalar>(det: F, m: F, w: F) -> bool {
    let splat = F::Lanes::splat;
    well_conditioned_lanes(splat(det), splat(m), splat(w)) & 1 != 0
}

/// [`well_conditioned`] for the corners in the lanes of `x`, `y` and `pz`
/// (the prepared test's form).
///
/// First [`roughly_conditioned`], lane by lane with no maximum across
/// lanes, with each corner's `k_i = max(|x_i|, |y_i|, |p_z,i|)` (every
/// lane passing is the test for the largest `k_i`, which is `max(m, w)`).
/// It fails only for triangles small next to their distance, which take
/// the exact threshold, out of line.
#[inline(always)]
fn corners_conditioned<W: Lanes>(x: W, y: W, pz: W, det: W::F) -> bool {
    let k = x.abs().max(y.abs()).max(pz.abs());
    roughly_conditioned(W::splat(det), k) == 0b111 || corners_conditioned_exactly(x, y, pz, det)
}

/// The cheaper sufficient test behind [`well_conditioned`], lane by lane:
/// `|det| > 200 u k^2` for a `k` at least `m` and `w`. With `M = max(m,
/// w) <= k`, the threshold is at most `u M^2 (192 + 1024 u)`, below
/// `193 u M^2`, and rounding the product twice keeps it above that.
#[inline(always)]
fn roughly_conditioned<W: Lanes>(det: W, k: W) -> u32 {
    let bound = W::splat(W::F::from_u32(200) * W::F::UNIT_ROUNDOFF);
    k.mul(k).mul(bound).lt(det.abs())
}

/// The corners of `tri` in the frame of the ray with origin lanes
/// `origin_lanes` and shear `shear`, a corner per lane: the sheared `x` and
/// `y`, the unscaled depth `p_z`, and the edge functions.
#[inline(always)]
fn frame_lanes<V: Vector>(
    origin_lanes: &[L<V>; 3],
    shear_lanes: &[L<V>; 3],
    axes: &[Axis; 3],
    tri: &Triangle<V>,
) -> (L<V>, L<V>, L<V>, L<V>) {
    let corners = |k: Axis| L::<V>::new(tri.a.get(k), tri.b.get(k), tri.c.get(k));
    let [sx, sy, _] = *shear_lanes;
    let [ox, oy, oz] = *origin_lanes;
    let [kx, ky, kz] = *axes;
    // Translate, permute (the corners' coordinates are read in the ray's
    // axis order), shear.
    let px = corners(kx).sub(ox);
    let py = corners(ky).sub(oy);
    let pz = corners(kz).sub(oz);
    let x = px.add(sx.mul(pz));
    let y = py.add(sy.mul(pz));
    // Edge functions: lane i is x[i+1] y[i+2] - y[i+1] x[i+2].
    let e = x.rot1().mul(y.rot2()).sub(y.rot1().mul(x.rot2()));
    (x, y, pz, e)
}

/// The answer to a plain miss of [`watertight_lanes`] with some corner in
/// front of the origin: a miss too where the determinant is well
/// conditioned, else the definition's (`slow`). Out of line, and given
/// only what the caller was given (it recomputes the frame, bit for bit),
/// so that the common paths keep no more values alive for it.
#[cold]
#[inline(never)]
fn plain_miss_lanes<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> PackedHit<V> {
    let (x, y, pz, e) = frame_lanes(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, tri);
    if corners_conditioned(x, y, pz, e.sum3()) {
        S::<V>::pack_hit(None)
    } else {
        prepared_slow(ray, tri, t_max)
    }
}

/// The threshold of [`well_conditioned`] itself, for
/// [`corners_conditioned`].
#[cold]
#[inline(never)]
fn corners_conditioned_exactly<W: Lanes>(x: W, y: W, pz: W, det: W::F) -> bool {
    let m = x.abs().max(y.abs()).max_all().x();
    let w = pz.abs().max_all().x();
    well_conditioned(det, m, w)
}

/// [`well_conditioned`] on lanes, its one formula: lane `i` tests `det[i]`
/// against `m[i]` and `w[i]` (the per-call test's lanes are its three
/// frames).
#[inline(always)]
fn well_conditioned_lanes<W: Lanes>(det: W, m: W, w: W) -> u32 {
    let u = W::F::UNIT_ROUNDOFF;
    let s = m.add(w);
    let threshold = m
        .mul(m.add(w.add(w)))
        .mul(W::splat(W::F::from_u32(64) * u))
        .add(s.mul(s).mul(W::splat(W::F::from_u32(256) * u * u)));
    threshold.lt(det.abs())
}

/// `(max |z_i|, dz)` with `dz` the bound on `|z_i - Z_i|` of
/// [`ErrorBounds`].
///
/// Scale: z = fl(p_z fl(1/d_z)) = Z (1 + theta_3), so
/// |z - Z| <= gamma(3)|Z| <= gamma(4)|z|. (1 rounding.)
#[inline(always)]
pub(crate) fn z_error<F: Scalar>(z: &[F; 3]) -> (F, F) {
    let mz = max3(z);
    (mz, bound_up(F::gamma_n(4) * mz, 1))
}

/// The `t` of a hit whose determinant's sign rounding leaves unknown: the
/// depth of the point of the triangle's longest edge in the sheared plane
/// nearest the ray (clamped to the edge), and a bound on its distance from
/// the same point of the exact edge. For a triangle whose corners are
/// exactly collinear, that point is where the ray passes the segment.
/// `None` when the edge is too short for the bound (the ray runs along it).
///
/// With `p` the edge's first corner and `D` the edge, `s = clamp(-(p . D) /
/// (D . D), 0, 1)` and `t = z_i + s (z_j - z_i)`; see [`EdgeLine::param`]
/// for `|s - s*|` (clamping does not increase it) and
/// [`EdgeLine::depth_error`] for `|t - t*|`.
#[cold]
#[inline(never)]
fn longest_edge_t<F: Scalar>(f: &Frame<F>, z: &[F; 3], b: &ErrorBounds<F>) -> Option<(F, F)> {
    let line = EdgeLine::new(f, z, b)?;
    let (sigma, es) = line.param(-line.px, -line.py, line.d, line.d)?;
    let s = min2(max2(sigma, F::ZERO), F::ONE);
    let t = line.zi + s * line.dzij;
    let bound = line.depth_error(line.zi.abs(), F::ONE, es);
    (t.is_finite() && bound.is_finite()).then_some((t, bound))
}

/// A bound on the distance of a `t` that [`longest_edge_t`] gave for a
/// triangle of zero area from where the ray passes the segment: its own
/// bound plus how far the third corner's depth is from the edge's depth line
/// (zero in exact arithmetic, as the corners are collinear; the computed
/// deviation carries the rounding of the coordinates, which this also
/// covers). The same sum bounds the distance from the exact plane's
/// crossing for a sliver the ray meets (the plane's depth is affine, so at
/// the ray it differs from the edge's by at most the third corner's
/// deviation), which is what makes it a natural bound; the test uses the
/// route only for zero-area triangles.
fn longest_edge_t_error<F: Scalar>(f: &Frame<F>, z: &[F; 3], b: &ErrorBounds<F>) -> Option<F> {
    let (_, bound) = longest_edge_t(f, z, b)?;
    let line = EdgeLine::new(f, z, b)?;
    let k = line.k;
    // The third corner relative to the first: each component within 2d
    // plus its rounding.
    let (ax, ay) = (f.x[k] - line.px, f.y[k] - line.py);
    let u = F::UNIT_ROUNDOFF;
    let (eax, eay) = (
        F::TWO * line.d + u * ax.abs(),
        F::TWO * line.d + u * ay.abs(),
    );
    let (sk, esk) = line.param(ax, ay, eax, eay)?;
    let on_line = line.zi + sk * line.dzij;
    // |Z_k - line*(sk*)| <= |z_k - on_line| + dz + depth_error(...).
    let deviation = bound_up(
        (z[k] - on_line).abs() + line.dz + line.depth_error(line.zi.abs(), sk.abs(), esk),
        3,
    );
    let total = bound_up(bound + deviation, 1);
    total.is_finite().then_some(total)
}

/// The longest edge `i -> j` of a triangle in the sheared plane, with what
/// [`longest_edge_t`] and its error bound need.
struct EdgeLine<F> {
    /// The third corner.
    k: usize,
    /// The first corner.
    px: F,
    py: F,
    /// The edge `D`, and bounds on its components' distances from the
    /// exact edge's: each coordinate is within `d` of the exact one, so
    /// each difference within `2d` plus its own rounding.
    dx: F,
    dy: F,
    edx: F,
    edy: F,
    /// `D . D`, and a bound on its distance from the exact edge's.
    den: F,
    eden: F,
    /// The first corner's depth, the edge's change in depth, and the
    /// bounds on the coordinates' and depths' errors.
    zi: F,
    dzij: F,
    d: F,
    dz: F,
}

impl<F: Scalar> EdgeLine<F> {
    fn new(f: &Frame<F>, z: &[F; 3], b: &ErrorBounds<F>) -> Option<Self> {
        let len2 = |i: usize, j: usize| {
            let (dx, dy) = (f.x[j] - f.x[i], f.y[j] - f.y[i]);
            dx * dx + dy * dy
        };
        let (mut i, mut j, mut k, mut best) = (0, 1, 2, len2(0, 1));
        for (a, c, r) in [(1, 2, 0), (2, 0, 1)] {
            let l = len2(a, c);
            if l > best {
                (i, j, k, best) = (a, c, r, l);
            }
        }
        let (px, py) = (f.x[i], f.y[i]);
        let (dx, dy) = (f.x[j] - px, f.y[j] - py);
        let den = dx * dx + dy * dy;
        let (d, u, two) = (b.xy, F::UNIT_ROUNDOFF, F::TWO);
        let (edx, edy) = (two * d + u * dx.abs(), two * d + u * dy.abs());
        // Rounding of the dot product, and the perturbation of each square.
        let eden = bound_up(
            F::gamma_n(2) * den + edx * (two * dx.abs() + edx) + edy * (two * dy.abs() + edy),
            12,
        );
        (den > eden && eden.is_finite()).then_some(Self {
            k,
            px,
            py,
            dx,
            dy,
            edx,
            edy,
            den,
            eden,
            zi: z[i],
            dzij: z[j] - z[i],
            d,
            dz: b.z,
        })
    }

    /// `sigma = (a . D) / (D . D)` for a vector `a` whose components are
    /// within `ea_x`, `ea_y` of the exact ones, and a bound on `|sigma -
    /// sigma*|` (`sigma*` from exact values). The numerator is within
    /// `en = gamma(2) (|a_x D_x| + |a_y D_y|) + sum_k (|a_k| eD_k + (|D_k| +
    /// eD_k) ea_k)` of the exact one and the denominator within `eden`;
    /// `sigma - sigma* = (num - num*) / den + sigma* (den* - den) / den`,
    /// with `|sigma*| <= (|num| + en) / (den - eden)`, and the division adds
    /// `gamma(1) |sigma|`.
    fn param(&self, ax: F, ay: F, eax: F, eay: F) -> Option<(F, F)> {
        let num = ax * self.dx + ay * self.dy;
        let sigma = num / self.den;
        let (adx, ady) = (self.dx.abs(), self.dy.abs());
        let en = bound_up(
            F::gamma_n(2) * (ax.abs() * adx + ay.abs() * ady)
                + ax.abs() * self.edx
                + ay.abs() * self.edy
                + (adx + self.edx) * eax
                + (ady + self.edy) * eay,
            12,
        );
        let exact = bound_up((num.abs() + en) / (self.den - self.eden), 4);
        let es = bound_up(
            F::gamma_n(1) * sigma.abs() + (en + exact * self.eden) / self.den,
            4,
        );
        (sigma.is_finite() && es.is_finite()).then_some((sigma, es))
    }

    /// A bound on `|z_i + s (z_j - z_i) - (Z_i + s* (Z_j - Z_i))|` for
    /// `|s| <= s_abs` and `|s - s*| <= es`: the rounding `gamma(3) (|z_i| +
    /// max(1, s_abs) |z_j - z_i|)`, the depths' errors `(1 + 2 max(1,
    /// s_abs)) dz`, and `es (|z_j - z_i| (1 + u) + 2 dz)`, evaluated with at
    /// most eight roundings.
    fn depth_error(&self, abs_zi: F, s_abs: F, es: F) -> F {
        let (u, two) = (F::UNIT_ROUNDOFF, F::TWO);
        let adz = self.dzij.abs();
        let s = max2(F::ONE, s_abs);
        bound_up(
            F::gamma_n(3) * (abs_zi + s * adz)
                + (F::ONE + two * s) * self.dz
                + es * (adz * (F::ONE + u) + two * self.dz),
            8,
        )
    }
}

/// The conditioning of a hit: lower and upper bounds of `|sum E_i|` (the
/// exact determinant) from the computed one. Exists only when the lower
/// bound is positive, i.e. when the exact determinant is known to have the
/// computed one's sign.
#[derive(Clone, Copy, Debug)]
struct HitCondition<F> {
    /// `<= |sum E_i|`, and `> 0`.
    lower: F,
    /// `>= |sum E_i|`.
    upper: F,
}

impl<F: Scalar> HitCondition<F> {
    /// `det = fl(fl(e0 + e1) + e2)` with all `e_i` of one sign, so
    /// `|sum e_i| / (1 + gamma(2)) <= |det| <= |sum e_i| (1 + gamma(2))`, and
    /// `|sum E_i - sum e_i| <= 3 de`. Outward rounding throughout; `4 de`
    /// (exact) stands in for `3 de` to absorb the rounding of the product.
    #[inline(always)]
    fn new(b: &ErrorBounds<F>, det: F) -> Option<Self> {
        use crate::real::outward::{add_up, mul_down, mul_up, sub_down};
        let g = F::gamma_n(4);
        let sum_lo = mul_down(det.abs(), F::ONE - g);
        let sum_hi = mul_up(det.abs(), F::ONE + g);
        let four_de = F::from_u32(4) * b.e;
        let lower = sub_down(sum_lo, four_de);
        (lower > F::ZERO).then(|| Self {
            lower,
            upper: add_up(sum_hi, four_de),
        })
    }

    /// A bound on `|t - t_exact|` for the reported `t`.
    ///
    /// Write `t(e, z) = sum e_i z_i / sum e_i`; the exact crossing is
    /// `t(E, Z)`, and the reported `t` comes from `t(e, z)` by rounding.
    /// - Rounding: `t = fl(fl(sum e_i z_i) fl(1/det))` is `t(e, z)` times
    ///   `(1 + eta)`, `|eta| <= gamma(4)`, plus `gamma(3) sum|e_i z_i| / |sum e_i|
    ///   <= gamma(3) max|z|` (the `e_i` share a sign); `|t(e, z)| <= max|z|`
    ///   (a convex combination), so `|t - t(e, z)| <= gamma(8) max|z|`.
    /// - Edge functions: for any `c`, `t(e, z) - c = sum e_i (z_i - c) /
    ///   sum e_i`. With `c = t(E, z)`, `sum E_i (z_i - c) = 0`, so
    ///   `t(e, z) - t(E, z) = sum (e_i - E_i)(z_i - c) / sum e_i`, and with
    ///   `S = sum |z_i - t(e, z)|`: `|t(e, z) - t(E, z)| <= de S / (|sum e| - 3 de)`.
    ///   (The sensitivity is to the spread of the `z_i`, not their size.)
    /// - Coordinates: `t(E, z) - t(E, Z) = sum E_i (z_i - Z_i) / sum E_i`,
    ///   at most `dz sum|E_i| / |sum E_i| <= dz (|sum e| + 3 de) / (|sum e| - 3 de)`.
    #[inline(always)]
    fn t_error(&self, b: &ErrorBounds<F>, z: &[F; 3], t: F) -> F {
        use crate::real::outward::{add_up, div_up, mul_up};
        let rounding = mul_up(F::gamma_n(8), b.max_z);
        let spread = |zi: F| (zi - t).abs().next_up();
        let s = add_up(add_up(spread(z[0]), spread(z[1])), spread(z[2]));
        let s = add_up(s, mul_up(F::from_u32(3), rounding));
        let edges = div_up(mul_up(b.e, s), self.lower);
        let coords = div_up(mul_up(b.z, self.upper), self.lower);
        add_up(add_up(rounding, edges), coords)
    }

    /// A bound on `|w - w_exact|` for a reported barycentric `w = min(e_i /
    /// det, 1)` (rounded; `w_exact = E_i / sum E_i`).
    ///
    /// Rounding: `w = (e_i / sum e_i)(1 + eta)`, `|eta| <= gamma(4)`, and
    /// clamping to 1 only moves it towards `e_i / sum e_i <= 1`; so the
    /// rounding error is at most `gamma(5) w`. Edge functions: `e_i/sum e -
    /// E_i/sum E = ((e_i - E_i) - w' sum (e_j - E_j)) / sum E` with
    /// `w' = e_i / sum e`, at most `de (1 + 3 w') / (|sum e| - 3 de)`.
    #[inline(always)]
    fn barycentric_error(&self, b: &ErrorBounds<F>, w: F) -> F {
        use crate::real::outward::{add_up, div_up, mul_up};
        let rounding = mul_up(F::gamma_n(5), w);
        let w_plain = add_up(w, rounding);
        let factor = add_up(F::ONE, mul_up(F::from_u32(3), w_plain));
        add_up(rounding, div_up(mul_up(b.e, factor), self.lower))
    }
}

/// The watertight ray/triangle test (closed: edges and corners hit).
///
/// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT
/// 2(1), 2013, as in pbrt-v4: translate the corners to the ray origin,
/// permute the axes so that the ray runs mostly along `z`, shear so that it
/// runs exactly along `z`, and decide inside/outside with three 2-D edge
/// functions; an edge function that rounds to exactly zero is recomputed
/// with its sign exact (in `f64` for `f32`).
///
/// Conventions: two-sided (the [`Side`] is reported); `t` in units of
/// `ray.dir` with `0 < t <= t_max`; barycentrics as in [`TriangleHit`].
/// The triangle is closed in the ray's frame: an edge function of exactly
/// zero counts as inside. (A ray that exact arithmetic puts exactly on the
/// edge of a lone triangle can still miss it: translating and shearing the
/// corners rounds them by a few ulps, and the test is exact for the rounded
/// corners. Where two triangles share the edge, one of them is hit.)
///
/// Guarantees:
/// - **Watertight.** The signs of the edge functions are exact for the
///   rounded corners in the ray's frame, and two triangles that share an
///   edge (bit-identical corners) compute that edge's function as exact
///   negatives. So a ray that crosses a shared edge or corner of a mesh
///   (locally a proper surface, seen from one side) hits at least one of the
///   triangles around it: no ray leaks through.
/// - **`t > 0` decided conservatively**: the reported `t` is positive, and
///   the hit is in front of the origin in exact arithmetic by one of four
///   tests: all three corners are in front (so is any crossing), or the
///   scaled numerator exceeds its rounding error bound (pbrt-v4's test), or
///   `t` exceeds its error bound, or, for a triangle of zero area (corners
///   exactly collinear) that rounding leaves a sliver, the depth of the
///   point of its longest edge nearest the ray (where the ray passes the
///   segment, and then the reported `t`) exceeds its own error bound. Where
///   every corner is behind the origin there is no hit. A ray spawned from the triangle with
///   [`offset_ray_origin`](crate::offset_ray_origin) does not hit it again.
/// - `t`, `u` and `v` are within [`ray_triangle_error_bounds`] of the
///   exact crossing (where that bound is finite); `t` always lies between
///   the nearest and farthest corner's depth along the ray, up to rounding.
/// - Triangles of zero area in the ray's sheared frame (after rounding),
///   non-finite triangles, invalid rays and NaN or negative `t_max` give
///   `None`; never panics, never NaN. A triangle of exactly zero area can
///   still be hit where rounding leaves it a sliver (see [`Triangle`]).
/// - Precondition for all of the above: coordinates relative to the ray
///   origin small enough that the edge-function products do not overflow
///   (`|coordinate| < 2^63` in `f32`, `2^511` in `f64`).
///
/// ```
/// use rayhit::{Ray, Side, Triangle, ray_triangle, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.u, hit.v, hit.side), (2.0, 0.25, 0.125, Side::Front));
/// // On the edge from b to c: closed, so a hit.
/// let edge = Ray::new(Vec3::new(1.0, 1.0, 4.0), Vec3::new(0.0, 0.0, -1.0));
/// assert!(ray_triangle(&edge, &tri, f32::INFINITY).is_some());
/// ```
#[inline]
#[must_use]
pub fn ray_triangle<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    watertight(ray, tri, t_max, EdgeRule::Closed)
}

/// [`ray_triangle`] on a [`PreparedRay`]: the same answer, bit for bit,
/// without recomputing the ray's shear (three divisions) per triangle.
///
/// ```
/// use rayhit::{PreparedRay, Ray, Triangle, ray_triangle, ray_triangle_prepared, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let prepared = PreparedRay::new(&ray);
/// assert_eq!(
///     ray_triangle_prepared(&prepared, &tri, f32::INFINITY),
///     ray_triangle(&ray, &tri, f32::INFINITY),
/// );
/// ```
// (Always inlined: it is the body of a traversal's inner loop, and its rare
// paths are out of line. Left to the inliner, a program that calls it from
// several places got one shared copy, which paid a call and returned its
// answer through memory: 1.45 times the time on rays aimed at their
// triangles, in `benches/peers`.)
#[inline(always)]
#[must_use]
pub fn ray_triangle_prepared<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    if !t_max_ok(t_max) {
        return None;
    }
    watertight_lanes(ray, tri, t_max)
}

/// The watertight test with exactly one hit per crossing of a mesh: each
/// point of a shared edge or corner belongs to exactly one of the triangles
/// around it.
///
/// Same test and guarantees as [`ray_triangle`], except for an edge function
/// of exactly zero (the ray crosses the edge's line in the sheared plane).
/// Instead of counting as inside, it is decided as if the ray were moved by
/// an infinitesimal `(eps1, eps2)`, `0 < eps2 << eps1`, in its sheared plane
/// (simulation of simplicity, Edelsbrunner and Mucke, 1990; the rasteriser's
/// top-left rule is the same idea in screen space). The moved ray lies on no
/// edge line, so every triangle's answer is the exact answer for the same
/// moved ray.
///
/// What that gives: where a consistently wound mesh is, around the crossing
/// point, a surface seen from one side (every interior edge shared by two
/// triangles with bit-identical corners, and opposite directions), the ray
/// hits exactly one triangle, so counting crossings gives the right parity
/// for inside/outside tests and CSG. For a closed mesh the count is even
/// for every ray line (up to the `t` range), even grazing a silhouette.
///
/// What it gives up: a point on the mesh's open boundary, or on the edge of
/// a lone triangle, belongs to a triangle only if the perturbed ray is
/// inside it, so about half of the boundary points hit nothing. Use
/// [`ray_triangle`] for a lone triangle.
///
/// ```
/// use rayhit::{Ray, Triangle, ray_triangle_one_hit, glam::Vec3};
/// // Two triangles of the unit square, sharing the diagonal from (1,0) to (0,1).
/// let (p00, p10, p01, p11) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
/// let mesh = [Triangle::new(p00, p10, p01), Triangle::new(p10, p11, p01)];
/// // Straight down through the middle of the shared diagonal.
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::new(0.0, 0.0, -1.0));
/// let hits = mesh.iter().filter(|t| ray_triangle_one_hit(&ray, t, 10.0).is_some()).count();
/// assert_eq!(hits, 1);
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_one_hit<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    watertight(ray, tri, t_max, EdgeRule::OneHit)
}

/// The point of a hit from its barycentrics, `a + u (b - a) + v (c - a)`,
/// and a per-component bound on its distance from a point of the exact
/// triangle's plane.
///
/// For any reals `u, v`, `q = a + u (b - a) + v (c - a)` lies exactly in the
/// plane; the computed point differs from `q` only by rounding: the edges
/// (one each), the products and the two sums, at most
/// `gamma(5) (|a_j| + |u e1_j| + |v e2_j|)` with the computed edges, plus
/// four roundings to evaluate that. This is the error that matters for
/// spawning a ray off the surface (with [`offset_ray_origin`](crate::offset_ray_origin)
/// and [`Triangle::normal_with_error`]); where on the triangle the point
/// lies is the barycentrics' business ([`ray_triangle_error_bounds`]).
///
/// ```
/// use rayhit::{Ray, Triangle, ray_triangle, triangle_hit_point, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0));
/// let ray = Ray::new(Vec3::new(1.0, 2.0, 5.0), -Vec3::Z);
/// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// let (p, err) = triangle_hit_point(&tri, &hit);
/// assert_eq!(p, Vec3::new(1.0, 2.0, 0.0));
/// assert!(err.z == 0.0 && err.x < 1e-5);
/// ```
#[must_use]
pub fn triangle_hit_point<V: Vector>(tri: &Triangle<V>, hit: &TriangleHit<S<V>>) -> (V, V) {
    let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
    let (ue, ve) = (e1 * hit.u, e2 * hit.v);
    let p = tri.a + (ue + ve);
    let g5 = S::<V>::gamma_n(5);
    let err = (tri.a.abs() + ue.abs() + ve.abs()) * g5;
    let e = |j: usize| bound_up(err[j], 4);
    (p, V::new(e(0), e(1), e(2)))
}

/// Bounds on the errors of a watertight hit: `|t - t_exact|`,
/// `|u - u_exact|`, `|v - v_exact|`, where the exact values are those of the
/// crossing of the ray's line with the triangle's plane, computed exactly
/// from the same inputs. See [`ray_triangle_error_bounds`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHitError<F = f32> {
    /// Bound on the error of `t`.
    pub t: F,
    /// Bound on the error of `u`.
    pub u: F,
    /// Bound on the error of `v`.
    pub v: F,
}

/// Bounds on the errors of a hit that [`ray_triangle`] or
/// [`ray_triangle_one_hit`] returned for the same ray and triangle.
///
/// The derivation is in the source, step by step: the rounding of the
/// sheared coordinates and edge functions (as in pbrt-v4), then the
/// sensitivity of `t = sum e_i z_i / sum e_i` and of `e_i / sum e_i` to
/// them. The `t` bound grows with the spread of the corners' distances along
/// the ray, not with the distance itself, so it stays within a few ulps of
/// `t` for a triangle facing the ray, however far away.
///
/// Where the exact determinant's sign is not known, the bounds are infinite
/// (the ray is within rounding of parallel to the triangle, or the triangle
/// is so thin, seen from the ray, that rounding its corners could flip it:
/// a sliver far away), with one exception: for a triangle of zero area
/// (corners exactly collinear) the test takes `t` from the point of the
/// longest edge (in the ray's frame) nearest the ray, and the `t` bound is
/// finite, a bound on the distance from where the ray passes the segment
/// (`u` and `v` are then only known to be in `[0, 1]`, and their bounds are
/// infinite). Every bound is infinite for invalid input.
///
/// ```
/// use rayhit::{Ray, Triangle, ray_triangle, ray_triangle_error_bounds, glam::Vec3};
/// let cz = 3.1f32;
/// let tri = Triangle::new(Vec3::new(0.0, 0.0, 3.0), Vec3::new(1.0, 0.0, 3.0), Vec3::new(0.0, 1.0, cz));
/// let (dy, dz) = (0.2f32, 1.0f32);
/// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.1, dy, dz));
/// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// let err = ray_triangle_error_bounds(&ray, &tri, &hit);
/// // The plane is z - 3 = (cz - 3) y, so t = 3 / (dz - (cz - 3) dy); f64
/// // evaluates that far more accurately than the f32 bound.
/// let exact = 3.0 / (f64::from(dz) - (f64::from(cz) - 3.0) * f64::from(dy));
/// assert!((f64::from(hit.t) - exact).abs() <= f64::from(err.t));
/// assert!(err.t < 1e-5 * hit.t);
/// ```
#[must_use]
pub fn ray_triangle_error_bounds<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    hit: &TriangleHit<S<V>>,
) -> TriangleHitError<S<V>> {
    let inf = S::<V>::INFINITY;
    let unbounded = TriangleHitError {
        t: inf,
        u: inf,
        v: inf,
    };
    if !(ray.is_valid() && hit.t.is_finite() && hit.u.is_finite() && hit.v.is_finite()) {
        return unbounded;
    }
    let shear = Shear::new(&ray.dir);
    let f = Frame::new(ray.origin, tri, &shear);
    let z = f.scaled_z(&shear);
    let b = ErrorBounds::new(&f, &z, &shear);
    let det = f.e[0] + f.e[1] + f.e[2];
    let zero = S::<V>::ZERO;
    let same_sign = f.e.iter().all(|&e| e >= zero) || f.e.iter().all(|&e| e <= zero);
    match HitCondition::new(&b, det) {
        Some(c) if same_sign => TriangleHitError {
            t: c.t_error(&b, &z, hit.t),
            u: c.barycentric_error(&b, hit.u),
            v: c.barycentric_error(&b, hit.v),
        },
        // The test took `t` from the longest edge.
        None if same_sign && det != zero && tri.is_degenerate() => TriangleHitError {
            t: longest_edge_t_error(&f, &z, &b).unwrap_or(inf),
            ..unbounded
        },
        _ => unbounded,
    }
}

/// For the exact oracle's band: the watertight test's bound on `|e_i - E_i|`
/// (its computed edge functions against the exact ones, `E_i = s_i / d_z`
/// with `s_i` the exact Plucker product of the ray and the edge opposite
/// corner `i`, up to one sign shared by the three), and `|d_z|`. Where two
/// exact products have opposite signs and each exceeds `|d_z|` times the
/// bound, so do the computed edge functions, and every watertight test
/// misses. The bound is infinite or NaN where the frame overflows.
///
/// `ErrorBounds` is relative; an underflowing result is off by up to half a
/// subnormal `tiny` instead. For an edge function `x_1 y_2 - y_1 x_2`: its
/// two products (`tiny`); the shear products `s p_z` in `x` and `y` (half a
/// `tiny` each, times the other factor, at most `m`); and a shear factor
/// `s` that underflowed (half a `tiny`, times `|p_z|` and then `m`). With
/// `m` the largest sheared coordinate, `4 tiny (1 + m)(1 + max |p_z|)`
/// covers them all.
#[cfg(feature = "exact")]
pub(crate) fn edge_function_error<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> (S<V>, S<V>) {
    let shear = Shear::new(&ray.dir);
    let f = Frame::new(ray.origin, tri, &shear);
    let z = f.scaled_z(&shear);
    let m = max2(max3(&f.x), max3(&f.y));
    let one = S::<V>::ONE;
    let underflow = S::<V>::from_u32(4) * S::<V>::TINY * (one + m) * (one + max3(&f.pz));
    let e = ErrorBounds::new(&f, &z, &shear).e + underflow;
    (e, shear.dz.abs())
}

/// Moller-Trumbore ray/triangle test: the fast path.
///
/// Moller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection",
/// JGT 1997: solve `origin + t dir = a + u (b - a) + v (c - a)` by Cramer's
/// rule with the determinant `det = (b - a) . (dir x (c - a))`.
///
/// Same signature, conventions and invalid-input behaviour as
/// [`ray_triangle`]. **Not watertight**: `u`, `v` and `u + v <= 1` are
/// tested on rounded values computed differently for each triangle, so a
/// ray through a shared edge can miss both triangles. It agrees with
/// [`ray_triangle`] away from edges.
///
/// The determinant test is relative, not an absolute epsilon: the ray is
/// treated as parallel to the triangle when `|det|` is not larger than its
/// own rounding error bound (a sum of products of the magnitudes that make
/// it up), i.e. when the sign of `det` is not known. That test does not
/// change when the scene or the direction is scaled.
///
/// ```
/// use rayhit::{Ray, Side, Triangle, ray_triangle_mt, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, -4.0), Vec3::new(0.0, 0.0, 2.0));
/// let hit = ray_triangle_mt(&ray, &tri, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.u, hit.v, hit.side), (2.0, 0.25, 0.125, Side::Back));
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_mt<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<TriangleHit<S<V>>> {
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    // Invalid input needs no test of its own: a zero direction gives
    // `det = 0`, so `u` is NaN or infinite, a NaN or infinite coordinate
    // makes `det` or `u`, `v`, `t` NaN or infinite, and each fails a range
    // test, as does a NaN or negative `t_max`.
    let lanes = |v: V| L::<V>::new(v.x(), v.y(), v.z());
    let (a, d) = (lanes(tri.a), lanes(ray.dir));
    let e1 = lanes(tri.b).sub(a);
    let e2 = lanes(tri.c).sub(a);
    // p = d x e2, lane k = d[k+1] e2[k+2] - d[k+2] e2[k+1], with the two
    // products of each component kept for the determinant's error bound.
    let (m1, m2) = (d.rot1().mul(e2.rot2()), d.rot2().mul(e2.rot1()));
    let p = m1.sub(m2);
    let det = e1.mul(p).sum3();
    let inv_det = one / det;
    let s = lanes(ray.origin).sub(a);
    let u = s.mul(p).sum3() * inv_det;
    // (One branch for both of `u`'s limits: on rays that mostly miss, `u`
    // falls on either side about equally, and two branches were each
    // unpredictable where one is not.)
    if !u.in_unit_interval() {
        return None;
    }
    // q = s x e1.
    let q = s.rot1().mul(e1.rot2()).sub(s.rot2().mul(e1.rot1()));
    let v = d.mul(q).sum3() * inv_det;
    if !(v >= zero && u + v <= one) {
        return None;
    }
    let t = e2.mul(q).sum3() * inv_det;
    // (`t > 0` makes `is_finite` the same as `t <= MAX`, so the two upper
    // limits are one comparison; `min2` returns its second argument when
    // the comparison fails, so a NaN `t_max` stays NaN and fails it.)
    if !(t > zero && t <= min2(S::<V>::MAX, t_max)) {
        return None;
    }
    // The determinant's sign must be certain, or the ray is taken as
    // parallel. (Tested last, so that the common misses above skip it;
    // every test is a pure function of the same values, so the order
    // changes no answer: a determinant of zero makes `u` NaN or infinite,
    // which the first test rejects.)
    //
    // Each monomial e1_i d_j e2_k of det carries at most 7 roundings (two
    // edge subtractions, a product, a difference, a product, two sums), so
    // |det - det_exact| <= gamma(7) sum_i |e1_i| (|d_j e2_k| + |d_k e2_j|).
    // The sum is evaluated from the computed e1 and products m, which are
    // rounded versions of the exact ones (at most 6 roundings along any
    // path, with the sum's own), and `bound_up` makes it an upper bound.
    let mag = m1.abs().add(m2.abs());
    let det_bound = bound_up(S::<V>::gamma_n(7) * e1.abs().mul(mag).sum3(), 7);
    if !(det.abs() > det_bound) {
        return None;
    }
    // det = e1 . (d x e2) = -d . ((b - a) x (c - a)): positive when the ray
    // runs against the normal.
    let side = if det > zero { Side::Front } else { Side::Back };
    Some(TriangleHit { t, u, v, side })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A coordinate on a coarse grid (so that shared edges, zero edge
    /// functions and axis-parallel rays are common) or, one time in four, a
    /// float with random bits in a moderate range.
    fn coordinate(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        if (*state).is_multiple_of(4) {
            let m = ((*state >> 11) % (1 << 20)) as f64 / (1 << 20) as f64;
            (m - 0.5) * 2f64.powi(((*state >> 40) % 40) as i32 - 20)
        } else {
            ((*state >> 8) % 17) as f64 / 4.0 - 2.0
        }
    }

    /// The watertight test on lanes (what `ray_triangle` and
    /// `ray_triangle_prepared` run) and the triangle batch give, bit for
    /// bit, the answer of the one-component-at-a-time definition,
    /// `watertight_sheared`, in both precisions and for any `t_max`: on
    /// random triangles, and on zero-area ones (T-junction fillers `a, m, b`
    /// with `m` the midpoint, and `a, b, a + 2 (b - a)`, all exact on the
    /// grid) with rays aimed at points of their segment, where the
    /// definition can hit what the plain test rejects (it takes `t` from the
    /// segment when the determinant's sign is unknown).
    #[test]
    fn lanes_are_the_definition() {
        fn check<V: Vector>(state: &mut u64, zero_area: bool) -> usize {
            let mut v = || {
                V::new(
                    S::<V>::from_f64(coordinate(state)),
                    S::<V>::from_f64(coordinate(state)),
                    S::<V>::from_f64(coordinate(state)),
                )
            };
            let (a, b, c, origin) = (v(), v(), v(), v());
            let (filler, s) = (
                (*state >> 20).is_multiple_of(2),
                ((*state >> 24) % 9) as f64 / 8.0,
            );
            let (tri, on_segment) = if zero_area {
                let (half, two) = (S::<V>::HALF, S::<V>::TWO);
                let tri = if filler {
                    Triangle::new(a, (a + b) * half, b)
                } else {
                    Triangle::new(a, b, a + (b - a) * two)
                };
                (tri, Some(a + (b - a) * S::<V>::from_f64(s)))
            } else {
                (Triangle::new(a, b, c), None)
            };
            // Half of the rays aimed at an edge's midpoint or the centroid
            // (rounded), for hits and edge cases.
            let half = S::<V>::HALF;
            let pick = coordinate(state);
            let mut v = || {
                V::new(
                    S::<V>::from_f64(coordinate(state)),
                    S::<V>::from_f64(coordinate(state)),
                    S::<V>::from_f64(coordinate(state)),
                )
            };
            let dir = match (on_segment, (pick * 4.0) as i64 % 4) {
                (Some(p), _) => p - origin,
                (None, 0) => (tri.a + tri.b) * half - origin,
                (None, 1) => (tri.a + tri.b + tri.c) * (S::<V>::ONE / S::<V>::from_u32(3)) - origin,
                _ => v(),
            };
            let ray = Ray::new(origin, dir);
            let t_max = S::<V>::from_f64(coordinate(state).abs() * 4.0);
            let mut hits = 0;
            for t_max in [t_max, S::<V>::INFINITY] {
                let expected = (ray.is_valid() && t_max_ok(t_max)).then(|| {
                    let shear = Shear::new(&ray.dir);
                    watertight_sheared(ray.origin, &shear, &tri, t_max, EdgeRule::Closed)
                });
                let bits = |h: Option<TriangleHit<S<V>>>| {
                    h.map(|h| {
                        (
                            h.t.to_f64().to_bits(),
                            h.u.to_f64().to_bits(),
                            h.v.to_f64().to_bits(),
                            h.side,
                        )
                    })
                };
                let expected = bits(expected.flatten());
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(ray_triangle(&ray, &tri, t_max)),
                    expected,
                    "{ray:?} {tri:?}"
                );
                let prepared = PreparedRay::new(&ray);
                assert_eq!(
                    bits(ray_triangle_prepared(&prepared, &tri, t_max)),
                    expected,
                    "{ray:?} {tri:?}"
                );
                if let Some(batch) = crate::TriangleBatch::<V, 8>::from_slice(&[tri]) {
                    let h = crate::ray_triangle_batch(&prepared, &batch, t_max);
                    let lane = (h.mask & 1 != 0).then(|| {
                        let side = if h.front & 1 != 0 {
                            Side::Front
                        } else {
                            Side::Back
                        };
                        (h.t[0].to_f64().to_bits(), side)
                    });
                    assert_eq!(lane, expected.map(|e| (e.0, e.3)), "{ray:?} {tri:?}");
                }
            }
            hits
        }
        let mut state = 0x1234_5678_9abc_def1_u64;
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut state, false) + check::<DVec3>(&mut state, false);
        }
        // Enough hits that the comparison means something (about a third).
        assert!(hits > 100_000, "{hits}");
        let mut hits = 0;
        for _ in 0..50_000 {
            hits += check::<Vec3>(&mut state, true) + check::<DVec3>(&mut state, true);
        }
        // Zero-area triangles are hit only where rounding leaves them a
        // sliver; enough of them that the comparison means something.
        assert!(hits > 1_000, "{hits}");
    }

    /// Moller-Trumbore as written with glam's `cross` and `dot`, one
    /// component at a time: the definition the lanes form must match.
    fn mt_definition<V: Vector>(
        ray: &Ray<V>,
        tri: &Triangle<V>,
        t_max: S<V>,
    ) -> Option<TriangleHit<S<V>>> {
        let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
        if !(ray.is_valid() && t_max_ok(t_max)) {
            return None;
        }
        let d = ray.dir;
        let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
        let (m1, m2) = (d.y() * e2.z(), d.z() * e2.y());
        let (m3, m4) = (d.z() * e2.x(), d.x() * e2.z());
        let (m5, m6) = (d.x() * e2.y(), d.y() * e2.x());
        let p = V::new(m1 - m2, m3 - m4, m5 - m6);
        let det = e1.dot(p);
        let mag = V::new(
            m1.abs() + m2.abs(),
            m3.abs() + m4.abs(),
            m5.abs() + m6.abs(),
        );
        let det_bound = bound_up(S::<V>::gamma_n(7) * e1.abs().dot(mag), 7);
        if !(det.abs() > det_bound) {
            return None;
        }
        let inv_det = one / det;
        let s = ray.origin - tri.a;
        let u = s.dot(p) * inv_det;
        if !(u >= zero && u <= one) {
            return None;
        }
        let q = s.cross(e1);
        let v = d.dot(q) * inv_det;
        if !(v >= zero && u + v <= one) {
            return None;
        }
        let t = e2.dot(q) * inv_det;
        if !(t > zero && t <= t_max && t.is_finite()) {
            return None;
        }
        let side = if det > zero { Side::Front } else { Side::Back };
        Some(TriangleHit { t, u, v, side })
    }

    /// `ray_triangle_mt` (on lanes, with no separate validity test) is bit
    /// for bit its definition, invalid input included.
    #[test]
    fn mt_lanes_are_the_definition() {
        fn check<V: Vector>(state: &mut u64) -> usize {
            let mut v = || {
                let special = [
                    S::<V>::NAN,
                    S::<V>::INFINITY,
                    -S::<V>::INFINITY,
                    S::<V>::ZERO,
                ];
                let c = |state: &mut u64| {
                    let x = coordinate(state);
                    if (*state).is_multiple_of(97) {
                        special[(*state >> 9) as usize % 4]
                    } else {
                        S::<V>::from_f64(x)
                    }
                };
                V::new(c(state), c(state), c(state))
            };
            let tri = Triangle::new(v(), v(), v());
            let (origin, other) = (v(), v());
            let dir = if (*state).is_multiple_of(2) {
                (tri.a + tri.b + tri.c) * (S::<V>::ONE / S::<V>::from_u32(3)) - origin
            } else {
                other
            };
            let ray = Ray::new(origin, dir);
            let mut hits = 0;
            let t_max = S::<V>::from_f64(coordinate(state) * 4.0);
            for t_max in [t_max, S::<V>::INFINITY, S::<V>::NAN] {
                let bits = |h: Option<TriangleHit<S<V>>>| {
                    h.map(|h| {
                        (
                            h.t.to_f64().to_bits(),
                            h.u.to_f64().to_bits(),
                            h.v.to_f64().to_bits(),
                            h.side,
                        )
                    })
                };
                let expected = bits(mt_definition(&ray, &tri, t_max));
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(ray_triangle_mt(&ray, &tri, t_max)),
                    expected,
                    "{ray:?} {tri:?} {t_max:?}"
                );
            }
            hits
        }
        let mut state = 0x0fed_cba9_8765_4321_u64;
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut state) + check::<DVec3>(&mut state);
        }
        assert!(hits > 50_000, "{hits}");
    }
}
