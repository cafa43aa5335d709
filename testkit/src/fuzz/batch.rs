//! `batch`: [`AabbBatch::clip`](rayhit::Bounds::clip) and
//! [`TriangleBatch::hit`](rayhit::IntersectLanes::hit) against the scalar
//! kernels, lane by lane.
//!
//! Input: the first byte after the mode picks boxes or triangles, 8 or 16
//! lanes, and how many lanes are filled (0 to all); then `t_max` and the
//! ray, then one shape per filled lane. Raw mode: every float a raw bit
//! pattern (most shapes invalid, so most lanes empty). Structured mode: the
//! ray is aimed at the first shape ([`cases::boxes::uniform`],
//! [`cases::triangles::with_fillers`]) and the other shapes are drawn near
//! it, so that several lanes hit at once.
//!
//! Checks: each lane's answer is bit for bit the scalar kernel's on that
//! lane's shape (`Aabb::clip`'s entry on the `PreparedRay` for boxes;
//! `ray_triangle` and `Triangle::hit` on the `PreparedRay` for triangles,
//! `t`, `u`, `v` and side), empty lanes never hit, the batch stores each
//! valid shape as given, and `nearest` is the smallest `t` (lowest lane
//! among equals).

use arbitrary::Arbitrary;
use rayhit::{
    Aabb, Bounds, Intersect, IntersectLanes, PreparedRay, Ray, Scalar, Triangle, Vector,
    batch::{AabbBatch, TriangleBatch},
    ray_triangle,
};

use super::{Check, Input, S, raw};
use crate::bits::{bits, hit_bits};
use crate::cases;
use crate::source::Source;
use rayhit::strategies;

/// The `batch` target.
#[derive(Debug)]
pub struct Batch;

impl Check for Batch {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let layout = match input {
            Input::Raw(u) => raw::<u8>(u),
            Input::Structured(src) => src.below(256) as u8,
        };
        let triangles = layout & 1 != 0;
        let sixteen = layout & 2 != 0;
        let lanes = if sixteen { 16 } else { 8 };
        let filled = usize::from(layout >> 2) % (lanes + 1);
        if triangles {
            let (ray, tris, t_max) = triangle_inputs::<V>(input, filled);
            if sixteen {
                check_triangles::<V, 16>(&ray, &tris, t_max);
            } else {
                check_triangles::<V, 8>(&ray, &tris, t_max);
            }
        } else {
            let (ray, boxes, t_max) = box_inputs::<V>(input, filled);
            if sixteen {
                check_boxes::<V, 16>(&ray, &boxes, t_max);
            } else {
                check_boxes::<V, 8>(&ray, &boxes, t_max);
            }
        }
    }
}

/// A ray, `n` shapes and `t_max`: raw bit patterns, or (structured) the
/// first shape with a ray aimed at it and `t_max` from `first`, and each
/// further one from `next(src, first, previous)`.
fn shapes<'a, V, T>(
    input: &mut Input<'a>,
    n: usize,
    first: impl FnOnce(&mut Source) -> (T, Ray<V>, S<V>),
    next: impl Fn(&mut Source, &T, &T) -> T,
) -> (Ray<V>, Vec<T>, S<V>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
    T: Arbitrary<'a> + Default + Copy,
{
    match input {
        Input::Raw(u) => {
            let (t_max, ray) = (raw::<S<V>>(u), raw::<Ray<V>>(u));
            (ray, (0..n).map(|_| raw::<T>(u)).collect(), t_max)
        }
        Input::Structured(src) => {
            let (head, ray, t_max) = first(src);
            let mut all = vec![head];
            while all.len() < n {
                let shape = next(src, &head, &all[all.len() - 1]);
                all.push(shape);
            }
            all.truncate(n);
            (ray, all, t_max)
        }
    }
}

/// A ray, `n` boxes and `t_max`: raw, or the first box with a ray aimed at
/// it and the others moved to within their own size of it.
fn box_inputs<'a, V>(input: &mut Input<'a>, n: usize) -> (Ray<V>, Vec<Aabb<V>>, S<V>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
{
    shapes(input, n, cases::boxes::uniform::<V>, |src, first, _| {
        let b = src.draw(&strategies::aabb::<V>()).unwrap_or(*first);
        near(src, &first.min, &b.min, &b.max).unwrap_or(b)
    })
}

/// `b` translated so that its `min` lands within its size of `anchor`, or
/// `None` if that rounds it out of shape.
fn near<V: Vector>(src: &mut Source, anchor: &V, min: &V, max: &V) -> Option<Aabb<V>> {
    let size = cases::c(*max - *min);
    let a = cases::c(*anchor);
    let shift: [f64; 3] = [0, 1, 2].map(|k| a[k] + src.range(-size[k], size[k]));
    let lo = cases::v::<V>(shift);
    let hi = cases::v::<V>([0, 1, 2].map(|k| shift[k] + size[k]));
    let b = Aabb::new(lo, hi);
    b.is_valid().then_some(b)
}

/// A ray, `n` triangles and `t_max`: raw, or the first triangle with a ray
/// aimed at it and the others continuing a fan around its first corner or
/// the previous triangle's edge (so that lanes tie at shared edges and
/// corners, bit for bit), or drawn anew.
fn triangle_inputs<'a, V>(input: &mut Input<'a>, n: usize) -> (Ray<V>, Vec<Triangle<V>>, S<V>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
{
    shapes(
        input,
        n,
        cases::triangles::with_fillers::<V>,
        |src, first, prev| {
            let t = cases::triangles::any_triangle::<V>(src);
            match src.index(3) {
                0 => Triangle::new(first.a, prev.c, t.c),
                1 => Triangle::new(prev.b, prev.a, t.c),
                _ => t,
            }
        },
    )
}

fn check_boxes<V: Vector, const N: usize>(ray: &Ray<V>, boxes: &[Aabb<V>], t_max: S<V>) {
    let batch = AabbBatch::<V, N>::from_slice(boxes).expect("at most N boxes");
    let prepared = PreparedRay::new(ray);
    let hits = batch.clip(&prepared, t_max);
    let ctx = || format!("ray {ray:?}, boxes {boxes:?}, t_max {t_max:?}");
    for lane in 0..N {
        let scalar = boxes
            .get(lane)
            .and_then(|b| b.clip(&prepared, t_max))
            .map(|(enter, _)| enter);
        assert!(
            hits.get(lane).map(bits) == scalar.map(bits),
            "lane {lane}: batch {:?}, scalar {scalar:?}: {}",
            hits.get(lane),
            ctx()
        );
        let stored = boxes.get(lane).filter(|b| b.is_valid()).copied();
        assert!(
            batch.get(lane) == stored,
            "lane {lane} stores {:?}: {}",
            batch.get(lane),
            ctx()
        );
    }
}

fn check_triangles<V: Vector, const N: usize>(ray: &Ray<V>, tris: &[Triangle<V>], t_max: S<V>) {
    let batch = TriangleBatch::<V, N>::from_slice(tris).expect("at most N triangles");
    let prepared = PreparedRay::new(ray);
    let hits = batch.hit(&prepared, t_max);
    let ctx = || format!("ray {ray:?}, triangles {tris:?}, t_max {t_max:?}");
    let mut nearest: Option<(usize, S<V>)> = None;
    for lane in 0..N {
        let tri = tris.get(lane);
        let scalar = tri.and_then(|t| ray_triangle(ray, t, t_max));
        let from_prepared = tri.and_then(|t| t.hit(&prepared, t_max));
        let got = hits.get(lane);
        assert!(
            hit_bits(got) == hit_bits(scalar) && hit_bits(from_prepared) == hit_bits(scalar),
            "lane {lane}: batch {got:?}, prepared {from_prepared:?}, scalar {scalar:?}: {}",
            ctx()
        );
        if let Some(h) = got
            && nearest.is_none_or(|(_, t)| h.t < t)
        {
            nearest = Some((lane, h.t));
        }
    }
    let found = hits.nearest().map(|(lane, h)| (lane, bits(h.t)));
    let expected = nearest.map(|(lane, t)| (lane, bits(t)));
    assert_eq!(found, expected, "nearest: {}", ctx());
}
