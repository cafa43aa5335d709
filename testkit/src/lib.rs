//! rayhit's test kit: what the repository's tests, fuzz targets, corpus
//! tools, demo and benches share, so that none of it is written twice. Not
//! published; the crate's users get the public parts it builds on
//! (`rayhit::strategies`, `rayhit::exact`, the `arbitrary` impls).
//!
//! | module | what | feature |
//! | --- | --- | --- |
//! | [`bits`] | bit-for-bit comparisons of answers | |
//! | [`mesh`] | procedural meshes (icosahedron tables, icosphere, torus, shell) and a small BVH | |
//! | [`rng`], [`workloads`] | the benches' fixed-seed generator and workloads | |
//! | [`source`] | where test cases' randomness comes from: seeded, or a fuzz input's bytes | `cases` |
//! | [`cases`] | the case generators, built on `rayhit::strategies` | `cases` |
//! | [`oracle`] | `rayhit::exact::oracle` for inputs known to be finite | `exact` |
//! | [`fuzz`] | the fuzz targets' checks, which `cargo fuzz` runs on generated inputs and `cargo test` on the seeds and saved crashes | `fuzz` |

pub mod bits;
pub mod mesh;
pub mod rng;
pub mod workloads;

#[cfg(feature = "cases")]
pub mod cases;
#[cfg(feature = "cases")]
pub mod source;

#[cfg(feature = "fuzz")]
pub mod fuzz;
#[cfg(feature = "exact")]
pub mod oracle;
