//! `batch`: [`ray_aabb_batch`] and [`ray_triangle_batch`] against the scalar
//! kernels, lane by lane.
//!
//! Input: the first byte after the mode picks boxes or triangles, 8 or 16
//! lanes, and how many lanes are filled (0 to all); then `t_max` and the
//! ray, then one shape per filled lane. Raw mode: every float a raw bit
//! pattern (most shapes invalid, so most lanes empty). Structured mode: the
//! ray is aimed at the first shape ([`inputs::aabb_and_ray`],
//! [`inputs::triangle_and_ray`]) and the other shapes are drawn near it, so
//! that several lanes hit at once.
//!
//! Checks: each lane's answer is bit for bit the scalar kernel's on that
//! lane's shape (`ray_aabb_prepared`'s entry for boxes; `ray_triangle` and
//! `ray_triangle_prepared` for triangles, `t`, `u`, `v` and side), empty
//! lanes never hit, the batch stores each valid shape as given, and
//! `nearest` is the smallest `t` (lowest lane among equals).

use arbitrary::{Arbitrary, Unstructured};
use rayhit::{
    Aabb, AabbBatch, PreparedRay, Ray, Scalar, Triangle, TriangleBatch, TriangleHit, Vector,
    ray_aabb_batch, ray_aabb_prepared, ray_triangle, ray_triangle_batch, ray_triangle_prepared,
};

use crate::{Check, Mode, S, inputs, raw};

/// The `batch` target.
#[derive(Debug)]
pub struct Batch;

impl Check for Batch {
    fn run<'a, V>(u: &mut Unstructured<'a>, mode: Mode)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        let layout = raw::<u8>(u);
        let triangles = layout & 1 != 0;
        let sixteen = layout & 2 != 0;
        let lanes = if sixteen { 16 } else { 8 };
        let filled = usize::from(layout >> 2) % (lanes + 1);
        let t_max = match mode {
            Mode::Raw => raw::<S<V>>(u),
            Mode::Structured => inputs::t_max::<V>(u),
        };
        if triangles {
            let (ray, tris) = triangle_inputs::<V>(u, mode, filled);
            if sixteen {
                check_triangles::<V, 16>(&ray, &tris, t_max);
            } else {
                check_triangles::<V, 8>(&ray, &tris, t_max);
            }
        } else {
            let (ray, boxes) = box_inputs::<V>(u, mode, filled);
            if sixteen {
                check_boxes::<V, 16>(&ray, &boxes, t_max);
            } else {
                check_boxes::<V, 8>(&ray, &boxes, t_max);
            }
        }
    }
}

/// A ray and `n` shapes: raw bit patterns, or (structured) the first shape
/// with a ray aimed at it from `first`, and each further one from
/// `next(u, first, previous)`.
fn shapes<'a, V, T>(
    u: &mut Unstructured<'a>,
    mode: Mode,
    n: usize,
    first: impl FnOnce(&mut Unstructured<'a>) -> (T, Ray<V>),
    next: impl Fn(&mut Unstructured<'a>, &T, &T) -> T,
) -> (Ray<V>, Vec<T>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
    T: Arbitrary<'a> + Default + Copy,
{
    match mode {
        Mode::Raw => {
            let ray = raw::<Ray<V>>(u);
            (ray, (0..n).map(|_| raw::<T>(u)).collect())
        }
        Mode::Structured => {
            let (head, ray) = first(u);
            let mut all = vec![head];
            while all.len() < n {
                let shape = next(u, &head, &all[all.len() - 1]);
                all.push(shape);
            }
            all.truncate(n);
            (ray, all)
        }
    }
}

/// A ray and `n` boxes: raw, or the first box with a ray aimed at it and
/// the others moved to within their own size of it.
fn box_inputs<'a, V>(u: &mut Unstructured<'a>, mode: Mode, n: usize) -> (Ray<V>, Vec<Aabb<V>>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
{
    shapes(u, mode, n, inputs::aabb_and_ray::<V>, |u, first, _| {
        let b = inputs::aabb::<V>(u);
        near(u, &first.min, &b.min, &b.max).unwrap_or(b)
    })
}

/// `b` translated so that its `min` lands within its size of `anchor`, or
/// `None` if that rounds it out of shape.
fn near<V: Vector>(u: &mut Unstructured, anchor: &V, min: &V, max: &V) -> Option<Aabb<V>> {
    let size = inputs::c(*max - *min);
    let a = inputs::c(*anchor);
    let shift: [f64; 3] = [0, 1, 2].map(|k| a[k] + inputs::range(u, -size[k], size[k]));
    let lo = inputs::v::<V>(shift);
    let hi = inputs::v::<V>([0, 1, 2].map(|k| shift[k] + size[k]));
    let b = Aabb::new(lo, hi);
    b.is_valid().then_some(b)
}

/// A ray and `n` triangles: raw, or the first triangle with a ray aimed at
/// it and the others continuing a fan around its first corner or the
/// previous triangle's edge (so that lanes tie at shared edges and
/// corners, bit for bit), or drawn anew.
fn triangle_inputs<'a, V>(
    u: &mut Unstructured<'a>,
    mode: Mode,
    n: usize,
) -> (Ray<V>, Vec<Triangle<V>>)
where
    V: Vector,
    S<V>: Arbitrary<'a> + Scalar,
{
    shapes(
        u,
        mode,
        n,
        inputs::triangle_and_ray::<V>,
        |u, first, prev| {
            let t = inputs::triangle::<V>(u);
            match inputs::index(u, 3) {
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
    let hits = ray_aabb_batch(&prepared, &batch, t_max);
    let ctx = || format!("ray {ray:?}, boxes {boxes:?}, t_max {t_max:?}");
    for lane in 0..N {
        let scalar = boxes
            .get(lane)
            .and_then(|b| ray_aabb_prepared(&prepared, b, t_max))
            .map(|(enter, _)| enter);
        assert!(
            bits(hits.get(lane)) == bits(scalar),
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
    let hits = ray_triangle_batch(&prepared, &batch, t_max);
    let ctx = || format!("ray {ray:?}, triangles {tris:?}, t_max {t_max:?}");
    let mut nearest: Option<(usize, S<V>)> = None;
    for lane in 0..N {
        let tri = tris.get(lane);
        let scalar = tri.and_then(|t| ray_triangle(ray, t, t_max));
        let from_prepared = tri.and_then(|t| ray_triangle_prepared(&prepared, t, t_max));
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
    let found = hits
        .nearest()
        .map(|(lane, h)| (lane, h.t.to_f64().to_bits()));
    let expected = nearest.map(|(lane, t)| (lane, t.to_f64().to_bits()));
    assert_eq!(found, expected, "nearest: {}", ctx());
}

fn bits<F: Scalar>(x: Option<F>) -> Option<u64> {
    x.map(|x| x.to_f64().to_bits())
}

fn hit_bits<F: Scalar>(h: Option<TriangleHit<F>>) -> Option<([u64; 3], bool)> {
    h.map(|h| {
        (
            [h.t, h.u, h.v].map(|x| x.to_f64().to_bits()),
            h.side == rayhit::Side::Front,
        )
    })
}
