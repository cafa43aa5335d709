//! What the property tests share: proptest's configuration, the macro that
//! declares a property in both precisions, and the exact absolute value.
//!
//! Bounds in the property tests are evaluated exactly (as big rationals),
//! so the tests add no rounding of their own; each is derived in a comment.

use proptest::prelude::*;
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
