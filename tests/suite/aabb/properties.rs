//! The box kernels' properties against the exact oracle, in both
//! precisions, on rays aimed at chosen points (see `rayhit::strategies`):
//! the slab test never misses what exact arithmetic hits, its entry and
//! exit lie within their bounds and its false hits within the documented
//! band, the prepared form and `ValidAabb` give the same answers bit for
//! bit, the naive face test agrees away from edges, and the entry point
//! lies on the box. Bounds are evaluated exactly (see `common::props`).

use crate::common::props::{abs, config, in_both_precisions};
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Aabb, Bounds, PreparedRay, Ray, Scalar, ValidAabb, Vector, ray_aabb};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, gamma, r, rv};

type S<V> = <V as Vector>::Scalar;

fn check_box<V: Vector>(aabb: Aabb<V>, ray: Ray<V>, t_max: S<V>) -> Result<(), TestCaseError> {
    let zero = S::<V>::ZERO;
    let slab = ray_aabb(&ray, &aabb, t_max);
    let prepared = aabb.clip(&PreparedRay::new(&ray), t_max);
    prop_assert_eq!(slab, prepared, "prepared and unprepared differ");
    // The same box checked once, when made: the same answers, bit for bit.
    // (The strategy's boxes are valid; the unit test of `ValidAabb` and the
    // `aabb` fuzz target hold its constructor to exactly the valid boxes.)
    let valid = ValidAabb::new(aabb).expect("strategy boxes are valid");
    let bits =
        |h: Option<(S<V>, S<V>)>| h.map(|(e, x)| (e.to_f64().to_bits(), x.to_f64().to_bits()));
    prop_assert_eq!(bits(valid.clip(&ray, t_max)), bits(slab));
    let p = valid.clip(&PreparedRay::new(&ray), t_max);
    prop_assert_eq!(bits(p), bits(slab));
    let naive = aabb.clip_by_faces(&ray, t_max);
    let raw = oracle::box_raw(&ray, &aabb, t_max);
    let exact = raw.clone().filter(|(e, x)| e <= x);
    let u = r(S::<V>::UNIT_ROUNDOFF);

    for (name, res) in [("slab", slab), ("naive", naive)] {
        if let Some((e, x)) = res {
            prop_assert!(
                zero <= e && e <= x && x <= t_max && e.is_finite(),
                "{name}: bad interval ({e:?}, {x:?})"
            );
        }
    }
    // The slab test never misses what exact arithmetic hits.
    prop_assert!(
        exact.is_none() || slab.is_some(),
        "slab false miss, exact {:?}",
        exact
            .as_ref()
            .map(|(e, x)| (oracle::to_f64(e), oracle::to_f64(x)))
    );
    // ... and hits whenever the naive test does.
    prop_assert!(naive.is_none() || slab.is_some(), "naive hits, slab misses");

    if let Some((e, x)) = slab {
        match &exact {
            Some((ee, xx)) => {
                // Entry: three roundings per axis distance, and max/min are
                // exact, so |enter - E| <= gamma(3) E. Exit: at least the
                // exact exit (the widening), and at most W-widened (1 + 10u)
                // times three roundings plus the slack: below X (1 + 16u) + 2 tiny.
                prop_assert!(
                    oracle::reciprocal_overflows(ray.dir)
                        || abs(&(r(e) - ee)) <= gamma::<S<V>>(3) * ee,
                    "enter {e:?} vs exact {}",
                    oracle::to_f64(ee)
                );
                prop_assert!(&r(x) >= xx, "exit {x:?} below exact {}", oracle::to_f64(xx));
                let cap = xx * (R::from_integer(1.into()) + R::from_integer(16.into()) * &u)
                    + r(S::<V>::TINY) * R::from_integer(2.into());
                prop_assert!(
                    oracle::reciprocal_overflows(ray.dir) || r(x) <= cap,
                    "exit {x:?} widened beyond the bound, exact {}",
                    oracle::to_f64(xx)
                );
                if e > zero {
                    entry_point_on_surface(&ray, &aabb, e)?;
                }
            }
            None => {
                // A false hit: the exact entry exceeds the exact exit by less
                // than the documented band.
                let (ee, xx) = raw
                    .as_ref()
                    .expect("a false hit through an axis the ray does not move along");
                let cap = xx * (R::from_integer(1.into()) + R::from_integer(16.into()) * &u)
                    + r(S::<V>::TINY) * R::from_integer(2.into());
                prop_assert!(
                    oracle::reciprocal_overflows(ray.dir) || ee <= &cap,
                    "false hit beyond the band: enter {} exit {}",
                    oracle::to_f64(ee),
                    oracle::to_f64(xx)
                );
            }
        }
    }

    // Away from the boundary band the slab and naive tests agree on
    // hit/miss, and the naive distances are within their two roundings.
    // Band: the slab test can be wrong by 16u relative (its false-hit band),
    // the naive face test by gamma(4) relative (see
    // `Aabb::clip_by_faces`); 32u covers both.
    if let Some((ee, xx)) = &raw {
        let scale = if abs(ee) > abs(xx) { abs(ee) } else { abs(xx) };
        let clear = abs(&(xx - ee)) > R::from_integer(32.into()) * &u * scale;
        if clear {
            prop_assert_eq!(
                slab.is_some(),
                naive.is_some(),
                "slab and naive disagree away from edges"
            );
            // The naive distances are those of the faces it crossed; where
            // the exact entry or exit is within the band of another face
            // (near an edge), it may have taken that face instead.
            let (gap_in, gap_out) =
                oracle::box_face_margins(&ray, &aabb, t_max).expect("raw exists");
            let band = R::from_integer(32.into()) * &u;
            let unambiguous = gap_in > &band * abs(ee) && gap_out > &band * abs(xx);
            if let (true, Some((e, x)), Some((ee, xx))) = (unambiguous, naive, &exact) {
                prop_assert!(abs(&(r(e) - ee)) <= gamma::<S<V>>(2) * ee, "naive enter");
                prop_assert!(abs(&(r(x) - xx)) <= gamma::<S<V>>(2) * xx, "naive exit");
            }
        }
    } else {
        prop_assert!(
            slab.is_none() && naive.is_none(),
            "hit through an axis the ray does not move along"
        );
    }
    Ok(())
}

/// The point `ray.at(enter)` lies on the box surface within its bound.
///
/// With E the exact entry, `|enter - E| <= gamma(3) E`, and the point
/// `p = fl(o + fl(enter d))` is within `gamma(2)(|o_j| + |enter d_j|)` of
/// `o + enter d`; so `|p_j - p*_j| <= gamma(2)|o_j| + gamma(6) enter |d_j|`
/// (using `gamma(3)/(1 - gamma(3)) + gamma(2) <= gamma(6)`), where
/// `p* = o + E d` is on the surface: inside the box, and on the entry face.
fn entry_point_on_surface<V: Vector>(
    ray: &Ray<V>,
    aabb: &Aabb<V>,
    enter: S<V>,
) -> Result<(), TestCaseError> {
    let (p, o, d) = (rv(ray.at(enter)), rv(ray.origin), rv(ray.dir));
    let (lo, hi) = (rv(aabb.min), rv(aabb.max));
    let (g2, g6, e) = (gamma::<S<V>>(2), gamma::<S<V>>(6), r(enter));
    let mut on_face = false;
    for j in 0..3 {
        let b = &g2 * abs(&o[j]) + &g6 * &e * abs(&d[j]);
        prop_assert!(
            &lo[j] - &b <= p[j] && p[j] <= &hi[j] + &b,
            "entry point outside the box on axis {j}"
        );
        on_face |= abs(&(&p[j] - &lo[j])) <= b || abs(&(&p[j] - &hi[j])) <= b;
    }
    prop_assert!(on_face, "entry point on no face");
    Ok(())
}

in_both_precisions! {
    fn aabb((aabb, ray) in strat::aabb_and_ray::<V>(), t_max in strat::t_max::<V>()) {
        check_box(aabb, ray, t_max)?;
    }
}
