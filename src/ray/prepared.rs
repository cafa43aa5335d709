//! [`PreparedRay`]: everything per ray that the box and triangle tests
//! need, computed once.

use glam::Vec3;

use super::{Ray, Shear, SlabRay, invalid_stand_in, valid_lanes};
use crate::num::{Axis, L, Lanes, S, Scalar, Vector, lanes, vector};

/// A ray prepared for many box and triangle tests: its origin and, per
/// axis, the reciprocal of its direction rounded down and rounded up in
/// magnitude, and the per-ray part of the watertight triangle test.
///
/// Prepare once per ray, then call
/// [`Aabb`'s `clip`](crate::Aabb#method.clip) for each box (the inner
/// loop of BVH traversal). An invalid ray (see [`Ray::is_valid`]) prepares
/// into one that every kernel misses.
///
/// ```
/// use rayhit::{Aabb, Bounds, PreparedRay, Ray, glam::Vec3};
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::X));
/// let near = Aabb::new(Vec3::new(1.0, -1.0, -1.0), Vec3::new(2.0, 1.0, 1.0));
/// let far = Aabb::new(Vec3::new(5.0, -1.0, -1.0), Vec3::new(6.0, 1.0, 1.0));
/// let (enter, _) = near.clip(&ray, f32::INFINITY).unwrap();
/// assert_eq!(enter, 1.0);
/// assert!(far.clip(&ray, 4.0).is_none());
/// ```
///
/// The prepared ray also carries the per-ray part of the watertight
/// triangle test (the axis permutation and shear of Woop et al.), so that
/// [`Triangle`'s `hit` on a prepared ray](crate::Triangle#method.hit) and
/// [`TriangleBatch`'s `hit`](crate::batch::TriangleBatch#method.hit) need not recompute it
/// per triangle.
#[derive(Clone, Copy, Debug)]
pub struct PreparedRay<V: Vector = Vec3> {
    /// The slab test's part: origin and the directed reciprocals.
    pub(crate) slab: SlabRay<V>,
    /// True when every reciprocal is a normal float (so the two of `slab`
    /// are equal, and no distance is NaN for a valid box): the batch
    /// kernels then take each axis' near and far plane from the sign of
    /// the direction instead of ordering each pair (see `aabb::batch`).
    pub(crate) simple: bool,
    /// The triangle tests' shear factors `sx`, `sy`, `sz` (see `Shear`),
    /// each in every lane.
    pub(crate) shear_lanes: [L<V>; 3],
    /// The origin's coordinates in the shear's axis order, each in every
    /// lane (see `Shear::origin_lanes`).
    pub(crate) origin_lanes: [L<V>; 3],
    /// The shear's axis order, `kx`, `ky`, `kz`.
    pub(crate) axes: [Axis; 3],
    /// The ray's direction, for the entry face and the shear's `d_z`.
    pub(crate) dir: V,
}
// (The shear is stored only as the hot paths read it, and `Shear` rebuilt
// from it where the rest is needed: where each test has its own ray, the
// prepared ray is read once per test, and a smaller one costs less memory
// traffic; BENCHMARKS.md has the measurement.)

impl<V: Vector> PartialEq for PreparedRay<V> {
    fn eq(&self, o: &Self) -> bool {
        // The rest is a function of these two.
        self.slab == o.slab && self.shear() == o.shear()
    }
}

impl<V: Vector> PreparedRay<V> {
    /// Prepares `ray` for box and triangle tests.
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
    ///
    /// An invalid ray is prepared as the ray from `(+inf, +inf, +inf)`
    /// along `+z`, whatever it was: every kernel misses that one by its
    /// arithmetic alone, and equal invalid rays prepare equal.
    #[inline]
    #[must_use]
    pub fn new(ray: &Ray<V>) -> Self {
        // From the ray's components in lanes, and a branch to the invalid
        // ray's preparation, not a choice between two rays: choosing a
        // reference, or a whole ray, made the compiler store a ray it had
        // just computed (a ray mapped into an instance, say) and load it
        // back in pieces that straddle its stores, a store-forwarding
        // stall each time (much of the instance row's time in
        // `benches/peers`).
        let (origin, dir) = (lanes(ray.origin), lanes(ray.dir));
        if valid_lanes::<V>(origin, dir) {
            Self::build(origin, dir)
        } else {
            Self::invalid()
        }
    }

    /// Every invalid ray's preparation: that of [`invalid_stand_in`].
    #[cold]
    #[inline(never)]
    fn invalid() -> Self {
        let ray = invalid_stand_in::<V>();
        Self::build(lanes(ray.origin), lanes(ray.dir))
    }

    /// The preparation of the ray from `origin` along `dir` (lanes 0 to
    /// 2; lane 3 as [`lanes`] puts it), valid or the stand-in.
    #[inline(always)]
    fn build(origin: L<V>, dir: L<V>) -> Self {
        let (o, d) = (origin.to_array(), dir.to_array());
        let shear = Shear::<S<V>>::of(d);
        let (slab, simple) = SlabRay::of(origin, dir);
        Self {
            slab,
            simple,
            shear_lanes: shear.lanes(),
            origin_lanes: shear.origin_lanes_of(o),
            axes: [shear.kx, shear.ky, shear.kz],
            dir: vector(dir),
        }
    }

    /// The triangle tests' shear, as [`PreparedRay::new`] computed it.
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

    /// The ray this was prepared from, bit for bit; for an invalid ray,
    /// the stand-in every invalid ray is prepared as.
    #[inline(always)]
    pub(crate) fn ray(&self) -> Ray<V> {
        Ray::new(self.origin(), self.dir)
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

    /// Every invalid ray prepares as the ray from `+inf` along `+z`,
    /// field by field: the one encoding the kernels rely on.
    #[test]
    fn invalid_rays_prepare_as_the_stand_in() {
        fn check<V: Vector>() {
            let (nan, inf, zero, one) = (S::<V>::NAN, S::<V>::INFINITY, S::<V>::ZERO, S::<V>::ONE);
            let bits = |a: [S<V>; 3]| a.map(|c| c.to_f64().to_bits());
            for ray in [
                Ray::new(V::splat(nan), V::new(one, zero, zero)),
                Ray::new(V::ZERO, V::ZERO),
                Ray::new(V::new(zero, inf, zero), V::new(one, one, one)),
                Ray::new(V::ZERO, V::new(-inf, zero, one)),
            ] {
                let p = PreparedRay::new(&ray);
                assert!(!p.is_valid());
                assert_eq!(p.origin(), V::splat(inf));
                assert_eq!(p.dir, V::new(zero, zero, one));
                // +z's shear: s_x = -0 / 1, s_y = -0 / 1, s_z = 1 / 1.
                let s = p.shear();
                assert_eq!((s.kx, s.ky, s.kz), (Axis::X, Axis::Y, Axis::Z));
                assert_eq!(bits([s.sx, s.sy, s.sz]), bits([-zero, -zero, one]));
                assert_eq!(bits([s.dz; 3]), bits([one; 3]));
                for l in p.origin_lanes {
                    assert_eq!(bits(l.to_array()), bits([inf; 3]));
                }
                // The reciprocals of (0, 0, 1).
                assert_eq!(bits(p.slab.inv_to_min.to_array()), bits([inf, inf, one]));
                assert_eq!(bits(p.slab.inv_to_max.to_array()), bits([inf, inf, one]));
                assert!(!p.simple);
                assert!(p == PreparedRay::new(&Ray::new(V::ZERO, V::ZERO)));
            }
        }
        check::<Vec3>();
        check::<DVec3>();
    }
}
