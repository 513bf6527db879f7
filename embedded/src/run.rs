//! Running a problem with an algorithm in caller-provided static memory.

#[cfg(feature = "auto")]
use hodr_core::optim::{Auto, AutoOptions, AutoTermination};
use hodr_core::optim::{Budget, Method, Optimiser, Schedule, Termination};
use hodr_core::{Error, Estimator, MIN_ROWS, NoiseSeed, Workspace};

use crate::algorithm::Algorithm;
use crate::problem::{PROBLEMS, Problem};
use crate::report::{self, Output};

/// The largest problem dimension (QUAD's).
pub const MAX_DIM: usize = 2;

/// Batch capacity of the workspace: hodr-core's minimum. Estimates do not depend on it,
/// and a single-threaded microcontroller gains nothing from preparing more points at once.
pub const ROWS: usize = MIN_ROWS;

/// Optimiser memory: `Method::buffer_len` of the largest method, OurH's
/// n + 3n + n² floats (θ saved, ĝ, d, Ĥd, Ĥ).
pub const OPTIMISER_FLOATS: usize = MAX_DIM * (4 + MAX_DIM);

const WORKSPACE_FLOATS: usize = Workspace::<f32>::buffer_len(MAX_DIM, ROWS);

/// Auto's memory: [`hodr_core::optim::auto::buffer_len`] of the largest problem, which
/// covers the smaller ones (the length grows with n; checked at compile time below).
#[cfg(feature = "auto")]
pub const AUTO_FLOATS: usize = hodr_core::optim::auto::buffer_len(MAX_DIM);

#[cfg(feature = "auto")]
const _: () = {
    let mut k = 0;
    while k < PROBLEMS.len() {
        assert!(hodr_core::optim::auto::buffer_len(PROBLEMS[k].start.len()) <= AUTO_FLOATS);
        k += 1;
    }
};

/// All the memory a run needs besides the stack, reused by every run. Put it in a
/// `static` (the firmware) or anywhere else (the host): ≈ 0.2 KiB, and with Auto
/// [`AUTO_FLOATS`] `f32`s more.
#[derive(Clone, Debug)]
pub struct Storage {
    theta: [f32; MAX_DIM],
    optimiser: [f32; OPTIMISER_FLOATS],
    workspace: [f32; WORKSPACE_FLOATS],
    seeds: [NoiseSeed; ROWS],
    #[cfg(feature = "auto")]
    auto: [f32; AUTO_FLOATS],
}

impl Storage {
    /// Zeroed storage; usable in a `static` initialiser.
    pub const fn new() -> Self {
        Storage {
            theta: [0.0; MAX_DIM],
            optimiser: [0.0; OPTIMISER_FLOATS],
            workspace: [0.0; WORKSPACE_FLOATS],
            seeds: [0; ROWS],
            #[cfg(feature = "auto")]
            auto: [0.0; AUTO_FLOATS],
        }
    }
}

impl Default for Storage {
    fn default() -> Self {
        Self::new()
    }
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    /// The optimiser stopped normally.
    Finished(Termination),
    /// Auto stopped normally.
    #[cfg(feature = "auto")]
    Auto(AutoTermination),
    /// Setting up (iteration 0) or an iteration failed; θ is the last good one.
    Failed {
        /// The 1-based failed iteration, 0 for the set-up.
        iteration: usize,
        /// What failed.
        error: Error,
    },
}

/// The result of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunResult {
    /// Final parameters, the first `dim` entries meaningful.
    pub theta: [f32; MAX_DIM],
    /// The problem's dimension n.
    pub dim: usize,
    /// Objective evaluations used.
    pub evaluations: usize,
    /// Iterations completed.
    pub iterations: usize,
    /// Why the run stopped.
    pub end: End,
}

impl RunResult {
    /// A run in dimension `n` that has done nothing yet, ending with `end` unless told
    /// otherwise.
    fn unstarted(n: usize, end: End) -> Self {
        RunResult {
            theta: [0.0; MAX_DIM],
            dim: n,
            evaluations: 0,
            iterations: 0,
            end,
        }
    }

    /// The final parameters θ (length n).
    pub fn theta(&self) -> &[f32] {
        &self.theta[..self.dim]
    }
}

/// Minimises `problem` with `algorithm` from its start, its seed and its budget.
///
/// Deterministic: the same problem and algorithm give bit-identical results on every
/// target whose `f32` arithmetic is IEEE 754 round-to-nearest without fused operations.
///
/// # Panics
/// If the problem's dimension exceeds [`MAX_DIM`] (the built-in problems do not).
// Out of line: the firmware calls it once per run from `run_all`, and inlined there (its
// one call site) its frame merged into the caller's cost more than the call saves
// (Cortex-M0 minimal 6 052 -> 5 908 B, M4F 5 112 -> 5 008 B with it out of line).
#[inline(never)]
pub fn run_one(problem: &Problem, algorithm: Algorithm, storage: &mut Storage) -> RunResult {
    let Some(method) = algorithm.method(&problem.settings) else {
        #[cfg(feature = "auto")]
        return run_auto(problem, storage);
        #[cfg(not(feature = "auto"))]
        unreachable!("every algorithm but Auto has a method");
    };
    let n = problem.start.len();
    let mut result = RunResult::unstarted(n, End::Finished(Termination::MaxEvaluations));
    result.end = match run_method(
        problem,
        method,
        algorithm.schedule(&problem.settings),
        storage,
        &mut result,
    ) {
        Ok(t) => End::Finished(t),
        Err(end) => end,
    };
    result.theta[..n].copy_from_slice(&storage.theta[..n]);
    result
}

/// [`run_one`] for an algorithm with a method: runs it from the problem's start in
/// `storage.theta`, counting evaluations and iterations into `result`.
fn run_method(
    problem: &Problem,
    method: Method<f32>,
    schedule: Schedule<f32>,
    storage: &mut Storage,
    result: &mut RunResult,
) -> Result<Termination, End> {
    let setup = |error| End::Failed {
        iteration: 0,
        error,
    };
    let n = problem.start.len();
    let theta = &mut storage.theta[..n];
    theta.copy_from_slice(problem.start);
    let s = &problem.settings;
    let mut ws = Workspace::new(n, &mut storage.workspace, &mut storage.seeds).map_err(setup)?;
    let estimator = Estimator::new(s.sigma_start, s.pairs, problem.seed.rng()).map_err(setup)?;
    let mut opt = Optimiser::new(
        method,
        schedule,
        Budget::evaluations(s.evaluations),
        estimator,
        theta,
        &mut storage.optimiser,
    )
    .map_err(setup)?;
    let mut f = problem.objective;
    let end = opt.run(&mut f, &mut ws, || 0.0, |_, _| {});
    result.evaluations = opt.evaluations();
    result.iterations = opt.iteration();
    end.map_err(|e| End::Failed {
        iteration: e.iteration,
        error: e.error,
    })
}

/// Minimises `problem` with Auto from its start, its seed, its scale σ₀ (`sigma_start`)
/// and its budget, in `storage`.
#[cfg(feature = "auto")]
fn run_auto(problem: &Problem, storage: &mut Storage) -> RunResult {
    let n = problem.start.len();
    let mut result = RunResult::unstarted(n, End::Auto(AutoTermination::MaxEvaluations));
    let theta = &mut storage.theta[..n];
    theta.copy_from_slice(problem.start);
    let s = &problem.settings;
    let rng = problem.seed.rng();
    let auto = AutoOptions::default()
        .with_max_evaluations(s.evaluations)
        .and_then(|options| {
            Auto::new(theta, s.sigma_start, &mut storage.auto, rng).map(|a| a.with_options(options))
        });
    match auto {
        Ok(mut auto) => {
            let mut f = problem.objective;
            result.end = match auto.run(&mut f, |_, _| {}) {
                Ok(t) => End::Auto(t),
                Err(error) => End::Failed {
                    iteration: auto.iteration() + 1,
                    error,
                },
            };
            result.evaluations = auto.evaluations();
            result.iterations = auto.iteration();
        }
        Err(error) => {
            result.end = End::Failed {
                iteration: 0,
                error,
            }
        }
    }
    result.theta[..n].copy_from_slice(&storage.theta[..n]);
    result
}

/// Runs every problem with every compiled-in algorithm, writing one report line per run
/// (see [`report::write_run`]) to `out`.
pub fn run_all<O: Output + ?Sized>(out: &mut O, storage: &mut Storage) {
    for problem in &PROBLEMS {
        for &algorithm in Algorithm::ALL {
            let result = run_one(problem, algorithm, storage);
            report::write_run(out, problem.name, algorithm.name(), &result);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::{PLATEAU, QUAD};

    fn distance(r: &RunResult, optimum: &[f32]) -> f32 {
        r.theta()
            .iter()
            .zip(optimum)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f32>()
            .sqrt()
    }

    #[test]
    fn every_run_spends_its_budget_and_approaches_the_optimum() {
        let mut storage = Storage::new();
        for p in PROBLEMS {
            for &a in Algorithm::ALL {
                let r = run_one(&p, a, &mut storage);
                assert!(r.evaluations <= p.settings.evaluations, "{r:?}");
                match r.end {
                    // A preset spends its budget up to less than one iteration, and does
                    // not overrun it: an iteration that would pass it at the costliest
                    // cost so far is not started.
                    End::Finished(t) => {
                        assert_eq!(t, Termination::MaxEvaluations);
                        assert!(r.evaluations * 10 >= p.settings.evaluations * 9, "{r:?}");
                    }
                    // Auto may converge before the budget is spent.
                    #[cfg(feature = "auto")]
                    End::Auto(_) => {}
                    End::Failed { .. } => panic!("{} {}: {r:?}", p.name, a.name()),
                }
                let d = distance(&r, p.optimum);
                std::println!("{} {}: {:?}, distance {d}", p.name, a.name(), r);
                if r.end == End::Finished(Termination::MaxEvaluations) {
                    // σ annealed to its end: θ is near the smoothed objective's minimiser.
                    assert!(d < 0.05, "{} {}: {r:?}", p.name, a.name());
                } else {
                    // Auto minimises f itself: f(θ) is within 1e-6 of f at that minimiser
                    // (on PLATEAU, θ anywhere in the well).
                    let f = p.objective;
                    let gap = f(r.theta()) - f(p.optimum);
                    assert!(gap <= 1e-6, "{} {}: {r:?}", p.name, a.name());
                }
            }
        }
    }

    #[test]
    fn optimiser_storage_fits_every_method() {
        for p in [QUAD, PLATEAU] {
            for &a in Algorithm::ALL {
                if let Some(method) = a.method(&p.settings) {
                    assert!(method.buffer_len(p.start.len()) <= OPTIMISER_FLOATS);
                }
            }
        }
    }

    #[test]
    fn runs_repeat_bit_for_bit() {
        let (mut s1, mut s2) = (Storage::new(), Storage::new());
        for &a in Algorithm::ALL {
            assert_eq!(run_one(&QUAD, a, &mut s1), run_one(&QUAD, a, &mut s2));
        }
    }
}
