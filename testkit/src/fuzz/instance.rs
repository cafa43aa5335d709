//! `instance`: [`Instance`] construction, [`Instance::object_to_world_box`]
//! and [`Instance::world_to_object`] with its error bound.
//!
//! Input: raw mode, the matrix's three columns and the translation, an
//! object box and a world ray, every float a raw bit pattern; structured
//! mode, a transform from [`rayhit::strategies::transform`], a box from
//! [`rayhit::strategies::aabb`] and a ray aimed at it.
//!
//! Checks: no panic; a NaN or infinite entry is an error; for a built
//! instance, the world box of a valid object box, when there is one,
//! contains the exact image of the object box (its exact extremes on every
//! axis, [`rayhit::exact::judge_world_box`]); the ray's error bound is
//! never NaN for a finite ray; and in structured mode (within the tested
//! ranges) the bound holds exactly at `t = 0` and `t = 1`:
//! `|F(object.at(t)) - world.at(t)| <= err.at(t)`; and, on a triangle
//! across the object box hit by the ray taken as an object ray, the
//! shadow-ray segment from the hit's world point to a light off the
//! surface ([`Instance::spawn_to_point_through`]), where there is one,
//! traced back into the instance, does not report the triangle over its
//! interval (both edge rules) and crosses the triangle's exact plane at
//! `t < 0`.

use arbitrary::Arbitrary;
use rayhit::{
    Aabb, EdgeRule, Instance, Intersect, Ray, Scalar, Surface, Triangle, Vector, exact,
    instance::InstanceError, ray_triangle, strategies,
};

use super::{Check, Input, S, raw, raw_vec};

/// The `instance` target.
#[derive(Debug)]
pub struct InstanceCheck;

impl Check for InstanceCheck {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let structured = input.is_structured();
        let (cols, t, object, ray) = match input {
            Input::Raw(u) => {
                let cols = [raw_vec::<V>(u), raw_vec::<V>(u), raw_vec::<V>(u)];
                let t = raw_vec::<V>(u);
                let object = raw::<Aabb<V>>(u);
                let ray = raw::<Ray<V>>(u);
                (cols, t, object, ray)
            }
            Input::Structured(src) => {
                let Some((cols, t)) = src.draw(&strategies::transform::<V>()) else {
                    return;
                };
                let Some((object, ray)) = src.draw(&strategies::aabb_and_ray::<V>()) else {
                    return;
                };
                (cols, t, object, ray)
            }
        };
        let finite = cols.iter().all(|c| c.is_finite()) && t.is_finite();
        let inst = match Instance::new(cols, t) {
            Ok(inst) => inst,
            Err(e) => {
                assert!(
                    finite || e == InstanceError::NotFinite,
                    "{cols:?} {t:?}: {e:?}"
                );
                return;
            }
        };
        assert!(finite, "built from non-finite {cols:?} {t:?}");
        let map = exact::AffineMap::of(&inst);
        if object.is_valid()
            && let Some(world) = inst.object_to_world_box(&object)
        {
            let j = exact::judge_world_box(&map, &object, &world).expect("a valid object box");
            assert!(
                j.contains,
                "world box {world:?} misses the exact image of {object:?} under {cols:?} {t:?}: {j:?}"
            );
        }
        if !(ray.origin.is_finite() && ray.dir.is_finite()) {
            return;
        }
        let err = inst.world_to_object_error(&ray);
        let nan = |v: V| (0..3).any(|i| v[i].partial_cmp(&v[i]).is_none());
        assert!(
            !nan(err.at_origin) && !nan(err.per_t),
            "NaN bound for {ray:?} under {cols:?} {t:?}"
        );
        if !structured {
            return;
        }
        let object_ray = inst.world_to_object(&ray);
        segment_to_a_light(&inst, &object, &ray);
        for t_param in [S::<V>::ZERO, S::<V>::ONE] {
            let bound = err.at(t_param);
            let j =
                exact::judge_ray_map(&map, &ray, &object_ray, t_param, bound).expect("finite rays");
            assert!(
                j.within,
                "ray bound {bound:?} fails at t = {t_param:?} for {ray:?} under {cols:?} {t:?}: {j:?}"
            );
        }
    }
}

/// The segment check of structured inputs: a triangle across `object`
/// (three of its corners) hit by `ray` in object space; the segment from
/// the hit's world point to a light along the world normal, a thousandth
/// of the point's distance from the origin away (at least one unit),
/// traced back into the instance.
fn segment_to_a_light<V: Vector>(inst: &Instance<V>, object: &Aabb<V>, ray: &Ray<V>) {
    let (lo, hi) = (object.min, object.max);
    let mid = (lo.z() + hi.z()) * S::<V>::HALF;
    let tri = Triangle::new(
        lo,
        V::new(hi.x(), lo.y(), mid),
        V::new(lo.x(), hi.y(), hi.z()),
    );
    let Some(hit) = ray_triangle(ray, &tri, S::<V>::INFINITY) else {
        return;
    };
    let world = inst.surface_to_world(&tri.surface_point(&ray, &hit));
    let n = world.normal.length();
    if !(n > S::<V>::ZERO && n.is_finite()) {
        return;
    }
    let away = world.point.length() * S::<V>::from_f64(1e-3) + S::<V>::ONE;
    let light = world.point + world.normal * (away / n);
    let Some((shadow, interval)) = Instance::spawn_to_point_through(&[inst], &world, light) else {
        return;
    };
    let back = inst.world_to_object(&shadow);
    assert!(
        tri.hit(&back, interval).is_none()
            && tri.hit(&back, (interval, EdgeRule::OneHit)).is_none(),
        "the segment {shadow:?} reports its start triangle {tri:?} through {inst:?}"
    );
    let crossing = crate::oracle::triangle(&back, &tri);
    assert!(
        crossing.t.is_none_or(|t| t < crate::oracle::int(0)),
        "the segment {shadow:?} crosses its start plane ahead: {tri:?} through {inst:?}"
    );
}
