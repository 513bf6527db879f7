//! Objectives that fail at random: BBOB functions whose every evaluation returns NaN with
//! probability p, wherever it lies — a renderer or simulation that sometimes crashes, at
//! a point where it returns a value when called again.
//!
//! A failure is drawn from a hash of the problem's name, the bits of x and how many times
//! the run evaluated x before ([`super::trace::Clamped`] counts), so a point evaluated
//! again draws afresh and runs are reproducible whatever the thread count. The methods
//! are not told: they see NaN where the evaluation failed. A run is judged on f at the
//! points whose evaluation returned a value; a failed evaluation counts towards the
//! budget and finds nothing ([`super::trace::Counter::record`]). The functions, bounds,
//! starts and σ₀ are those of [`super::bbob`].

use super::bbob;
use super::problem::{Family, Observation, Problem};
use super::random;

/// The BBOB functions of the family: the sphere, the separable ellipsoid, Rosenbrock's
/// function, the rotated ellipsoid and the rotated Rastrigin function.
pub const IDS: [u32; 5] = [1, 2, 8, 10, 15];

/// The failure probabilities of the family, in per cent.
pub const PERCENTS: [u32; 2] = [10, 30];

/// The problem for BBOB function `id` (one of [`IDS`]), dimension `n`, instance
/// `instance`, each evaluation failing with probability `percent`/100.
pub fn problem(id: u32, percent: u32, n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    let name = format!("failing-p{percent:02}-f{id:02}-n{n:02}-i{instance}");
    let salt = random::seed_of(&name, &[]);
    let p = f64::from(percent) / 100.0;
    let observe = move |x: &[f64], value: f64, repeat: u64| {
        let draw = random::seed_of("failure", &[salt, random::point_seed(x), repeat]);
        if random::uniform(1, 0.0, 1.0, draw)[0] < p {
            f64::NAN
        } else {
            value
        }
    };
    Problem {
        name,
        family: Family::Failing,
        observation: Observation::Unseeded(Box::new(observe)),
        ..bbob::problem(id, n, instance, budget_per_dim)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::suite::trace::Counter;

    /// A failed evaluation counts towards the budget and finds nothing: the run's first
    /// event is the first evaluation that returned a value.
    #[test]
    fn a_failed_evaluation_counts_and_finds_nothing() {
        let problem = problem(1, 30, 2, 1, 10);
        let x = (0..)
            .map(|k| random::uniform(2, -4.0, 4.0, k))
            .find(|x| problem.observe(x, 0).is_nan())
            .expect("a point whose first evaluation fails");
        let mut counter = Counter::new(&problem, 100);
        let seen: Vec<f64> = (0..12).map(|_| counter.evaluate(&x)).collect();
        let first = seen
            .iter()
            .position(|v| v.is_finite())
            .expect("a value in 12");
        assert!(first > 0);
        let trace = counter.into_trace(1.0, None);
        assert_eq!(trace.evaluations, 12);
        assert_eq!(trace.events.len(), 1);
        assert_eq!(trace.events[0].evaluation, first + 1);
        assert_eq!(trace.events[0].f, problem.value(&x) - problem.f_opt);
    }

    /// The observed value is f or NaN, a repeat draws afresh, and the failure rate over
    /// many points is p within five standard errors.
    #[test]
    fn evaluations_fail_at_the_stated_rate_and_a_repeat_draws_afresh() {
        let problem = problem(8, 30, 3, 1, 10);
        let base = bbob::problem(8, 3, 1, 10);
        let draws: u32 = 4000;
        let (mut failed, mut differ) = (0_u32, 0_u32);
        for k in 0..draws {
            let x = random::uniform(3, -4.0, 4.0, u64::from(k));
            let seen = problem.observe(&x, 0);
            assert_eq!(seen.is_nan(), problem.observe(&x, 0).is_nan(), "pure");
            if seen.is_nan() {
                failed += 1;
            } else {
                assert_eq!(seen, base.value(&x));
            }
            if seen.is_nan() != problem.observe(&x, 1).is_nan() {
                differ += 1;
            }
        }
        let rate = f64::from(failed) / f64::from(draws);
        let se = (0.3 * 0.7 / f64::from(draws)).sqrt();
        assert!((rate - 0.3).abs() < 5.0 * se, "rate {rate}");
        // A repeat fails independently: the two disagree with probability 2p(1 − p).
        let disagree = f64::from(differ) / f64::from(draws);
        let se = (0.42 * 0.58 / f64::from(draws)).sqrt();
        assert!((disagree - 0.42).abs() < 5.0 * se, "disagree {disagree}");
        assert_eq!(problem.family, Family::Failing);
        assert_eq!(problem.x_opt, base.x_opt);
    }
}
