//! The watertight test on a batch: [`TriangleBatch`], up to 32 triangles
//! structure-of-arrays, and `ray_triangle_batch`, which tests one prepared
//! ray against eight of them at a time, each lane bit for bit the answer of
//! [`ray_triangle`](crate::ray_triangle) on its triangle (the definition's
//! common case, lane by lane; the rare lanes go to the definition itself);
//! `ray_triangle_batch_in`, the same over an interval; and the lanes of
//! the one-hit rule, each the scalar test.

use core::marker::PhantomData;

use glam::Vec3;

use super::definition::{EdgeRule, watertight_definition};
use super::lanes::{RayLanes, outside};
use super::{Side, Triangle, TriangleHit};
use crate::num::round::max2;
use crate::num::{Lanes8, S, Scalar, Vector};
use crate::ray::{PreparedRay, t_max_ok};
use crate::simd::{Isa, Kernel, check_lanes, put};

/// Up to `N` triangles, structure-of-arrays.
///
/// Triangles are stored as given (a non-finite one is a lane that the
/// watertight test misses, and a zero-area one is hit exactly where the
/// scalar test hits it); empty lanes hold NaN corners and are masked off.
///
/// ```
/// use rayhit::{IntersectLanes, PreparedRay, Ray, Triangle, glam::Vec3};
/// use rayhit::batch::TriangleBatch;
/// // Four unit right triangles stacked along z at z = 1, 2, 3, 4.
/// let tris: Vec<Triangle> = (1..=4)
///     .map(|k| {
///         let z = k as f32;
///         Triangle::new(Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z), Vec3::new(0.0, 1.0, z))
///     })
///     .collect();
/// let batch = TriangleBatch::<Vec3, 4>::from_slice(&tris).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.25, 0.25, 0.0), Vec3::Z));
/// let hits = batch.hit(&ray, 3.5);
/// assert_eq!(hits.mask, 0b0111);
/// let (lane, nearest) = hits.nearest().unwrap();
/// assert_eq!((lane, nearest.t, nearest.u, nearest.v), (0, 1.0, 0.25, 0.25));
/// ```
///
/// Its query is [`IntersectLanes`](crate::IntersectLanes): every lane's
/// hit at once, each the scalar test's answer bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
// Aligned as `AabbBatch` is, for the same reason.
#[repr(C, align(32))]
pub struct TriangleBatch<V: Vector = Vec3, const N: usize = 8> {
    /// `p[corner][axis][lane]`, corners `a, b, c`.
    pub(super) p: [[[S<V>; N]; 3]; 3],
    /// Per lane, the triangle's reach from its first corner: at least
    /// `|p_i[a] - p_0[a]|` for the other corners `i` and every axis `a`
    /// (NaN in an empty lane, like its corners), for the interval forms' edge-sign test
    /// (`edge_signs_known`).
    pub(super) reach: [S<V>; N],
    /// The lanes that hold a triangle.
    pub(super) used: u32,
    /// The lanes whose triangle has zero area ([`Triangle::is_degenerate`]),
    /// decided once when stored: their hits take the scalar code's route
    /// for `t`.
    degenerate: u32,
}

impl<V: Vector, const N: usize> TriangleBatch<V, N> {
    /// The number of lanes, `N`.
    pub const LANES: usize = N;

    /// A batch with every lane empty.
    #[inline]
    #[must_use]
    pub fn empty() -> Self {
        const { check_lanes::<N>() };
        let nan = S::<V>::NAN;
        Self {
            p: [[[nan; N]; 3]; 3],
            reach: [nan; N],
            used: 0,
            degenerate: 0,
        }
    }

    /// The batch of `triangles` in lanes `0..triangles.len()`, the rest
    /// empty, or `None` when there are more than `N` triangles.
    #[inline]
    #[must_use]
    pub fn from_slice(triangles: &[Triangle<V>]) -> Option<Self> {
        if triangles.len() > N {
            return None;
        }
        let mut batch = Self::empty();
        for (lane, t) in triangles.iter().enumerate() {
            batch.set(lane, t);
        }
        Some(batch)
    }

    /// Stores `tri` in `lane`.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    pub fn set(&mut self, lane: usize, tri: &Triangle<V>) {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        for (i, corner) in [tri.a, tri.b, tri.c].into_iter().enumerate() {
            for k in 0..3 {
                self.p[i][k][lane] = corner[k];
            }
        }
        self.reach[lane] = reach(tri);
        self.used |= 1 << lane;
        if tri.is_degenerate() {
            self.degenerate |= 1 << lane;
        } else {
            self.degenerate &= !(1 << lane);
        }
    }

    /// Empties `lane`.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    pub fn clear(&mut self, lane: usize) {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        let nan = S::<V>::NAN;
        for corner in &mut self.p {
            for axis in corner.iter_mut() {
                axis[lane] = nan;
            }
        }
        self.reach[lane] = nan;
        self.used &= !(1 << lane);
        self.degenerate &= !(1 << lane);
    }

    /// The triangle in `lane`, if it holds one.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<Triangle<V>> {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        (self.used & (1 << lane) != 0).then(|| self.lane(lane))
    }

    /// The lanes that hold a triangle, one bit each.
    #[inline]
    #[must_use]
    pub fn mask(&self) -> u32 {
        self.used
    }

    #[inline(always)]
    fn lane(&self, lane: usize) -> Triangle<V> {
        let corner = |i: usize| V::new(self.p[i][0][lane], self.p[i][1][lane], self.p[i][2][lane]);
        Triangle::new(corner(0), corner(1), corner(2))
    }
}

/// The largest `|p_i[a] - p_0[a]|` over the corners `i = 1, 2` and the axes
/// `a`, rounded up: each difference rounds to nearest, so the exact one is
/// at most its float's successor. Infinite where a difference overflows.
/// (A triangle with a NaN or infinite corner has NaN edge functions, which
/// fail the edge-sign test whatever the reach.)
pub(super) fn reach<V: Vector>(tri: &Triangle<V>) -> S<V> {
    let (d1, d2) = ((tri.b - tri.a).abs(), (tri.c - tri.a).abs());
    (0..3)
        .map(|k| max2(d1[k], d2[k]))
        .fold(S::<V>::ZERO, max2)
        .next_up()
}

/// The answer of [`TriangleBatch`]'s [`hit`](crate::Intersect::hit): which lanes are hit, where, and
/// from which side.
///
/// For a lane in `mask`, `t`, `u`, `v` and the side (bit set in `front`
/// for [`Side::Front`]) are those [`ray_triangle`](crate::ray_triangle)
/// returns for that triangle; other lanes have `t = +inf`, `u = v = 0` and
/// no `front` bit, so the smallest `t` is the nearest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleBatchHits<F = f32, const N: usize = 8> {
    /// Lane `i` is hit when bit `i` is set.
    pub mask: u32,
    /// Lanes hit from the front ([`Side::Front`]); a subset of `mask`.
    pub front: u32,
    /// Per lane, the distance `t` (`+inf` for a lane not hit).
    pub t: [F; N],
    /// Per lane, the barycentric `u`.
    pub u: [F; N],
    /// Per lane, the barycentric `v`.
    pub v: [F; N],
}

/// No lane hit: the answer of a batch nothing hits.
impl<F: Scalar, const N: usize> Default for TriangleBatchHits<F, N> {
    #[inline]
    fn default() -> Self {
        Self::none()
    }
}

impl<F: Scalar, const N: usize> TriangleBatchHits<F, N> {
    /// No lane hit: `t = +inf`, `u = v = 0` everywhere.
    #[inline(always)]
    pub(crate) fn none() -> Self {
        Self {
            mask: 0,
            front: 0,
            t: [F::INFINITY; N],
            u: [F::ZERO; N],
            v: [F::ZERO; N],
        }
    }

    /// The hit in `lane` as the scalar test returns it; `None` for a lane
    /// not hit and for `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<TriangleHit<F>> {
        (lane < N && self.mask & (1 << lane) != 0).then(|| TriangleHit {
            t: self.t[lane],
            u: self.u[lane],
            v: self.v[lane],
            side: if self.front & (1 << lane) != 0 {
                Side::Front
            } else {
                Side::Back
            },
        })
    }

    /// The nearest hit and its lane: the smallest `t`, the lowest lane
    /// among equal ones. `None` when no lane is hit.
    #[inline]
    #[must_use]
    pub fn nearest(&self) -> Option<(usize, TriangleHit<F>)> {
        let mut best: Option<usize> = None;
        let mut bits = self.mask;
        while bits != 0 {
            let l = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            if best.is_none_or(|b| self.t[l] < self.t[b]) {
                best = Some(l);
            }
        }
        best.and_then(|l| self.get(l).map(|h| (l, h)))
    }
}

/// [`TriangleBatch`'s `hit`](crate::batch::TriangleBatch#method.hit) as a kernel, for any instruction set (see
/// `crate::simd`).
pub(crate) struct TriangleBatchKernel<V, const N: usize>(PhantomData<V>);

impl<V: Vector, const N: usize> Kernel for TriangleBatchKernel<V, N> {
    type Ray = PreparedRay<V>;
    type Shapes = TriangleBatch<V, N>;
    type Limit = S<V>;
    type Output = TriangleBatchHits<S<V>, N>;
    /// Compiled with AVX-512 the triangle batch comes out slower than its
    /// AVX2 copy, which `Avx512` runs instead.
    const AVX512: bool = false;

    #[inline(always)]
    fn run<I: Isa>(
        _: I,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> Self::Output {
        triangle_batch_body::<I::W<S<V>>, V, N>(ray, batch, t_max)
    }
}

/// The body of [`TriangleBatch`'s `hit`](crate::batch::TriangleBatch#method.hit) with the eight-lane type `W`, eight
/// lanes at a time.
#[inline(always)]
fn triangle_batch_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    t_max: S<V>,
) -> TriangleBatchHits<S<V>, N> {
    const { check_lanes::<N>() };
    let zero = S::<V>::ZERO;
    let one = S::<V>::ONE;
    let inf = S::<V>::INFINITY;
    let mut out = TriangleBatchHits::none();
    if !(ray.is_valid() && t_max_ok(t_max)) {
        return out;
    }
    let sh = ray.shear();
    let ray_front = sh.dz > zero;
    let frame = RayLanes::<W>::new(ray);

    let splat = W::splat;
    let (lo, top, ones) = (splat(zero), splat(t_max), splat(one));
    let sz = splat(sh.sz);

    let top_max = splat(if t_max < S::<V>::MAX {
        t_max
    } else {
        S::<V>::MAX
    });
    let (mut hit, mut slow, mut front) = (0, 0, 0);
    let all = lo.le(lo);
    for c in 0..N.div_ceil(8) {
        // Lanes past N hold NaN, and are not in `batch.used`.
        let ([e0, e1, e2], [pz0, pz1, pz2]) = frame.edges(&batch.p, c);
        // (A NaN edge function makes `det` NaN and the range test below
        // fails, as in the scalar test, whatever `outside` says.)
        let (outside, e_min, e_max) = outside([e0, e1, e2], lo);
        // A zero edge function sends a lane inside to the scalar code,
        // which recomputes it with its sign exact (a lane outside stays
        // outside whatever that sign). Inside, the edge functions share a
        // sign, so one is zero exactly when the smallest or the largest is.
        let zero_edge = W::or(e_min.eq(lo), e_max.eq(lo));
        if W::bits(W::and_not(all, outside)) == 0 {
            // Every lane outside (most rays miss most triangles of a leaf):
            // nothing more to compute for this chunk, and with one chunk,
            // nothing to do but return (so the answer is written once,
            // not kept on the stack for the end).
            if N <= 8 {
                return out;
            }
            continue;
        }
        let det = e0.add(e1).add(e2);
        // Scaled distance and range test.
        let (z0, z1, z2) = (pz0.mul(sz), pz1.mul(sz), pz2.mul(sz));
        let t_scaled = e0.mul(z0).add(e1.mul(z1)).add(e2.mul(z2));
        let limit = top.mul(det);
        let ahead_range = W::and(W::and(lo.lt(det), lo.lt(t_scaled)), t_scaled.le(limit));
        let behind_range = W::and(W::and(det.lt(lo), t_scaled.lt(lo)), limit.le(t_scaled));
        let inv_det = ones.div(det);
        let t = t_scaled.mul(inv_det);
        // (`t > 0` makes `is_finite` the same as `t <= MAX`, and `top_max`
        // is `min(t_max, MAX)`.)
        let t_ok = W::and(lo.lt(t), t.le(top_max));
        let pass = W::and(W::and_not(W::or(ahead_range, behind_range), outside), t_ok);
        // The first sufficient test for t > 0 (see `watertight_definition`):
        // every `z_i > 0`, that is `min z_i > 0` (where it matters, `pass`
        // and no zero edge function, every `z_i` is finite: a NaN or
        // infinite one makes `det` or `t` fail above).
        let (z_min, z_max) = (z0.min(z1.min(z2)), z0.max(z1.max(z2)));
        let ahead = lo.lt(z_min);
        // u and v: finite whenever `pass` holds and no edge function is
        // zero (each `|e_i| <= |det|`, as the `e_i` share a sign, and
        // `1 / det` is finite, as `t` is), so the definition's finiteness
        // test of `u` and `v` is always passed here and is not repeated.
        let u = e1.mul(inv_det).min(ones);
        let v = e2.mul(inv_det).min(ones);
        let hit_c = W::and(W::and_not(pass, zero_edge), ahead);
        let shift = 8 * c;
        hit |= W::bits(hit_c) << shift;
        slow |= W::bits(W::or(zero_edge, W::and_not(pass, ahead))) << shift;
        // Zero-area triangles (marked when stored; most batches have none):
        // a hit goes to the scalar code, which takes its `t` from the
        // segment (the scalar kernels find such hits by a conditioning
        // test), and so does a plain miss inside the triangle with some
        // corner in front of the origin (`max z_i > 0`), which the
        // definition may turn into a hit; for any other triangle the plain
        // miss is the definition's answer (see `watertight_lanes`; a NaN
        // depth leaves the lane to the plain miss, which is then the
        // answer).
        let degenerate = (batch.degenerate >> shift) & 0xff;
        if degenerate != 0 {
            let inside = W::and_not(all, outside);
            let reconsider = W::and(W::and_not(inside, pass), lo.lt(z_max));
            hit &= !(degenerate << shift);
            slow |= (W::bits(W::or(hit_c, reconsider)) & degenerate) << shift;
        }
        front |= W::bits(lo.lt(det)) << shift;
        put(&mut out.t, c, W::select(hit_c, t, splat(inf)));
        put(&mut out.u, c, W::select(hit_c, u, lo));
        put(&mut out.v, c, W::select(hit_c, v, lo));
    }
    let used = batch.used;
    let hit = hit & used;
    out.mask = hit;
    // A hit is from the front when the sign of its determinant differs
    // from that of the ray's main component (see `watertight_definition`).
    out.front = if ray_front { !front & hit } else { front & hit };
    let slow = slow & used;
    if slow != 0 {
        out = slow_lanes(ray, batch, t_max, slow, out);
    }
    out
}

/// The lanes in `slow` of [`triangle_batch_body`]'s answer, from the scalar
/// code. Out of line (they are rare), so that the vector code keeps its
/// registers.
#[cold]
#[inline(never)]
fn slow_lanes<V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    t_max: S<V>,
    slow: u32,
    out: TriangleBatchHits<S<V>, N>,
) -> TriangleBatchHits<S<V>, N> {
    let (origin, shear) = (ray.origin(), ray.shear());
    scalar_lanes(batch, slow, false, out, |tri| {
        watertight_definition((origin, ray.dir), &shear, tri, t_max, EdgeRule::Closed)
    })
}

/// The lanes in `slow` of a batch answer from the scalar `test` on each
/// lane's triangle (a lane can arrive with an answer already written,
/// which is replaced); with `any`, it stops at the first hit.
#[inline(always)]
pub(super) fn scalar_lanes<V: Vector, const N: usize>(
    batch: &TriangleBatch<V, N>,
    mut slow: u32,
    any: bool,
    mut out: TriangleBatchHits<S<V>, N>,
    test: impl Fn(&Triangle<V>) -> Option<TriangleHit<S<V>>>,
) -> TriangleBatchHits<S<V>, N> {
    while slow != 0 {
        let l = slow.trailing_zeros() as usize;
        slow &= slow - 1;
        (out.t[l], out.u[l], out.v[l]) = (S::<V>::INFINITY, S::<V>::ZERO, S::<V>::ZERO);
        if let Some(h) = test(&batch.lane(l)) {
            out.mask |= 1 << l;
            if h.side == Side::Front {
                out.front |= 1 << l;
            }
            (out.t[l], out.u[l], out.v[l]) = (h.t, h.u, h.v);
            if any {
                break;
            }
        }
    }
    out
}

/// Every lane of the batch with the one-hit rule: the scalar test on each
/// lane's triangle (the rule runs the definition, which has no lane form).
pub(super) fn one_hit_lanes<V: Vector, const N: usize>(
    ray: &crate::ray::Ray<V>,
    batch: &TriangleBatch<V, N>,
    search: crate::query::Search<S<V>>,
) -> TriangleBatchHits<S<V>, N> {
    use crate::query::Intersect;
    let mut hits = TriangleBatchHits::none();
    for lane in 0..N {
        let Some(hit) = batch.get(lane).and_then(|tri| tri.hit(ray, search)) else {
            continue;
        };
        hits.mask |= 1 << lane;
        if hit.side == Side::Front {
            hits.front |= 1 << lane;
        }
        (hits.t[lane], hits.u[lane], hits.v[lane]) = (hit.t, hit.u, hit.v);
    }
    hits
}
