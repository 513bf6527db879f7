//! The stability suite: stiff, extreme and pathological cases. Every case must end with
//! finite parameters and either make progress or return a typed error — never NaN,
//! never a panic.

mod common;
use common::newton_cg;

use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::{Budget, Failed, Optimiser};
use hodr_core::{Error, Estimator, Objective, Real, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

fn hyper<T: Real>(sigma: f64, trust: f64) -> Hyper<T> {
    Hyper {
        sigma_start: T::from_f64(sigma),
        sigma_end: T::from_f64(sigma * 0.1),
        trust_radius: T::from_f64(trust),
        line_search_tolerance: T::from_f64(1e-12),
        recompute: 5,
        learning_rate: T::from_f64(0.1 * sigma),
        common_random_numbers: true,
        ..Hyper::default()
    }
}

/// Runs `preset` for `iterations` from `start`; returns the final θ and the result.
fn optimise<T: Real, O: Objective<T>>(
    preset: Preset,
    h: &Hyper<T>,
    objective: &mut O,
    start: &[T],
    iterations: usize,
    mut observe: impl FnMut(&[T]),
) -> (Vec<T>, Result<(), Failed>) {
    let n = start.len();
    let method = preset.method(h);
    let mut theta = start.to_vec();
    let mut buffer = vec![T::ZERO; method.buffer_len(n)];
    let est = Estimator::new(
        h.sigma_start,
        h.pairs,
        Xoshiro256PlusPlus::seed_from_u64(11),
    )
    .unwrap();
    let mut opt = Optimiser::new(
        method,
        preset.schedule(h),
        Budget::iterations(iterations),
        est,
        &mut theta,
        &mut buffer,
    )
    .unwrap();
    let (mut wb, mut seeds) = (vec![T::ZERO; method.workspace_len(n, 16)], vec![0; 16]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds).unwrap();
    let result = opt
        .run(objective, &mut ws, || T::ZERO, |_, t| observe(t))
        .map(|_| ());
    let last = opt.theta().to_vec();
    (last, result)
}

fn finite<T: Real>(x: &[T]) -> bool {
    x.iter().all(|v| v.is_finite())
}

fn dist(x: &[f64], y: &[f64]) -> f64 {
    x.iter()
        .zip(y)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// ½(x − x*)ᵀA(x − x*), A with eigenvalues log-spaced in [1, κ] on axes mixed by a
/// fixed sequence of plane rotations.
struct Stiff {
    n: usize,
    a: Vec<f64>,
    optimum: Vec<f64>,
}

impl Stiff {
    fn new(n: usize, kappa: f64) -> Self {
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            let t = if n > 1 {
                i as f64 / (n - 1) as f64
            } else {
                0.0
            };
            a[i * n + i] = kappa.powf(t);
        }
        // A ← G A Gᵀ for rotations G in planes (i, i+1), angle 0.5 rad.
        let (s, c) = (0.5f64.sin(), 0.5f64.cos());
        for i in 0..n.saturating_sub(1) {
            let j = i + 1;
            for k in 0..n {
                let (x, y) = (a[i * n + k], a[j * n + k]);
                a[i * n + k] = c * x - s * y;
                a[j * n + k] = s * x + c * y;
            }
            for k in 0..n {
                let (x, y) = (a[k * n + i], a[k * n + j]);
                a[k * n + i] = c * x - s * y;
                a[k * n + j] = s * x + c * y;
            }
        }
        let optimum = (0..n).map(|k| 0.1 * k as f64 - 0.2).collect();
        Stiff { n, a, optimum }
    }
}

impl Objective<f64> for Stiff {
    fn evaluate(&mut self, x: &[f64], _seed: u64) -> f64 {
        let n = self.n;
        let d: Vec<f64> = x.iter().zip(&self.optimum).map(|(a, b)| a - b).collect();
        (0..n)
            .map(|i| d[i] * (0..n).map(|j| self.a[i * n + j] * d[j]).sum::<f64>())
            .sum::<f64>()
            * 0.5
    }
}

/// The stiff cases: n ∈ {2, 50}, κ ∈ {1e2, 1e4, 1e6, 1e8}, each with its start at
/// distance 1 from the optimum along (1, …, 1).
fn stiff_cases() -> impl Iterator<Item = (usize, f64, Stiff, Vec<f64>)> {
    [2, 50].into_iter().flat_map(|n| {
        [1e2, 1e4, 1e6, 1e8].into_iter().map(move |kappa| {
            let f = Stiff::new(n, kappa);
            let start = f
                .optimum
                .iter()
                .map(|x| x + 1.0 / (n as f64).sqrt())
                .collect();
            (n, kappa, f, start)
        })
    })
}

/// Condition numbers 1e2…1e8 in 2 and 50 dimensions with the noise-limited presets:
/// parameters stay finite, and NewtonCG-A's error stays within ten times its start.
/// (Their isotropic estimator noise makes the attainable error grow with κ; the preset
/// that reaches 1e-6 is NewtonCG-LS, `newton_cg_ls_solves_stiff_quadratics`.)
#[test]
fn stiff_quadratics_stay_finite_and_do_not_diverge() {
    for (n, kappa, mut f, start) in stiff_cases() {
        let d0 = dist(&start, &f.optimum);
        for preset in [newton_cg("NewtonCG/linear"), Preset::OurHvpa] {
            let h = hyper::<f64>(0.5, 10.0);
            let optimum = f.optimum.clone();
            let mut worst = 0.0f64;
            let (theta, result) = optimise(preset, &h, &mut f, &start, 30, |t| {
                worst = worst.max(dist(t, &optimum))
            });
            result.unwrap();
            assert!(finite(&theta), "{} n={n} κ={kappa:e}", preset);
            let d = dist(&theta, &f.optimum);
            assert!(worst.is_finite(), "{} n={n} κ={kappa:e}", preset);
            // NCG with independent-looking noise can wander on stiff problems (measured:
            // OurHVPA at n = 50, κ = 1e4 ends 14× farther than it started); Newton-CG
            // with one sample set per iteration stays within its start's scale.
            if preset == newton_cg("NewtonCG/linear") {
                assert!(
                    d <= 10.0 * d0,
                    "{} n={n} κ={kappa:e}: {d} from {d0}",
                    preset
                );
            }
        }
    }
}

/// Iterations and evaluations NewtonCG-LS needs to bring ‖θ − θ*‖ to `target`·‖θ₀ − θ*‖
/// (`None` if not within `max_iterations`).
fn iterations_to<O: Objective<f64>>(
    objective: &mut O,
    start: &[f64],
    optimum: &[f64],
    target: f64,
    max_iterations: usize,
) -> Option<(usize, usize)> {
    let preset = newton_cg("NewtonCG/ls/linear");
    let h = hyper::<f64>(0.5, 10.0);
    let method = preset.method(&h);
    let n = start.len();
    let mut theta = start.to_vec();
    let mut buffer = vec![0.0; method.buffer_len(n)];
    let est = Estimator::new(
        h.sigma_start,
        h.pairs,
        Xoshiro256PlusPlus::seed_from_u64(11),
    )
    .unwrap();
    let mut opt = Optimiser::new(
        method,
        preset.schedule(&h),
        Budget::iterations(max_iterations),
        est,
        &mut theta,
        &mut buffer,
    )
    .unwrap();
    let (mut wb, mut seeds) = (vec![0.0; method.workspace_len(n, 16)], vec![0; 16]);
    let mut ws = Workspace::new(n, &mut wb, &mut seeds).unwrap();
    let d0 = dist(start, optimum);
    while let Some(report) = opt.step(objective, &mut ws, 0.0).unwrap() {
        assert!(finite(opt.theta()));
        if dist(opt.theta(), optimum) <= target * d0 {
            return Some((report.iteration, report.evaluations));
        }
    }
    None
}

/// Newton-CG with least-squares estimates (NewtonCG-LS) reaches 1e-6 relative parameter
/// error on every stiff quadratic, κ up to 1e8, n = 2 and 50 (f64): its gradient and HVPs
/// are exact on quadratics, so only the inner CG's truncation and rounding remain.
#[test]
fn newton_cg_ls_solves_stiff_quadratics() {
    for (n, kappa, mut f, start) in stiff_cases() {
        let optimum = f.optimum.clone();
        let reached = iterations_to(&mut f, &start, &optimum, 1e-6, 30);
        eprintln!("n = {n}, κ = {kappa:e}: (iterations, evaluations) = {reached:?}");
        assert!(reached.is_some(), "n={n} κ={kappa:e}");
    }
}

fn rosenbrock(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| 100.0 * (w[1] - w[0] * w[0]).powi(2) + (1.0 - w[0]).powi(2))
        .sum()
}

#[test]
fn rosenbrock_2_and_10_dimensions_improve() {
    for n in [2, 10] {
        let start: Vec<f64> = (0..n)
            .map(|k| if k % 2 == 0 { -1.2 } else { 1.0 })
            .collect();
        let f0 = rosenbrock(&start);
        for preset in [
            newton_cg("NewtonCG/linear"),
            Preset::OurHvpa,
            Preset::NcgKernel,
        ] {
            let h = hyper::<f64>(0.1, 5.0);
            let mut f = rosenbrock;
            let (theta, result) = optimise(preset, &h, &mut f, &start, 60, |_| {});
            result.unwrap();
            assert!(finite(&theta));
            assert!(
                rosenbrock(&theta) < f0,
                "{} n={n}: {} from {f0}",
                preset,
                rosenbrock(&theta)
            );
        }
    }
}

/// −exp(−|x|²/2): non-PSD Hessian outside the unit ball. Its smoothed version is
/// −(1+σ²)^{−n/2}·exp(−|θ|²/(2(1+σ²))); no iterate may rise above the start's smoothed
/// loss by more than the noise, and the centre is found from starts in (−3, 3)².
#[test]
fn negated_gaussian_is_descended_to_its_centre() {
    let smoothed = |t: &[f64], s: f64| {
        -(1.0 / (1.0 + s * s)) * (-(t[0] * t[0] + t[1] * t[1]) / (2.0 * (1.0 + s * s))).exp()
    };
    for start in [[2.5, -2.0], [-2.9, 0.3], [0.5, 2.8], [1.5, 1.5]] {
        for preset in [
            Preset::OurHvpa,
            newton_cg("NewtonCG/linear"),
            Preset::NcgKernel,
        ] {
            let h = hyper::<f64>(0.5, 2.0);
            let mut f = |x: &[f64]| -(-(x[0] * x[0] + x[1] * x[1]) / 2.0).exp();
            let start_loss = smoothed(&start, 0.05);
            let mut worst = f64::NEG_INFINITY;
            let (theta, result) = optimise(preset, &h, &mut f, &start, 80, |t| {
                worst = worst.max(smoothed(t, 0.05))
            });
            result.unwrap();
            assert!(finite(&theta));
            assert!(
                worst <= start_loss + 0.02,
                "{}: rose to {worst} from {start_loss}",
                preset
            );
            assert!(
                dist(&theta, &[0.0, 0.0]) < 0.1,
                "{} from {start:?}: ended at {theta:?}",
                preset
            );
        }
    }
}

/// x² − y²: unbounded below along y. The smoothed loss equals f; it must only go down.
#[test]
fn saddle_is_only_descended() {
    for preset in [
        Preset::OurHvpa,
        newton_cg("NewtonCG/linear"),
        Preset::NcgKernel,
        Preset::OurHNewton,
    ] {
        let h = hyper::<f64>(0.5, 2.0);
        let mut f = |x: &[f64]| x[0] * x[0] - x[1] * x[1];
        let start = [0.8, 0.1];
        let mut last = 0.8f64 * 0.8 - 0.01;
        let mut rises = 0.0f64;
        let (theta, result) = optimise(preset, &h, &mut f, &start, 20, |t| {
            let v = t[0] * t[0] - t[1] * t[1];
            rises = rises.max(v - last);
            last = v;
        });
        result.unwrap();
        assert!(finite(&theta));
        assert!(rises <= 0.05, "{}: loss rose by {rises}", preset);
        assert!(last < 0.63, "{}: no descent ({last})", preset);
    }
}

/// Every preset, and the Newton-CG presets also with their first curvature from a line
/// along ĝ (`Hyper::line_curvature`): (preset, line curvature).
fn variants() -> impl Iterator<Item = (Preset, bool)> {
    Preset::ALL
        .into_iter()
        .flat_map(|p| [(p, false), (p, true)])
}

/// `hyper(sigma, trust)` with the line curvature on or off.
fn hyper_with<T: Real>(sigma: f64, trust: f64, line: bool) -> Hyper<T> {
    Hyper {
        line_curvature: line,
        ..hyper(sigma, trust)
    }
}

/// A constant objective and a step 10σ away: zero gradients and curvatures must not
/// divide by zero, and the iterate stays put (within the trust radius of noise).
#[test]
fn plateaus_give_no_division_by_zero() {
    for (preset, line) in variants() {
        let h = hyper_with::<f64>(0.1, 2.0, line);
        let mut flat = |_: &[f64]| 3.0;
        let (theta, result) = optimise(preset, &h, &mut flat, &[1.0, -1.0], 10, |_| {});
        result.unwrap();
        assert_eq!(theta, [1.0, -1.0], "{} line={line}", preset);
        let mut step = |x: &[f64]| if x[0] > 2.0 { 1.0 } else { 0.0 };
        let (theta, result) = optimise(preset, &h, &mut step, &[1.0, 0.0], 10, |_| {});
        result.unwrap();
        assert!(
            finite(&theta) && dist(&theta, &[1.0, 0.0]) < 2.0,
            "{} line={line}: {theta:?}",
            preset
        );
        // Single precision too.
        let h32 = hyper_with::<f32>(0.1, 2.0, line);
        let mut flat32 = |_: &[f32]| 3.0f32;
        let (theta, result) = optimise(preset, &h32, &mut flat32, &[1.0f32, -1.0], 5, |_| {});
        result.unwrap();
        assert_eq!(theta, [1.0f32, -1.0], "{} f32 line={line}", preset);
    }
}

/// σ from 1e-12 to 1e12, parameters of magnitude 1e8, values of magnitude 1e30 and
/// 1e-30, in f64 and f32: finite parameters or a typed error.
#[test]
fn extreme_scales_give_finite_results_or_typed_errors() {
    for sigma in [1e-12, 1e-6, 1.0, 1e6, 1e12] {
        for (offset, scale) in [(0.0, 1.0), (1e8, 1.0), (0.0, 1e30), (0.0, 1e-30)] {
            for (preset, line) in variants() {
                let h = hyper_with::<f64>(sigma, 2.0, line);
                let mut f =
                    |x: &[f64]| scale * ((x[0] - offset).powi(2) + 2.0 * (x[1] - offset).powi(2));
                let start = [offset + 1.0, offset - 1.0];
                let (theta, result) = optimise(preset, &h, &mut f, &start, 5, |_| {});
                assert!(
                    finite(&theta),
                    "σ={sigma:e} offset={offset:e} scale={scale:e} {} line={line}",
                    preset
                );
                if let Err(e) = result {
                    assert!(
                        matches!(
                            e.error,
                            Error::NonFiniteEstimate { .. }
                                | Error::NonFiniteObjective { .. }
                                | Error::InvalidSigma
                        ),
                        "{e}"
                    );
                }
                let h32 = hyper_with::<f32>(sigma, 2.0, line);
                let (o32, s32) = (offset as f32, scale as f32);
                let mut f32q = |x: &[f32]| {
                    s32 * ((x[0] - o32) * (x[0] - o32) + 2.0 * (x[1] - o32) * (x[1] - o32))
                };
                let start32 = [o32 + 1.0, o32 - 1.0];
                let (theta, result) = optimise(preset, &h32, &mut f32q, &start32, 5, |_| {});
                assert!(
                    finite(&theta),
                    "f32 σ={sigma:e} offset={offset:e} scale={scale:e} {} line={line}",
                    preset
                );
                if let Err(e) = result {
                    assert!(
                        matches!(
                            e.error,
                            Error::NonFiniteEstimate { .. }
                                | Error::NonFiniteObjective { .. }
                                | Error::InvalidSigma
                        ),
                        "{e}"
                    );
                }
            }
        }
    }
}

/// An objective that returns NaN beyond x₀ > 1.5: the run stops with an error naming
/// the iteration, and the last good parameters remain available.
#[test]
fn non_finite_objective_stops_with_the_iteration_and_keeps_parameters() {
    for (preset, line) in variants() {
        let h = hyper_with::<f64>(0.3, 2.0, line);
        let mut f = |x: &[f64]| {
            if x[0] > 1.5 {
                f64::NAN
            } else {
                (x[0] - 3.0).powi(2) + x[1] * x[1]
            }
        };
        let (theta, result) = optimise(preset, &h, &mut f, &[0.0, 0.5], 200, |_| {});
        let failed = result.expect_err(&format!("{} line={line}", preset));
        assert!(failed.iteration >= 1);
        assert!(
            matches!(failed.error, Error::NonFiniteObjective { .. }),
            "{failed}"
        );
        assert!(
            finite(&theta) && theta[0] <= 1.5 + 10.0 * 0.3,
            "{} line={line}: {theta:?}",
            preset
        );
        assert!(format!("{failed}").contains(&format!("iteration {}", failed.iteration)));
    }
}

/// x⁴/4 − x²/2 + x/10 + y²: from x = 0.2, on the ridge between two wells, the gradient
/// points to the shallow well (x ≈ 0.95, f ≈ −0.15) and the curvature along it is
/// negative. With the two-sided negative-curvature step NCG and Newton-CG reach the deep
/// well (x ≈ −1.05, f ≈ −0.35). (So does OurHVPA's fallback with this seed and σ: the
/// test pins the two-sided path, not a contrast.)
#[test]
fn two_sided_negative_curvature_step_finds_the_deeper_side() {
    use hodr_core::optim::{Method, NegativeCurvature};
    for preset in [Preset::OurHvpa, newton_cg("NewtonCG/linear")] {
        {
            let nc = NegativeCurvature::TwoSided;
            let h = hyper::<f64>(0.5, 2.0);
            let mut method = preset.method(&h);
            match &mut method {
                Method::Ncg(m) => m.negative_curvature = nc,
                Method::NewtonCg(m) => m.negative_curvature = nc,
                _ => unreachable!(),
            }
            let mut f =
                |t: &[f64]| t[0].powi(4) / 4.0 - t[0] * t[0] / 2.0 + t[0] / 10.0 + t[1] * t[1];
            let mut theta = vec![0.2, 0.0];
            let mut buffer = vec![0.0; method.buffer_len(2)];
            let est = Estimator::new(
                h.sigma_start,
                h.pairs,
                Xoshiro256PlusPlus::seed_from_u64(11),
            )
            .unwrap();
            let mut opt = Optimiser::new(
                method,
                preset.schedule(&h),
                Budget::iterations(30),
                est,
                &mut theta,
                &mut buffer,
            )
            .unwrap();
            let (mut wb, mut seeds) = (vec![0.0; Workspace::<f64>::buffer_len(2, 16)], vec![0; 16]);
            let mut ws = Workspace::new(2, &mut wb, &mut seeds).unwrap();
            opt.run(&mut f, &mut ws, || 0.0, |_, _| {}).unwrap();
            let x = opt.theta()[0];
            assert!(x < -0.8, "{} {nc:?}: ended at x = {x}", preset);
        }
    }
}
