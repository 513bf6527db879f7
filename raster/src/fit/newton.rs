//! The per-shape optimiser of the fit: hodr-core's [`Newton`] on the smoothed loss.
//!
//! Each iteration estimates the smoothed gradient and Hessian at θ with the aggregate
//! estimators (docs/design.md §1.3: 2P + 2P + 1 evaluations for all n + n(n+1)/2 elements; n
//! is 3–6 here, so the full Hessian is cheaper than HVP line searches), solves the
//! shifted Newton system, truncates the step to the trust radius Δ·σ, and steps; σ
//! anneals linearly over the iterations.

use hodr_core::optim::{Budget, Method, Newton, Optimiser, Schedule as SigmaSchedule};
use hodr_core::{Estimator, GradientMethod, HessianMethod, Objective, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::error::Error;

/// Batch capacity of the estimators' workspace: enough rows for both threads.
const ROWS: usize = 64;

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

/// Runs `schedule.iterations` Newton steps from `theta` (updated in place). A failed
/// iteration (not expected: the objective is finite everywhere) ends the run with θ
/// as it was before that iteration.
///
/// # Errors
/// The optimiser's setting errors.
pub(crate) fn optimise<O: Objective<f64>>(
    objective: &mut O,
    theta: &mut [f64],
    schedule: &Schedule,
    seed: u64,
) -> Result<(), Error> {
    if schedule.iterations == 0 {
        return Ok(());
    }
    let n = theta.len();
    let mut buffer = vec![0.0; Workspace::<f64>::buffer_len(n, ROWS)];
    let mut seeds = vec![0; ROWS];
    let mut ws = Workspace::new(n, &mut buffer, &mut seeds)?;
    let estimator = Estimator::new(
        schedule.sigma_start,
        schedule.pairs,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )?;
    let method = Method::Newton(Newton {
        gradient: GradientMethod::Aggregate,
        hessian: HessianMethod::Aggregate,
        trust_radius: schedule.trust,
    });
    let mut memory = vec![0.0; method.buffer_len(n)];
    let mut optimiser = Optimiser::new(
        method,
        SigmaSchedule::Linear {
            start: schedule.sigma_start,
            end: schedule.sigma_end,
        },
        Budget::iterations(schedule.iterations),
        estimator,
        theta,
        &mut memory,
    )?;
    // A failure leaves θ at its last good value, which is all the fit needs.
    let _ = optimiser.run(objective, &mut ws, || 0.0, |_, _| {});
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
