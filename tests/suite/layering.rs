//! The crate's layering, checked: every file under `src/` is in
//! CONTRIBUTING.md's map and every file the map names exists; no file
//! uses a module listed after it in the map (files on one row may use each
//! other); and there is no import circle among the files.
//!
//! What counts as a use: a `crate::` or `super::` path in a file's code
//! (comments and unit-test modules left out; a file declared under
//! `#[cfg(test)]` is test code as a whole), resolved to the file of the
//! longest module prefix it names; a name the crate root re-exports
//! (`crate::Triangle`) resolves to the file it is re-exported from. A
//! parent's paths into its own children are declarations, not uses.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// A module path, `["triangle", "batch"]` for `crate::triangle::batch`.
type Module = Vec<String>;

/// The map's rows, in order: each row's files, as paths from the
/// repository's root.
fn map_rows(contributing: &str) -> Vec<Vec<String>> {
    let map = contributing
        .split("\n## The map\n")
        .nth(1)
        .expect("CONTRIBUTING.md has a `## The map` section");
    let mut rows = Vec::new();
    let mut in_table = false;
    for line in map.lines() {
        if !line.starts_with('|') {
            if in_table {
                break;
            }
            continue;
        }
        in_table = true;
        let first = line.split('|').nth(1).unwrap_or("");
        let paths: Vec<&str> = first.split('`').skip(1).step_by(2).collect();
        let Some(lead) = paths.first().filter(|p| p.starts_with("src/")) else {
            continue;
        };
        let dir = lead.rsplit_once('/').map_or("", |(d, _)| d);
        let mut row = vec![lead.to_string()];
        row.extend(paths[1..].iter().map(|p| format!("{dir}/{p}")));
        rows.push(row);
    }
    rows
}

/// Every `.rs` file under `dir`, as paths from `root`.
fn rust_files(root: &Path, dir: &Path, out: &mut Vec<String>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("a readable source folder")
        .map(|e| e.expect("a readable entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(root, &p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let rel = p.strip_prefix(root).expect("under the root");
            out.push(rel.to_string_lossy().replace('\\', "/"));
        }
    }
}

/// The module a file holds, from its path (`src/a/mod.rs` and `src/a.rs`
/// are `a`), unless a `#[path]` attribute in `lib.rs` placed it.
fn module_of(file: &str, placed: &BTreeMap<String, Module>) -> Module {
    if let Some(m) = placed.get(file) {
        return m.clone();
    }
    let rel = file.trim_start_matches("src/").trim_end_matches(".rs");
    let mut parts: Module = rel.split('/').map(str::to_string).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The code of a file without its comments and unit-test modules, and
/// the child modules it declares under `#[cfg(test)]`.
fn code(text: &str) -> (String, Vec<String>) {
    let mut out = String::new();
    let mut test_children = Vec::new();
    // The indentation of each inline module the line is in.
    let mut inline: Vec<usize> = Vec::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("//") {
            continue;
        }
        if trimmed == "#[cfg(test)]" {
            let next = lines.peek().map_or("", |l| l.trim_start());
            if let Some(decl) = next
                .strip_prefix("mod ")
                .or_else(|| next.strip_prefix("pub(crate) mod "))
            {
                if let Some(name) = decl.strip_suffix(';') {
                    test_children.push(name.to_string());
                    lines.next();
                    continue;
                }
                // An inline test module: skip to its closing brace, at the
                // indentation it opened at.
                let indent = line.len() - trimmed.len();
                for l in lines.by_ref() {
                    // (`get` checks that the indentation ends on a
                    // character boundary, so the slice after it is safe.)
                    let opened = l.get(..indent).is_some_and(|p| p.trim().is_empty());
                    if opened && l[indent..].starts_with('}') {
                        break;
                    }
                }
                continue;
            }
        }
        let indent = line.len() - trimmed.len();
        // A trailing comment.
        let line = match line.find("//") {
            Some(i) if !line[..i].contains('"') => &line[..i],
            _ => line,
        };
        if inline
            .last()
            .is_some_and(|&i| i == indent && trimmed.starts_with('}'))
        {
            inline.pop();
        }
        let is_mod = ["mod ", "pub mod ", "pub(crate) mod ", "pub(super) mod "]
            .iter()
            .any(|m| trimmed.starts_with(m));
        if is_mod && trimmed.trim_end().ends_with('{') {
            inline.push(indent);
        }
        // In an inline module, `super` is the file's own module.
        if inline.is_empty() {
            out.push_str(line);
        } else {
            out.push_str(&line.replace("super::", "self::"));
        }
        out.push('\n');
    }
    (out, test_children)
}

/// The paths a file's code names: `crate::...` and `super::...` paths,
/// with `use` groups (`use crate::{a::B, c::{D, E}}`) expanded.
fn paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let chars: Vec<char> = code.chars().collect();
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < chars.len() {
        let starts = |w: &str| code_at(&chars, i, w) && (i == 0 || !ident(chars[i - 1]));
        if starts("crate::") || starts("super::") {
            let (list, end) = path_tree(&chars, i);
            out.extend(list);
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

fn code_at(s: &[char], i: usize, w: &str) -> bool {
    w.chars().enumerate().all(|(k, c)| s.get(i + k) == Some(&c))
}

/// The paths of a path or `use` tree starting at `i`, and where it ends.
fn path_tree(s: &[char], mut i: usize) -> (Vec<Vec<String>>, usize) {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut prefix = Vec::new();
    loop {
        while s.get(i).is_some_and(|c| c.is_whitespace()) {
            i += 1;
        }
        let start = i;
        while s.get(i).is_some_and(|&c| ident(c)) {
            i += 1;
        }
        if i > start {
            prefix.push(s[start..i].iter().collect::<String>());
        }
        if code_at(s, i, "::") {
            i += 2;
            while s.get(i).is_some_and(|c| c.is_whitespace()) {
                i += 1;
            }
            if s.get(i) == Some(&'{') {
                i += 1;
                let mut all = Vec::new();
                loop {
                    while s.get(i).is_some_and(|c| c.is_whitespace() || *c == ',') {
                        i += 1;
                    }
                    match s.get(i) {
                        None => return (all, i),
                        Some('}') => return (all, i + 1),
                        _ => {}
                    }
                    let (sub, end) = path_tree(s, i);
                    all.extend(sub.into_iter().map(|p| [prefix.clone(), p].concat()));
                    // Skip an `as` rename.
                    i = end;
                    while s.get(i).is_some_and(|&c| c != ',' && c != '}') {
                        i += 1;
                    }
                }
            }
            continue;
        }
        return (vec![prefix], i);
    }
}

#[test]
fn every_file_is_in_the_map_and_uses_only_modules_above_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    check(root);
}

fn check(root: &Path) {
    let read =
        |p: &str| std::fs::read_to_string(root.join(p)).unwrap_or_else(|e| panic!("{p}: {e}"));
    let rows = map_rows(&read("CONTRIBUTING.md"));
    let mut files = Vec::new();
    rust_files(root, &root.join("src"), &mut files);
    let mapped: BTreeSet<String> = rows.iter().flatten().cloned().collect();
    let on_disk: BTreeSet<String> = files.iter().cloned().collect();
    let missing: Vec<_> = on_disk.difference(&mapped).collect();
    let stale: Vec<_> = mapped.difference(&on_disk).collect();
    assert!(
        missing.is_empty() && stale.is_empty(),
        "CONTRIBUTING.md's map misses {missing:?} and names {stale:?}, which do not exist"
    );
    let row_of: BTreeMap<&str, usize> = rows
        .iter()
        .enumerate()
        .flat_map(|(i, r)| r.iter().map(move |f| (f.as_str(), i)))
        .collect();

    // Modules placed by `#[path]`, and the root's re-exported names.
    let lib = read("src/lib.rs");
    let mut placed = BTreeMap::new();
    let mut lines = lib.lines().peekable();
    while let Some(l) = lines.next() {
        let Some(p) = l
            .trim()
            .strip_prefix("#[path = \"")
            .and_then(|p| p.strip_suffix("\"]"))
        else {
            continue;
        };
        for next in lines.by_ref() {
            let name = next
                .trim()
                .trim_start_matches("pub ")
                .strip_prefix("mod ")
                .and_then(|n| n.strip_suffix(';'));
            if let Some(name) = name {
                placed.insert(format!("src/{p}"), vec![name.to_string()]);
                break;
            }
        }
    }
    let module_file: BTreeMap<Module, String> = files
        .iter()
        .map(|f| (module_of(f, &placed), f.clone()))
        .collect();
    let mut reexported: BTreeMap<String, Module> = BTreeMap::new();
    for p in paths(&code(&lib).0) {
        if p.first().map(String::as_str) == Some("crate") && p.len() > 2 {
            let name = p.last().expect("nonempty").clone();
            reexported
                .entry(name)
                .or_insert_with(|| p[1..p.len() - 1].to_vec());
        }
    }

    // Test-only files: declared under `#[cfg(test)]`.
    let mut test_only = BTreeSet::new();
    for f in &files {
        let m = module_of(f, &placed);
        for child in code(&read(f)).1 {
            let mut c = m.clone();
            c.push(child);
            if let Some(file) = module_file.get(&c) {
                test_only.insert(file.clone());
            }
        }
    }

    let resolve = |from: &Module, path: &[String]| -> Option<String> {
        let mut m: Module = Vec::new();
        let mut rest = path;
        match path.first().map(String::as_str) {
            Some("crate") => rest = &path[1..],
            Some("super") => {
                m = from.clone();
                while rest.first().map(String::as_str) == Some("super") {
                    m.pop();
                    rest = &rest[1..];
                }
            }
            _ => return None,
        }
        if m.is_empty() {
            let first = rest.first()?;
            if let Some(target) = reexported.get(first) {
                return module_file.get(target).cloned();
            }
            // A path into something that is not a module of the crate
            // (the re-exported `glam`).
            module_file.get(&vec![first.clone()])?;
        }
        let mut best = module_file.get(&m).cloned();
        let mut cur = m;
        for seg in rest {
            cur.push(seg.clone());
            if let Some(f) = module_file.get(&cur) {
                best = Some(f.clone());
            } else {
                break;
            }
        }
        best
    };

    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut wrong_way = Vec::new();
    for f in files.iter().filter(|f| !test_only.contains(*f)) {
        let from = module_of(f, &placed);
        for p in paths(&code(&read(f)).0) {
            let Some(to) = resolve(&from, &p) else {
                continue;
            };
            if &to == f || test_only.contains(&to) {
                continue;
            }
            // A parent's path into its own children declares them.
            let to_module = module_of(&to, &placed);
            if to_module.len() > from.len()
                && to_module.starts_with(&from)
                && (f.ends_with("mod.rs") || f.ends_with("lib.rs"))
            {
                continue;
            }
            if row_of[to.as_str()] > row_of[f.as_str()] {
                wrong_way.push(format!("{f} uses {to} ({})", p.join("::")));
            }
            edges.entry(f.clone()).or_default().insert(to);
        }
    }
    wrong_way.sort();
    wrong_way.dedup();
    assert!(
        wrong_way.is_empty(),
        "uses of a module listed later in CONTRIBUTING.md's map:\n{}",
        wrong_way.join("\n")
    );
    // Circles: a depth-first search for a back edge.
    fn visit<'a>(
        f: &'a str,
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<&'a str, u8>,
        stack: &mut Vec<&'a str>,
    ) -> Option<Vec<String>> {
        state.insert(f, 1);
        stack.push(f);
        for g in edges.get(f).into_iter().flatten() {
            match state.get(g.as_str()) {
                Some(1) => {
                    let at = stack.iter().position(|s| s == g).expect("on the stack");
                    return Some(stack[at..].iter().map(|s| s.to_string()).collect());
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(g, edges, state, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        state.insert(f, 2);
        None
    }
    let mut state = BTreeMap::new();
    for f in edges.keys() {
        if !state.contains_key(f.as_str()) {
            let mut stack = Vec::new();
            if let Some(circle) = visit(f, &edges, &mut state, &mut stack) {
                panic!("an import circle: {}", circle.join(" -> "));
            }
        }
    }
}
