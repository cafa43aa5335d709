//! Holding your own ray/triangle function against `rayhit`.
//!
//! `cargo run --release -p rayhit-corpus --example compare`
//!
//! `their_ray_triangle` below stands for a renderer's own kernel: a textbook
//! Moller-Trumbore with an absolute epsilon and back faces dropped, the way
//! it is often written. It is compared twice:
//! 1. against the reference corpus (`corpus/data/triangle_f32.txt`), whose
//!    answers were decided in exact arithmetic: on the cases marked `clear`
//!    (outside the rounding band) any disagreement on hit or miss is a bug
//!    of theirs, and `t` is compared with the exact value;
//! 2. against `rayhit::ray_triangle` on generated cases (the crate's
//!    `proptest` strategies, fixed seed), with `rayhit`'s documented error
//!    bound telling how far apart the two `t` may honestly be.
//!
//! Replace `their_ray_triangle` with your own function to get the same table
//! for it.
//!
//! `cargo run --release -p rayhit-corpus --example compare -- --dump FILE` also writes every
//! case and the kernel's answer (`t`, `u`, `v`) in the checker's format (see
//! the `rayhit-check` crate in `check/`), for
//! `cargo run --release -p rayhit-check -- --front-only FILE`.

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, TestRng, TestRunner};
use rayhit::exact::{self, Band, CorpusLine};
use rayhit::glam::Vec3;
use rayhit::{Ray, Surface, Triangle, ray_triangle, strategies};

/// The kernel under test: Moller-Trumbore with `EPSILON = 1e-7`, one-sided.
fn their_ray_triangle(o: Vec3, d: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, f32)> {
    const EPSILON: f32 = 1e-7;
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det < EPSILON {
        return None; // parallel, or a back face
    }
    let s = o - a;
    let u = s.dot(p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) / det;
    (t > EPSILON).then_some((t, u, v))
}

/// A line of the checker's format: the case and the kernel's answer.
fn dump_line(
    family: &str,
    ray: &Ray,
    tri: &Triangle,
    t_max: f32,
    answer: Option<(f32, f32, f32)>,
) -> String {
    let h = |x: f32| format!("{:08x}", x.to_bits());
    let inputs: Vec<String> = [ray.origin, ray.dir, tri.a, tri.b, tri.c]
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .chain([t_max])
        .map(h)
        .collect();
    let answer = answer.map_or("miss".to_string(), |(t, u, v)| {
        format!("hit {} {} {}", h(t), h(u), h(v))
    });
    format!("triangle f32 {family} | {} | {answer}", inputs.join(" "))
}

/// One row of the table.
#[derive(Default)]
struct Row {
    cases: usize,
    agree: usize,
    false_hits: usize,
    false_misses: usize,
    worst_ulps: f32,
}

impl Row {
    fn add(&mut self, theirs: Option<f32>, reference: Option<f32>) {
        self.cases += 1;
        match (theirs, reference) {
            (Some(a), Some(b)) => {
                self.agree += 1;
                let ulp = b.abs().next_up() - b.abs();
                self.worst_ulps = self.worst_ulps.max((a - b).abs() / ulp);
            }
            (None, None) => self.agree += 1,
            (Some(_), None) => self.false_hits += 1,
            (None, Some(_)) => self.false_misses += 1,
        }
    }

    fn print(&self, name: &str) {
        println!(
            "{name:<34} {:>6} {:>7.2}% {:>10} {:>12} {:>14.1}",
            self.cases,
            100.0 * self.agree as f64 / self.cases.max(1) as f64,
            self.false_hits,
            self.false_misses,
            self.worst_ulps
        );
    }
}

/// A case of the corpus's triangle file, read with `rayhit::exact`'s
/// corpus reader.
struct CorpusTriangle {
    ray: Ray,
    tri: Triangle,
    t_max: f32,
    /// The exact hit's `t` and whether it is from the front; `None` for a
    /// miss.
    exact: Option<(f32, bool)>,
    /// Outside the rounding band.
    clear: bool,
}

/// Reads a line of `corpus/data/triangle_f32.txt` (see its header):
/// `origin dir a b c t_max | miss, or hit T U V front|back | band`.
fn corpus_case(line: &str) -> Result<CorpusTriangle, String> {
    let line = CorpusLine::new(line);
    let mut f = line.fields(0)?;
    let ray = Ray::new(f.vector()?, f.vector()?);
    let tri = Triangle::new(f.vector()?, f.vector()?, f.vector()?);
    let t_max = f.scalar()?;
    let mut answer = line.fields(1)?;
    let exact = match answer.word()? {
        "hit" => {
            let t = answer.scalar()?;
            // `u` and `v`: not compared here.
            answer.scalar::<f32>()?;
            answer.scalar::<f32>()?;
            Some((t, answer.word()? == "front"))
        }
        _ => None,
    };
    Ok(CorpusTriangle {
        ray,
        tri,
        t_max,
        exact,
        clear: line.band(2)? == Band::Clear,
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dump_path = match args.iter().position(|a| a == "--dump") {
        Some(i) => match args.get(i + 1) {
            Some(p) => Some(p.clone()),
            None => {
                eprintln!("--dump needs a file name");
                std::process::exit(2);
            }
        },
        None => None,
    };
    let mut dump = Vec::new();
    println!(
        "{:<34} {:>6} {:>8} {:>10} {:>12} {:>14}",
        "reference", "cases", "agree", "false hits", "false misses", "worst t (ulps)"
    );

    // 1. The corpus: exact answers. Only front faces count, as the kernel
    // under test drops back faces (a renderer comparing a two-sided kernel
    // would drop this filter).
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/triangle_f32.txt");
    let text = std::fs::read_to_string(path).expect("the corpus (corpus/data)");
    let (mut clear, mut edge) = (Row::default(), Row::default());
    for (number, line) in exact::corpus_lines(&text) {
        let case = corpus_case(line).unwrap_or_else(|e| panic!("{path}:{number}: {e}"));
        let (ray, tri) = (case.ray, case.tri);
        let full = their_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c)
            .filter(|h| h.0 <= case.t_max);
        let theirs = full.map(|h| h.0);
        dump.push(dump_line("corpus", &ray, &tri, case.t_max, full));
        let exact = match case.exact {
            // A back face: the kernel under test drops it, so it is not counted.
            Some((_, false)) => continue,
            hit => hit.map(|(t, _)| t),
        };
        if case.clear { &mut clear } else { &mut edge }.add(theirs, exact);
    }
    clear.print("corpus, clear cases (exact)");
    edge.print("corpus, edge cases (exact)");

    // 2. Generated cases against rayhit, front faces only; a disagreement
    // on t counts only beyond rayhit's own error bound.
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::deterministic_rng(Default::default()),
    );
    let strategy = strategies::triangle_and_ray::<Vec3>();
    let (mut row, mut beyond_bound) = (Row::default(), 0usize);
    for _ in 0..20_000 {
        let (tri, ray): (Triangle, Ray) = strategy.new_tree(&mut runner).expect("a case").current();
        let reference =
            ray_triangle(&ray, &tri, f32::INFINITY).filter(|h| h.side == rayhit::Side::Front);
        let full = their_ray_triangle(ray.origin, ray.dir, tri.a, tri.b, tri.c);
        dump.push(dump_line("generated", &ray, &tri, f32::INFINITY, full));
        let theirs = full.map(|h| h.0);
        if let (Some(t), Some(h)) = (theirs, reference)
            && (t - h.t).abs() > tri.hit_error(&ray, &h).t
        {
            beyond_bound += 1;
        }
        row.add(theirs, reference.map(|h| h.t));
    }
    row.print("rayhit::ray_triangle, generated");
    println!(
        "\n{beyond_bound} generated hits differ from rayhit's t by more than rayhit's error bound."
    );
    if let Some(path) = dump_path {
        let mut text = String::from(
            "# Textbook Moller-Trumbore (corpus/examples/compare.rs): cases and its answers.\n",
        );
        for line in &dump {
            text.push_str(line);
            text.push('\n');
        }
        if let Err(e) = std::fs::write(&path, text) {
            eprintln!("cannot write {path}: {e}");
            std::process::exit(2);
        }
        println!("wrote {} cases to {path}", dump.len());
    }
}
