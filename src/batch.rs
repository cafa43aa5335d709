//! Batch kernels: one ray against a small batch of boxes or triangles
//! stored structure-of-arrays, the inner loops of BVH traversal.
//!
//! A batch holds up to `N` shapes (`N` from 1 to 32; 8 and 16 are the
//! useful sizes), each coordinate in an array of its own, so that one
//! arithmetic operation serves eight lanes. The kernels work on eight lanes
//! at a time (`crate::lanes::Lanes8`: one AVX register, two SSE registers,
//! or an array elsewhere and for `f64`), from one source. On x86-64 with
//! the `std` feature, when the target lacks AVX2 (the default target has
//! only SSE2), each kernel also exists compiled with AVX2 and is picked at
//! run time on CPUs that have it: per call by [`ray_aabb_batch`] and
//! [`ray_triangle_batch`], or once for a whole traversal by [`with_simd`].
//!
//! Every lane's answer is, bit for bit, the answer of the scalar kernel on
//! that lane's shape: [`ray_aabb_batch`] runs the very arithmetic of
//! [`ray_aabb_prepared`](crate::ray_aabb_prepared), and
//! [`ray_triangle_batch`] that of [`ray_triangle`](crate::ray_triangle),
//! handing the rare lanes that need the exact-sign fallback or the slower
//! `t > 0` tests to the scalar code itself. So every guarantee of the
//! scalar kernels (conservative boxes, watertight triangles, `t > 0` in
//! exact arithmetic, the error bounds) holds for every lane.

use glam::Vec3;

use crate::aabb::{Aabb, PreparedRay, exit_slack, exit_widening};
use crate::lanes::{Lanes, Lanes8};
use crate::quantized::{QuantizedChildren, quantized_body};
use crate::ray::t_max_ok;
use crate::real::{S, Scalar, Vector};
use crate::triangle::{EdgeRule, Side, Triangle, TriangleHit, watertight_sheared};

/// Checks `1 <= N <= 32` at compile time (the hit masks are `u32`).
const fn check_lanes<const N: usize>() {
    assert!(N >= 1 && N <= 32, "a batch has 1 to 32 lanes");
}

/// Lanes `8 c .. 8 c + 8` of `row`, lanes past its end NaN.
///
/// The kernels on eight lanes call only functions marked
/// `#[inline(always)]`, never closures: the AVX2 copies must be inlined,
/// whole, into the functions compiled with AVX2.
#[inline(always)]
fn lanes_at<W: Lanes8, const N: usize>(row: &[W::F; N], c: usize) -> W {
    match row.get(8 * c..8 * c + 8) {
        Some(full) => W::load(full.try_into().expect("8 lanes")),
        None => W::load(&core::array::from_fn(|l| {
            row.get(8 * c + l).copied().unwrap_or(W::F::NAN)
        })),
    }
}

/// Stores lanes `8 c .. 8 c + 8` of `row` from `lanes` (those that exist).
#[inline(always)]
fn put<W: Lanes8, const N: usize>(row: &mut [W::F; N], c: usize, lanes: W) {
    if let Some(full) = row.get_mut(8 * c..8 * c + 8) {
        lanes.store(full.try_into().expect("8 lanes"));
    } else {
        let mut a = [W::F::ZERO; 8];
        lanes.store(&mut a);
        for (l, x) in a.into_iter().enumerate() {
            if let Some(slot) = row.get_mut(8 * c + l) {
                *slot = x;
            }
        }
    }
}

/// One axis of the slab test's NaN-safe fold (see
/// [`ray_aabb_prepared`](crate::ray_aabb_prepared)): the entry and exit
/// through the slab with plane distances `t0`, `t1`, clipped to `[lo, hi]`.
#[inline(always)]
fn fold<W: Lanes8>(t0: W, t1: W, lo: W, hi: W) -> (W, W) {
    (t0.max(lo).min(t1.max(lo)), t0.min(hi).max(t1.min(hi)))
}

/// A prepared ray's slab test on eight boxes at a time: the ray's values
/// in every lane, ready for [`Slab8::test`].
pub(crate) struct Slab8<W: Lanes8> {
    origin: [W; 3],
    inv_to_min: [W; 3],
    inv_to_max: [W; 3],
    /// `0` and `t_max` in every lane.
    lo: W,
    hi: W,
    simple: bool,
}

impl<W: Lanes8> Slab8<W> {
    #[inline(always)]
    pub(crate) fn new<V: Vector<Scalar = W::F>>(ray: &PreparedRay<V>, t_max: W::F) -> Self {
        let [ox, oy, oz] = ray.slab.origin.to_array();
        let [ax, ay, az] = ray.slab.inv_to_min.to_array();
        let [bx, by, bz] = ray.slab.inv_to_max.to_array();
        Self {
            origin: [W::splat(ox), W::splat(oy), W::splat(oz)],
            inv_to_min: [W::splat(ax), W::splat(ay), W::splat(az)],
            inv_to_max: [W::splat(bx), W::splat(by), W::splat(bz)],
            lo: W::splat(W::F::ZERO),
            hi: W::splat(t_max),
            simple: ray.simple,
        }
    }

    /// The slab test of eight valid boxes (for `t_max >= 0`): the lanes
    /// hit, and the entry `t` of each (`+inf` where not hit), bit for bit
    /// what [`ray_aabb_prepared`](crate::ray_aabb_prepared) gives for each.
    ///
    /// For rays whose reciprocals are all normal (every component
    /// nonzero), the per-axis folds simplify. Every reciprocal is then
    /// normal (the two per axis are equal) and every box valid, so no
    /// distance is NaN, and the definition's folds reduce to the textbook
    /// order of each pair: the entry through an axis,
    /// `min(max(t0, 0), max(t1, 0))`, is `max(min(t0, t1), 0)`, and the exit,
    /// `max(min(t0, t_max), min(t1, t_max))`, is `min(max(t0, t1), t_max)`
    /// (max and min commute with the clamps for values that are not NaN).
    /// The largest entry is taken before the clamp at 0 rather than after:
    /// the same value, and `+0`, never `-0`, when it is 0; a `-0`/`+0` tie
    /// among the exits widens to the same limit. So the answers are the
    /// definition's, bit for bit.
    #[inline(always)]
    pub(crate) fn test(&self, min: [W; 3], max: [W; 3]) -> (W::Mask, W) {
        let (lo, hi, o) = (self.lo, self.hi, self.origin);
        let (r0, r1) = (self.inv_to_min, self.inv_to_max);
        let t0 = [
            min[0].sub(o[0]).mul(r0[0]),
            min[1].sub(o[1]).mul(r0[1]),
            min[2].sub(o[2]).mul(r0[2]),
        ];
        let t1 = [
            max[0].sub(o[0]).mul(r1[0]),
            max[1].sub(o[1]).mul(r1[1]),
            max[2].sub(o[2]).mul(r1[2]),
        ];
        let (enter, exit) = if self.simple {
            let near = t0[0].min(t1[0]).max(t0[1].min(t1[1])).max(t0[2].min(t1[2]));
            let far = t0[0].max(t1[0]).min(t0[1].max(t1[1])).min(t0[2].max(t1[2]));
            (near.max(lo), far.min(hi))
        } else {
            // The definition's folds, lane by lane.
            let (ex, xx) = fold(t0[0], t1[0], lo, hi);
            let (ey, xy) = fold(t0[1], t1[1], lo, hi);
            let (ez, xz) = fold(t0[2], t1[2], lo, hi);
            (ex.max(ey.max(ez)), xx.min(xy.min(xz)))
        };
        // The end of the definition, lane by lane (`enter <= limit &&
        // enter <= MAX` as `enter <= min(limit, MAX)`: `limit` is not NaN
        // here, as `t_max` is not).
        let limit = exit
            .mul(W::splat(exit_widening()))
            .add(W::splat(exit_slack()));
        let hit = enter.le(limit.min(W::splat(W::F::MAX)));
        let exit = limit.min(hi);
        (
            hit,
            W::select(hit, enter.min(exit), W::splat(W::F::INFINITY)),
        )
    }
}

/// Up to `N` boxes, structure-of-arrays, validated when stored.
///
/// A lane holds a valid box (see [`Aabb::is_valid`]) or nothing: storing an
/// invalid box (inverted, NaN or infinite) empties the lane, so that the
/// kernel needs no validity test. An empty lane holds the box
/// `[+inf, +inf] x [-inf, -inf] x [0, 0]`, which every prepared ray misses
/// with the slab test's arithmetic alone: along `x` (or `y`, whichever the
/// ray's direction component makes a distance of `+inf`) the entry is
/// `+inf`, and along the other the exit is `-inf`; a ray with no valid
/// origin (prepared with its origin at `+inf`) gets `inf - inf = NaN` on
/// `x`, which leaves the interval alone, and an exit of `-inf` on `y`. The
/// hit mask is also and-ed with the lanes in use.
///
/// ```
/// use rayhit::{Aabb, AabbBatch, PreparedRay, Ray, ray_aabb_batch, glam::Vec3};
/// let boxes: Vec<Aabb> = (0..8)
///     .map(|i| {
///         let x = 2.0 * i as f32;
///         Aabb::new(Vec3::new(x, -1.0, -1.0), Vec3::new(x + 1.0, 1.0, 1.0))
///     })
///     .collect();
/// let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// // Along +x from x = 5.5: boxes 3 (x in [6, 7]) to 7 are ahead.
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(5.5, 0.0, 0.0), Vec3::X));
/// let hits = ray_aabb_batch(&ray, &batch, f32::INFINITY);
/// assert_eq!(hits.mask, 0b1111_1000);
/// assert_eq!(hits.get(3), Some(0.5));
/// assert_eq!(hits.get(2), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
// Aligned so that, for 8 and 16 lanes, every row of `f32` starts a 32-byte
// boundary: an AVX load that straddles a cache line costs about twice as
// much, and a 196-byte batch would make that depend on where it lies.
#[repr(C, align(32))]
pub struct AabbBatch<V: Vector = Vec3, const N: usize = 8> {
    /// `planes[0][k][lane]`: the box's lower bound on axis `k`;
    /// `planes[1][k][lane]` its upper bound. (One array, so that a kernel
    /// picks the near plane of an axis by index, not by branch.)
    planes: [[[S<V>; N]; 3]; 2],
    /// The lanes that hold a valid box.
    used: u32,
}

impl<V: Vector, const N: usize> AabbBatch<V, N> {
    /// The number of lanes, `N`.
    pub const LANES: usize = N;

    /// A batch with every lane empty.
    #[inline]
    #[must_use]
    pub fn empty() -> Self {
        const { check_lanes::<N>() };
        let (inf, zero) = (S::<V>::INFINITY, S::<V>::ZERO);
        let empty = [inf, -inf, zero].map(|c| [c; N]);
        Self {
            planes: [empty, empty],
            used: 0,
        }
    }

    /// The batch of `boxes` in lanes `0..boxes.len()`, the rest empty, or
    /// `None` when there are more than `N` boxes.
    #[inline]
    #[must_use]
    pub fn from_slice(boxes: &[Aabb<V>]) -> Option<Self> {
        if boxes.len() > N {
            return None;
        }
        let mut batch = Self::empty();
        for (lane, b) in boxes.iter().enumerate() {
            batch.set(lane, b);
        }
        Some(batch)
    }

    /// Stores `aabb` in `lane`, or empties the lane if the box is invalid.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    pub fn set(&mut self, lane: usize, aabb: &Aabb<V>) {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        if aabb.is_valid() {
            for k in 0..3 {
                self.planes[0][k][lane] = aabb.min[k];
                self.planes[1][k][lane] = aabb.max[k];
            }
            self.used |= 1 << lane;
        } else {
            self.clear(lane);
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
        let empty = Self::empty();
        for k in 0..3 {
            self.planes[0][k][lane] = empty.planes[0][k][lane];
            self.planes[1][k][lane] = empty.planes[1][k][lane];
        }
        self.used &= !(1 << lane);
    }

    /// The box in `lane`, if it holds one.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<Aabb<V>> {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        let corner = |c: &[[S<V>; N]; 3]| V::new(c[0][lane], c[1][lane], c[2][lane]);
        let [min, max] = &self.planes;
        (self.used & (1 << lane) != 0).then(|| Aabb::new(corner(min), corner(max)))
    }

    /// The lanes that hold a box, one bit each (lane `i` is bit `i`).
    #[inline]
    #[must_use]
    pub fn mask(&self) -> u32 {
        self.used
    }
}

/// The answer of [`ray_aabb_batch`]: which lanes are hit, and where the ray
/// enters each box hit.
///
/// For a lane in `mask`, `enter[lane]` is the entry `t` that
/// [`ray_aabb_prepared`](crate::ray_aabb_prepared) returns for that box;
/// for any other lane it is `+inf`, so the smallest `enter` is the nearest
/// box hit. (The exit, rarely wanted in traversal, is left out; the scalar
/// test gives it for a lane that needs it.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AabbBatchHits<F = f32, const N: usize = 8> {
    /// Lane `i` is hit when bit `i` is set.
    pub mask: u32,
    /// Per lane, the entry `t` (`+inf` for a lane not hit).
    pub enter: [F; N],
}

impl<F: Scalar, const N: usize> AabbBatchHits<F, N> {
    /// The entry `t` of a lane that is hit, as the scalar test returns it;
    /// `None` otherwise, and for `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<F> {
        (lane < N && self.mask & (1 << lane) != 0).then(|| self.enter[lane])
    }
}

/// The slab test of one prepared ray against every box of a batch.
///
/// Lane by lane, the answer is exactly (bit for bit) what
/// [`ray_aabb_prepared`](crate::ray_aabb_prepared) returns for that box:
/// hit or miss, and the entry `t`. So all of its guarantees hold per lane:
/// no false miss against exact arithmetic, false hits only within a few
/// ulps of an edge, `0 <= enter <= t_max`, `enter` finite. Empty lanes, an
/// invalid ray and a NaN or negative `t_max` give no hits. Never panics.
///
/// ```
/// use rayhit::{Aabb, AabbBatch, PreparedRay, Ray, ray_aabb_batch, ray_aabb_prepared, glam::Vec3};
/// let a = Aabb::new(Vec3::new(-1.0, -1.0, 2.0), Vec3::new(1.0, 1.0, 3.0));
/// let b = Aabb::new(Vec3::new(4.0, 4.0, 2.0), Vec3::new(5.0, 5.0, 3.0));
/// let batch = AabbBatch::<Vec3, 4>::from_slice(&[a, b]).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::Z));
/// let hits = ray_aabb_batch(&ray, &batch, f32::INFINITY);
/// assert_eq!(hits.mask, 0b01);
/// assert_eq!(hits.get(0), Some(2.0));
/// assert_eq!(hits.get(0), ray_aabb_prepared(&ray, &a, f32::INFINITY).map(|(enter, _)| enter));
/// ```
#[inline]
#[must_use]
pub fn ray_aabb_batch<V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &AabbBatch<V, N>,
    t_max: S<V>,
) -> AabbBatchHits<S<V>, N> {
    #[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
    if let Some(simd) = Avx2::detect() {
        return simd.ray_aabb_batch(ray, batch, t_max);
    }
    TargetSimd.ray_aabb_batch(ray, batch, t_max)
}

/// The body of [`ray_aabb_batch`], inlined into both the default build and
/// the AVX2 copy, with the eight-lane type `W` of each, eight lanes at a
/// time.
#[inline(always)]
fn aabb_batch_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &AabbBatch<V, N>,
    t_max: S<V>,
) -> AabbBatchHits<S<V>, N> {
    let inf = S::<V>::INFINITY;
    let mut enter = [inf; N];
    if !t_max_ok(t_max) {
        return AabbBatchHits { mask: 0, enter };
    }
    let slab = Slab8::<W>::new(ray, t_max);
    let [min, max] = &batch.planes;
    let mut mask = 0;
    for c in 0..N.div_ceil(8) {
        // Lanes past N hold NaN, and are not in `batch.used`.
        let (hit, enter_c) = slab.test(
            [
                lanes_at::<W, N>(&min[0], c),
                lanes_at::<W, N>(&min[1], c),
                lanes_at::<W, N>(&min[2], c),
            ],
            [
                lanes_at::<W, N>(&max[0], c),
                lanes_at::<W, N>(&max[1], c),
                lanes_at::<W, N>(&max[2], c),
            ],
        );
        put(&mut enter, c, enter_c);
        mask |= W::bits(hit) << (8 * c);
    }
    // Empty lanes never hit (see `AabbBatch`); the mask of used lanes is
    // applied all the same.
    AabbBatchHits {
        mask: mask & batch.used,
        enter,
    }
}

/// Up to `N` triangles, structure-of-arrays.
///
/// Triangles are stored as given (a non-finite one is a lane that the
/// watertight test misses, and a zero-area one is hit exactly where the
/// scalar test hits it); empty lanes hold NaN corners and are masked off.
///
/// ```
/// use rayhit::{PreparedRay, Ray, Triangle, TriangleBatch, ray_triangle_batch, glam::Vec3};
/// // Four unit right triangles stacked along z at z = 1, 2, 3, 4.
/// let tris: Vec<Triangle> = (1..=4)
///     .map(|k| {
///         let z = k as f32;
///         Triangle::new(Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z), Vec3::new(0.0, 1.0, z))
///     })
///     .collect();
/// let batch = TriangleBatch::<Vec3, 4>::from_slice(&tris).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.25, 0.25, 0.0), Vec3::Z));
/// let hits = ray_triangle_batch(&ray, &batch, 3.5);
/// assert_eq!(hits.mask, 0b0111);
/// let (lane, nearest) = hits.nearest().unwrap();
/// assert_eq!((lane, nearest.t, nearest.u, nearest.v), (0, 1.0, 0.25, 0.25));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
// Aligned as `AabbBatch` is, for the same reason.
#[repr(C, align(32))]
pub struct TriangleBatch<V: Vector = Vec3, const N: usize = 8> {
    /// `p[corner][axis][lane]`, corners `a, b, c`.
    p: [[[S<V>; N]; 3]; 3],
    /// The lanes that hold a triangle.
    used: u32,
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

/// The answer of [`ray_triangle_batch`]: which lanes are hit, where, and
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

impl<F: Scalar, const N: usize> TriangleBatchHits<F, N> {
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

/// One corner of eight triangles in the ray's frame, as `Frame::new`
/// computes it: translated, its axes in the ray's order `k`, sheared.
#[inline(always)]
fn sheared<W: Lanes8, const N: usize>(
    p: &[[W::F; N]; 3],
    c: usize,
    k: [usize; 3],
    o: [W; 3],
    sx: W,
    sy: W,
) -> (W, W, W) {
    let px = lanes_at::<W, N>(&p[k[0]], c).sub(o[0]);
    let py = lanes_at::<W, N>(&p[k[1]], c).sub(o[1]);
    let pz = lanes_at::<W, N>(&p[k[2]], c).sub(o[2]);
    (px.add(sx.mul(pz)), py.add(sy.mul(pz)), pz)
}

/// The watertight test ([`ray_triangle`](crate::ray_triangle)) of one
/// prepared ray against every triangle of a batch.
///
/// Lane by lane, the answer is exactly (bit for bit) what
/// [`ray_triangle`](crate::ray_triangle) returns for the ray the
/// [`PreparedRay`] was made from and that lane's triangle, so all of its
/// guarantees hold per lane: watertight across shared edges, `t > 0` in
/// exact arithmetic, `t`, `u`, `v` within
/// [`ray_triangle_error_bounds`](crate::ray_triangle_error_bounds).
///
/// How: every lane runs the scalar test's arithmetic, in the same order, on
/// its own triangle. Two rare cases leave the vector path and run the
/// scalar code itself for their lane: an edge function that rounds to
/// exactly zero (the exact-sign recomputation), and a crossing inside the
/// triangle and the `t` range for which the cheapest of the three
/// sufficient tests for `t > 0` (all corners in front of the origin)
/// fails, so that the other two must decide. The answer is the same either
/// way; such a lane costs a scalar call more.
///
/// Empty lanes, an invalid ray and a NaN or negative `t_max` give no hits.
/// Never panics.
///
/// ```
/// use rayhit::{PreparedRay, Ray, Triangle, TriangleBatch, ray_triangle, ray_triangle_batch, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let batch = TriangleBatch::<Vec3, 8>::from_slice(&[tri, tri.flipped()]).unwrap();
/// let hits = ray_triangle_batch(&PreparedRay::new(&ray), &batch, f32::INFINITY);
/// assert_eq!((hits.mask, hits.front), (0b11, 0b01));
/// assert_eq!(hits.get(0), ray_triangle(&ray, &tri, f32::INFINITY));
/// assert_eq!(hits.get(1), ray_triangle(&ray, &tri.flipped(), f32::INFINITY));
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_batch<V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    t_max: S<V>,
) -> TriangleBatchHits<S<V>, N> {
    #[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
    if let Some(simd) = Avx2::detect() {
        return simd.ray_triangle_batch(ray, batch, t_max);
    }
    TargetSimd.ray_triangle_batch(ray, batch, t_max)
}

/// The body of [`ray_triangle_batch`], inlined into both the default build
/// and the AVX2 copy, with the eight-lane type `W` of each, eight lanes at a
/// time.
#[inline(always)]
fn triangle_batch_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &TriangleBatch<V, N>,
    t_max: S<V>,
) -> TriangleBatchHits<S<V>, N> {
    let zero = S::<V>::ZERO;
    let one = S::<V>::ONE;
    let inf = S::<V>::INFINITY;
    let mut out = TriangleBatchHits {
        mask: 0,
        front: 0,
        t: [inf; N],
        u: [zero; N],
        v: [zero; N],
    };
    if !(ray.is_valid() && t_max_ok(t_max)) {
        return out;
    }
    let sh = ray.shear();
    // The permuted axes: x, y, z of the ray's frame.
    let (kx, ky, kz) = (sh.kx as usize, sh.ky as usize, sh.kz as usize);
    // The origin in the ray's axis order, from the prepared lanes (indexing
    // the origin by axis would branch on the axis).
    let [ox, oy, oz] = ray.origin_lanes.map(|l| l.x());
    let ray_front = sh.dz > zero;

    let splat = W::splat;
    let (lo, top, ones) = (splat(zero), splat(t_max), splat(one));
    let (sx, sy, sz) = (splat(sh.sx), splat(sh.sy), splat(sh.sz));
    let (ox, oy, oz) = (splat(ox), splat(oy), splat(oz));

    let top_max = splat(if t_max < S::<V>::MAX {
        t_max
    } else {
        S::<V>::MAX
    });
    let (mut hit, mut slow, mut front) = (0, 0, 0);
    let all = lo.le(lo);
    for c in 0..N.div_ceil(8) {
        // Lanes past N hold NaN, and are not in `batch.used`.
        let (k, o) = ([kx, ky, kz], [ox, oy, oz]);
        let (x0, y0, pz0) = sheared::<W, N>(&batch.p[0], c, k, o, sx, sy);
        let (x1, y1, pz1) = sheared::<W, N>(&batch.p[1], c, k, o, sx, sy);
        let (x2, y2, pz2) = sheared::<W, N>(&batch.p[2], c, k, o, sx, sy);
        // Edge functions.
        let e0 = x1.mul(y2).sub(y1.mul(x2));
        let e1 = x2.mul(y0).sub(y2.mul(x0));
        let e2 = x0.mul(y1).sub(y0.mul(x1));
        // Inside test of `EdgeRule::Closed`: not both signs among the edge
        // functions. For non-NaN values "some e_i < 0" is "min e_i < 0",
        // which is cheaper; a NaN edge function makes `det` NaN and the
        // range test below fails, as in the scalar test, whatever this
        // says.
        let (e_min, e_max) = (e0.min(e1.min(e2)), e0.max(e1.max(e2)));
        let outside = W::and(e_min.lt(lo), lo.lt(e_max));
        // A zero edge function sends a lane inside to the scalar code,
        // which recomputes it with its sign exact (a lane outside stays
        // outside whatever that sign). Inside, the edge functions share a
        // sign, so one is zero exactly when the smallest or the largest is.
        let zero_edge = W::or(e_min.eq(lo), e_max.eq(lo));
        if W::bits(W::and_not(all, outside)) == 0 {
            // Every lane outside (most rays miss most triangles of a leaf):
            // nothing more to compute for this chunk.
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
        // The first sufficient test for t > 0 (see `watertight_sheared`):
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
    // from that of the ray's main component (see `watertight_sheared`).
    out.front = if ray_front { !front & hit } else { front & hit };
    let slow = slow & used;
    if slow != 0 {
        slow_lanes(ray, batch, t_max, slow, &mut out);
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
    mut slow: u32,
    out: &mut TriangleBatchHits<S<V>, N>,
) {
    while slow != 0 {
        let l = slow.trailing_zeros() as usize;
        slow &= slow - 1;
        let tri = batch.lane(l);
        // (A lane can arrive here with the plain answer already written.)
        (out.t[l], out.u[l], out.v[l]) = (S::<V>::INFINITY, S::<V>::ZERO, S::<V>::ZERO);
        if let Some(h) =
            watertight_sheared(ray.origin(), &ray.shear(), &tri, t_max, EdgeRule::Closed)
        {
            out.mask |= 1 << l;
            if h.side == Side::Front {
                out.front |= 1 << l;
            }
            (out.t[l], out.u[l], out.v[l]) = (h.t, h.u, h.v);
        }
    }
}

/// Work that [`with_simd`] runs compiled for the CPU's widest SIMD: a BVH
/// traversal, a tile of primary rays, any loop that calls the batch
/// kernels many times.
///
/// [`SimdWork::run`] gets the chosen instruction set as `simd`; calling the
/// batch kernels through it ([`Simd::ray_aabb_batch`],
/// [`Simd::ray_triangle_batch`]) runs them with no check and no call per
/// batch. Implement `run` with `#[inline(always)]`: `with_simd` compiles
/// it once per instruction set, and the attribute is what makes the
/// compiler copy the body into each (functions it calls need at least
/// `#[inline]`, and closures are not always inlined: write the loop out).
pub trait SimdWork {
    /// What the work returns.
    type Output;
    /// The work itself.
    fn run<I: Simd>(self, simd: I) -> Self::Output;
}

mod sealed {
    pub trait Sealed {}
}

/// An instruction set the batch kernels are compiled for; [`with_simd`]
/// hands one to [`SimdWork::run`].
///
/// Sealed. The kernels' answers are the same bits whichever it is.
pub trait Simd: Copy + core::fmt::Debug + sealed::Sealed {
    /// [`ray_aabb_batch`], compiled for this instruction set.
    #[must_use]
    fn ray_aabb_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &AabbBatch<V, N>,
        t_max: S<V>,
    ) -> AabbBatchHits<S<V>, N>;

    /// [`ray_triangle_batch`], compiled for this instruction set.
    #[must_use]
    fn ray_triangle_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N>;

    /// [`ray_quantized_children`](crate::ray_quantized_children), compiled
    /// for this instruction set.
    #[must_use]
    fn ray_quantized_children<V: Vector<Scalar = f32>>(
        self,
        ray: &PreparedRay<V>,
        node: &QuantizedChildren<'_, V>,
        t_max: f32,
    ) -> AabbBatchHits<f32, 8>;
}

/// The instruction set the build's target has (SSE2 on the default x86-64
/// target; AVX2 and more with `-C target-cpu=native` on such a CPU).
#[derive(Clone, Copy, Debug, Default)]
pub struct TargetSimd;

impl sealed::Sealed for TargetSimd {}

impl Simd for TargetSimd {
    #[inline(always)]
    fn ray_aabb_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &AabbBatch<V, N>,
        t_max: S<V>,
    ) -> AabbBatchHits<S<V>, N> {
        const { check_lanes::<N>() };
        aabb_batch_body::<<S<V> as Scalar>::Lanes8, V, N>(ray, batch, t_max)
    }

    #[inline(always)]
    fn ray_triangle_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N> {
        const { check_lanes::<N>() };
        triangle_batch_body::<<S<V> as Scalar>::Lanes8, V, N>(ray, batch, t_max)
    }

    #[inline(always)]
    fn ray_quantized_children<V: Vector<Scalar = f32>>(
        self,
        ray: &PreparedRay<V>,
        node: &QuantizedChildren<'_, V>,
        t_max: f32,
    ) -> AabbBatchHits<f32, 8> {
        quantized_body::<<f32 as Scalar>::Lanes8, V>(ray, node, t_max)
    }
}

/// AVX2, on a CPU that has it: [`with_simd`] makes one only after checking
/// (x86-64 builds with `std` whose target does not already assume AVX2).
#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
impl sealed::Sealed for Avx2 {}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
impl Avx2 {
    /// `Some` when the CPU has AVX2.
    #[inline]
    pub(crate) fn detect() -> Option<Self> {
        std::is_x86_feature_detected!("avx2").then_some(Avx2(()))
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
#[allow(unsafe_code)]
impl Simd for Avx2 {
    #[inline(always)]
    fn ray_aabb_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &AabbBatch<V, N>,
        t_max: S<V>,
    ) -> AabbBatchHits<S<V>, N> {
        const { check_lanes::<N>() };
        // SAFETY: the one precondition of calling a function compiled with
        // `#[target_feature(enable = "avx2")]` is that the CPU has AVX2;
        // an `Avx2` exists only where `Avx2::detect` found it.
        unsafe { avx2::aabb(ray, batch, t_max) }
    }

    #[inline(always)]
    fn ray_triangle_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N> {
        const { check_lanes::<N>() };
        // SAFETY: as above.
        unsafe { avx2::triangle(ray, batch, t_max) }
    }

    #[inline(always)]
    fn ray_quantized_children<V: Vector<Scalar = f32>>(
        self,
        ray: &PreparedRay<V>,
        node: &QuantizedChildren<'_, V>,
        t_max: f32,
    ) -> AabbBatchHits<f32, 8> {
        // SAFETY: as above.
        unsafe { avx2::quantized(ray, node, t_max) }
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
/// AVX-512 (with its 256-bit forms, AVX-512VL), on a CPU that has it and
/// AVX2: [`with_simd`] makes one only after checking (the same builds as
/// [`Avx2`]).
///
/// The box kernels run on the same eight lanes as with [`Avx2`], compiled
/// with AVX-512 enabled: twice the vector registers, so a ray's prepared
/// values stay in registers across a node's boxes, and comparisons into
/// mask registers. The triangle batch runs its AVX2 copy (compiled with
/// AVX-512 it comes out slower). The answers are the same bits.
#[derive(Clone, Copy, Debug)]
pub struct Avx512(());

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
impl sealed::Sealed for Avx512 {}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
impl Avx512 {
    /// `Some` when the CPU has AVX2, AVX-512F and AVX-512VL.
    #[inline]
    pub(crate) fn detect() -> Option<Self> {
        (std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl"))
        .then_some(Avx512(()))
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
#[allow(unsafe_code)]
impl Simd for Avx512 {
    #[inline(always)]
    fn ray_aabb_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &AabbBatch<V, N>,
        t_max: S<V>,
    ) -> AabbBatchHits<S<V>, N> {
        const { check_lanes::<N>() };
        // SAFETY: the one precondition of calling a function compiled with
        // `#[target_feature(enable = "avx2,avx512f,avx512vl")]` is that the
        // CPU has those; an `Avx512` exists only where `Avx512::detect`
        // found them.
        unsafe { avx512::aabb(ray, batch, t_max) }
    }

    #[inline(always)]
    fn ray_triangle_batch<V: Vector, const N: usize>(
        self,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N> {
        avx512::triangle(Avx2(()), ray, batch, t_max)
    }

    #[inline(always)]
    fn ray_quantized_children<V: Vector<Scalar = f32>>(
        self,
        ray: &PreparedRay<V>,
        node: &QuantizedChildren<'_, V>,
        t_max: f32,
    ) -> AabbBatchHits<f32, 8> {
        // SAFETY: as above.
        unsafe { avx512::quantized(ray, node, t_max) }
    }
}

/// Runs `work` compiled for the widest SIMD instruction set the CPU has,
/// and gives it that instruction set to call the batch kernels with: the
/// choice is made once, here, instead of on every batch.
///
/// [`ray_aabb_batch`] and [`ray_triangle_batch`] pick their SIMD copy at
/// run time on each call (on x86-64 with `std`, AVX2 where the CPU has it
/// and the build does not already assume it): a check and a function call
/// per batch, a large part of the cost of testing 8 boxes. Inside
/// `with_simd`, on a CPU with AVX-512 the work is compiled with it enabled
/// ([`Avx512`]: the box kernels inlined, the triangle batch as its AVX2
/// copy), on one with AVX2 with AVX2 enabled ([`Avx2`], every kernel
/// inlined); elsewhere it runs as compiled for the build's target
/// ([`TargetSimd`]). The answers are the same bits either way.
///
/// ```
/// use rayhit::{Aabb, AabbBatch, PreparedRay, Ray, Simd, SimdWork, with_simd, glam::Vec3};
///
/// /// Counts, for every ray, the boxes of one node it hits.
/// struct CountHits<'a> {
///     rays: &'a [PreparedRay],
///     node: &'a AabbBatch<Vec3, 8>,
/// }
///
/// impl SimdWork for CountHits<'_> {
///     type Output = u32;
///     #[inline(always)]
///     fn run<I: Simd>(self, simd: I) -> u32 {
///         let mut hits = 0;
///         for ray in self.rays {
///             hits += simd.ray_aabb_batch(ray, self.node, f32::INFINITY).mask.count_ones();
///         }
///         hits
///     }
/// }
///
/// let boxes: Vec<Aabb> = (0..8)
///     .map(|i| Aabb::new(Vec3::new(i as f32, 0.0, 0.0), Vec3::new(i as f32 + 0.5, 1.0, 1.0)))
///     .collect();
/// let node = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// let rays: Vec<PreparedRay> = (0..100)
///     .map(|i| PreparedRay::new(&Ray::new(Vec3::new(-1.0, 0.5, i as f32 / 100.0), Vec3::X)))
///     .collect();
/// assert_eq!(with_simd(CountHits { rays: &rays, node: &node }), 800);
/// ```
#[inline]
pub fn with_simd<W: SimdWork>(work: W) -> W::Output {
    #[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
    if let Some(simd) = Avx512::detect() {
        #[allow(unsafe_code)]
        // SAFETY: the one precondition of calling a function compiled with
        // `#[target_feature(enable = "avx2,avx512f,avx512vl")]` is that the
        // CPU has those, which `Avx512::detect` has just checked.
        return unsafe { avx512::run(work, simd) };
    } else if let Some(simd) = Avx2::detect() {
        #[allow(unsafe_code)]
        // SAFETY: the one precondition of calling a function compiled with
        // `#[target_feature(enable = "avx2")]` is that the CPU has AVX2,
        // which `Avx2::detect` has just checked.
        return unsafe { avx2::run(work, simd) };
    }
    work.run(TargetSimd)
}

/// The kernels a SIMD copy compiles for its instruction set (`$features`,
/// the `#[target_feature]` list): [`with_simd`]'s entry point and the box
/// kernels, the same source as the target's own copy.
#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
macro_rules! simd_copy {
    ($token:ty, $features:literal) => {
        /// `work.run(simd)`, compiled for this instruction set (see
        /// [`with_simd`]).
        #[target_feature(enable = $features)]
        #[inline]
        pub(super) fn run<W: SimdWork>(work: W, simd: $token) -> W::Output {
            work.run(simd)
        }

        #[target_feature(enable = $features)]
        #[inline]
        pub(super) fn aabb<V: Vector, const N: usize>(
            ray: &PreparedRay<V>,
            batch: &AabbBatch<V, N>,
            t_max: S<V>,
        ) -> AabbBatchHits<S<V>, N> {
            aabb_batch_body::<<S<V> as Scalar>::Lanes8Avx2, V, N>(ray, batch, t_max)
        }

        #[target_feature(enable = $features)]
        #[inline]
        pub(super) fn quantized<V: Vector<Scalar = f32>>(
            ray: &PreparedRay<V>,
            node: &QuantizedChildren<'_, V>,
            t_max: f32,
        ) -> AabbBatchHits<f32, 8> {
            quantized_body::<<f32 as Scalar>::Lanes8Avx2, V>(ray, node, t_max)
        }
    };
}

/// The batch kernels compiled a second time with AVX2 enabled, for x86-64
/// builds whose target does not already have it (the default one has only
/// SSE2): the same source, so the same answers bit for bit (Rust never
/// contracts `a * b + c` into a fused multiply-add, and the crate's one
/// explicit fused operation is correctly rounded either way), with 8 `f32`
/// lanes per instruction instead of 4.
#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
mod avx2 {
    use super::*;

    simd_copy!(Avx2, "avx2");

    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) fn triangle<V: Vector, const N: usize>(
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N> {
        triangle_batch_body::<<S<V> as Scalar>::Lanes8Avx2, V, N>(ray, batch, t_max)
    }
}

/// The box kernels compiled a third time, with AVX-512 (F and VL) enabled:
/// the same eight lanes, twice the registers.
#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
mod avx512 {
    use super::*;

    simd_copy!(Avx512, "avx2,avx512f,avx512vl");

    /// The AVX2 triangle batch, kept out of line so that it is not
    /// inlined into (and recompiled for) the AVX-512 caller.
    #[inline(never)]
    pub(super) fn triangle<V: Vector, const N: usize>(
        simd: Avx2,
        ray: &PreparedRay<V>,
        batch: &TriangleBatch<V, N>,
        t_max: S<V>,
    ) -> TriangleBatchHits<S<V>, N> {
        simd.ray_triangle_batch(ray, batch, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Ray;
    use std::vec;

    /// The empty lane's box is invalid, and the slab arithmetic alone
    /// misses it for rays along and against every axis, with signed zero
    /// components, and for invalid rays (origin prepared at `+inf`).
    #[test]
    fn empty_lanes_are_missed_by_the_arithmetic_alone() {
        let empty = AabbBatch::<Vec3, 4>::empty();
        let lane = |l: usize| {
            let [lo, hi] = &empty.planes;
            let min = [lo[0][l], lo[1][l], lo[2][l]];
            let max = [hi[0][l], hi[1][l], hi[2][l]];
            (min, max)
        };
        let (min, max) = lane(0);
        assert!(!Aabb::new(Vec3::from(min), Vec3::from(max)).is_valid());
        let mut rays = vec![
            Ray::new(Vec3::splat(f32::NAN), Vec3::X),
            Ray::new(Vec3::ZERO, Vec3::ZERO),
            Ray::new(Vec3::splat(f32::MAX), Vec3::splat(f32::MIN_POSITIVE)),
        ];
        for d in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::ONE,
            Vec3::new(1e-38, -1e38, 3.0),
        ] {
            for s in [1.0, -1.0] {
                rays.push(Ray::new(Vec3::new(-1e30, 1e30, 5.0), d * s));
                rays.push(Ray::new(Vec3::ZERO, d * s));
            }
        }
        rays.push(Ray::new(Vec3::ZERO, Vec3::new(0.0, -0.0, 1.0)));
        rays.push(Ray::new(Vec3::ZERO, Vec3::new(-0.0, 0.0, -1.0)));
        for ray in rays {
            let p = PreparedRay::new(&ray);
            for t_max in [0.0, 1.0, f32::MAX, f32::INFINITY] {
                for l in 0..4 {
                    let (min, max) = lane(l);
                    let s = &p.slab;
                    let (o, r0, r1) = (
                        s.origin.to_array(),
                        s.inv_to_min.to_array(),
                        s.inv_to_max.to_array(),
                    );
                    let (hit, _, _) =
                        crate::aabb::definition::slab_core(o, r0, r1, min, max, t_max);
                    assert!(!hit, "{ray:?}");
                }
            }
        }
    }

    /// A grid coordinate in `[-4, 4]` in steps of `1/8`, so that shared
    /// edges, face planes, zero direction components and exactly zero edge
    /// functions are common.
    fn grid(state: &mut u64) -> f32 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        ((*state % 65) as f32 - 32.0) / 8.0
    }

    fn hit_bits(h: Option<TriangleHit<f32>>) -> Option<([u32; 3], bool)> {
        h.map(|h| {
            (
                [h.t.to_bits(), h.u.to_bits(), h.v.to_bits()],
                h.side == Side::Front,
            )
        })
    }

    /// Each compiled copy of the batch kernels (the target's own and, on a
    /// CPU with AVX2, the AVX2 copy that `ray_*_batch` then picks, and on
    /// one with AVX-512 the copy `with_simd` picks) gives
    /// the scalar kernels' answers bit for bit: the copy not picked here
    /// is tested too.
    #[test]
    fn every_copy_agrees_with_the_scalar_kernels() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for case in 0..20_000 {
            let mut v = || Vec3::new(grid(&mut state), grid(&mut state), grid(&mut state));
            let ray = Ray::new(v(), v());
            let boxes: [Aabb; 8] = core::array::from_fn(|_| {
                let (a, b) = (v(), v());
                Aabb::new(a.min(b), a.max(b))
            });
            let tris: [Triangle; 8] = core::array::from_fn(|_| Triangle::new(v(), v(), v()));
            let t_max = if case % 2 == 0 { f32::INFINITY } else { 2.0 };
            let p = PreparedRay::new(&ray);
            let bb = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
            let tb = TriangleBatch::<Vec3, 8>::from_slice(&tris).unwrap();
            let mut box_answers = vec![aabb_batch_body::<<f32 as Scalar>::Lanes8, _, 8>(
                &p, &bb, t_max,
            )];
            let mut tri_answers = vec![triangle_batch_body::<<f32 as Scalar>::Lanes8, _, 8>(
                &p, &tb, t_max,
            )];
            #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
            if std::is_x86_feature_detected!("avx2") {
                #[allow(unsafe_code)]
                // SAFETY: AVX2 was just detected.
                unsafe {
                    box_answers.push(avx2::aabb(&p, &bb, t_max));
                    tri_answers.push(avx2::triangle(&p, &tb, t_max));
                }
            }
            #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
            if let Some(simd) = Avx512::detect() {
                #[allow(unsafe_code)]
                // SAFETY: AVX2, AVX-512F and AVX-512VL were just detected.
                unsafe {
                    box_answers.push(avx512::aabb(&p, &bb, t_max));
                }
                tri_answers.push(simd.ray_triangle_batch(&p, &tb, t_max));
            }
            for l in 0..8 {
                let scalar = crate::ray_aabb_prepared(&p, &boxes[l], t_max).map(|(e, _)| e);
                for a in &box_answers {
                    assert_eq!(
                        a.get(l).map(f32::to_bits),
                        scalar.map(f32::to_bits),
                        "{ray:?} {:?}",
                        boxes[l]
                    );
                }
                let scalar = crate::ray_triangle(&ray, &tris[l], t_max);
                for a in &tri_answers {
                    assert_eq!(
                        hit_bits(a.get(l)),
                        hit_bits(scalar),
                        "{ray:?} {:?}",
                        tris[l]
                    );
                }
            }
        }
    }
}
