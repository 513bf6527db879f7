//! Set-up shared by the optimiser tests: one run of a method from a start, with the
//! estimator, optimiser buffer and workspace allocated here.

// Each test binary includes this module and uses a part of it.
#![allow(dead_code)]

use hodr_core::optim::preset::Hyper;
use hodr_core::optim::{Budget, Method, Optimiser, Schedule, StepReport};
use hodr_core::{Estimator, Objective, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// One antithetic pair per estimate with σ from `sigma_start` to 0.01, trust radius
/// `trust_radius`·σ, common random numbers and the default adaptive shrink and inner
/// steps (the line-search and Adam settings are the paper's BOX2 ones, unused by
/// Newton-CG).
pub fn one_pair(sigma_start: f64, trust_radius: f64) -> Hyper<f64> {
    Hyper {
        pairs: 1,
        sigma_start,
        trust_radius,
        line_search_iterations: 2,
        common_random_numbers: true,
        ..Hyper::default()
    }
}

/// Batch capacity of the workspace.
const ROWS: usize = 64;

/// The estimator's starting σ, its pairs per estimate and its RNG seed.
pub struct Sampling {
    pub sigma: f64,
    pub pairs: usize,
    pub seed: u64,
}

impl Sampling {
    /// σ and pairs of `h`, with the RNG seeded by `seed`.
    pub fn of(h: &Hyper<f64>, seed: u64) -> Self {
        Sampling {
            sigma: h.sigma_start,
            pairs: h.pairs,
            seed,
        }
    }
}

/// Runs `method` under `schedule` from `theta` (updated in place) until `budget` is
/// used, calling `observe` after every iteration. Panics on any error: a test's set-up
/// is valid by construction.
pub fn optimise(
    method: Method<f64>,
    schedule: Schedule<f64>,
    budget: Budget<f64>,
    sampling: Sampling,
    theta: &mut [f64],
    objective: &mut impl Objective<f64>,
    observe: impl FnMut(&StepReport<f64>, &[f64]),
) {
    let n = theta.len();
    let mut buffer = vec![0.0; method.buffer_len(n)];
    let estimator = Estimator::new(
        sampling.sigma,
        sampling.pairs,
        Xoshiro256PlusPlus::seed_from_u64(sampling.seed),
    )
    .unwrap();
    let mut opt = Optimiser::new(method, schedule, budget, estimator, theta, &mut buffer).unwrap();
    let (mut wb, mut seeds) = (vec![0.0; method.workspace_len(n, ROWS)], vec![0; ROWS]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds).unwrap();
    opt.run(objective, &mut ws, || 0.0, observe).unwrap();
}

/// The Newton-CG preset written `text` (a [`hodr_core::optim::recipe::Recipe`]'s text
/// form, e.g. `NewtonCG/fr22/compare`).
pub fn newton_cg(text: &str) -> hodr_core::optim::preset::Preset {
    hodr_core::optim::preset::Preset::from_name(text).expect("a Newton-CG recipe")
}
