//! What the property tests share: proptest's configuration, the macro that
//! declares a property in both precisions, and the exact absolute value.
//!
//! Bounds in the property tests are evaluated exactly (as big rationals),
//! so the tests add no rounding of their own; each is derived in a comment.

use proptest::prelude::*;
use rayhit::Scalar;
use rayhit_testkit::case_count;
use rayhit_testkit::oracle::R;

/// Cases per property and precision: 2048 times `RAYHIT_CASES`
/// (`RAYHIT_CASES=50 cargo test --release --test suite properties::`).
pub fn config() -> ProptestConfig {
    ProptestConfig {
        cases: case_count(2048).try_into().unwrap_or(u32::MAX),
        ..ProptestConfig::default()
    }
}

/// `|x|`, exactly.
pub fn abs(x: &R) -> R {
    num_traits::Signed::abs(x)
}

/// Declares each property once and runs it in both precisions: `$name`
/// becomes the tests `$name_f32` and `$name_f64`, with the type `V` standing
/// for `Vec3` and `DVec3` in the strategies. The generated modules take
/// what they use from the invoking module (`use super::*`): `config`,
/// `Vec3`, `DVec3`, proptest's prelude and the checks must be in scope
/// there.
macro_rules! in_both_precisions {
    ($(fn $name:ident($($arg:pat in $strategy:expr),* $(,)?) $body:block)*) => {
        mod f32_cases {
            use super::*;
            type V = Vec3;
            proptest! {
                #![proptest_config(config())]
                $(#[test] fn $name($($arg in $strategy),*) $body)*
            }
        }
        mod f64_cases {
            use super::*;
            type V = DVec3;
            proptest! {
                #![proptest_config(config())]
                $(#[test] fn $name($($arg in $strategy),*) $body)*
            }
        }
    };
}

pub(crate) use in_both_precisions;

/// Ends of an interval from two picks in `[0, 1)`, around a case's
/// reported `crossings`: each `0`, infinity, a crossing or one of its
/// float neighbours, or a value up to twice the farthest crossing (at
/// least 1); in order.
pub fn ends_among<F: Scalar>(crossings: &[F], picks: [f64; 2]) -> (F, F) {
    let mut candidates = vec![F::ZERO, F::INFINITY];
    for &t in crossings {
        candidates.extend([t, t.next_up(), t.next_down()]);
    }
    let far = crossings
        .iter()
        .fold(F::ONE, |m, &t| if t > m { t } else { m });
    let n = candidates.len() + 1;
    let [a, b] = picks.map(|p| {
        let x = p * n as f64;
        candidates
            .get(x as usize)
            .copied()
            .unwrap_or_else(|| far * F::from_f64(2.0 * x.fract()))
    });
    if b < a { (b, a) } else { (a, b) }
}
