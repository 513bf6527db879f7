//! One render of a task at θ*, for instruction counts under callgrind, which (unlike
//! wall time on a shared machine) repeat exactly:
//!
//! ```text
//! cargo build --release -p hodr-host --example render_cost
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind target/release/examples/render_cost \
//!     [SEQUENCE] [TASK] [SIZE] [SPP]
//! ```
//!
//! SEQUENCE is `PaddedSobol` (default), `PaddedR2`, `Kronecker` or `Independent`; TASK
//! a path-traced task (default SHADOW); the image is SIZE × SIZE (default 64) at SPP
//! samples per pixel (default 16). Prints the mean pixel value, so the render cannot be
//! optimised away and runs can be compared.

use std::process::ExitCode;

use hodr_host::render::{Film, Sequence, render};
use hodr_host::tasks;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |k: usize, default: &str| args.get(k).cloned().unwrap_or(default.to_owned());
    let sequence = match arg(0, "PaddedSobol").as_str() {
        "PaddedSobol" => Sequence::PaddedSobol,
        "PaddedR2" => Sequence::PaddedR2,
        "Kronecker" => Sequence::Kronecker,
        "Independent" => Sequence::Independent,
        other => {
            eprintln!("error: unknown sequence {other}");
            return ExitCode::FAILURE;
        }
    };
    let (Ok(size), Ok(spp)) = (arg(2, "64").parse::<u32>(), arg(3, "16").parse::<u32>()) else {
        eprintln!("error: SIZE and SPP must be positive integers");
        return ExitCode::FAILURE;
    };
    let result = (|| -> Result<f64, Box<dyn std::error::Error>> {
        let task = tasks::by_name(&arg(1, "SHADOW")).ok_or("unknown task")?;
        let mut parametric = task.scene()?;
        parametric.set_params(&task.true_params())?;
        let mut scene = parametric.scene().clone();
        scene.set_sequence(sequence);
        let mut film = Film::new(size, size)?;
        render(&scene, &mut film, spp, 1)?;
        let sum: f64 = film.data().iter().map(|&v| f64::from(v)).sum();
        Ok(sum / film.data().len() as f64)
    })();
    match result {
        Ok(mean) => {
            println!("mean pixel value {mean:.6}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
