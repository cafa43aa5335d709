//! `rayhit-check`: judges a kernel's answers, read from a file (or `-` for
//! standard input), against exact arithmetic; see the library's docs for
//! the format. Exits with 0 when nothing counts against the kernel, 1 when
//! something does, 2 on bad usage or input.

use std::io::Read;
use std::process::ExitCode;

use rayhit_check::{Options, run};

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let mut opts = Options {
        front_only: false,
        t_ulps: None,
    };
    let mut file = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--front-only" => opts.front_only = true,
            "--t-ulps" => match args.next().and_then(|s| s.parse::<f64>().ok()) {
                Some(b) if b >= 0.0 => opts.t_ulps = Some(b),
                _ => {
                    eprintln!("--t-ulps needs a number of ulps");
                    return ExitCode::from(2);
                }
            },
            _ if file.is_none() => file = Some(a),
            _ => {
                eprintln!("usage: rayhit-check [--front-only] [--t-ulps N] FILE");
                return ExitCode::from(2);
            }
        }
    }
    let Some(file) = file else {
        eprintln!("usage: rayhit-check [--front-only] [--t-ulps N] FILE");
        return ExitCode::from(2);
    };
    let mut text = String::new();
    let read = if file == "-" {
        std::io::stdin().read_to_string(&mut text).map(|_| ())
    } else {
        std::fs::read_to_string(&file).map(|t| text = t)
    };
    if let Err(e) = read {
        eprintln!("cannot read {file}: {e}");
        return ExitCode::from(2);
    }

    match run(&opts, &text) {
        Ok((table, failed)) => {
            print!("{table}");
            if failed {
                ExitCode::FAILURE
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
