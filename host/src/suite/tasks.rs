//! Built-in rendering tasks as suite problems: BOX2 of hodr-raster (a square's position
//! on a 64×64 image, image MSE, starts on the plateau where the square does not overlap
//! its target; `hodr_raster::tasks`). Its definition is the task's own — truth, start
//! distribution — with σ₀ the task's σ at the start (the square's half-width), bounds
//! the image ([0, 8]² in the task's units of size/8 px) and f* = f(θ*), the target being
//! the render at θ*.

use std::sync::Mutex;

use anyhow::{Context, Result};
use hodr_core::Objective;
use hodr_raster::RasterObjective;

use super::problem::{Bounds, Family, Measure, Observation, Problem};

/// The image side in the task's parameter units (θ is in units of size/8 px).
const EXTENT: f64 = 8.0;

/// BOX2 as a suite problem.
///
/// The raster objective keeps caches and is evaluated through `&mut`, so the problem's
/// f draws one from a pool (building another when every pooled one is in use by a
/// parallel evaluation) and returns it afterwards; rasterisation is deterministic, so
/// which objective evaluates a point does not matter.
///
/// # Errors
/// When the task or its objective cannot be built.
pub fn box2(budget_per_dim: usize) -> Result<Problem> {
    let task = hodr_raster::tasks::by_name("box2").context("raster task box2")?;
    let n = task.dim();
    let pool: Mutex<Vec<RasterObjective>> = Mutex::new(vec![task.objective()?]);
    let maker = task.clone();
    let f = move |x: &[f64]| {
        let taken = pool.lock().map(|mut p| p.pop()).unwrap_or(None);
        let mut objective = match taken {
            Some(o) => o,
            None => match maker.objective() {
                Ok(o) => o,
                Err(_) => return f64::NAN,
            },
        };
        let value = objective.evaluate(x, 0);
        if let Ok(mut p) = pool.lock() {
            p.push(objective);
        }
        value
    };
    let x_opt = task.theta_true().to_vec();
    let f_opt = f(&x_opt);
    let start_task = task.clone();
    Ok(Problem {
        name: task.name().to_ascii_uppercase(),
        family: Family::Tasks,
        n,
        f: Box::new(f),
        observation: Observation::Exact,
        f_opt,
        x_opt,
        measure: Measure::Euclidean,
        start: Box::new(move |seed| start_task.start(seed)),
        sigma0: task.settings().sigma_start,
        bounds: Some(Bounds::cube(n, 0.0, EXTENT)),
        budget: budget_per_dim * n,
    })
}
