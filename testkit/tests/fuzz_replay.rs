//! Every fuzz target's checked-in seeds (`fuzz/seeds/<target>/`) and saved
//! crashes (`fuzz/crashes/<target>/`, where a crash's reproducer goes once
//! it is fixed) run through the same checks `cargo fuzz` runs, and so do a
//! few thousand inputs of random bytes per target.
//!
//! The targets are the `[[bin]]` entries of `fuzz/Cargo.toml`, the one list
//! of them (`cargo fuzz` builds them, CI runs them); each is replayed
//! through the check `rayhit_testkit::fuzz::TARGETS` gives its name, and a
//! target missing from either, or a file or directory under `fuzz/` that
//! belongs to no target, fails here.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use rayhit_testkit::fuzz::{self, TARGETS};
use rayhit_testkit::source::Source;

/// The fuzz crate's manifest: its `[[bin]]` entries are the targets.
const MANIFEST: &str = include_str!("../../fuzz/Cargo.toml");

/// A `[[bin]]` entry of the manifest: the target's name and its file's
/// path (relative to `fuzz/`).
#[derive(Debug)]
struct Bin {
    name: String,
    path: String,
}

/// The `[[bin]]` entries of a Cargo manifest, in order: within each, its
/// `name = "..."` and `path = "..."` lines (the form `cargo fuzz add`
/// writes). Panics, naming the entry, when one lacks either or has it in
/// another form.
fn bins(manifest: &str) -> Vec<Bin> {
    let mut entries: Vec<(Option<String>, Option<String>)> = Vec::new();
    let mut in_bin = false;
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_bin = line == "[[bin]]";
            if in_bin {
                entries.push((None, None));
            }
            continue;
        }
        let (Some(entry), Some((key, value))) =
            (entries.last_mut().filter(|_| in_bin), line.split_once('='))
        else {
            continue;
        };
        let slot = match key.trim() {
            "name" => &mut entry.0,
            "path" => &mut entry.1,
            _ => continue,
        };
        let value = value.trim();
        let text = value.strip_prefix('"').and_then(|v| v.strip_suffix('"'));
        *slot = Some(
            text.unwrap_or_else(|| panic!("fuzz/Cargo.toml: not a plain string: {line}"))
                .to_string(),
        );
    }
    entries
        .into_iter()
        .enumerate()
        .map(|(i, entry)| match entry {
            (Some(name), Some(path)) => Bin { name, path },
            entry => panic!(
                "fuzz/Cargo.toml: [[bin]] number {}: no name or path: {entry:?}",
                i + 1
            ),
        })
        .collect()
}

/// The targets, sorted by name.
fn targets() -> Vec<Bin> {
    let mut bins = bins(MANIFEST);
    bins.sort_by(|a, b| a.name.cmp(&b.name));
    bins
}

/// The check of the target `name`.
fn check(name: &str) -> fn(&[u8]) {
    fuzz::check(name).unwrap_or_else(|| {
        panic!("fuzz/Cargo.toml: [[bin]] {name} has no entry in rayhit_testkit::fuzz::TARGETS")
    })
}

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

/// The manifest's `[[bin]]` entries are read whole: as many as it has
/// `[[bin]]` lines, each with a name and a path, no name twice.
#[test]
fn the_manifest_lists_the_targets() {
    let listed = bins(MANIFEST);
    let headers = MANIFEST.lines().filter(|l| l.trim() == "[[bin]]").count();
    assert!(headers > 0, "fuzz/Cargo.toml has no [[bin]]");
    assert_eq!(listed.len(), headers);
    let names: BTreeSet<&str> = listed.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        names.len(),
        listed.len(),
        "a [[bin]] name twice: {listed:?}"
    );
    // The parse itself, on a manifest of two targets.
    let two = bins(
        "[package]\nname = \"x\"\n\n[[bin]]\nname = \"a\"\npath = \"fuzz_targets/a.rs\"\ntest = false\n\n\
         [profile.release]\ndebug = 1\n\n[[bin]]\npath = \"fuzz_targets/b.rs\"\nname = \"b\"\n",
    );
    let two: Vec<(&str, &str)> = two
        .iter()
        .map(|b| (b.name.as_str(), b.path.as_str()))
        .collect();
    assert_eq!(
        two,
        [("a", "fuzz_targets/a.rs"), ("b", "fuzz_targets/b.rs")]
    );
}

/// Every `[[bin]]` has a check in `TARGETS`, its file and its seeds, and
/// every check, file, seed and crash directory belongs to a `[[bin]]`.
#[test]
fn every_target_is_replayed() {
    let bins = targets();
    let listed: BTreeSet<&str> = bins.iter().map(|b| b.name.as_str()).collect();
    for bin in &bins {
        check(&bin.name);
        assert!(
            fuzz_dir().join(&bin.path).is_file(),
            "fuzz/Cargo.toml: [[bin]] {}: no file fuzz/{}",
            bin.name,
            bin.path
        );
        assert!(
            !names(&fuzz_dir().join("seeds").join(&bin.name)).is_empty(),
            "fuzz/seeds/{}: no seeds",
            bin.name
        );
    }
    for (name, _) in TARGETS {
        assert!(
            listed.contains(name),
            "rayhit_testkit::fuzz::TARGETS: {name} has no [[bin]] in fuzz/Cargo.toml"
        );
    }
    assert_eq!(TARGETS.len(), listed.len(), "a name twice in TARGETS");
    let files: BTreeSet<PathBuf> = bins.iter().map(|b| fuzz_dir().join(&b.path)).collect();
    for name in names(&fuzz_dir().join("fuzz_targets")) {
        let file = fuzz_dir().join("fuzz_targets").join(format!("{name}.rs"));
        assert!(
            files.contains(&file),
            "fuzz/fuzz_targets/{name}.rs: the path of no [[bin]] in fuzz/Cargo.toml"
        );
    }
    for dir in ["seeds", "crashes"] {
        for name in names(&fuzz_dir().join(dir)) {
            assert!(
                listed.contains(name.as_str()),
                "fuzz/{dir}/{name}: no such target"
            );
        }
    }
}

#[test]
fn seeds_and_saved_crashes_pass() {
    let mut total = 0;
    for bin in targets() {
        let (name, target) = (&bin.name, check(&bin.name));
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
    for bin in targets() {
        let (name, target) = (&bin.name, check(&bin.name));
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
