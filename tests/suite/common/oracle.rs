//! The oracle suite's tallies, shared by `aabb::oracle`, `plane::oracle`
//! and `triangle::oracle`: the exact oracle against every kernel, on the
//! cases that break textbook code.
//!
//! Each case is classified against exact rational arithmetic on the same
//! floating-point inputs as right, false hit or false miss, and every false
//! hit is measured: how far (in ulps of the largest coordinate involved) the
//! ray passes from the shape. The guarantees are asserted (no false miss for
//! the slab test, no crack and exactly one hit per crossing for the mesh
//! tests); the rest is reported (run with `--nocapture` to see the tables).
//!
//! `cargo test --test suite oracle::` runs 10,000 cases per generator and
//! precision, for every shape. The long runs, 1,000,000 per generator:
//! `cargo test --release --test suite oracle:: -- --ignored --nocapture`.
//! `RAYHIT_CASES=k` multiplies both (`rayhit_testkit::case_count`).

use std::fmt;

use num_traits::Zero;
use rayhit::{Scalar, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::oracle::{self, R};

type S<V> = <V as Vector>::Scalar;

/// Cases per generator and precision, times `RAYHIT_CASES`.
pub const DEFAULT_CASES: usize = 10_000;

/// The long runs' cases per generator and precision, times `RAYHIT_CASES`.
pub const LONG_CASES: usize = 1_000_000;

/// An exact value, rounded to `f64`.
pub fn f(x: &R) -> f64 {
    oracle::to_f64(x)
}

/// Right / false hit / false miss counts for one kernel on one generator,
/// with the largest distance of a false hit (and of a false miss) from the
/// shape's boundary, in ulps of the largest coordinate involved.
#[derive(Default, Clone)]
pub struct Tally {
    cases: usize,
    exact_hits: usize,
    false_hits: usize,
    false_misses: usize,
    worst_false_hit_ulps: f64,
    worst_false_miss_ulps: f64,
}

impl Tally {
    /// Records one answer; `ulps` is the distance of the ray from the
    /// boundary (used only when the answer is wrong).
    pub fn record(&mut self, kernel: bool, exact: bool, ulps: impl FnOnce() -> f64) {
        self.cases += 1;
        self.exact_hits += usize::from(exact);
        if kernel && !exact {
            self.false_hits += 1;
            self.worst_false_hit_ulps = self.worst_false_hit_ulps.max(ulps());
        } else if !kernel && exact {
            self.false_misses += 1;
            self.worst_false_miss_ulps = self.worst_false_miss_ulps.max(ulps());
        }
    }
}

impl fmt::Display for Tally {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let pct = |n: usize| 100.0 * n as f64 / self.cases.max(1) as f64;
        write!(
            out,
            "{:>8} cases {:>5.1}% hit | false hits {:>6} ({:.4}%, worst {:.3e} ulps) | false misses {:>6} ({:.4}%, worst {:.3e} ulps)",
            self.cases,
            pct(self.exact_hits),
            self.false_hits,
            pct(self.false_hits),
            self.worst_false_hit_ulps,
            self.false_misses,
            pct(self.false_misses),
            self.worst_false_miss_ulps,
        )
    }
}

/// Prints a table row per kernel: `precision`, `generator`, and the
/// kernel's tally.
pub fn report(precision: &str, generator: &str, rows: &[(&str, &Tally)]) {
    for (kernel, t) in rows {
        println!("{precision:>3} {generator:<22} {kernel:<11} {t}");
    }
}

/// `"f32"` or `"f64"`, for the tables.
pub fn precision<V: Vector>() -> &'static str {
    if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        "f32"
    } else {
        "f64"
    }
}

/// The long run, a million cases per generator and precision, one test per
/// kind of shape so that each can be rerun alone (`-- --ignored long_meshes`).
pub fn long<F: Fn(usize) + Sync>(f32_part: F, f64_part: impl Fn(usize) + Sync) {
    let n = case_count(LONG_CASES);
    std::thread::scope(|s| {
        s.spawn(|| f32_part(n));
        s.spawn(|| f64_part(n));
    });
}

#[test]
fn tally_counts_what_it_is_told() {
    let mut t = Tally::default();
    t.record(true, true, || unreachable!());
    t.record(true, false, || 3.0);
    t.record(false, true, || 5.0);
    t.record(false, false, || unreachable!());
    assert_eq!(
        (t.cases, t.exact_hits, t.false_hits, t.false_misses),
        (4, 2, 1, 1)
    );
    assert_eq!(
        (t.worst_false_hit_ulps, t.worst_false_miss_ulps),
        (3.0, 5.0)
    );
    let _ = R::zero();
}
