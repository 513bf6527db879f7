//! A damped-Newton step loop on the smoothed loss: the per-shape optimiser of the fit.
//!
//! Each iteration estimates the smoothed gradient g and Hessian H at θ with hodr-core's
//! aggregate estimators (DESIGN §1.3: 2P + 2P + 1 evaluations for all n + n(n+1)/2
//! elements), solves (H + λI)s = −g with the smallest λ ∈ {0, λ₀·10ᵏ} for which the
//! Cholesky factorisation succeeds (a positive-definite model even where the smoothed
//! loss is not convex), truncates s to the trust radius Δ = `trust`·σ, and steps. σ
//! anneals linearly from `sigma_start` to `sigma_end`.
//!
//! This is a small stand-in for hodr-core's optimisers (NCG, Newton): it needs nothing
//! but the estimators, and the fit calls it through one function so it can be swapped.

use hodr_core::{Estimator, GradientMethod, HessianMethod, Objective, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::error::Error;

/// Batch capacity of the estimators' workspace: enough rows for both threads.
const ROWS: usize = 64;

/// Most λ increases tried before falling back to a gradient step.
const MAX_DAMPING_TRIES: usize = 24;

/// Settings of [`optimise`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Schedule {
    pub(crate) iterations: usize,
    pub(crate) pairs: usize,
    pub(crate) sigma_start: f64,
    pub(crate) sigma_end: f64,
    /// Trust radius in units of σ.
    pub(crate) trust: f64,
}

/// Runs `schedule.iterations` damped Newton steps from `theta` (updated in place).
///
/// # Errors
/// The estimators' errors (a non-finite value or estimate).
pub(crate) fn optimise<O: Objective<f64>>(
    objective: &mut O,
    theta: &mut [f64],
    schedule: &Schedule,
    seed: u64,
) -> Result<(), Error> {
    let n = theta.len();
    let mut buffer = vec![0.0; Workspace::<f64>::buffer_len(n, ROWS)];
    let mut seeds = vec![0; ROWS];
    let mut ws = Workspace::new(n, &mut buffer, &mut seeds)?;
    let mut estimator = Estimator::new(
        schedule.sigma_start,
        schedule.pairs,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )?;
    let (mut g, mut h, mut factor, mut step) = (
        vec![0.0; n],
        vec![0.0; n * n],
        vec![0.0; n * n],
        vec![0.0; n],
    );
    let last = schedule.iterations.saturating_sub(1).max(1) as f64;
    for it in 0..schedule.iterations {
        let t = it as f64 / last;
        let sigma = schedule.sigma_start + (schedule.sigma_end - schedule.sigma_start) * t;
        estimator.set_sigma(sigma)?;
        estimator.gradient(GradientMethod::Aggregate, objective, theta, &mut ws, &mut g)?;
        estimator.hessian(HessianMethod::Aggregate, objective, theta, &mut ws, &mut h)?;
        damped_newton(&h, &g, &mut factor, &mut step);
        let radius = schedule.trust * sigma;
        let norm = step.iter().map(|s| s * s).sum::<f64>().sqrt();
        let shrink = if norm > radius { radius / norm } else { 1.0 };
        for (x, s) in theta.iter_mut().zip(&step) {
            *x += shrink * s;
        }
    }
    Ok(())
}

/// s = −(H + λI)⁻¹g with the smallest damping λ that makes H + λI positive definite;
/// s = −g if none of the tries does (then the caller's trust radius bounds it).
fn damped_newton(h: &[f64], g: &[f64], factor: &mut [f64], step: &mut [f64]) {
    let n = g.len();
    let scale = (0..n)
        .map(|i| h[i * n + i].abs())
        .fold(0.0, f64::max)
        .max(1e-12);
    let mut lambda = 0.0;
    for _ in 0..MAX_DAMPING_TRIES {
        factor.copy_from_slice(h);
        for i in 0..n {
            factor[i * n + i] += lambda;
        }
        if cholesky(factor, n) {
            solve(factor, n, g, step);
            return;
        }
        lambda = if lambda == 0.0 {
            1e-6 * scale
        } else {
            lambda * 10.0
        };
    }
    for (s, &gi) in step.iter_mut().zip(g) {
        *s = -gi;
    }
}

/// In-place lower Cholesky factor of the symmetric n×n `a`; false if not positive definite.
fn cholesky(a: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut v = a[i * n + j];
            for k in 0..j {
                v -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = v / d;
        }
    }
    true
}

/// Solves L Lᵀ s = −g with the factor from [`cholesky`].
fn solve(l: &[f64], n: usize, g: &[f64], s: &mut [f64]) {
    for i in 0..n {
        let mut v = -g[i];
        for k in 0..i {
            v -= l[i * n + k] * s[k];
        }
        s[i] = v / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut v = s[i];
        for k in i + 1..n {
            v -= l[k * n + i] * s[k];
        }
        s[i] = v / l[i * n + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damped_newton_solves_positive_definite_systems_exactly() {
        let h = [4.0, 1.0, 1.0, 3.0];
        let g = [1.0, 2.0];
        let (mut f, mut s) = ([0.0; 4], [0.0; 2]);
        damped_newton(&h, &g, &mut f, &mut s);
        // H s = −g.
        assert!((4.0 * s[0] + s[1] + 1.0).abs() < 1e-12);
        assert!((s[0] + 3.0 * s[1] + 2.0).abs() < 1e-12);
    }

    #[test]
    fn indefinite_hessians_are_damped_into_descent_directions() {
        let h = [-2.0, 0.0, 0.0, 1.0];
        let g = [1.0, 1.0];
        let (mut f, mut s) = ([0.0; 4], [0.0; 2]);
        damped_newton(&h, &g, &mut f, &mut s);
        assert!(s[0] * g[0] + s[1] * g[1] < 0.0, "{s:?}");
    }

    #[test]
    fn a_smooth_bowl_is_minimised() {
        let mut f = |x: &[f64]| (x[0] - 1.0).powi(2) + 2.0 * (x[1] + 0.5).powi(2);
        let mut theta = [3.0, 2.0];
        let schedule = Schedule {
            iterations: 20,
            pairs: 8,
            sigma_start: 0.3,
            sigma_end: 0.05,
            trust: 4.0,
        };
        optimise(&mut f, &mut theta, &schedule, 1).unwrap();
        assert!(
            (theta[0] - 1.0).abs() < 0.1 && (theta[1] + 0.5).abs() < 0.1,
            "{theta:?}"
        );
    }
}
