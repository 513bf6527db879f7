//! The methods compared: hodr-core's presets and CMA-ES (the `cmaes` crate), run on a
//! task for one seed while recording error against time.
//!
//! Timing: a run's clock measures only optimisation; it is paused while the report
//! probes the image error after each iteration (one extra, untimed evaluation at a fixed
//! noise seed). Runs execute one after another, each free to use both cores inside its
//! objective's batch evaluation, so no two runs compete for a core.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use hodr_core::optim::preset::Preset;
use hodr_core::optim::{Auto, AutoOptions, AutoStep, Budget, Optimiser};
use hodr_core::{Batch, Estimator, NoiseSeed, Objective, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use serde::Serialize;

use super::Settings;
use super::task::Task;

/// A method of the comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// hodr's default optimiser ([`hodr_core::optim::Auto`]): the task's scale σ₀ and
    /// bounds, nothing else.
    Auto,
    /// A hodr-core preset.
    Preset(Preset),
    /// CMA-ES (Hansen), initial step σ₀ of the task, default population; points (and the
    /// mean it reports) mirrored into the task's bounds, as in the suite.
    CmaEs,
}

impl Method {
    /// Every method: Auto, the presets, then CMA-ES.
    pub fn all() -> Vec<Method> {
        [Method::Auto]
            .into_iter()
            .chain(Preset::ALL.iter().map(|&p| Method::Preset(p)))
            .chain([Method::CmaEs])
            .collect()
    }

    /// Display name (a Newton-CG recipe's text form, e.g. `NewtonCG/fr22/compare`).
    pub fn name(&self) -> String {
        match self {
            Method::Auto => "Auto".into(),
            Method::Preset(p) => p.to_string(),
            Method::CmaEs => "CMA-ES".into(),
        }
    }

    /// The method called `name` (case-insensitive), or an error naming it and listing
    /// every method.
    ///
    /// # Errors
    /// An unknown name.
    pub fn parse(name: &str) -> Result<Method> {
        Method::from_name(name).with_context(|| {
            let all: Vec<String> = Method::all().iter().map(Method::name).collect();
            format!(
                "unknown method `{name}` (methods: {}; a Newton-CG recipe adds options to \
                 NewtonCG: /fr22, /ls, /gaussian or /per-element for the gradient, /kernel \
                 for the curvature, /linear for σ, /compare; e.g. NewtonCG/fr22/compare)",
                all.join(", ")
            )
        })
    }

    /// The method called `name` (case-insensitive).
    pub fn from_name(name: &str) -> Option<Method> {
        if name.eq_ignore_ascii_case("cma-es") || name.eq_ignore_ascii_case("cmaes") {
            return Some(Method::CmaEs);
        }
        if name.eq_ignore_ascii_case("auto") {
            return Some(Method::Auto);
        }
        Preset::from_name(name).map(Method::Preset)
    }
}

/// Objective evaluations of a preset's first estimate — its gradient's, or its
/// Hessian's where the method estimates one: a run whose first estimate alone exceeds
/// the budget is skipped rather than run far past it (`--set pairs=100000` on a budget
/// of 200; the per-element Hessian at n = 1024 needs 10⁶ evaluations).
fn first_estimate_cost(
    preset: Preset,
    n: usize,
    h: &hodr_core::optim::preset::Hyper<f64>,
) -> usize {
    let gradient = preset.gradient();
    let hessian = match preset {
        Preset::OurH | Preset::OurHNewton => n * (n + 1) * h.pairs + 1,
        _ => 0,
    };
    gradient.evaluations(n, h.pairs).max(hessian)
}

/// One recorded point of a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Point {
    /// Optimisation wall time, seconds.
    pub time: f64,
    /// Objective evaluations.
    pub evaluations: usize,
    /// ‖θ − θ*‖.
    pub param_error: f64,
    /// The loss at a fixed noise seed.
    pub image_error: f64,
    /// The smoothing width σ of the iteration (CMA-ES: its overall step size); none at
    /// the start.
    pub sigma: Option<f64>,
    /// What Auto's iteration did (accepted a step, probed, …) and the descent the run
    /// is in after it ([`AutoReport::descent`](hodr_core::optim::AutoReport::descent));
    /// none for other methods and at the start. Printed by `hodr optimize`, not written
    /// to files.
    #[serde(skip)]
    pub step: Option<(AutoStep, usize)>,
}

/// One run: task × method × seed.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    /// Task name.
    pub task: String,
    /// Method name.
    pub method: String,
    /// Seed.
    pub seed: u64,
    /// Points after every iteration (the first is the start). Written to
    /// `traces.csv`, not to `results.json`.
    #[serde(skip)]
    pub points: Vec<Point>,
    /// The final θ.
    pub theta: Vec<f64>,
    /// Why the run stopped early, if it did (a failed iteration or an interrupt).
    pub stopped: Option<String>,
    /// Index into `points` of the lowest image error (the latest among equals, so that a
    /// method's own answer — Auto's centre of a flat minimum — wins over the first point
    /// that reached that error): the point a user would keep, which need not be the last.
    #[serde(skip)]
    pub best: usize,
    /// θ at `points[best]`.
    #[serde(skip)]
    pub best_theta: Vec<f64>,
}

impl Run {
    /// True when the method never ran: its first estimate alone exceeds the budget.
    pub fn skipped(&self) -> bool {
        self.stopped
            .as_deref()
            .is_some_and(|s| s.starts_with(SKIPPED))
    }
}

/// How [`Run::stopped`] begins for a run that was skipped.
const SKIPPED: &str = "skipped";

/// Runs `method` on `task` from `task.start(seed)` until the evaluation budget
/// (`settings.budget`, else the task's) is used or `interrupt` is set. Hyper-parameters
/// are the task's with `settings.overrides` applied.
///
/// # Errors
/// When the task's objective cannot be built.
pub fn run(
    task: &dyn Task,
    method: Method,
    seed: u64,
    settings: &Settings,
    interrupt: &AtomicBool,
) -> Result<Run> {
    run_observed(task, method, seed, settings, interrupt, &mut |_| {})
}

/// [`run`], calling `observe` with every point as it is recorded.
///
/// # Errors
/// As [`run`].
pub fn run_observed(
    task: &dyn Task,
    method: Method,
    seed: u64,
    settings: &Settings,
    interrupt: &AtomicBool,
    observe: &mut dyn FnMut(&Point),
) -> Result<Run> {
    let budget = settings
        .budget
        .unwrap_or_else(|| task.budget(settings.quick));
    let mut objective = Guarded {
        inner: task.objective()?,
        interrupt,
        left: budget,
        exhausted: false,
    };
    let mut probe = task.objective()?;
    let start = task.start(seed);
    let param_error = |t: &[f64]| task.param_error(t);
    let mut points = vec![Point {
        time: 0.0,
        evaluations: 0,
        param_error: param_error(&start),
        image_error: task.image_error(probe.as_mut(), &start),
        sigma: None,
        step: None,
    }];
    observe(&points[0]);
    let mut best = (0, start.clone());
    let mut record = |elapsed: Duration,
                      evaluations: usize,
                      sigma: f64,
                      step: Option<(AutoStep, usize)>,
                      theta: &[f64],
                      points: &mut Vec<Point>| {
        let p = Point {
            time: elapsed.as_secs_f64(),
            evaluations,
            param_error: param_error(theta),
            image_error: task.image_error(probe.as_mut(), theta),
            sigma: Some(sigma),
            step,
        };
        observe(&p);
        if p.image_error <= points[best.0].image_error {
            best = (points.len(), theta.to_vec());
        }
        points.push(p);
    };
    let mut stopped = None;
    let theta = match method {
        Method::Preset(preset)
            if first_estimate_cost(
                preset,
                task.dim(),
                &settings.overrides.apply(task.run_hyper(preset)),
            ) > budget =>
        {
            let h = settings.overrides.apply(task.run_hyper(preset));
            let cost = first_estimate_cost(preset, task.dim(), &h);
            stopped = Some(format!(
                "{SKIPPED}: one estimate needs {cost} evaluations, the budget is {budget}"
            ));
            start.clone()
        }
        Method::Preset(preset) => {
            let h = settings.overrides.apply(task.run_hyper(preset));
            let m = preset.method(&h);
            let n = task.dim();
            let mut theta = start.clone();
            let mut buffer = vec![0.0; m.buffer_len(n)];
            let est = Estimator::new(
                h.sigma_start,
                h.pairs,
                Xoshiro256PlusPlus::seed_from_u64(seed),
            )?;
            let mut opt = Optimiser::new(
                m,
                preset.schedule(&h),
                Budget::evaluations(budget),
                est,
                &mut theta,
                &mut buffer,
            )?;
            let rows = 64;
            let (mut wb, mut seeds) = (vec![0.0; m.workspace_len(n, rows)], vec![0; rows]);
            let mut ws = Workspace::new(n, &mut wb, &mut seeds)?;
            let mut elapsed = Duration::ZERO;
            loop {
                if interrupt.load(Ordering::Relaxed) {
                    stopped = Some("interrupted".to_string());
                    break;
                }
                let clock = Instant::now();
                let step = opt.step(&mut objective, &mut ws, 0.0);
                elapsed += clock.elapsed();
                if objective.exhausted {
                    // The iteration that would overrun the budget, abandoned.
                    break;
                }
                match step {
                    Err(failed) if failed.error == hodr_core::Error::Cancelled => {
                        stopped = Some("interrupted".to_string());
                        break;
                    }
                    Ok(Some(report)) => record(
                        elapsed,
                        report.evaluations,
                        report.sigma,
                        None,
                        opt.theta(),
                        &mut points,
                    ),
                    Ok(None) => break,
                    Err(failed) => {
                        stopped = Some(failed.to_string());
                        break;
                    }
                }
            }
            if objective.exhausted && points.len() == 1 {
                stopped = Some(format!(
                    "{SKIPPED}: its first iteration needs more than the budget of {budget} evaluations"
                ));
            }
            opt.theta().to_vec()
        }
        Method::Auto => {
            let n = task.dim();
            let mut theta = start.clone();
            let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
            let options = AutoOptions::default().with_max_evaluations(budget)?;
            let mut auto = Auto::new(
                &mut theta,
                task.scale(),
                &mut buffer,
                Xoshiro256PlusPlus::seed_from_u64(seed),
            )?
            .with_options(options);
            if let Some((lower, upper)) = task.bounds() {
                auto = auto.with_bounds(&lower, &upper)?;
            }
            let mut elapsed = Duration::ZERO;
            loop {
                if interrupt.load(Ordering::Relaxed) {
                    stopped = Some("interrupted".to_string());
                    break;
                }
                let clock = Instant::now();
                let step = auto.step(&mut objective);
                elapsed += clock.elapsed();
                match step {
                    Err(hodr_core::Error::Cancelled) => {
                        stopped = Some("interrupted".to_string());
                        break;
                    }
                    Ok(Some(report)) => record(
                        elapsed,
                        report.evaluations,
                        report.sigma,
                        Some((report.kind, report.descent)),
                        auto.theta(),
                        &mut points,
                    ),
                    Ok(None) => break,
                    Err(error) => {
                        stopped = Some(error.to_string());
                        break;
                    }
                }
            }
            auto.theta().to_vec()
        }
        Method::CmaEs => {
            let sigma = task.scale();
            // The task's bounds as the suite gives them: points mirrored into the box.
            let bounds = task
                .bounds()
                .map(|(lower, upper)| crate::suite::problem::Bounds { lower, upper });
            let inside = move |x: &[f64]| {
                let mut x = x.to_vec();
                if let Some(b) = &bounds {
                    b.reflect(&mut x);
                }
                x
            };
            let mut noise = 0u64;
            let mut f = |x: &cmaes::DVector<f64>| {
                noise = noise.wrapping_add(1);
                objective.inner.evaluate(&inside(x.as_slice()), noise)
            };
            let mut cma = cmaes::CMAESOptions::new(start.clone(), sigma)
                .seed(seed)
                .max_function_evals(budget)
                .build(&mut f)
                .map_err(|e| anyhow::anyhow!("CMA-ES options: {e:?}"))?;
            let mut elapsed = Duration::ZERO;
            let lambda = cma.parameters().lambda();
            loop {
                if interrupt.load(Ordering::Relaxed) {
                    stopped = Some("interrupted".to_string());
                    break;
                }
                if cma.function_evals() + lambda > budget {
                    // A generation would overrun the budget.
                    if cma.function_evals() == 0 {
                        stopped = Some(format!(
                            "{SKIPPED}: one generation needs {lambda} evaluations, the budget is {budget}"
                        ));
                    }
                    break;
                }
                let clock = Instant::now();
                let done = cma.next();
                elapsed += clock.elapsed();
                let mean = inside(cma.mean().as_slice());
                record(
                    elapsed,
                    cma.function_evals(),
                    cma.sigma(),
                    None,
                    &mean,
                    &mut points,
                );
                if done.is_some() {
                    break;
                }
            }
            inside(cma.mean().as_slice())
        }
    };
    let (best, best_theta) = best;
    Ok(Run {
        task: task.name().to_string(),
        method: method.name(),
        seed,
        points,
        theta,
        stopped,
        best,
        best_theta,
    })
}

/// A task's objective that evaluates at most `left` points and reports the run's
/// interrupt flag after every batch, so Ctrl-C stops an estimate within one batch
/// ([`Objective::cancelled`]). Past the budget it evaluates nothing: the points it
/// skips get NaN and it reports itself cancelled, so the iteration that would overrun
/// the budget is abandoned (a preset's iteration costs several estimates, which its
/// optimiser cannot foresee) and the run keeps the iterations that fit.
struct Guarded<'a> {
    inner: Box<dyn Objective<f64> + Send>,
    interrupt: &'a AtomicBool,
    /// Evaluations the budget has left.
    left: usize,
    /// Whether an evaluation was refused for the budget.
    exhausted: bool,
}

impl Objective<f64> for Guarded<'_> {
    fn evaluate(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        if self.left == 0 {
            self.exhausted = true;
            return f64::NAN;
        }
        self.left -= 1;
        self.inner.evaluate(theta, seed)
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) {
        let rows = batch.len().min(self.left);
        if rows == batch.len() {
            self.inner.evaluate_batch(batch, out);
        } else {
            self.exhausted = true;
            let n = batch.dim();
            if let Ok(part) = Batch::new(&batch.points()[..rows * n], &batch.seeds()[..rows], n) {
                self.inner.evaluate_batch(&part, &mut out[..rows]);
            }
            out[rows..batch.len()].fill(f64::NAN);
        }
        self.left -= rows;
    }

    fn deterministic(&self) -> bool {
        self.inner.deterministic()
    }

    fn cancelled(&mut self) -> bool {
        self.exhausted || self.interrupt.load(Ordering::Relaxed) || self.inner.cancelled()
    }
}
