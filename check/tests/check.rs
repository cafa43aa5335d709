//! The checker on hand-made answer files: a right
//! kernel passes, a wrong answer on a clear case, or a `t` beyond the bound,
//! fails it, and `--front-only` excuses a culled back face.

use rayhit_check::{Options, run};

/// A triangle in the plane z = 0 and a ray straight down onto its interior
/// at (0.25, 0.25) from z = 1: exactly t = 1, u = v = 0.25; the ray arrives
/// from the front (the normal is +z).
const INPUTS: &str = "3e800000 3e800000 3f800000 00000000 00000000 bf800000 \
                      00000000 00000000 00000000 3f800000 00000000 00000000 \
                      00000000 3f800000 00000000 7f800000";

fn line(answer: &str) -> String {
    format!("triangle f32 down | {INPUTS} | {answer}\n")
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
