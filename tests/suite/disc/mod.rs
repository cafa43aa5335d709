//! The disc and annulus (`Disc`): the ray/disc test over a `t_max` and
//! over an interval, against exact arithmetic on aimed cases (`oracle`)
//! and in properties on the crate's strategies (`properties`: scaling,
//! hit points, sides, consecutive intervals, the box).

mod fuzz_regressions;
mod oracle;
mod properties;
