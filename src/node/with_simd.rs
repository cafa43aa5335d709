//! The batch kernels on a chosen instruction set: [`Simd`], an instruction
//! set, [`SimdRay`], a prepared ray on one (a [`RayForm`] that the batch
//! queries run on that instruction set), and [`with_simd`], which picks the
//! widest the CPU has once for a whole traversal ([`SimdWork`]). The
//! instruction sets themselves, their tokens and the dispatch are
//! `crate::simd`'s; every batch kernel is a kernel body there.

use glam::Vec3;

use crate::num::Vector;
use crate::query::{Form, RayForm, sealed::Sealed};
use crate::ray::{PreparedRay, Ray};
#[cfg(rayhit_runtime_avx)]
use crate::simd::Work;
use crate::simd::{Isa, Kernel, TargetSimd};

/// Work that [`with_simd`] runs compiled for the CPU's widest SIMD: a BVH
/// traversal, a tile of primary rays, any loop that calls the batch
/// kernels many times.
///
/// [`SimdWork::run`] gets the chosen instruction set as `simd`; a query on
/// a ray put on it ([`Simd::ray`]) runs the batch kernels with no check and
/// no call per batch. Implement `run` with `#[inline(always)]`: `with_simd` compiles
/// it once per instruction set, and the attribute is what makes the
/// compiler copy the body into each (functions it calls need at least
/// `#[inline]`, and closures are not always inlined: write the loop out).
pub trait SimdWork {
    /// What the work returns.
    type Output;
    /// The work itself.
    fn run<I: Simd>(self, simd: I) -> Self::Output;
}

/// An instruction set the batch kernels are compiled for; [`with_simd`]
/// hands one to [`SimdWork::run`].
///
/// Sealed. The kernels' answers are the same bits whichever it is.
pub trait Simd: Copy + core::fmt::Debug + Isa {
    /// `ray` on this instruction set: every query on it
    /// ([`Intersect`](crate::Intersect), [`Bounds`](crate::Bounds)) runs
    /// the batch kernels compiled for this instruction set, with no check
    /// and no call per batch, and answers as on `ray` itself, bit for bit.
    #[inline(always)]
    #[must_use]
    fn ray<V: Vector>(self, ray: &PreparedRay<V>) -> SimdRay<'_, Self, V> {
        SimdRay { ray, isa: self }
    }
}

/// A prepared ray on an instruction set (from [`Simd::ray`]), a
/// [`RayForm`]: the form of a ray that the batch queries take inside
/// [`with_simd`]. Scalar queries read it as the prepared ray.
#[derive(Clone, Copy, Debug)]
pub struct SimdRay<'a, I, V: Vector = Vec3> {
    ray: &'a PreparedRay<V>,
    isa: I,
}

impl<I, V: Vector> SimdRay<'_, I, V> {
    /// The prepared ray.
    #[inline]
    #[must_use]
    pub fn prepared(&self) -> &PreparedRay<V> {
        self.ray
    }
}

impl<I: Simd, V: Vector> Sealed<V> for SimdRay<'_, I, V> {
    #[inline(always)]
    fn form(&self) -> Form<'_, V> {
        Form::Prepared(self.ray)
    }

    #[inline(always)]
    fn batch<K: Kernel<Ray = PreparedRay<V>>>(
        &self,
        shapes: &K::Shapes,
        limit: K::Limit,
    ) -> K::Output {
        self.isa.kernel::<K>(self.ray, shapes, limit)
    }
}

impl<I: Simd, V: Vector> RayForm<V> for SimdRay<'_, I, V> {
    #[inline(always)]
    fn to_ray(&self) -> Ray<V> {
        self.ray.ray()
    }
}

impl Simd for TargetSimd {}
#[cfg(rayhit_runtime_avx)]
impl Simd for crate::simd::Avx2 {}
#[cfg(rayhit_runtime_avx)]
impl Simd for crate::simd::Avx512 {}

/// [`SimdWork`] as the instruction sets run it: the work, given the token
/// of the instruction set it is compiled for (used where the build picks
/// the instruction set at run time).
#[cfg(rayhit_runtime_avx)]
struct WorkBody<W, T>(W, T);

#[cfg(rayhit_runtime_avx)]
impl<W: SimdWork, T: Simd> Work for WorkBody<W, T> {
    type Output = W::Output;

    #[inline(always)]
    fn run<I: Isa>(self, _: I) -> W::Output {
        self.0.run(self.1)
    }
}

/// Runs `work` compiled for the widest SIMD instruction set the CPU has,
/// and gives it that instruction set to call the batch kernels with: the
/// choice is made once, here, instead of on every batch.
///
/// The batch queries ([`AabbBatch`](crate::batch::AabbBatch)'s and
/// [`QuantizedChildren`](crate::batch::QuantizedChildren)'s
/// [`clip`](crate::Bounds::clip), [`TriangleBatch`](crate::batch::TriangleBatch)'s
/// [`hit`](crate::IntersectLanes::hit)) on a plain or prepared ray pick their
/// SIMD copy at run time on each call (on x86-64 with `std`, AVX2 where the CPU has
/// it and the build does not already assume it): a check and a function
/// call per batch, a large part of the cost of testing 8 boxes. Inside
/// `with_simd`, on a CPU with AVX-512 the work is compiled with it enabled
/// (`Avx512`: the box kernels inlined, the triangle batch as its AVX2
/// copy), on one with AVX2 with AVX2 enabled (`Avx2`, every kernel
/// inlined); elsewhere it runs as compiled for the build's target
/// ([`TargetSimd`]). The answers are the same bits either way.
///
/// ```
/// use rayhit::{Aabb, Bounds, Camera, PreparedRay, Ray, glam::Vec3};
/// use rayhit::batch::{AabbBatch, Simd, SimdWork, with_simd};
///
/// /// Counts, for every ray, the boxes of one node it hits.
/// struct CountHits<'a> {
///     rays: &'a [PreparedRay],
///     node: &'a AabbBatch<Vec3, 8>,
/// }
///
/// impl SimdWork for CountHits<'_> {
///     type Output = u32;
///     #[inline(always)]
///     fn run<I: Simd>(self, simd: I) -> u32 {
///         let mut hits = 0;
///         for ray in self.rays {
///             let ray = simd.ray(ray);
///             hits += self.node.clip(&ray, f32::INFINITY).mask.count_ones();
///         }
///         hits
///     }
/// }
///
/// let boxes: Vec<Aabb> = (0..8)
///     .map(|i| Aabb::new(Vec3::new(i as f32, 0.0, 0.0), Vec3::new(i as f32 + 0.5, 1.0, 1.0)))
///     .collect();
/// let node = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
/// let rays: Vec<PreparedRay> = (0..100)
///     .map(|i| PreparedRay::new(&Ray::new(Vec3::new(-1.0, 0.5, i as f32 / 100.0), Vec3::X)))
///     .collect();
/// assert_eq!(with_simd(CountHits { rays: &rays, node: &node }), 800);
/// ```
#[inline]
pub fn with_simd<W: SimdWork>(work: W) -> W::Output {
    #[cfg(rayhit_runtime_avx)]
    match crate::simd::Widest::get() {
        crate::simd::Widest::Avx512(isa) => return isa.work(WorkBody(work, isa)),
        crate::simd::Widest::Avx2(isa) => return isa.work(WorkBody(work, isa)),
        crate::simd::Widest::Target => {}
    }
    work.run(TargetSimd)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::IntersectLanes;
    use crate::aabb::AabbBatch;
    use crate::testing::Draws;
    use crate::triangle::TriangleBatch;
    use crate::{Aabb, Bounds, Side, Triangle, TriangleHit};
    use glam::Vec3;
    use std::vec;

    fn hit_bits(h: Option<TriangleHit<f32>>) -> Option<([u32; 3], bool)> {
        h.map(|h| {
            (
                [h.t.to_bits(), h.u.to_bits(), h.v.to_bits()],
                h.side == Side::Front,
            )
        })
    }

    /// Each instruction set's copy of the batch kernels (the target's own,
    /// and the AVX2 and AVX-512 ones where the CPU has them, whichever the
    /// per-call kernels pick) gives the scalar kernels' answers bit for bit.
    #[test]
    #[cfg_attr(not(rayhit_runtime_avx), allow(unused_mut))]
    fn every_copy_agrees_with_the_scalar_kernels() {
        let mut draws = Draws(0x9e37_79b9_7f4a_7c15);
        for case in 0..20_000 {
            let mut v = || Vec3::new(draws.eighth(), draws.eighth(), draws.eighth());
            let ray = Ray::new(v(), v());
            let boxes: [Aabb; 8] = core::array::from_fn(|_| {
                let (a, b) = (v(), v());
                Aabb::new(a.min(b), a.max(b))
            });
            let tris: [Triangle; 8] = core::array::from_fn(|_| Triangle::new(v(), v(), v()));
            let t_max = if case % 2 == 0 { f32::INFINITY } else { 2.0 };
            let p = PreparedRay::new(&ray);
            let bb = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
            let tb = TriangleBatch::<Vec3, 8>::from_slice(&tris).unwrap();
            let target = TargetSimd.ray(&p);
            let mut box_answers = vec![bb.clip(&target, t_max)];
            let mut tri_answers = vec![tb.hit(&target, t_max)];
            #[cfg(rayhit_runtime_avx)]
            if let Some(isa) = crate::simd::Avx2::detect() {
                box_answers.push(bb.clip(&isa.ray(&p), t_max));
                tri_answers.push(tb.hit(&isa.ray(&p), t_max));
            }
            #[cfg(rayhit_runtime_avx)]
            if let Some(isa) = crate::simd::Avx512::detect() {
                box_answers.push(bb.clip(&isa.ray(&p), t_max));
                tri_answers.push(tb.hit(&isa.ray(&p), t_max));
            }
            // The per-call copy (whichever `Widest` picks), and `meets`'
            // copies: the same mask.
            box_answers.push(bb.clip(&p, t_max));
            for a in &box_answers {
                assert_eq!(bb.meets(&p, t_max), a.mask);
                assert_eq!(bb.meets(&target, t_max), a.mask);
            }
            for l in 0..8 {
                let scalar = boxes[l].clip(&p, t_max).map(|(e, _)| e);
                for a in &box_answers {
                    assert_eq!(
                        a.get(l).map(f32::to_bits),
                        scalar.map(f32::to_bits),
                        "{ray:?} {:?}",
                        boxes[l]
                    );
                }
                let scalar = crate::ray_triangle(&ray, &tris[l], t_max);
                for a in &tri_answers {
                    assert_eq!(
                        hit_bits(a.get(l)),
                        hit_bits(scalar),
                        "{ray:?} {:?}",
                        tris[l]
                    );
                }
            }
        }
    }
}
