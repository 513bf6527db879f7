//! The firmware's workload on the host, and the check that the firmware agrees with it.
//!
//! ```sh
//! cargo run -p hodr-embedded --example host_reference                    # print the report
//! cargo run -p hodr-embedded --example host_reference -- --check FW.log  # compare
//! ```
//!
//! Build it with the same features as the firmware (`--no-default-features`,
//! `--features ncg`, or the default) so that both run the same list of algorithms.
//! `--check` exits with status 1 when the firmware's report differs beyond
//! `hodr_embedded::report::TOLERANCE`, 2 on a usage or I/O error; when the reports
//! agree it also prints each run's θ in decimal (the report itself has only bits).

use std::io::Write;
use std::process::ExitCode;

use hodr_embedded::report::{compare, parse_run};
use hodr_embedded::{Storage, run_all};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut storage = Storage::new();
    let mut report = Vec::new();
    run_all(
        &mut |bytes: &[u8]| report.extend_from_slice(bytes),
        &mut storage,
    );
    let report = String::from_utf8(report).expect("the report is ASCII");

    match args.as_slice() {
        [] => {
            print!("{report}");
            std::io::stdout()
                .flush()
                .map_or(ExitCode::from(2), |()| ExitCode::SUCCESS)
        }
        [flag, path] if flag == "--check" => {
            let firmware = match std::fs::read_to_string(path) {
                Ok(text) => text,
                Err(e) => {
                    eprintln!("host_reference: cannot read {path}: {e}");
                    return ExitCode::from(2);
                }
            };
            match compare(&report, &firmware) {
                Ok(a) => {
                    let how = if a.bit_identical {
                        "bit-identical".to_string()
                    } else {
                        format!("largest scaled difference {:e}", a.max_deviation)
                    };
                    println!("firmware agrees with the host: {} runs, {how}", a.runs);
                    for run in report.lines().filter_map(parse_run) {
                        let theta: Vec<String> = run.theta[..run.dim]
                            .iter()
                            .map(|x| format!("{x:e}"))
                            .collect();
                        let theta = theta.join(", ");
                        println!("  {} {}: θ = ({theta})", run.problem, run.algorithm);
                    }
                    ExitCode::SUCCESS
                }
                Err(mismatch) => {
                    eprintln!("firmware disagrees with the host: {mismatch}");
                    eprintln!("host report:\n{report}");
                    ExitCode::FAILURE
                }
            }
        }
        _ => {
            eprintln!("usage: host_reference [--check FIRMWARE_REPORT]");
            ExitCode::from(2)
        }
    }
}
