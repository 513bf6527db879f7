//! First-order optimisers: gradient descent (feature `gradient-descent`) and Adam (the
//! paper's first-order rows).

use rand_core::Rng;

use super::oracle::Oracle;
use super::vector::norm;
use super::{Outcome, check_positive};
use crate::error::Error;
use crate::estimate::GradientMethod;
use crate::objective::Objective;
use crate::real::Real;

/// θ ← θ − η·ĝ.
#[cfg(feature = "gradient-descent")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GradientDescent<T> {
    /// The gradient estimator.
    pub gradient: GradientMethod,
    /// η, in parameter units per unit gradient.
    pub learning_rate: T,
}

#[cfg(feature = "gradient-descent")]
impl<T: Real> GradientDescent<T> {
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_positive(self.learning_rate, "learning_rate")
    }

    /// Buffer floats needed: ĝ.
    pub(crate) fn buffer_len(n: usize) -> usize {
        n
    }

    pub(crate) fn step<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &mut [T],
        buf: &mut [T],
        tolerance: Option<T>,
    ) -> Result<Outcome<T>, Error> {
        let g = &mut buf[..theta.len()];
        oracle.gradient(self.gradient, theta, g)?;
        let gn = norm(g);
        if let Some(done) = Outcome::converged(gn, tolerance) {
            return Ok(done);
        }
        for (x, &gi) in theta.iter_mut().zip(g.iter()) {
            *x -= self.learning_rate * gi;
        }
        Ok(Outcome {
            gradient_norm: gn,
            step_length: self.learning_rate * gn,
            ..Outcome::default()
        })
    }
}

/// Adam (Kingma & Ba 2015): m ← β₁m + (1−β₁)ĝ, v ← β₂v + (1−β₂)ĝ²,
/// θ ← θ − η·m̂/(√v̂ + ε) with the bias corrections m̂ = m/(1−β₁ᵗ), v̂ = v/(1−β₂ᵗ).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adam<T> {
    /// The gradient estimator.
    pub gradient: GradientMethod,
    /// η, in parameter units per step.
    pub learning_rate: T,
    /// β₁. Default: 0.9.
    pub beta1: T,
    /// β₂. Default: 0.999.
    pub beta2: T,
    /// ε. Default: 1e-8.
    pub epsilon: T,
}

impl<T: Real> Adam<T> {
    /// Adam with the usual β₁ = 0.9, β₂ = 0.999, ε = 1e-8.
    pub fn new(gradient: GradientMethod, learning_rate: T) -> Self {
        Adam {
            gradient,
            learning_rate,
            beta1: T::from_f64(0.9),
            beta2: T::from_f64(0.999),
            epsilon: T::from_f64(1e-8),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_positive(self.learning_rate, "learning_rate")?;
        let unit = |b: T| b >= T::ZERO && b < T::ONE;
        if !unit(self.beta1) {
            return Err(Error::InvalidSetting { name: "beta1" });
        }
        if !unit(self.beta2) {
            return Err(Error::InvalidSetting { name: "beta2" });
        }
        check_positive(self.epsilon, "epsilon")
    }

    /// Buffer floats needed: ĝ, m, v.
    pub(crate) fn buffer_len(n: usize) -> usize {
        3 * n
    }

    /// `powers` holds (β₁ᵗ, β₂ᵗ) of the previous step, (1, 1) at the start.
    pub(crate) fn step<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &mut [T],
        buf: &mut [T],
        powers: &mut (T, T),
        tolerance: Option<T>,
    ) -> Result<Outcome<T>, Error> {
        let n = theta.len();
        let (g, rest) = buf.split_at_mut(n);
        let (m, rest) = rest.split_at_mut(n);
        let v = &mut rest[..n];
        oracle.gradient(self.gradient, theta, g)?;
        let gradient_norm = norm(g);
        if let Some(done) = Outcome::converged(gradient_norm, tolerance) {
            return Ok(done);
        }
        powers.0 *= self.beta1;
        powers.1 *= self.beta2;
        let (c1, c2) = (T::ONE - powers.0, T::ONE - powers.1);
        let mut step2 = T::ZERO;
        for i in 0..n {
            m[i] = self.beta1 * m[i] + (T::ONE - self.beta1) * g[i];
            v[i] = self.beta2 * v[i] + (T::ONE - self.beta2) * g[i].sq();
            let delta = self.learning_rate * (m[i] / c1) / ((v[i] / c2).sqrt() + self.epsilon);
            theta[i] -= delta;
            step2 += delta.sq();
        }
        Ok(Outcome {
            gradient_norm,
            step_length: step2.sqrt(),
            ..Outcome::default()
        })
    }
}
