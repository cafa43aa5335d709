//! Axis-aligned boxes: the conservative slab test, its prepared form, and the
//! naive face-by-face reference.

use glam::Vec3;

use crate::lanes::{Axis, Lanes};
use crate::ray::{Ray, t_max_ok};
use crate::real::{L, S, Scalar, Vector, at_most, max2, min2, scale_to_one};
use crate::triangle::Shear;

/// The closed box `min <= p <= max` (component-wise).
///
/// A box is valid when every coordinate is finite and `min <= max` on every
/// axis; a box of zero thickness on some axes (a rectangle, a segment, a
/// point) is valid. An invalid box (inverted on any axis, NaN or infinite)
/// is hit by nothing.
///
/// ```
/// use rayhit::{Aabb, glam::Vec3};
/// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// assert!(b.is_valid());
/// assert!(!Aabb::new(Vec3::ONE, Vec3::ZERO).is_valid());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Aabb<V = Vec3> {
    /// The corner with the smallest coordinates.
    pub min: V,
    /// The corner with the largest coordinates.
    pub max: V,
}

impl<V: Vector> Aabb<V> {
    /// The box from `min` to `max`. Nothing is checked; see [`Aabb::is_valid`].
    #[inline]
    #[must_use]
    pub const fn new(min: V, max: V) -> Self {
        Self { min, max }
    }

    /// True when all coordinates are finite and `min <= max` on every axis.
    #[inline]
    #[must_use]
    pub fn is_valid(&self) -> bool {
        valid_box(self.min, self.max)
    }
}

/// A box known to be valid ([`Aabb::is_valid`]): checked once, when it is
/// made, so that the slab tests ([`ray_aabb_prepared`], [`ray_aabb`]) need
/// not check it on every call. Store a BVH's node boxes this way.
///
/// Its corners can be read, not changed, so the check holds for as long
/// as the value lives. The tests give the same answers, bit for bit, as for
/// the [`Aabb`] it holds.
///
/// ```
/// use rayhit::{Aabb, PreparedRay, Ray, ValidAabb, ray_aabb_prepared, glam::Vec3};
/// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let node = ValidAabb::new(b).unwrap();
/// assert!(ValidAabb::new(Aabb::new(Vec3::ONE, Vec3::ZERO)).is_none());
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X));
/// let (enter, exit) = ray_aabb_prepared(&ray, &node, f32::INFINITY).unwrap();
/// // The exit is widened by its rounding bound (see `ray_aabb`).
/// assert!(enter == 1.0 && exit >= 2.0 && exit < 2.0001);
/// assert_eq!(ray_aabb_prepared(&ray, &b, f32::INFINITY), Some((enter, exit)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct ValidAabb<V = Vec3>(Aabb<V>);

impl<V: Vector> ValidAabb<V> {
    /// `aabb`, if it is valid ([`Aabb::is_valid`]); `None` otherwise.
    #[inline]
    #[must_use]
    pub fn new(aabb: Aabb<V>) -> Option<Self> {
        aabb.is_valid().then_some(Self(aabb))
    }

    /// The box.
    #[inline]
    #[must_use]
    pub const fn aabb(&self) -> &Aabb<V> {
        &self.0
    }
}

impl<V> From<ValidAabb<V>> for Aabb<V> {
    #[inline]
    fn from(b: ValidAabb<V>) -> Self {
        b.0
    }
}

mod sealed {
    pub trait Sealed {}
}

/// The boxes the slab tests take: an [`Aabb`], whose validity they check on
/// every call (an invalid box is hit by nothing), or a [`ValidAabb`],
/// checked once when it was made. Sealed.
pub trait SlabBox<V: Vector>: sealed::Sealed {
    /// Whether the tests must check the box's validity.
    #[doc(hidden)]
    const CHECK: bool;
    /// The box.
    fn corners(&self) -> &Aabb<V>;
}

impl<V> sealed::Sealed for Aabb<V> {}
impl<V> sealed::Sealed for ValidAabb<V> {}

impl<V: Vector> SlabBox<V> for Aabb<V> {
    const CHECK: bool = true;
    #[inline(always)]
    fn corners(&self) -> &Aabb<V> {
        self
    }
}

impl<V: Vector> SlabBox<V> for ValidAabb<V> {
    const CHECK: bool = false;
    #[inline(always)]
    fn corners(&self) -> &Aabb<V> {
        &self.0
    }
}

/// `-MAX <= min[k] <= max[k] <= MAX` on every axis: finite and not
/// inverted (a NaN fails), as three packed comparisons.
#[inline(always)]
pub(crate) fn valid_box<V: Vector>(min: V, max: V) -> bool {
    let big = V::splat(S::<V>::MAX);
    (-big).all_le(min) & min.all_le(max) & max.all_le(big)
}

/// A ray prepared for many box tests: its origin and, per axis, the
/// reciprocal of its direction rounded down and rounded up in magnitude.
///
/// Prepare once per ray, then call [`ray_aabb_prepared`] for each box (the
/// inner loop of BVH traversal). An invalid ray (see [`Ray::is_valid`])
/// prepares into one that misses every box.
///
/// ```
/// use rayhit::{Aabb, PreparedRay, Ray, ray_aabb_prepared, glam::Vec3};
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::X));
/// let near = Aabb::new(Vec3::new(1.0, -1.0, -1.0), Vec3::new(2.0, 1.0, 1.0));
/// let far = Aabb::new(Vec3::new(5.0, -1.0, -1.0), Vec3::new(6.0, 1.0, 1.0));
/// let (enter, _) = ray_aabb_prepared(&ray, &near, f32::INFINITY).unwrap();
/// assert_eq!(enter, 1.0);
/// assert!(ray_aabb_prepared(&ray, &far, 4.0).is_none());
/// ```
///
/// The prepared ray also carries the per-ray part of the watertight
/// triangle test (the axis permutation and shear of Woop et al.), so that
/// [`ray_triangle_prepared`](crate::ray_triangle_prepared) and
/// [`ray_triangle_batch`](crate::ray_triangle_batch) need not recompute it
/// per triangle.
#[derive(Clone, Copy, Debug)]
pub struct PreparedRay<V: Vector = Vec3> {
    /// The slab test's part: origin (`+inf` for an invalid ray) and the
    /// directed reciprocals. The triangle tests use the origin too (only
    /// for a valid ray, where it is the ray's).
    pub(crate) slab: SlabRay<V>,
    /// True when every reciprocal is a normal float (so the two of `slab`
    /// are equal, and no distance is NaN for a valid box): the batch
    /// kernels then take each axis' near and far plane from the sign of
    /// the direction instead of ordering each pair (see `batch`).
    pub(crate) simple: bool,
    /// The triangle tests' shear factors `sx`, `sy`, `sz` (see `Shear`),
    /// each in every lane.
    pub(crate) shear_lanes: [L<V>; 3],
    /// The origin's coordinates in the shear's axis order, each in every
    /// lane (see `Shear::origin_lanes`); NaN for an invalid ray.
    pub(crate) origin_lanes: [L<V>; 3],
    /// The shear's axis order, `kx`, `ky`, `kz`.
    pub(crate) axes: [Axis; 3],
    /// The ray's direction (zero for an invalid ray), for the entry face
    /// and the shear's `d_z`.
    pub(crate) dir: V,
}
// (The shear is stored only as the hot paths read it, and `Shear` rebuilt
// from it where the rest is needed: where each test has its own ray, the
// prepared ray is read once per test, and a smaller one costs less memory
// traffic. 160 bytes for `Vec3`; storing `Shear` whole, with its scalars
// and padding, took 208, and cost `ray_triangle_prepared` about 8% on the
// camera rows of `benches/peers`, where each test reads a ray of its own.)

impl<V: Vector> PartialEq for PreparedRay<V> {
    fn eq(&self, o: &Self) -> bool {
        // The rest is a function of these two.
        self.slab == o.slab && self.shear() == o.shear()
    }
}

/// The slab test's per-ray data, in lanes: see [`PreparedRay::new`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlabRay<V: Vector> {
    pub(crate) origin: L<V>,
    /// Per axis, the reciprocal used for the distance to the `min` plane.
    pub(crate) inv_to_min: L<V>,
    /// Per axis, the reciprocal used for the distance to the `max` plane.
    pub(crate) inv_to_max: L<V>,
}

impl<V: Vector> PartialEq for SlabRay<V> {
    fn eq(&self, o: &Self) -> bool {
        self.origin.to_array() == o.origin.to_array()
            && self.inv_to_min.to_array() == o.inv_to_min.to_array()
            && self.inv_to_max.to_array() == o.inv_to_max.to_array()
    }
}

impl<V: Vector> PreparedRay<V> {
    /// Prepares `ray` for box tests.
    ///
    /// Per axis with direction `d`, `r = fl(1/d)`. Where `r` is a normal
    /// float it is within a relative `u` of `1/d`, which the exit widening
    /// absorbs, and both planes use it. Where it is not, `r` is subnormal
    /// (`|d|` near the top of the range) or has overflowed to infinity
    /// (`|d|` below `1/MAX`), and its relative error is unbounded; then the
    /// plane the ray enters the slab through gets `r` stepped one ulp towards
    /// zero and the plane it leaves through gets `r` stepped one ulp away
    /// from zero. A correctly rounded `r` is within half an ulp of `1/d`, so
    /// the two bracket the exact reciprocal (an overflowed `r` gives `MAX`
    /// and `inf`): the entry distance can only come out smaller and the exit
    /// distance larger than with the exact reciprocal. `d = +-0` gives
    /// `+-inf` on both sides; the slab test handles the `0 * inf = NaN` this
    /// produces.
    ///
    /// For triangles it stores the ray's origin and the shear that the
    /// watertight test computes from the direction, exactly as
    /// [`ray_triangle`](crate::ray_triangle) computes them per call.
    #[inline]
    #[must_use]
    pub fn new(ray: &Ray<V>) -> Self {
        // An invalid ray's shear is never used (the triangle tests find no
        // crossing for it, see below); that of `+z` stands in, so that
        // equal invalid rays prepare equal.
        let z = S::<V>::ZERO;
        let dir = if ray.is_valid() {
            ray.dir
        } else {
            V::new(z, z, S::<V>::ONE)
        };
        let shear = Shear::<S<V>>::new(&dir);
        // An invalid ray's origin lanes are NaN: the prepared triangle test
        // then finds no crossing without a test of its own (see
        // `watertight_lanes`).
        let nan = S::<V>::NAN;
        let origin = if ray.is_valid() {
            ray.origin
        } else {
            V::new(nan, nan, nan)
        };
        let (slab, simple) = SlabRay::new(ray);
        Self {
            slab,
            simple,
            shear_lanes: shear.lanes(),
            origin_lanes: shear.origin_lanes(origin),
            axes: [shear.kx, shear.ky, shear.kz],
            dir: if ray.is_valid() { ray.dir } else { V::ZERO },
        }
    }

    /// The triangle tests' shear, as [`PreparedRay::new`] computed it (its
    /// `d_z` is zero for an invalid ray, whose shear no test uses).
    #[inline(always)]
    pub(crate) fn shear(&self) -> Shear<S<V>> {
        let [kx, ky, kz] = self.axes;
        let [sx, sy, sz] = self.shear_lanes.map(|l| l.x());
        Shear {
            kx,
            ky,
            kz,
            sx,
            sy,
            sz,
            dz: self.dir.get(kz),
        }
    }

    /// `Ray::is_valid` of the ray this was prepared from: a valid ray's
    /// origin is finite, and an invalid one's is prepared at `+inf`.
    #[inline(always)]
    pub(crate) fn is_valid(&self) -> bool {
        self.slab.origin.x() < S::<V>::INFINITY
    }

    /// The ray's origin; `+inf` in every component for an invalid ray.
    #[inline]
    #[must_use]
    pub fn origin(&self) -> V {
        let [x, y, z] = self.slab.origin.to_array();
        V::new(x, y, z)
    }
}

impl<V: Vector> SlabRay<V> {
    /// See [`PreparedRay::new`]; and whether every reciprocal is a normal
    /// float (`PreparedRay::simple`).
    #[inline(always)]
    pub(crate) fn new(ray: &Ray<V>) -> (Self, bool) {
        let lanes = |v: V| L::<V>::new(v.x(), v.y(), v.z());
        let (one, zero) = (L::<V>::splat(S::<V>::ONE), L::<V>::splat(S::<V>::ZERO));
        let (origin, dir) = (lanes(ray.origin), lanes(ray.dir));
        // `Ray::is_valid`, on the lanes: finite, and the direction not zero.
        let big = L::<V>::splat(S::<V>::MAX);
        let finite = origin.abs().le(big) & dir.abs().le(big) == 0b111;
        if !(finite && dir.eq(zero) != 0b111) {
            // An origin at +inf puts every box at t = -inf: a miss for every
            // valid box, with no flag to test in the hot loop.
            let slab = Self {
                origin: L::<V>::splat(S::<V>::INFINITY),
                inv_to_min: one,
                inv_to_max: one,
            };
            return (slab, false);
        }
        let r = one.div(dir);
        // Where every reciprocal is a normal float (or an exact infinity,
        // from d = +-0), both planes use it.
        let a = r.abs();
        let normal =
            L::<V>::splat(S::<V>::MIN_POSITIVE).le(a) & a.lt(L::<V>::splat(S::<V>::INFINITY));
        if normal | dir.eq(zero) == 0b111 {
            let slab = Self {
                origin,
                inv_to_min: r,
                inv_to_max: r,
            };
            return (slab, normal == 0b111);
        }
        (Self::stepped(origin, ray.dir), false)
    }

    /// The rare case of [`SlabRay::new`]: some reciprocal is subnormal or
    /// has overflowed.
    ///
    /// A subnormal reciprocal `r = fl(1/d)` is within half a subnormal
    /// `tiny` of `1/d`, so each step is within `1.5 tiny`, that is within
    /// `1.5 tiny |d| <= 1.5 tiny MAX < 12u` relative (`u` the unit
    /// roundoff: `2^-21 1.5 = 12 2^-24` in `f32`, `2^-50 1.5 = 12 2^-53` in
    /// `f64`). An entry distance through that slab is then at least `E (1 -
    /// u)^2 (1 - 12u)` and an exit at most `X (1 + u)^2 (1 + 12u)`, so the
    /// `exit_slack` argument gives a false-hit factor of `(1 + u)^3 (1 +
    /// 12u) W / ((1 - u)^2 (1 - 12u))`, about `1 + 37u`: the documented
    /// `1 + 40u`. The reported entry stays within `(1 - u)^2 (1 - 12u)`, so
    /// within `15u`.
    #[cold]
    #[inline(never)]
    fn stepped(origin: L<V>, dir: V) -> Self {
        // Stepping: for d > 0 the min plane is the entry (wants the smaller
        // magnitude, r stepped down) and the max plane the exit (r stepped
        // up). For d < 0, r is negative and the roles swap, and stepping
        // down again gives the min plane (now the exit) the larger magnitude.
        // So in both cases the min plane gets `r.next_down()` and the max
        // plane `r.next_up()`.
        let axis = |d: S<V>| {
            let r = S::<V>::ONE / d;
            let normal = r.abs() >= S::<V>::MIN_POSITIVE && r.abs() < S::<V>::INFINITY;
            if normal || d == S::<V>::ZERO {
                (r, r)
            } else {
                (r.next_down(), r.next_up())
            }
        };
        let (x0, x1) = axis(dir.x());
        let (y0, y1) = axis(dir.y());
        let (z0, z1) = axis(dir.z());
        Self {
            origin,
            inv_to_min: L::<V>::new(x0, y0, z0),
            inv_to_max: L::<V>::new(x1, y1, z1),
        }
    }
}

/// The widening factor `W = 1 + 2*gamma(4)` for the exit distance, rounded
/// up.
///
/// Derivation. For one axis, the computed entry distance is
/// `fl(fl(min - o) * inv)` with `inv` the rounded reciprocal (or, outside the
/// normal range, one no larger in magnitude than `1/d`): at most three
/// roundings, so for an exact entry `e >= 0` it is at most `e (1 + u)^3`
/// (plus at most half a subnormal if the product underflows). The exit is
/// likewise at least `x (1 - u)^3`. `0` and `t_max` are exact, and min and
/// max are exact. If exactly `max(E, 0) <= L = min(X, t_max)` (the box is
/// hit), the computed entry is at most `L (1 + u)^3` and the computed limit
/// at least `L (1 - u)^3`; multiplying the limit by `W` and rounding once
/// more keeps `entry <= fl(limit * W)` whenever `W (1 - u)^4 >= (1 + u)^3`.
/// With `W = 1 + 8u/(1 - 4u)`, multiplying out,
/// `(1 + 4u)(1 - u)^4 - (1 + u)^3 (1 - 4u) = u - u^2 + 31u^3 - 11u^4 + 4u^5`,
/// which is positive. pbrt-v4 widens by `1 + 2*gamma(3)`, enough for its two
/// roundings per distance; Ize, "Robust BVH Ray Traversal", JCGT 2013, makes
/// the same argument in ulps. The value is stepped up one ulp to cover its
/// own rounding.
#[inline(always)]
pub(crate) fn exit_widening<F: Scalar>() -> F {
    (F::ONE + F::TWO * F::gamma_n(4)).next_up()
}

/// The absolute slack `2 * TINY` added to the widened exit. Where products
/// underflow, rounding errors are absolute (at most half a subnormal each)
/// rather than relative; three of them (entry, exit, widening) are covered by
/// two subnormals. For normal-range distances adding it changes nothing.
///
/// The false-hit band pays for it: exactly, `E (1 - u)^3 - TINY/2` is at
/// most the computed entry, which is at most the computed limit,
/// `(X (1 + u)^3 + TINY/2) W (1 + u) + TINY/2 + 2 TINY`. So
/// `E <= X (1 + u)^4 W / (1 - u)^3 + 3.5 TINY / (1 - u)^3`, that is
/// `E < X (1 + 16u) + 4 TINY`: the documented band has four subnormals, not
/// two (the fuzzer found a false hit 2.5 subnormals out, which the
/// regression tests keep).
#[inline(always)]
pub(crate) fn exit_slack<F: Scalar>() -> F {
    F::TWO * F::TINY
}

/// The slab test on a prepared ray: the part of `[0, t_max]` the ray spends
/// inside the closed box, or `None`.
///
/// Returns `Some((enter, exit))` with `0 <= enter <= exit <= t_max`, `enter`
/// finite. See [`ray_aabb`] for the guarantees; this is the same test with
/// the reciprocal computed once per ray.
#[inline]
#[must_use]
pub fn ray_aabb_prepared<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &impl SlabBox<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    slab_test(&ray.slab, aabb, t_max)
}

/// [`ray_aabb_prepared`] on the slab part of a prepared ray (which is all
/// that [`ray_aabb`] prepares).
///
/// All three axes at once, on lanes (see `crate::lanes`). The unit tests
/// hold it, bit for bit, to the same operations written one axis at a time
/// (`definition::slab_core`), which the box batches also match: the
/// per-axis folds are lane-wise; the largest entry and the smallest exit
/// are taken in every lane (values that are never NaN: the folds see to
/// that; the entries are never `-0`, and a `-0`/`+0` tie among the exits
/// widens to the same limit); and the final comparisons, with
/// `enter <= limit && enter <= MAX` as `enter <= min(limit, MAX)`, and the
/// box's validity, are one mask.
#[inline(always)]
fn slab_test<V: Vector, B: SlabBox<V>>(
    ray: &SlabRay<V>,
    aabb: &B,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    let aabb = aabb.corners();
    let splat = L::<V>::splat;
    let lanes = |v: V| L::<V>::new(v.x(), v.y(), v.z());
    // (Lane 3 is never read. Where a vector is its three components and
    // nothing more (`Vec3`, `DVec3`, not `Vec3A`), the maximum's `x` is
    // stored right after the minimum's `z`: filling lane 3 with it lets the
    // four lanes come from one load.)
    let packed = core::mem::size_of::<V>() == 3 * core::mem::size_of::<S<V>>();
    let (x, y, z) = (aabb.min.x(), aabb.min.y(), aabb.min.z());
    let min = L::<V>::new4(x, y, z, if packed { aabb.max.x() } else { z });
    let max = lanes(aabb.max);
    let big = S::<V>::MAX;
    let (zero, limit) = (splat(S::<V>::ZERO), splat(t_max));
    let t0 = min.sub(ray.origin).mul(ray.inv_to_min);
    let t1 = max.sub(ray.origin).mul(ray.inv_to_max);
    // Each axis folds its two plane distances into the interval [0, t_max]
    // the way Tavian Barnes does ("Fast, Branchless Ray/Bounding Box
    // Intersections, Part 3", 2022): `max(t, 0)` and `min(t, t_max)` give
    // the second operand for a NaN `t` (origin exactly on a slab plane of
    // an axis the ray does not move along), which leaves the interval
    // unchanged, as exact arithmetic says of a closed box.
    let enter = t0.max(zero).min(t1.max(zero));
    let exit = t0.min(limit).max(t1.min(limit));
    // Widen the exit by the rounding bound so that no box that exact
    // arithmetic hits is missed (see `exit_widening`). `enter` is infinite
    // only for an axis the ray never enters (its direction component is
    // zero, or so small that every distance overflows): a miss even when
    // the limit is infinite too, hence the `MAX`.
    let widened = exit.mul(splat(exit_widening())).add(splat(exit_slack()));
    // The box is hit when the last entry is at most every widened exit and
    // at most `MAX`. The last entry, in every lane, is ready before the
    // exits are widened, so the test waits on one comparison after the
    // widening. (Widening rounds monotonically, so widening each exit and
    // then taking the smallest is widening the smallest: the same bits as
    // the definition. Nothing here is NaN, unless `t_max` is, which fails
    // below.)
    let enter = enter.max_all();
    let miss = widened.lt(enter) | splat(big).lt(enter);
    // The box must be valid: `-MAX <= min <= max <= MAX` on every axis, a
    // NaN failing. (A `ValidAabb` was checked when it was made.)
    let invalid = if B::CHECK {
        splat(-big).nle(min) | min.nle(max) | max.nle(splat(big))
    } else {
        0
    };
    if (miss | invalid) != 0 || !t_max_ok(t_max) {
        return None;
    }
    let exit = at_most(widened.min_all().x(), t_max);
    Some((at_most(enter.x(), exit), exit))
}

/// The slab test: the part of `[0, t_max]` that `ray` spends inside the
/// closed box `aabb`, as `Some((enter, exit))`, or `None`.
///
/// Conventions: `t` in units of `ray.dir`; the box is a closed solid, so a
/// ray starting inside has `enter = 0`, and a ray through a face, edge or
/// corner, or lying in a face plane, hits. `0 <= enter <= exit <= t_max`
/// and `enter` is finite; `exit` is `+inf` only if `t_max` is.
///
/// Guarantees, for a valid ray and box and `t_max >= 0`:
/// - **No false miss.** If exact arithmetic on the same inputs says the
///   closed box meets the ray on `[0, t_max]`, this returns `Some`. This
///   covers axis-parallel rays, rays in a face plane, zero-thickness boxes,
///   `-0.0` direction components and components so small that their
///   reciprocal overflows. The reported `exit` is at least the exact exit
///   (clipped to `t_max`). Precondition: no difference `min - o`, `max - o`
///   overflows, and the exact entry and exit distances are below `MAX / 2`
///   (with a direction component below `1/MAX`, an entry far beyond the
///   range can otherwise come out as a hit at a huge finite `t`).
/// - **False hits only at the boundary.** A `Some` for a box exact
///   arithmetic misses means the exact entry exceeds the exact exit (or
///   `t_max`) by less than a factor `1 + 16u` plus four subnormals (`u` the
///   unit roundoff, so a few ulps): the ray passes within a few ulps of an
///   edge or corner; and the reported exit is at most that factor above the
///   exact one. Where a direction component is so large that its
///   reciprocal is subnormal (`|d_i| > 2^126` in `f32`, `2^1022` in `f64`),
///   the factor is `1 + 40u`: the reciprocal then carries up to `12u` of
///   relative error. Both hold when every nonzero direction component has
///   a finite reciprocal (`|d_i| >= 1/MAX`). A smaller component's reciprocal
///   overflows, its exit distance comes out infinite, and the reported exit
///   can be far too large, and its entry distance (computed with `MAX` for
///   the reciprocal) far too small; a false hit then passes the box at a
///   distance below `enter / (MAX (1 - u)^2)` along that axis (the computed
///   entry through that slab is at least `|b - o| MAX (1 - u)^2`, and a ray
///   already past the slab is at most `enter |d_i|` beyond it).
/// - `enter` is within three roundings of the exact entry when every
///   reciprocal is a normal float, within `15u` when one is subnormal, and
///   can be far below it when one overflows; it is not a lower bound. To cull against a closest hit so far, pass that as `t_max`,
///   which the test honours conservatively.
/// - Invalid input (NaN or infinite coordinates, zero direction, inverted
///   box, NaN or negative `t_max`) gives `None`. Never panics.
///
/// ```
/// use rayhit::{Aabb, Ray, ray_aabb, glam::Vec3};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0));
/// // x = -1 + 2t is in [0, 1] for t in [0.5, 1]; the exit is widened by a
/// // few ulps so that no hit is ever lost.
/// let (enter, exit) = ray_aabb(&ray, &unit, f32::INFINITY).unwrap();
/// assert_eq!(enter, 0.5);
/// assert!(exit >= 1.0 && exit <= 1.0 + 8.0 * f32::EPSILON);
/// // Lying in the face plane y = 1 of the closed box: a hit.
/// let in_face = Ray::new(Vec3::new(-1.0, 1.0, 0.5), Vec3::X);
/// assert!(ray_aabb(&in_face, &unit, f32::INFINITY).is_some());
/// ```
#[inline]
#[must_use]
pub fn ray_aabb<V: Vector>(
    ray: &Ray<V>,
    aabb: &impl SlabBox<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    slab_test(&SlabRay::new(ray).0, aabb, t_max)
}

/// A face of a box: one axis's `min` or `max` side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoxFace {
    /// The face `x = min.x`, outward normal `-x`.
    MinX,
    /// The face `x = max.x`, outward normal `+x`.
    MaxX,
    /// The face `y = min.y`, outward normal `-y`.
    MinY,
    /// The face `y = max.y`, outward normal `+y`.
    MaxY,
    /// The face `z = min.z`, outward normal `-z`.
    MinZ,
    /// The face `z = max.z`, outward normal `+z`.
    MaxZ,
}

impl BoxFace {
    /// The face on `axis` (0, 1, 2 for x, y, z; `None` above), on the `max`
    /// side or the `min` side.
    #[inline]
    #[must_use]
    pub const fn new(axis: usize, max_side: bool) -> Option<Self> {
        Some(match (axis, max_side) {
            (0, false) => BoxFace::MinX,
            (0, true) => BoxFace::MaxX,
            (1, false) => BoxFace::MinY,
            (1, true) => BoxFace::MaxY,
            (2, false) => BoxFace::MinZ,
            (2, true) => BoxFace::MaxZ,
            _ => return None,
        })
    }

    /// The face's axis: 0, 1 or 2 for x, y, z.
    #[inline]
    #[must_use]
    pub const fn axis(self) -> usize {
        self as usize / 2
    }

    /// True for the `max` side of the axis.
    #[inline]
    #[must_use]
    pub const fn is_max(self) -> bool {
        self as usize % 2 == 1
    }

    /// The outward unit normal: `+1` or `-1` on the face's axis, exactly.
    #[inline]
    #[must_use]
    pub fn normal<V: Vector>(self) -> V {
        let s = if self.is_max() {
            S::<V>::ONE
        } else {
            -S::<V>::ONE
        };
        let z = S::<V>::ZERO;
        match self.axis() {
            0 => V::new(s, z, z),
            1 => V::new(z, s, z),
            _ => V::new(z, z, s),
        }
    }

    /// The coordinate of the face's plane on its axis, for `aabb`.
    #[inline]
    #[must_use]
    pub fn plane<V: Vector>(self, aabb: &Aabb<V>) -> S<V> {
        let corner = if self.is_max() { aabb.max } else { aabb.min };
        corner[self.axis()]
    }
}

/// A box hit: the slab test's interval and the face the ray enters through.
///
/// `enter` and `exit` are exactly what [`ray_aabb`] (or
/// [`ray_aabb_prepared`]) returns. `face` is decided in exact arithmetic:
/// see [`ray_aabb_face`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxHit<F = f32> {
    /// Where the ray enters the box (0 when it starts inside).
    pub enter: F,
    /// Where it leaves the box, or `t_max`.
    pub exit: F,
    /// The face it enters through; `None` when it starts inside the box or
    /// on its boundary (the exact entry is at `t <= 0`).
    pub face: Option<BoxFace>,
}

/// The face through which the ray `origin + t dir` enters the box, decided
/// exactly: among the axes whose entry plane the ray crosses at a `t > 0`,
/// the one it crosses last (largest `t`), the lowest axis on a tie;
/// `None` when there is none.
fn entry_face<V: Vector>(origin: V, dir: V, aabb: &Aabb<V>) -> Option<BoxFace> {
    let zero = S::<V>::ZERO;
    // Per candidate axis: the axis and `(s, e, d, c)`, with the exact
    // distance to its entry plane `(s + e) / d`, `s + e = plane - o`
    // exactly, and `c = fl(s / d)`.
    type Distance<F> = (F, F, F, F);
    let mut best: Option<(usize, Distance<S<V>>)> = None;
    for k in 0..3 {
        let d = dir[k];
        if !(d != zero) {
            continue; // parallel to the slab: no entry plane
        }
        let plane = if d > zero { aabb.min[k] } else { aabb.max[k] };
        let (s, e) = S::<V>::two_diff(plane, origin[k]);
        // `fl(plane - o)` has the exact difference's sign (and is zero only
        // when it is): the plane is ahead exactly when `s` has `d`'s sign.
        if !(s != zero && (s > zero) == (d > zero)) {
            continue;
        }
        let c = s / d;
        let later = match best {
            None => true,
            Some((_, other)) => crosses_later((s, e, d, c), other),
        };
        if later {
            best = Some((k, (s, e, d, c)));
        }
    }
    best.and_then(|(k, (_, _, d, _))| BoxFace::new(k, d < zero))
}

/// Whether the exact distance `(s + e) / d` of the first plane is larger
/// than that of the second (both positive; `c` is `fl(s / d)`).
///
/// `c` carries two roundings of the exact distance (that of `s`, and the
/// division), so where both are normal floats `c` lies within a factor
/// `(1 + u)^2` of it, and `c1 > c2 (1 + 8u)` (or `<` with `1 - 8u`) settles
/// the comparison. Otherwise (within about four ulps, or an overflowed or
/// tiny quotient) the sign of `(s1 + e1) |d2| - (s2 + e2) |d1|` is computed
/// exactly from the four products, in `f64` (exact for `f32` inputs), with
/// the two numerators and the two directions each scaled by a common power
/// of two first, so that tiny or huge inputs do not underflow or overflow
/// the products. (For `f64` inputs whose two numerators, or two
/// directions, differ by a factor beyond `2^900`, a product can still
/// underflow: the crate's standing precondition of no intermediate
/// underflow.)
fn crosses_later<F: Scalar>(
    (s1, e1, d1, c1): (F, F, F, F),
    (s2, e2, d2, c2): (F, F, F, F),
) -> bool {
    let normal = |c: F| c >= F::MIN_POSITIVE && c <= F::MAX;
    if normal(c1) && normal(c2) {
        let margin = F::from_u32(8) * F::UNIT_ROUNDOFF;
        if c1 > c2 * (F::ONE + margin) {
            return true;
        }
        if c1 < c2 * (F::ONE - margin) {
            return false;
        }
    }
    let (s1, e1, d1, s2, e2, d2) = (
        s1.to_f64(),
        e1.to_f64(),
        d1.to_f64(),
        s2.to_f64(),
        e2.to_f64(),
        d2.to_f64(),
    );
    // |plane - o| = sign(s) (s + e): both distances are positive.
    let (g1, g2) = (s1.signum(), s2.signum());
    let ks = |x: f64| scale_to_one(x, s1.abs().max(s2.abs()));
    let kd = |x: f64| scale_to_one(x, d1.abs().max(d2.abs()));
    let terms = [
        (ks(g1 * s1), kd(d2.abs())),
        (ks(g1 * e1), kd(d2.abs())),
        (-ks(g2 * s2), kd(d1.abs())),
        (-ks(g2 * e2), kd(d1.abs())),
    ];
    f64::sum_of_products_sign(&terms) == core::cmp::Ordering::Greater
}

/// [`ray_aabb`] with the face the ray enters through.
///
/// Same interval as [`ray_aabb`], bit for bit, and the same `None`. The
/// face is decided in exact arithmetic on the same inputs: it is a face
/// whose plane the exact ray crosses at the exact entry distance. Where
/// several do (the ray enters through an edge or a corner), it is the one
/// on the lowest axis (x, then y, then z). Where the exact entry is at
/// `t <= 0` (the ray starts inside the box or on its boundary) there is no
/// entry face, and `face` is `None`. Where the conservative test reports a
/// box that the exact ray misses by a few ulps (see [`ray_aabb`]), the face
/// is still the entry plane the exact ray crosses last.
///
/// Cost: the entry face needs the axes' distances compared; where two are
/// within about four ulps of each other (near an edge or corner) the
/// comparison is redone exactly, from error-free products. Use [`ray_aabb`]
/// when only the interval is wanted.
///
/// Precondition of the exact face, for `f64` only (`f32` has none): on each
/// axis the origin coordinate and the box's are each zero or within a
/// factor `2^300` of each other, and the nonzero direction components are
/// within a factor `2^300` of each other (beyond that a product in the
/// exact comparison can underflow, and a tie can be decided wrongly).
///
/// ```
/// use rayhit::{Aabb, BoxFace, Ray, ray_aabb_face, glam::Vec3};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// // From the left, enters through x = 0.
/// let hit = ray_aabb_face(&Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X), &unit, f32::INFINITY).unwrap();
/// assert_eq!((hit.enter, hit.face), (1.0, Some(BoxFace::MinX)));
/// assert_eq!(BoxFace::MinX.normal::<Vec3>(), -Vec3::X);
/// // Through the edge x = 0, y = 1: both planes at t = 1; x is chosen.
/// let edge = Ray::new(Vec3::new(-1.0, 2.0, 0.5), Vec3::new(1.0, -1.0, 0.0));
/// assert_eq!(ray_aabb_face(&edge, &unit, f32::INFINITY).unwrap().face, Some(BoxFace::MinX));
/// // From inside: no entry face.
/// let inside = Ray::new(Vec3::splat(0.5), Vec3::Y);
/// assert_eq!(ray_aabb_face(&inside, &unit, f32::INFINITY).unwrap().face, None);
/// ```
#[must_use]
pub fn ray_aabb_face<V: Vector>(ray: &Ray<V>, aabb: &Aabb<V>, t_max: S<V>) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb(ray, aabb, t_max)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face(ray.origin, ray.dir, aabb),
    })
}

/// [`ray_aabb_prepared`] with the face the ray enters through: the same
/// interval, bit for bit, and the face as [`ray_aabb_face`] decides it.
///
/// ```
/// use rayhit::{Aabb, BoxFace, PreparedRay, Ray, ray_aabb_prepared_face, glam::Vec3};
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.5, 5.0, 0.5), -Vec3::Y));
/// let hit = ray_aabb_prepared_face(&ray, &Aabb::new(Vec3::ZERO, Vec3::ONE), 10.0).unwrap();
/// assert_eq!((hit.enter, hit.face), (4.0, Some(BoxFace::MaxY)));
/// ```
#[must_use]
pub fn ray_aabb_prepared_face<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &Aabb<V>,
    t_max: S<V>,
) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb_prepared(ray, aabb, t_max)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face(ray.origin(), ray.dir, aabb),
    })
}

/// The face a prepared ray enters `aabb` through, as [`ray_aabb_face`]
/// decides it, whether or not the ray hits the box (for a box batch's hit
/// lanes: [`AabbBatch::get`](crate::AabbBatch::get) gives the box).
/// `None` for an invalid ray or box, and where the ray starts inside.
///
/// ```
/// use rayhit::{Aabb, AabbBatch, BoxFace, PreparedRay, Ray, aabb_entry_face, ray_aabb_batch, glam::Vec3};
/// let boxes = [Aabb::new(Vec3::new(2.0, -1.0, -1.0), Vec3::new(3.0, 1.0, 1.0))];
/// let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::X));
/// let hits = ray_aabb_batch(&ray, &batch, f32::INFINITY);
/// assert_eq!(hits.mask, 1);
/// assert_eq!(aabb_entry_face(&ray, &batch.get(0).unwrap()), Some(BoxFace::MinX));
/// ```
#[must_use]
pub fn aabb_entry_face<V: Vector>(ray: &PreparedRay<V>, aabb: &Aabb<V>) -> Option<BoxFace> {
    if !(ray.is_valid() && aabb.is_valid()) {
        return None;
    }
    entry_face(ray.origin(), ray.dir, aabb)
}

/// The reference box test, face by face: each of the six faces is treated as
/// a plane, the crossing point is tested against the face's closed
/// rectangle, and the interval runs from the first face crossed to the last,
/// clipped to `[0, t_max]`.
///
/// Same signature, conventions and invalid-input behaviour as [`ray_aabb`].
/// It is slower, and it is *not* conservative: a point computed a rounding
/// outside a face rectangle is a miss, so near edges and corners it can
/// disagree with the slab test (which is). Away from edges the two agree on
/// hit or miss, and the distances agree within a few ulps: each face
/// distance is `fl(fl(b - o) / d)`, two roundings, and the crossing point
/// is tested in coordinates relative to the origin
/// (`min - o <= t * d <= max - o`), so each test is wrong only within a
/// relative `gamma(4)` of the face rectangle's edge, however far the origin
/// is from the coordinate origin.
///
/// ```
/// use rayhit::{Aabb, Ray, ray_aabb_naive, glam::Vec3};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 3.0), Vec3::new(0.0, 0.0, -1.0));
/// assert_eq!(ray_aabb_naive(&ray, &unit, f32::INFINITY), Some((2.0, 3.0)));
/// assert_eq!(ray_aabb_naive(&ray, &unit, 1.0), None);
/// ```
#[must_use]
pub fn ray_aabb_naive<V: Vector>(
    ray: &Ray<V>,
    aabb: &Aabb<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    if !(ray.is_valid() && aabb.is_valid() && t_max_ok(t_max)) {
        return None;
    }
    let mut first = S::<V>::INFINITY;
    let mut last = -S::<V>::INFINITY;
    for k in 0..3 {
        let d = ray.dir[k];
        if d == S::<V>::ZERO {
            continue;
        }
        let (j, l) = ((k + 1) % 3, (k + 2) % 3);
        for plane in [aabb.min[k], aabb.max[k]] {
            let t = (plane - ray.origin[k]) / d;
            let on_face = |m: usize| {
                let q = t * ray.dir[m];
                aabb.min[m] - ray.origin[m] <= q && q <= aabb.max[m] - ray.origin[m]
            };
            if t.is_finite() && on_face(j) && on_face(l) {
                first = min2(first, t);
                last = max2(last, t);
            }
        }
    }
    let enter = max2(first, S::<V>::ZERO);
    let exit = min2(last, t_max);
    (enter <= exit).then_some((enter, exit))
}

#[cfg(test)]
pub(crate) mod definition {
    //! The slab test written one axis at a time, with scalar comparisons:
    //! the definition the kernels on lanes are held to.
    use crate::real::{Scalar, at_most, max2, min2};

    use super::{exit_slack, exit_widening};

    /// `t` unless it is below `lo` or NaN, else `lo`.
    fn at_least<F: Scalar>(t: F, lo: F) -> F {
        if t > lo { t } else { lo }
    }

    /// The slab test's arithmetic for one box, one axis at a time, without
    /// the checks of the box's validity and of `t_max >= 0`: `(hit, enter,
    /// exit)`, where `enter` and `exit` are the answer when `hit` holds.
    /// [`ray_aabb_prepared`](crate::ray_aabb_prepared) and the box batches
    /// must give exactly these bits.
    pub(crate) fn slab_core<F: Scalar>(
        origin: [F; 3],
        inv_to_min: [F; 3],
        inv_to_max: [F; 3],
        min: [F; 3],
        max: [F; 3],
        t_max: F,
    ) -> (bool, F, F) {
        let zero = F::ZERO;
        // Each axis folds its two plane distances into the interval [0, t_max]
        // the way Tavian Barnes does ("Fast, Branchless Ray/Bounding Box
        // Intersections, Part 3", 2022): a NaN distance (origin exactly on a slab
        // plane of an axis the ray does not move along) leaves the interval
        // unchanged, which is what exact arithmetic says of a closed box.
        let slab = |k: usize| {
            let t0 = (min[k] - origin[k]) * inv_to_min[k];
            let t1 = (max[k] - origin[k]) * inv_to_max[k];
            let enter = min2(at_least(t0, zero), at_least(t1, zero));
            let exit = max2(at_most(t0, t_max), at_most(t1, t_max));
            (enter, exit)
        };
        let (ex, xx) = slab(0);
        let (ey, xy) = slab(1);
        let (ez, xz) = slab(2);
        slab_finish(max2(ex, max2(ey, ez)), min2(xx, min2(xy, xz)), t_max)
    }

    /// The end of the slab test, from the largest per-axis entry and the
    /// smallest per-axis exit: `(hit, enter, exit)`.
    fn slab_finish<F: Scalar>(enter: F, exit: F, t_max: F) -> (bool, F, F) {
        // Widen the exit by the rounding bound so that no box that exact
        // arithmetic hits is missed (see `exit_widening`).
        let limit = exit * exit_widening::<F>() + exit_slack::<F>();
        // `enter` is infinite only for an axis the ray never enters (its
        // direction component is zero, or so small that every distance
        // overflows): a miss even when `limit` is infinite too. (`enter` is
        // never NaN, `at_least` sees to that, so `enter <= MAX` is
        // `enter < inf`, in one comparison.)
        let hit = (enter <= limit) & (enter <= F::MAX);
        let exit = at_most(limit, t_max);
        (hit, at_most(enter, exit), exit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// The prepared ray holds nine registers of four `f32` lanes (the
    /// slab test's origin and two reciprocals, the triangle test's shear
    /// factors and permuted origin, each of the last two in three
    /// registers), the direction (12 bytes) and four one-byte fields: 160
    /// bytes, with nothing lost to padding.
    #[test]
    fn prepared_ray_is_160_bytes() {
        assert_eq!(core::mem::size_of::<PreparedRay<Vec3>>(), 9 * 16 + 12 + 4);
    }

    /// `ValidAabb::new` takes exactly the valid boxes: flat ones in, and
    /// NaN, infinite and inverted ones (on any axis) out; the slab test on
    /// it misses nothing the checked test hits, here for a flat box.
    #[test]
    fn valid_aabb_takes_exactly_the_valid_boxes() {
        let flat = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0));
        let valid = ValidAabb::new(flat).unwrap();
        assert_eq!(valid.aabb(), &flat);
        let ray = PreparedRay::new(&Ray::new(Vec3::new(0.5, -1.0, 0.5), Vec3::Y));
        let hit = ray_aabb_prepared(&ray, &valid, f32::INFINITY);
        assert!(hit.is_some());
        assert_eq!(hit, ray_aabb_prepared(&ray, &flat, f32::INFINITY));
        for axis in 0..3 {
            for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 2.0] {
                let mut min = Vec3::ZERO;
                min[axis] = bad;
                let b = Aabb::new(min, Vec3::ONE);
                assert!(!b.is_valid() && ValidAabb::new(b).is_none(), "{b:?}");
                let mut max = Vec3::ONE;
                max[axis] = if bad == 2.0 { -1.0 } else { bad };
                let b = Aabb::new(Vec3::ZERO, max);
                assert!(!b.is_valid() && ValidAabb::new(b).is_none(), "{b:?}");
            }
        }
    }

    /// A coordinate on a coarse grid (so that face planes, zero direction
    /// components and origins on slab planes are common), or one time in
    /// four a float with random bits in a wide range.
    fn coordinate(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        if (*state).is_multiple_of(4) {
            let m = ((*state >> 11) % (1 << 20)) as f64 / (1 << 20) as f64;
            (m - 0.5) * 2f64.powi(((*state >> 40) % 200) as i32 - 100)
        } else {
            ((*state >> 8) % 17) as f64 / 4.0 - 2.0
        }
    }

    /// `ray_aabb_prepared` and `ray_aabb` (all axes at once) give, bit for
    /// bit, the answer of the one-axis-at-a-time definition, in both
    /// precisions, for valid and invalid boxes and any `t_max`.
    #[test]
    fn lanes_are_the_definition() {
        fn check<V: Vector>(state: &mut u64) -> usize {
            let mut c = || S::<V>::from_f64(coordinate(state));
            let ray = Ray::new(V::new(c(), c(), c()), V::new(c(), c(), c()));
            let (a, b) = (V::new(c(), c(), c()), V::new(c(), c(), c()));
            // Mostly valid boxes, some inverted.
            let aabb = if c() > S::<V>::from_f64(-1.5) {
                Aabb::new(
                    V::new(min2(a.x(), b.x()), min2(a.y(), b.y()), min2(a.z(), b.z())),
                    V::new(max2(a.x(), b.x()), max2(a.y(), b.y()), max2(a.z(), b.z())),
                )
            } else {
                Aabb::new(a, b)
            };
            let mut hits = 0;
            for t_max in [c().abs() * S::<V>::TWO, S::<V>::INFINITY, S::<V>::NAN] {
                let p = PreparedRay::new(&ray);
                let s = &p.slab;
                let expected = (ray.is_valid() && aabb.is_valid() && t_max_ok(t_max))
                    .then(|| {
                        let [min, max] = [aabb.min, aabb.max].map(|v| [v.x(), v.y(), v.z()]);
                        let arrays = (
                            s.origin.to_array(),
                            s.inv_to_min.to_array(),
                            s.inv_to_max.to_array(),
                        );
                        let (hit, enter, exit) =
                            definition::slab_core(arrays.0, arrays.1, arrays.2, min, max, t_max);
                        hit.then_some((enter, exit))
                    })
                    .flatten();
                let bits = |h: Option<(S<V>, S<V>)>| {
                    h.map(|(e, x)| (e.to_f64().to_bits(), x.to_f64().to_bits()))
                };
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(ray_aabb_prepared(&p, &aabb, t_max)),
                    bits(expected),
                    "{ray:?} {aabb:?}"
                );
                assert_eq!(
                    bits(ray_aabb(&ray, &aabb, t_max)),
                    bits(expected),
                    "{ray:?} {aabb:?}"
                );
            }
            hits
        }
        let mut state = 0x0123_4567_89ab_cdef_u64;
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut state) + check::<DVec3>(&mut state);
        }
        assert!(hits > 20_000, "{hits}");
    }
}
