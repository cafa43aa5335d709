//! The exact sign that places a ray's crossing with a disc's plane against
//! the disc's rim (or its hole's): the fallback of the radius test, taken
//! only where the computed point lies within its error bound of a circle.
//!
//! With `w = c - o`, `N = w . n` and `D = d . n` (not zero), the crossing
//! is `p* = o + (N / D) d`, and `D (p* - c) = G = N d - D w`. So `|p* -
//! c|^2 - R^2` has the sign of `|G|^2 - (R D)^2`. Each `G_i` is a sum of
//! products of three floats (`w` held as exact pairs, Knuth's two-sum),
//! summed exactly as a floating-point expansion (Shewchuk, 1997); its
//! square, and that of `R D`, are sums of products of two of their
//! components, summed the same way.

use core::cmp::Ordering;

use crate::num::exact_sign::{Expansion, exponent, scale2, two_diff, two_product};

/// The exact `G` and `D` of a ray's line against a disc's plane, scaled
/// (for `f64` inputs) so that their values are near one.
///
/// Exactness: for `f32` inputs every factor is an `f32` value or the
/// rounding error of an `f32` difference (a multiple of `2^-149` below
/// `2^129`), so every expansion component is a multiple of `2^-447` below
/// `2^390` and every product of two of them is exact in `f64`: the sign is
/// always exact. For `f64` inputs `w` (with the largest radius), `d` and `n` are
/// each scaled by a power of two to put their largest magnitude in `[1,
/// 2)` (`G` and `R D` scale alike, so the sign is unchanged); the sign is
/// then exact while every nonzero scaled factor (the differences' rounding
/// errors included) is at least `2^-150`. A non-finite term gives `None`.
pub(crate) struct DiscSigns {
    /// `c - o`, exact pairs.
    w: [(f64, f64); 3],
    d: [f64; 3],
    n: [f64; 3],
}

impl DiscSigns {
    /// From the origin, direction, centre, normal and the largest radius
    /// asked about, as `f64`; `scale` for `f64` inputs. The radii given to
    /// [`DiscSigns::rim`] are scaled with `w` (by `2^-ew`, `ew` returned).
    pub(crate) fn new(
        o: [f64; 3],
        d: [f64; 3],
        c: [f64; 3],
        n: [f64; 3],
        radius: f64,
        scale: bool,
    ) -> (Self, i32) {
        let mut w = [0, 1, 2].map(|i| two_diff(c[i], o[i]));
        let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, x| m.max(x.abs()));
        let exp = |m: f64| {
            if m > 0.0 && m.is_finite() {
                exponent(m)
            } else {
                0
            }
        };
        let (mut ew, mut ed, mut en) = (0, 0, 0);
        if scale {
            ew = exp(largest(&mut w.iter().map(|p| p.0).chain([radius])));
            ed = exp(largest(&mut d.iter().copied()));
            en = exp(largest(&mut n.iter().copied()));
            for p in &mut w {
                *p = (scale2(p.0, -ew), scale2(p.1, -ew));
            }
        }
        (
            Self {
                w,
                d: d.map(|x| scale2(x, -ed)),
                n: n.map(|x| scale2(x, -en)),
            },
            ew,
        )
    }

    /// `D = d . n` as an expansion.
    fn den(&self) -> Expansion {
        let mut e = Expansion::new();
        for i in 0..3 {
            e.add_product(&[self.d[i], self.n[i]], false);
        }
        e
    }

    /// The exact sign of `D = d . n` (`None` where a term overflows).
    pub(crate) fn den_sign(&self) -> Option<Ordering> {
        self.den().sign()
    }

    /// The sign of `|p* - c|^2 - radius^2` for a radius already scaled as
    /// `w` is (`None` where a term overflows; `D` must not be zero).
    pub(crate) fn rim(&self, radius: f64) -> Option<Ordering> {
        let (w, d, n) = (self.w, self.d, self.n);
        let mut total = Expansion::new();
        for i in 0..3 {
            // G_i = (w . n) d_i - (d . n) w_i.
            let mut g = Expansion::new();
            for m in 0..3 {
                g.add_product(&[w[m].0, n[m], d[i]], false);
                g.add_product(&[w[m].1, n[m], d[i]], false);
                g.add_product(&[d[m], n[m], w[i].0], true);
                g.add_product(&[d[m], n[m], w[i].1], true);
            }
            g.sign()?;
            let parts = g.components();
            for a in parts {
                for b in parts {
                    total.add_product(&[*a, *b], false);
                }
            }
        }
        // (R D)^2, R D exactly as the components of each R D_k.
        let den = self.den();
        den.sign()?;
        let mut rd = Expansion::new();
        for &x in den.components() {
            let (p, e) = two_product(radius, x);
            rd.add(p);
            rd.add(e);
        }
        let parts = rd.components();
        for a in parts {
            for b in parts {
                total.add_product(&[*a, *b], true);
            }
        }
        total.sign()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::oracle;
    use crate::testing::Draws;
    use crate::{Disc, Ray, Scalar, Vector};
    use glam::{DVec3, Vec3};

    /// The rim sign against the exact module's big rationals, for radii
    /// at and around the crossing's exact distance, in both precisions and
    /// over scales `2^-60` to `2^60`.
    fn against_oracle<V: Vector>() -> usize {
        let mut draws = Draws(9);
        let f = |x: f64| V::Scalar::from_f64(x);
        let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
        let mut checked = 0;
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
            let n = V::new(
                f(draws.coordinate(4)),
                f(draws.coordinate(4)),
                f(draws.coordinate(4)),
            );
            let ray = Ray::new(o, d);
            let Some(e) = oracle::disc(&ray, &Disc::new(c, n, f(1.0))) else {
                continue;
            };
            let wide = V::Scalar::UNIT_ROUNDOFF.to_f64() < 1e-10;
            let near = crate::exact::round::<V::Scalar>(&e.dist2).sqrt();
            for radius in [
                near,
                near.next_up(),
                near.next_down(),
                f(draws.coordinate(4).abs() * scale),
            ] {
                let Some(rr) = oracle::r(radius) else {
                    continue;
                };
                let (signs, ew) = DiscSigns::new(w(o), w(d), w(c), w(n), radius.to_f64(), wide);
                // (The documented range for `f64`: a scaled radius below
                // `2^-150` of the largest is outside it.)
                let scaled = scale2(radius.to_f64(), -ew);
                if wide && scaled != 0.0 && scaled < 2f64.powi(-150) {
                    continue;
                }
                let expected = e.rim_cmp(&(&rr * &rr));
                let got = signs.rim(scale2(radius.to_f64(), -ew));
                assert_eq!(got, Some(expected), "{ray:?} {c:?} {n:?} {radius:?}");
            }
            checked += 1;
        }
        checked
    }

    #[test]
    fn rim_signs_agree_with_the_exact_module() {
        assert!(against_oracle::<Vec3>() > 2000);
        assert!(against_oracle::<DVec3>() > 2000);
    }
}
