//! MUG converges with OurHVPA (NCG + aggregate gradient + aggregate HVP) from plateau
//! starts, for a stated fraction of fixed seeds. (SHADOW does not, from the DESIGN's
//! starts: see BENCHMARKS.md, section "hodr-host path tracer".)
//!
//! The objectives are the tasks' own scenes at a reduced resolution and sample count, so
//! that the suite stays fast in debug builds; the hyper-parameters are the paper's
//! (DESIGN §3) with the iteration budgets stated per test.

use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::{Budget, Method, NegativeCurvature, Optimiser};
use hodr_core::{Estimator, Workspace};
use hodr_host::tasks::{self, Task3d, TaskObjective, TaskSettings};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// Starting and final parameter error of one run of `method` (σ schedule of `h`).
fn run(
    task: &dyn Task3d,
    settings: TaskSettings,
    method: Method<f64>,
    h: &Hyper<f64>,
    iterations: usize,
    seed: u64,
) -> (f64, f64) {
    let n = task.dimension();
    let mut theta = task.start(seed);
    let start_error = task.parameter_error(&theta);
    let mut objective = TaskObjective::with_settings(task, settings).unwrap();
    let mut buffer = vec![0.0; method.buffer_len(n)];
    let estimator = Estimator::new(
        h.sigma_start,
        h.pairs,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )
    .unwrap();
    let mut opt = Optimiser::new(
        method,
        Preset::OurHvpa.schedule(h),
        Budget::iterations(iterations),
        estimator,
        &mut theta,
        &mut buffer,
    )
    .unwrap();
    let (mut wb, mut seeds) = (vec![0.0; Workspace::<f64>::buffer_len(n, 64)], vec![0; 64]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds).unwrap();
    opt.run(
        &mut objective,
        &mut ws,
        || 0.0,
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
    )
    .unwrap();
    (start_error, task.parameter_error(opt.theta()))
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
/// 3.6–5.9 units (0.7–1.2 rad) below 0.25 units (0.05 rad) for 4 of the 20 fixed seeds
/// 0–19 (measured: seeds 0, 8, 11, 16). The others end on the plateau or beyond it: early on the trust
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
        sigma_end: 0.01,
        trust_radius: 4.0,
        line_search_iterations: 1,
        line_search_tolerance: 1e-3,
        recompute: 5,
        learning_rate: 0.05,
        common_random_numbers: true,
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

/// SHADOW explore.
#[test]
#[ignore]
fn shadow_explore() {
    let task = tasks::by_name("SHADOW").unwrap();
    let env = |k: &str, d: f64| std::env::var(k).map(|v| v.parse().unwrap()).unwrap_or(d);
    let h = Hyper {
        pairs: env("PAIRS", 1.0) as usize,
        sigma_start: 0.5,
        sigma_end: 0.01,
        trust_radius: 3.0,
        line_search_iterations: env("LS", 10.0) as usize,
        line_search_tolerance: 1e-3,
        recompute: 5,
        learning_rate: 0.1,
        common_random_numbers: env("CRN", 1.0) > 0.5,
    };
    let preset = Preset::from_name(&std::env::var("PRESET").unwrap_or("OurHVPA".into())).unwrap();
    let mut method = preset.method(&h);
    if env("FALLBACK", 0.0) > 0.5 {
        match &mut method {
            Method::Ncg(m) => m.negative_curvature = NegativeCurvature::Fallback,
            Method::NewtonCg(m) => m.negative_curvature = NegativeCurvature::Fallback,
            _ => {}
        }
    }
    let w = env("W", 32.0) as u32;
    let spp = env("SPP", 4.0) as u32;
    let iters = env("IT", 40.0) as usize;
    let seeds = env("SEEDS", 10.0) as u64;
    let t0 = std::time::Instant::now();
    let wins = (0..seeds)
        .filter(|&seed| {
            let (e0, e1) = run(task.as_ref(), small(w, spp, 64), method, &h, iters, seed);
            eprintln!("SHADOW seed {seed}: error {e0:.3} → {e1:.4}");
            e1 < 0.05
        })
        .count();
    eprintln!(
        "{} wins {wins}/{seeds} in {:?}",
        preset.name(),
        t0.elapsed()
    );
}
