//! Newton-CG where nothing is seen, and on objectives that need no second look.
//!
//! BOX2-REF's plateau is flat only up to the pixel grid: a square drawn at sub-pixel
//! offsets covers slightly different pixel sums, so the loss wobbles by ~1e-6 relative.
//! Estimates built from such wobbles are noise; before the plateau rule they gave short
//! "model minimum" steps, σ collapsed far from the target and 2 of 20 seeds never found
//! it (docs/notes/2026-11-23-benchmarks-before-auto.md, "BOX2-REF: forward differences, plateaus, remembered values").

mod common;
use common::newton_cg;

use common::{Sampling, optimise};
use hodr_core::optim::preset::Hyper;
use hodr_core::optim::{Budget, Schedule};
use hodr_core::{NoiseSeed, Objective};

/// A bowl at the origin of radius 3 on a plateau of height 1 that wobbles by 1e-6.
fn bowl_on_wobbly_plateau(x: &[f64]) -> f64 {
    let r2: f64 = x.iter().map(|v| v * v).sum();
    let wobble = 1e-6 * x.iter().map(|v| (40.0 * v).sin()).sum::<f64>();
    (r2 / 9.0).min(1.0) + wobble
}

fn hyper() -> Hyper<f64> {
    common::one_pair(1.0, 2.0)
}

/// Far out on the plateau every sample ties with every other (within the comparison
/// margin): Newton-CG takes no step, estimates no curvature (one gradient, 2P
/// evaluations, per iteration) and σ does not shrink below the budget's linear cap.
#[test]
fn newton_cg_waits_on_a_plateau_without_shrinking_sigma() {
    for preset in [
        newton_cg("NewtonCG/linear"),
        newton_cg("NewtonCG"),
        newton_cg("NewtonCG/compare"),
        newton_cg("NewtonCG/fr22"),
    ] {
        let h = hyper();
        let start = [40.0, -35.0];
        let mut theta = start;
        let (mut iterations, mut last_evaluations) = (0, 0);
        optimise(
            preset.method(&h),
            Schedule::Adaptive {
                start: h.sigma_start,
                end: h.sigma_end,
                shrink: h.sigma_shrink,
            },
            Budget::iterations(20),
            Sampling::of(&h, 3),
            &mut theta,
            &mut bowl_on_wobbly_plateau,
            |report, _| {
                assert_eq!(
                    report.evaluations - last_evaluations,
                    2 * h.pairs,
                    "{preset:?}"
                );
                // σ stays at its cap, the linear schedule start → end.
                let progress = (report.iteration - 1) as f64 / 20.0;
                let cap = h.sigma_start + (h.sigma_end - h.sigma_start) * progress;
                assert!(
                    report.sigma >= cap * (1.0 - 1e-12),
                    "{preset:?}: σ {}",
                    report.sigma
                );
                last_evaluations = report.evaluations;
                iterations += 1;
            },
        );
        assert_eq!(iterations, 20);
        assert_eq!(theta, start, "{preset:?}");
    }
}

/// The same bowl behind the trait's default: nothing promised about the seed.
struct Undeclared;

impl Objective<f64> for Undeclared {
    fn evaluate(&mut self, x: &[f64], _seed: NoiseSeed) -> f64 {
        bowl_on_wobbly_plateau(x)
    }
}

/// Twelve NewtonCG-ASC iterations from (2, 1.5): the final θ and the evaluation count.
fn compared_run(objective: &mut impl Objective<f64>) -> ([f64; 2], usize) {
    let h = hyper();
    let preset = newton_cg("NewtonCG/compare");
    let mut theta = [2.0, 1.5];
    let mut evaluations = 0;
    optimise(
        preset.method(&h),
        preset.schedule(&h),
        Budget::iterations(12),
        Sampling::of(&h, 5),
        &mut theta,
        objective,
        |report, _| evaluations = report.evaluations,
    );
    (theta, evaluations)
}

/// NewtonCG-ASC compares each model step with the current point on f itself. A
/// deterministic objective's f(θ) (a plain closure) is remembered from the last
/// comparison instead of evaluated again: the same path, one evaluation fewer per
/// compared iteration after the first.
#[test]
fn compared_steps_remember_a_deterministic_value() {
    let (remembered, fewer) = compared_run(&mut bowl_on_wobbly_plateau);
    let (evaluated, more) = compared_run(&mut Undeclared);
    assert_eq!(remembered, evaluated);
    assert!(remembered.iter().all(|x| x.abs() < 0.1), "{remembered:?}");
    assert!(
        more - fewer >= 8,
        "{fewer} evaluations remembering, {more} evaluating"
    );
}
