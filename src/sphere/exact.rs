//! The exact signs that place a ray's crossings with a sphere against a
//! float `t`: the fallback of the sphere's interval form (and of its
//! `t_max` form where the error bounds are unusable), taken only where a
//! crossing lies within its error bound of an end or the line is within
//! rounding of tangent.
//!
//! With `f = c - o`, the line `o + t d` meets the sphere where `Q(t) = a
//! t^2 - 2 beta t + k` is zero: `a = d . d`, `beta = d . f`, `k = f . f -
//! r^2`. It meets the closed ball where `beta^2 - a k >= 0`, and a float
//! `x` lies against the crossings by the signs of `a x - beta` (which
//! side of the nearest point `beta / a`) and `Q(x)` (inside or outside the
//! ball). Each is a sum of products of up to four floats (a difference
//! held as an exact pair, Knuth's two-sum), expanded exactly and summed
//! as a floating-point expansion (Shewchuk, 1997), as
//! [`PlaneCrossing`](crate::ray::PlaneCrossing) does for planes.

use core::cmp::Ordering;

use crate::num::exact_sign::{Expansion, exponent, scale2, two_diff};
use crate::ray::ExactPlace;

/// Which of the two crossings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Root {
    /// The smaller root `t-`, where the line enters the ball.
    Entry,
    /// The larger root `t+`, where it leaves.
    Exit,
}

/// The exact quadratic of a line against a sphere, scaled (for `f64`
/// inputs) so that its values are near one.
///
/// Exactness: for `f32` inputs every factor is an `f32` value or the
/// rounding error of an `f32` difference, a multiple of `2^-149` below
/// `2^129`, so every product of four and its successive rounding errors
/// are far inside `f64`'s range: the signs are always exact. For `f64`
/// inputs `f` (with `r`) and `d` are each scaled by a power of two to put
/// their largest magnitude in `[1, 2)`, and `x` by the matching power
/// (`X = x 2^(ed - ef)`, with `Q(x) = 2^(2 ef) (a' X^2 - 2 beta' X + k')`
/// and `a x - beta = 2^(ed + ef) (a' X - beta')`). Then `a' >= 1`, `|beta'|
/// <= |d'| |f'| < 12.1` and `|k'| < 12.1`, so for `|X| >= 64` the signs
/// are those of `a' X^2` and `X`, decided without products. Otherwise the
/// products are exact while every nonzero scaled factor (the
/// differences' rounding errors included, and `X`) is at least `2^-150`
/// (a product of four is then at least `2^-600` and its last rounding
/// error at least `2^-760`, above `2^-969`); beyond that range the signs
/// are not guaranteed. A non-finite term gives `None`.
pub(crate) struct SphereSigns {
    /// `c - o`, exact pairs, scaled by `2^-ef`.
    f: [(f64, f64); 3],
    /// The direction, scaled by `2^-ed`.
    d: [f64; 3],
    /// `|r|`, scaled by `2^-ef`.
    r: f64,
    /// `ed - ef`.
    shift: i32,
    /// Whether the values were scaled (`f64` inputs).
    scaled: bool,
}

impl SphereSigns {
    /// From the origin, direction, centre and radius as `f64`; `scale`
    /// for `f64` inputs.
    pub(crate) fn new(o: [f64; 3], d: [f64; 3], c: [f64; 3], r: f64, scale: bool) -> Self {
        let mut f = [0, 1, 2].map(|i| two_diff(c[i], o[i]));
        let mut r = r.abs();
        let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, x| m.max(x.abs()));
        let (mut ef, mut ed) = (0, 0);
        if scale {
            let mf = largest(&mut f.iter().map(|p| p.0).chain([r]));
            let md = largest(&mut d.iter().copied());
            if mf > 0.0 && mf.is_finite() {
                ef = exponent(mf);
            }
            if md > 0.0 && md.is_finite() {
                ed = exponent(md);
            }
            for p in &mut f {
                *p = (scale2(p.0, -ef), scale2(p.1, -ef));
            }
            r = scale2(r, -ef);
        }
        Self {
            f,
            d: d.map(|x| scale2(x, -ed)),
            r,
            shift: ed - ef,
            scaled: scale,
        }
    }

    /// The terms of `beta = d . f`: two products per component.
    fn beta_terms(&self) -> [[f64; 2]; 6] {
        let (d, f) = (self.d, self.f);
        [
            [d[0], f[0].0],
            [d[1], f[1].0],
            [d[2], f[2].0],
            [d[0], f[0].1],
            [d[1], f[1].1],
            [d[2], f[2].1],
        ]
    }

    /// The terms of `k = f . f - r^2` with their signs (`true`: subtract).
    fn k_terms(&self) -> [([f64; 2], bool); 10] {
        let f = self.f;
        let mut out = [([0.0; 2], false); 10];
        for i in 0..3 {
            out[3 * i] = ([f[i].0, f[i].0], false);
            out[3 * i + 1] = ([f[i].0, 2.0 * f[i].1], false);
            out[3 * i + 2] = ([f[i].1, f[i].1], false);
        }
        out[9] = ([self.r, self.r], true);
        out
    }

    /// The sign of `beta^2 - a k`: the line meets the closed ball where it
    /// is not negative.
    pub(crate) fn disc_sign(&self) -> Option<Ordering> {
        let mut e = Expansion::new();
        let beta = self.beta_terms();
        for p in &beta {
            for q in &beta {
                e.add_product(&[p[0], p[1], q[0], q[1]], false);
            }
        }
        for &di in &self.d {
            for (p, neg) in self.k_terms() {
                e.add_product(&[di, di, p[0], p[1]], !neg);
            }
        }
        e.sign()
    }

    /// `x` scaled as the quadratic is, or the sign of `x` where `|X| >= 64`
    /// (see the type's documentation).
    fn scaled_x(&self, x: f64) -> Result<f64, Ordering> {
        if !self.scaled {
            return Ok(x);
        }
        let big = x.is_infinite() || (x != 0.0 && exponent(x) + self.shift >= 6);
        if big {
            return Err(if x > 0.0 {
                Ordering::Greater
            } else {
                Ordering::Less
            });
        }
        Ok(scale2(x, self.shift))
    }

    /// The sign of `a x - beta`: `x` against the nearest point `beta / a`.
    fn lin_sign(&self, x: f64) -> Option<Ordering> {
        let x = match self.scaled_x(x) {
            Ok(x) => x,
            Err(sign) => return Some(sign),
        };
        let mut e = Expansion::new();
        for &di in &self.d {
            e.add_product(&[di, di, x], false);
        }
        for p in self.beta_terms() {
            e.add_product(&p, true);
        }
        e.sign()
    }

    /// The sign of `Q(x)`: negative inside the ball.
    fn q_sign(&self, x: f64) -> Option<Ordering> {
        let x = match self.scaled_x(x) {
            Ok(x) => x,
            Err(_) => return Some(Ordering::Greater),
        };
        let mut e = Expansion::new();
        for &di in &self.d {
            e.add_product(&[di, di, x, x], false);
        }
        let minus_2x = -2.0 * x;
        for p in self.beta_terms() {
            e.add_product(&[p[0], p[1], minus_2x], false);
        }
        for (p, neg) in self.k_terms() {
            e.add_product(&p, neg);
        }
        e.sign()
    }

    /// The crossing `root` against `x` (`Greater` where the crossing is
    /// above `x`), for a line that meets the ball. Below the nearest
    /// point `Q` falls through `t-`, above it rises through `t+`; at the
    /// nearest point itself both crossings are there only where the line
    /// touches the sphere.
    pub(crate) fn place(&self, root: Root, x: f64) -> Option<Ordering> {
        let side = self.lin_sign(x)?;
        Some(match (root, side) {
            (Root::Entry, Ordering::Greater) | (Root::Exit, Ordering::Less) => {
                if root == Root::Entry {
                    Ordering::Less
                } else {
                    Ordering::Greater
                }
            }
            (_, Ordering::Equal) => {
                if self.disc_sign()? == Ordering::Equal {
                    Ordering::Equal
                } else if root == Root::Entry {
                    Ordering::Less
                } else {
                    Ordering::Greater
                }
            }
            (Root::Entry, _) => self.q_sign(x)?,
            (Root::Exit, _) => self.q_sign(x)?.reverse(),
        })
    }
}

/// One crossing of a [`SphereSigns`] line, for the interval decision.
pub(crate) struct SphereCrossing {
    pub(crate) signs: SphereSigns,
    pub(crate) root: Root,
}

impl ExactPlace for SphereCrossing {
    fn exists(&self) -> Option<bool> {
        Some(self.signs.disc_sign()? != Ordering::Less)
    }

    fn place(&self, x: f64) -> Option<Ordering> {
        self.signs.place(self.root, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::oracle::{self, R};
    use crate::testing::Draws;
    use crate::{Ray, Scalar, Vector};
    use glam::{DVec3, Vec3};
    use std::vec;

    /// The signs against the exact module's big rationals (an independent
    /// computation: the quadratic's coefficients as rationals), on lines
    /// that miss, touch and cross, for `x` at random, at the crossings'
    /// float neighbours and at the nearest point, in both precisions and
    /// over scales `2^-60` to `2^60`.
    fn against_oracle<V: Vector>() -> usize {
        let mut draws = Draws(5);
        let mut checked = 0;
        let f = |x: f64| V::Scalar::from_f64(x);
        let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
        for i in 0..3000 {
            let scale = 2f64.powi((i % 121) - 60);
            let mut v = || {
                V::new(
                    f(draws.coordinate(4) * scale),
                    f(draws.coordinate(4) * scale),
                    f(draws.coordinate(4) * scale),
                )
            };
            let (o, d, c) = (v(), v(), v());
            let radius = f(draws.coordinate(4).abs() * scale * 2.0);
            let ray = Ray::new(o, d);
            let Some(exact) = oracle::sphere(&ray, c, radius) else {
                continue;
            };
            let wide = V::Scalar::UNIT_ROUNDOFF.to_f64() < 1e-10;
            let signs = SphereSigns::new(w(o), w(d), w(c), radius.to_f64(), wide);
            let zero_cmp = |x: &R| x.cmp(&R::from_integer(0.into()));
            assert_eq!(signs.disc_sign(), Some(zero_cmp(&exact.discriminant())));
            if !exact.line_hits() {
                continue;
            }
            let near = crate::exact::round::<V::Scalar>(&exact.nearest());
            let mut xs = vec![near, near.next_up(), near.next_down(), V::Scalar::ZERO];
            xs.push(f(draws.coordinate(4) * scale));
            for x in xs {
                let xr = oracle::r(x).unwrap();
                assert_eq!(
                    signs.place(Root::Entry, x.to_f64()),
                    exact.entry_cmp(&xr),
                    "{x:?}"
                );
                assert_eq!(
                    signs.place(Root::Exit, x.to_f64()),
                    exact.exit_cmp(&xr),
                    "{x:?}"
                );
            }
            checked += 1;
        }
        checked
    }

    #[test]
    fn signs_agree_with_the_exact_module() {
        assert!(against_oracle::<Vec3>() > 500);
        assert!(against_oracle::<DVec3>() > 500);
    }

    /// A line touching the sphere exactly: the discriminant is zero and
    /// both crossings are at the nearest point.
    #[test]
    fn touching_line() {
        let signs = SphereSigns::new([-2.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0; 3], 1.0, true);
        assert_eq!(signs.disc_sign(), Some(Ordering::Equal));
        assert_eq!(signs.place(Root::Entry, 2.0), Some(Ordering::Equal));
        assert_eq!(signs.place(Root::Exit, 2.0), Some(Ordering::Equal));
        assert_eq!(signs.place(Root::Exit, 1e300), Some(Ordering::Less));
    }
}
