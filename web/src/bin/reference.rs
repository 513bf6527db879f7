//! The native reference for the browser test and the render benchmark.
//!
//! `reference run TASK METHOD SEED` prints the outcome of [`hodr_web::run::run`] as
//! JSON; `reference bench RENDERS` prints BOX2 renders per second and the checksum.

use std::process::ExitCode;
use std::time::Instant;

use hodr_web::run::{self, Method, RenderLoop, RunSettings, Unpaced};

fn floats(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
    format!("[{}]", items.join(","))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let result = match args.as_slice() {
        ["run", task, method, seed] => run_one(task, method, seed),
        ["bench", renders] => bench(renders),
        _ => Err("usage: reference run TASK METHOD SEED | reference bench RENDERS".into()),
    };
    match result {
        Ok(json) => {
            println!("{json}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("reference: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_one(task: &str, method: &str, seed: &str) -> Result<String, String> {
    let method = Method::from_name(method).map_err(|e| e.to_string())?;
    let seed: u64 = seed.parse().map_err(|_| format!("bad seed {seed}"))?;
    let settings = RunSettings::new(task, method, seed);
    let out = run::block_on(run::run(&settings, &mut Unpaced)).map_err(|e| e.to_string())?;
    let to_target = out
        .evaluations_to_target
        .map_or("null".to_string(), |e| e.to_string());
    Ok(format!(
        "{{\"method\":\"{}\",\"evaluations\":{},\"iterations\":{},\"theta\":{},\"initialError\":{:?},\"error\":{:?},\"evaluationsToTarget\":{},\"stopped\":\"{}\"}}",
        out.method.name(),
        out.evaluations,
        out.iterations,
        floats(&out.theta),
        out.initial_error,
        out.error,
        to_target,
        out.stopped
    ))
}

fn bench(renders: &str) -> Result<String, String> {
    let renders: usize = renders
        .parse()
        .map_err(|_| format!("bad count {renders}"))?;
    let mut bench = RenderLoop::box2().map_err(|e| e.to_string())?;
    bench.run(1000);
    let clock = Instant::now();
    let checksum = bench.run(renders);
    let seconds = clock.elapsed().as_secs_f64();
    Ok(format!(
        "{{\"renders\":{renders},\"seconds\":{seconds:?},\"rendersPerSecond\":{:?},\"checksum\":{checksum:?}}}",
        renders as f64 / seconds
    ))
}
