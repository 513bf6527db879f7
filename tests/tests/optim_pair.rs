//! Newton-CG iterations whose gradient comes from one antithetic pair θ ± σt take their
//! curvature along t from the pair's second difference (`NewtonCg::pair_curvature`):
//! the step is the minimum of the parabola through f(θ − σt), f(θ), f(θ + σt), and
//! costs f(θ) (remembered, or one evaluation) instead of a gradient estimate at θ + εu.

mod common;
use common::newton_cg;

use common::{Sampling, optimise};
use hodr_core::optim::preset::Hyper;
use hodr_core::optim::{Budget, Schedule};
use hodr_core::{NoiseSeed, Objective};

/// ½xᵀAx with A = [[3, 1], [1, 2]].
fn quadratic(x: &[f64]) -> f64 {
    0.5 * (3.0 * x[0] * x[0] + 2.0 * x[0] * x[1] + 2.0 * x[1] * x[1])
}

fn gradient(x: &[f64]) -> [f64; 2] {
    [3.0 * x[0] + x[1], x[0] + 2.0 * x[1]]
}

fn hyper() -> Hyper<f64> {
    common::one_pair(0.5, 100.0)
}

fn adaptive(h: &Hyper<f64>) -> Schedule<f64> {
    Schedule::Adaptive {
        start: h.sigma_start,
        end: h.sigma_end,
        shrink: h.sigma_shrink,
    }
}

/// On a quadratic the second difference is exact, so each step lands on the minimum of
/// f along its line: ∇f at the new θ is orthogonal to the step. Aggregate (weighted)
/// and Gaussian (unweighted) estimates alike, as the curvature is put in the
/// estimator's own scale. Without compare, f(θ) is evaluated: 3 evaluations per
/// iteration (2 + 1), where a forward-difference HVP costs 4.
#[test]
fn one_pair_steps_to_the_minimum_along_its_line() {
    for preset in [
        newton_cg("NewtonCG"),
        newton_cg("NewtonCG/gaussian/kernel/linear"),
    ] {
        let h = hyper();
        let mut method = preset.method(&h);
        if let hodr_core::optim::Method::NewtonCg(m) = &mut method {
            m.pair_curvature = true;
            m.reuse_samples = true;
        }
        for seed in 0..10 {
            let mut theta = [2.0, -1.5];
            let mut previous = theta;
            let mut last_evaluations = 0;
            optimise(
                method,
                adaptive(&h),
                Budget::iterations(4),
                Sampling::of(&h, seed),
                &mut theta,
                &mut quadratic,
                |report, now| {
                    let step = [now[0] - previous[0], now[1] - previous[1]];
                    let g = gradient(now);
                    let along = g[0] * step[0] + g[1] * step[1];
                    let g0 = gradient(&previous);
                    let before = (g0[0] * step[0] + g0[1] * step[1]).abs();
                    assert!(
                        along.abs() <= 1e-9 * before.max(1e-300),
                        "{preset:?} seed {seed}: ∇f·step {along} after, {before} before"
                    );
                    assert!(report.step_length > 0.0, "{preset:?} seed {seed}");
                    assert_eq!(report.evaluations - last_evaluations, 3, "{preset:?}");
                    last_evaluations = report.evaluations;
                    previous = [now[0], now[1]];
                },
            );
            assert!(quadratic(&theta) < quadratic(&[2.0, -1.5]));
        }
    }
}

/// The quadratic behind the trait's default: its values may depend on the noise seed.
struct Stochastic;

impl Objective<f64> for Stochastic {
    fn evaluate(&mut self, x: &[f64], _seed: NoiseSeed) -> f64 {
        quadratic(x)
    }
}

/// NewtonCG-ASC on one pair: a deterministic objective's f(θ) is remembered from the
/// last comparison (2 + 1 evaluations per iteration after the first); otherwise f(θ)
/// is evaluated once with the pair's noise seed and the comparison reuses it
/// (2 + 1 + 1, where the forward-difference HVP and a fresh f(θ) cost 2 + 2 + 2).
#[test]
fn compared_one_pair_iterations_evaluate_f_at_theta_at_most_once() {
    let h = Hyper {
        trust_radius: 2.0,
        ..hyper()
    };
    let preset = newton_cg("NewtonCG/compare");
    let run = |objective: &mut dyn Objective<f64>| {
        let mut theta = [2.0, -1.5];
        let mut per_iteration = Vec::new();
        let mut last = 0;
        optimise(
            preset.method(&h),
            preset.schedule(&h),
            Budget::iterations(6),
            Sampling::of(&h, 7),
            &mut theta,
            &mut DynObjective(objective),
            |report, _| {
                per_iteration.push(report.evaluations - last);
                last = report.evaluations;
            },
        );
        per_iteration
    };
    let mut plain = quadratic as fn(&[f64]) -> f64;
    let deterministic = run(&mut plain);
    let stochastic = run(&mut Stochastic);
    assert_eq!(deterministic[0], 4, "{deterministic:?}");
    assert!(
        deterministic[1..].iter().all(|&e| e == 3),
        "{deterministic:?}"
    );
    assert!(stochastic.iter().all(|&e| e == 4), "{stochastic:?}");
}

/// Forwards to a `dyn Objective`, so one helper runs both kinds.
struct DynObjective<'a>(&'a mut dyn Objective<f64>);

impl Objective<f64> for DynObjective<'_> {
    fn evaluate(&mut self, x: &[f64], seed: NoiseSeed) -> f64 {
        self.0.evaluate(x, seed)
    }
    fn deterministic(&self) -> bool {
        self.0.deterministic()
    }
}

/// FR22's one-pair estimate points along sign(t), not t: the pair's second difference
/// says nothing about the curvature along it, so NewtonCG-FR keeps its HVP (2 + 2
/// evaluations per iteration in two dimensions) and still descends.
#[test]
fn fr22_in_two_dimensions_keeps_its_hvp() {
    let h = hyper();
    let preset = newton_cg("NewtonCG/fr22");
    let mut theta = [2.0, -1.5];
    let mut last = 0;
    optimise(
        preset.method(&h),
        preset.schedule(&h),
        Budget::iterations(5),
        Sampling::of(&h, 3),
        &mut theta,
        &mut quadratic,
        |report, _| {
            assert_eq!(report.evaluations - last, 4);
            last = report.evaluations;
        },
    );
    assert!(quadratic(&theta) < quadratic(&[2.0, -1.5]));
}
