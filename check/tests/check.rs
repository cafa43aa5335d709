//! The checker on hand-made answer files: a right
//! kernel passes, a wrong answer on a clear case, or a `t` beyond the bound,
//! fails it, and `--front-only` excuses a culled back face; quads and
//! patches are read and judged, a patch's side with them.

use rayhit_check::{Options, run};

/// A triangle in the plane z = 0 and a ray straight down onto its interior
/// at (0.25, 0.25) from z = 1: exactly t = 1, u = v = 0.25; the ray arrives
/// from the front (the normal is +z).
const INPUTS: &str = "3e800000 3e800000 3f800000 00000000 00000000 bf800000 \
                      00000000 00000000 00000000 3f800000 00000000 00000000 \
                      00000000 3f800000 00000000 7f800000";

fn line(answer: &str) -> String {
    line_of("triangle f32 down", INPUTS, answer)
}

/// A checker line: kind, precision and family, the inputs, the answer.
fn line_of(head: &str, inputs: &str, answer: &str) -> String {
    format!("{head} | {inputs} | {answer}\n")
}

/// Whether the checker fails a file of one line.
fn fails(line: &str) -> bool {
    run(&opts(), line).expect("a readable line").1
}

fn opts() -> Options {
    Options {
        front_only: false,
        t_ulps: None,
    }
}

#[test]
fn right_answers_pass() {
    let (table, failed) = run(&opts(), &line("hit 3f800000 3e800000 3e800000")).unwrap();
    assert!(!failed, "{table}");
    assert!(table.contains("triangle  f32  down"), "{table}");
}

#[test]
fn a_false_miss_on_a_clear_case_fails() {
    let (table, failed) = run(&opts(), &line("miss")).unwrap();
    assert!(failed, "{table}");
    assert!(
        table.contains("worst wrong on clear cases (1 in all)"),
        "{table}"
    );
    // The worst case is printed as a line to paste back.
    assert!(table.contains(&line("miss").trim().to_string()), "{table}");
}

#[test]
fn a_t_beyond_the_bound_fails() {
    // t = 1 + 2^-10: far beyond any rounding of this easy case.
    let (table, failed) = run(&opts(), &line("hit 3f802000 3e800000 3e800000")).unwrap();
    assert!(failed, "{table}");
    assert!(table.contains("t beyond the bound (1 in all)"), "{table}");
    // A generous bound excuses it.
    let loose = Options {
        front_only: false,
        t_ulps: Some(1.0e6),
    };
    assert!(
        !run(&loose, &line("hit 3f802000 3e800000 3e800000"))
            .unwrap()
            .1
    );
}

#[test]
fn front_only_excuses_a_culled_back_face() {
    // The same triangle wound the other way: the ray arrives from the back.
    let back = INPUTS.replace(
        "3f800000 00000000 00000000 00000000 3f800000 00000000",
        "00000000 3f800000 00000000 3f800000 00000000 00000000",
    );
    let text = format!("triangle f32 back | {back} | miss\n");
    assert!(
        run(&opts(), &text).unwrap().1,
        "a two-sided kernel must hit it"
    );
    let culling = Options {
        front_only: true,
        t_ulps: None,
    };
    assert!(!run(&culling, &text).unwrap().1);
}

#[test]
fn malformed_lines_are_errors() {
    assert!(run(&opts(), "triangle f32 x | 00 | miss\n").is_err());
    assert!(run(&opts(), "cone f32 x | | miss\n").is_err());
    assert!(run(&opts(), "# only a comment\n\n").is_ok());
}

/// The unit square in the plane z = 0 as a quad, a b c d, and a ray
/// straight down onto (0.5, 0.25) from z = 1: exactly t = 1, u = 0.5, v =
/// 0.25.
const QUAD: &str = "3f000000 3e800000 3f800000 00000000 00000000 bf800000 \
                    00000000 00000000 00000000 3f800000 00000000 00000000 \
                    3f800000 3f800000 00000000 00000000 3f800000 00000000 7f800000";

#[test]
fn quads_are_judged() {
    let line = |answer: &str| line_of("quad f32 square", QUAD, answer);
    let (table, failed) = run(&opts(), &line("hit 3f800000 3f000000 3e800000")).unwrap();
    assert!(!failed, "{table}");
    assert!(table.contains("quad      f32  square"), "{table}");
    assert!(fails(&line("miss")));
    // t = 1 + 2^-10.
    assert!(fails(&line("hit 3f802000 3f000000 3e800000")));
}

/// The saddle z = x y over the unit square (p00, p10, p01, p11 = (0, 0,
/// 0), (1, 0, 0), (0, 1, 0), (1, 1, 1)) and a ray straight down onto (0.5,
/// 0.5) from z = 3: P(0.5, 0.5) has height 0.25, so t = 2.75, u = v = 0.5,
/// and the ray arrives against dP/du x dP/dv = (-0.5, -0.5, 1): the front.
const SADDLE: &str = "3f000000 3f000000 40400000 00000000 00000000 bf800000 \
                      00000000 00000000 00000000 3f800000 00000000 00000000 \
                      00000000 3f800000 00000000 3f800000 3f800000 3f800000 7f800000";

#[test]
fn patches_are_judged_with_their_side() {
    let line = |answer: &str| line_of("patch f32 saddle", SADDLE, answer);
    let (table, failed) = run(&opts(), &line("hit 40300000 3f000000 3f000000 front")).unwrap();
    assert!(!failed, "{table}");
    // The wrong side is a value beyond the bound; a miss is a false miss.
    let (table, failed) = run(&opts(), &line("hit 40300000 3f000000 3f000000 back")).unwrap();
    assert!(
        failed && table.contains("t beyond the bound (1 in all)"),
        "{table}"
    );
    assert!(fails(&line("miss")));
    // A patch answer needs its side.
    assert!(run(&opts(), &line("hit 40300000 3f000000 3f000000")).is_err());
}
