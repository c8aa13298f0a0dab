//! The `hertz` command: thin CLI over the library. Exit codes: 0 success, 1 failed check rules,
//! 2 bad input or usage, 3 solver failure, 4 output failure.

use hertz::app::{run_file, RunOptions};
use hertz::output::check::describe_failure;
use std::path::PathBuf;
use std::process::ExitCode;

const HELP: &str = "\
hertz — finite-element solver for contact mechanics that reads OOFEM input files

USAGE:
    hertz run FILE.in [-o DIR] [-q|-v] solve; write FILE's .out, .vtu per step and .pvd; evaluate
                                      the #%BEGIN_CHECK% rules if the file has an errorcheck module
    hertz check FILE.in [-q|-v]       solve and evaluate the check rules; write nothing else
    hertz bench [--dim 2|3] [--n N] [--ordering auto|amd|metis]
                                      solve a generated linear-elastic block with N elements per
                                      side and print sizes and timings
    hertz bench --contact [--n N] [--multipliers]
                                      the contact benchmark: a 2N x N block pushed against a rigid
                                      circle with node-to-segment penalty (or multiplier) contact
    hertz bench --sphere H | --patch N [--multipliers] [--write DIR]
                                      3D contact benchmarks: the Hertz sphere on a block in bricks
                                      of spacing H under the contact (0.085: 10^5 unknowns), or the
                                      contact patch test with N x N master bricks ((2N+1)^2 contact
                                      nodes); prints phase times, peak memory and the errors against
                                      the exact solution, or writes the input to DIR
    hertz bench --suite [--write DIR] the robustness suite's table of setups (or their inputs)
    hertz bench --examples DIR        write the verification examples of examples/ to DIR
    hertz --help | --version

OPTIONS:
    -o, --output DIR   directory for the output files (default: next to the input file)
    -q, --quiet        no per-step log lines on stderr
    -v, --verbose      one log line per Newton iteration (residual, contact state)

EXIT CODES:
    0 success, 1 a check rule failed, 2 bad input or usage, 3 the solver failed, 4 output failed
";

fn usage_error(msg: &str) -> ExitCode {
    eprintln!("error: {msg}\n\n{HELP}");
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(cmd) = args.first() else {
        return usage_error("no command given");
    };
    match cmd.as_str() {
        "-h" | "--help" | "help" => {
            print!("{HELP}");
            ExitCode::SUCCESS
        }
        "-V" | "--version" => {
            println!("hertz {}", env!("CARGO_PKG_VERSION"));
            ExitCode::SUCCESS
        }
        "run" | "check" => run_or_check(cmd == "run", &args[1..]),
        "bench" => hertz::bench::main(&args[1..]),
        other => usage_error(&format!("unknown command `{other}`")),
    }
}

fn run_or_check(run: bool, args: &[String]) -> ExitCode {
    let mut file: Option<PathBuf> = None;
    let mut opts = RunOptions {
        write_outputs: run,
        log_steps: true,
        log_iterations: false,
        out_dir: None,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "-o" | "--output" if run => match it.next() {
                Some(d) => opts.out_dir = Some(PathBuf::from(d)),
                None => return usage_error("-o needs a directory"),
            },
            "-q" | "--quiet" => opts.log_steps = false,
            "-v" | "--verbose" => opts.log_iterations = true,
            "-h" | "--help" => {
                print!("{HELP}");
                return ExitCode::SUCCESS;
            }
            s if s.starts_with('-') => return usage_error(&format!("unknown option `{s}`")),
            s if file.is_none() => file = Some(PathBuf::from(s)),
            s => return usage_error(&format!("unexpected argument `{s}`")),
        }
    }
    let Some(file) = file else {
        return usage_error("no input file given");
    };
    match run_file(&file, &opts) {
        Ok(report) => {
            for w in &report.warnings {
                eprintln!("warning: {w}");
            }
            let failed = report.n_failed();
            if report.has_errorcheck {
                for o in report.outcomes.iter().filter(|o| !o.passed) {
                    println!("{}", describe_failure(o));
                }
                println!(
                    "{} passed, {} failed",
                    report.outcomes.len() - failed,
                    failed
                );
            } else if !run {
                println!(
                    "no errorcheck module in {}: nothing to check",
                    file.display()
                );
            }
            if run {
                for p in &report.written {
                    if p.extension().is_some_and(|e| e == "out" || e == "pvd") {
                        eprintln!("wrote {}", p.display());
                    }
                }
            }
            if failed > 0 {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
