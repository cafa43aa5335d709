//! The bilinear patch: against exact crossings (`oracle`), its
//! metamorphic properties (`properties`), its degenerate cases against the
//! quad and the triangle they become (`degenerate`), and closed meshes of
//! patches, and of patches and triangles with T-junctions, with no crack
//! and no leak, the textbook patch test beside it (`watertight`). The
//! textbook test is the test kit's `textbook::reshetov`.

mod degenerate;
mod oracle;
mod properties;
mod watertight;

pub use rayhit_testkit::textbook::reshetov;
