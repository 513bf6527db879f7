//! The generalisation suite behind `hodr suite` (docs/design.md §6): optimisers judged on
//! problems nobody tuned for, against baselines in the same run.
//!
//! * A [`Problem`] is one definition — f, f*, x*, the start distribution, σ₀, bounds,
//!   budget — and says nothing about any method. Families: BBOB noiseless functions
//!   ([`bbob`]), disc and integer plateaus ([`plateau`]), a flat direction ([`flat`]),
//!   the built-in BOX2 task ([`tasks`]), the sphere and Rosenbrock's function under
//!   BBOB's noise models ([`noisy`]), discs rendered on the method's noise seed
//!   ([`rendered`]) and BBOB functions whose evaluations fail at random ([`failing`]).
//!   [`catalogue`] lists them.
//! * A [`Method`] (Auto, CMA-ES, BOBYQA, FR22; [`methods`]) sees x₀, σ₀, bounds and
//!   budget, and evaluates through one counting wrapper ([`trace`]) that records every
//!   new best, so all are measured alike.
//! * [`summary`] turns runs into evaluations to targets, success rates and family
//!   aggregates; [`output`] and [`plot`] write `suite.md`, `suite.csv` and `ecdf.png`.
//!
//! Order and seeds: problems run in catalogue order; within a problem the methods take
//! turns seed by seed (seed 0 of every method, then seed 1, …), so a slow drift of the
//! machine falls on every method alike. Run seed s of a problem is a function of the
//! problem's name and s only ([`problem::run_seed`]); every method of that seed starts
//! from the same x₀. Runs execute one at a time unless [`Config::jobs`] says otherwise
//! (then they share the machine, but their results and order are the same); a method
//! may use both cores inside a run (CMA-ES generations, hodr-core batches).

pub mod bbob;
pub mod failing;
pub mod flat;
pub mod methods;
pub mod noisy;
pub mod output;
pub mod plateau;
pub mod plot;
pub mod problem;
pub mod random;
pub mod rendered;
pub mod summary;
pub mod tasks;
pub mod trace;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

pub use methods::Method;
pub use problem::{Family, MAX_DIM, Problem};
pub use summary::{FamilyRow, Row, Run};

/// Instances per function and dimension (BBOB) or per dimension (the other generated
/// families).
pub const INSTANCES: usize = 5;
/// Default seeds per problem.
pub const SEEDS: usize = 5;
/// Default evaluations per dimension.
pub const BUDGET_PER_DIM: usize = 1000;
/// Seeds per problem with `--quick`.
pub const QUICK_SEEDS: usize = 2;

/// The most evaluations one run may be given: `--budget-per-dim` × n.
pub const MAX_BUDGET: usize = 1 << 40;
/// Evaluations per dimension with `--quick`.
pub const QUICK_BUDGET_PER_DIM: usize = 200;
/// Instances per function and dimension with `--quick`.
pub const QUICK_INSTANCES: usize = 2;
/// Largest dimension with `--quick` (the flat-direction problem, defined only at n = 6,
/// is kept).
pub const QUICK_MAX_DIM: usize = 5;

/// What `hodr suite` runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// Families, in [`Family::ALL`] order.
    pub families: Vec<Family>,
    /// Dimensions to run, each in the families defined there ([`Family::defined_at`]);
    /// `None`: every family's own (with `quick`, those up to [`QUICK_MAX_DIM`], and the
    /// flat problem).
    pub dims: Option<Vec<usize>>,
    /// BBOB, noisy and failing functions to run, in [`bbob::IDS`] then [`noisy::IDS`]
    /// order (the failing family's are BBOB's numbers, [`failing::IDS`]); `None`: all of
    /// them.
    pub functions: Option<Vec<u32>>,
    /// Methods, in [`Method::ALL`] order.
    pub methods: Vec<Method>,
    /// Seeds per problem.
    pub seeds: usize,
    /// Evaluations per dimension: a problem's budget is this times n.
    pub budget_per_dim: usize,
    /// Instances per function (BBOB) or per dimension (the other generated families).
    pub instances: usize,
    /// Whether `--quick` chose the defaults.
    pub quick: bool,
    /// Output directory.
    pub out: PathBuf,
    /// Runs executed at once (default 1: one at a time, so that each run's time is
    /// measured on an otherwise idle machine).
    pub jobs: usize,
}

impl Config {
    /// Runs `jobs` runs at once on a pool of that many threads. Results, their order and
    /// every evaluation count are those of `jobs` = 1; only the times share the machine.
    ///
    /// # Errors
    /// For 0.
    pub fn with_jobs(mut self, jobs: usize) -> Result<Config> {
        if jobs == 0 {
            bail!("--jobs must be at least 1");
        }
        self.jobs = jobs;
        Ok(self)
    }

    /// Runs only the functions `ids` of the BBOB family ([`bbob::IDS`], e.g. 2 and 10),
    /// of the noisy family ([`noisy::IDS`], e.g. 104) and of the failing family
    /// ([`failing::IDS`], BBOB's numbers); the other families run whole. A selected
    /// BBOB, noisy or failing family none of whose functions is listed runs none.
    /// Empty: all of them.
    ///
    /// # Errors
    /// A one-line message naming the culprit: a function the suite does not define, one
    /// listed twice, or one none of whose families (bbob for 1–15, failing for 1, 2, 8,
    /// 10 and 15, noisy for 101–112) is selected.
    pub fn with_functions(mut self, ids: &[u32]) -> Result<Config> {
        if ids.is_empty() {
            self.functions = None;
            return Ok(self);
        }
        for (k, id) in ids.iter().enumerate() {
            let families: Vec<Family> = [
                (Family::Bbob, &bbob::IDS[..]),
                (Family::Failing, &failing::IDS[..]),
                (Family::Noisy, &noisy::IDS[..]),
            ]
            .into_iter()
            .filter(|(_, have)| have.contains(id))
            .map(|(family, _)| family)
            .collect();
            if families.is_empty() {
                bail!(
                    "unknown function {id} (bbob has {:?}, failing {:?}, noisy {:?})",
                    bbob::IDS,
                    failing::IDS,
                    noisy::IDS
                );
            }
            if !families.iter().any(|f| self.families.contains(f)) {
                let names: Vec<&str> = families.iter().map(|f| f.name()).collect();
                bail!(
                    "function {id} belongs to the {} family, which is not selected",
                    names.join(" or ")
                );
            }
            if ids[..k].contains(id) {
                bail!("function {id} listed twice");
            }
        }
        let order = bbob::IDS.into_iter().chain(noisy::IDS);
        self.functions = Some(order.filter(|i| ids.contains(i)).collect());
        Ok(self)
    }

    /// Whether function `id` of the BBOB, noisy or failing family runs.
    fn runs_function(&self, id: u32) -> bool {
        self.functions.as_ref().is_none_or(|f| f.contains(&id))
    }

    /// The configuration of the command line's arguments: empty lists mean "all";
    /// `seeds` and `budget_per_dim` default to [`SEEDS`] and [`BUDGET_PER_DIM`], or
    /// [`QUICK_SEEDS`] and [`QUICK_BUDGET_PER_DIM`] with `quick`.
    ///
    /// # Errors
    /// A one-line message naming the culprit: an unknown or repeated family or method,
    /// a dimension no selected family has, zero seeds or budget.
    pub fn from_args(
        families: &[String],
        dims: &[usize],
        methods: &[String],
        seeds: Option<usize>,
        budget_per_dim: Option<usize>,
        quick: bool,
        out: PathBuf,
    ) -> Result<Config> {
        let families = parse_list(families, "family", Family::from_name, &Family::ALL)?;
        let methods = parse_list(methods, "method", Method::from_name, &Method::ALL)?;
        let dims = if dims.is_empty() {
            None
        } else {
            for &d in dims {
                if !families.iter().any(|f| f.defined_at(d)) {
                    let have: Vec<String> = families
                        .iter()
                        .map(|f| match f {
                            Family::Bbob | Family::Noisy | Family::Failing => {
                                format!("{f} 2–{MAX_DIM}")
                            }
                            _ => format!("{f} {:?}", f.dims()),
                        })
                        .collect();
                    bail!(
                        "no selected family has dimension {d} (families: {})",
                        have.join(", ")
                    );
                }
            }
            Some(dims.to_vec())
        };
        let seeds = seeds.unwrap_or(if quick { QUICK_SEEDS } else { SEEDS });
        if seeds == 0 {
            bail!("--seeds must be at least 1");
        }
        let budget_per_dim = budget_per_dim.unwrap_or(if quick {
            QUICK_BUDGET_PER_DIM
        } else {
            BUDGET_PER_DIM
        });
        if budget_per_dim == 0 {
            bail!("--budget-per-dim must be at least 1");
        }
        let widest = dims
            .as_deref()
            .unwrap_or(&[])
            .iter()
            .chain(families.iter().flat_map(|f| f.dims()))
            .copied()
            .max()
            .unwrap_or(1);
        if budget_per_dim
            .checked_mul(widest)
            .is_none_or(|b| b > MAX_BUDGET)
        {
            bail!(
                "--budget-per-dim {budget_per_dim}: a run's budget (× n = {widest}) must be at most {MAX_BUDGET}"
            );
        }
        Ok(Config {
            families,
            dims,
            functions: None,
            methods,
            seeds,
            budget_per_dim,
            instances: if quick { QUICK_INSTANCES } else { INSTANCES },
            quick,
            out,
            jobs: 1,
        })
    }

    /// The dimensions `family` runs at: those chosen that it is defined at, or by default
    /// its own (at most [`QUICK_MAX_DIM`] with `quick`, except the flat problem's).
    fn dims_of(&self, family: Family) -> Vec<usize> {
        match &self.dims {
            Some(chosen) => chosen
                .iter()
                .copied()
                .filter(|&n| family.defined_at(n))
                .collect(),
            None => family
                .dims()
                .iter()
                .copied()
                .filter(|&n| !self.quick || n <= QUICK_MAX_DIM || family == Family::Flat)
                .collect(),
        }
    }
}

/// Parses a comma-separated selection: each name must be known and listed once; an empty
/// list selects `all`. The result follows `all`'s order.
fn parse_list<T: Copy + PartialEq>(
    names: &[String],
    what: &str,
    parse: impl Fn(&str) -> Option<T>,
    all: &[T],
) -> Result<Vec<T>> {
    if names.is_empty() {
        return Ok(all.to_vec());
    }
    let mut chosen = Vec::new();
    for name in names {
        let Some(x) = parse(name) else {
            bail!("unknown {what} `{name}`");
        };
        if chosen.contains(&x) {
            bail!("{what} `{name}` listed twice");
        }
        chosen.push(x);
    }
    Ok(all.iter().copied().filter(|x| chosen.contains(x)).collect())
}

/// Every problem `config` selects, in run order: family, then (BBOB) function, then
/// dimension, then instance 1, 2, ….
///
/// # Errors
/// When a built-in task cannot be built.
pub fn catalogue(config: &Config) -> Result<Vec<Problem>> {
    let b = config.budget_per_dim;
    let instances = 1..=config.instances as u64;
    let mut out = Vec::new();
    for &family in &config.families {
        let dims = config.dims_of(family);
        match family {
            Family::Bbob => {
                for id in bbob::IDS.into_iter().filter(|&i| config.runs_function(i)) {
                    for &n in &dims {
                        for i in instances.clone() {
                            out.push(bbob::problem(id, n, i, b));
                        }
                    }
                }
            }
            Family::Plateau => {
                for &n in &dims {
                    for i in instances.clone() {
                        out.push(plateau::discs(n, i, b));
                    }
                }
            }
            Family::Integer => {
                for &n in &dims {
                    for i in instances.clone() {
                        out.push(plateau::integer(n, i, b));
                    }
                }
            }
            Family::Flat => {
                if !dims.is_empty() {
                    for i in instances.clone() {
                        out.push(flat::problem(i, b));
                    }
                }
            }
            Family::Tasks => {
                if !dims.is_empty() {
                    out.push(tasks::box2(b)?);
                }
            }
            Family::Rendered => {
                for &n in &dims {
                    for i in instances.clone() {
                        out.push(rendered::discs(n, i, b));
                    }
                }
            }
            Family::Noisy => {
                for id in noisy::IDS.into_iter().filter(|&i| config.runs_function(i)) {
                    for &n in &dims {
                        for i in instances.clone() {
                            out.push(noisy::problem(id, n, i, b));
                        }
                    }
                }
            }
            Family::Failing => {
                for percent in failing::PERCENTS {
                    for id in failing::IDS
                        .into_iter()
                        .filter(|&i| config.runs_function(i))
                    {
                        for &n in &dims {
                            for i in instances.clone() {
                                out.push(failing::problem(id, percent, n, i, b));
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(out)
}

/// What a suite run produced.
#[derive(Debug)]
pub struct Outcome {
    /// The problems, indexed by [`Run::problem`].
    pub problems: Vec<Problem>,
    /// Every finished run, in run order.
    pub runs: Vec<Run>,
    /// Per problem × method.
    pub rows: Vec<Row>,
    /// Per family × method.
    pub families: Vec<FamilyRow>,
    /// The method ratios are taken against: CMA-ES when it ran, else the first method.
    pub reference: Method,
    /// True when Ctrl-C stopped the run early.
    pub interrupted: bool,
}

impl Outcome {
    /// The short per-family table for stdout.
    pub fn table(&self) -> String {
        output::family_table(&self.families, self.reference)
    }
}

/// Runs the suite and writes `suite.md`, `suite.csv` and `ecdf.png` to `config.out`.
/// `interrupt` stops it before the next run; the files then hold the finished runs.
/// `progress` shows a progress bar on stderr.
///
/// # Errors
/// When a problem cannot be built or a file cannot be written.
pub fn run(config: &Config, interrupt: &AtomicBool, progress: bool) -> Result<Outcome> {
    let problems = catalogue(config)?;
    if problems.is_empty() {
        bail!("no problem matches the selected families and dimensions");
    }
    let total = (problems.len() * config.seeds * config.methods.len()) as u64;
    let bar = if progress {
        ProgressBar::new(total)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {msg}  [{elapsed_precise}]")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    // Every run in turn order: problem, seed, method.
    let order: Vec<(usize, usize, Method)> = (0..problems.len())
        .flat_map(|index| {
            (0..config.seeds).flat_map(move |s| config.methods.iter().map(move |&m| (index, s, m)))
        })
        .collect();
    let one = |&(index, s, m): &(usize, usize, Method)| {
        if interrupt.load(Ordering::Relaxed) {
            return None;
        }
        let p = &problems[index];
        bar.set_message(p.name.clone());
        let seed = problem::run_seed(&p.name, s);
        let trace = m.run(p, &p.start(seed), seed);
        bar.inc(1);
        Some(Run {
            problem: index,
            method: m,
            seed: s,
            trace,
        })
    };
    let done: Vec<Option<Run>> = if config.jobs == 1 {
        order.iter().map(one).collect()
    } else {
        rayon::ThreadPoolBuilder::new()
            .num_threads(config.jobs)
            .build()
            .context("starting the suite's thread pool")?
            .install(|| order.par_iter().map(one).collect())
    };
    bar.finish_and_clear();
    let interrupted = done.iter().any(Option::is_none);
    // An interrupted run keeps what finished before the first run it skipped.
    let runs: Vec<Run> = done.into_iter().map_while(|r| r).collect();
    let reference = if config.methods.contains(&Method::CmaEs) {
        Method::CmaEs
    } else {
        config.methods[0]
    };
    let rows = summary::rows(&problems, &config.methods, &runs);
    let families = summary::families(&problems, &config.methods, reference, &rows, &runs);
    write(
        config,
        &problems,
        &runs,
        &rows,
        &families,
        reference,
        interrupted,
    )?;
    Ok(Outcome {
        problems,
        runs,
        rows,
        families,
        reference,
        interrupted,
    })
}

fn write(
    config: &Config,
    problems: &[Problem],
    runs: &[Run],
    rows: &[Row],
    families: &[FamilyRow],
    reference: Method,
    interrupted: bool,
) -> Result<()> {
    let out: &Path = &config.out;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    output::write_csv(&out.join("suite.csv"), problems, runs)?;
    output::write_markdown(
        &out.join("suite.md"),
        config,
        problems,
        rows,
        families,
        reference,
        interrupted,
    )?;
    plot::ecdf_plot(
        &out.join("ecdf.png"),
        problems,
        &config.methods,
        runs,
        config.budget_per_dim as f64,
    )
}
