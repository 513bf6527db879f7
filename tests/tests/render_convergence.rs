//! MUG converges with OurHVPA (NCG + aggregate gradient + aggregate HVP) from plateau
//! starts, and SHADOW with OurHVPA's estimators and the two-sided negative-curvature step
//! from the design's starts (docs/design.md §3), each for a stated fraction of fixed seeds (docs/notes/2026-11-23-benchmarks-before-auto.md,
//! section "Convergence of OurHVPA from plateau starts").
//!
//! The objectives are the tasks' own scenes at a reduced resolution and sample count, so
//! that the suite stays fast in debug builds; the hyper-parameters are the paper's
//! (docs/design.md §3) with the iteration budgets stated per test.

mod common;

use common::{Sampling, optimise};
use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::{Budget, Method, NegativeCurvature};
use hodr_host::tasks::{self, Task3d, TaskObjective, TaskSettings};

/// Starting and final parameter error of one run of `method` (σ schedule of `h`).
fn run(
    task: &dyn Task3d,
    settings: TaskSettings,
    method: Method<f64>,
    h: &Hyper<f64>,
    iterations: usize,
    seed: u64,
) -> (f64, f64) {
    let mut theta = task.start(seed);
    let start_error = task.parameter_error(&theta);
    let mut objective = TaskObjective::with_settings(task, settings).unwrap();
    optimise(
        method,
        Preset::OurHvpa.schedule(h),
        Budget::iterations(iterations),
        Sampling::of(h, seed),
        &mut theta,
        &mut objective,
        |r, t| {
            if std::env::var("DBG").is_ok() {
                eprintln!(
                    "{} seed {seed} it{} σ={:.3} g={:.3e} θ={:?} err={:.4}",
                    task.name(),
                    r.iteration,
                    r.sigma,
                    r.gradient_norm,
                    t,
                    task.parameter_error(t)
                );
            }
        },
    );
    (start_error, task.parameter_error(&theta))
}

fn small(width: u32, spp: u32, target_spp: u32) -> TaskSettings {
    TaskSettings {
        objective_resolution: (width, width),
        objective_spp: spp,
        target_spp,
        image_resolution: (width, width),
    }
}

/// MUG from its plateau starts (rotation π/2 ± 0.25 rad: the handle hides behind the
/// body, where the loss is flat): OurHVPA with the paper's MUG settings (1 pair,
/// σ 3 → 0.01, trust region 4σ, 1 line-search step, restart every 5) and common random
/// numbers, 40 iterations on a 32×32, 4-spp objective, brings the angular error from
/// 3.6–5.9 units (0.7–1.2 rad) below 0.25 units (0.05 rad) for 7 of the 20 fixed seeds
/// 0–19 (measured with the default `PaddedSobol` sequence: seeds 2, 3, 5, 10, 13, 16, 18;
/// 4 of 20 with the earlier `PaddedR2`). The others end on the plateau or beyond it: early on the trust
/// region (4σ = 12 units) lets single noisy steps jump across the narrow basin of θ*.
/// The runs are deterministic, so this pins the measured fraction; it is low, and a
/// finding about the optimiser settings rather than a target.
///
/// About 9 s: the workspace builds hodr-host with opt-level 3 even in debug profiles.
#[test]
fn mug_converges_from_plateau_starts() {
    let task = tasks::by_name("MUG").unwrap();
    let h = Hyper {
        pairs: 1,
        sigma_start: 3.0,
        trust_radius: 4.0,
        line_search_iterations: 1,
        recompute: 5,
        learning_rate: 0.05,
        common_random_numbers: true,
        ..Hyper::default()
    };
    let wins = (0..20)
        .filter(|&seed| {
            let method = Preset::OurHvpa.method(&h);
            let (e0, e1) = run(task.as_ref(), small(32, 4, 64), method, &h, 40, seed);
            eprintln!("MUG seed {seed}: error {e0:.3} → {e1:.4}");
            e1 < 0.25
        })
        .count();
    assert!(wins >= 4, "MUG: {wins}/20 seeds converged");
}

/// SHADOW's paper hyper-parameters (docs/design.md §3) with `pairs` pairs, `ls` line-search steps
/// and common random numbers, and OurHVPA's NCG with `negative_curvature`.
fn shadow_method(pairs: usize, ls: usize, nc: NegativeCurvature) -> (Method<f64>, Hyper<f64>) {
    let h = Hyper {
        pairs,
        sigma_start: 0.5,
        trust_radius: 3.0,
        line_search_iterations: ls,
        recompute: 5,
        common_random_numbers: true,
        negative_curvature: nc,
        ..Hyper::default()
    };
    (Preset::OurHvpa.method(&h), h)
}

/// SHADOW from the design's starts (docs/design.md §3) ((0.55, 0.55) ± 0.1, on a mesa of the loss whose
/// smoothed Hessian is negative definite; θ* is a narrow well 1.56 away, along the
/// direction the smoothed gradient points *away* from): NCG with the aggregate gradient
/// and CRN HVP (OurHVPA's estimators), σ 0.5 → 0.01, trust region 3σ, and the two-sided
/// negative-curvature step, 16 pairs, 3 line-search steps, 20 iterations on a 24×24,
/// 2-spp objective, ends within 0.05 of θ* for 3 of the 8 fixed seeds 0–7 (measured:
/// seeds 3, 5, 7; over seeds 0–19, 4 of 20 with either padded sequence, `PaddedSobol` or
/// `PaddedR2`). With the gradient-like fallback instead (the presets'), 0 of 8;
/// with 1 pair (the paper's), 0 of 8 either way: the one-pair gradient's direction is
/// nearly random at the start, and the two-sided step needs d near the diagonal.
///
/// About 16 s.
#[test]
fn shadow_converges_with_two_sided_negative_curvature_steps() {
    let task = tasks::by_name("SHADOW").unwrap();
    let (method, h) = shadow_method(16, 3, NegativeCurvature::TwoSided);
    let wins = (0..8)
        .filter(|&seed| {
            let (e0, e1) = run(task.as_ref(), small(24, 2, 64), method, &h, 20, seed);
            eprintln!("SHADOW seed {seed}: error {e0:.3} → {e1:.4}");
            e1 < 0.05
        })
        .count();
    assert!(wins >= 3, "SHADOW: {wins}/8 seeds converged");
}

/// SHADOW sweep for docs/notes/2026-11-23-benchmarks-before-auto.md (ignored): OurHVPA's NCG on SHADOW with the settings
/// read from the environment — PAIRS (16), LS line-search steps (3), IT iterations (20),
/// W resolution (24), SPP (2), SEEDS (8), FALLBACK=1 for the presets' fallback step
/// instead of the two-sided one. E.g.
/// `FALLBACK=1 cargo test -p hodr-tests --test render_convergence shadow_sweep -- --ignored --nocapture`.
#[test]
#[ignore]
fn shadow_sweep() {
    let task = tasks::by_name("SHADOW").unwrap();
    let env = |k: &str, d: usize| std::env::var(k).map_or(d, |v| v.parse().unwrap());
    let nc = if env("FALLBACK", 0) == 1 {
        NegativeCurvature::Fallback
    } else {
        NegativeCurvature::TwoSided
    };
    let (method, h) = shadow_method(env("PAIRS", 16), env("LS", 3), nc);
    let settings = small(env("W", 24) as u32, env("SPP", 2) as u32, 64);
    let seeds = env("SEEDS", 8) as u64;
    let wins = (0..seeds)
        .filter(|&seed| {
            let (e0, e1) = run(task.as_ref(), settings, method, &h, env("IT", 20), seed);
            eprintln!("SHADOW seed {seed}: error {e0:.3} → {e1:.4}");
            e1 < 0.05
        })
        .count();
    eprintln!("SHADOW {nc:?}: {wins}/{seeds} seeds converged");
}
