//! The methods of the suite, each run on one (problem, seed) through the counting
//! wrapper ([`super::trace::Counter`]) so that every method is measured identically.
//!
//! A method sees only the problem's statement: x₀, σ₀, bounds and the budget.
//!
//! * **Auto**: hodr-core's default optimiser ([`hodr_core::optim::Auto`]) with its
//!   defaults, σ₀ and the bounds; it stops at the budget or at its own termination.
//! * **CMA-ES** (the `cmaes` crate): initial mean x₀, step size σ₀, the default
//!   population 4 + ⌊3 ln n⌋, no restarts; a generation's population is evaluated in
//!   parallel (`next_parallel`, rayon) when its expected work pays for the threads
//!   ([`Counter::parallel_pays`], as for the batches of Auto and FR22). Bounds are
//!   respected by evaluating each sample reflected into the box ([`super::problem::Bounds::reflect`]); the distribution is
//!   not told about them. Not by clamping: f at a clamped point is constant along every
//!   clamped coordinate outside the box, so there the ranking cannot pull the mean back;
//!   it drifts, σ collapses, and the run ends at the crate's tolerances far from the
//!   optimum (pycma's default bound handling, a smooth mirror, avoids this the same
//!   way). Within a generation the λ evaluations are counted in a fixed order — by the
//!   points' bit patterns — since the crate does not expose its sampling order; the
//!   points are i.i.d., so this order is as good as any, and it does not depend on
//!   thread scheduling. A run stops at the budget or at the crate's own termination
//!   criteria. A failed evaluation (NaN) is passed to it as +∞, worse than any value:
//!   its ranking needs a total order (the crate takes NaN as equal to everything).
//! * **BOBYQA** (the `bobyqa` crate, Powell's method ported from PRIMA): 2n + 1
//!   interpolation points, ρ_begin = min(σ₀, ½·narrowest box width), ρ_end = 10⁻⁸·ρ_begin,
//!   max_fun = the budget; bounds are passed to it (±∞ where the problem has none), and it
//!   only evaluates inside them. Sequential.
//! * **FR22**: hodr-core's [`Preset::Fr22`] (Adam on the FR22 gradient estimate, σ
//!   annealed linearly over the budget) with σ_start = σ₀, σ_end = σ₀/100, Adam learning
//!   rate 0.1·σ₀ and 6 antithetic pairs: the baseline's only task-independent setting,
//!   expressed in the problem's own scale. Points are clamped into the bounds inside the
//!   objective; batches are evaluated in parallel when that pays.

use std::fmt;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use anyhow::{Result, anyhow};
use hodr_core::optim::preset::{Hyper, NEWTON_CG_INNER_STEPS, Preset, SIGMA_SHRINK};
use hodr_core::optim::{Auto, AutoOptions, AutoTermination, Budget, NegativeCurvature, Optimiser};
use hodr_core::{Estimator, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use super::problem::Problem;
use super::random;
use super::trace::{Counter, Trace};

/// A method of the suite.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// hodr's default optimiser.
    Auto,
    /// CMA-ES.
    CmaEs,
    /// BOBYQA.
    Bobyqa,
    /// The paper's FR22 baseline.
    Fr22,
}

impl Method {
    /// Every method, in run order.
    pub const ALL: [Method; 4] = [Method::Auto, Method::CmaEs, Method::Bobyqa, Method::Fr22];

    /// Display name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "Auto",
            Method::CmaEs => "CMA-ES",
            Method::Bobyqa => "BOBYQA",
            Method::Fr22 => "FR22",
        }
    }

    /// The method called `name` (case-insensitive; "cmaes" is accepted for CMA-ES).
    pub fn from_name(name: &str) -> Option<Method> {
        let name = name.trim();
        if name.eq_ignore_ascii_case("cmaes") {
            return Some(Method::CmaEs);
        }
        Method::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
    }

    /// Runs the method on `problem` from `x0` with `seed` for at most `problem.budget`
    /// counted evaluations.
    pub fn run(self, problem: &Problem, x0: &[f64], seed: u64) -> Trace {
        let mut counter = Counter::new(problem, problem.budget);
        let initial_error = problem.param_error(&counter.clamped().point(x0));
        let stopped = match self {
            Method::Auto => auto(problem, x0, seed, &mut counter),
            Method::CmaEs => cma_es(problem, x0, seed, &mut counter),
            Method::Bobyqa => bobyqa(problem, x0, &mut counter),
            Method::Fr22 => fr22(problem, x0, seed, &mut counter),
        };
        let stopped = match stopped {
            Ok(why) => why.filter(|_| !counter.exhausted()),
            Err(e) => Some(format!("error: {e:#}")),
        };
        counter.into_trace(initial_error, stopped)
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a runner stopped before the budget, if it knows (`Ok(None)`: the budget).
type Stop = Result<Option<String>>;

/// Auto, exactly through its public API.
fn auto(problem: &Problem, x0: &[f64], seed: u64, counter: &mut Counter<'_>) -> Stop {
    let n = problem.n;
    let budget = problem.budget;
    let mut theta = x0.to_vec();
    let mut buf = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
    let rng = Xoshiro256PlusPlus::seed_from_u64(random::seed_of("auto", &[seed]));
    let options = AutoOptions::default().with_max_evaluations(budget)?;
    let mut auto = Auto::new(&mut theta, problem.sigma0, &mut buf, rng)?.with_options(options);
    if let Some(b) = &problem.bounds {
        auto = auto.with_bounds(&b.lower, &b.upper)?;
    }
    // Each iteration either evaluates or shrinks σ towards Auto's own tolerance, so
    // this cap is never the binding one; it is there so the loop has one.
    for _ in 0..budget.saturating_mul(100).max(10_000) {
        if auto.step(counter)?.is_none() {
            return Ok(auto
                .termination()
                .filter(|&t| t != AutoTermination::MaxEvaluations)
                .map(|t| t.to_string()));
        }
    }
    Ok(Some("iteration cap".into()))
}

/// CMA-ES through the `cmaes` crate, a generation evaluated in parallel when that pays
/// ([`Counter::parallel_pays`]).
fn cma_es(problem: &Problem, x0: &[f64], seed: u64, counter: &mut Counter<'_>) -> Stop {
    // Evaluations of the current generation with the time each took, gathered from
    // rayon's threads.
    let pending: Mutex<Vec<(Vec<f64>, f64, Duration)>> = Mutex::new(Vec::new());
    let f = counter.clamped();
    let evaluate = |x: &cmaes::DVector<f64>| {
        let clock = Instant::now();
        let mut x = x.as_slice().to_vec();
        if let Some(b) = &problem.bounds {
            b.reflect(&mut x);
        }
        let f = f.value(&x);
        let took = clock.elapsed();
        if let Ok(mut p) = pending.lock() {
            p.push((x, f, took));
        }
        if f.is_nan() { f64::INFINITY } else { f }
    };
    let mut cma = cmaes::CMAESOptions::new(x0.to_vec(), problem.sigma0)
        .seed(seed)
        .max_function_evals(problem.budget)
        .build(&evaluate)
        .map_err(|e| anyhow!("CMA-ES options: {e:?}"))?;
    let lambda = cma.parameters().lambda();
    let mut generation = Vec::new();
    let mut ended = None;
    while ended.is_none() && !counter.exhausted() {
        ended = if counter.parallel_pays(lambda) {
            cma.next_parallel()
        } else {
            cma.next()
        };
        std::mem::swap(
            &mut generation,
            &mut *pending.lock().map_err(|_| anyhow!("poisoned"))?,
        );
        counter.note_cost(generation.iter().map(|g| g.2).sum(), generation.len());
        generation.sort_by(|a, b| {
            let key = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            key(&a.0).cmp(&key(&b.0))
        });
        for (x, f, _) in generation.drain(..) {
            counter.record(&x, f);
        }
    }
    Ok(ended.map(|t| format!("{:?}", t.reasons)))
}

/// BOBYQA through the `bobyqa` crate.
fn bobyqa(problem: &Problem, x0: &[f64], counter: &mut Counter<'_>) -> Stop {
    let n = problem.n;
    let (lower, upper) = match &problem.bounds {
        Some(b) => (b.lower.clone(), b.upper.clone()),
        None => (vec![f64::NEG_INFINITY; n], vec![f64::INFINITY; n]),
    };
    let width = problem
        .bounds
        .as_ref()
        .map_or(f64::INFINITY, |b| b.narrowest());
    let rho_begin = problem.sigma0.min(0.5 * width);
    let config = bobyqa::Config {
        rho_begin,
        rho_end: 1e-8 * rho_begin,
        max_fun: problem.budget,
        ..bobyqa::Config::new(n)
    };
    let mut solver = bobyqa::Bobyqa::new(n, config).map_err(|s| {
        anyhow!(
            "BOBYQA settings ({s}; budget {} against {} interpolation points)",
            problem.budget,
            config.npt
        )
    })?;
    let mut x = counter.clamped().point(x0);
    let outcome = solver.minimize(|x| counter.evaluate(x), &mut x, &lower, &upper);
    Ok(match outcome.status {
        bobyqa::Status::MaxFunReached => None,
        s => Some(s.to_string()),
    })
}

/// FR22 (Adam + FR22 gradient) with the task-independent settings of the module doc.
fn fr22(problem: &Problem, x0: &[f64], seed: u64, counter: &mut Counter<'_>) -> Stop {
    let n = problem.n;
    let h = fr22_hyper(problem.sigma0);
    let preset = Preset::Fr22;
    let method = preset.method(&h);
    let mut theta = x0.to_vec();
    let mut buffer = vec![0.0; method.buffer_len(n)];
    let rng = Xoshiro256PlusPlus::seed_from_u64(random::seed_of("fr22", &[seed]));
    let estimator = Estimator::new(h.sigma_start, h.pairs, rng)?;
    let mut opt = Optimiser::new(
        method,
        preset.schedule(&h),
        Budget::evaluations(problem.budget),
        estimator,
        &mut theta,
        &mut buffer,
    )?;
    let rows = 64;
    let (mut wb, mut seeds) = (vec![0.0; method.workspace_len(n, rows)], vec![0; rows]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds)?;
    loop {
        match opt.step(counter, &mut ws, 0.0) {
            Ok(Some(_)) => {}
            Ok(None) => return Ok(None),
            Err(failed) => return Ok(Some(failed.to_string())),
        }
    }
}

/// FR22's settings on a problem of scale σ₀: 6 antithetic pairs, σ from σ₀ to σ₀/100,
/// Adam learning rate 0.1·σ₀ (the rest is unused by Adam).
pub fn fr22_hyper(sigma0: f64) -> Hyper<f64> {
    Hyper {
        pairs: 6,
        sigma_start: sigma0,
        sigma_end: sigma0 / 100.0,
        trust_radius: 2.0,
        line_search_iterations: 2,
        line_search_tolerance: 1e-3,
        recompute: 10,
        learning_rate: 0.1 * sigma0,
        common_random_numbers: false,
        negative_curvature: NegativeCurvature::Fallback,
        sigma_shrink: SIGMA_SHRINK,
        inner_steps: NEWTON_CG_INNER_STEPS,
        line_curvature: false,
    }
}
