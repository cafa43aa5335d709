//! A world ray in object space, and the bound relating the two rays.
//!
//! # Derivation
//!
//! The object ray is `o' = fl(A o + b)`, `d' = fl(A d)`, each component a
//! dot product of length four (three for `d'`), so
//! `o' = A o + b + e_o` with `|e_o| <= gamma(4) (|A||o| + |b|)` and
//! `d' = A d + e_d` with `|e_d| <= gamma(3) |A||d|`. Mapping the object
//! ray's point at `t` to the world exactly, with `M A = I + R` and
//! `M b + T = beta`:
//!
//! ```text
//! F(o' + t d') = M (A o + b + e_o) + T + t M (A d + e_d)
//!              = o + t d + (R o + beta + M e_o) + t (R d + M e_d)
//! ```
//!
//! so, per component, `|F(o' + t d') - (o + t d)|` is at most
//!
//! ```text
//! Rb|o| + |beta| + g(4)|M|(|A||o| + |b|)  +  t (Rb|d| + g(3)|M||A||d|)
//!   = K_o |o| + c_o  +  t (K_d |d| + c_d)
//! ```
//!
//! with `K_o`, `c_o`, `K_d`, `c_d` from `inverse.rs` (`c_d`, `U` in `c_o`:
//! roundings into the subnormal range). The same `t` on both sides: the
//! direction is mapped linearly, so the object ray's `t` is the world
//! ray's `t` up to this bound, and a hit at object `t` is a world hit at
//! the same `t`. Evaluating the bound rounds up (`abs_apply_up`).

use super::{Instance, abs_apply_up, apply, bound_up_l, load3};
use crate::Ray;
use crate::num::round::{bound_up, max2};
use crate::num::{L, Lanes, S, Scalar, Vector};
use crate::num::{lanes, vector};

/// A bound on how far a world ray and its object ray
/// ([`Instance::world_to_object`]) are apart at the same `t`: per
/// component, `|F(object.at(t)) - world.at(t)| <= at_origin + t * per_t`
/// for every `t >= 0`, with `F` the instance's exact object-to-world map
/// and the points taken exactly (not rounded).
///
/// ```
/// use rayhit::{Instance, Ray, glam::{Affine3A, Quat, Vec3}};
/// let inst = Instance::from_affine3a(Affine3A::from_rotation_translation(Quat::from_rotation_z(1.0), Vec3::splat(100.0))).unwrap();
/// let world = Ray::new(Vec3::new(90.0, 95.0, 101.0), Vec3::new(1.0, 0.5, -0.25));
/// let err = inst.world_to_object_error(&world);
/// // A few ulps of the coordinates (100 here, an ulp of 7.6e-6).
/// assert!(err.at(2.0).max_element() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstanceRayError<V> {
    /// The bound at `t = 0`, per component (world units).
    pub at_origin: V,
    /// The growth of the bound per unit of `t`, per component.
    pub per_t: V,
}

impl<V: Vector> InstanceRayError<V> {
    /// The bound at `t` (`t >= 0`), rounded up: `at_origin + t * per_t`.
    ///
    /// ```
    /// use rayhit::{glam::Vec3, instance::InstanceRayError};
    /// let e = InstanceRayError { at_origin: Vec3::splat(1.0), per_t: Vec3::splat(0.5) };
    /// assert!(e.at(4.0).x >= 3.0);
    /// ```
    #[must_use]
    pub fn at(&self, t: S<V>) -> V {
        let t = t.abs();
        let c = |i: usize| bound_up(self.at_origin[i] + self.per_t[i] * t, 2);
        V::new(c(0), c(1), c(2))
    }

    /// The bound of a nested instance: `outer` maps the world ray to a ray
    /// with bound `outer_error`, an inner instance maps that ray to the
    /// object ray with bound `inner_error` (in `outer`'s object space).
    /// Then, with `F_1`, `F_2` the exact maps,
    /// `F_1(F_2(x)) - w = M_1 (F_2(x) - y) + (F_1(y) - w)`, so the world
    /// bound is `|M_1| inner + outer`, per `t` and at the origin.
    ///
    /// ```
    /// use rayhit::{Instance, Ray, glam::{Affine3A, Vec3}, instance::InstanceRayError};
    /// let outer = Instance::from_affine3a(Affine3A::from_scale(Vec3::splat(2.0))).unwrap();
    /// let inner = Instance::from_affine3a(Affine3A::from_translation(Vec3::splat(3.0))).unwrap();
    /// let world = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::X);
    /// let mid = outer.world_to_object(&world);
    /// let e = InstanceRayError::nested(&outer, &outer.world_to_object_error(&world), &inner.world_to_object_error(&mid));
    /// assert!(e.at_origin.x > 0.0 && e.at_origin.x < 1e-5);
    /// ```
    #[must_use]
    pub fn nested(outer: &Instance<V>, outer_error: &Self, inner_error: &Self) -> Self {
        let bound = |inner: V, outer_term: V| {
            vector(abs_apply_up::<V>(
                &load3(&outer.m_abs_cols),
                lanes(inner),
                lanes(outer_term),
            ))
        };
        Self {
            at_origin: bound(inner_error.at_origin, outer_error.at_origin),
            per_t: bound(inner_error.per_t, outer_error.per_t),
        }
    }
}

impl<V: Vector> InstanceRayError<V> {
    /// `(at_origin, per_t)`.
    pub(crate) fn parts(&self) -> (V, V) {
        (self.at_origin, self.per_t)
    }
}

impl<V: Vector> Instance<V> {
    /// The bound relating `ray` and its object ray through the instances
    /// `path` (outermost first: `path[0]` maps the world ray, `path[1]`
    /// maps the result, and so on): each level's
    /// [`Instance::world_to_object_error`] for the ray it receives,
    /// composed with [`InstanceRayError::nested`] from the innermost out.
    /// Zero for an empty path; infinite for a path deeper than eight
    /// levels (not covered).
    ///
    /// ```
    /// use rayhit::{Instance, Ray, glam::{Affine3A, Vec3}};
    /// let outer = Instance::from_affine3a(Affine3A::from_scale(Vec3::splat(2.0))).unwrap();
    /// let inner = Instance::from_affine3a(Affine3A::from_translation(Vec3::splat(3.0))).unwrap();
    /// let world = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::X);
    /// let both = Instance::path_error(&[&outer, &inner], &world);
    /// assert!(both.at_origin.x >= outer.world_to_object_error(&world).at_origin.x);
    /// assert_eq!(Instance::path_error(&[&outer], &world), outer.world_to_object_error(&world));
    /// ```
    #[must_use]
    pub fn path_error(path: &[&Self], ray: &Ray<V>) -> InstanceRayError<V> {
        let zero = InstanceRayError {
            at_origin: V::ZERO,
            per_t: V::ZERO,
        };
        let Some((&last, outer)) = path.split_last() else {
            return zero;
        };
        if path.len() > 8 {
            let inf = V::splat(S::<V>::INFINITY);
            return InstanceRayError {
                at_origin: inf,
                per_t: inf,
            };
        }
        // The rays each level receives.
        let mut rays = [*ray; 8];
        for k in 1..path.len() {
            rays[k] = path[k - 1].world_to_object(&rays[k - 1]);
        }
        let mut acc = last.world_to_object_error(&rays[outer.len()]);
        for (k, inst) in outer.iter().enumerate().rev() {
            acc = InstanceRayError::nested(inst, &inst.world_to_object_error(&rays[k]), &acc);
        }
        acc
    }

    /// The world ray in object space: `origin' = A origin + b`,
    /// `dir' = A dir`, rounded, with the stored inverse `A x + b`.
    ///
    /// Call it once per visit of an instance and test every triangle of the
    /// instance against the one object ray (prepare it once with
    /// [`PreparedRay::new`](crate::PreparedRay::new)): the watertight test
    /// then holds inside the instance exactly as it does for a mesh in
    /// world space. `t` is shared: a hit at `t` on the object ray is the
    /// world ray's hit at `t`, up to [`Instance::world_to_object_error`],
    /// so `t_max` carries over between instances and world geometry
    /// unchanged. A world ray that is not valid ([`Ray::is_valid`]) maps to
    /// a ray that is not valid either when its entries are NaN or infinite;
    /// a valid world ray whose image overflows gives non-finite components,
    /// which every kernel treats as a miss.
    ///
    /// ```
    /// use rayhit::{Instance, Ray, glam::{Affine3A, Vec3}};
    /// let inst = Instance::from_affine3a(Affine3A::from_scale_rotation_translation(
    ///     Vec3::splat(2.0), Default::default(), Vec3::new(10.0, 0.0, 0.0))).unwrap();
    /// let object = inst.world_to_object(&Ray::new(Vec3::new(12.0, 4.0, 0.0), Vec3::new(0.0, -2.0, 0.0)));
    /// assert_eq!(object, Ray::new(Vec3::new(1.0, 2.0, 0.0), Vec3::new(0.0, -1.0, 0.0)));
    /// ```
    #[inline]
    #[must_use]
    pub fn world_to_object(&self, ray: &Ray<V>) -> Ray<V> {
        let a = load3(&self.a_cols);
        let origin = apply::<V>(&a, lanes(ray.origin)).add(self.b.load());
        let dir = apply::<V>(&a, lanes(ray.dir));
        Ray::new(vector(origin), vector(dir))
    }

    /// The bound relating `ray` and its object ray
    /// ([`Instance::world_to_object`]) at every `t`: see
    /// [`InstanceRayError`]. It is a few ulps of the coordinates times the
    /// matrix's condition (the residual `M A - I` of the stored inverse is
    /// part of it), and it is infinite only when the
    /// ray's coordinates are near overflow.
    ///
    /// A hit found at `t` in object space, at object point `p` with error
    /// `e` (from [`Triangle::surface_point_at`](crate::Triangle::surface_point_at)),
    /// corresponds to the world point `ray.at(t)` within
    /// `at(t) + |M| e` plus the rounding of `at` itself.
    ///
    /// Whether the instance resolves its object from this ray is the same
    /// bound in object units, against the object's scale:
    /// [`Instance::object_error_at`].
    ///
    /// ```
    /// use rayhit::{Instance, Ray, glam::{DAffine3, DVec3}};
    /// let inst = Instance::from_daffine3(DAffine3::from_translation(DVec3::splat(1e5))).unwrap();
    /// let world = Ray::new(DVec3::splat(1e5 + 1.0), DVec3::NEG_ONE);
    /// let err = inst.world_to_object_error(&world);
    /// assert!(err.at(1.0).max_element() < 1e-9);
    /// ```
    #[inline]
    #[must_use]
    pub fn world_to_object_error(&self, ray: &Ray<V>) -> InstanceRayError<V> {
        let (origin, dir) = (lanes(ray.origin).abs(), lanes(ray.dir).abs());
        InstanceRayError {
            at_origin: vector(abs_apply_up::<V>(
                &load3(&self.k_origin),
                origin,
                self.c_origin.load(),
            )),
            per_t: vector(abs_apply_up::<V>(
                &load3(&self.k_dir),
                dir,
                self.tiny_world.load(),
            )),
        }
    }

    /// [`Instance::world_to_object_error`]'s bound at `t`, in object
    /// units: per object axis, how far the object ray's point at `t`
    /// (exactly, on [`Instance::world_to_object`] of `ray`) can be from the
    /// exact preimage of the world ray's point at `t`. It says whether the
    /// instance resolves its object from this ray: compare it with the
    /// object's scale (its box, or the smallest feature that must stay
    /// apart). Where it is not well below that scale, the object ray
    /// cannot tell those features apart (no kernel can), and the instance
    /// should be flattened or its transform made less anisotropic; the
    /// bound grows with the ray's distance from the instance's origin
    /// times the matrix's condition number.
    ///
    /// Derivation: the world bound `v = at(t)` bounds `M delta`, with
    /// `delta` the object-space difference, so `delta = M^-1 (M delta)`.
    /// With the stored inverse `A` and its residual `M A = I + R`,
    /// `M^-1 = A (I + R)^-1`, and `w = (I + R)^-1 (M delta)` has `|w_i| <=
    /// v_i + rho / (1 - rho) sum_j v_j` (`rho` the largest column sum of
    /// the residual's bound, at most 1/2: `|w| <= |M delta| + |R| |w|`,
    /// each entry of `|R|` at most `rho`, and `sum |w_j| <= sum v_j / (1 -
    /// rho)`); then `|delta| <= |A| |w|`, evaluated rounding up.
    ///
    /// ```
    /// use rayhit::{Aabb, Instance, Ray, glam::{Affine3A, Vec3}};
    /// // A mesh 2 units across, squashed a thousandfold along z and set down
    /// // 30,000 units from the origin; seen from 3,000 units off.
    /// let object_box = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
    /// let size = object_box.max - object_box.min;
    /// let inst = Instance::from_affine3a(Affine3A::from_scale_rotation_translation(
    ///     Vec3::new(1.0, 1.0, 1e-3), Default::default(), Vec3::splat(3e4))).unwrap();
    /// let ray = Ray::new(Vec3::new(3e4 + 3e3, 3e4, 3e4), -Vec3::X);
    /// let err = inst.object_error_at(&ray, 3e3);
    /// // Along x and y, under 1% of the box: resolved.
    /// assert!(err.x < 0.01 * size.x && err.y < 0.01 * size.y);
    /// // Along z, more than the whole box: world coordinates near 3e4 are
    /// // multiples of 2^-9, and the box is 0.002 thick in the world.
    /// assert!(err.z > size.z);
    /// ```
    #[must_use]
    pub fn object_error_at(&self, ray: &Ray<V>, t: S<V>) -> V {
        let v = lanes(self.world_to_object_error(ray).at(t));
        let [r0, r1, r2] = self.normal_residual.load().to_array();
        let ratio = max2(max2(r0, r1), r2);
        let [v0, v1, v2] = v.to_array();
        let spread = bound_up(ratio * (v0 + v1 + v2), 3);
        let w = bound_up_l::<V>(v.add(L::<V>::splat(spread)), 1);
        let a = load3(&self.a_cols).map(|c| c.abs());
        vector(abs_apply_up::<V>(&a, w, L::<V>::splat(S::<V>::ZERO)))
    }
}
