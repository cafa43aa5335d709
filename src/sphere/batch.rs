//! Spheres on a batch: [`SphereBatch`], up to 32 spheres
//! structure-of-arrays (a particle leaf), and its kernel, which tests one
//! ray against eight of them at a time, each lane bit for bit the answer of
//! [`Sphere`]'s `hit` over a `t_max` (the fast path's arithmetic, lane by
//! lane, in the same order; the rare lanes it leaves undecided go to the
//! scalar code itself).

use core::marker::PhantomData;

use glam::Vec3;

use super::{Sphere, SphereHit, ray_sphere};
use crate::num::round::bound_up;
use crate::num::{Lanes8, S, Scalar, Vector};
use crate::ray::PreparedRay;
use crate::simd::{Isa, Kernel, check_lanes, lanes_at, put};
use crate::triangle::Side;

/// Up to `N` spheres, structure-of-arrays: a BVH leaf of particles.
///
/// Spheres are stored as given (one with a NaN or infinite value is a lane
/// nothing hits); empty lanes hold NaN and are masked off. Its query is
/// [`IntersectLanes`](crate::IntersectLanes): every lane's hit at once,
/// each [`Sphere`]'s answer bit for bit.
///
/// ```
/// use rayhit::{IntersectLanes, Intersect, Ray, Sphere, glam::Vec3};
/// use rayhit::batch::SphereBatch;
/// // Four unit spheres along x, at x = 3, 6, 9, 12.
/// let balls: Vec<Sphere> = (1..=4).map(|k| Sphere::new(Vec3::new(3.0 * k as f32, 0.0, 0.0), 1.0)).collect();
/// let batch = SphereBatch::<Vec3, 8>::from_slice(&balls).unwrap();
/// let ray = Ray::new(Vec3::ZERO, Vec3::X);
/// let hits = batch.hit(&ray, 10.0);
/// assert_eq!(hits.mask, 0b0111);
/// assert_eq!(hits.get(2), balls[2].hit(&ray, 10.0));
/// assert_eq!(hits.nearest().map(|(lane, h)| (lane, h.t)), Some((0, 2.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct SphereBatch<V: Vector = Vec3, const N: usize = 8> {
    /// `c[axis][lane]`, the centres.
    c: [[S<V>; N]; 3],
    /// The radii's magnitudes.
    r: [S<V>; N],
    /// The lanes that hold a sphere.
    pub(super) used: u32,
}

impl<V: Vector, const N: usize> SphereBatch<V, N> {
    /// The number of lanes, `N`.
    pub const LANES: usize = N;

    /// A batch with every lane empty.
    #[inline]
    #[must_use]
    pub fn empty() -> Self {
        const { check_lanes::<N>() };
        let nan = S::<V>::NAN;
        Self {
            c: [[nan; N]; 3],
            r: [nan; N],
            used: 0,
        }
    }

    /// The batch of `spheres` in lanes `0..spheres.len()`, the rest empty,
    /// or `None` when there are more than `N` spheres.
    #[inline]
    #[must_use]
    pub fn from_slice(spheres: &[Sphere<V>]) -> Option<Self> {
        if spheres.len() > N {
            return None;
        }
        let mut batch = Self::empty();
        for (lane, s) in spheres.iter().enumerate() {
            batch.set(lane, s);
        }
        Some(batch)
    }

    /// Stores `sphere` in `lane`.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    pub fn set(&mut self, lane: usize, sphere: &Sphere<V>) {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        for k in 0..3 {
            self.c[k][lane] = sphere.center[k];
        }
        self.r[lane] = sphere.radius.abs();
        self.used |= 1 << lane;
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
        for axis in &mut self.c {
            axis[lane] = nan;
        }
        self.r[lane] = nan;
        self.used &= !(1 << lane);
    }

    /// The sphere in `lane` (its radius's magnitude), if it holds one.
    ///
    /// # Panics
    ///
    /// If `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<Sphere<V>> {
        assert!(lane < N, "lane {lane} out of range for a batch of {N}");
        (self.used & (1 << lane) != 0).then(|| self.lane(lane))
    }

    /// The lanes that hold a sphere, one bit each.
    #[inline]
    #[must_use]
    pub fn mask(&self) -> u32 {
        self.used
    }

    #[inline(always)]
    pub(super) fn lane(&self, lane: usize) -> Sphere<V> {
        Sphere::new(
            V::new(self.c[0][lane], self.c[1][lane], self.c[2][lane]),
            self.r[lane],
        )
    }
}

/// The answer of [`SphereBatch`]'s [`hit`](crate::IntersectLanes::hit):
/// which lanes are hit, where, and whether entering.
///
/// For a lane in `mask`, `t` and the side (bit set in `front` for
/// [`Side::Front`], entering the ball) are those [`Sphere`]'s `hit`
/// returns for that sphere; other lanes have `t = +inf` and no `front`
/// bit, so the smallest `t` is the nearest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereBatchHits<F = f32, const N: usize = 8> {
    /// Lane `i` is hit when bit `i` is set.
    pub mask: u32,
    /// Lanes entered ([`Side::Front`]); a subset of `mask`.
    pub front: u32,
    /// Per lane, the distance `t` (`+inf` for a lane not hit).
    pub t: [F; N],
}

/// No lane hit.
impl<F: Scalar, const N: usize> Default for SphereBatchHits<F, N> {
    #[inline]
    fn default() -> Self {
        Self::none()
    }
}

impl<F: Scalar, const N: usize> SphereBatchHits<F, N> {
    /// No lane hit: `t = +inf` everywhere.
    #[inline(always)]
    pub(crate) fn none() -> Self {
        Self {
            mask: 0,
            front: 0,
            t: [F::INFINITY; N],
        }
    }

    /// The hit in `lane` as the scalar test returns it; `None` for a lane
    /// not hit and for `lane >= N`.
    #[inline]
    #[must_use]
    pub fn get(&self, lane: usize) -> Option<SphereHit<F>> {
        (lane < N && self.mask & (1 << lane) != 0).then(|| SphereHit {
            t: self.t[lane],
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
    pub fn nearest(&self) -> Option<(usize, SphereHit<F>)> {
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

    /// Sets `lane` to `hit` (or to no hit).
    #[inline(always)]
    pub(super) fn set(&mut self, lane: usize, hit: Option<SphereHit<F>>) {
        let bit = 1 << lane;
        self.mask &= !bit;
        self.front &= !bit;
        self.t[lane] = F::INFINITY;
        if let Some(h) = hit {
            self.mask |= bit;
            if h.side == Side::Front {
                self.front |= bit;
            }
            self.t[lane] = h.t;
        }
    }
}

/// [`SphereBatch`]'s `hit` over a `t_max` as a kernel, for any
/// instruction set (see `crate::simd`).
pub(crate) struct SphereBatchKernel<V, const N: usize>(PhantomData<V>);

impl<V: Vector, const N: usize> Kernel for SphereBatchKernel<V, N> {
    type Ray = PreparedRay<V>;
    type Shapes = SphereBatch<V, N>;
    type Limit = S<V>;
    type Output = SphereBatchHits<S<V>, N>;
    const AVX512: bool = false;

    #[inline(always)]
    fn run<I: Isa>(
        _: I,
        ray: &PreparedRay<V>,
        batch: &SphereBatch<V, N>,
        t_max: S<V>,
    ) -> Self::Output {
        sphere_batch_body::<I::W<S<V>>, V, N>(ray, batch, t_max)
    }
}

/// `|x|` on lanes, as the scalar `abs` (`-0.0` to `+0.0`; NaN lanes are
/// never used).
#[inline(always)]
fn abs<W: Lanes8>(x: W, zero: W) -> W {
    x.max(zero.sub(x))
}

/// The body of [`SphereBatch`]'s `hit` with the eight-lane type `W`: the
/// scalar fast path (`roots::fast`) on eight spheres at a time, every
/// operation the scalar one in the same order; lanes it leaves undecided
/// run the scalar test.
#[inline(always)]
fn sphere_batch_body<W: Lanes8<F = S<V>>, V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &SphereBatch<V, N>,
    t_max: S<V>,
) -> SphereBatchHits<S<V>, N> {
    const { check_lanes::<N>() };
    let mut out = SphereBatchHits::none();
    let (o, d) = (ray.origin(), ray.dir);
    let g = S::<V>::gamma_n;
    let splat = W::splat;
    let zero = splat(S::<V>::ZERO);
    let tiny = S::<V>::MIN_POSITIVE;
    // The ray's own quantities, as the scalar code computes them.
    let a = d.dot(d);
    let d1 = d.x().abs() + d.y().abs() + d.z().abs();
    let (dx, dy, dz) = (splat(d.x()), splat(d.y()), splat(d.z()));
    let (av, d1v) = (splat(a), splat(d1));
    let (mut hit, mut front, mut slow) = (0u32, 0u32, 0u32);
    let two = splat(S::<V>::TWO);
    // `bound_up(v, n)` is `v` times a constant.
    let up = |n: u32| splat(bound_up(S::<V>::ONE, n));
    let (up7, up2, up3) = (up(7), up(2), up(3));
    let top = splat(t_max);
    for c in 0..N.div_ceil(8) {
        let cx: W = lanes_at(&batch.c[0], c);
        let cy: W = lanes_at(&batch.c[1], c);
        let cz: W = lanes_at(&batch.c[2], c);
        let r: W = lanes_at(&batch.r, c);
        let (fx, fy, fz) = (
            splat(o.x()).sub(cx),
            splat(o.y()).sub(cy),
            splat(o.z()).sub(cz),
        );
        let ff = fx.mul(fx).add(fy.mul(fy)).add(fz.mul(fz));
        let rr = r.mul(r);
        // `cross(f, d)` as glam computes it.
        let crx = fy.mul(dz).sub(dy.mul(fz));
        let cry = fz.mul(dx).sub(dz.mul(fx));
        let crz = fx.mul(dy).sub(dx.mul(fy));
        let cc = crx.mul(crx).add(cry.mul(cry)).add(crz.mul(crz));
        let ar = av.mul(rr);
        let x = ar.sub(cc);
        let nd = zero.sub(fx.mul(dx).add(fy.mul(dy)).add(fz.mul(dz)));
        let k = ff.sub(rr);
        // `usable`: the sum finite (its difference with itself is zero);
        // `a` is the ray's, checked below.
        let sum = x.add(ff).add(av);
        let usable = sum.sub(sum).eq(zero);
        let (ax, ay, az) = (abs(fx, zero), abs(fy, zero), abs(fz, zero));
        let m = ax.max(ay).max(az).mul(d1v);
        let e = splat(g(3)).mul(m).add(splat(S::<V>::TWO * tiny));
        let c1 = abs(crx, zero).add(abs(cry, zero)).add(abs(crz, zero));
        let err_x = splat(g(5))
            .mul(ar)
            .add(splat(g(4)).mul(cc))
            .add(e.mul(two.mul(c1).add(splat(S::<V>::from_u32(3)).mul(e))))
            .add(splat(S::<V>::UNIT_ROUNDOFF).mul(abs(x, zero)))
            .add(av.add(splat(S::<V>::from_u32(8))).mul(splat(tiny)))
            .mul(up7);
        let miss = W::and(x.lt(zero), x.lt(zero.sub(err_x)));
        let err_nd = splat(g(4)).mul(m).add(splat(tiny)).mul(up2);
        let err_k = splat(g(8))
            .mul(ff.add(rr))
            .add(splat(S::<V>::TWO * tiny))
            .mul(up3);
        let root = W::select(zero.lt(x), x, zero).sqrt();
        let toward = err_nd.lt(nd);
        let away = nd.lt(zero.sub(err_nd));
        let q = W::select(zero.le(nd), nd.add(root), nd.sub(root));
        let outside = err_k.lt(k);
        let inside = k.lt(zero.sub(err_k));
        let (t_kq, t_qa) = (k.div(q), q.div(av));
        // Toward: the entry from outside, else the exit; away: the exit
        // from inside.
        let entering = W::and(toward, outside);
        let t = W::select(W::and_not(toward, outside), t_qa, t_kq);
        let candidate = W::or(toward, W::and(away, inside));
        let in_range = W::and(zero.lt(t), t.le(top));
        let hit_c = W::and_not(W::and(W::and(candidate, in_range), usable), miss);
        // Not usable, or neither toward nor away (and not a miss): the
        // scalar code's exact path.
        let all = zero.eq(zero);
        let neither = W::and_not(W::and_not(W::and_not(usable, miss), toward), away);
        let undecided = W::or(W::and_not(all, usable), neither);
        let shift = 8 * c;
        hit |= W::bits(hit_c) << shift;
        front |= W::bits(W::and(hit_c, entering)) << shift;
        slow |= W::bits(undecided) << shift;
        put(&mut out.t, c, W::select(hit_c, t, splat(S::<V>::INFINITY)));
    }
    let used = batch.used;
    let floor = S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF;
    if !(a >= floor) {
        slow = used;
    }
    out.mask = hit & used & !slow;
    out.front = front & out.mask;
    let slow = slow & used;
    if slow != 0 {
        out = slow_lanes(ray, batch, t_max, slow, out);
    }
    out
}

/// The lanes in `slow` from the scalar test. Out of line (they are rare),
/// so that the vector code keeps its registers.
#[cold]
#[inline(never)]
fn slow_lanes<V: Vector, const N: usize>(
    ray: &PreparedRay<V>,
    batch: &SphereBatch<V, N>,
    t_max: S<V>,
    mut slow: u32,
    mut out: SphereBatchHits<S<V>, N>,
) -> SphereBatchHits<S<V>, N> {
    let ray = ray.ray();
    while slow != 0 {
        let l = slow.trailing_zeros() as usize;
        slow &= slow - 1;
        out.set(l, ray_sphere(&ray, &batch.lane(l), t_max));
    }
    out
}
