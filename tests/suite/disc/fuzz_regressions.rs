//! Inputs the `disc` fuzz target found, as literal floats.

use crate::sphere::q;
use rayhit::exact::oracle::disc as exact_disc;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Disc, Intersect, Interval, Ray, Scalar, Vector};

/// The exact crossing of `ray` with `d`'s plane is within the circles and
/// inside `Disc::bounds`, exactly; and the interval form reports it.
fn crossing_in_bounds<V: Vector>(ray: Ray<V>, d: Disc<V>) {
    let e = exact_disc(&ray, &d).expect("a crossing");
    assert!(e.within_rims() && e.t > q(<V::Scalar as Scalar>::ZERO));
    let b = d.bounds();
    for i in 0..3 {
        let p = q(ray.origin[i]) + &e.t * q(ray.dir[i]);
        assert!(
            q(b.min[i]) <= p && p <= q(b.max[i]),
            "axis {i}: {b:?} misses {}",
            rayhit::exact::oracle::to_f64(&p)
        );
    }
    // The interval form decides exactly (the `t_max` form may drop such a
    // crossing: `dir . normal` is below the bound's underflow floor).
    let inf = <V::Scalar as Scalar>::INFINITY;
    assert!(d.hit(&ray, Interval::up_to(inf).unwrap()).is_some());
}

/// `disc` (a seed, raw `f32`): `Disc::bounds` of a disc whose normal's
/// squared components underflow (`n = (2^-149, 0, 1e-30)`, `|n|^2` rounds
/// to zero) reached `3.7e-23` from the centre on every axis instead of
/// the radius `1` across the plane; the exact crossing at `y = 0.5` lay
/// outside. Fixed: the normal is scaled by a power of two before it is
/// squared, and an axis whose reach needs a square that still underflows
/// gets the whole radius (as the docs said for what cannot be bounded).
#[test]
fn bounds_of_a_tiny_normal() {
    let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.1, -1.0));
    let d = Disc::new(Vec3::ZERO, Vec3::new(f32::from_bits(1), 0.0, 1e-30), 1.0);
    crossing_in_bounds(ray, d);
    // In f64: squares below 2^-1074.
    let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.1, -1.0));
    let d = Disc::new(DVec3::ZERO, DVec3::new(1e-300, 0.0, 1e-200), 1.0);
    crossing_in_bounds(ray, d);
}

/// The same bug the other way (found reading the code while fixing the
/// one above, not by the fuzzer): where a squared component overflows
/// (`n_x^2 = 1e60` in `f32`), `|n|^2` was infinite and the reach along `x`
/// zero, although the disc, of radius `1e30`, reaches `r |n_y| / |n| = 1`
/// along `x`; a ray crosses it at `x = -0.5`.
#[test]
fn bounds_of_a_huge_normal() {
    let d = Disc::new(Vec3::ZERO, Vec3::new(1e30, 1.0, 0.0), 1e30);
    let b = d.bounds();
    assert!(b.min.x <= -0.999 && b.max.x >= 0.999, "{b:?}");
    crossing_in_bounds(Ray::new(Vec3::new(0.5, 5e29, 0.0), -Vec3::X), d);
}

/// `disc` (raw `f64`): over `(0, inf]` a ray whose `dir . normal`
/// underflows to zero (`-2^-149 * 9.9e-310`) crosses the disc exactly at
/// `t* = 3.6e45`, arriving against the normal (`Front`); the interval form
/// found the crossing (decided exactly) but reported `Back`, the sign of
/// the computed `dir . normal`, zero. Fixed: within rounding of parallel,
/// or where the bound does not cover underflow, the side is the exact sign
/// of `dir . normal`. (The reported `t` is the successor of `0`: the
/// quotient, `-inf`, brought into the interval, with no error bound, as
/// documented.)
#[test]
fn side_where_dir_dot_normal_underflows() {
    let ray = Ray::new(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::new(0.0, 0.0, -1.401298464324817e-45),
    );
    let d = Disc::new(
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 9.92075472192084e-310),
        1.0,
    );
    let e = exact_disc(&ray, &d).expect("a crossing");
    assert_eq!(e.side, rayhit::Side::Front);
    let h = d
        .hit(&ray, Interval::up_to(f64::INFINITY).unwrap())
        .expect("the exact verdict: a hit");
    assert_eq!(h.side, rayhit::Side::Front);
    // The t_max form drops it (within rounding of parallel).
    assert!(d.hit(&ray, f64::INFINITY).is_none());
}
