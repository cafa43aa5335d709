//! Instances: one object placed in the world by an affine map
//! ([`Instance`]), with the crate's guarantees carried through the map and
//! back: a world box that contains the exact image of the object's box, one
//! object ray per world ray ([`InstanceRayError`] bounds how far apart the
//! two are), a world [`SurfacePoint`] for an object hit, and rays and
//! shadow segments that leave it ([`Instance::spawn`],
//! [`Instance::spawn_through`], [`Instance::spawn_to_through`],
//! [`Instance::spawn_to_point_through`]). [`InstanceError`] says why a
//! matrix cannot be an instance.
//!
//! # Notation, used by every derivation in this module
//!
//! The instance maps object space to world space by `F(x) = M x + T`, with
//! `M` and `T` the float entries the user gave, taken as exact rationals:
//! `F` is the exact map the instance *means*, and the exact world surface
//! of an object triangle is `F` of the exact triangle. The stored inverse
//! `G(x) = A x + b` is computed in floating point and is not exact. Its
//! quality is measured, never assumed: the residual `R = M A - I` and
//! `beta = M b + T` (both zero for an exact inverse) are bounded entrywise
//! from the stored floats when the instance is built (`inverse.rs`). `u`
//! is the unit roundoff of the precision and `gamma(n) = n u / (1 - n u)`;
//! `|X|` is the entrywise absolute value, inequalities between vectors hold
//! per component.
//!
//! [`SurfacePoint`]: crate::SurfacePoint

// Files: `mod.rs`, the type, its errors and accessors; `inverse.rs`, the
// stored inverse and the bounds on its error derived from the matrix
// itself (the residual `M A - I`); `ray.rs`, a world ray into object space
// and the bound relating the two rays; `bounds.rs`, an object box to a
// world box, rounded outward; `surface.rs`, an object hit to a world
// surface point, the rays that leave it and shadow segments.

mod bounds;
mod inverse;
mod ray;
mod surface;

use core::fmt;

use glam::{Affine3A, DAffine3, DVec3, Vec3, Vec3A};

use crate::num::{L, Lanes, S, Scalar, Vector, vector};

pub use ray::InstanceRayError;

/// [`Instance`] in `f64`.
pub type DInstance = Instance<DVec3>;

/// Why an [`Instance`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum InstanceError {
    /// A matrix or translation entry is NaN or infinite.
    NotFinite,
    /// The matrix is singular: its determinant is zero (or underflows to
    /// zero), so there is no inverse to trace rays with.
    Singular,
    /// The computed inverse is too far from the exact one: the residual
    /// `M A - I` has a column sum above `1/2` (a condition number near
    /// `1 / u`), so the normal's error cannot be bounded.
    IllConditioned,
    /// The inverse, its translation or an error bound overflows.
    Overflow,
}

impl fmt::Display for InstanceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::NotFinite => "instance transform is not finite",
            Self::Singular => "instance transform is singular",
            Self::IllConditioned => "instance transform is too ill-conditioned to invert",
            Self::Overflow => "instance transform's inverse or error bounds overflow",
        })
    }
}

impl core::error::Error for InstanceError {}

/// An object-to-world affine transform `x -> M x + T`, with its inverse
/// computed once and the error of that inverse bounded: what a renderer
/// needs to trace one mesh placed many times (an instance, or a
/// bottom-level acceleration structure under a top-level one).
///
/// Build it from glam's [`Affine3A`] ([`Instance::from_affine3a`], `f32`)
/// or [`DAffine3`] ([`Instance::from_daffine3`], `f64`), or from the
/// matrix's columns and the translation for any [`Vector`] type
/// ([`Instance::new`]). The matrix and translation are taken as exact: the
/// guarantees below are about the exact map of the floats given.
///
/// What it gives, each with its guarantee in its own docs:
///
/// - [`Instance::world_to_object`]: the world ray in object space, once per
///   instance visit, with [`Instance::world_to_object_error`] bounding, at
///   every `t`, the distance between the object ray's point mapped exactly
///   to the world and the world ray's point. Every triangle of the instance
///   is tested against this one object ray, so the watertight test's
///   guarantees hold inside the instance exactly as without instances.
/// - [`Instance::object_to_world_box`]: a world box containing the exact
///   image of every point of an object box (a conservative top-level box).
/// - [`Instance::surface_to_world`]: an object-space [`SurfacePoint`] in
///   the world, with error bounds on the exact world surface.
/// - [`Instance::spawn`] and [`Instance::spawn_through`]: a ray leaving
///   that world point which, mapped back into the instance through the
///   stored inverse as a renderer does, cannot meet the surface it left.
/// - [`Instance::spawn_to_through`] and [`Instance::spawn_to_point_through`]:
///   a shadow-ray segment `(0, 1]` between two such points (or to a point
///   light) that, traced into either end's instance, meets neither end's
///   surface.
///
/// Nested instances (an instance of instances) chain the maps: each level
/// maps the ray it receives, and the error bounds compose (see
/// [`InstanceRayError::nested`], [`Instance::path_error`] and
/// [`Instance::spawn_through`]). Matrices are
/// never multiplied together, so no rounding of a product needs a bound.
///
/// Two *different* instances that meet at a seam (two copies of a tile
/// placed side by side) are not watertight with each other: each sees its
/// own rounded object ray, and a ray can pass between them by a rounding.
/// Copies whose transforms are equal see the same object ray and keep the
/// mesh's watertightness.
///
/// [`SurfacePoint`]: crate::SurfacePoint
///
/// ```
/// use rayhit::{Instance, Ray, Triangle, glam::{Affine3A, Quat, Vec3}, ray_triangle};
/// let place = Affine3A::from_scale_rotation_translation(
///     Vec3::splat(2.0), Quat::from_rotation_y(0.5), Vec3::new(1e4, 0.0, 0.0),
/// );
/// let instance = Instance::from_affine3a(place).unwrap();
/// let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
/// // A world ray aimed at the instance's origin.
/// let world = Ray::new(place.transform_point3(Vec3::new(0.0, 0.0, 5.0)), place.transform_vector3(-Vec3::Z));
/// let object = instance.world_to_object(&world);
/// let hit = ray_triangle(&object, &tri, f32::INFINITY).unwrap();
/// assert!((hit.t - 5.0).abs() < 1e-3);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Instance<V: Vector = Vec3> {
    // Everything as the per-ray and per-hit arithmetic reads it, computed
    // once here: matrices as columns, so that a matrix times a vector is
    // three products and two sums of whole registers (no row is gathered
    // per call), the absolute values and the bounds' constant terms
    // precomputed, and every vector in a `Four` (one aligned load, the
    // fourth lane a stored zero).
    /// Columns of `M`.
    m_cols: [Four<V>; 3],
    /// `T`.
    t: Four<V>,
    /// Columns of the stored inverse's matrix `A`.
    a_cols: [Four<V>; 3],
    /// The stored inverse's translation `b`.
    b: Four<V>,
    /// Rows of `A` (the columns of `A^T`, for the normal).
    a_rows: [Four<V>; 3],
    /// Columns of `|M|`.
    m_abs_cols: [Four<V>; 3],
    /// Rows of `|A|` (the columns of `|A^T|`).
    a_abs_rows: [Four<V>; 3],
    /// Columns of `K_o`, the origin's error matrix (see `inverse.rs`).
    k_origin: [Four<V>; 3],
    /// `c_o`, the origin's absolute error term.
    c_origin: Four<V>,
    /// Columns of `K_d`, the direction's error matrix.
    k_dir: [Four<V>; 3],
    /// `c_p = g(4) |T| + U`, rounded up: the world point's error bound
    /// but for the terms that depend on the point (see `surface.rs`).
    c_point: Four<V>,
    /// Per component, the column sum of the residual bound divided by
    /// `1 - rho` (see `surface.rs`).
    normal_residual: Four<V>,
    /// `U`, an absolute term covering roundings into the subnormal range:
    /// `MIN_POSITIVE (1 + max row sum of |M|)`, in every component. It is
    /// also `c_d`, the direction's absolute error term.
    tiny_world: Four<V>,
}

/// A vector as the per-call arithmetic loads it: in lanes, the fourth a
/// stored zero, 16-byte aligned (for `f32`, one aligned load that the
/// instruction using it reads from memory itself).
///
/// The fourth lane is computed along with the others and never read, so
/// it must hold an ordinary number: an operation with a subnormal operand
/// or result takes the CPU's slow path whichever lane it is in. Stored as
/// a `V` in a 16-byte slot, a `Vec3`'s fourth lane was padding, which no
/// code writes and a move need not copy, and which the compiler loaded
/// along with the three lanes where the fourth lane's results go unread;
/// on the peers' data it held halves of stack addresses, subnormal as
/// floats, and put `surface_to_world` on that slow path. (This needs
/// `V: Vector`, the lanes' type being its precision's, on `Instance` too.)
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct Four<V: Vector> {
    l: L<V>,
}

impl<V: Vector> Four<V> {
    /// `v` in lanes 0 to 2, zero in lane 3.
    fn new(v: V) -> Self {
        Self {
            l: L::<V>::new4(v.x(), v.y(), v.z(), S::<V>::ZERO),
        }
    }

    /// The stored vector in lanes.
    #[inline(always)]
    fn load(&self) -> L<V> {
        self.l
    }

    /// The stored vector.
    fn get(&self) -> V {
        vector(self.l)
    }
}

/// The lanes of three stored vectors (a matrix's columns).
#[inline(always)]
fn load3<V: Vector>(c: &[Four<V>; 3]) -> [L<V>; 3] {
    [c[0].load(), c[1].load(), c[2].load()]
}

impl<V: Vector> PartialEq for Instance<V> {
    fn eq(&self, o: &Self) -> bool {
        // The rest is a function of these two.
        self.matrix_columns() == o.matrix_columns() && self.translation() == o.translation()
    }
}

impl<V: Vector> Instance<V> {
    /// The instance with matrix columns `cols` (so `M x = x_0 cols[0] +
    /// x_1 cols[1] + x_2 cols[2]`, glam's convention) and translation `T`.
    ///
    /// Errors: [`InstanceError::NotFinite`] for a NaN or infinite entry,
    /// [`InstanceError::Singular`] for a zero determinant,
    /// [`InstanceError::IllConditioned`] when the computed inverse is too
    /// inaccurate for the bounds (condition number near `1 / u`), and
    /// [`InstanceError::Overflow`] when the inverse or a bound overflows.
    /// Never panics.
    ///
    /// ```
    /// use rayhit::{Instance, glam::DVec3, instance::InstanceError};
    /// let shear = Instance::new([DVec3::X, DVec3::new(0.5, 1.0, 0.0), DVec3::Z], DVec3::new(0.0, 0.0, 1e5)).unwrap();
    /// assert_eq!(shear.translation(), DVec3::new(0.0, 0.0, 1e5));
    /// let flat = Instance::new([DVec3::X, DVec3::X, DVec3::Z], DVec3::ZERO);
    /// assert_eq!(flat, Err(InstanceError::Singular));
    /// ```
    pub fn new(cols: [V; 3], translation: V) -> Result<Self, InstanceError> {
        inverse::build(cols, translation)
    }

    /// The matrix `M`'s columns, as given.
    ///
    /// ```
    /// use rayhit::{Instance, glam::Vec3};
    /// let i = Instance::new([Vec3::X, Vec3::Y * 2.0, Vec3::Z], Vec3::ZERO).unwrap();
    /// assert_eq!(i.matrix_columns()[1], Vec3::new(0.0, 2.0, 0.0));
    /// ```
    #[must_use]
    pub fn matrix_columns(&self) -> [V; 3] {
        self.m_cols.map(|c| c.get())
    }

    /// The translation `T`, as given.
    ///
    /// ```
    /// use rayhit::{Instance, glam::Vec3};
    /// let i = Instance::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::ONE).unwrap();
    /// assert_eq!(i.translation(), Vec3::ONE);
    /// ```
    #[must_use]
    pub fn translation(&self) -> V {
        self.t.get()
    }

    /// The stored inverse `x -> A x + b`: the columns of `A` and `b`. It is
    /// the rounded inverse of the exact map, not the exact one; every
    /// bound of the instance accounts for the difference.
    ///
    /// ```
    /// use rayhit::{Instance, glam::Vec3};
    /// let i = Instance::new([Vec3::X * 4.0, Vec3::Y, Vec3::Z], Vec3::new(8.0, 0.0, 0.0)).unwrap();
    /// let (cols, b) = i.inverse();
    /// assert_eq!((cols[0], b), (Vec3::new(0.25, 0.0, 0.0), Vec3::new(-2.0, 0.0, 0.0)));
    /// ```
    #[must_use]
    pub fn inverse(&self) -> ([V; 3], V) {
        (self.a_cols.map(|c| c.get()), self.b.get())
    }
}

impl Instance<Vec3> {
    /// The instance of glam's `f32` affine transform (object to world).
    /// Errors as for [`Instance::new`].
    ///
    /// ```
    /// use rayhit::{Instance, glam::{Affine3A, Vec3}, instance::InstanceError};
    /// assert!(Instance::from_affine3a(Affine3A::from_translation(Vec3::X)).is_ok());
    /// assert_eq!(Instance::from_affine3a(Affine3A::from_scale(Vec3::ZERO)), Err(InstanceError::Singular));
    /// assert_eq!(Instance::from_affine3a(Affine3A::from_scale(Vec3::NAN)), Err(InstanceError::NotFinite));
    /// ```
    pub fn from_affine3a(affine: Affine3A) -> Result<Self, InstanceError> {
        let m = affine.matrix3;
        Self::new(
            [m.x_axis.into(), m.y_axis.into(), m.z_axis.into()],
            affine.translation.into(),
        )
    }
}

impl Instance<Vec3A> {
    /// The instance of glam's `f32` affine transform, on `Vec3A` (the same
    /// answers, bit for bit, as on `Vec3`). Errors as for
    /// [`Instance::new`].
    ///
    /// ```
    /// use rayhit::{Instance, glam::{Affine3A, Vec3A}};
    /// let i = Instance::<Vec3A>::from_affine3a_simd(Affine3A::from_translation(Vec3A::X.into())).unwrap();
    /// assert_eq!(i.translation(), Vec3A::X);
    /// ```
    pub fn from_affine3a_simd(affine: Affine3A) -> Result<Self, InstanceError> {
        let m = affine.matrix3;
        Self::new([m.x_axis, m.y_axis, m.z_axis], affine.translation)
    }
}

impl Instance<DVec3> {
    /// The instance of glam's `f64` affine transform (object to world).
    /// Errors as for [`Instance::new`].
    ///
    /// ```
    /// use rayhit::{Instance, glam::{DAffine3, DVec3}};
    /// let i = Instance::from_daffine3(DAffine3::from_scale(DVec3::splat(1e-3))).unwrap();
    /// assert_eq!(i.matrix_columns()[2], DVec3::new(0.0, 0.0, 1e-3));
    /// ```
    pub fn from_daffine3(affine: DAffine3) -> Result<Self, InstanceError> {
        let m = affine.matrix3;
        Self::new([m.x_axis, m.y_axis, m.z_axis], affine.translation)
    }
}

impl TryFrom<Affine3A> for Instance<Vec3> {
    type Error = InstanceError;
    fn try_from(affine: Affine3A) -> Result<Self, InstanceError> {
        Self::from_affine3a(affine)
    }
}

impl TryFrom<Affine3A> for Instance<Vec3A> {
    type Error = InstanceError;
    fn try_from(affine: Affine3A) -> Result<Self, InstanceError> {
        Self::from_affine3a_simd(affine)
    }
}

impl TryFrom<DAffine3> for Instance<DVec3> {
    type Error = InstanceError;
    fn try_from(affine: DAffine3) -> Result<Self, InstanceError> {
        Self::from_daffine3(affine)
    }
}

/// The matrix with columns `cols` times `v`: per component, bit for bit
/// the dot product of the matrix's row with `v` as [`Vector::dot`] sums
/// it (`(x + y) + z`), computed as `(col_0 v_x + col_1 v_y) + col_2 v_z`
/// on whole registers: a product's longest path has three roundings (a
/// product and two sums).
#[inline(always)]
pub(crate) fn apply<V: Vector>(cols: &[L<V>; 3], v: L<V>) -> L<V> {
    let [x, y, z] = v.to_array();
    let splat = L::<V>::splat;
    cols[0]
        .mul(splat(x))
        .add(cols[1].mul(splat(y)))
        .add(cols[2].mul(splat(z)))
}

/// `apply(cols, v) + c` per component for non-negative `cols`, `v`, `c`,
/// made an upper bound of its exact value: one product and three
/// additions on the longest path, four roundings ([`bound_up_l`]).
#[inline(always)]
pub(crate) fn abs_apply_up<V: Vector>(cols: &[L<V>; 3], v: L<V>, c: L<V>) -> L<V> {
    bound_up_l::<V>(apply::<V>(cols, v).add(c), 4)
}

/// [`bound_up`](crate::num::round::bound_up) of every lane: bit for bit
/// the same (one product by the same factor).
#[inline(always)]
pub(crate) fn bound_up_l<V: Vector>(v: L<V>, roundings: u32) -> L<V> {
    use crate::num::round::bound_up;
    v.mul(L::<V>::splat(bound_up(S::<V>::ONE, roundings)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stored vector loads as its three components and a zero, in
    /// every vector type; the instance holds 27 of them and nothing else.
    #[test]
    fn stored_vectors_load_with_a_zero_fourth_lane() {
        fn check<V: Vector>() {
            let s = |x: f64| S::<V>::from_f64(x);
            let v = V::new(s(1.0), s(-2.0), s(3.5));
            let four = Four::new(v);
            let bits = |a: [S<V>; 4]| a.map(|c| c.to_f64().to_bits());
            assert_eq!(
                bits(four.load().to_array4()),
                bits([s(1.0), s(-2.0), s(3.5), s(0.0)])
            );
            assert_eq!(four.get(), v);
        }
        check::<Vec3>();
        check::<Vec3A>();
        check::<DVec3>();
        assert_eq!(size_of::<Instance<Vec3>>(), 27 * 16);
    }
}
