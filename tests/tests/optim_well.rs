//! A narrow well beside a plateau and a wall, in one dimension: the landscape of MUG
//! (docs/notes/2026-11-23-benchmarks-before-auto.md, "Why MUG converges so rarely") without the renderer.
//!
//! f(x) = 1 − 0.3·exp(−x²/(2·0.2²)) + 10·max(0, −1 − x)², minimum at x = 0, starts in
//! [4, 6]. Gaussian smoothing at the starting σ = 3 averages the well away and the wall
//! pushes f̄'s minimum onto the plateau, so a method that follows f̄ waits there for σ to
//! fall; MUG's hyper-parameters (one pair, σ 3 → 0.01, Δ = 4).

mod common;
use common::newton_cg;

use common::{Sampling, optimise};
use hodr_core::optim::Budget;
use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::{NoiseSeed, Objective};
use hodr_host::report::task;

struct Well;

impl Objective<f64> for Well {
    fn evaluate(&mut self, x: &[f64], _seed: NoiseSeed) -> f64 {
        let x = x[0];
        let wall = (-1.0 - x).max(0.0);
        1.0 - 0.3 * (-x * x / (2.0 * 0.2 * 0.2)).exp() + 10.0 * wall * wall
    }
}

/// MUG's hyper-parameters as the report runs NewtonCG-AS and NewtonCG-ASC with them.
fn hyper(preset: Preset) -> Hyper<f64> {
    let mug = task::select(&["MUG".to_string()], false).unwrap().remove(0);
    mug.run_hyper(preset)
}

/// Final |x| after `evaluations` from a start in [4, 6] fixed by `seed`.
fn final_error(preset: Preset, seed: u64, evaluations: usize) -> f64 {
    let h = hyper(preset);
    let mut theta = [4.0 + 2.0 * (seed as f64 * 0.618_034).fract()];
    optimise(
        preset.method(&h),
        preset.schedule(&h),
        Budget::evaluations(evaluations),
        Sampling::of(&h, seed),
        &mut theta,
        &mut Well,
        |_, _| {},
    );
    theta[0].abs()
}

fn wins(preset: Preset, evaluations: usize) -> usize {
    (0..20)
        .filter(|&seed| final_error(preset, seed, evaluations) < 0.05)
        .count()
}

/// Comparing each model step on f with the current point and the iteration's lowest
/// sample finds the well from σ = 3 and stays in it while σ shrinks. Without the
/// comparison the same optimiser follows f̄ onto the plateau, where the well is
/// invisible to its model, and finds the well only when noise carries it there.
/// Measured within 150 evaluations: 16 of 20 seeds with the comparison, 3 without
/// (19 and 6 with central-difference HVPs, whose curvature is local to θ; the forward
/// difference's is the secant over [θ, θ + σ/3], blunter on a well of width σ/15).
#[test]
fn compared_steps_find_a_narrow_well_beside_a_wall() {
    let compared = wins(newton_cg("NewtonCG/compare"), 150);
    let uncompared = wins(newton_cg("NewtonCG"), 150);
    assert!(
        compared >= 15 && uncompared <= 8,
        "NewtonCG-ASC {compared}/20, NewtonCG-AS {uncompared}/20"
    );
}
