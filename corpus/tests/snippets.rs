//! The README's and the `exact` module docs'
//! snippets for dependents: the property test below is the snippet itself
//! (run here), the fuzz body is the fuzz target `exact_judge`, and every
//! copy must match them.

// snippet: proptest start
use proptest::prelude::*;
use rayhit::exact::{self, Band, Case, Claim, Verdict};
use rayhit::glam::Vec3;
use rayhit::strategies;

/// The kernel under test (yours here): textbook Moller-Trumbore, two-sided.
fn my_ray_triangle(o: Vec3, d: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, f32)> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let (s, inv) = (o - a, 1.0 / det);
    let q = s.cross(e1);
    let (u, v, t) = (s.dot(p) * inv, d.dot(q) * inv, e2.dot(q) * inv);
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

proptest! {
    #[test]
    fn my_kernel_agrees_with_exact((tri, ray) in strategies::triangle_and_ray::<Vec3>()) {
        let claim = match my_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c) {
            Some((t, u, v)) => Claim::Triangle { t, u, v },
            None => Claim::Miss,
        };
        let j = exact::judge(&Case::Triangle(ray, tri, f32::INFINITY), &claim, f64::INFINITY);
        // Outside the rounding band, hit or miss must be exactly right.
        prop_assert!(j.band == Band::Edge || j.verdict == Verdict::Right, "{:?}", j);
    }
}
// snippet: proptest end

fn between(text: &str, start: &str, end: &str) -> String {
    let a = text.find(start).expect("start marker") + start.len();
    let b = text.find(end).expect("end marker");
    text[a..b].trim_start_matches('\n').to_string()
}

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))).expect(path)
}

/// The module docs without their `//! ` prefixes.
fn module_docs() -> String {
    read("src/exact/mod.rs")
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .map(|l| format!("{l}\n"))
        .collect()
}

#[test]
fn snippet_copies_match() {
    let me = read("corpus/tests/snippets.rs");
    let prop = between(
        &me,
        "// snippet: proptest start\n",
        "// snippet: proptest end",
    );
    let fuzz = read("fuzz/fuzz_targets/exact_judge.rs");
    assert!(prop.len() > 500 && fuzz.len() > 500);
    for (name, text) in [
        ("README.md", read("README.md")),
        ("src/exact/mod.rs", module_docs()),
    ] {
        assert!(
            text.contains(&prop),
            "{name}: the proptest snippet differs from corpus/tests/snippets.rs"
        );
        assert!(
            text.contains(&fuzz),
            "{name}: the fuzz snippet differs from fuzz/fuzz_targets/exact_judge.rs"
        );
    }
}
