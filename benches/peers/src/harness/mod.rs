//! The timing harness: the thread's CPU clock, one timed row
//! ([`Kernel`]), the loop that times every row round after round, and the
//! Markdown table the rows are printed as.

use std::hint::black_box;
use std::time::Duration;

pub mod loops;

/// The calling thread's CPU time.
fn cpu_now() -> Duration {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec, and
    // CLOCK_THREAD_CPUTIME_ID is a clock every Linux kernel since 2.6.12
    // provides; the call only writes `ts`.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// `t_max` for the rows that ask for every hit along the ray.
pub const INF: f32 = f32::INFINITY;
pub const ROUNDS: usize = 31;
const MIN_ROUND: Duration = Duration::from_millis(2);

/// One timed kernel: a closure over its prepared data that returns a
/// checksum (so that nothing is optimised away), and the number of
/// ray/shape tests one call makes.
pub struct Kernel<'a> {
    pub section: &'static str,
    pub name: String,
    pub workload: String,
    pub tests: usize,
    /// `None` for rayhit's own rows.
    pub agreement: Option<f64>,
    pub run: Box<dyn Fn() -> u64 + 'a>,
    pub reps: u32,
    pub best: f64,
}

pub fn kernel<'a>(
    section: &'static str,
    name: &str,
    workload: &str,
    tests: usize,
    agreement: Option<f64>,
    run: impl Fn() -> u64 + 'a,
) -> Kernel<'a> {
    Kernel {
        section,
        name: name.to_string(),
        workload: workload.to_string(),
        tests,
        agreement,
        run: Box::new(run),
        reps: 1,
        best: f64::INFINITY,
    }
}

/// Rows timed with fewer repetitions than this per round run one untimed
/// pass before each round.
const WARM_BELOW: u32 = 4;

pub fn time_all(kernels: &mut [Kernel<'_>]) {
    // Calibrate: enough repetitions for MIN_ROUND.
    for k in kernels.iter_mut() {
        loop {
            let start = cpu_now();
            for _ in 0..k.reps {
                black_box((k.run)());
            }
            if cpu_now() - start >= MIN_ROUND {
                break;
            }
            k.reps *= 2;
        }
    }
    for round in 0..ROUNDS {
        // Every other round runs the rows in reverse order, so that no row
        // always follows the same neighbour. (The first row timed on a
        // workload after another's ran up to 25% slower, round after
        // round, whichever row it was and with a warm-up pass before it;
        // two rows swapped in the list swapped which one was slow.)
        for k in if round % 2 == 0 {
            kernels.iter_mut().collect::<Vec<_>>()
        } else {
            kernels.iter_mut().rev().collect()
        } {
            // A row of few long passes (a traversal over a mesh larger
            // than the level-2 cache) would start each round with the
            // caches holding the previous row's data and time that
            // refill; one untimed pass first times it warm, as rows of
            // many short passes are.
            if k.reps < WARM_BELOW {
                black_box((k.run)());
            }
            let start = cpu_now();
            for _ in 0..k.reps {
                black_box((k.run)());
            }
            let ns = (cpu_now() - start).as_secs_f64() * 1e9 / f64::from(k.reps) / k.tests as f64;
            k.best = k.best.min(ns);
        }
    }
}

/// The fastest round of the row `name` on `workload` in `section` (NaN
/// when there is no such row, as when `--only` left it out).
pub fn find(kernels: &[Kernel<'_>], section: &str, name: &str, workload: &str) -> f64 {
    kernels
        .iter()
        .find(|k| k.section == section && k.name == name && k.workload == workload)
        .map_or(f64::NAN, |k| k.best)
}

/// The rows rayhit is compared against: the other crates and the
/// textbook kernels written here (`floors`).
fn is_peer(name: &str) -> bool {
    ["bvh", "parry3d", "textbook", "obvhs", "glam"]
        .iter()
        .any(|p| name.starts_with(p))
}

/// The table: one line per row, a heading line where a section starts,
/// each row's speed against the fastest peer on the same workload.
pub fn print_table(kernels: &[Kernel<'_>]) {
    println!("| kernel | workload | ns/test | speed vs fastest peer | agrees with rayhit |");
    println!("| --- | --- | ---: | ---: | ---: |");
    let mut last = "";
    for k in kernels {
        if k.section != last {
            println!("| **{}** | | | | |", k.section);
            last = k.section;
        }
        let fastest_peer = kernels
            .iter()
            .filter(|p| p.section == k.section && p.workload == k.workload)
            .filter(|p| is_peer(&p.name))
            .map(|p| p.best)
            .fold(f64::INFINITY, f64::min);
        let agreement = k
            .agreement
            .map_or(String::new(), |a| format!("{:.2}%", 100.0 * a));
        println!(
            "| {} | {} | {:.2} | {:.2}x | {} |",
            k.name,
            k.workload,
            k.best,
            fastest_peer / k.best,
            agreement
        );
    }
}
