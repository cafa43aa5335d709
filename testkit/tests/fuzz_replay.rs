//! Every fuzz target's checked-in seeds (`fuzz/seeds/<target>/`) and saved
//! crashes (`fuzz/crashes/<target>/`, where a crash's reproducer goes once
//! it is fixed) run through the same checks `cargo fuzz` runs, and so do a
//! few thousand inputs of random bytes per target; and every target in
//! `fuzz/fuzz_targets/` is replayed here.

use std::path::{Path, PathBuf};

use rayhit_testkit::fuzz::targets;
use rayhit_testkit::source::Source;

/// The README's example target, as `cargo fuzz` builds it (see `build.rs`).
mod exact_judge {
    /// `fuzz_target!` as libfuzzer-sys expands it for a typed input: too
    /// short an input, or one `arbitrary` rejects, is skipped.
    macro_rules! fuzz_target {
        (|$input:ident: $ty:ty| $body:block) => {
            pub fn run(bytes: &[u8]) {
                use arbitrary::{Arbitrary, Unstructured};
                if bytes.len() < <$ty as Arbitrary>::size_hint(0).0 {
                    return;
                }
                if let Ok($input) =
                    <$ty as Arbitrary>::arbitrary_take_rest(Unstructured::new(bytes))
                {
                    $body
                }
            }
        };
    }
    include!(concat!(env!("OUT_DIR"), "/exact_judge.rs"));
}

/// A fuzz target: its name and its body.
type Target = (&'static str, fn(&[u8]));

/// Every target, by the name of its file in `fuzz/fuzz_targets/`.
const TARGETS: [Target; 18] = [
    ("aabb", targets::aabb),
    ("aabb_slab_vs_naive", targets::aabb_slab_vs_naive),
    ("batch", targets::batch),
    ("camera", targets::camera),
    ("equal_area", targets::equal_area),
    ("equirectangular", targets::equirectangular),
    ("exact_judge", exact_judge::run),
    ("hit_differentials", targets::hit_differentials),
    ("instance", targets::instance),
    ("interval", targets::interval),
    ("matrix_camera", targets::matrix_camera),
    ("orthographic", targets::orthographic),
    ("plane", targets::plane),
    ("spawn", targets::spawn),
    ("spawn_to", targets::spawn_to),
    ("thin_lens", targets::thin_lens),
    ("triangle", targets::triangle),
    (
        "triangle_watertight_vs_mt",
        targets::triangle_watertight_vs_mt,
    ),
];

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The names in `dir` with the extension stripped, sorted (none if `dir`
/// does not exist).
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// Runs `target` on every file in `dir`, naming the file of a failure.
fn replay(target: fn(&[u8]), dir: &Path) -> usize {
    let mut files = names(dir);
    files.retain(|f| !f.starts_with('.'));
    for name in &files {
        let path = dir.join(name);
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let outcome = std::panic::catch_unwind(|| target(&bytes));
        assert!(
            outcome.is_ok(),
            "fuzz input {} fails its checks",
            path.display()
        );
    }
    files.len()
}

/// The table above lists every target `cargo fuzz` builds, and every seed
/// and crash directory belongs to one of them.
#[test]
fn every_target_is_replayed() {
    let listed: Vec<&str> = TARGETS.iter().map(|(name, _)| *name).collect();
    assert_eq!(names(&fuzz_dir().join("fuzz_targets")), listed);
    for dir in ["seeds", "crashes"] {
        for name in names(&fuzz_dir().join(dir)) {
            assert!(
                listed.contains(&name.as_str()),
                "fuzz/{dir}/{name}: no such target"
            );
        }
    }
}

#[test]
fn seeds_and_saved_crashes_pass() {
    let mut total = 0;
    for (name, target) in TARGETS {
        let seeds = replay(target, &fuzz_dir().join("seeds").join(name));
        assert!(seeds > 0, "fuzz/seeds/{name} is empty");
        total += seeds + replay(target, &fuzz_dir().join("crashes").join(name));
    }
    assert!(total > 200, "{total}");
}

/// Random inputs of every length up to 400 bytes, every mode, for every
/// target: what a short fuzzing run would try first.
#[test]
fn random_inputs_pass() {
    let mut src = Source::seeded(0x5eed_f022);
    for (name, target) in TARGETS {
        for i in 0..1500 {
            let len = src.index(400);
            let mut bytes: Vec<u8> = (0..len).map(|_| src.below(256) as u8).collect();
            if let Some(mode) = bytes.first_mut() {
                *mode = (i % 4) as u8;
            }
            let outcome = std::panic::catch_unwind(|| target(&bytes));
            assert!(outcome.is_ok(), "{name}: fails on {bytes:?}");
        }
    }
}
