//! The interval forms' windows, shared by `plane::interval`,
//! `aabb::interval` and `shapes::interval`: values on a grid, ulp steps,
//! the ends windows are made of and the partitions of `[0, T]`, exact
//! comparison with a window, and the tally.

use crate::common::draw::{f, v};
use rayhit::exact::{self, Rational, oracle};
use rayhit::{Scalar, Vector};
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// Cases per kind and precision, times `RAYHIT_CASES`.
pub const CASES: usize = 150;

/// A value on a grid of `2^-k`, from `bits` random bits (few, so that
/// sums and products of them stay exact).
pub fn grid(rng: &mut Pcg32, bits: u32, k: i32) -> f64 {
    (f64::from(rng.below(1 << bits)) - f64::from(1u32 << (bits - 1))) * 2f64.powi(-k)
}

pub fn grid_v<V: Vector>(rng: &mut Pcg32, bits: u32, k: i32) -> V {
    v::<V>(grid(rng, bits, k), grid(rng, bits, k), grid(rng, bits, k))
}

/// `x` moved by `k` ulps (up for `k > 0`).
pub fn step<F: Scalar>(x: F, k: i32) -> F {
    let mut x = x;
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

/// Whether `V` is single precision.
pub fn single<V: Vector>() -> bool {
    S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10
}

/// `x`, exactly (finite).
pub fn r<F: Scalar>(x: F) -> Rational {
    oracle::r(x).expect("finite")
}

/// The bits of `x` as an `f64`.
pub fn bits<F: Scalar>(x: F) -> u64 {
    x.to_f64().to_bits()
}

/// The ends windows are made of: 0, `around` rounded and two ulps either
/// side (each non-negative finite one), a few fixed values and one random
/// value; sorted, without repeats.
pub fn ends<V: Vector>(rng: &mut Pcg32, around: &[Rational]) -> Vec<S<V>> {
    let mut out = vec![
        S::<V>::ZERO,
        S::<V>::TINY,
        S::<V>::ONE,
        S::<V>::MAX,
        f::<V>(2f64.powi(rng.below(40) as i32 - 20)),
    ];
    for t in around {
        let t0 = exact::round::<S<V>>(t);
        for k in -2..=2 {
            out.push(step(t0, k));
        }
    }
    out.retain(|e| *e >= S::<V>::ZERO && e.is_finite());
    out.sort_by(|a, b| a.partial_cmp(b).unwrap());
    out.dedup_by(|a, b| bits(*a) == bits(*b) || (*a == S::<V>::ZERO && *b == S::<V>::ZERO));
    out
}

/// `lo < t <= hi`, exactly, with `hi` capped at `MAX` (`None` for an
/// infinite `hi`: no upper end below `MAX`).
pub fn in_window<F: Scalar>(t: &Rational, lo: F, hi: F) -> bool {
    let cap = if hi < F::MAX { hi } else { F::MAX };
    *t > r(lo) && *t <= r(cap)
}

/// `[0, T]` cut at random points and around `around` (rounded, and two
/// ulps either side), then `(T, inf]`: the windows' ends, from 0.
pub fn partition<V: Vector>(rng: &mut Pcg32, around: Option<&Rational>) -> Vec<S<V>> {
    let t0 = around.map(exact::round::<S<V>>);
    let base = t0.filter(|t| t.is_finite() && *t > S::<V>::ZERO);
    let top = base.map_or(S::<V>::ONE, |t| {
        t * f::<V>(0.5 + 2.0 * f64::from(rng.unit()))
    });
    let mut cuts = vec![S::<V>::ZERO, top];
    for _ in 0..rng.below(6) {
        cuts.push(top * f::<V>(f64::from(rng.unit())));
    }
    if let Some(t) = base {
        for k in -2..=2 {
            if rng.below(2) == 0 {
                cuts.push(step(t, k));
            }
        }
    }
    cuts.retain(|c| *c >= S::<V>::ZERO && *c <= top);
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    cuts.dedup_by(|a, b| a == b);
    cuts.push(S::<V>::INFINITY);
    cuts
}

/// What the interval cases found, for the tests' assertions and the
/// `--nocapture` output.
#[derive(Default, Debug)]
pub struct Tally {
    pub cases: usize,
    pub windows: usize,
    pub hits: usize,
    /// Windows where `ray_plane`'s quotient and `t*` lie on different
    /// sides of an end: a float comparison would have been wrong there.
    pub float_wrong: usize,
    /// Cases `ray_plane` drops (within rounding of parallel, or `t` not
    /// above 0) that cross the plane at `t* > 0`.
    pub dropped_by_plain: usize,
    /// Cases crossing at exactly a float.
    pub exact_float: usize,
    /// Clear cases where `(0, t_max]` matched `ray_plane` bit for bit.
    pub plain_equal: usize,
    /// Box windows the exact segment meets.
    pub exact_hits: usize,
    /// Box windows reported where the exact segment misses them.
    pub false_hits: usize,
    /// Box faces reported.
    pub faces: usize,
    /// Partitions checked, and those with a report.
    pub partitions: usize,
    pub reported_once: usize,
}
