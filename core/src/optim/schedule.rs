//! The smoothing schedule σ(progress) and the budgets that define progress.

use crate::error::Error;
use crate::real::Real;

/// How σ changes over the run. Progress p ∈ [0, 1] is the largest used fraction of the
/// [`Budget`]'s iteration, evaluation and time limits.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Schedule<T> {
    /// σ fixed.
    Constant(T),
    /// σ = start + (end − start)·p: the paper's linear annealing.
    Linear {
        /// σ at p = 0.
        start: T,
        /// σ at p = 1.
        end: T,
    },
    /// σ follows what the run finds rather than the budget ([`Schedule::adapt`]). After
    /// an iteration that stepped to a minimum of its curvature model (positive
    /// curvature, no fallback step) less than σ away, σ ← max(end, shrink^c·σ), c the
    /// fraction of the directions its samples spanned ([`StepKind::ToModelMinimum`]);
    /// after one whose model step the objective rejected ([`StepKind::Rejected`]),
    /// σ ← max(end, shrink·σ); after one without a
    /// model minimum (non-positive curvature or a vanishing gradient), or whose step
    /// stopped at the trust boundary on the way to a model minimum beyond it and the
    /// objective confirmed that step, σ ← σ/√shrink; after a step of at least σ to a
    /// model minimum, or an unconfirmed one to the boundary, σ stays. σ never
    /// exceeds the linear schedule start → end at the same progress, so it reaches `end`
    /// by the end of the budget at the latest.
    ///
    /// A short step to a model minimum says that the minimum of f̄_σ lies within one
    /// smoothing width: smoothing at this scale has nothing more to show, and a smaller
    /// σ resolves finer structure (a narrow well the wide kernel averaged away) and cuts
    /// the estimators' σ-proportional error. A longer step to a model minimum keeps σ;
    /// one cut short by the trust boundary (radius Δσ) widens it once the objective has
    /// confirmed the step, as a trust region grows after a successful step to its edge;
    /// unconfirmed, a boundary step is as likely the estimates' noise (widening on it
    /// keeps σ oscillating in a noisy end game). No model minimum —
    /// a plateau, where the gradient vanishes because nothing is seen, or a ridge —
    /// calls for a wider kernel. A model fitted from samples along fewer directions
    /// than n (one antithetic pair in two dimensions) sees its minimum along those
    /// directions only, so a short step there shrinks σ by the matching fraction of
    /// `shrink`: shrink^c, c = directions/n, and n/directions such steps shrink it by
    /// `shrink`. The square root makes σ fall on balance only while
    /// more than a third of the iterations find a nearby minimum, as evolution
    /// strategies' success rules adapt their step size. A
    /// rejected model step says the model at this σ does not describe f near θ — the
    /// trust-region rule, with the radius Δσ shrinking through σ.
    /// First-order methods measure no curvature, so for them σ only grows back to the
    /// linear cap: use [`Schedule::Linear`] with them.
    Adaptive {
        /// σ at the start.
        start: T,
        /// The floor, and σ at p = 1.
        end: T,
        /// Factor in (0, 1) applied after a short or rejected step.
        shrink: T,
    },
}

/// What an iteration's step says about the smoothing scale ([`Schedule::adapt`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepKind<T> {
    /// A step to a minimum of the iteration's curvature model.
    ToModelMinimum {
        /// The step's length.
        length: T,
        /// The fraction of the n parameter directions the iteration's samples spanned,
        /// in (0, 1]: min(1, antithetic directions / n).
        coverage: T,
    },
    /// A step to the trust boundary toward a minimum of the curvature model beyond it;
    /// `confirmed` when the objective compared it with the current point and kept it
    /// ([`super::NewtonCg::compare_samples`]).
    TowardModelMinimum {
        /// The objective kept the step.
        confirmed: bool,
    },
    /// The model had no minimum: non-positive curvature, a fallback step or a vanishing
    /// gradient.
    NoModelMinimum,
    /// The objective preferred the current point or one of the iteration's samples to
    /// the model's step ([`super::NewtonCg::compare_samples`]).
    Rejected,
}

impl<T: Real> Schedule<T> {
    /// σ at progress p (clamped to [0, 1]).
    pub fn sigma(&self, progress: T) -> T {
        match *self {
            Schedule::Constant(s) => s,
            Schedule::Linear { start, end } | Schedule::Adaptive { start, end, .. } => {
                let p = progress.max(T::ZERO).min(T::ONE);
                start + (end - start) * p
            }
        }
    }

    /// σ for the next iteration of an adaptive schedule (before the cap of
    /// [`Schedule::sigma`]), given this iteration's σ and what its step was; `None` for
    /// the other schedules, whose σ depends on progress alone.
    pub fn adapt(&self, sigma: T, step: StepKind<T>) -> Option<T> {
        match *self {
            Schedule::Adaptive { end, shrink, .. } => Some(match step {
                StepKind::NoModelMinimum | StepKind::TowardModelMinimum { confirmed: true } => {
                    sigma / shrink.sqrt()
                }
                StepKind::TowardModelMinimum { confirmed: false } => sigma,
                StepKind::ToModelMinimum { length, .. } if length >= sigma => sigma,
                StepKind::ToModelMinimum { coverage, .. } => {
                    let c = coverage.max(T::ZERO).min(T::ONE);
                    let factor = if c == T::ONE {
                        shrink
                    } else {
                        (c * shrink.ln()).exp()
                    };
                    (factor * sigma).max(end)
                }
                StepKind::Rejected => (shrink * sigma).max(end),
            }),
            _ => None,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        let ok = |s: T| s.is_finite() && s > T::ZERO;
        let valid = match *self {
            Schedule::Constant(s) => ok(s),
            Schedule::Linear { start, end } => ok(start) && ok(end),
            Schedule::Adaptive { start, end, shrink } => {
                ok(start) && ok(end) && ok(shrink) && shrink < T::ONE
            }
        };
        if valid {
            Ok(())
        } else {
            Err(Error::InvalidSigma)
        }
    }
}

/// When to stop. Limits are checked between iterations. An iteration is not started
/// when it would take the evaluations past `max_evaluations` at the cost of the
/// costliest iteration so far, so a run overruns that limit only when an iteration
/// costs more than every earlier one (the first, or a longer line search).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget<T> {
    /// Stop after this many iterations. Default: `None`.
    pub max_iterations: Option<usize>,
    /// Stop once this many objective evaluations are used. Default: `None`.
    pub max_evaluations: Option<usize>,
    /// Stop once the caller's clock (the `now` passed to each step, in the caller's
    /// units) reaches this. Default: `None`.
    pub max_time: Option<T>,
    /// Stop when the estimated gradient norm falls to this or below. Default: `None`.
    pub gradient_tolerance: Option<T>,
}

impl<T: Real> Default for Budget<T> {
    fn default() -> Self {
        Budget {
            max_iterations: None,
            max_evaluations: None,
            max_time: None,
            gradient_tolerance: None,
        }
    }
}

impl<T: Real> Budget<T> {
    /// A budget of `iterations` iterations and nothing else.
    pub fn iterations(iterations: usize) -> Self {
        Budget {
            max_iterations: Some(iterations),
            ..Self::default()
        }
    }

    /// A budget of `evaluations` objective evaluations and nothing else.
    pub fn evaluations(evaluations: usize) -> Self {
        Budget {
            max_evaluations: Some(evaluations),
            ..Self::default()
        }
    }

    /// Progress p ∈ [0, 1]: the largest used fraction of the limits that are set.
    pub fn progress(&self, iterations: usize, evaluations: usize, now: T) -> T {
        let mut p = T::ZERO;
        if let Some(m) = self.max_iterations {
            p = p.max(T::from_usize(iterations) / T::from_usize(m.max(1)));
        }
        if let Some(m) = self.max_evaluations {
            p = p.max(T::from_usize(evaluations) / T::from_usize(m.max(1)));
        }
        if let Some(m) = self.max_time {
            p = p.max(now / m);
        }
        p.max(T::ZERO).min(T::ONE)
    }

    /// Which limit is reached, if any.
    pub fn exhausted(&self, iterations: usize, evaluations: usize, now: T) -> Option<Termination> {
        if self.max_iterations.is_some_and(|m| iterations >= m) {
            Some(Termination::MaxIterations)
        } else if self.max_evaluations.is_some_and(|m| evaluations >= m) {
            Some(Termination::MaxEvaluations)
        } else if self.max_time.is_some_and(|m| now >= m) {
            Some(Termination::TimeLimit)
        } else {
            None
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        if self.max_iterations.is_none()
            && self.max_evaluations.is_none()
            && self.max_time.is_none()
        {
            return Err(Error::InvalidSetting { name: "budget" });
        }
        if self
            .max_time
            .is_some_and(|t| !(t.is_finite() && t > T::ZERO))
        {
            return Err(Error::InvalidSetting { name: "max_time" });
        }
        if self
            .gradient_tolerance
            .is_some_and(|t| !(t.is_finite() && t >= T::ZERO))
        {
            return Err(Error::InvalidSetting {
                name: "gradient_tolerance",
            });
        }
        Ok(())
    }
}

/// Why a run ended (an outcome, not an error).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Termination {
    /// The estimated gradient norm reached the tolerance.
    Converged,
    /// The iteration limit was reached.
    MaxIterations,
    /// The evaluation limit was reached.
    MaxEvaluations,
    /// The caller's clock passed the time limit.
    TimeLimit,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_schedule_and_progress() {
        let s = Schedule::Linear {
            start: 1.5,
            end: 0.01,
        };
        assert_eq!(s.sigma(0.0), 1.5);
        assert!((s.sigma(1.0) - 0.01).abs() < 1e-15);
        assert_eq!(s.sigma(2.0), s.sigma(1.0));
        let b = Budget {
            max_iterations: Some(10),
            max_evaluations: Some(1000),
            ..Budget::default()
        };
        assert_eq!(b.progress(5, 100, 0.0), 0.5);
        assert_eq!(b.progress(1, 800, 0.0), 0.8);
        assert_eq!(b.exhausted(10, 0, 0.0), Some(Termination::MaxIterations));
        assert_eq!(b.exhausted(3, 1000, 0.0), Some(Termination::MaxEvaluations));
        assert_eq!(b.exhausted(3, 10, 0.0), None);
        assert_eq!(
            Budget::<f64>::default().validate(),
            Err(Error::InvalidSetting { name: "budget" })
        );
        assert_eq!(
            Schedule::Linear {
                start: 1.0,
                end: 0.0
            }
            .validate(),
            Err(Error::InvalidSigma)
        );
    }

    #[test]
    fn adaptive_schedule_shrinks_after_short_steps_only() {
        let s = Schedule::Adaptive {
            start: 2.0,
            end: 0.1,
            shrink: 0.5,
        };
        assert_eq!(s.validate(), Ok(()));
        // The cap is the linear schedule.
        assert_eq!(s.sigma(0.0), 2.0);
        assert!((s.sigma(0.5) - 1.05).abs() < 1e-15);
        // Short steps shrink, down to the floor; long ones keep σ.
        let to_minimum = |length| StepKind::ToModelMinimum {
            length,
            coverage: 1.0,
        };
        assert_eq!(s.adapt(2.0, to_minimum(0.5)), Some(1.0));
        assert_eq!(s.adapt(2.0, to_minimum(2.0)), Some(2.0));
        assert_eq!(s.adapt(0.15, to_minimum(0.0)), Some(0.1));
        // Samples along half the directions: two short steps shrink σ by `shrink`.
        let half = StepKind::ToModelMinimum {
            length: 0.5,
            coverage: 0.5,
        };
        let once = s.adapt(2.0, half).unwrap();
        assert!((once - 2.0 * 0.5f64.sqrt()).abs() < 1e-15);
        assert!((s.adapt(once, half).unwrap() - 1.0).abs() < 1e-15);
        // A rejected model step shrinks whatever its length.
        assert_eq!(s.adapt(2.0, StepKind::Rejected), Some(1.0));
        // No model minimum (a plateau) widens the kernel; so does a confirmed step to the
        // trust boundary, while an unconfirmed one keeps it.
        assert!((s.adapt(1.0, StepKind::NoModelMinimum).unwrap() - 2f64.sqrt()).abs() < 1e-15);
        let confirmed = StepKind::TowardModelMinimum { confirmed: true };
        assert!((s.adapt(1.0, confirmed).unwrap() - 2f64.sqrt()).abs() < 1e-15);
        let unconfirmed = StepKind::TowardModelMinimum { confirmed: false };
        assert_eq!(s.adapt(1.0, unconfirmed), Some(1.0));
        let linear = Schedule::Linear {
            start: 2.0,
            end: 0.1,
        };
        assert_eq!(linear.adapt(2.0, to_minimum(0.0)), None);
        for shrink in [0.0, 1.0, f64::NAN] {
            let bad = Schedule::Adaptive {
                start: 2.0,
                end: 0.1,
                shrink,
            };
            assert_eq!(bad.validate(), Err(Error::InvalidSigma));
        }
    }
}
