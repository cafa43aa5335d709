//! The public `rayhit::exact` module itself (the other subjects use it as
//! their oracle): raw float bits, and its verdicts and bands.

mod fuzz_regressions;
mod raw_bits;
mod verdicts;
