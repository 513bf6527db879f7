//! Nonlinear conjugate gradient, the paper's main optimiser (docs/design.md §1.7).
//!
//! Residual r = −ĝ, direction d. Each iteration:
//!
//! 1. restart d = r at the first iteration, every `recompute` iterations, or when
//!    rᵀd ≤ 0 after the update; otherwise d ← r + βd with Fletcher–Reeves
//!    β = rᵀr / r_oldᵀr_old;
//! 2. line search along d by Newton–Raphson steps α = −ĝᵀd / dᵀĤd (dᵀĤd from one HVP,
//!    or from a full Hessian estimate), at most `line_search_iterations` steps, stopping
//!    when α²·dᵀd < `line_search_tolerance`; the gradient is re-estimated at each new
//!    point of the line search;
//! 3. every step is at most Δ·σ long (Δ = `trust_radius`).
//!
//! Where dᵀĤd ≤ 0 (or is not finite) there is no Newton step to take. Estimated
//! curvature changes sign under noise far more often than the smoothed loss does, so
//! jumping to the trust boundary (the Steihaug choice) would let noise throw the
//! iterate Δ·σ at a time. Instead the fallback is a gradient-descent-like step along
//! the downhill sign of d, α = −ĝᵀd / (κ̄·dᵀd), where κ̄ is a running mean of the positive
//! curvatures dᵀĤd/dᵀd this run has measured — a step the data so far can justify —
//! or a step of one σ before any curvature is known; it is capped at Δ·σ like every
//! step, and zero when ĝᵀd = 0. (The authors' code divides by 1 instead, which moves
//! |ĝ|²·|d| — up to 50σ — and throws a quadratic's iterates far from the optimum.) With
//! [`NegativeCurvature::TwoSided`] that step competes with the two trust-boundary
//! steps α = ±Δσ/‖d‖, and the objective picks the lowest of the three.

use rand_core::Rng;

use super::oracle::Oracle;
use super::vector::{dot, norm};
use super::{NegativeCurvature, Outcome, check_positive};
use crate::error::Error;
#[cfg(feature = "hessian")]
use crate::estimate::HessianMethod;
use crate::estimate::{GradientMethod, HvpMethod};
use crate::objective::Objective;
use crate::real::Real;

/// Where the line search's curvature dᵀĤd comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Curvature {
    /// One Hessian-vector product Ĥd per line-search step.
    Hvp(HvpMethod),
    /// A full Hessian estimate per line-search step (the paper's OurH with NCG).
    #[cfg(feature = "hessian")]
    Hessian(HessianMethod),
}

/// Nonlinear conjugate gradient with a Newton–Raphson line search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ncg<T> {
    /// The gradient estimator.
    pub gradient: GradientMethod,
    /// The curvature source.
    pub curvature: Curvature,
    /// Δ: each line-search step is at most Δ·σ long.
    pub trust_radius: T,
    /// Newton–Raphson steps per line search (≥ 1).
    pub line_search_iterations: usize,
    /// The line search stops when α²·dᵀd falls below this (parameter units squared).
    pub line_search_tolerance: T,
    /// Restart d = r every this many iterations (≥ 1).
    pub recompute: usize,
    /// Reuse one sample set for every estimate of an iteration (gradient, HVPs, line
    /// search): the RNG is rewound to its state at the iteration's start before each
    /// estimate, so all of them see the same offsets and noise seeds. The iteration then
    /// works on one fixed sample-average approximation of f̄: with central- or
    /// forward-difference HVPs of the same gradient estimator, Ĥv = M·∇²f̄·v and
    /// ĝ = M·∇f̄ share the random matrix M, which cancels from the Newton step on
    /// quadratics; a forward difference then reuses ĝ(θ) itself
    /// ([`HvpMethod::ForwardDifference`]). Fresh samples come with each new iteration.
    pub reuse_samples: bool,
    /// The step where dᵀĤd ≤ 0. Presets: [`NegativeCurvature::Fallback`].
    pub negative_curvature: NegativeCurvature,
}

/// NCG's memory between iterations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct NcgState<T> {
    /// r_oldᵀr_old, `None` before the first iteration.
    pub rr_old: Option<T>,
    /// Iterations since the last restart.
    pub since_restart: usize,
    /// κ̄: running mean (weight ½) of the positive curvatures dᵀĤd/dᵀd measured.
    pub mean_curvature: Option<T>,
}

impl<T: Real> Ncg<T> {
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_positive(self.trust_radius, "trust_radius")?;
        if self.line_search_iterations == 0 {
            return Err(Error::InvalidSetting {
                name: "line_search_iterations",
            });
        }
        if self.recompute == 0 {
            return Err(Error::InvalidSetting { name: "recompute" });
        }
        if !(self.line_search_tolerance.is_finite() && self.line_search_tolerance >= T::ZERO) {
            return Err(Error::InvalidSetting {
                name: "line_search_tolerance",
            });
        }
        Ok(())
    }

    /// Buffer floats needed: ĝ, d, Ĥd (and Ĥ for Hessian curvature).
    pub(crate) fn buffer_len(&self, n: usize) -> usize {
        match self.curvature {
            Curvature::Hvp(_) => 3 * n,
            #[cfg(feature = "hessian")]
            Curvature::Hessian(_) => 3 * n + n * n,
        }
    }

    pub(crate) fn step<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &mut [T],
        buf: &mut [T],
        state: &mut NcgState<T>,
        tolerance: Option<T>,
    ) -> Result<Outcome<T>, Error> {
        let n = theta.len();
        let (g, rest) = buf.split_at_mut(n);
        let (d, rest) = rest.split_at_mut(n);
        let (hd, rest) = rest.split_at_mut(n);

        oracle.gradient(self.gradient, theta, g)?;
        let rr = dot(g, g);
        let gradient_norm = norm(g);
        if let Some(done) = Outcome::converged(gradient_norm, tolerance) {
            return Ok(done);
        }

        // Direction: Fletcher–Reeves update, or restart.
        let restarted = match state.rr_old {
            Some(rr_old) if state.since_restart < self.recompute && rr_old > T::ZERO => {
                let beta = rr / rr_old;
                for (di, &gi) in d.iter_mut().zip(g.iter()) {
                    *di = -gi + beta * *di;
                }
                // rᵀd = −ĝᵀd must be positive for d to lead downhill.
                !(-dot(g, d) > T::ZERO && beta.is_finite())
            }
            _ => true,
        };
        if restarted {
            for (di, &gi) in d.iter_mut().zip(g.iter()) {
                *di = -gi;
            }
            state.since_restart = 0;
        }
        state.rr_old = Some(rr);

        // Newton–Raphson line search along d.
        let dd = dot(d, d);
        let d_norm = dd.sqrt();
        let mut outcome = Outcome {
            gradient_norm,
            restarted,
            ..Outcome::default()
        };
        if !(d_norm > T::ZERO && d_norm.is_finite()) {
            state.since_restart += 1;
            return Ok(outcome);
        }
        for j in 0..self.line_search_iterations {
            let shared = j > 0 && self.shares_samples();
            if shared {
                #[cfg(feature = "gaussian")]
                oracle.gradient_and_hvp(theta, d, g, hd)?;
            } else {
                if j > 0 {
                    oracle.gradient(self.gradient, theta, g)?;
                }
                self.curvature_along(oracle, theta, g, d, hd, rest)?;
            }
            let gd = dot(g, d);
            let dhd = dot(d, hd);
            outcome.curvature = Some(dhd / dd);
            let radius = self.trust_radius * oracle.sigma();
            let cap = radius / d_norm;
            let positive = dhd > T::ZERO && dhd.is_finite();
            let alpha = if positive {
                let kappa = dhd / dd;
                state.mean_curvature = Some(match state.mean_curvature {
                    Some(m) => T::HALF * (m + kappa),
                    None => kappa,
                });
                -gd / dhd
            } else {
                outcome.fallback = true;
                match state.mean_curvature {
                    Some(kappa) => -gd / (kappa * dd),
                    None => -gd.sign() * oracle.sigma() / d_norm,
                }
            };
            let mut alpha = alpha.max(-cap).min(cap);
            if !positive && self.negative_curvature == NegativeCurvature::TwoSided {
                let candidates = [alpha, cap, -cap];
                let origin: &[T] = theta;
                let best = oracle.lowest::<3>(|k, x| {
                    for ((xi, &o), &di) in x.iter_mut().zip(origin).zip(d.iter()) {
                        *xi = o + candidates[k] * di;
                    }
                })?;
                alpha = candidates[best];
            }
            for (x, &di) in theta.iter_mut().zip(d.iter()) {
                *x += alpha * di;
            }
            outcome.step_length += alpha.abs() * d_norm;
            if alpha.sq() * dd < self.line_search_tolerance {
                break;
            }
        }
        state.since_restart += 1;
        Ok(outcome)
    }

    /// True when the gradient and the HVP can come from one shared sample set.
    fn shares_samples(&self) -> bool {
        #[cfg(feature = "gaussian")]
        return self.gradient == GradientMethod::Gaussian
            && self.curvature == Curvature::Hvp(HvpMethod::Kernel);
        #[cfg(not(feature = "gaussian"))]
        false
    }

    /// Ĥd into `hd` (ĝ = `g` at θ), using `hess` (n² floats) for Hessian curvature.
    #[cfg_attr(not(feature = "hessian"), allow(unused_variables))]
    fn curvature_along<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &[T],
        g: &[T],
        d: &[T],
        hd: &mut [T],
        hess: &mut [T],
    ) -> Result<(), Error> {
        match self.curvature {
            Curvature::Hvp(m) => oracle.hvp(m, theta, (self.gradient, g), d, hd),
            #[cfg(feature = "hessian")]
            Curvature::Hessian(m) => {
                let n = theta.len();
                let hess = &mut hess[..n * n];
                oracle.hessian(m, theta, hess)?;
                for (i, out) in hd.iter_mut().enumerate() {
                    *out = dot(&hess[i * n..(i + 1) * n], d);
                }
                Ok(())
            }
        }
    }
}
