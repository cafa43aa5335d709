//! The sphere in exact arithmetic: whether a ray's line meets a closed
//! ball, and where its two crossings lie against exact values of `t`.
//!
//! The crossings are roots of a quadratic with rational coefficients, so
//! they are irrational in general; every question a kernel's contract
//! asks of them (is there one, is it above this float, below that one) is
//! the sign of a polynomial in the inputs, answered here without a square
//! root.

use super::values::*;
use crate::{Ray, Scalar, Side, Sphere, Vector};
use core::cmp::Ordering;
use num_traits::{Signed, Zero};

/// A ray's line `o + t d` against the sphere `|p - c| = r`: the quadratic
/// `Q(t) = |o + t d - c|^2 - r^2 = a t^2 - 2 b t + k`, exactly, with `a =
/// d . d`, `b = d . (c - o)` and `k = |c - o|^2 - r^2`. `Q` is negative
/// inside the ball, so the line enters at the smaller root `t-` and leaves
/// at the larger `t+`.
#[derive(Debug, Clone)]
pub struct ExactSphere {
    /// `d . d`, positive for a valid ray.
    pub a: R,
    /// `d . (c - o)`.
    pub b: R,
    /// `|c - o|^2 - r^2`: negative for an origin inside the ball, zero on
    /// the sphere.
    pub k: R,
}

impl ExactSphere {
    /// `b^2 - a k`, a quarter of the discriminant: the line meets the
    /// closed ball where it is at least zero, and touches the sphere where
    /// it is zero. (`a` times the squared distance from the centre to the
    /// line is `a r^2 - disc`.)
    #[must_use]
    pub fn discriminant(&self) -> R {
        &self.b * &self.b - &self.a * &self.k
    }

    /// The line meets the closed ball (touching included).
    #[must_use]
    pub fn line_hits(&self) -> bool {
        !self.discriminant().is_negative()
    }

    /// `Q(t)`, exactly.
    #[must_use]
    pub fn q(&self, t: &R) -> R {
        (&self.a * t - int(2) * &self.b) * t + &self.k
    }

    /// `b / a`: where the line passes nearest the centre, half way between
    /// the crossings.
    #[must_use]
    pub fn nearest(&self) -> R {
        &self.b / &self.a
    }

    /// The entry crossing `t-` against `x`: `Less` where `t- < x`; `None`
    /// where the line misses the ball. Below the nearest point `Q`
    /// decreases through `t-`, so there the sign of `Q(x)` places `x`.
    #[must_use]
    pub fn entry_cmp(&self, x: &R) -> Option<Ordering> {
        self.place(Side::Front).map(|place| place(x))
    }

    /// The exit crossing `t+` against `x`, as [`ExactSphere::entry_cmp`];
    /// above the nearest point `Q` increases through `t+`.
    #[must_use]
    pub fn exit_cmp(&self, x: &R) -> Option<Ordering> {
        self.place(Side::Back).map(|place| place(x))
    }

    /// The crossing on `side` against any `x` (the discriminant and the
    /// nearest point computed once, for the many comparisons of a
    /// rounding); `None` where the line misses.
    pub(crate) fn place(&self, side: Side) -> Option<impl Fn(&R) -> Ordering + '_> {
        let disc = self.discriminant();
        if disc.is_negative() {
            return None;
        }
        let (v, touching) = (self.nearest(), disc.is_zero());
        Some(move |x: &R| match (side, x.cmp(&v)) {
            (_, Ordering::Equal) if touching => Ordering::Equal,
            (Side::Front, Ordering::Less) => zero_cmp(&self.q(x)),
            (Side::Front, _) => Ordering::Less,
            (Side::Back, Ordering::Greater) => zero_cmp(&self.q(x)).reverse(),
            (Side::Back, _) => Ordering::Greater,
        })
    }

    /// Whether the entry crossing lies in `(lo, hi]` (`hi` `None`: no
    /// upper end); `false` where the line misses.
    #[must_use]
    pub fn entry_in(&self, lo: &R, hi: Option<&R>) -> bool {
        self.entry_cmp(lo) == Some(Ordering::Greater)
            && hi.is_none_or(|h| self.entry_cmp(h) != Some(Ordering::Greater))
    }

    /// Whether the exit crossing lies in `(lo, hi]`, as
    /// [`ExactSphere::entry_in`].
    #[must_use]
    pub fn exit_in(&self, lo: &R, hi: Option<&R>) -> bool {
        self.exit_cmp(lo) == Some(Ordering::Greater)
            && hi.is_none_or(|h| self.exit_cmp(h) != Some(Ordering::Greater))
    }
}

impl ExactSphere {
    /// The crossing on `side` against `x`: the entry `t-` for
    /// [`Side::Front`], the exit `t+` for [`Side::Back`] (see
    /// [`ExactSphere::entry_cmp`]); `None` where the line misses the ball.
    #[must_use]
    pub fn crossing_cmp(&self, side: Side, x: &R) -> Option<Ordering> {
        match side {
            Side::Front => self.entry_cmp(x),
            Side::Back => self.exit_cmp(x),
        }
    }

    /// The first crossing in `(lo, hi]` (`hi` `None`: no upper end): the
    /// entry ([`Side::Front`]) where it is in, else the exit
    /// ([`Side::Back`]) where it is, else `None`. A tangent line's double
    /// crossing is the entry. This is the crossing the ray/sphere test
    /// reports.
    #[must_use]
    pub fn first_in(&self, lo: &R, hi: Option<&R>) -> Option<Side> {
        if self.entry_in(lo, hi) {
            Some(Side::Front)
        } else if self.exit_in(lo, hi) {
            Some(Side::Back)
        } else {
            None
        }
    }

    /// The crossing on `side` as an `f64`, roughly (the stable pair of
    /// roots from `a`, `b`, `k` and the discriminant, each rounded to
    /// `f64` once): a starting point, not an answer; NaN where the line
    /// misses.
    #[must_use]
    pub fn estimate(&self, side: Side) -> f64 {
        let (a, b, k) = (to_f64(&self.a), to_f64(&self.b), to_f64(&self.k));
        let disc = to_f64(&self.discriminant());
        if disc < 0.0 {
            return f64::NAN;
        }
        // q = b + sign(b) sqrt(disc): the roots are q / a and k / q.
        let q = if b >= 0.0 {
            b + disc.sqrt()
        } else {
            b - disc.sqrt()
        };
        let (far, near) = (q / a, k / q);
        match (side, b >= 0.0) {
            (Side::Front, true) | (Side::Back, false) => near,
            _ => far,
        }
    }

    /// The crossing on `side`, a positive root, rounded to the nearest
    /// float of precision `F` (ties to even; the infinity at or above
    /// `MAX` plus half an ulp): bracketed between floats with
    /// [`ExactSphere::crossing_cmp`] from [`ExactSphere::estimate`] (see
    /// [`nearest_float`]), never a floating-point square root alone.
    /// Zero where the crossing is not positive; `None` where the line
    /// misses.
    ///
    /// ```
    /// use rayhit::exact::oracle::sphere;
    /// use rayhit::{Ray, Side, glam::Vec3};
    /// // From (0, 0, -3) along z at the unit sphere around (0.5, 0, 0):
    /// // t = 3 -+ sqrt(3) / 2.
    /// let ray = Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z);
    /// let s = sphere(&ray, Vec3::new(0.5, 0.0, 0.0), 1.0).unwrap();
    /// let half_root3 = 3f64.sqrt() / 2.0;
    /// assert_eq!(s.rounded::<f32>(Side::Front), Some((3.0 - half_root3) as f32));
    /// // 3 + sqrt(3) / 2 = 3.86602540378443864676...: the nearest f64 is
    /// // 3.866025403784439; the same sum in f64 rounds twice and lands one
    /// // float below it.
    /// assert_eq!(s.rounded::<f64>(Side::Back), Some(3.866025403784439));
    /// assert_eq!(3.0 + half_root3, 3.866025403784439f64.next_down());
    /// ```
    #[must_use]
    pub fn rounded<F: Scalar>(&self, side: Side) -> Option<F> {
        let place = self.place(side)?;
        Some(nearest_float(self.estimate(side), place))
    }
}

/// The sphere case is outside the ray/sphere test's rounding band (the
/// `t_max` form's: see [`Sphere`'s `hit`](crate::Sphere#method.hit)):
/// `false` (an `Edge` case) where
///
/// - the line is within twice the miss test's band of tangent: `|b^2 - a
///   k|` at most twice that test's bound on the discriminant's error
///   (`E_x` in `src/sphere/roots.rs`), evaluated for the exact values
///   with every computed value replaced by an upper bound of it (there a
///   false hit, or a `t` as ill-conditioned as a square root, is
///   legitimate);
/// - the line meets the ball and the origin is within twice the
///   rounding of `k = |o - c|^2 - r^2` of the sphere (`2 (gamma(8) (|o -
///   c|^2 (1 + gamma(3)) + r^2 (1 + u)) + 2 MIN_POSITIVE)`: there the
///   test may count the origin as on the sphere, dropping the entry or
///   the exit just ahead of it);
/// - the first crossing ahead of the origin (the entry, else the exit) is
///   within [`Sphere`'s `hit_error`](crate::Sphere#method.hit_error) of
///   `0` or of `t_max` (of `MAX` for an infinite `t_max`), or that bound
///   is infinite.
///
/// Elsewhere a kernel with the crate's guarantees answers hit or miss and
/// the side as the exact answer does. False when a value is not finite
/// or the direction is zero.
#[must_use]
pub fn sphere_clear<V: Vector>(ray: &Ray<V>, sph: &Sphere<V>, t_max: V::Scalar) -> bool {
    let Some(e) = sphere(ray, sph.center, sph.radius) else {
        return false;
    };
    let (Some(o), Some(d), Some(c), Some(radius)) = (
        rv(ray.origin),
        rv(ray.dir),
        rv(sph.center),
        r(sph.radius.abs()),
    ) else {
        return false;
    };
    if t_max.partial_cmp(&t_max).is_none() {
        return false;
    }
    let u = V::Scalar::UNIT_ROUNDOFF.to_f64();
    let g = |n: f64| n * u / (1.0 - n * u);
    let tiny = V::Scalar::MIN_POSITIVE.to_f64();
    let f = sub(&o, &c);
    let (fx, dx, cx) = (
        f.clone().map(|x| to_f64(&x).abs()),
        d.clone().map(|x| to_f64(&x).abs()),
        cross(&f, &d).map(|x| to_f64(&x).abs()),
    );
    let (a, rr) = (to_f64(&e.a), to_f64(&(&radius * &radius)));
    // The miss test's `E_x`, every computed value replaced by a bound.
    let m = fx[0].max(fx[1]).max(fx[2]) * (dx[0] + dx[1] + dx[2]);
    let ec = g(3.0) * m + 2.0 * tiny;
    let ar = a * rr * (1.0 + g(5.0)) + a * tiny;
    let cc = cx.iter().map(|x| (x + ec) * (x + ec)).sum::<f64>() * (1.0 + g(4.0));
    let c1 = cx.iter().sum::<f64>() + 3.0 * ec;
    let err_x = g(5.0) * ar
        + g(4.0) * cc
        + ec * (2.0 * c1 + 3.0 * ec)
        + u * (ar + cc)
        + (a * (1.0 + g(4.0)) + 8.0) * tiny;
    let ff = fx.iter().map(|x| x * x).sum::<f64>();
    let err_k = g(8.0) * (ff * (1.0 + g(3.0)) + rr * (1.0 + u)) + 2.0 * tiny;
    let (Some(band_x), Some(band_k)) = (R::from_float(2.0 * err_x), R::from_float(2.0 * err_k))
    else {
        return false;
    };
    let disc = e.discriminant();
    if disc.abs() <= band_x {
        return false;
    }
    if disc.is_negative() {
        return true;
    }
    if e.k.abs() <= band_k {
        return false;
    }
    let zero = int(0);
    let Some(side) = e.first_in(&zero, None) else {
        // Both crossings behind the origin.
        return true;
    };
    let Some(t) = e.rounded::<V::Scalar>(side) else {
        return false;
    };
    let hit = crate::SphereHit { t, side };
    let Some(err) = r(crate::Surface::hit_error(sph, ray, &hit).next_up()) else {
        return false;
    };
    let end = limit(t_max).unwrap_or_else(|| constant(V::Scalar::MAX));
    let place = |x: &R| e.crossing_cmp(side, x);
    place(&err) == Some(Ordering::Greater)
        && (place(&(&end - &err)) == Some(Ordering::Less)
            || place(&(&end + &err)) == Some(Ordering::Greater))
}

/// `x` against zero.
fn zero_cmp(x: &R) -> Ordering {
    if x.is_negative() {
        Ordering::Less
    } else if x.is_zero() {
        Ordering::Equal
    } else {
        Ordering::Greater
    }
}

/// Exact ray/sphere for the sphere with centre `center` and radius
/// `radius` (its magnitude: a sphere of radius `-r` is the sphere of radius
/// `r`); `None` when a value is not finite or the direction is zero.
#[must_use]
pub fn sphere<V: Vector>(ray: &Ray<V>, center: V, radius: V::Scalar) -> Option<ExactSphere> {
    let (o, d, c, rr) = (rv(ray.origin)?, rv(ray.dir)?, rv(center)?, r(radius)?);
    let a = dot(&d, &d);
    if a.is_zero() {
        return None;
    }
    let f = sub(&c, &o);
    Some(ExactSphere {
        b: dot(&d, &f),
        k: dot(&f, &f) - &rr * &rr,
        a,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glam::DVec3;
    use crate::testing::Draws;

    /// A ray along `x` through the centre of the unit sphere, from two
    /// units before it: in at `t = 1`, out at `t = 3`, exactly.
    #[test]
    fn crossings_through_the_centre() {
        let ray = Ray::new(DVec3::new(-2.0, 0.0, 0.0), DVec3::X);
        let s = sphere(&ray, DVec3::ZERO, 1.0).unwrap();
        assert_eq!(s.entry_cmp(&int(1)), Some(Ordering::Equal));
        assert_eq!(s.exit_cmp(&int(3)), Some(Ordering::Equal));
        assert_eq!(s.entry_cmp(&int(2)), Some(Ordering::Less));
        assert_eq!(s.exit_cmp(&int(2)), Some(Ordering::Greater));
        assert!(s.entry_in(&int(0), Some(&int(1))) && !s.entry_in(&int(1), None));
        assert!(s.exit_in(&int(1), None) && !s.exit_in(&int(0), Some(&dyadic(5, -1))));
        // A radius of -1 is the same sphere.
        let neg = sphere(&ray, DVec3::ZERO, -1.0).unwrap();
        assert_eq!(neg.discriminant(), s.discriminant());
    }

    /// A ray touching the sphere: one double root at the nearest point; a
    /// ray one ulp outside misses, one ulp inside crosses twice.
    #[test]
    fn a_touching_ray_has_one_double_crossing() {
        let touch = Ray::new(DVec3::new(-2.0, 1.0, 0.0), DVec3::X);
        let s = sphere(&touch, DVec3::ZERO, 1.0).unwrap();
        assert!(s.discriminant().is_zero());
        assert_eq!(s.entry_cmp(&int(2)), Some(Ordering::Equal));
        assert_eq!(s.exit_cmp(&int(2)), Some(Ordering::Equal));
        let outside = Ray::new(DVec3::new(-2.0, 1f64.next_up(), 0.0), DVec3::X);
        assert!(!sphere(&outside, DVec3::ZERO, 1.0).unwrap().line_hits());
        let inside = Ray::new(DVec3::new(-2.0, 1f64.next_down(), 0.0), DVec3::X);
        let s = sphere(&inside, DVec3::ZERO, 1.0).unwrap();
        assert!(s.discriminant().is_positive());
        assert_eq!(s.entry_cmp(&int(2)), Some(Ordering::Less));
        assert_eq!(s.exit_cmp(&int(2)), Some(Ordering::Greater));
    }

    /// An origin inside: the entry is behind it (`t- < 0`), the exit ahead.
    #[test]
    fn from_inside_the_entry_is_behind() {
        let ray = Ray::new(DVec3::new(0.25, -0.5, 0.125), DVec3::new(0.3, 0.2, -0.7));
        let s = sphere(&ray, DVec3::ZERO, 1.0).unwrap();
        assert!(s.k.is_negative());
        assert_eq!(s.entry_cmp(&int(0)), Some(Ordering::Less));
        assert_eq!(s.exit_cmp(&int(0)), Some(Ordering::Greater));
        assert!(s.exit_in(&int(0), None) && !s.entry_in(&int(0), None));
    }

    /// Against the roots in `f64` where they are well conditioned (the
    /// line well inside the ball): each root lies between its `f64`
    /// value moved by a relative `1e-9` either way. Values a few powers of
    /// two apart, so the formula's rounding is far below that.
    #[test]
    fn against_f64_roots_where_well_conditioned() {
        let mut draws = Draws(71);
        let mut checked = 0;
        for _ in 0..2000 {
            let v = |d: &mut Draws| DVec3::new(d.coordinate(4), d.coordinate(4), d.coordinate(4));
            let (o, dir, c) = (v(&mut draws), v(&mut draws), v(&mut draws));
            let radius = draws.coordinate(4).abs() + 0.5;
            let ray = Ray::new(o, dir);
            let Some(s) = sphere(&ray, c, radius) else {
                continue;
            };
            let (a, f) = (dir.dot(dir), c - o);
            let b = dir.dot(f);
            let disc = b * b - a * (f.dot(f) - radius * radius);
            if disc < 0.25 * b * b + 0.25 * a * radius * radius {
                continue;
            }
            let root = disc.sqrt();
            for (t, cmp) in [
                (
                    (b - root) / a,
                    ExactSphere::entry_cmp as fn(&ExactSphere, &R) -> Option<Ordering>,
                ),
                ((b + root) / a, ExactSphere::exit_cmp),
            ] {
                let eps = 1e-9 * (t.abs() + b.abs() / a + 1.0);
                assert_eq!(
                    cmp(&s, &R::from_float(t - eps).unwrap()),
                    Some(Ordering::Greater)
                );
                assert_eq!(
                    cmp(&s, &R::from_float(t + eps).unwrap()),
                    Some(Ordering::Less)
                );
            }
            checked += 1;
        }
        assert!(checked > 200, "{checked}");
    }
}
