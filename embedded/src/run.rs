//! Running a problem with an algorithm in caller-provided static memory.

use hodr_core::optim::{Budget, Optimiser, Termination};
use hodr_core::{Error, Estimator, MIN_ROWS, NoiseSeed, Workspace};
use rand_xoshiro::Xoshiro128PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

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

/// All the memory a run needs besides the stack, reused by every run. Put it in a
/// `static` (the firmware) or anywhere else (the host): ≈ 0.2 KiB.
#[derive(Clone, Debug)]
pub struct Storage {
    theta: [f32; MAX_DIM],
    optimiser: [f32; OPTIMISER_FLOATS],
    workspace: [f32; WORKSPACE_FLOATS],
    seeds: [NoiseSeed; ROWS],
}

impl Storage {
    /// Zeroed storage; usable in a `static` initialiser.
    pub const fn new() -> Self {
        Storage {
            theta: [0.0; MAX_DIM],
            optimiser: [0.0; OPTIMISER_FLOATS],
            workspace: [0.0; WORKSPACE_FLOATS],
            seeds: [0; ROWS],
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
pub fn run_one(problem: &Problem, algorithm: Algorithm, storage: &mut Storage) -> RunResult {
    let n = problem.start.len();
    let mut result = RunResult {
        theta: [0.0; MAX_DIM],
        dim: n,
        evaluations: 0,
        iterations: 0,
        end: End::Finished(Termination::MaxEvaluations),
    };
    let theta = &mut storage.theta[..n];
    theta.copy_from_slice(problem.start);
    let setup = |error| End::Failed {
        iteration: 0,
        error,
    };
    let s = &problem.settings;
    let ws = Workspace::new(n, &mut storage.workspace, &mut storage.seeds);
    let rng = Xoshiro128PlusPlus::seed_from_u64(problem.seed);
    let optimiser = Estimator::new(s.sigma_start, s.pairs, rng).and_then(|estimator| {
        Optimiser::new(
            algorithm.method(s),
            algorithm.schedule(s),
            Budget::evaluations(s.evaluations),
            estimator,
            theta,
            &mut storage.optimiser,
        )
    });
    match (ws, optimiser) {
        (Ok(mut ws), Ok(mut opt)) => {
            let mut f = problem.objective;
            result.end = match opt.run(&mut f, &mut ws, || 0.0, |_, _| {}) {
                Ok(t) => End::Finished(t),
                Err(e) => End::Failed {
                    iteration: e.iteration,
                    error: e.error,
                },
            };
            result.evaluations = opt.evaluations();
            result.iterations = opt.iteration();
        }
        (Err(e), _) | (_, Err(e)) => result.end = setup(e),
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
                assert_eq!(r.end, End::Finished(Termination::MaxEvaluations));
                // The budget is spent up to less than one iteration, and not overrun: an
                // iteration that would pass it at the costliest cost so far is not started.
                assert!(r.evaluations <= p.settings.evaluations, "{r:?}");
                assert!(r.evaluations * 10 >= p.settings.evaluations * 9, "{r:?}");
                let d = distance(&r, p.optimum);
                std::println!("{} {}: {:?}, distance {d}", p.name, a.name(), r);
                assert!(d < 0.05, "{} {}: {r:?}", p.name, a.name());
            }
        }
    }

    #[test]
    fn optimiser_storage_fits_every_method() {
        for p in [QUAD, PLATEAU] {
            for &a in Algorithm::ALL {
                let needed = a.method(&p.settings).buffer_len(p.start.len());
                assert!(needed <= OPTIMISER_FLOATS);
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
