//! Newton-CG with `NewtonCg::line_curvature`: the first inner step's curvature comes
//! from f on the line θ ± σ√n·ĝ/‖ĝ‖ (2 evaluations, 3 where f(θ) is not known) instead
//! of a gradient estimate at θ + εu (2P), and the step is the minimum of the parabola
//! through the three values.

mod common;
use common::newton_cg;

use common::{Sampling, optimise};
use hodr_core::optim::preset::Hyper;
use hodr_core::optim::{Budget, StepReport};
use hodr_core::{NoiseSeed, Objective};

const N: usize = 10;
const PAIRS: usize = 8;

/// ½ Σ aᵢxᵢ² with aᵢ from 1 to 10, plus x₀x₁ (not axis-aligned).
fn quadratic(x: &[f64]) -> f64 {
    let diagonal: f64 = x
        .iter()
        .enumerate()
        .map(|(i, v)| 0.5 * (1.0 + i as f64) * v * v)
        .sum();
    diagonal + x[0] * x[1]
}

fn gradient(x: &[f64]) -> Vec<f64> {
    let mut g: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(i, v)| (1.0 + i as f64) * v)
        .collect();
    g[0] += x[1];
    g[1] += x[0];
    g
}

fn start() -> Vec<f64> {
    (0..N).map(|i| 2.0 - 0.4 * i as f64).collect()
}

/// `PAIRS` pairs, one inner step, curvature from the line; σ large enough that the
/// trust radius (100σ) never clips a step.
fn hyper() -> Hyper<f64> {
    Hyper {
        pairs: PAIRS,
        inner_steps: 1,
        line_curvature: true,
        ..common::one_pair(0.5, 100.0)
    }
}

/// On a quadratic the line's second difference is exact, so every step that is not a
/// fallback lands on the minimum of f along its line (∇f at the new θ is orthogonal to
/// the step), for the aggregate and the FR22 estimator alike: the curvature is put in
/// each estimator's own scale. A deterministic objective's f(θ) is evaluated on the
/// line (it moves every iteration): 2P + 3 evaluations per iteration, where the HVP
/// would cost 2P + 2P.
#[test]
fn line_steps_land_on_the_minimum_along_the_gradient() {
    for preset in [newton_cg("NewtonCG"), newton_cg("NewtonCG/fr22")] {
        let h = hyper();
        for seed in 0..5 {
            let mut theta = start();
            let mut previous = theta.clone();
            let (mut last, mut minima) = (0, 0);
            optimise(
                preset.method(&h),
                preset.schedule(&h),
                Budget::iterations(6),
                Sampling::of(&h, seed),
                &mut theta,
                &mut quadratic,
                |report: &StepReport<f64>, now| {
                    assert_eq!(report.evaluations - last, 2 * PAIRS + 3, "{preset:?}");
                    last = report.evaluations;
                    let step: Vec<f64> = now.iter().zip(&previous).map(|(a, b)| a - b).collect();
                    if !report.fallback && report.step_length > 0.0 {
                        let along = |g: Vec<f64>| -> f64 {
                            g.iter().zip(&step).map(|(gi, si)| gi * si).sum()
                        };
                        let after = along(gradient(now));
                        let before = along(gradient(&previous)).abs();
                        assert!(
                            after.abs() <= 1e-9 * before,
                            "{preset:?} seed {seed}: ∇f·step {after} after, {before} before"
                        );
                        minima += 1;
                    }
                    previous = now.to_vec();
                },
            );
            assert!(minima >= 3, "{preset:?} seed {seed}: {minima} model steps");
            assert!(
                quadratic(&theta) < 0.5 * quadratic(&start()),
                "{preset:?} seed {seed}"
            );
        }
    }
}

/// NewtonCG-ASC: the line's points share the lowest sample's noise seed, so the
/// comparison, which evaluates θ and θ + p at that seed, reuses the line's f(θ):
/// 2P + 3 + 1 evaluations for a stochastic objective; a deterministic one remembers f(θ)
/// from the last comparison, 2P + 2 + 1 after the first iteration.
#[test]
fn compared_line_iterations_evaluate_f_at_theta_at_most_once() {
    let h = hyper();
    let preset = newton_cg("NewtonCG/compare");
    let counts = |deterministic| {
        let mut per_iteration = Vec::new();
        let mut last = 0;
        let mut theta = start();
        optimise(
            preset.method(&h),
            preset.schedule(&h),
            Budget::iterations(6),
            Sampling::of(&h, 1),
            &mut theta,
            &mut Quadratic { deterministic },
            |report, _| {
                per_iteration.push(report.evaluations - last);
                last = report.evaluations;
            },
        );
        assert!(quadratic(&theta) < quadratic(&start()));
        per_iteration
    };
    let noisy = counts(false);
    let remembered = counts(true);
    assert!(noisy.iter().all(|&e| e == 2 * PAIRS + 4), "{noisy:?}");
    assert_eq!(remembered[0], 2 * PAIRS + 4, "{remembered:?}");
    assert!(
        remembered[1..].iter().all(|&e| e == 2 * PAIRS + 3),
        "{remembered:?}"
    );
}

/// [`quadratic`] declared deterministic or not (then its values may depend on the seed
/// as far as the optimiser knows).
struct Quadratic {
    deterministic: bool,
}

impl Objective<f64> for Quadratic {
    fn evaluate(&mut self, x: &[f64], _seed: NoiseSeed) -> f64 {
        quadratic(x)
    }
    fn deterministic(&self) -> bool {
        self.deterministic
    }
}
