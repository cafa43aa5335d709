//! Several shapes' kernels at once: the tests that hold the box, plane and
//! triangle kernels together (a test of one shape goes to that shape's
//! module).

mod interval;
mod properties;
