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
//! | [`textbook`] | textbook kernels to compare against (Reshetov's bilinear patch test) | |
//! | [`source`] | where test cases' randomness comes from: seeded, or a fuzz input's bytes | `cases` |
//! | [`cases`] | the case generators, built on `rayhit::strategies` | `cases` |
//! | [`oracle`] | `rayhit::exact::oracle` for inputs known to be finite | `exact` |
//! | [`fuzz`] | the fuzz targets' checks, which `cargo fuzz` runs on generated inputs and `cargo test` on the seeds and saved crashes | `fuzz` |
//!
//! And [`case_count`]: how many cases a test runs, its default times the
//! factor `RAYHIT_CASES`.

pub mod bits;
pub mod mesh;
pub mod rng;
pub mod textbook;
pub mod workloads;

#[cfg(feature = "cases")]
pub mod cases;
#[cfg(feature = "cases")]
pub mod source;

#[cfg(feature = "fuzz")]
pub mod fuzz;
#[cfg(feature = "exact")]
pub mod oracle;

/// How many cases a test runs: `default` times the factor in the
/// environment variable `RAYHIT_CASES`, a positive whole number (`1` when
/// it is unset, so that every test runs its default cases, with the same
/// seeds). Every count the crate's integration tests (`tests/suite`) draw
/// goes through here: seeded loops, proptest's cases and the long runs'
/// counts, so that one variable scales them all. Ten times the cases of
/// every test:
///
/// ```sh
/// RAYHIT_CASES=10 cargo test --release --test suite
/// ```
///
/// # Panics
///
/// If `RAYHIT_CASES` is set to anything but a positive whole number (a
/// typo should not quietly run the defaults).
pub fn case_count(default: usize) -> usize {
    let factor = match std::env::var("RAYHIT_CASES") {
        Err(std::env::VarError::NotPresent) => 1,
        Ok(s) => match s.trim().parse::<usize>() {
            Ok(k) if k > 0 => k,
            _ => panic!("RAYHIT_CASES={s:?}: must be a positive whole number"),
        },
        Err(e) => panic!("RAYHIT_CASES: {e}"),
    };
    default.saturating_mul(factor)
}
