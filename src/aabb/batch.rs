//! The slab test on a batch: [`AabbBatch`], up to 32 boxes
//! structure-of-arrays, and [`AabbBatch`'s `clip`](crate::batch::AabbBatch#method.clip), which tests one prepared ray
//! against eight of them at a time, each lane bit for bit the answer of
//! [`Aabb`'s `clip`](crate::Aabb#method.clip) on its box (the
//! definition's operations, lane by lane).

use core::marker::PhantomData;

use glam::Vec3;

use super::Aabb;
use super::definition::{exit_slack, exit_widening};
use crate::num::{Lanes, Lanes8, S, Scalar, Vector};
use crate::ray::PreparedRay;
use crate::simd::{Isa, Kernel, check_lanes, lanes_at, put};

/// One axis of the slab test's NaN-safe fold (see
/// [`Aabb`'s `clip`](crate::Aabb#method.clip)): the entry and exit
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
    /// `t_min` (zero but for the interval forms) and `t_max` in every
    /// lane.
    lo: W,
    hi: W,
    simple: bool,
}

impl<W: Lanes8> Slab8<W>
where
    W::F: Scalar,
{
    #[inline(always)]
    pub(crate) fn new<V: Vector<Scalar = W::F>>(
        ray: &PreparedRay<V>,
        (t_min, t_max): (W::F, W::F),
    ) -> Self {
        let [ox, oy, oz] = ray.slab.origin.to_array();
        let [ax, ay, az] = ray.slab.inv_to_min.to_array();
        let [bx, by, bz] = ray.slab.inv_to_max.to_array();
        Self {
            origin: [W::splat(ox), W::splat(oy), W::splat(oz)],
            inv_to_min: [W::splat(ax), W::splat(ay), W::splat(az)],
            inv_to_max: [W::splat(bx), W::splat(by), W::splat(bz)],
            lo: W::splat(t_min),
            hi: W::splat(t_max),
            simple: ray.simple,
        }
    }

    /// The slab test of eight valid boxes (for `0 <= t_min <= t_max`,
    /// `t_min` not `-0`): the lanes hit, and the entry `t` of each (`+inf`
    /// where not hit), bit for bit what
    /// [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip) gives for each
    /// (and so [`Aabb`'s `clip`](crate::Aabb#method.clip) for `t_min =
    /// 0`).
    ///
    /// For rays whose reciprocals are all normal (every component
    /// nonzero), the per-axis folds simplify. Every reciprocal is then
    /// normal (the two per axis are equal) and every box valid, so no
    /// distance is NaN, and the definition's folds reduce to the textbook
    /// order of each pair: the entry through an axis,
    /// `min(max(t0, 0), max(t1, 0))`, is `max(min(t0, t1), 0)`, and the exit,
    /// `max(min(t0, t_max), min(t1, t_max))`, is `min(max(t0, t1), t_max)`
    /// (max and min commute with the clamps for values that are not NaN).
    /// The largest entry is taken before the clamp at `t_min` rather than
    /// after: the same value, and `+0`, never `-0`, when it is 0 (`t_min`
    /// is never `-0`); a `-0`/`+0` tie
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
/// use rayhit::{Aabb, Bounds, PreparedRay, Ray, glam::Vec3};
/// use rayhit::batch::AabbBatch;
/// let boxes: Vec<Aabb> = (0..8)
///     .map(|i| {
///         let x = 2.0 * i as f32;
///         Aabb::new(Vec3::new(x, -1.0, -1.0), Vec3::new(x + 1.0, 1.0, 1.0))
///     })
///     .collect();
/// let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// // Along +x from x = 5.5: boxes 3 (x in [6, 7]) to 7 are ahead.
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(5.5, 0.0, 0.0), Vec3::X));
/// let hits = batch.clip(&ray, f32::INFINITY);
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

/// The answer of [`AabbBatch`]'s [`clip`](crate::Bounds::clip): which lanes are hit, and where the ray
/// enters each box hit.
///
/// For a lane in `mask`, `enter[lane]` is the entry `t` that
/// [`Aabb`'s `clip`](crate::Aabb#method.clip) returns for that box;
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
    /// No lane hit.
    #[inline(always)]
    pub(crate) fn none() -> Self {
        Self {
            mask: 0,
            enter: [F::INFINITY; N],
        }
    }

    /// The entry `t` of a lane that is hit, as the scalar test returns it;
    /// `None` otherwise, and for `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<F> {
        (lane < N && self.mask & (1 << lane) != 0).then(|| self.enter[lane])
    }
}

/// [`AabbBatch`'s `clip`](crate::batch::AabbBatch#method.clip) as a kernel, for any instruction set (see
/// `crate::simd`).
pub(crate) struct AabbBatchKernel<V, const N: usize>(PhantomData<V>);

impl<V: Vector, const N: usize> Kernel for AabbBatchKernel<V, N> {
    type Ray = PreparedRay<V>;
    type Shapes = AabbBatch<V, N>;
    /// `(t_min, t_max)`: see [`Slab8::new`]; a NaN or negative `t_max`
    /// is answered at the call (`batch_query`).
    type Limit = (S<V>, S<V>);
    type Output = AabbBatchHits<S<V>, N>;

    #[inline(always)]
    fn run<I: Isa>(
        _: I,
        ray: &PreparedRay<V>,
        batch: &AabbBatch<V, N>,
        ends: (S<V>, S<V>),
    ) -> Self::Output {
        aabb_batch_body::<I::W<S<V>>, V, N>(ray, batch, ends)
    }
}

/// A box-batch kernel's mask alone, for [`Bounds::meets`](crate::Bounds::meets):
/// `K` inlined whole, so that the entries it would compute, select and
/// store are dropped, and the answer comes back in a register.
pub(crate) struct MaskOf<K>(PhantomData<K>);

impl<F, const N: usize, K: Kernel<Output = AabbBatchHits<F, N>>> Kernel for MaskOf<K> {
    type Ray = K::Ray;
    type Shapes = K::Shapes;
    type Limit = K::Limit;
    type Output = u32;
    const AVX512: bool = K::AVX512;

    #[inline(always)]
    fn run<I: Isa>(isa: I, ray: &K::Ray, shapes: &K::Shapes, ends: K::Limit) -> u32 {
        K::run(isa, ray, shapes, ends).mask
    }
}

/// A batch kernel over `(t_min, t_max)` run with `t_min` the constant
/// zero, for a plain `t_max` (one broadcast fewer per call).
pub(crate) struct FromZero<K>(PhantomData<K>);

impl<F: Scalar, K: Kernel<Limit = (F, F)>> Kernel for FromZero<K> {
    type Ray = K::Ray;
    type Shapes = K::Shapes;
    type Limit = (F, F);
    type Output = K::Output;
    const AVX512: bool = K::AVX512;

    #[inline(always)]
    fn run<I: Isa>(isa: I, ray: &K::Ray, shapes: &K::Shapes, (_, t_max): (F, F)) -> K::Output {
        K::run(isa, ray, shapes, (F::ZERO, t_max))
    }
}

/// The body of [`AabbBatch`'s `clip`](crate::batch::AabbBatch#method.clip) with the eight-lane type `W`, eight lanes
/// at a time.
#[inline(always)]
fn aabb_batch_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &AabbBatch<V, N>,
    ends: (S<V>, S<V>),
) -> AabbBatchHits<S<V>, N> {
    const { check_lanes::<N>() };
    let inf = S::<V>::INFINITY;
    let mut enter = [inf; N];
    let slab = Slab8::<W>::new(ray, ends);
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

#[cfg(test)]
mod tests {
    use super::super::definition::slab_definition;
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
                    let (hit, _, _) = slab_definition(o, r0, r1, min, max, t_max);
                    assert!(!hit, "{ray:?}");
                }
            }
        }
    }
}
