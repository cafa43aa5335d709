//! Judging any kernel's answers against exact arithmetic: the library
//! behind the `rayhit-check` command.
//!
//! `rayhit-check [--front-only] [--t-ulps N] FILE`
//!
//! Install it with `cargo install rayhit-check` (or, in a clone of the
//! repository, `cargo install --path check`).
//!
//! Reads cases and a kernel's answers from `FILE` (`-` for standard input),
//! one case a line, and prints, per kind, precision and family, the false
//! hits and misses (those on `clear` cases apart), the worst distance of a
//! wrong answer from the boundary in ulps, the worst `t` error of a right hit
//! in ulps, and how many right hits have a `t` (or box entry or exit) beyond
//! the bound; then the worst cases, as lines to paste into a test file. Exits
//! with status 1 when anything counts against the kernel: a false hit or
//! miss on a `clear` case, or a `t` beyond the bound.
//!
//! # Format
//!
//! Blank lines and lines starting with `#` are skipped. Every other line is
//!
//! ```text
//! KIND PRECISION FAMILY | INPUTS | ANSWER [| BAND]
//! ```
//!
//! - `KIND`: `box`, `triangle`, `plane`, `sphere`, `disc`, `quad` or
//!   `patch`; `PRECISION`: `f32` or `f64`;
//!   `FAMILY`: any word, the row the case is counted in.
//! - `INPUTS`: every float as its IEEE 754 bit pattern in hex (8 digits for
//!   `f32`, 16 for `f64`), as in the crate's corpus: `box`: origin, dir,
//!   min, max, t_max (13 numbers); `triangle`: origin, dir, a, b, c, t_max
//!   (16); `plane`: origin, dir, point, normal, t_max (13); `sphere`:
//!   origin, dir, centre, radius, t_max (11); `disc`: origin, dir, centre,
//!   normal, radius, inner radius, t_max (15); `quad`: origin, dir, a, b,
//!   c, d, t_max (19; the two triangles a b c and a c d); `patch`: origin,
//!   dir, p00, p10, p01, p11, t_max (19; the bilinear patch).
//! - `ANSWER`, the kernel's: `miss`, or `hit ENTER EXIT` (box), `hit T U V`
//!   (triangle and quad; any further words, like `front`, are ignored),
//!   `hit T` (plane), `hit T front` or `hit T back` (sphere: entering or
//!   leaving the ball; disc: arriving against or along the normal), `hit T
//!   U V front` or `hit T U V back` (patch: arriving against or along
//!   `dP/du x dP/dv`), in hex bit patterns. A sphere's, disc's or patch's
//!   side must be the exact one; a wrong side counts as a value beyond the
//!   bound (on a sphere's or patch's `edge` case values are not held, see
//!   `rayhit::exact::judge`).
//! - `BAND`, optional (`clear` or `edge`): ignored; the checker decides the
//!   band itself (`rayhit::exact::band`), so corpus lines can be used as
//!   they are.
//!
//! The lines are read with the crate's own corpus reader
//! (`rayhit::exact::corpus_lines`, `CorpusLine` and `parse_case`).
//!
//! # Options
//!
//! - `--front-only`: the kernel culls back faces; an exact triangle hit from
//!   the back counts as a miss.
//! - `--t-ulps N`: the bound on `t` (and box entry and exit) in ulps of the
//!   exact value. By default it is rayhit's own documented bound for the
//!   case: `Triangle::hit_error`, `Plane::hit_error`, `Sphere::hit_error`,
//!   `Disc::hit_error`, `Quad::hit_error` (the bound of the triangle the
//!   exact crossing is on) and `Patch::hit_error` at the exact answer, and
//!   for boxes 16 ulps.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use rayhit::exact::TriangleAnswer;
use rayhit::exact::{self, Case, CorpusLine, Field, Judgement, Tally, Verdict};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Ray, Scalar, Side, Surface, Triangle, TriangleHit, Vector};

/// The documented box bound used by default, in ulps.
const BOX_ULPS: f64 = 16.0;

/// How the answers are judged.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Options {
    /// The kernel culls back faces: an exact hit from the back counts as a
    /// miss (`--front-only`).
    pub front_only: bool,
    /// The bound on `t` (and box entry and exit) in ulps of the exact value
    /// (`--t-ulps N`); `None` for rayhit's own documented bound per case.
    pub t_ulps: Option<f64>,
}

/// A worst case: how bad, and the line.
type Worst = Vec<(f64, String)>;

fn ulp<F: Scalar>(x: f64) -> f64 {
    let a = F::from_f64(x.abs());
    (a.next_up().to_f64() - a.to_f64()).max(F::TINY.to_f64())
}

/// Judges one case of precision `V`: its kind, inputs and answer as
/// [`exact::parse_case`] reads them.
fn judge_line<V: Vector>(
    kind: &str,
    inputs: &str,
    answer: &str,
    opts: &Options,
) -> Result<Judgement, String> {
    let (case, claim) = exact::parse_case::<V>(kind, inputs, answer)?;
    // The t bound for this case, in ulps of the exact t.
    let bound = match (&case, opts.t_ulps) {
        (_, Some(b)) => b,
        (Case::Box(..), None) => BOX_ULPS,
        (Case::Triangle(ray, tri, t_max), None) => exact::ray_triangle(ray, tri, *t_max)
            .map_or(f64::INFINITY, |h| triangle_ulps(ray, tri, &h)),
        (Case::Plane(ray, plane, t_max), None) => exact::ray_plane(ray, plane, *t_max)
            .map_or(f64::INFINITY, |t| {
                plane.hit_error(ray, &t.rounded).to_f64() / ulp::<V::Scalar>(t.rounded.to_f64())
            }),
        (Case::Sphere(ray, sphere, t_max), None) => exact::ray_sphere(ray, sphere, *t_max)
            .map_or(f64::INFINITY, |h| {
                sphere.hit_error(ray, &h).to_f64() / ulp::<V::Scalar>(h.t.to_f64())
            }),
        (Case::Disc(ray, disc, t_max), None) => exact::ray_disc(ray, disc, *t_max)
            .map_or(f64::INFINITY, |h| {
                disc.hit_error(ray, &h).to_f64() / ulp::<V::Scalar>(h.t.to_f64())
            }),
        // A quad's `t` bound is the triangle's it is on: the first whose
        // exact crossing is the quad's (as `exact::ray_quad` picks it).
        (Case::Quad(ray, quad, t_max), None) => exact::ray_quad(ray, quad, *t_max)
            .and_then(|h| {
                quad.triangles().iter().find_map(|tri| {
                    exact::ray_triangle(ray, tri, *t_max)
                        .filter(|e| e.t.value == h.t.value)
                        .map(|e| triangle_ulps(ray, tri, &e))
                })
            })
            .unwrap_or(f64::INFINITY),
        (Case::Patch(ray, patch, t_max), None) => exact::ray_patch(ray, patch, *t_max)
            .map_or(f64::INFINITY, |h| {
                patch.hit_error(ray, &h).t.to_f64() / ulp::<V::Scalar>(h.t.to_f64())
            }),
        // A shape this checker has no bound for yet: hit or miss alone.
        (_, None) => f64::INFINITY,
    };
    let mut j = exact::judge(&case, &claim, bound);
    // Only t, entry, exit and a sphere's, disc's or patch's side count
    // against the bound here.
    j.outside
        .retain(|f| matches!(f, Field::T | Field::Enter | Field::Exit | Field::Side));
    if opts.front_only
        && let Case::Triangle(ray, tri, t_max) = &case
        && exact::ray_triangle(ray, tri, *t_max).is_some_and(|h| h.side == Side::Back)
    {
        // The culling kernel must miss it.
        j.verdict = if claim.is_hit() {
            Verdict::FalseHit
        } else {
            Verdict::Right
        };
        j.errors.clear();
        j.outside.clear();
    }
    Ok(j)
}

/// The watertight test's bound on `t` at a triangle's exact answer, in
/// ulps of the exact `t` (`Triangle::hit_error` at the rounded answer).
fn triangle_ulps<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, h: &TriangleAnswer<V::Scalar>) -> f64 {
    let probe = TriangleHit {
        t: h.t.rounded,
        u: h.u.rounded,
        v: h.v.rounded,
        side: h.side,
    };
    let err = tri.hit_error(ray, &probe).t.to_f64();
    err / ulp::<V::Scalar>(h.t.rounded.to_f64())
}

/// The three words before a line's first `|`: kind, precision and family.
fn head<'a>(line: &CorpusLine<'a>) -> Option<[&'a str; 3]> {
    let mut words = line.fields(0).ok()?;
    let head = [words.word().ok()?, words.word().ok()?, words.word().ok()?];
    words.word().is_err().then_some(head)
}

/// Judges every line of `text`: the table and worst cases as text, and
/// whether anything counts against the kernel.
pub fn run(opts: &Options, text: &str) -> Result<(String, bool), String> {
    let mut out = String::new();
    let mut rows: BTreeMap<(String, String, String), Tally> = BTreeMap::new();
    let (mut wrong, mut over): (Worst, Worst) = (Vec::new(), Vec::new());
    for (number, line) in exact::corpus_lines(text) {
        let parts = CorpusLine::new(line);
        let (Some(head), &[_, inputs, answer, ..]) = (head(&parts), parts.sections()) else {
            return Err(format!(
                "line {number}: expected `KIND PRECISION FAMILY | INPUTS | ANSWER [| BAND]`"
            ));
        };
        let j = match head[1] {
            "f32" => judge_line::<Vec3>(head[0], inputs, answer, opts),
            "f64" => judge_line::<DVec3>(head[0], inputs, answer, opts),
            p => Err(format!("unknown precision {p}")),
        };
        let j = match j {
            Ok(j) => j,
            Err(e) => return Err(format!("line {number}: {e}")),
        };
        if j.verdict != Verdict::Right && j.band == exact::Band::Clear {
            wrong.push((j.distance_ulps, line.to_string()));
        }
        if !j.outside.is_empty() {
            over.push((j.worst_t_error(), line.to_string()));
        }
        rows.entry((head[0].into(), head[1].into(), head[2].into()))
            .or_default()
            .add(&j);
    }

    writeln!(
        out,
        "{:<9} {:<4} {:<14} {:>8} {:>10} {:>7} {:>12} {:>7} {:>14} {:>14} {:>10}",
        "kind",
        "prec",
        "family",
        "cases",
        "false hits",
        "clear",
        "false misses",
        "clear",
        "worst (ulps)",
        "worst t (ulps)",
        "over bound"
    )
    .unwrap();
    let mut failed = false;
    for ((kind, prec, family), t) in &rows {
        writeln!(
            out,
            "{kind:<9} {prec:<4} {family:<14} {:>8} {:>10} {:>7} {:>12} {:>7} {:>14.3e} {:>14.2} {:>10}",
            t.cases,
            t.false_hits,
            t.clear_false_hits,
            t.false_misses,
            t.clear_false_misses,
            t.worst_false_hit_ulps.max(t.worst_false_miss_ulps),
            t.worst_t_error,
            t.outside_bound
        )
        .unwrap();
        failed |= t.failed();
    }
    // The farthest from the boundary first: the least excusable.
    for (title, mut list) in [
        ("wrong on clear cases", wrong),
        ("t beyond the bound", over),
    ] {
        if list.is_empty() {
            continue;
        }
        list.sort_by(|a, b| b.0.total_cmp(&a.0));
        writeln!(out, "\nworst {title} ({} in all):", list.len()).unwrap();
        for (_, line) in list.iter().take(5) {
            writeln!(out, "{line}").unwrap();
        }
    }
    Ok((out, failed))
}
