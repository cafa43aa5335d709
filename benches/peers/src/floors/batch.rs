//! Floors for the eight-lane triangle batches: the watertight test on eight
//! triangles at a time written directly in AVX2 intrinsics, the fastest way
//! found for this core, with only what each question needs.
//!
//! - [`Question::UpTo`]: hits in `(0, t_max]`, what `TriangleBatch::hit`
//!   answers, with the checks its guarantee needs beyond the textbook test
//!   (an edge function of exactly zero leaves for an exact recomputation,
//!   `t > 0` decided on the corners' depths, a finite `t`).
//! - [`Question::Within`]: hits in `(t_min, t_max]` decided against the exact
//!   crossing, what `TriangleBatch::hit` over an interval answers: instead
//!   of the range test on the computed `t`, the test that every edge
//!   function's sign is exact (without it the corners' depths say nothing
//!   of where the exact line crosses the plane), from the first corner and
//!   a reach stored with the batch, then the corners' depths against both
//!   ends, with the lanes neither accepted nor rejected leaving for the
//!   exact steps.
//!
//! Both compute `t`, `u` and `v` for the lanes hit, as the batches do, and
//! both leave their rare lanes to stubs out of line, so the pair measures
//! what the interval question costs over the plain one, written the same
//! way. The exact steps are not part of a floor: a row of these agrees
//! with rayhit on every lane but those.

use std::arch::x86_64::{
    _CMP_EQ_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_add_ps, _mm256_and_ps, _mm256_andnot_ps,
    _mm256_blendv_ps, _mm256_cmp_ps, _mm256_div_ps, _mm256_load_ps, _mm256_max_ps, _mm256_min_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_ps, _mm256_set1_ps, _mm256_setzero_ps,
    _mm256_store_ps, _mm256_sub_ps,
};

use rayhit::Triangle;

use super::FloorRay;

/// Eight triangles structure-of-arrays, with each one's reach from its
/// first corner (an upper bound on `|p_i[a] - p_0[a]|`, as
/// `TriangleBatch` stores it).
#[repr(C, align(32))]
pub struct FloorBatch {
    p: [[[f32; 8]; 3]; 3],
    reach: [f32; 8],
}

impl FloorBatch {
    /// Eight triangles (a shorter slice leaves NaN lanes).
    pub fn new(tris: &[Triangle]) -> Self {
        let mut b = Self {
            p: [[[f32::NAN; 8]; 3]; 3],
            reach: [f32::NAN; 8],
        };
        for (lane, t) in tris.iter().enumerate().take(8) {
            for (c, corner) in [t.a, t.b, t.c].into_iter().enumerate() {
                for k in 0..3 {
                    b.p[c][k][lane] = corner[k];
                }
            }
            let d = (t.b - t.a).abs().max((t.c - t.a).abs());
            b.reach[lane] = d.max_element().next_up();
        }
        b
    }
}

/// Which question a floor answers.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Question {
    /// `(0, t_max]`, the plain batch's.
    UpTo,
    /// `(t_min, t_max]` against the exact crossing, the interval batch's.
    Within,
}

/// The lanes hit, with `t`, `u`, `v` (the batches' answer).
#[repr(C, align(32))]
pub struct FloorHits {
    pub t: [f32; 8],
    pub u: [f32; 8],
    pub v: [f32; 8],
    pub mask: u32,
}

/// The rare lanes, out of line (a floor does not answer them).
#[cold]
#[inline(never)]
fn stub(slow: i32) {
    std::hint::black_box(slow);
}

/// Whether the floors can run here (they need AVX2).
pub fn available() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// The floor for `question` on one ray and eight triangles, over `(lo,
/// hi]` (`lo` is zero for [`Question::UpTo`]).
///
/// # Panics
///
/// Without AVX2 ([`available`]).
#[inline(always)]
pub fn floor_batch(
    question: Question,
    r: &FloorRay,
    b: &FloorBatch,
    lo: f32,
    hi: f32,
) -> FloorHits {
    assert!(AVX2.with(|a| *a), "the floors need AVX2");
    // SAFETY: the CPU has AVX2 (asserted above), the one precondition of
    // calling a function compiled with it; its loads and stores are of
    // 32-byte aligned arrays of eight floats (`FloorBatch` and `FloorHits`
    // are `align(32)`, their arrays at multiples of 32 bytes).
    unsafe {
        match question {
            Question::UpTo => floor_avx2::<false>(r, b, lo, hi),
            Question::Within => floor_avx2::<true>(r, b, lo, hi),
        }
    }
}

thread_local! {
    /// [`available`], asked once per thread.
    static AVX2: bool = available();
}

#[target_feature(enable = "avx2")]
fn floor_avx2<const WITHIN: bool>(r: &FloorRay, b: &FloorBatch, lo: f32, hi: f32) -> FloorHits {
    let mut out = FloorHits {
        mask: 0,
        t: [f32::INFINITY; 8],
        u: [0.0; 8],
        v: [0.0; 8],
    };
    let hi = hi.min(f32::MAX);
    if !(r.valid && lo < hi) {
        return out;
    }
    let splat = _mm256_set1_ps;
    let ld = |a: &[f32; 8]| unsafe { _mm256_load_ps(a.as_ptr()) };
    let (add, sub, mul) = (_mm256_add_ps, _mm256_sub_ps, _mm256_mul_ps);
    let (min, max) = (_mm256_min_ps, _mm256_max_ps);
    let lt = |a, b| _mm256_cmp_ps::<_CMP_LT_OQ>(a, b);
    let le = |a, b| _mm256_cmp_ps::<_CMP_LE_OQ>(a, b);
    let (and, or, and_not) = (_mm256_and_ps, _mm256_or_ps, _mm256_andnot_ps);
    let bits = _mm256_movemask_ps;
    let [kx, ky, kz] = r.k;
    let [ox, oy, oz] = r.origin.map(|o| splat(o.x));
    let [sx, sy, sz] = r.s.map(|s| splat(s.x));
    let corner = |c: usize| {
        let pz = sub(ld(&b.p[c][kz]), oz);
        let x = add(sub(ld(&b.p[c][kx]), ox), mul(sx, pz));
        let y = add(sub(ld(&b.p[c][ky]), oy), mul(sy, pz));
        (x, y, pz)
    };
    let ((x0, y0, pz0), (x1, y1, pz1), (x2, y2, pz2)) = (corner(0), corner(1), corner(2));
    let e0 = sub(mul(x1, y2), mul(y1, x2));
    let e1 = sub(mul(x2, y0), mul(y2, x0));
    let e2 = sub(mul(x0, y1), mul(y0, x1));
    let zero = _mm256_setzero_ps();
    let (e_min, e_max) = (min(e0, min(e1, e2)), max(e0, max(e1, e2)));
    let outside = and(lt(e_min, zero), lt(zero, e_max));
    if bits(outside) == 0xff {
        return out;
    }
    let det = add(add(e0, e1), e2);
    let (z0, z1, z2) = (mul(pz0, sz), mul(pz1, sz), mul(pz2, sz));
    let (z_min, z_max) = (min(z0, min(z1, z2)), max(z0, max(z1, z2)));
    let t_scaled = add(add(mul(e0, z0), mul(e1, z1)), mul(e2, z2));
    let one = splat(1.0);
    let hit = if WITHIN {
        let u = f32::EPSILON / 2.0;
        let inside = _mm256_cmp_ps::<_CMP_EQ_OQ>(outside, zero);
        // Every edge function's sign exact (rayhit's `edge_signs_known`).
        let min_abs_e = max(e_min, sub(zero, e_max));
        let finite = _mm256_cmp_ps::<_CMP_EQ_OQ>(sub(det, det), zero);
        let abs = |v| and_not(splat(-0.0), v);
        let reach = ld(&b.reach);
        let w_b = add(abs(pz0), reach);
        let n = add(
            max(
                add(max(abs(x0), abs(y0)), reach),
                splat(2.0 * 2f32.powi(-50)),
            ),
            mul(w_b, splat(32.0 * u)),
        );
        let threshold = mul(mul(n, splat(64.0 * u)), add(n, add(w_b, w_b)));
        let known = and(and(lt(threshold, min_abs_e), finite), inside);
        // The corners' depths against both ends.
        let normal = splat(f32::MIN_POSITIVE);
        let (low, high) = (
            mul(z_min, splat(1.0 - 8.0 * u)),
            mul(z_max, splat(1.0 + 8.0 * u)),
        );
        let accept = and(
            lt(splat(lo.max(f32::MIN_POSITIVE)), low),
            le(high, splat(hi)),
        );
        let reject = or(
            or(
                lt(splat(hi.max(f32::MIN_POSITIVE)), low),
                le(z_max, sub(zero, normal)),
            ),
            and(le(normal, z_min), le(high, splat(lo))),
        );
        let slow = bits(and_not(and(known, or(accept, reject)), inside));
        if slow != 0 {
            stub(slow);
        }
        and(known, accept)
    } else {
        let limit = mul(splat(hi), det);
        let ahead_range = and(and(lt(zero, det), lt(zero, t_scaled)), le(t_scaled, limit));
        let behind_range = and(and(lt(det, zero), lt(t_scaled, zero)), le(limit, t_scaled));
        let pass = and_not(outside, or(ahead_range, behind_range));
        let zero_edge = or(
            _mm256_cmp_ps::<_CMP_EQ_OQ>(e_min, zero),
            _mm256_cmp_ps::<_CMP_EQ_OQ>(e_max, zero),
        );
        let ahead = lt(zero, z_min);
        let slow = bits(or(zero_edge, and_not(ahead, pass)));
        if slow != 0 {
            stub(slow);
        }
        and_not(zero_edge, and(pass, ahead))
    };
    let mask = bits(hit) as u32;
    if mask == 0 {
        return out;
    }
    let inv_det = _mm256_div_ps(one, det);
    let mut t = mul(t_scaled, inv_det);
    if WITHIN {
        // Into (lo, hi]: lo's successor below, hi above.
        let above = splat(f32::from_bits((lo.to_bits() & 0x7fff_ffff) + 1));
        t = min(_mm256_blendv_ps(above, t, lt(splat(lo), t)), splat(hi));
    } else {
        // A finite t (above zero, at most MAX).
        let ok = bits(and(lt(zero, t), le(t, splat(f32::MAX)))) as u32;
        out.mask = mask & ok;
    }
    if WITHIN {
        out.mask = mask;
    }
    let u = min(mul(e1, inv_det), one);
    let v = min(mul(e2, inv_det), one);
    let inf = splat(f32::INFINITY);
    // SAFETY: as in `floor_batch` (aligned arrays of eight floats).
    unsafe {
        _mm256_store_ps(out.t.as_mut_ptr(), _mm256_blendv_ps(inf, t, hit));
        _mm256_store_ps(out.u.as_mut_ptr(), _mm256_blendv_ps(zero, u, hit));
        _mm256_store_ps(out.v.as_mut_ptr(), _mm256_blendv_ps(zero, v, hit));
    }
    out
}
