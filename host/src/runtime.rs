//! Error against run time for every preset on QUAD, BOX2-REF and stiff quadratics.
//!
//! For each task × preset × seed the optimiser runs on one thread, stepping under a
//! wall clock; after every iteration the parameter error ‖θ − θ*‖ is recorded with the
//! elapsed time and evaluation count ([`crate::metrics`]). The table gives, per preset,
//! the median over seeds of the time and evaluations to 90 / 99 / 99.9 % parameter-error
//! reduction ("—" when half or more of the seeds never get there).
//!
//! QUAD, QUAD-far and BOX2-REF are the report's tasks ([`crate::report::task`]), run as
//! the report runs them: the same starts, objective and hyper-parameters
//! ([`Task::run_hyper`]: the paper's, docs/design.md §3, for its presets; what the task states
//! for a Newton-CG recipe) and the full report's evaluation budget ([`Task::budget`]).
//! STIFF-κ ([`Stiff`]) is defined here:
//!
//! | task | start | pairs | σ | Δ | LS | recompute | Adam η | budget |
//! |---|---|---|---|---|---|---|---|---|
//! | STIFF-κ | θ* + 1·(unit vector) | 4 | 0.5 → 0.05 | 10 | 3 | 5 | 0.05 | 3000 evaluations |
//!
//! STIFF-κ is ½(x − θ*)ᵀA(x − θ*) in 2-D with eigenvalues 1 and κ on axes rotated by 30°.
//! With `crn`, the paper's central-difference presets draw their two gradients with
//! common random numbers.

use std::fmt::Write as _;
use std::time::Instant;

use anyhow::Result;
use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::{Budget, Optimiser};
use hodr_core::{Estimator, Objective, Real, Workspace};
use image::RgbImage;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::metrics::{REDUCTIONS, Sample, first_reaching, format_seconds, median};
use crate::report::task::{Box2RefTask, Quad, Task};

/// The tasks of the default table: QUAD, QUAD-far, BOX2-REF, then STIFF-κ for
/// κ = 10², 10⁴, 10⁶, 10⁸.
pub fn tasks() -> Vec<Box<dyn Task>> {
    let mut tasks: Vec<Box<dyn Task>> = vec![
        Box::new(Quad::new(false)),
        Box::new(Quad::new(true)),
        Box::new(Box2RefTask),
    ];
    for kappa in [1e2, 1e4, 1e6, 1e8] {
        tasks.push(Box::new(Stiff::new(kappa)));
    }
    tasks
}

/// STIFF-κ: ½(x − θ*)ᵀA(x − θ*) with A = R diag(1, κ) Rᵀ, R a rotation by 30°,
/// θ* = (0.3, −0.2); starts at distance 1 from θ* in a uniformly random direction.
pub struct Stiff {
    kappa: f64,
    name: String,
    /// Row-major A.
    a: [f64; 4],
}

impl Stiff {
    /// θ*.
    pub const OPTIMUM: [f64; 2] = [0.3, -0.2];

    /// STIFF-κ with condition number `kappa`.
    pub fn new(kappa: f64) -> Self {
        let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        let a = [
            c * c + kappa * s * s,
            (1.0 - kappa) * c * s,
            (1.0 - kappa) * c * s,
            s * s + kappa * c * c,
        ];
        Stiff {
            kappa,
            name: format!("STIFF-{kappa:.0e}"),
            a,
        }
    }
}

impl Task for Stiff {
    fn name(&self) -> &str {
        &self.name
    }
    fn description(&self) -> String {
        format!(
            "2-D quadratic, eigenvalues 1 and {:.0e} on axes rotated by 30°, starts 1 from θ*",
            self.kappa
        )
    }
    fn dim(&self) -> usize {
        2
    }
    fn optimum(&self) -> Vec<f64> {
        Stiff::OPTIMUM.to_vec()
    }
    fn start(&self, seed: u64) -> Vec<f64> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ 0x5EED_0F57_A127);
        let angle = std::f64::consts::TAU * f64::uniform_open(&mut rng);
        let o = Stiff::OPTIMUM;
        vec![o[0] + angle.cos(), o[1] + angle.sin()]
    }
    /// 4 pairs, σ 0.5 → 0.05, Δ = 10, 3 line-search steps to tolerance 1e-12, recompute
    /// 5, Adam η = 0.05.
    fn hyper(&self, _preset: Preset) -> Hyper<f64> {
        Hyper {
            pairs: 4,
            sigma_start: 0.5,
            sigma_end: 0.05,
            trust_radius: 10.0,
            line_search_iterations: 3,
            line_search_tolerance: 1e-12,
            recompute: 5,
            learning_rate: 0.05,
            ..Hyper::default()
        }
    }
    fn budget(&self, quick: bool) -> usize {
        if quick { 1500 } else { 3000 }
    }
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>> {
        let (a, o) = (self.a, Stiff::OPTIMUM);
        Ok(Box::new(move |x: &[f64]| {
            let d = [x[0] - o[0], x[1] - o[1]];
            0.5 * (d[0] * (a[0] * d[0] + a[1] * d[1]) + d[1] * (a[2] * d[0] + a[3] * d[1]))
        }))
    }
    fn image(&self, _theta: &[f64]) -> Result<Option<RgbImage>> {
        Ok(None)
    }
}

/// One run of `preset` on `task` from `task.start(seed)` for `budget` evaluations: the
/// samples (time, evaluations, parameter error) after every iteration. A failed
/// iteration ends the run; its samples so far stand.
///
/// # Errors
/// When the task's objective cannot be built or its settings are invalid.
pub fn run(
    task: &dyn Task,
    preset: Preset,
    seed: u64,
    budget: usize,
    crn: bool,
) -> Result<Vec<Sample>> {
    let h = task.run_hyper(preset).with_common_random_numbers(crn);
    let method = preset.method(&h);
    let n = task.dim();
    let mut theta = task.start(seed);
    let mut buffer = vec![0.0; method.buffer_len(n)];
    let est = Estimator::new(
        h.sigma_start,
        h.pairs,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )?;
    let mut opt = Optimiser::new(
        method,
        preset.schedule(&h),
        Budget::evaluations(budget),
        est,
        &mut theta,
        &mut buffer,
    )?;
    let rows = 64;
    let (mut wb, mut seeds) = (vec![0.0; method.workspace_len(n, rows)], vec![0; rows]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds)?;
    let mut objective = task.objective()?;
    let error = |t: &[f64]| task.param_error(t);
    let mut samples = vec![Sample {
        time: 0.0,
        evaluations: 0,
        error: error(opt.theta()),
    }];
    let clock = Instant::now();
    while let Ok(Some(report)) = opt.step(objective.as_mut(), &mut ws, 0.0) {
        samples.push(Sample {
            time: clock.elapsed().as_secs_f64(),
            evaluations: report.evaluations,
            error: error(opt.theta()),
        });
    }
    Ok(samples)
}

/// The Markdown tables for `tasks` × `presets` over `seeds` seeds, each run with its
/// task's full evaluation budget ([`Task::budget`]).
///
/// # Errors
/// As [`run`].
pub fn table(tasks: &[Box<dyn Task>], presets: &[Preset], seeds: u64, crn: bool) -> Result<String> {
    let mut md = String::new();
    for task in tasks {
        let budget = task.budget(false);
        let _ = writeln!(md, "### {}\n", task.name());
        let _ = writeln!(
            md,
            "| method | 90 %: time / evals | 99 %: time / evals | 99.9 %: time / evals | median final error |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|");
        for &preset in presets {
            let runs = (0..seeds)
                .map(|s| run(task.as_ref(), preset, s, budget, crn))
                .collect::<Result<Vec<Vec<Sample>>>>()?;
            let _ = write!(md, "| {preset} |");
            for reduction in REDUCTIONS {
                let reached: Vec<_> = runs.iter().map(|r| first_reaching(r, reduction)).collect();
                let t = median(
                    &reached
                        .iter()
                        .map(|r| r.map(|x| x.time))
                        .collect::<Vec<_>>(),
                );
                let e = median(
                    &reached
                        .iter()
                        .map(|r| r.map(|x| x.evaluations as f64))
                        .collect::<Vec<_>>(),
                );
                let evals = e.map_or("—".to_string(), |e| format!("{e:.0}"));
                let _ = write!(md, " {} / {} |", format_seconds(t), evals);
            }
            let finals: Vec<Option<f64>> = runs.iter().map(|r| r.last().map(|s| s.error)).collect();
            let _ = writeln!(md, " {:.2e} |", median(&finals).unwrap_or(f64::NAN));
        }
        let _ = writeln!(md);
    }
    Ok(md)
}
