//! The sphere in exact arithmetic: whether a ray's line meets a closed
//! ball, and where its two crossings lie against exact values of `t`.
//!
//! The crossings are roots of a quadratic with rational coefficients, so
//! they are irrational in general; every question a kernel's contract
//! asks of them (is there one, is it above this float, below that one) is
//! the sign of a polynomial in the inputs, answered here without a square
//! root.

use super::values::*;
use crate::{Ray, Vector};
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
        let disc = self.discriminant();
        if disc.is_negative() {
            return None;
        }
        let v = self.nearest();
        Some(match x.cmp(&v) {
            Ordering::Greater => Ordering::Less,
            Ordering::Equal if disc.is_zero() => Ordering::Equal,
            Ordering::Equal => Ordering::Less,
            Ordering::Less => zero_cmp(&self.q(x)),
        })
    }

    /// The exit crossing `t+` against `x`, as [`ExactSphere::entry_cmp`];
    /// above the nearest point `Q` increases through `t+`.
    #[must_use]
    pub fn exit_cmp(&self, x: &R) -> Option<Ordering> {
        let disc = self.discriminant();
        if disc.is_negative() {
            return None;
        }
        let v = self.nearest();
        Some(match x.cmp(&v) {
            Ordering::Less => Ordering::Greater,
            Ordering::Equal if disc.is_zero() => Ordering::Equal,
            Ordering::Equal => Ordering::Greater,
            Ordering::Greater => zero_cmp(&self.q(x)).reverse(),
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
