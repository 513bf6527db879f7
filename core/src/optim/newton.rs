//! Newton's method with the full estimated Hessian (docs/design.md §1.7).
//!
//! p solves (Ĥ + λI)p = −ĝ, λ the smallest shift in {0, λ₀, 10λ₀, …} for which a
//! Cholesky factorisation succeeds (so the step is a descent direction of the model even
//! where the smoothed loss is not convex); then p is truncated to the trust radius Δ·σ.
//! If no shift works (a non-finite Hessian), the step falls back to −ĝ truncated alike.

use rand_core::Rng;

use super::oracle::Oracle;
use super::vector::norm;
use super::{Outcome, check_positive};
use crate::cholesky::{factor_shifted, solve};
use crate::error::Error;
use crate::estimate::{GradientMethod, HessianMethod};
use crate::objective::Objective;
use crate::real::Real;

/// Newton's method with a shifted-Cholesky solve and a trust-radius cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Newton<T> {
    /// The gradient estimator.
    pub gradient: GradientMethod,
    /// The Hessian estimator.
    pub hessian: HessianMethod,
    /// Δ: steps are at most Δ·σ long.
    pub trust_radius: T,
}

impl<T: Real> Newton<T> {
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_positive(self.trust_radius, "trust_radius")
    }

    /// Buffer floats needed: ĝ, p, Ĥ, L.
    pub(crate) fn buffer_len(n: usize) -> usize {
        2 * n + 2 * n * n
    }

    pub(crate) fn step<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &mut [T],
        buf: &mut [T],
        tolerance: Option<T>,
    ) -> Result<Outcome<T>, Error> {
        let n = theta.len();
        let (g, rest) = buf.split_at_mut(n);
        let (p, rest) = rest.split_at_mut(n);
        let (h, rest) = rest.split_at_mut(n * n);
        let l = &mut rest[..n * n];
        oracle.gradient(self.gradient, theta, g)?;
        let gradient_norm = norm(g);
        if let Some(done) = Outcome::converged(gradient_norm, tolerance) {
            return Ok(done);
        }
        oracle.hessian(self.hessian, theta, h)?;
        for (pi, &gi) in p.iter_mut().zip(g.iter()) {
            *pi = -gi;
        }
        let shift = factor_shifted(h, l, n);
        if shift.is_some() {
            solve(l, n, p);
        }
        let radius = self.trust_radius * oracle.sigma();
        let length = norm(p);
        let scale = if length > radius {
            radius / length
        } else {
            T::ONE
        };
        for (x, &pi) in theta.iter_mut().zip(p.iter()) {
            *x += scale * pi;
        }
        Ok(Outcome {
            gradient_norm,
            step_length: length.min(radius),
            shift,
            fallback: shift.is_none(),
            ..Outcome::default()
        })
    }
}
