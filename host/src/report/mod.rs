//! The report harness: error against run time for every method on every task
//! (docs/design.md §4–5).
//!
//! For each task × method × seed it records, after every iteration, the optimisation
//! wall time, the objective evaluations, the image error (the loss at a fixed noise
//! seed) and the parameter error ‖θ − θ*‖; then it writes
//!
//! * `report.md`: per task, the median time / evaluations to 90, 99, 99.9 % reduction
//!   of image and parameter error, each method's ratio to the best, the plots and strip;
//! * `plot_<task>_{image,param}.png`: median error against time, log–log;
//! * `strip_<task>.png`: init / result / target (tasks with images);
//! * `results.csv` (one row per run), `traces.csv` (one row per recorded point) and
//!   `results.json` (settings, summary, each run's outcome);
//! * unless [`Config::suite`] is [`SuiteScope::Off`], the generalisation suite
//!   ([`crate::suite`]) in `suite/`, its per-family table and ECDF plot in `report.md`.
//!
//! Timing policy: runs execute one at a time; inside a run the objective may use both
//! cores (batch evaluation); the clock is paused while the error probe runs. Within a
//! task the methods take turns seed by seed (seed 0 of every method, then seed 1, …),
//! so that a slow drift of the machine's speed (other tenants, clock boosts) falls on
//! every method alike rather than on whichever ran during it. An
//! interrupt (Ctrl-C or SIGTERM) stops the current run at its next iteration, and the report is
//! written from the runs finished so far.

mod method;
mod output;
pub(crate) mod plot;
mod summary;
pub mod task;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result, bail};
use hodr_core::optim::NegativeCurvature;
use hodr_core::optim::preset::Hyper;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

pub use method::{Method, Point, Run, run, run_observed};
pub use summary::{ErrorKind, Row};

/// Command-line overrides of the per-task hyper-parameters (applied to every task).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Overrides {
    /// Antithetic pairs.
    pub pairs: Option<usize>,
    /// σ at the start.
    pub sigma_start: Option<f64>,
    /// σ at the end.
    pub sigma_end: Option<f64>,
    /// Trust radius Δ (units of σ).
    pub trust_radius: Option<f64>,
    /// Line-search steps.
    pub line_search_iterations: Option<usize>,
    /// NCG restart period.
    pub recompute: Option<usize>,
    /// Adam's learning rate.
    pub learning_rate: Option<f64>,
    /// Common random numbers for the paper's HVP presets.
    pub common_random_numbers: Option<bool>,
    /// The step of NCG and Newton-CG at non-positive curvature.
    #[serde(serialize_with = "serialize_negative_curvature")]
    pub negative_curvature: Option<NegativeCurvature>,
    /// The adaptive schedule's shrink factor.
    pub sigma_shrink: Option<f64>,
    /// Newton-CG's inner CG steps per iteration.
    pub inner_steps: Option<usize>,
    /// Newton-CG's first curvature from f on a line along ĝ.
    pub line_curvature: Option<bool>,
}

/// `--set negative_curvature=` names, both ways.
const NEGATIVE_CURVATURE_NAMES: [(&str, NegativeCurvature); 2] = [
    ("fallback", NegativeCurvature::Fallback),
    ("two-sided", NegativeCurvature::TwoSided),
];

fn serialize_negative_curvature<S: serde::Serializer>(
    value: &Option<NegativeCurvature>,
    serializer: S,
) -> std::result::Result<S::Ok, S::Error> {
    let name = value.and_then(|v| {
        NEGATIVE_CURVATURE_NAMES
            .iter()
            .find(|(_, c)| *c == v)
            .map(|(n, _)| *n)
    });
    match name {
        Some(n) => serializer.serialize_some(n),
        None => serializer.serialize_none(),
    }
}

impl Overrides {
    /// `h` with every set override applied.
    pub fn apply(&self, mut h: Hyper<f64>) -> Hyper<f64> {
        if let Some(v) = self.pairs {
            h.pairs = v;
        }
        if let Some(v) = self.sigma_start {
            h.sigma_start = v;
        }
        if let Some(v) = self.sigma_end {
            h.sigma_end = v;
        }
        if let Some(v) = self.trust_radius {
            h.trust_radius = v;
        }
        if let Some(v) = self.line_search_iterations {
            h.line_search_iterations = v;
        }
        if let Some(v) = self.recompute {
            h.recompute = v;
        }
        if let Some(v) = self.learning_rate {
            h.learning_rate = v;
        }
        if let Some(v) = self.common_random_numbers {
            h.common_random_numbers = v;
        }
        if let Some(v) = self.negative_curvature {
            h.negative_curvature = v;
        }
        if let Some(v) = self.sigma_shrink {
            h.sigma_shrink = v;
        }
        if let Some(v) = self.inner_steps {
            h.inner_steps = v;
        }
        if let Some(v) = self.line_curvature {
            h.line_curvature = v;
        }
        h
    }

    /// Whether no override is set.
    pub fn is_empty(&self) -> bool {
        *self == Overrides::default()
    }

    /// Parses one `key=value` override.
    ///
    /// # Errors
    /// An unknown key, an unparsable value, or one out of the key's range (counts ≥ 1;
    /// σ, radius and rate finite and > 0; sigma_shrink in (0, 1)), named as typed.
    pub fn set(&mut self, assignment: &str) -> Result<()> {
        let (key, value) = assignment
            .split_once('=')
            .with_context(|| format!("`{assignment}` is not key=value"))?;
        let bad = || format!("bad value `{value}` for `{key}`");
        let value = value.trim();
        let count = || -> Result<usize> {
            match value.parse().with_context(bad)? {
                0 => bail!("--set {key}={value}: {key} must be at least 1"),
                n => Ok(n),
            }
        };
        let positive = || -> Result<f64> {
            let x: f64 = value.parse().with_context(bad)?;
            if !(x.is_finite() && x > 0.0) {
                bail!("--set {key}={value}: {key} must be a finite number above 0");
            }
            Ok(x)
        };
        match key.trim() {
            "pairs" => self.pairs = Some(count()?),
            "sigma_start" => self.sigma_start = Some(positive()?),
            "sigma_end" => self.sigma_end = Some(positive()?),
            "trust_radius" => self.trust_radius = Some(positive()?),
            "ls_iters" | "line_search_iterations" => self.line_search_iterations = Some(count()?),
            "recompute" => self.recompute = Some(count()?),
            "lr" | "learning_rate" => self.learning_rate = Some(positive()?),
            "crn" => self.common_random_numbers = Some(value.parse().with_context(bad)?),
            "sigma_shrink" => {
                let x = positive()?;
                if x >= 1.0 {
                    bail!("--set {key}={value}: {key} must lie between 0 and 1");
                }
                self.sigma_shrink = Some(x);
            }
            "inner_steps" => self.inner_steps = Some(count()?),
            "line_curvature" => self.line_curvature = Some(value.parse().with_context(bad)?),
            "negative_curvature" => {
                let named = NEGATIVE_CURVATURE_NAMES
                    .iter()
                    .find(|(n, _)| *n == value)
                    .map(|(_, c)| *c);
                self.negative_curvature =
                    Some(named.with_context(|| format!("{} (fallback or two-sided)", bad()))?);
            }
            other => bail!(
                "unknown hyper-parameter `{other}` (pairs, sigma_start, sigma_end, trust_radius, ls_iters, recompute, lr, crn, negative_curvature, sigma_shrink, inner_steps, line_curvature)"
            ),
        }
        Ok(())
    }
}

/// How runs are made.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Settings {
    /// The smaller budgets of `--quick`.
    pub quick: bool,
    /// Evaluations per run for every task, instead of the task's own.
    pub budget: Option<usize>,
    /// Hyper-parameter overrides.
    pub overrides: Overrides,
}

impl Settings {
    /// Checks that the overrides tune some method of `methods`: only the presets have
    /// hyper-parameters.
    ///
    /// # Errors
    /// Overrides set where no method is a preset.
    pub fn check_for(&self, methods: &[Method]) -> Result<()> {
        if !self.overrides.is_empty() && !methods.iter().any(|m| matches!(m, Method::Preset(_))) {
            let names: Vec<String> = methods.iter().map(|m| m.name()).collect();
            let verb = if names.len() == 1 { "takes" } else { "take" };
            bail!(
                "--set tunes the paper's presets; {} {verb} no hyper-parameters",
                names.join(" and ")
            );
        }
        Ok(())
    }
}

/// What to run.
#[derive(Clone, Debug, Serialize)]
pub struct Config {
    /// Task names (empty: all).
    pub tasks: Vec<String>,
    /// Method names (empty: all).
    pub methods: Vec<String>,
    /// Seeds 0..seeds per task × method.
    pub seeds: u64,
    /// Run settings.
    pub settings: Settings,
    /// Output directory.
    pub out: PathBuf,
    /// The generalisation suite run after the tasks, into `out/suite`.
    pub suite: SuiteScope,
}

/// How much of the generalisation suite ([`crate::suite`]) a report runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum SuiteScope {
    /// None.
    Off,
    /// `hodr suite --quick`: n ≤ 5, 2 seeds, 2 instances, 200·n evaluations (seconds).
    #[default]
    Quick,
    /// `hodr suite`: every dimension, 5 seeds, 5 instances, 1 000·n evaluations (tens of
    /// minutes).
    Full,
}

/// Runs the report and writes its files; returns the path of `report.md`.
///
/// # Errors
/// Unknown tasks or methods, a task that cannot be set up, unwritable output.
pub fn report(config: &Config, interrupt: &AtomicBool, progress: bool) -> Result<PathBuf> {
    let tasks = task::select(&config.tasks, config.settings.quick)?;
    let methods: Vec<Method> = if config.methods.is_empty() {
        Method::all()
    } else {
        let mut chosen: Vec<Method> = Vec::new();
        for name in &config.methods {
            let m = Method::parse(name)?;
            if chosen.contains(&m) {
                bail!("method `{name}` listed twice");
            }
            chosen.push(m);
        }
        chosen
    };
    if config.seeds == 0 {
        bail!("--seeds must be at least 1");
    }
    config.settings.check_for(&methods)?;
    std::fs::create_dir_all(&config.out)
        .with_context(|| format!("creating {}", config.out.display()))?;
    let total = tasks.len() as u64 * methods.len() as u64 * config.seeds;
    let bar = if progress {
        ProgressBar::new(total)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut runs = Vec::new();
    'outer: for t in &tasks {
        for seed in 0..config.seeds {
            for &m in &methods {
                if interrupt.load(Ordering::Relaxed) {
                    break 'outer;
                }
                bar.set_message(format!("{} {} seed {seed}", t.name(), m.name()));
                let r = run(t.as_ref(), m, seed, &config.settings, interrupt)?;
                let interrupted = r.stopped.as_deref() == Some("interrupted");
                if !interrupted {
                    runs.push(r);
                }
                bar.inc(1);
            }
        }
    }
    bar.finish_and_clear();
    // Rows by task, method, seed (the order they were asked for).
    let task_names: Vec<&str> = tasks.iter().map(|t| t.name()).collect();
    let method_names: Vec<String> = methods.iter().map(Method::name).collect();
    let method_names: Vec<&str> = method_names.iter().map(String::as_str).collect();
    let index = |names: &[&str], name: &str| names.iter().position(|n| *n == name);
    runs.sort_by_key(|r| {
        (
            index(&task_names, &r.task),
            index(&method_names, &r.method),
            r.seed,
        )
    });
    let suite = if config.suite == SuiteScope::Off || interrupt.load(Ordering::Relaxed) {
        None
    } else {
        let scope = crate::suite::Config::from_args(
            &[],
            &[],
            &[],
            None,
            None,
            config.suite == SuiteScope::Quick,
            config.out.join(SUITE_DIR),
        )?;
        Some(crate::suite::run(&scope, interrupt, progress)?)
    };
    write_outputs(
        config,
        &tasks,
        &methods,
        &runs,
        suite.as_ref(),
        interrupt.load(Ordering::Relaxed),
    )
}

/// The report's subdirectory holding the suite's files.
const SUITE_DIR: &str = "suite";

fn write_outputs(
    config: &Config,
    tasks: &[Box<dyn task::Task>],
    methods: &[Method],
    runs: &[Run],
    suite: Option<&crate::suite::Outcome>,
    interrupted: bool,
) -> Result<PathBuf> {
    use std::fmt::Write as _;
    let out = &config.out;
    let names: Vec<String> = methods.iter().map(Method::name).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut all_rows = Vec::new();
    let mut md = String::from("# hodr report: error against run time\n\n");
    // The seeds of `task` every method finished (an interrupt cuts a task short).
    let seeds_run = |task: &str| {
        (0..config.seeds)
            .take_while(|&s| {
                methods.iter().all(|m| {
                    runs.iter()
                        .any(|r| r.task == task && r.method == m.name() && r.seed == s)
                })
            })
            .count() as u64
    };
    let _ = writeln!(
        md,
        "Seeds: {}{} per task × method{}. Cells: median wall time / objective evaluations to 90, 99 and 99.9 % \
         reduction of the image error (the loss at a fixed noise seed) and of the parameter error ‖θ − θ*‖; \
         \"—\" where half or more of the seeds never got there. ×best: median time to 99 % parameter-error \
         reduction over the best method's. Runs execute one at a time, the methods taking turns seed by seed; \
         the clock excludes the error probes.\n",
        if interrupted { "up to " } else { "" },
        config.seeds,
        if config.settings.quick {
            " (quick budgets)"
        } else {
            ""
        }
    );
    if interrupted {
        let _ = writeln!(
            md,
            "**Interrupted**: only the runs finished before the signal (Ctrl-C or SIGTERM) are included.\n"
        );
    }
    for t in tasks {
        let mine: Vec<Run> = runs
            .iter()
            .filter(|r| r.task == t.name())
            .cloned()
            .collect();
        if mine.is_empty() {
            continue;
        }
        let rows = summary::rows(t.name(), &names, &mine);
        let slug = output::slug(t.name());
        let ran = seeds_run(t.name());
        let _ = writeln!(
            md,
            "## {}\n\n{} (n = {}){}.\n",
            t.name(),
            t.description(),
            t.dim(),
            if ran < config.seeds {
                format!(
                    "; interrupted: {ran} of {} seeds finished by every method",
                    config.seeds
                )
            } else {
                String::new()
            }
        );
        md.push_str(&output::table(&rows));
        md.push('\n');
        let mut skipped: Vec<&str> = mine
            .iter()
            .filter(|r| r.skipped())
            .map(|r| r.method.as_str())
            .collect();
        skipped.dedup();
        if !skipped.is_empty() {
            let _ = writeln!(
                md,
                "Skipped (one estimate, iteration or generation exceeds the run's budget): {}.\n",
                skipped.join(", ")
            );
        }
        // Runs that stopped on an error (not the budget, an interrupt or a skip): named,
        // so that a row of a failed method does not read as one that merely did badly.
        for r in mine.iter().filter(|r| {
            r.stopped
                .as_deref()
                .is_some_and(|why| why != "interrupted" && !r.skipped())
        }) {
            let _ = writeln!(
                md,
                "Failed: {} seed {}: {}.\n",
                r.method,
                r.seed,
                r.stopped.as_deref().unwrap_or_default()
            );
        }
        for kind in ErrorKind::BOTH {
            let file = format!("plot_{slug}_{}.png", kind.label());
            plot::error_against_time(&out.join(&file), t.name(), kind, &names, &mine)?;
            if out.join(&file).exists() {
                let _ = writeln!(
                    md,
                    "![{} {} error against time]({file})\n",
                    t.name(),
                    kind.label()
                );
            }
        }
        if let Some(best) = rows
            .iter()
            .filter(|r| r.final_param_error.is_some())
            .min_by(|a, b| {
                a.final_param_error
                    .partial_cmp(&b.final_param_error)
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            && let Some(run) = mine.iter().find(|r| r.method == best.method && r.seed == 0)
        {
            let file = format!("strip_{slug}.png");
            if output::write_strip(&out.join(&file), t.as_ref(), &t.start(0), &run.theta)? {
                let _ = writeln!(
                    md,
                    "Init / result ({}, seed 0) / target:\n\n![strip]({file})\n",
                    best.method
                );
            }
        }
        all_rows.extend(rows);
    }
    if let Some(suite) = suite {
        let _ = writeln!(
            md,
            "## Generalisation suite\n\n\
             The optimisers on problems nobody tuned for — BBOB functions, disc and integer \
             plateaus, a flat direction, BOX2, noisy functions — each seeing x₀, σ₀, bounds \
             and budget only \
             ({} configuration{}). Evaluations to targets per problem: \
             [{SUITE_DIR}/suite.md]({SUITE_DIR}/suite.md).\n",
            if config.suite == SuiteScope::Quick {
                "`--quick`"
            } else {
                "full"
            },
            if suite.interrupted {
                "; interrupted, finished runs only"
            } else {
                ""
            }
        );
        md.push_str(&suite.table());
        let _ = writeln!(
            md,
            "\n![fraction of (problem, target) pairs solved against evaluations]({SUITE_DIR}/ecdf.png)\n"
        );
    }
    output::write_csv(&out.join("results.csv"), runs)?;
    output::write_traces(&out.join("traces.csv"), runs)?;
    output::write_json(
        &out.join("results.json"),
        config,
        runs,
        &all_rows,
        interrupted,
    )?;
    let path = out.join("report.md");
    std::fs::write(&path, md).with_context(|| format!("writing {}", path.display()))?;
    Ok(path)
}

/// The default output directory of `hodr report`.
pub fn default_out() -> &'static Path {
    Path::new("report")
}
