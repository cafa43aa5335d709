//! The plane (`Plane`): the ray/plane test, its hit point and error
//! bounds, and the interval form.

mod fuzz_regressions;
pub mod interval;
mod oracle;
mod properties;
