//! The floor of a plain call into an eight-box batch: the slab test on
//! eight boxes with the guarantee's arithmetic and nothing else, compiled
//! with AVX-512 (256-bit forms) in a function of its own, called once per
//! batch from code compiled for the default target, as `AabbBatch::meets`
//! is on this CPU.
//!
//! What it leaves out of `meets`: the instruction-set choice per call (the
//! row checks once, outside its loop), the check of `t_max`, the branch to
//! the NaN-safe folds for rays with a zero direction component (every ray
//! of the workload has none), the mask of used lanes, and the ray's
//! preparation (its 24 bytes are origin and reciprocal). What it keeps:
//! the call, the arguments through memory and the answer in a register,
//! the slab arithmetic and the exit's widening. So no plain call into a
//! batch can be faster than this row, whatever `rayhit` does inside it.

use std::arch::x86_64::{
    __m256, _CMP_LE_OQ, _mm256_add_ps, _mm256_cmp_ps, _mm256_load_ps, _mm256_max_ps, _mm256_min_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_sub_ps,
};

use rayhit::{Aabb, Ray};
use rayhit_peers::avx512::Avx512;

use super::WIDENING;

/// A ray as the floor reads it: origin and `1 / dir`.
#[derive(Clone, Copy)]
pub struct FloorSlabRay {
    origin: [f32; 3],
    inv: [f32; 3],
}

impl FloorSlabRay {
    pub fn new(r: &Ray) -> Self {
        Self {
            origin: r.origin.to_array(),
            inv: r.dir.recip().to_array(),
        }
    }
}

/// Eight boxes structure-of-arrays (a shorter slice leaves NaN lanes, which
/// the comparison never hits).
#[repr(C, align(32))]
pub struct FloorBoxes8 {
    min: [[f32; 8]; 3],
    max: [[f32; 8]; 3],
}

impl FloorBoxes8 {
    pub fn new(boxes: &[Aabb]) -> Self {
        let mut b = Self {
            min: [[f32::NAN; 8]; 3],
            max: [[f32::NAN; 8]; 3],
        };
        for (lane, x) in boxes.iter().enumerate().take(8) {
            for k in 0..3 {
                b.min[k][lane] = x.min[k];
                b.max[k][lane] = x.max[k];
            }
        }
        b
    }
}

/// The lanes whose box the ray meets within `[0, t_max]`, one bit each.
#[inline(always)]
pub fn meets(_: Avx512, ray: &FloorSlabRay, boxes: &FloorBoxes8, t_max: f32) -> u32 {
    // SAFETY: the CPU has the features the function is compiled with: an
    // `Avx512` is made only by detecting them.
    unsafe { meets_avx512(ray, boxes, t_max) }
}

#[target_feature(enable = "avx2,avx512f,avx512vl")]
#[inline(never)]
fn meets_avx512(ray: &FloorSlabRay, boxes: &FloorBoxes8, t_max: f32) -> u32 {
    let (w, slack) = WIDENING;
    let axis = |k: usize| -> (__m256, __m256) {
        let o = _mm256_set1_ps(ray.origin[k]);
        let inv = _mm256_set1_ps(ray.inv[k]);
        // SAFETY: the rows are 32-byte aligned (`repr(align(32))`, rows of
        // 32 bytes) and eight floats long.
        let (lo, hi) = unsafe {
            (
                _mm256_load_ps(boxes.min[k].as_ptr()),
                _mm256_load_ps(boxes.max[k].as_ptr()),
            )
        };
        let t0 = _mm256_mul_ps(_mm256_sub_ps(lo, o), inv);
        let t1 = _mm256_mul_ps(_mm256_sub_ps(hi, o), inv);
        (_mm256_min_ps(t0, t1), _mm256_max_ps(t0, t1))
    };
    let (nx, fx) = axis(0);
    let (ny, fy) = axis(1);
    let (nz, fz) = axis(2);
    let near = _mm256_max_ps(
        _mm256_max_ps(nx, ny),
        _mm256_max_ps(nz, _mm256_setzero_ps()),
    );
    let far = _mm256_min_ps(
        _mm256_min_ps(fx, fy),
        _mm256_min_ps(fz, _mm256_set1_ps(t_max)),
    );
    let limit = _mm256_add_ps(_mm256_mul_ps(far, _mm256_set1_ps(w)), _mm256_set1_ps(slack));
    _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, limit)) as u32
}
