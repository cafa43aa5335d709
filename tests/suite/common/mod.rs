//! Helpers the subjects share (no subject of their own; the only test here
//! is the oracle tally's own).

pub mod draw;
pub mod oracle;
pub mod props;
pub mod window;
