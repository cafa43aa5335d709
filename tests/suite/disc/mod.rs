//! The disc and annulus (`Disc`): the ray/disc test over a `t_max` and
//! over an interval, against exact arithmetic.

mod oracle;
