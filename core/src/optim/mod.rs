//! Optimisers driven by the smoothed estimators (docs/design.md §1.7).
//!
//! An [`Optimiser`] is a step machine: [`Optimiser::step`] performs one iteration and
//! returns a plain-data [`StepReport`]; the caller owns the clock (no_std has none), any
//! logging, progress display and checkpoints, and may inspect θ between steps.
//! [`Optimiser::run`] loops to a [`Termination`].
//!
//! | method | per iteration |
//! |---|---|
//! | [`GradientDescent`] (`gradient-descent`) | θ ← θ − ηĝ |
//! | [`Adam`] | Adam on ĝ |
//! | [`Newton`] (`hessian`) | (Ĥ + λI)p = −ĝ by shifted Cholesky, ‖p‖ ≤ Δσ |
//! | [`Ncg`] (`cg`) | Fletcher–Reeves NCG, Newton–Raphson line search with HVPs |
//! | [`NewtonCg`] (`newton-cg`) | Steihaug trust-region CG on Ĥp = −ĝ with HVPs |
//!
//! σ follows a [`Schedule`] over the [`Budget`]'s progress. Memory is the caller's: θ and
//! one buffer of [`Method::buffer_len`] floats.

#[cfg(feature = "auto")]
pub mod auto;
mod first_order;
#[cfg(feature = "cg")]
mod ncg;
#[cfg(feature = "hessian")]
mod newton;
mod oracle;
#[cfg(all(
    feature = "hessian",
    feature = "aggregate",
    feature = "newton-cg",
    feature = "regression",
    feature = "per-element",
    feature = "gaussian"
))]
pub mod preset;
#[cfg(all(
    feature = "hessian",
    feature = "aggregate",
    feature = "newton-cg",
    feature = "regression",
    feature = "per-element",
    feature = "gaussian"
))]
pub mod recipe;
mod schedule;
#[cfg(feature = "newton-cg")]
mod steihaug;
pub(crate) mod vector;

use core::fmt;

use rand_core::Rng;

#[cfg(feature = "auto")]
pub use auto::{
    Auto, AutoModel, AutoOptions, AutoReport, AutoStep, AutoTermination, FixedAuto, NonFinite,
    unbudgeted_cap,
};
pub use first_order::Adam;
#[cfg(feature = "gradient-descent")]
pub use first_order::GradientDescent;
#[cfg(feature = "cg")]
pub use ncg::{Curvature, Ncg};
#[cfg(feature = "hessian")]
pub use newton::Newton;
pub use schedule::{Budget, Schedule, StepKind, Termination};
#[cfg(feature = "newton-cg")]
pub use steihaug::{COMPARISON_MARGIN, NewtonCg, PLATEAU_MARGIN};

use crate::error::Error;
#[cfg(all(feature = "regression", feature = "cg"))]
use crate::estimate::HvpMethod;
use crate::estimate::{Estimator, GradientMethod};
use crate::objective::Objective;
use crate::real::Real;
use crate::workspace::Workspace;
use oracle::Oracle;

/// Which optimiser, with its settings.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Method<T> {
    /// Plain gradient descent.
    #[cfg(feature = "gradient-descent")]
    GradientDescent(GradientDescent<T>),
    /// Adam.
    Adam(Adam<T>),
    /// Newton with the full estimated Hessian.
    #[cfg(feature = "hessian")]
    Newton(Newton<T>),
    /// Nonlinear conjugate gradient.
    #[cfg(feature = "cg")]
    Ncg(Ncg<T>),
    /// Newton-CG with a Steihaug trust region.
    #[cfg(feature = "newton-cg")]
    NewtonCg(NewtonCg<T>),
}

impl<T: Real> Method<T> {
    /// Floats of optimiser memory needed in dimension n (besides θ and the workspace).
    pub fn buffer_len(&self, n: usize) -> usize {
        // One extra vector keeps θ at the start of the iteration, restored on failure.
        n + self.lowest_len(n)
            + match self {
                #[cfg(feature = "gradient-descent")]
                Method::GradientDescent(_) => GradientDescent::<T>::buffer_len(n),
                Method::Adam(_) => Adam::<T>::buffer_len(n),
                #[cfg(feature = "hessian")]
                Method::Newton(_) => Newton::<T>::buffer_len(n),
                #[cfg(feature = "cg")]
                Method::Ncg(m) => m.buffer_len(n),
                #[cfg(feature = "newton-cg")]
                Method::NewtonCg(m) => m.buffer_len(n),
            }
    }

    /// Floats that keep the point of an iteration's lowest sample: n for Newton-CG
    /// comparing samples ([`NewtonCg::compare_samples`]), the only method that steps to
    /// it; else none.
    #[cfg_attr(not(feature = "newton-cg"), allow(unused_variables))]
    fn lowest_len(&self, n: usize) -> usize {
        match self {
            #[cfg(feature = "newton-cg")]
            Method::NewtonCg(m) if m.compare_samples => n,
            _ => 0,
        }
    }

    /// Length of the workspace buffer ([`Workspace::new`]) this method's estimates need
    /// in dimension `dim` with batch capacity `rows`: [`Workspace::buffer_len`], plus
    /// [`Workspace::moments_len`] when one of its gradient estimators is
    /// least-squares.
    pub fn workspace_len(&self, dim: usize, rows: usize) -> usize {
        let base = Workspace::<T>::buffer_len(dim, rows);
        if self.fits_least_squares() {
            base + Workspace::<T>::moments_len(dim)
        } else {
            base
        }
    }

    /// True when a gradient estimator of this method (direct or differenced for HVPs)
    /// is [`GradientMethod::Regression`].
    fn fits_least_squares(&self) -> bool {
        #[cfg(feature = "regression")]
        {
            let fits = |g: GradientMethod| g == GradientMethod::Regression;
            #[cfg(feature = "cg")]
            let hvp_fits = |h: HvpMethod| h.differenced().is_some_and(fits);
            match self {
                #[cfg(feature = "gradient-descent")]
                Method::GradientDescent(m) => fits(m.gradient),
                Method::Adam(m) => fits(m.gradient),
                #[cfg(feature = "hessian")]
                Method::Newton(m) => fits(m.gradient),
                #[cfg(feature = "cg")]
                Method::Ncg(m) => {
                    fits(m.gradient) || matches!(m.curvature, Curvature::Hvp(h) if hvp_fits(h))
                }
                #[cfg(feature = "newton-cg")]
                Method::NewtonCg(m) => fits(m.gradient) || hvp_fits(m.hvp),
            }
        }
        #[cfg(not(feature = "regression"))]
        false
    }

    /// The estimator of this method's gradient.
    pub fn gradient_method(&self) -> GradientMethod {
        match self {
            #[cfg(feature = "gradient-descent")]
            Method::GradientDescent(m) => m.gradient,
            Method::Adam(m) => m.gradient,
            #[cfg(feature = "hessian")]
            Method::Newton(m) => m.gradient,
            #[cfg(feature = "cg")]
            Method::Ncg(m) => m.gradient,
            #[cfg(feature = "newton-cg")]
            Method::NewtonCg(m) => m.gradient,
        }
    }

    /// The fraction of the n parameter directions one gradient estimate with `pairs`
    /// antithetic pairs samples: min(1, antithetic offsets / n). One pair in two
    /// dimensions sees one direction (½); per-element estimators see every coordinate.
    pub fn coverage(&self, n: usize, pairs: usize) -> T {
        let offsets = self.gradient_method().evaluations(n, pairs) / 2;
        if offsets >= n {
            T::ONE
        } else {
            T::from_usize(offsets) / T::from_usize(n)
        }
    }

    /// True when every estimate of an iteration reuses the same samples.
    pub fn reuses_samples(&self) -> bool {
        match self {
            #[cfg(feature = "cg")]
            Method::Ncg(m) => m.reuse_samples,
            #[cfg(feature = "newton-cg")]
            Method::NewtonCg(m) => m.reuse_samples,
            _ => false,
        }
    }

    fn validate(&self) -> Result<(), Error> {
        match self {
            #[cfg(feature = "gradient-descent")]
            Method::GradientDescent(m) => m.validate(),
            Method::Adam(m) => m.validate(),
            #[cfg(feature = "hessian")]
            Method::Newton(m) => m.validate(),
            #[cfg(feature = "cg")]
            Method::Ncg(m) => m.validate(),
            #[cfg(feature = "newton-cg")]
            Method::NewtonCg(m) => m.validate(),
        }
    }
}

/// What NCG and Newton-CG do where the estimated curvature dᵀĤd along their direction is
/// not positive, so that the quadratic model has no minimiser along ±d.
#[cfg(feature = "cg")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NegativeCurvature {
    /// Take the method's gradient-descent-like fallback step (see [`Ncg`], [`NewtonCg`]).
    Fallback,
    /// Evaluate the objective at three candidates with one shared noise seed (common
    /// random numbers) — the fallback step, and the two points where the line along d
    /// meets the trust boundary Δ·σ on either side — and move to the lowest (ties: the
    /// fallback).
    ///
    /// At a ridge of f̄ the model is unbounded below both ways and its linear term ĝᵀd,
    /// small and noisy there, only weakly prefers one side; the fallback follows that
    /// preference. The objective itself decides between the sides instead, as a
    /// trust-region method's acceptance test would, and the fallback stays a candidate,
    /// so noise-made negative curvature can only move the iterate to the boundary where f
    /// is measured lower there. The comparison uses f, not f̄: f̄ is what the iteration
    /// models, f is what the run minimises (the schedule takes σ → 0), and at the
    /// boundary (≥ 1σ away) f̄ blurs both candidates toward the same value. Costs 3
    /// evaluations per non-positive curvature.
    TwoSided,
}

/// What one iteration did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepReport<T> {
    /// 1-based number of this iteration.
    pub iteration: usize,
    /// Objective evaluations used so far (all iterations).
    pub evaluations: usize,
    /// σ used in this iteration.
    pub sigma: T,
    /// Mean objective value of this iteration's last estimate: an estimate of the loss
    /// near θ (unbiased for f̄ only with Gaussian sampling).
    pub loss: Option<T>,
    /// ‖ĝ‖ at the start of the iteration.
    pub gradient_norm: T,
    /// Total distance θ moved in this iteration.
    pub step_length: T,
    /// The latest dᵀĤd/dᵀd seen (NCG, Newton-CG).
    pub curvature: Option<T>,
    /// The diagonal shift λ of the Newton solve.
    pub shift: Option<T>,
    /// The trust radius Δ·σ in force (0 for first-order methods).
    pub trust_radius: T,
    /// NCG restarted its direction.
    pub restarted: bool,
    /// A non-positive-curvature (or failed-factorisation) fallback step was taken.
    pub fallback: bool,
    /// Set when this iteration ended the run.
    pub termination: Option<Termination>,
}

/// The per-method part of a step's result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Outcome<T> {
    pub gradient_norm: T,
    pub step_length: T,
    pub curvature: Option<T>,
    pub shift: Option<T>,
    pub restarted: bool,
    pub fallback: bool,
    /// The step stopped at the trust boundary on the way to a model minimum beyond it
    /// (Newton-CG).
    pub at_boundary: bool,
    /// What the objective made of the model's step (Newton-CG's `compare_samples`).
    pub verdict: Verdict,
    pub converged: bool,
}

/// What comparing the model's step on the objective decided ([`Oracle::settle`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// Not compared: the step was taken unevaluated.
    Uncompared,
    /// The objective kept the model's step.
    Kept,
    /// The objective preferred the current point or the iteration's lowest sample.
    Rejected,
}

impl<T: Real> Outcome<T> {
    /// The outcome of an iteration that stops at its gradient estimate because
    /// ‖ĝ‖ ≤ `tolerance`; `None` when there is no tolerance or ‖ĝ‖ is above it.
    fn converged(gradient_norm: T, tolerance: Option<T>) -> Option<Self> {
        tolerance.filter(|&t| gradient_norm <= t).map(|_| Outcome {
            gradient_norm,
            converged: true,
            ..Outcome::default()
        })
    }
}

impl<T: Real> Default for Outcome<T> {
    fn default() -> Self {
        Outcome {
            gradient_norm: T::ZERO,
            step_length: T::ZERO,
            curvature: None,
            shift: None,
            restarted: false,
            fallback: false,
            at_boundary: false,
            verdict: Verdict::Uncompared,
            converged: false,
        }
    }
}

/// An iteration failed; θ is back at its value from the start of that iteration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Failed {
    /// The 1-based iteration that failed.
    pub iteration: usize,
    /// What failed.
    pub error: Error,
}

impl fmt::Display for Failed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "iteration {} failed: {}", self.iteration, self.error)
    }
}

impl core::error::Error for Failed {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// Optimiser memory between iterations.
#[derive(Clone, Copy, Debug)]
struct State<T> {
    iteration: usize,
    evaluations: usize,
    adam_powers: (T, T),
    #[cfg(feature = "cg")]
    ncg: ncg::NcgState<T>,
    /// Newton-CG's running mean of positive curvatures.
    #[cfg(feature = "newton-cg")]
    mean_curvature: Option<T>,
    /// σ chosen by an adaptive schedule for the next iteration (before the cap).
    adapted_sigma: Option<T>,
    /// f(θ) at the current θ, when a deterministic objective was evaluated there.
    value_at_theta: Option<T>,
    /// Evaluations of the costliest iteration so far.
    costliest: usize,
    finished: Option<Termination>,
}

/// A resumable optimisation of θ (borrowed, updated in place).
pub struct Optimiser<'b, T, R> {
    method: Method<T>,
    schedule: Schedule<T>,
    budget: Budget<T>,
    estimator: Estimator<T, R>,
    theta: &'b mut [T],
    buffer: &'b mut [T],
    state: State<T>,
}

impl<T: Real, R: Rng + Clone> fmt::Debug for Optimiser<'_, T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Optimiser")
            .field("method", &self.method)
            .field("iteration", &self.state.iteration)
            .field("evaluations", &self.state.evaluations)
            .field("theta", &self.theta)
            .finish_non_exhaustive()
    }
}

impl<'b, T: Real, R: Rng + Clone> Optimiser<'b, T, R> {
    /// An optimiser starting at `theta` (updated in place), with `buffer` of at least
    /// [`Method::buffer_len`] floats. The estimator's σ is set by the schedule; its
    /// number of pairs and its RNG are used as they are.
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] naming the offending setting, [`Error::InvalidSigma`]
    /// for a bad schedule, [`Error::WorkspaceTooSmall`] for a short buffer,
    /// [`Error::NonFiniteInput`] for a non-finite start.
    pub fn new(
        method: Method<T>,
        schedule: Schedule<T>,
        budget: Budget<T>,
        estimator: Estimator<T, R>,
        theta: &'b mut [T],
        buffer: &'b mut [T],
    ) -> Result<Self, Error> {
        method.validate()?;
        schedule.validate()?;
        budget.validate()?;
        let n = theta.len();
        if n == 0 {
            return Err(Error::DimensionMismatch {
                expected: 1,
                found: 0,
            });
        }
        if let Some(index) = theta.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFiniteInput { index });
        }
        let needed = method.buffer_len(n);
        if buffer.len() < needed {
            return Err(Error::WorkspaceTooSmall {
                needed,
                available: buffer.len(),
            });
        }
        buffer[..needed].fill(T::ZERO);
        Ok(Optimiser {
            method,
            schedule,
            budget,
            estimator,
            theta,
            buffer,
            state: State {
                iteration: 0,
                evaluations: 0,
                adam_powers: (T::ONE, T::ONE),
                #[cfg(feature = "cg")]
                ncg: ncg::NcgState::default(),
                #[cfg(feature = "newton-cg")]
                mean_curvature: None,
                adapted_sigma: None,
                value_at_theta: None,
                costliest: 0,
                finished: None,
            },
        })
    }

    /// The current parameters (after a failure: those from before the failed iteration).
    pub fn theta(&self) -> &[T] {
        self.theta
    }

    /// Iterations completed.
    pub fn iteration(&self) -> usize {
        self.state.iteration
    }

    /// Objective evaluations used.
    pub fn evaluations(&self) -> usize {
        self.state.evaluations
    }

    /// Why the run ended, once it has.
    pub fn termination(&self) -> Option<Termination> {
        self.state.finished
    }

    /// The method and its settings.
    pub fn method(&self) -> &Method<T> {
        &self.method
    }

    /// The estimator (σ, pairs, RNG).
    pub fn estimator(&self) -> &Estimator<T, R> {
        &self.estimator
    }

    /// One iteration. `now` is the caller's clock in the units of
    /// [`Budget::max_time`] (pass 0 when there is no time limit).
    ///
    /// Returns `Ok(None)` without evaluating anything once the run has ended (see
    /// [`Optimiser::termination`]).
    ///
    /// # Errors
    /// [`Failed`] naming the iteration when an estimate fails (a non-finite objective
    /// value, an overflowing estimate, [`Error::Cancelled`]); θ is restored to its value at the start of the
    /// iteration, and further steps may be attempted.
    pub fn step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        ws: &mut Workspace<'_, T>,
        now: T,
    ) -> Result<Option<StepReport<T>>, Failed> {
        if self.state.finished.is_some() {
            return Ok(None);
        }
        let st = &mut self.state;
        if let Some(t) = self.budget.exhausted(st.iteration, st.evaluations, now) {
            st.finished = Some(t);
            return Ok(None);
        }
        if self
            .budget
            .max_evaluations
            .is_some_and(|m| st.evaluations.saturating_add(st.costliest) > m)
        {
            st.finished = Some(Termination::MaxEvaluations);
            return Ok(None);
        }
        let iteration = st.iteration + 1;
        let fail = |error| Failed { iteration, error };
        let n = self.theta.len();
        if ws.dim() != n {
            return Err(fail(Error::DimensionMismatch {
                expected: n,
                found: ws.dim(),
            }));
        }
        let scheduled =
            self.schedule
                .sigma(self.budget.progress(st.iteration, st.evaluations, now));
        let sigma = st.adapted_sigma.map_or(scheduled, |s| s.min(scheduled));
        self.estimator.set_sigma(sigma).map_err(fail)?;

        let (saved, buf) = self.buffer.split_at_mut(n);
        saved.copy_from_slice(self.theta);
        #[cfg_attr(not(feature = "newton-cg"), allow(unused_variables))]
        let (lowest_point, buf) = buf.split_at_mut(self.method.lowest_len(n));
        let snapshot = self
            .method
            .reuses_samples()
            .then(|| self.estimator.rng_mut().clone());
        let mut oracle = Oracle {
            estimator: &mut self.estimator,
            objective,
            ws,
            evaluations: 0,
            loss: None,
            snapshot,
            value_at_theta: st.value_at_theta,
            #[cfg(feature = "newton-cg")]
            centre_sample: None,
            settled: false,
            #[cfg(feature = "newton-cg")]
            lowest: None,
            #[cfg(feature = "newton-cg")]
            lowest_point,
            #[cfg(feature = "newton-cg")]
            highest: None,
        };
        let tol = self.budget.gradient_tolerance;
        let theta = &mut *self.theta;
        let (result, trust) = match &self.method {
            #[cfg(feature = "gradient-descent")]
            Method::GradientDescent(m) => (m.step(&mut oracle, theta, buf, tol), T::ZERO),
            Method::Adam(m) => (
                m.step(&mut oracle, theta, buf, &mut st.adam_powers, tol),
                T::ZERO,
            ),
            #[cfg(feature = "hessian")]
            Method::Newton(m) => (m.step(&mut oracle, theta, buf, tol), m.trust_radius * sigma),
            #[cfg(feature = "cg")]
            Method::Ncg(m) => (
                m.step(&mut oracle, theta, buf, &mut st.ncg, tol),
                m.trust_radius * sigma,
            ),
            #[cfg(feature = "newton-cg")]
            Method::NewtonCg(m) => (
                m.step(&mut oracle, theta, buf, &mut st.mean_curvature, tol),
                m.trust_radius * sigma,
            ),
        };
        st.evaluations += oracle.evaluations;
        st.costliest = st.costliest.max(oracle.evaluations);
        let loss = oracle.loss;
        // A value stays known while θ stays put or comes from a comparison.
        let value_at_theta = if oracle.settled || theta[..] == saved[..] {
            oracle.value_at_theta
        } else {
            None
        };
        if self.method.reuses_samples() {
            // Fresh samples next iteration: step the stream past this iteration's draws.
            let _ = self.estimator.rng_mut().next_u64();
        }
        let outcome = match result {
            Ok(o) => o,
            Err(error) => {
                theta.copy_from_slice(saved);
                return Err(fail(error));
            }
        };
        if let Some(index) = theta.iter().position(|x| !x.is_finite()) {
            theta.copy_from_slice(saved);
            return Err(fail(Error::NonFiniteEstimate { index }));
        }
        st.iteration = iteration;
        st.value_at_theta = value_at_theta;
        let kind = if outcome.verdict == Verdict::Rejected {
            StepKind::Rejected
        } else if !outcome.fallback && outcome.curvature.is_some_and(|c| c > T::ZERO) {
            if outcome.at_boundary {
                StepKind::TowardModelMinimum {
                    confirmed: outcome.verdict == Verdict::Kept,
                }
            } else {
                StepKind::ToModelMinimum {
                    length: outcome.step_length,
                    coverage: self.method.coverage(n, self.estimator.pairs()),
                }
            }
        } else {
            StepKind::NoModelMinimum
        };
        st.adapted_sigma = self.schedule.adapt(sigma, kind);
        let termination = if outcome.converged {
            Some(Termination::Converged)
        } else {
            self.budget.exhausted(st.iteration, st.evaluations, now)
        };
        // A budget reached after this step is recorded at the next call; convergence now.
        if outcome.converged {
            st.finished = termination;
        }
        Ok(Some(StepReport {
            iteration,
            evaluations: st.evaluations,
            sigma,
            loss,
            gradient_norm: outcome.gradient_norm,
            step_length: outcome.step_length,
            curvature: outcome.curvature,
            shift: outcome.shift,
            trust_radius: trust,
            restarted: outcome.restarted,
            fallback: outcome.fallback,
            termination,
        }))
    }

    /// Steps until the run ends, calling `observe` after every iteration. `clock` gives
    /// the caller's time in the units of [`Budget::max_time`].
    ///
    /// # Errors
    /// The first [`Failed`] iteration; θ keeps the last good parameters.
    pub fn run<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        ws: &mut Workspace<'_, T>,
        mut clock: impl FnMut() -> T,
        mut observe: impl FnMut(&StepReport<T>, &[T]),
    ) -> Result<Termination, Failed> {
        loop {
            match self.step(objective, ws, clock())? {
                Some(report) => observe(&report, self.theta),
                None => {
                    return Ok(self.state.finished.unwrap_or(Termination::MaxIterations));
                }
            }
        }
    }
}

fn check_positive<T: Real>(x: T, name: &'static str) -> Result<(), Error> {
    if x.is_finite() && x > T::ZERO {
        Ok(())
    } else {
        Err(Error::InvalidSetting { name })
    }
}
