//! Every register type against the portable definition, bit for bit:
//! the four lanes and the eight lanes the build's target uses (SSE2 or AVX2
//! on x86-64, NEON on aarch64), and the AVX2 lanes where the CPU has AVX2.

use super::portable::{Portable, Portable8};
use crate::num::{Lanes, Lanes8, Repr};
use crate::testing::Draws;

/// The `f32` four lanes of this target.
type F32Lanes = <f32 as Repr>::L4;
/// The `f32` eight lanes of this target.
type F32Lanes8 = <f32 as Repr>::L8;

/// The same bits in every lane.
fn same(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// The bits of `x`, with every NaN alike. An arithmetic operation with a
/// NaN operand gives a NaN whose payload Rust leaves open: the hardware
/// picks one operand's, and the compiler may swap the operands of an
/// addition or multiplication (it does, on aarch64, for `sum3`'s second
/// addition). No kernel answer is a NaN.
fn canonical(x: f32) -> u32 {
    if x.is_nan() { u32::MAX } else { x.to_bits() }
}

/// The same bits in every lane, every NaN alike.
fn same_value(a: [f32; 3], b: [f32; 3]) -> bool {
    a.map(canonical) == b.map(canonical)
}

/// Every operation of the register type gives the portable definition's
/// bits, NaN, infinities and signed zeros included (lane 3 aside): the
/// exact bits where the operation picks or moves a value (`max`, `min`,
/// `abs`, `neg`, the rotations), and any NaN where the portable code
/// computes a NaN.
#[test]
fn registers_match_the_definition() {
    let mut draws = Draws(0x2545_f491_4f6c_dd1d);
    for _ in 0..200_000 {
        let mut v = || {
            [
                draws.special_f32(),
                draws.special_f32(),
                draws.special_f32(),
            ]
        };
        let (a, b) = (v(), v());
        let (pa, pb) = (
            Portable::new(a[0], a[1], a[2]),
            Portable::new(b[0], b[1], b[2]),
        );
        let (fa, fb) = (
            F32Lanes::new(a[0], a[1], a[2]),
            F32Lanes::new(b[0], b[1], b[2]),
        );
        type Op<L> = fn(L, L) -> L;
        let arithmetic: [(Op<Portable<f32>>, Op<F32Lanes>); 4] = [
            (Lanes::add, Lanes::add),
            (Lanes::sub, Lanes::sub),
            (Lanes::mul, Lanes::mul),
            (Lanes::div, Lanes::div),
        ];
        for (p, f) in arithmetic {
            assert!(
                same_value(p(pa, pb).to_array(), f(fa, fb).to_array()),
                "{a:?} {b:?}"
            );
        }
        let selects: [(Op<Portable<f32>>, Op<F32Lanes>); 2] =
            [(Lanes::max, Lanes::max), (Lanes::min, Lanes::min)];
        for (p, f) in selects {
            assert!(
                same(p(pa, pb).to_array(), f(fa, fb).to_array()),
                "{a:?} {b:?}"
            );
        }
        for (p, f) in [
            (pa.abs(), fa.abs()),
            (pa.neg(), fa.neg()),
            (pa.rot1(), fa.rot1()),
            (pa.rot2(), fa.rot2()),
        ] {
            assert!(same(p.to_array(), f.to_array()), "{a:?}");
        }
        assert_eq!(pa.lt(pb), fa.lt(fb));
        assert_eq!(pa.le(pb), fa.le(fb));
        assert_eq!(pa.eq(pb), fa.eq(fb));
        assert_eq!(pa.nle(pb), fa.nle(fb));
        for (p, f) in [(pa.max_all(), fa.max_all()), (pa.min_all(), fa.min_all())] {
            assert!(same(p.to_array(), f.to_array()), "{a:?}");
        }
        assert_eq!(canonical(pa.sum3()), canonical(fa.sum3()), "{a:?}");
        assert_eq!(pa.x().to_bits(), fa.x().to_bits());
    }
}

/// The four-lane operations (every lane counts) give the portable
/// definition's bits: the masks of the comparisons (read through `select`,
/// whose result is one operand's exact bits, and as bits), the roll, and
/// the arithmetic on all four lanes (any NaN where the portable code
/// computes a NaN).
#[test]
fn four_lane_operations_match_the_definition() {
    fn four<L: Lanes<F = f32>>(l: L) -> [u32; 4] {
        l.to_array4().map(f32::to_bits)
    }
    let mut draws = Draws(0x7f4a_7c15_9e37_79b9);
    for _ in 0..100_000 {
        let a: [f32; 4] = core::array::from_fn(|_| draws.special_f32());
        let b: [f32; 4] = core::array::from_fn(|_| draws.special_f32());
        let (pa, pb) = (
            Portable::new4(a[0], a[1], a[2], a[3]),
            Portable::new4(b[0], b[1], b[2], b[3]),
        );
        let (fa, fb) = (
            F32Lanes::new4(a[0], a[1], a[2], a[3]),
            F32Lanes::new4(b[0], b[1], b[2], b[3]),
        );
        assert_eq!(four(pa), a.map(f32::to_bits));
        assert_eq!(four(fa), a.map(f32::to_bits));
        let masks = [(pa.lt_mask(pb), fa.lt_mask(fb))];
        let flag = a[0] < b[0];
        let masks = masks.into_iter().chain([
            (Portable::<f32>::mask_all(flag), F32Lanes::mask_all(flag)),
            (Portable::<f32>::mask_all(!flag), F32Lanes::mask_all(!flag)),
        ]);
        for (pm, fm) in masks {
            assert_eq!(
                four(Portable::select(pm, pa, pb)),
                four(F32Lanes::select(fm, fa, fb)),
                "{a:?} {b:?}"
            );
        }
        assert_eq!(four(pa.roll4()), four(fa.roll4()));
        assert_eq!(four(pa.roll4()), [a[1], a[2], a[3], a[0]].map(f32::to_bits));
        let bits = |f: fn(f32, f32) -> bool| (0..4).map(|k| u32::from(f(a[k], b[k])) << k).sum();
        assert_eq!(fa.lt4(fb), bits(|x, y| x < y), "{a:?} {b:?}");
        assert_eq!(fa.le4(fb), bits(|x, y| x <= y), "{a:?} {b:?}");
        assert_eq!(pa.lt4(pb), fa.lt4(fb), "{a:?} {b:?}");
        assert_eq!(pa.le4(pb), fa.le4(fb), "{a:?} {b:?}");
        assert_eq!(fa.eq4(fb), bits(|x, y| x == y), "{a:?} {b:?}");
        assert_eq!(pa.eq4(pb), fa.eq4(fb), "{a:?} {b:?}");
        assert_eq!(four(pa.neg()), four(fa.neg()));
        assert_eq!(four(pa.abs()), four(fa.abs()));
        type Op<L> = fn(L, L) -> L;
        let arithmetic: [(Op<Portable<f32>>, Op<F32Lanes>); 3] = [
            (Lanes::add, Lanes::add),
            (Lanes::sub, Lanes::sub),
            (Lanes::mul, Lanes::mul),
        ];
        for (p, f) in arithmetic {
            assert_eq!(
                p(pa, pb).to_array4().map(canonical),
                f(fa, fb).to_array4().map(canonical),
                "{a:?} {b:?}"
            );
        }
    }
}

/// Eight lanes of random specials and ordinary values.
fn eight(draws: &mut Draws) -> [f32; 8] {
    core::array::from_fn(|_| draws.special_f32())
}

/// Every operation of an eight-lane register type gives the portable
/// definition's bits and masks: the exact bits where the operation picks or
/// moves a value, and any NaN where the portable code computes a NaN (see
/// `canonical`).
fn check_lanes8<W: Lanes8<F = f32>>(a: [f32; 8], b: [f32; 8]) {
    let (pa, pb) = (Portable8::load(&a), Portable8::load(&b));
    let (wa, wb) = (W::load(&a), W::load(&b));
    let out = |w: W| {
        let mut x = [0.0; 8];
        w.store(&mut x);
        x.map(f32::to_bits)
    };
    let pout = |p: Portable8<f32>| {
        let mut x = [0.0; 8];
        p.store(&mut x);
        x.map(f32::to_bits)
    };
    let value = |bits: [u32; 8]| bits.map(|x| canonical(f32::from_bits(x)));
    assert_eq!(out(wa), a.map(f32::to_bits));
    type Op<L> = fn(L, L) -> L;
    let arithmetic: [(Op<Portable8<f32>>, Op<W>); 4] = [
        (Lanes8::add, Lanes8::add),
        (Lanes8::sub, Lanes8::sub),
        (Lanes8::mul, Lanes8::mul),
        (Lanes8::div, Lanes8::div),
    ];
    for (p, w) in arithmetic {
        assert_eq!(value(pout(p(pa, pb))), value(out(w(wa, wb))), "{a:?} {b:?}");
    }
    assert_eq!(value(pout(pa.sqrt())), value(out(wa.sqrt())), "{a:?}");
    let selects: [(Op<Portable8<f32>>, Op<W>); 2] =
        [(Lanes8::max, Lanes8::max), (Lanes8::min, Lanes8::min)];
    for (p, w) in selects {
        assert_eq!(pout(p(pa, pb)), out(w(wa, wb)), "{a:?} {b:?}");
    }
    let bytes = a.map(|x| x.to_bits() as u8);
    assert_eq!(
        pout(Portable8::from_bytes(&bytes)),
        out(W::from_bytes(&bytes))
    );
    assert_eq!(pout(Portable8::splat(a[3])), out(W::splat(a[3])));
    let masks = [
        (pa.lt(pb), wa.lt(wb)),
        (pa.le(pb), wa.le(wb)),
        (pa.eq(pb), wa.eq(wb)),
    ];
    for (p, w) in masks {
        assert_eq!(Portable8::<f32>::bits(p), W::bits(w), "{a:?} {b:?}");
    }
    let (pm, pn) = (pa.lt(pb), pb.le(pa));
    let (wm, wn) = (wa.lt(wb), wb.le(wa));
    assert_eq!(
        Portable8::<f32>::bits(Portable8::<f32>::and(pm, pn)),
        W::bits(W::and(wm, wn))
    );
    assert_eq!(
        Portable8::<f32>::bits(Portable8::<f32>::or(pm, pn)),
        W::bits(W::or(wm, wn))
    );
    assert_eq!(
        Portable8::<f32>::bits(Portable8::<f32>::and_not(pm, pn)),
        W::bits(W::and_not(wm, wn))
    );
    assert_eq!(
        pout(Portable8::select(pm, pa, pb)),
        out(W::select(wm, wa, wb))
    );
}

/// The eight-lane types the batch kernels use on this target, and the
/// AVX one where the CPU has AVX2, match the definition.
#[test]
fn eight_lane_registers_match_the_definition() {
    #[cfg(rayhit_runtime_avx)]
    #[target_feature(enable = "avx2")]
    fn with_avx2(a: [f32; 8], b: [f32; 8]) {
        check_lanes8::<super::avx2::F32x8>(a, b);
    }
    let mut draws = Draws(0x9e37_79b9_7f4a_7c15);
    for _ in 0..50_000 {
        let (a, b) = (eight(&mut draws), eight(&mut draws));
        check_lanes8::<F32Lanes8>(a, b);
        #[cfg(rayhit_runtime_avx)]
        if std::is_x86_feature_detected!("avx2") {
            #[allow(unsafe_code)]
            // SAFETY: AVX2 was just detected.
            unsafe {
                with_avx2(a, b)
            };
        }
    }
}

/// The semantics the slab test relies on, spelled out.
#[test]
fn max_and_min_return_the_second_operand_for_nan() {
    let nan = F32Lanes::splat(f32::NAN);
    let zero = F32Lanes::splat(0.0);
    let minus_zero = F32Lanes::splat(-0.0);
    assert_eq!(nan.max(zero).to_array(), [0.0; 3]);
    assert_eq!(nan.min(zero).to_array(), [0.0; 3]);
    assert!(zero.max(nan).x().is_nan());
    assert!(zero.min(nan).x().is_nan());
    // -0 > +0 and +0 < -0 are false: the second operand, whichever zero
    // it is (instructions that order -0 below +0 give -0 for the last two).
    assert_eq!(minus_zero.max(zero).x().to_bits(), 0);
    assert_eq!(zero.min(minus_zero).x().to_bits(), (-0.0f32).to_bits());
    assert_eq!(zero.max(minus_zero).x().to_bits(), (-0.0f32).to_bits());
    assert_eq!(minus_zero.min(zero).x().to_bits(), 0);
}

/// The lane types the tests above check are the registers `build.rs`
/// names for the target: on x86-64 SSE2's (AVX2's for eight lanes where
/// the target has AVX2), on aarch64 NEON's, and the arrays where the
/// build asks for them (`--cfg rayhit_portable`).
#[test]
#[cfg(any(rayhit_portable, target_arch = "x86_64", target_arch = "aarch64"))]
fn the_target_uses_its_registers() {
    use core::any::TypeId;
    fn is<A: 'static, B: 'static>() -> bool {
        TypeId::of::<A>() == TypeId::of::<B>()
    }
    let registers = (
        is::<F32Lanes, Portable<f32>>(),
        is::<F32Lanes8, Portable8<f32>>(),
    );
    #[cfg(rayhit_portable)]
    assert_eq!(registers, (true, true));
    #[cfg(all(target_arch = "x86_64", not(rayhit_portable)))]
    {
        assert_eq!(registers, (false, false));
        assert!(is::<F32Lanes, super::sse2::F32x4>());
        #[cfg(target_feature = "avx2")]
        assert!(is::<F32Lanes8, super::avx2::F32x8>());
        #[cfg(not(target_feature = "avx2"))]
        assert!(is::<F32Lanes8, super::sse2::pair::F32x4x2>());
    }
    #[cfg(all(target_arch = "aarch64", not(rayhit_portable)))]
    {
        assert_eq!(registers, (false, false));
        assert!(is::<F32Lanes, super::neon::F32x4>());
        assert!(is::<F32Lanes8, super::neon::F32x4x2>());
    }
}
