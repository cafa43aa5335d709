//! The cameras (pinhole, thin lens, orthographic, panoramic, from
//! matrices) and ray differentials: the pinhole camera's properties, every
//! camera's fuzz checks on seeded cases with worked examples, and what the
//! fuzzers found.

mod checks;
mod fuzz_regressions;
mod properties;
