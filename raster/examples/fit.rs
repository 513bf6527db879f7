//! Fits the shipped test image (or a given one) and reports time and RMSE:
//! `cargo run --release -p hodr-raster --example fit -- N KIND [OUT.png] [TARGET]`
//! (environment: `FIT_SEED`, `FIT_CANDIDATES`, `FIT_RESTARTS`, `FIT_ITERATIONS`,
//! `FIT_PAIRS` override the defaults of `FitOptions`).

use std::time::Instant;

use hodr_raster::fit::{FitOptions, fit};
use hodr_raster::{Target, test_image};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shapes = args.first().and_then(|s| s.parse().ok()).unwrap_or(16);
    let kind = args.get(1).map_or("triangle", String::as_str).parse()?;
    let target = match args.get(3) {
        Some(path) => Target::open(path)?,
        None => test_image::landscape(test_image::BENCHMARK_SIDE)?,
    };
    let env = |name: &str| {
        std::env::var(name)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
    };
    let defaults = FitOptions::new(shapes, kind);
    let options = FitOptions {
        seed: env("FIT_SEED").map_or(0, |s| s as u64),
        candidates: env("FIT_CANDIDATES").unwrap_or(defaults.candidates),
        restarts: env("FIT_RESTARTS").unwrap_or(defaults.restarts),
        iterations: env("FIT_ITERATIONS").unwrap_or(defaults.iterations),
        pairs: env("FIT_PAIRS").unwrap_or(defaults.pairs),
        ..defaults
    };
    let start = Instant::now();
    let result = fit(&target, &options)?;
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{shapes} {} shapes: {seconds:.3} s, RMSE {:.5} (from {:.5}), {} evaluations",
        kind.name(),
        result.rmse(),
        result.rmse_history()[0],
        result.evaluations()
    );
    if let Some(out) = args.get(2) {
        result.save_png(out)?;
        result.save_svg(format!("{out}.svg"))?;
    }
    Ok(())
}
