//! Every preset on QUAD, f = 5x₀² + 5x₁² + 7.5x₀x₁ (docs/design.md §3), with the paper's
//! hyper-parameters (with common random numbers for the central-difference HVPs): quick
//! convergence checks from both start distributions, as fractions of 10 fixed seeds.

mod common;
use common::newton_cg;

use common::{Sampling, optimise};
use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::recipe::SigmaControl;
use hodr_core::optim::{Budget, StepReport};
use hodr_host::report::task::{quad, quad_hyper};

fn hyper() -> Hyper<f64> {
    Hyper {
        common_random_numbers: true,
        ..quad_hyper()
    }
}

/// Final distance to the optimum (0, 0) after `iterations` from `start`.
fn run(preset: Preset, start: [f64; 2], iterations: usize, seed: u64) -> f64 {
    run_observed(preset, start, iterations, seed, |_| {})
}

/// [`run`], calling `observe` with every iteration's report.
fn run_observed(
    preset: Preset,
    start: [f64; 2],
    iterations: usize,
    seed: u64,
    mut observe: impl FnMut(&StepReport<f64>),
) -> f64 {
    let h = hyper();
    let mut theta = start;
    optimise(
        preset.method(&h),
        preset.schedule(&h),
        Budget::iterations(iterations),
        Sampling::of(&h, seed),
        &mut theta,
        &mut quad,
        |r, t| {
            observe(r);
            if std::env::var("DBG").is_ok() {
                eprintln!(
                    "{} it{} σ={:.3} g={:.3e} step={:.3e} curv={:?} fb={} rs={} θ={:?}",
                    preset,
                    r.iteration,
                    r.sigma,
                    r.gradient_norm,
                    r.step_length,
                    r.curvature,
                    r.fallback,
                    r.restarted,
                    t
                )
            }
        },
    );
    (theta[0] * theta[0] + theta[1] * theta[1]).sqrt()
}

/// Seeds out of 10 whose final distance is below `fraction` × the start distance.
fn successes(preset: Preset, start: [f64; 2], iterations: usize, fraction: f64) -> usize {
    let d0 = (start[0] * start[0] + start[1] * start[1]).sqrt();
    (0..10)
        .filter(|&seed| run(preset, start, iterations, 100 + seed) < fraction * d0)
        .count()
}

/// From a start in [−3, 3]², every preset reduces the distance to the optimum tenfold in
/// 60 iterations for most seeds; the noise-robust ones for every seed.
#[test]
fn every_preset_reduces_quad_error_from_near_starts() {
    for preset in Preset::ALL {
        let wins = successes(preset, [2.1, -1.3], 60, 0.1);
        let needed = match preset {
            Preset::OurHvpa
            | Preset::OurHvp
            | Preset::Fr22
            | Preset::OurG
            | Preset::OurH
            | Preset::NcgKernel => 10,
            // A per-element Hessian from 4 pairs per element is too noisy for a full Newton
            // step near the optimum; measured 5/10 with the eigenvalue floor.
            Preset::OurHNewton => 4,
            // Newton-CG's inner CG compounds HVP noise; measured 6/10 (aggregate, CRN) and
            // 3/10 (kernel) at 4 pairs with σ annealed over the budget.
            Preset::NewtonCg(r) if r.sigma == SigmaControl::Linear => 2,
            // σ shrinks as the run closes in, and with it the estimates' error: 10/10.
            Preset::NewtonCg(_) => 10,
            _ => 2,
        };
        assert!(wins >= needed, "{}: {wins}/10 seeds", preset);
    }
}

/// From the paper's far start, the NCG presets with common random numbers reach the
/// optimum (distance < 1 from ~1240) within 150 iterations for every seed.
#[test]
fn second_order_presets_reach_quad_optimum_from_far_starts() {
    for preset in [Preset::OurHvpa, Preset::OurHvp] {
        let wins = successes(preset, [900.0, 850.0], 150, 1.0 / 1240.0);
        assert_eq!(wins, 10, "{}", preset);
    }
}

/// The adaptive schedule follows the run: on QUAD (near start, 4 pairs) NewtonCG-AS's σ
/// reaches its floor in the first half of the run, while the linear schedule is still
/// near its start.
#[test]
fn adaptive_sigma_shrinks_ahead_of_the_linear_schedule() {
    let h = hyper();
    let iterations = 40;
    let mut sigmas = Vec::new();
    run_observed(newton_cg("NewtonCG"), [2.1, -1.3], iterations, 7, |r| {
        sigmas.push(r.sigma)
    });
    assert_eq!(sigmas[0], h.sigma_start);
    let floor = sigmas.iter().position(|&s| s == h.sigma_end);
    assert!(
        floor.is_some_and(|k| k < iterations / 2),
        "σ never reached its floor early: {sigmas:?}"
    );
}

/// An evaluation budget is not overrun by an iteration whose cost the run has seen:
/// every iteration of every preset on QUAD (budgets 60 and 500) starts only where the
/// costliest iteration before it would still end within the budget, and the run stops
/// where the next would not (the quick report's OurHVPA used 120 of 60 when the budget
/// was checked only between iterations). Only an iteration costlier than all before it
/// can overrun, by the difference.
#[test]
fn evaluation_budgets_are_kept() {
    let h = hyper();
    for preset in Preset::ALL {
        for budget in [60, 500] {
            let mut theta = [2.1, -1.3];
            let (mut used, mut costliest) = (0, 0);
            optimise(
                preset.method(&h),
                preset.schedule(&h),
                Budget::evaluations(budget),
                Sampling::of(&h, 3),
                &mut theta,
                &mut quad,
                |r, _| {
                    let name = preset;
                    assert!(used + costliest <= budget, "{name}: started at {used}");
                    costliest = costliest.max(r.evaluations - used);
                    used = r.evaluations;
                },
            );
            assert!(used + costliest > budget, "{}: stopped at {used}", preset);
        }
    }
}
