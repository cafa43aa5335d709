//! Exact answers to the instance questions: where an instance's exact map
//! puts a point and a box, how far a world ray and its object ray are
//! apart, and judgements of claimed answers.
//!
//! An [`Instance`] means the affine map `F(x) = M x + T` of the very floats
//! it was built from (see [`Instance`]'s docs); [`AffineMap`] is that map
//! with exact rational entries, and a path of nested instances composes
//! exactly into one.

use num_traits::{Signed, Zero};

use super::oracle::{R, R3, dot, r, rv, to_f64, ulp};
use super::{Exact, Rational};
use crate::{Aabb, Instance, Ray, Scalar, Vector};

/// An affine map `x -> M x + T` with exact rational entries: the map an
/// [`Instance`] means (its matrix and translation taken exactly), or the
/// exact composition of a path of nested instances.
///
/// ```
/// use rayhit::{Instance, exact::{AffineMap, Rational}, glam::Vec3};
/// let inst = Instance::new([Vec3::X * 3.0, Vec3::Y, Vec3::Z], Vec3::new(1.0, 0.0, 0.0)).unwrap();
/// let f = AffineMap::of(&inst);
/// let one = || Rational::from_integer(1.into());
/// // F(1, 1, 1) = (3 + 1, 1, 1), exactly.
/// let image = f.apply(&[one(), one(), one()]);
/// assert_eq!(image[0], Rational::from_integer(4.into()));
/// // The inverse is exact too: 1/3 is not a float, but it is a rational.
/// let back = f.inverse().unwrap();
/// assert_eq!(back.matrix[0][0], Rational::new(1.into(), 3.into()));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct AffineMap {
    /// The rows of `M`.
    pub matrix: [R3; 3],
    /// `T`.
    pub translation: R3,
}

impl AffineMap {
    /// The map with matrix columns `columns` (glam's convention, as in
    /// [`Instance::new`]) and translation `T`, exactly; `None` when an
    /// entry is NaN or infinite. A singular matrix is allowed here (it has
    /// no [`AffineMap::inverse`]).
    ///
    /// ```
    /// use rayhit::{exact::AffineMap, glam::DVec3};
    /// assert!(AffineMap::new([DVec3::X, DVec3::Y, DVec3::Z], DVec3::ONE).is_some());
    /// assert!(AffineMap::new([DVec3::X, DVec3::Y, DVec3::NAN], DVec3::ONE).is_none());
    /// ```
    #[must_use]
    pub fn new<V: Vector>(columns: [V; 3], translation: V) -> Option<Self> {
        let cols = [rv(columns[0])?, rv(columns[1])?, rv(columns[2])?];
        Some(Self {
            matrix: [0, 1, 2].map(|i| [0, 1, 2].map(|j| cols[j][i].clone())),
            translation: rv(translation)?,
        })
    }

    /// The exact map an instance means: its matrix and translation as
    /// given ([`Instance::matrix_columns`], [`Instance::translation`]),
    /// not its stored inverse.
    ///
    /// ```
    /// use rayhit::{Instance, exact::AffineMap, glam::Vec3};
    /// let inst = Instance::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::splat(0.1)).unwrap();
    /// // 0.1 is the float nearest to a tenth, taken as it is.
    /// assert_eq!(AffineMap::of(&inst).translation[0], rayhit::exact::rational(0.1f32).unwrap());
    /// ```
    #[must_use]
    pub fn of<V: Vector>(instance: &Instance<V>) -> Self {
        Self::new(instance.matrix_columns(), instance.translation())
            .expect("an instance's entries are finite")
    }

    /// The exact map of a path of nested instances, outermost first (the
    /// order [`Instance::spawn_through`] takes): `F_1(F_2(...F_k(x)))`,
    /// object space of the innermost to the world. `None` for an empty
    /// path.
    ///
    /// ```
    /// use rayhit::{Instance, exact::AffineMap, glam::Vec3};
    /// let outer = Instance::new([Vec3::X * 2.0, Vec3::Y * 2.0, Vec3::Z * 2.0], Vec3::ZERO).unwrap();
    /// let inner = Instance::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::ONE).unwrap();
    /// let f = AffineMap::of_path(&[&outer, &inner]).unwrap();
    /// // 2 (x + 1): the translation is 2.
    /// assert_eq!(f.translation[1], rayhit::exact::Rational::from_integer(2.into()));
    /// ```
    #[must_use]
    pub fn of_path<V: Vector>(path: &[&Instance<V>]) -> Option<Self> {
        path.iter()
            .map(|inst| Self::of(inst))
            .reduce(|outer, inner| outer.then(&inner))
    }

    /// The composition `self(inner(x))`, exactly.
    ///
    /// ```
    /// use rayhit::{exact::AffineMap, glam::Vec3};
    /// let shift = AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::X).unwrap();
    /// let double = AffineMap::new([Vec3::X * 2.0, Vec3::Y * 2.0, Vec3::Z * 2.0], Vec3::ZERO).unwrap();
    /// // 2 (x + e_x) = 2 x + 2 e_x.
    /// assert_eq!(double.then(&shift).translation[0], rayhit::exact::Rational::from_integer(2.into()));
    /// ```
    #[must_use]
    pub fn then(&self, inner: &AffineMap) -> AffineMap {
        let col = |j: usize| [0, 1, 2].map(|k| inner.matrix[k][j].clone());
        let cols = [col(0), col(1), col(2)];
        AffineMap {
            matrix: [0, 1, 2].map(|i| [0, 1, 2].map(|j| dot(&self.matrix[i], &cols[j]))),
            translation: self.apply(&inner.translation),
        }
    }

    /// `M x + T`, exactly.
    ///
    /// ```
    /// use rayhit::{exact::{AffineMap, oracle}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::ONE).unwrap();
    /// let x = oracle::rv(Vec3::new(0.5, 0.0, -1.0)).unwrap();
    /// assert_eq!(f.apply(&x), oracle::rv(Vec3::new(1.5, 1.0, 0.0)).unwrap());
    /// ```
    #[must_use]
    pub fn apply(&self, x: &R3) -> R3 {
        [0, 1, 2].map(|i| dot(&self.matrix[i], x) + &self.translation[i])
    }

    /// `M x`, exactly: the image of a direction.
    ///
    /// ```
    /// use rayhit::{exact::{AffineMap, oracle}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::ONE).unwrap();
    /// let d = oracle::rv(Vec3::Z).unwrap();
    /// assert_eq!(f.apply_linear(&d), d);
    /// ```
    #[must_use]
    pub fn apply_linear(&self, x: &R3) -> R3 {
        [0, 1, 2].map(|i| dot(&self.matrix[i], x))
    }

    /// The determinant of `M`, exactly.
    ///
    /// ```
    /// use rayhit::{exact::{AffineMap, Rational}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X * 2.0, Vec3::Y, Vec3::Z * -0.5], Vec3::ZERO).unwrap();
    /// assert_eq!(f.determinant(), Rational::from_integer((-1).into()));
    /// ```
    #[must_use]
    pub fn determinant(&self) -> Rational {
        let m = &self.matrix;
        &m[0][0] * self.cofactor(0, 0)
            + &m[0][1] * self.cofactor(0, 1)
            + &m[0][2] * self.cofactor(0, 2)
    }

    fn cofactor(&self, i: usize, j: usize) -> R {
        let m = &self.matrix;
        let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        &m[i1][j1] * &m[i2][j2] - &m[i1][j2] * &m[i2][j1]
    }

    /// The exact inverse map `x -> M^-1 (x - T)`, or `None` when `M` is
    /// singular (its exact determinant is zero).
    ///
    /// ```
    /// use rayhit::{exact::{AffineMap, oracle}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X, Vec3::new(0.5, 1.0, 0.0), Vec3::Z], Vec3::new(0.0, 3.0, 0.0)).unwrap();
    /// let x = oracle::rv(Vec3::new(0.1, 0.2, 0.3)).unwrap();
    /// assert_eq!(f.inverse().unwrap().apply(&f.apply(&x)), x);
    /// assert!(AffineMap::new([Vec3::X, Vec3::X, Vec3::Z], Vec3::ZERO).unwrap().inverse().is_none());
    /// ```
    #[must_use]
    pub fn inverse(&self) -> Option<AffineMap> {
        let det = self.determinant();
        if det.is_zero() {
            return None;
        }
        let inv: [R3; 3] = [0, 1, 2].map(|i| [0, 1, 2].map(|j| self.cofactor(j, i) / &det));
        let t = [0, 1, 2].map(|i| -dot(&inv[i], &self.translation));
        Some(AffineMap {
            matrix: inv,
            translation: t,
        })
    }

    /// The normal of the image of a plane whose normal is `n`: `M^-T n`,
    /// exactly (for `x` on the image plane, `(x - F(q)) . M^-T n =
    /// (M^-1 (x - F(q))) . n`, zero exactly when `F^-1(x)` is on the
    /// plane). Not normalised; `None` when `M` is singular.
    ///
    /// ```
    /// use rayhit::{exact::{AffineMap, oracle}, glam::Vec3};
    /// // A shear along x by z: the plane z = 0 keeps its normal, x = 0 tilts.
    /// let f = AffineMap::new([Vec3::X, Vec3::Y, Vec3::new(1.0, 0.0, 1.0)], Vec3::ZERO).unwrap();
    /// let z = oracle::rv(Vec3::Z).unwrap();
    /// assert_eq!(f.normal(&z).unwrap(), z);
    /// let x = oracle::rv(Vec3::X).unwrap();
    /// assert_eq!(f.normal(&x).unwrap(), oracle::rv(Vec3::new(1.0, 0.0, -1.0)).unwrap());
    /// ```
    #[must_use]
    pub fn normal(&self, n: &R3) -> Option<R3> {
        let det = self.determinant();
        if det.is_zero() {
            return None;
        }
        // (M^-T)_ij = (M^-1)_ji = cofactor_ij / det.
        Some([0, 1, 2].map(|i| {
            let row = [0, 1, 2].map(|j| self.cofactor(i, j));
            dot(&row, n) / &det
        }))
    }
}

/// The largest float at most `x` (`-inf` below the most negative float).
///
/// ```
/// use rayhit::exact::{self, Rational};
/// let third = Rational::new(1.into(), 3.into());
/// let (lo, hi) = (exact::round_down::<f32>(&third), exact::round_up::<f32>(&third));
/// assert!(lo < hi && hi == lo.next_up());
/// assert_eq!(exact::round_down::<f64>(&Rational::from_integer(2.into())), 2.0);
/// ```
#[must_use]
pub fn round_down<F: Scalar>(x: &Rational) -> F {
    let y: F = super::round(x);
    if y == F::INFINITY {
        return F::MAX;
    }
    match r(y) {
        Some(ry) if &ry > x => y.next_down(),
        _ => y,
    }
}

/// The smallest float at least `x` (`+inf` above the largest float).
///
/// ```
/// use rayhit::exact::{self, Rational};
/// let tenth = Rational::new(1.into(), 10.into());
/// assert!(exact::rational(exact::round_up::<f32>(&tenth)).unwrap() >= tenth);
/// ```
#[must_use]
pub fn round_up<F: Scalar>(x: &Rational) -> F {
    -round_down::<F>(&-x)
}

/// The exact image `F(p)` of an object point under `map`, each component
/// with its rounding to nearest (`None` when `p` is not finite). The
/// rounded point is the best a world point can be; a computed one (such
/// as [`Instance::surface_to_world`]'s) is judged against the exact value
/// by [`judge_world_point`].
///
/// ```
/// use rayhit::{Instance, exact::{self, AffineMap}, glam::Vec3};
/// let inst = Instance::new([Vec3::X * 3.0, Vec3::Y, Vec3::Z], Vec3::new(1e4, 0.0, 0.0)).unwrap();
/// let image = exact::instance_point(&AffineMap::of(&inst), Vec3::new(0.1, 2.0, 0.0)).unwrap();
/// // 3 * fl(0.1) + 1e4 is not a float; its nearest one:
/// assert_eq!(image[0].rounded, 10000.3);
/// assert_eq!((image[1].rounded, image[2].rounded), (2.0, 0.0));
/// ```
#[must_use]
pub fn instance_point<V: Vector>(map: &AffineMap, p: V) -> Option<[Exact<V::Scalar>; 3]> {
    Some(map.apply(&rv(p)?).map(Exact::new))
}

/// The exact image of an object box: per world axis, the smallest and the
/// largest coordinate of `F(x)` over the box, each with its rounding to
/// nearest. A world box contains the image exactly when its `min` is at
/// most and its `max` at least these values ([`ImageBox::is_within`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ImageBox<F> {
    /// Per axis, the image's smallest coordinate.
    pub min: [Exact<F>; 3],
    /// Per axis, the image's largest coordinate.
    pub max: [Exact<F>; 3],
}

impl<F: Scalar> ImageBox<F> {
    /// True when `world` contains the exact image, decided exactly: false
    /// for a box with a NaN or an invalid box.
    ///
    /// ```
    /// use rayhit::{Aabb, exact::{self, AffineMap}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::splat(0.1)).unwrap();
    /// let image = exact::instance_box(&f, &Aabb::new(Vec3::ZERO, Vec3::ONE)).unwrap();
    /// assert!(image.is_within(&image.outward::<Vec3>()));
    /// assert!(!image.is_within(&Aabb::new(Vec3::splat(0.2), Vec3::splat(2.0))));
    /// ```
    #[must_use]
    pub fn is_within<V: Vector<Scalar = F>>(&self, world: &Aabb<V>) -> bool {
        world.is_valid()
            && (0..3).all(|i| match (r(world.min[i]), r(world.max[i])) {
                (Some(lo), Some(hi)) => lo <= self.min[i].value && self.max[i].value <= hi,
                _ => false,
            })
    }

    /// The smallest box of floats that contains the exact image: each
    /// `min` rounded down and each `max` rounded up ([`round_down`],
    /// [`round_up`]). An image beyond the largest float gets an infinite
    /// side.
    ///
    /// ```
    /// use rayhit::{Aabb, exact::{self, AffineMap}, glam::Vec3};
    /// let f = AffineMap::new([Vec3::X * 2.0, Vec3::Y, Vec3::Z], Vec3::ZERO).unwrap();
    /// let image = exact::instance_box(&f, &Aabb::new(Vec3::splat(-1.0), Vec3::ONE)).unwrap();
    /// // Exact products and sums: the box is the exact image.
    /// assert_eq!(image.outward::<Vec3>(), Aabb::new(Vec3::new(-2.0, -1.0, -1.0), Vec3::new(2.0, 1.0, 1.0)));
    /// ```
    #[must_use]
    pub fn outward<V: Vector<Scalar = F>>(&self) -> Aabb<V> {
        let lo = |i: usize| round_down::<F>(&self.min[i].value);
        let hi = |i: usize| round_up::<F>(&self.max[i].value);
        Aabb::new(V::new(lo(0), lo(1), lo(2)), V::new(hi(0), hi(1), hi(2)))
    }
}

/// The exact image of the object box `object` under `map` (the question
/// [`Instance::object_to_world_box`] answers conservatively): on world
/// axis `i`, `T_i + sum_j min(M_ij lo_j, M_ij hi_j)` and the same with
/// `max` (each term is linear in one coordinate, so its extreme over the
/// box is at an end of that coordinate's range). `None` when `object` is
/// not valid ([`Aabb::is_valid`]).
///
/// ```
/// use rayhit::{Aabb, Instance, exact::{self, AffineMap}, glam::{Affine3A, Quat, Vec3}};
/// let inst = Instance::from_affine3a(Affine3A::from_rotation_translation(
///     Quat::from_rotation_z(0.7), Vec3::new(1e5, 0.0, 0.0))).unwrap();
/// let object = Aabb::new(Vec3::splat(-1.0), Vec3::ONE);
/// let image = exact::instance_box(&AffineMap::of(&inst), &object).unwrap();
/// // The crate's world box contains the exact image.
/// assert!(image.is_within(&inst.object_to_world_box(&object).unwrap()));
/// assert!(exact::instance_box(&AffineMap::of(&inst), &Aabb::new(Vec3::ONE, Vec3::ZERO)).is_none());
/// ```
#[must_use]
pub fn instance_box<V: Vector>(map: &AffineMap, object: &Aabb<V>) -> Option<ImageBox<V::Scalar>> {
    if !object.is_valid() {
        return None;
    }
    let (lo, hi) = (rv(object.min)?, rv(object.max)?);
    let end = |i: usize, upper: bool| -> R {
        let mut acc = map.translation[i].clone();
        for j in 0..3 {
            let (a, b) = (&map.matrix[i][j] * &lo[j], &map.matrix[i][j] * &hi[j]);
            acc += if (a < b) == upper { b } else { a };
        }
        acc
    };
    Some(ImageBox {
        min: [0, 1, 2].map(|i| Exact::new(end(i, false))),
        max: [0, 1, 2].map(|i| Exact::new(end(i, true))),
    })
}

/// How far apart a world ray and an object ray are at the same `t`, once
/// the object ray's point is mapped to the world exactly: per component,
/// `|F(object.origin + t object.dir) - (world.origin + t world.dir)|`,
/// exactly (the points themselves exact, not rounded). The quantity
/// [`Instance::world_to_object_error`] bounds; [`judge_ray_map`] compares
/// it with a claimed bound. `None` when an input is not finite.
///
/// ```
/// use rayhit::{Instance, Ray, exact::{self, AffineMap}, glam::Vec3};
/// let inst = Instance::new([Vec3::X * 4.0, Vec3::Y * 4.0, Vec3::Z * 4.0], Vec3::ONE).unwrap();
/// let world = Ray::new(Vec3::new(5.0, 1.0, 1.0), Vec3::NEG_X);
/// let object = inst.world_to_object(&world);
/// // A scale by a power of two and a small translation: mapped exactly.
/// let gap = exact::instance_ray_gap(&AffineMap::of(&inst), &world, &object, 3.0).unwrap();
/// assert!(gap.iter().all(|g| *g == exact::Rational::from_integer(0.into())));
/// ```
#[must_use]
pub fn instance_ray_gap<V: Vector>(
    map: &AffineMap,
    world: &Ray<V>,
    object: &Ray<V>,
    t: V::Scalar,
) -> Option<[Rational; 3]> {
    let t = r(t)?;
    let (o, d) = (rv(object.origin)?, rv(object.dir)?);
    let (wo, wd) = (rv(world.origin)?, rv(world.dir)?);
    let mapped = map.apply(&[0, 1, 2].map(|k| &o[k] + &t * &d[k]));
    Some([0, 1, 2].map(|k| (&mapped[k] - (&wo[k] + &t * &wd[k])).abs()))
}

/// A judgement of a claimed world box against the exact image of an
/// object box ([`judge_world_box`]).
#[derive(Clone, Debug, PartialEq)]
pub struct WorldBoxJudgement {
    /// The claimed box contains the exact image (decided exactly).
    pub contains: bool,
    /// How far the claimed box reaches beyond the exact image on its
    /// widest side, in ulps of the image's largest coordinate (the
    /// spacing of floats there); 0 when no side reaches beyond it.
    pub excess_ulps: f64,
    /// How far the exact image sticks out of the claimed box on its worst
    /// side, in the same ulps; 0 when it is contained, infinite for a
    /// claimed box that is not valid (a NaN, `min > max`).
    pub missed_ulps: f64,
}

/// Judges a claimed world box for the object box `object` under `map`:
/// whether it contains the exact image (the guarantee of
/// [`Instance::object_to_world_box`]) and how loose it is. `None` when
/// `object` is not valid.
///
/// ```
/// use rayhit::{Aabb, Instance, exact::{self, AffineMap}, glam::{DAffine3, DQuat, DVec3}};
/// let inst = Instance::from_daffine3(DAffine3::from_rotation_translation(
///     DQuat::from_rotation_x(0.3), DVec3::new(0.0, 5e4, 0.0))).unwrap();
/// let object = Aabb::new(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
/// let f = AffineMap::of(&inst);
/// let j = exact::judge_world_box(&f, &object, &inst.object_to_world_box(&object).unwrap()).unwrap();
/// assert!(j.contains && j.excess_ulps < 16.0);
/// // The box of the corners' rounded images is not enough in general.
/// let shrunk = Aabb::new(DVec3::ZERO, DVec3::ONE);
/// assert!(!exact::judge_world_box(&f, &object, &shrunk).unwrap().contains);
/// ```
#[must_use]
pub fn judge_world_box<V: Vector>(
    map: &AffineMap,
    object: &Aabb<V>,
    claimed: &Aabb<V>,
) -> Option<WorldBoxJudgement> {
    let image = instance_box(map, object)?;
    let scale = image
        .min
        .iter()
        .chain(&image.max)
        .map(|e| to_f64(&e.value).abs())
        .fold(0.0, f64::max);
    let unit = ulp::<V::Scalar>(scale);
    let contains = image.is_within(claimed);
    if !claimed.is_valid() {
        return Some(WorldBoxJudgement {
            contains,
            excess_ulps: 0.0,
            missed_ulps: f64::INFINITY,
        });
    }
    let (mut excess, mut missed) = (0.0f64, 0.0f64);
    for i in 0..3 {
        // Valid boxes are finite or infinite; an infinite side is
        // infinitely loose.
        let below =
            r(claimed.min[i]).map_or(f64::INFINITY, |lo| to_f64(&(&image.min[i].value - lo)));
        let above =
            r(claimed.max[i]).map_or(f64::INFINITY, |hi| to_f64(&(hi - &image.max[i].value)));
        for side in [below, above] {
            excess = excess.max(side);
            missed = missed.max(-side);
        }
    }
    Some(WorldBoxJudgement {
        contains,
        excess_ulps: excess / unit,
        missed_ulps: missed / unit,
    })
}

/// A judgement of a claimed point (or offset) against its exact value and
/// a claimed error bound ([`judge_world_point`], [`judge_ray_map`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PointJudgement {
    /// Every component's error is within the claimed bound, decided
    /// exactly (false when the claim or the bound is NaN or infinite).
    pub within: bool,
    /// Each component's error, exactly, as the nearest `f64`.
    pub error: [f64; 3],
    /// The largest component error in ulps of the exact point's largest
    /// coordinate (the spacing of floats there).
    pub error_ulps: f64,
}

fn judge_errors<F: Scalar>(errors: &[R; 3], scale: f64, bound: [F; 3]) -> PointJudgement {
    let within = (0..3).all(|k| r(bound[k]).is_some_and(|b| errors[k] <= b));
    let error = [0, 1, 2].map(|k| to_f64(&errors[k]));
    let worst = error.iter().copied().fold(0.0, f64::max);
    PointJudgement {
        within,
        error,
        error_ulps: worst / ulp::<F>(scale),
    }
}

/// Judges a claimed world point for the object point `object_point` under
/// `map`, with its claimed error bound per component (as
/// [`Instance::surface_to_world`] gives in `point_error`): whether
/// `|claimed - F(object_point)| <= bound` in every component. `None` when
/// `object_point` is not finite; a claim that is not finite is not within.
///
/// ```
/// use rayhit::{Instance, SurfacePoint, exact::{self, AffineMap}, glam::{Affine3A, Quat, Vec3}};
/// let inst = Instance::from_affine3a(Affine3A::from_scale_rotation_translation(
///     Vec3::splat(0.3), Quat::from_rotation_y(2.0), Vec3::new(-3e3, 7.0, 1e4))).unwrap();
/// let p = Vec3::new(0.25, -1.5, 3.0);
/// let at = SurfacePoint { point: p, point_error: Vec3::ZERO, normal: Vec3::Z, normal_error: Vec3::ZERO };
/// let world = inst.surface_to_world(&at);
/// let j = exact::judge_world_point(&AffineMap::of(&inst), p, world.point, world.point_error).unwrap();
/// assert!(j.within);
/// ```
#[must_use]
pub fn judge_world_point<V: Vector>(
    map: &AffineMap,
    object_point: V,
    claimed: V,
    bound: V,
) -> Option<PointJudgement> {
    let exact = map.apply(&rv(object_point)?);
    let scale = exact.iter().map(|x| to_f64(x).abs()).fold(0.0, f64::max);
    let errors: [R; 3] = match rv(claimed) {
        Some(c) => [0, 1, 2].map(|k| (&c[k] - &exact[k]).abs()),
        None => {
            return Some(PointJudgement {
                within: false,
                error: [f64::INFINITY; 3],
                error_ulps: f64::INFINITY,
            });
        }
    };
    Some(judge_errors(
        &errors,
        scale,
        [bound.x(), bound.y(), bound.z()],
    ))
}

/// Judges a claimed bound on how far a world ray and its object ray are
/// apart at `t` ([`instance_ray_gap`]; the claim
/// [`InstanceRayError::at`](crate::instance::InstanceRayError::at) makes): whether
/// the exact gap is within `bound` in every component. The error in ulps
/// is measured at the world ray's point at `t`. `None` when an input
/// (but the bound) is not finite.
///
/// ```
/// use rayhit::{Instance, Ray, exact::{self, AffineMap}, glam::{Affine3A, Quat, Vec3}};
/// let inst = Instance::from_affine3a(Affine3A::from_rotation_translation(
///     Quat::from_rotation_z(1.0), Vec3::splat(100.0))).unwrap();
/// let world = Ray::new(Vec3::new(90.0, 95.0, 101.0), Vec3::new(1.0, 0.5, -0.25));
/// let object = inst.world_to_object(&world);
/// let err = inst.world_to_object_error(&world);
/// let f = AffineMap::of(&inst);
/// for t in [0.0, 1.0, 1e3] {
///     assert!(exact::judge_ray_map(&f, &world, &object, t, err.at(t)).unwrap().within);
/// }
/// ```
#[must_use]
pub fn judge_ray_map<V: Vector>(
    map: &AffineMap,
    world: &Ray<V>,
    object: &Ray<V>,
    t: V::Scalar,
    bound: V,
) -> Option<PointJudgement> {
    let gap = instance_ray_gap(map, world, object, t)?;
    let at = world.origin + world.dir * t;
    let scale = (0..3).map(|k| at[k].to_f64().abs()).fold(0.0, f64::max);
    Some(judge_errors(&gap, scale, [bound.x(), bound.y(), bound.z()]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

    #[test]
    fn bad_input_gives_none() {
        let f = AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::ZERO).unwrap();
        assert!(AffineMap::new([Vec3::X, Vec3::Y, Vec3::Z], Vec3::INFINITY).is_none());
        assert!(instance_point(&f, Vec3::NAN).is_none());
        let inverted = Aabb::new(Vec3::ONE, Vec3::ZERO);
        assert!(instance_box(&f, &inverted).is_none());
        assert!(judge_world_box(&f, &inverted, &inverted).is_none());
        let ok = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let j = judge_world_box(&f, &ok, &inverted).unwrap();
        assert!(!j.contains && j.missed_ulps == f64::INFINITY);
        let nan = Aabb::new(Vec3::ZERO, Vec3::new(1.0, f32::NAN, 1.0));
        assert!(!judge_world_box(&f, &ok, &nan).unwrap().contains);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert!(instance_ray_gap(&f, &ray, &ray, f32::NAN).is_none());
        assert!(
            !judge_ray_map(&f, &ray, &ray, 1.0, Vec3::NAN)
                .unwrap()
                .within
        );
        let j = judge_world_point(&f, Vec3::ONE, Vec3::INFINITY, Vec3::ONE).unwrap();
        assert!(!j.within);
        assert!(AffineMap::of_path::<DVec3>(&[]).is_none());
    }

    #[test]
    fn directed_rounding_brackets_and_saturates() {
        let third = Rational::new(1.into(), 3.into());
        for x in [third.clone(), -third] {
            let (lo, hi) = (round_down::<f32>(&x), round_up::<f32>(&x));
            assert!(r(lo).unwrap() < x && x < r(hi).unwrap() && lo.next_up() == hi);
        }
        let huge = r(f64::MAX).unwrap() * Rational::from_integer(2.into());
        assert_eq!(round_down::<f64>(&huge), f64::MAX);
        assert_eq!(round_up::<f64>(&huge), f64::INFINITY);
        assert_eq!(round_down::<f64>(&-huge.clone()), f64::NEG_INFINITY);
        assert_eq!(round_up::<f32>(&Rational::zero()), 0.0);
    }
}
