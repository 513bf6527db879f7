//! Auto, the default optimiser: the anytime property, bounds, the non-finite policy, the
//! stability cases (σ₀ from 1e-12 to 1e12, f32 and f64, stiff, flat, saddle, huge θ),
//! and convergence rates asserted as binomial lower bounds.

use hodr_core::optim::auto::FAILURE_CHECKS;
use hodr_core::optim::{
    Auto, AutoModel, AutoOptions, AutoReport, AutoStep, AutoTermination, NonFinite, unbudgeted_cap,
};
use hodr_core::{Error, Objective, Real};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// Runs Auto to its end (or `budget` evaluations) from `x0` with scale `sigma0`;
/// returns the best θ, its value and why the run ended.
fn minimise<T: Real, O: Objective<T>>(
    objective: &mut O,
    x0: &[T],
    sigma0: T,
    bounds: Option<(&[T], &[T])>,
    budget: usize,
    seed: u64,
) -> (Vec<T>, Option<T>, AutoTermination) {
    let options = AutoOptions::default().with_max_evaluations(budget).unwrap();
    minimise_with(objective, x0, sigma0, bounds, options, seed)
}

/// [`minimise`] with its first descent only ([`AutoOptions::fresh_starts`] off): for
/// what a descent does by itself, such as ending on its own.
fn descend<T: Real, O: Objective<T>>(
    objective: &mut O,
    x0: &[T],
    sigma0: T,
    budget: usize,
    seed: u64,
) -> (Vec<T>, Option<T>, AutoTermination) {
    let options = AutoOptions::default()
        .with_max_evaluations(budget)
        .unwrap()
        .with_fresh_starts(false);
    minimise_with(objective, x0, sigma0, None, options, seed)
}

fn minimise_with<T: Real, O: Objective<T>>(
    objective: &mut O,
    x0: &[T],
    sigma0: T,
    bounds: Option<(&[T], &[T])>,
    options: AutoOptions<T>,
    seed: u64,
) -> (Vec<T>, Option<T>, AutoTermination) {
    let model = AutoModel::ByDimension;
    minimise_model(objective, x0, sigma0, bounds, options, seed, model)
}

/// [`minimise_with`] with the model `model`.
fn minimise_model<T: Real, O: Objective<T>>(
    objective: &mut O,
    x0: &[T],
    sigma0: T,
    bounds: Option<(&[T], &[T])>,
    options: AutoOptions<T>,
    seed: u64,
    model: AutoModel,
) -> (Vec<T>, Option<T>, AutoTermination) {
    let mut theta = x0.to_vec();
    let mut buffer = vec![T::ZERO; Auto::<T, Xoshiro256PlusPlus>::buffer_len(x0.len())];
    let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut auto = Auto::with_model(&mut theta, sigma0, &mut buffer, rng, model)
        .unwrap()
        .with_options(options);
    if let Some((lo, hi)) = bounds {
        auto = auto.with_bounds(lo, hi).unwrap();
    }
    let end = auto.run(objective, |_, _| {}).unwrap();
    let value = auto.value();
    (auto.theta().to_vec(), value, end)
}

fn sphere(centre: f64, scale: f64) -> impl FnMut(&[f64]) -> f64 {
    move |x: &[f64]| x.iter().map(|v| ((v - centre) / scale).powi(2)).sum()
}

/// The first k evaluations of a run do not depend on its budget.
#[test]
fn the_first_evaluations_do_not_depend_on_the_budget() {
    let log = |budget: usize| {
        let mut points: Vec<Vec<f64>> = Vec::new();
        let mut f = |x: &[f64]| {
            points.push(x.to_vec());
            let r = (0..x.len() - 1)
                .map(|i| 100.0 * (x[i] * x[i] - x[i + 1]).powi(2) + (1.0 - x[i]).powi(2))
                .sum::<f64>();
            r + (x[0] * 4.0).floor() * 0.01
        };
        minimise(&mut f, &[-1.0, 1.5, 0.5], 0.5, None, budget, 3);
        points
    };
    let short = log(60);
    let long = log(600);
    assert_eq!(short.len(), 60, "the budget is never exceeded");
    assert!(long.len() > 60);
    assert_eq!(short[..], long[..60]);
}

/// Every evaluated point lies in the box, also when the minimum lies outside it.
#[test]
fn bounds_are_never_violated() {
    let (lo, hi) = ([-1.0, 0.5, -2.0], [1.0, 2.0, 2.0]);
    let mut outside = 0;
    let mut f = |x: &[f64]| {
        if x.iter().zip(&lo).zip(&hi).any(|((v, l), h)| v < l || v > h) {
            outside += 1;
        }
        // Minimum at (3, −3, 0): outside in the first two coordinates.
        (x[0] - 3.0).powi(2) + (x[1] + 3.0).powi(2) + x[2].powi(2)
    };
    let (theta, _, _) = minimise(&mut f, &[0.0, 1.0, 1.0], 5.0, Some((&lo, &hi)), 2000, 1);
    assert_eq!(outside, 0);
    assert!(
        (theta[0] - 1.0).abs() < 1e-6 && (theta[1] - 0.5).abs() < 1e-6,
        "{theta:?}"
    );
    assert!(theta[2].abs() < 1e-4, "{theta:?}");
}

/// A pair whose halves the box folds onto one point — from a corner, θ + d and θ − d
/// mirror to the same point up to rounding — is evaluated once: no batch holds a point
/// twice on one seed, the run counts only what the objective evaluated, and the first survey (θ and
/// two pairs, each folded) costs 3 evaluations, not 5. The minimum lies beyond the
/// corner, so the whole run samples from it.
#[test]
fn a_point_folded_twice_is_evaluated_once() {
    struct Logged {
        batches: Vec<Vec<(Vec<f64>, u64)>>,
    }
    impl Objective<f64> for Logged {
        fn evaluate(&mut self, x: &[f64], _seed: u64) -> f64 {
            (x[0] - 3.0).powi(2) + (x[1] - 3.0).powi(2)
        }
        fn evaluate_batch(&mut self, batch: &hodr_core::Batch<'_, f64>, out: &mut [f64]) {
            let mut rows = Vec::new();
            for (k, v) in out.iter_mut().enumerate() {
                *v = self.evaluate(batch.point(k), batch.seed(k));
                rows.push((batch.point(k).to_vec(), batch.seed(k)));
            }
            self.batches.push(rows);
        }
        fn deterministic(&self) -> bool {
            true
        }
    }
    let (lo, hi) = ([0.0, 0.0], [1.0, 1.0]);
    for seed in 0..4 {
        let mut f = Logged {
            batches: Vec::new(),
        };
        let mut theta = vec![1.0, 1.0];
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
        let options = AutoOptions::default().with_max_evaluations(200).unwrap();
        let mut auto = Auto::new(
            &mut theta,
            0.5,
            &mut buffer,
            Xoshiro256PlusPlus::seed_from_u64(seed),
        )
        .unwrap()
        .with_options(options)
        .with_bounds(&lo, &hi)
        .unwrap();
        let mut counted = 0;
        auto.run(&mut f, |report, _| counted = report.evaluations)
            .unwrap();
        assert_eq!(auto.theta(), &[1.0, 1.0][..], "seed {seed}");
        let evaluated: usize = f.batches.iter().map(Vec::len).sum();
        assert_eq!(counted, evaluated, "seed {seed}");
        assert_eq!(f.batches[0].len(), 3, "seed {seed}: {:?}", f.batches[0]);
        // One point up to the rounding of the mirroring, on one seed.
        let same = |a: &(Vec<f64>, u64), b: &(Vec<f64>, u64)| {
            a.1 == b.1 && a.0.iter().zip(&b.0).all(|(x, y)| (x - y).abs() <= 1e-12)
        };
        for batch in &f.batches {
            for (k, row) in batch.iter().enumerate() {
                assert!(
                    !batch[..k].iter().any(|earlier| same(earlier, row)),
                    "seed {seed}: {row:?} twice in {batch:?}"
                );
            }
        }
    }
}

/// A quadratic is solved by the first model: the survey's 2n + 1 points (θ and n
/// antithetic pairs on lines through it) determine every curvature the model's
/// least-change fit needs for a round bowl, so the step after them lands on the minimum.
/// The start lies near a face of the box, where half of the survey's pairs are cut short
/// at the face to stay on their lines (a mirrored half would leave its line, and the
/// model would no longer be exact). At every n where the model is full (up to
/// `FULL_MODEL_MAX_DIM`), including n > 14 where later fits lean on their prior, the
/// first fit has none and is made exact. From n = 15 the default model first tests
/// whether f is separable (4 + 2⌈log₂ n⌉ evaluations, θ among them, which the survey
/// does not evaluate again), finds the bowl so and takes the diagonal model, whose first
/// step, its gradient held by a small ridge, lowers f a millionfold. Deterministic: holds
/// for every seed.
#[test]
fn a_round_bowl_is_solved_by_the_first_model() {
    for n in [2usize, 5, 10, 20, 30, 40] {
        let test = if n > 14 {
            3 + 2 * (usize::BITS - (n - 1).leading_zeros()) as usize
        } else {
            0
        };
        for (model, before) in [(AutoModel::Full, 0), (AutoModel::ByDimension, test)] {
            for seed in 0..20 {
                let mut evaluations = 0;
                let mut values = Vec::new();
                // Minimum 1.2 from the start, within the first trust radius σ₀√n.
                let centre: Vec<f64> = (0..n).map(|i| 1.5 + 1.2 * i as f64 / n as f64).collect();
                let mut f = |x: &[f64]| {
                    evaluations += 1;
                    let v: f64 = x.iter().zip(&centre).map(|(a, c)| (a - c) * (a - c)).sum();
                    values.push(v);
                    v
                };
                let (lo, hi) = (vec![0.0; n], vec![10.0; n]);
                let x0: Vec<f64> = centre.iter().map(|c| c - 1.2 / (n as f64).sqrt()).collect();
                let budget = before + 2 * n + 2;
                let options = AutoOptions::default().with_max_evaluations(budget).unwrap();
                let bounds = Some((&lo[..], &hi[..]));
                minimise_model(&mut f, &x0, 1.0, bounds, options, seed, model);
                assert_eq!(evaluations, budget);
                let last = values[budget - 1];
                // The diagonal model's fit holds its gradient by a small ridge (its first
                // step is not exact); the full model's first fit is.
                let exact = if before > 0 { 1e-6 } else { 1e-10 };
                assert!(
                    last < exact * values[0],
                    "n = {n}, {model:?}, seed {seed}: f {last:e} from {:e}",
                    values[0]
                );
            }
        }
    }
}

/// Runs Auto with its defaults on the bowl `offset` + ‖x‖² from x₀ = 1 (n coordinates),
/// σ₀ = 1, until it ends by itself, handing each iteration's report to `each`.
fn bowl_to_convergence(n: usize, offset: f64, seed: u64, mut each: impl FnMut(&AutoReport<f64>)) {
    let mut theta = vec![1.0; n];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        &mut buffer,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )
    .unwrap();
    let mut sphere = sphere(0.0, 1.0);
    let mut bowl = |x: &[f64]| offset + sphere(x);
    auto.run(&mut bowl, |report, _| each(report)).unwrap();
}

/// A model that puts its minimum at θ before enough points around θ validate it draws
/// the pairs it lacks in one batch, so that the next iteration is validated (σ shrinks,
/// or the model steps) rather than claiming the minimum again one pair later. On a
/// bowl run to convergence from x₀ = 1, 10 seeds per n, at most 5 % of the unvalidated
/// claims follow another: measured 6 of 226 at n = 2 (an exploring pair can land
/// beyond reach) and none of about 300 at n = 5, 10, 20 and 50, where one pair per
/// iteration repeated 54 % to 96 % of them. Deterministic: the same runs every time.
#[test]
fn a_claimed_minimum_draws_its_validation_at_once() {
    for n in [2, 5, 10, 20, 50] {
        let (mut claims, mut repeats) = (0, 0);
        for seed in 0..10 {
            let mut last_unvalidated = false;
            bowl_to_convergence(n, 0.0, seed, |report| {
                let unvalidated =
                    report.kind == AutoStep::AtModelMinimum && report.next_sigma == report.sigma;
                claims += usize::from(unvalidated);
                repeats += usize::from(unvalidated && last_unvalidated);
                last_unvalidated = unvalidated;
            });
        }
        assert!(claims > 0, "n = {n}: no claim to test");
        assert!(
            repeats * 20 <= claims,
            "n = {n}: {repeats} of {claims} unvalidated claims follow another"
        );
    }
}

/// A restart's survey is the restart's first model's geometry: on a bowl run to
/// convergence from x₀ = 1, 10 seeds per n, its restarts (at σ far above the converged
/// descent's, θ already at the minimum) fit the bowl exactly and reject no step. Measured:
/// none at n = 2 to 20. When each survey row evicted the last (the memory full of the
/// converged descent's points, all nearer θ), a restart's first fit saw one of them and
/// its model put the minimum away from θ, rejected step after step: 3 305 steps in 98
/// restarts at n = 2. Deterministic: the same runs every time.
#[test]
fn a_restart_keeps_its_survey() {
    for n in [2, 5, 10, 20] {
        let (mut restarts, mut rejected) = (0, 0);
        for seed in 0..10 {
            bowl_to_convergence(n, 0.0, seed, |report| {
                restarts += usize::from(report.next_sigma > report.sigma);
                rejected += usize::from(report.kind == AutoStep::Rejected);
            });
        }
        assert!(restarts > 0, "n = {n}: no restart to test");
        assert_eq!(
            rejected, 0,
            "n = {n}: {rejected} steps rejected, {restarts} restarts"
        );
    }
}

/// A run on a bowl with no budget (its first descent and `RESTARTS` restarts, each
/// confirming the minimum as σ halves) ends within a median of 64·(n + 1) evaluations
/// over seeds 0–4 from x₀ = 1, at n = 2, 5, 10 and 20, at f below 10⁻²⁰. Measured
/// 110–118, 294–318, 578–632 and 1 141–1 204 evaluations (38–56·(n + 1)). The fits of
/// those confirmations keep their exact prior (`EXACT`) and solve no system; a variant
/// that also shrank σ by ⅛ on an exact prior took 210–220 evaluations at n = 2, its
/// restarts alternating exact and inexact priors. Deterministic: the same runs every time.
#[test]
fn a_bowl_run_with_no_budget_ends_soon() {
    bowl_runs_end_soon(0.0, |best| best < 1e-20);
}

/// Runs [`bowl_to_convergence`] at n = 2, 5, 10 and 20, seeds 0–4, and asserts that each
/// run's best value is `solved` and that the median run takes at most 64(n + 1)
/// evaluations.
fn bowl_runs_end_soon(offset: f64, solved: impl Fn(f64) -> bool) {
    for n in [2, 5, 10, 20] {
        let mut runs = Vec::new();
        for seed in 0..5 {
            let mut evaluations = 0;
            let mut best = f64::INFINITY;
            bowl_to_convergence(n, offset, seed, |report| {
                evaluations = report.evaluations;
                best = report.value.map_or(best, |v| best.min(v));
            });
            assert!(solved(best), "n = {n}, seed {seed}: f {best:e}");
            runs.push(evaluations);
        }
        runs.sort_unstable();
        assert!(
            runs[runs.len() / 2] <= 64 * (n + 1),
            "n = {n}: runs took {runs:?} evaluations"
        );
    }
}

/// On a bowl whose minimum is away from zero, 10 + ‖x‖², f's values tie by rounding
/// once σ is a few 10⁻⁸ (16 ulps of 10 is 3.6·10⁻¹⁴), and σ never falls to the
/// tolerance: the descent ends there as converged, because the points that tie with θ
/// lie within the distance over which rounding hides the bowl's rise and the model at
/// twice that σ has just confirmed θ as its minimum (`Auto::ties_are_rounding`). Before,
/// σ went back and forth between that scale and twice it until the patience ran out,
/// 10n + 20 iterations of two evaluations, and again after each restart. Medians over
/// seeds 0–4: 100, 264, 536 and 1 069 evaluations at n = 2, 5, 10 and 20 (the largest
/// 110, 268, 546 and 1 084), where before 806, 2 591, 3 017 and 1 101 (the largest
/// 1 170, 3 387, 5 182 and 4 576); the bound is the zero-offset bowl's, 64(n + 1).
/// Deterministic: the same runs every time.
#[test]
fn a_bowl_away_from_zero_with_no_budget_ends_soon() {
    bowl_runs_end_soon(10.0, |best| best - 10.0 <= 1e-14);
}

/// BBOB's separable and rotated ellipsoids (f02, f10) pass x − x* through T_osz, whose
/// wobble is periodic in log|x − x*|: at every scale the model mispredicts a little, and
/// a restart from the best point finds a lower f a few 10⁻¹² away (10⁻¹⁹ → 10⁻²⁴ with
/// f* = 0). Such gains move the best point by less than the tolerance and earn no
/// further restart, so a run without a budget ends after its `restarts` fruitless
/// ones. Seeds 0–4 at n = 2 and 5 took medians of 414 and 848 evaluations on f02 and
/// 408 and 826 on f10 (the largest 415, 880, 412 and 874); counting every gain, seeds
/// 0–2 took medians of 890, 2 619, 975 and 1 877 (each run still below 10⁻²¹).
/// Bound: 200(n + 1), each run solved to 10⁻¹⁵.
#[test]
fn restarts_that_gain_below_the_tolerance_end_a_run_without_a_budget() {
    for id in [2, 10] {
        for n in [2, 5] {
            let mut runs = Vec::new();
            for seed in 0..5 {
                let problem = hodr_host::suite::bbob::problem(id, n, seed + 1, 1000);
                let mut theta = problem.start(seed);
                let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
                let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
                let mut auto = Auto::new(&mut theta, problem.sigma0, &mut buffer, rng).unwrap();
                let mut f = |x: &[f64]| problem.value(x);
                // A run that never ends fails the bound at this cap.
                while auto.evaluations() < 100_000 && auto.step(&mut f).unwrap().is_some() {}
                let best = auto.value().unwrap();
                assert!(best <= 1e-15, "f{id:02}, n = {n}, seed {seed}: f {best:e}");
                runs.push(auto.evaluations());
            }
            runs.sort_unstable();
            assert!(
                runs[runs.len() / 2] <= 200 * (n + 1),
                "f{id:02}, n = {n}: runs took {runs:?} evaluations"
            );
        }
    }
}

/// NaN and ∞ count as worse than any finite value by default: the run goes round them.
#[test]
fn non_finite_values_count_as_worst_by_default() {
    let mut f = |x: &[f64]| {
        if x[0] > 0.5 {
            f64::NAN
        } else if x[1] > 1.0 {
            f64::INFINITY
        } else {
            (x[0] + 1.0).powi(2) + (x[1] - 0.5).powi(2)
        }
    };
    let (theta, value, _) = minimise(&mut f, &[2.0, 3.0], 1.0, None, 2000, 2);
    assert!(theta.iter().all(|v| v.is_finite()));
    assert!(value.is_some_and(|v| v < 1e-8), "{theta:?} {value:?}");
}

/// With [`NonFinite::Error`] the first non-finite value is a typed error; θ is kept and
/// the point that failed can be read back.
#[test]
fn non_finite_values_are_an_error_when_asked() {
    let mut theta = [0.0, 0.0];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
    let options = AutoOptions::default().with_non_finite(NonFinite::Error);
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        &mut buffer,
        Xoshiro256PlusPlus::seed_from_u64(0),
    )
    .unwrap()
    .with_options(options);
    let mut f = |x: &[f64]| if x[0] > 0.1 { f64::NAN } else { x[0] * x[0] };
    let error = loop {
        match auto.step(&mut f) {
            Ok(Some(_)) => continue,
            Ok(None) => panic!("the run ended without meeting the NaN"),
            Err(e) => break e,
        }
    };
    assert!(
        matches!(error, Error::NonFiniteObjective { .. }),
        "{error:?}"
    );
    assert!(auto.theta().iter().all(|v| v.is_finite() && *v <= 0.1));
    let failed = auto.failed_point().expect("the point that failed");
    assert!(f(failed).is_nan(), "{failed:?}");
}

/// f that is +∞ outside the ball ‖x‖ < ½ in 10 dimensions (a constraint the objective
/// enforces itself) with its minimum 0.05 inside, at c = 0.45·e₁, from x₀ = 0 at
/// σ₀ = 0.3: the first survey's pairs, at σ₀√10 ≈ 0.95 from x₀, all fall outside. That
/// is no plateau: σ shrinks until samples fall inside, where it had widened to
/// [`hodr_core::optim::PLATEAU_WIDTH`]·σ₀ and sampled outside for the rest of the
/// budget. Measured: 400 of 400 seeds below 1e-8 within 5 000 evaluations (0 of 100
/// before); bound over seeds 0–19: P(X < 17 | p = 0.99, N = 20) = 4.3e-5.
#[test]
fn a_boundary_of_infinite_values_is_no_plateau() {
    let ball = |x: &[f64]| {
        if x.iter().map(|v| v * v).sum::<f64>() >= 0.25 {
            f64::INFINITY
        } else {
            (x[0] - 0.45).powi(2) + x[1..].iter().map(|v| v * v).sum::<f64>()
        }
    };
    let solved = (0..20)
        .filter(|&seed| {
            let mut f = ball;
            let (_, value, _) = minimise(&mut f, &[0.0; 10], 0.3, None, 5000, seed);
            value.is_some_and(|v| v < 1e-8)
        })
        .count();
    assert!(solved >= 17, "{solved} of 20");
}

/// Values that tie at every scale up to [`hodr_core::optim::PLATEAU_WIDTH`]·σ₀ because
/// σ₀ lies far below the scale at which f changes at all: σ₀ = 1e-12 beside an offset of
/// 1e8 in f64 (f's spacing there is 1.5e-8), and from x₀ = 0 in f32. σ widens until the
/// values differ, and the run reaches the minimum to what f resolves. Measured: 200 of
/// 200 seeds each (0 of 200 while the plateau's cap applied: the run stayed at x₀);
/// bound over seeds 0–19: P(X < 17 | p = 0.99, N = 20) = 4.3e-5.
#[test]
fn values_that_tie_at_sigma0_widen_sigma_until_they_differ() {
    let offset = |seed| {
        let mut f = |x: &[f64]| 1e8 + (x[0] - 1.0).powi(2) + 10.0 * (x[1] + 2.0).powi(2);
        let (theta, value, _) = minimise(&mut f, &[0.0, 0.0], 1e-12, None, 3000, seed);
        value.is_some_and(|v| v <= 1e8) && (theta[0] - 1.0).abs() + (theta[1] + 2.0).abs() < 1e-3
    };
    let single = |seed| {
        let mut f = |x: &[f32]| (x[0] - 1.0) * (x[0] - 1.0) + 10.0 * (x[1] + 2.0) * (x[1] + 2.0);
        let (_, value, _) = minimise(&mut f, &[0.0f32, 0.0], 1e-12, None, 3000, seed);
        value.is_some_and(|v| v < 1e-6)
    };
    let solved = (0..20).filter(|&seed| offset(seed)).count();
    assert!(solved >= 17, "f64 beside 1e8: {solved} of 20");
    let solved = (0..20).filter(|&seed| single(seed)).count();
    assert!(solved >= 17, "f32 from 0: {solved} of 20");
}

/// An objective that is never finite leaves θ at x₀ (nothing better was found), with no
/// value, whether the run ends by its budget or by itself.
#[test]
fn a_run_without_a_finite_value_returns_its_start() {
    for budget in [Some(50), Some(300), None] {
        let mut f = |_: &[f64]| f64::NAN;
        let mut options = AutoOptions::default();
        if let Some(b) = budget {
            options = options.with_max_evaluations(b).unwrap();
        }
        let (theta, value, _) = minimise_with(&mut f, &[1.0, 2.0], 1.0, None, options, 3);
        assert_eq!(theta, vec![1.0, 2.0], "budget {budget:?}");
        assert_eq!(value, None);
    }
}

/// A box of zero width in every coordinate leaves one point: the run evaluates it and
/// ends, converged, instead of spending its budget there.
#[test]
fn a_box_of_one_point_ends_the_run() {
    let (lower, upper) = ([0.2, 0.7], [0.2, 0.7]);
    let mut calls = 0;
    let mut f = |x: &[f64]| {
        calls += 1;
        x[0] + x[1]
    };
    let (theta, value, end) = minimise(&mut f, &[0.0, 0.0], 1.0, Some((&lower, &upper)), 500, 0);
    assert_eq!(theta, vec![0.2, 0.7]);
    assert_eq!(value, Some(0.2 + 0.7));
    assert_eq!(end, AutoTermination::Converged);
    assert!(calls <= 5, "{calls} evaluations");
}

/// `Auto::run` hands its observer the best point so far, whose value is the report's,
/// on a rugged f where the search centre often lies above it (continuation moves,
/// probes, later descents).
#[test]
fn the_observer_sees_the_best_point_with_its_value() {
    let rastrigin = |x: &[f64]| {
        x.iter()
            .map(|v| v * v - 10.0 * (2.0 * core::f64::consts::PI * v).cos() + 10.0)
            .sum::<f64>()
    };
    let mut theta = [3.3, -2.2];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
    let options = AutoOptions::default().with_max_evaluations(2000).unwrap();
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        &mut buffer,
        Xoshiro256PlusPlus::seed_from_u64(1),
    )
    .unwrap()
    .with_options(options);
    let mut f = rastrigin;
    let mut checked = 0;
    auto.run(&mut f, |report, best| {
        if let Some(v) = report.value {
            assert_eq!(rastrigin(best), v, "iteration {}", report.iteration);
            checked += 1;
        }
    })
    .unwrap();
    assert!(checked > 100);
}

/// The reports count the run's descents: 1 first, one more at each iteration that begins
/// a descent, the last report's count `Auto::descents`; a run with fresh starts off, or
/// on a noisy objective (whose values on different seeds no record can compare), makes
/// one descent whatever its budget. A 2-D sphere is solved in far fewer than 2 000
/// evaluations, so a run with fresh starts makes more than one.
#[test]
fn reports_count_the_descents() {
    let count = |fresh: bool, noisy: bool| {
        let mut theta = [1.5, -0.5];
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
        let options = AutoOptions::default()
            .with_max_evaluations(2000)
            .unwrap()
            .with_fresh_starts(fresh);
        let mut auto = Auto::new(
            &mut theta,
            1.0,
            &mut buffer,
            Xoshiro256PlusPlus::seed_from_u64(5),
        )
        .unwrap()
        .with_options(options);
        let mut descent = 1;
        let mut observe = |report: &AutoReport<f64>, _: &[f64]| {
            assert!(
                report.descent == descent || report.descent == descent + 1,
                "iteration {}: descent {} after {descent}",
                report.iteration,
                report.descent
            );
            descent = report.descent;
        };
        if noisy {
            let mut f = hodr_core::Seeded(|x: &[f64], _| x[0] * x[0] + x[1] * x[1]);
            auto.run(&mut f, &mut observe).unwrap();
        } else {
            let mut f = |x: &[f64]| x[0] * x[0] + x[1] * x[1];
            auto.run(&mut f, &mut observe).unwrap();
        }
        assert_eq!(auto.descents(), descent);
        descent
    };
    assert!(count(true, false) > 1);
    assert_eq!(count(false, false), 1);
    assert_eq!(count(true, true), 1);
}

/// Settings and inputs out of range are errors, not panics.
#[test]
fn bad_input_is_a_typed_error() {
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
    let rng = || Xoshiro256PlusPlus::seed_from_u64(0);
    let too_wide = Auto::<f64, Xoshiro256PlusPlus>::max_scale() * 2.0;
    for sigma in [0.0, -1.0, f64::NAN, f64::INFINITY, too_wide, f64::MAX] {
        let mut theta = [0.0, 0.0];
        let e = Auto::new(&mut theta, sigma, &mut buffer, rng()).unwrap_err();
        assert_eq!(e, Error::InvalidSigma);
    }
    // The widest σ₀ accepted evaluates finite points only.
    let mut theta = [1.0, 2.0];
    let sigma = Auto::<f64, Xoshiro256PlusPlus>::max_scale();
    let options = AutoOptions::default().with_max_evaluations(500).unwrap();
    let mut auto = Auto::new(&mut theta, sigma, &mut buffer, rng())
        .unwrap()
        .with_options(options);
    let mut non_finite = 0;
    let mut f = |x: &[f64]| {
        non_finite += usize::from(!x.iter().all(|v| v.is_finite()));
        x.iter().map(|v| v * v).sum::<f64>()
    };
    auto.run(&mut f, |_, _| {}).unwrap();
    assert_eq!(non_finite, 0);
    let mut theta = [0.0, f64::NAN];
    let e = Auto::new(&mut theta, 1.0, &mut buffer, rng()).unwrap_err();
    assert_eq!(e, Error::NonFiniteInput { index: 1 });
    let mut short = [0.0; 3];
    let mut theta = [0.0, 0.0];
    let e = Auto::new(&mut theta, 1.0, &mut short, rng()).unwrap_err();
    assert!(matches!(e, Error::WorkspaceTooSmall { .. }));
    let inf = f64::INFINITY;
    for (lower, upper, index) in [
        ([1.0, 0.0], [0.0, 1.0], 0),
        ([0.0, inf], [1.0, inf], 1),
        ([-inf, 0.0], [-inf, 1.0], 0),
    ] {
        let mut theta = [0.0, 0.0];
        let auto = Auto::new(&mut theta, 1.0, &mut buffer, rng()).unwrap();
        let e = auto.with_bounds(&lower, &upper).unwrap_err();
        assert_eq!(
            e,
            Error::InvalidEntry {
                name: "bounds",
                index
            },
            "{lower:?} {upper:?}"
        );
    }
    for (scales, index) in [
        ([1.0, 0.0], 1),
        ([1.0, -1.0], 1),
        ([f64::NAN, 1.0], 0),
        ([1.0, f64::INFINITY], 1),
    ] {
        let mut theta = [0.0, 0.0];
        let auto = Auto::new(&mut theta, 1.0, &mut buffer, rng()).unwrap();
        let e = auto.with_scales(&scales).unwrap_err();
        assert_eq!(
            e,
            Error::InvalidEntry {
                name: "scales",
                index
            }
        );
        assert!(e.to_string().ends_with(&format!("coordinate {index}")));
    }
    let mut theta = [0.0, 0.0];
    let auto = Auto::new(&mut theta, 1.0, &mut buffer, rng()).unwrap();
    let e = auto.with_scales(&[1.0]).unwrap_err();
    assert!(matches!(e, Error::DimensionMismatch { .. }));
    assert!(AutoOptions::<f64>::default().with_tolerance(0.0).is_err());
    assert!(AutoOptions::<f64>::default().with_patience(0).is_err());
    assert!(
        AutoOptions::<f64>::default()
            .with_max_evaluations(0)
            .is_err()
    );
}

/// The defaults are those documented on the fields.
#[test]
fn option_defaults() {
    let o = AutoOptions::<f64>::default();
    assert_eq!(o.tolerance, None);
    assert_eq!(o.patience, None);
    assert_eq!(o.restarts, None);
    assert_eq!(o.max_evaluations, None);
    assert!(o.fresh_starts);
    assert_eq!(o.non_finite, NonFinite::Worst);
}

/// σ₀ from 1e-12 to 1e12 on a problem of unit scale, in f64 and f32: finite results,
/// no increase of f, and convergence at every σ₀ — σ grows without a cap relative to σ₀
/// while steps to the trust boundary are confirmed, and shrinks past the tolerance
/// relative to σ₀ until it first finds a value below f(x₀). Likewise σ₀ = 1e-12 at a
/// start of magnitude 1e8, below what its floats resolve (raised to their resolution).
#[test]
fn extreme_scales_stay_finite_and_converge() {
    let mut shifted = sphere(1e8 + 0.5, 1.0);
    let (_, value, _) = minimise(
        &mut shifted,
        &[1e8, 1e8 + 1.0, 1e8 - 0.25],
        1e-12,
        None,
        3000,
        5,
    );
    assert!(value.unwrap() < 1e-10, "{value:?}");
    for exponent in (-12..=12).step_by(3) {
        let sigma0 = 10f64.powi(exponent);
        let mut f = sphere(0.3, 1.0);
        let start = [2.0, -1.0, 0.5];
        let f0 = f(&start);
        let (theta, value, _) = minimise(&mut f, &start, sigma0, None, 3000, 5);
        assert!(
            theta.iter().all(|v| v.is_finite()),
            "σ₀ = {sigma0:e}: {theta:?}"
        );
        let v = value.unwrap();
        assert!(v <= f0, "σ₀ = {sigma0:e}");
        assert!(v < 1e-10, "σ₀ = {sigma0:e}: f = {v:e}");
        let mut g = |x: &[f32]| x.iter().map(|v| (v - 0.3) * (v - 0.3)).sum::<f32>();
        let (theta, value, _) =
            minimise(&mut g, &[2.0f32, -1.0, 0.5], sigma0 as f32, None, 3000, 5);
        assert!(theta.iter().all(|v| v.is_finite()), "f32 σ₀ = {sigma0:e}");
        assert!(value.unwrap() < 1e-6, "f32 σ₀ = {sigma0:e}: {value:?}");
    }
}

/// Per-coordinate scales 24 decades apart, and a box side far narrower than its scale,
/// in f64 and f32: finite results and no increase of f (the scales are held within what
/// the metric can whiten).
#[test]
fn extreme_per_coordinate_scales_stay_finite() {
    for bounded in [false, true] {
        extreme_scales_run::<f64>(bounded.then_some(1e-9));
        extreme_scales_run::<f32>(bounded.then_some(1e-6));
    }
}

/// One run of [`extreme_per_coordinate_scales_stay_finite`] in precision T, the third
/// coordinate boxed to a side of `side` when given.
fn extreme_scales_run<T: Real>(side: Option<f64>) {
    let t = T::from_f64;
    let mut f = |x: &[T]| x.iter().fold(T::ZERO, |s, &v| s + (v - t(0.3)).sq());
    let start = [t(2.0), t(-1.0), t(0.5)];
    let f0 = f(&start);
    let mut theta = start;
    let mut buffer = vec![T::ZERO; Auto::<T, Xoshiro256PlusPlus>::buffer_len(3)];
    let options = AutoOptions::default().with_max_evaluations(2000).unwrap();
    let rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let mut auto = Auto::new(&mut theta, T::ONE, &mut buffer, rng)
        .unwrap()
        .with_options(options)
        .with_scales(&[t(1e-12), T::ONE, t(1e12)])
        .unwrap();
    if let Some(side) = side {
        let (lower, upper) = ([t(-5.0), t(-5.0), t(0.5)], [t(5.0), t(5.0), t(0.5 + side)]);
        auto = auto.with_bounds(&lower, &upper).unwrap();
    }
    assert!(auto.sigma().is_finite() && auto.sigma() > T::ZERO);
    auto.run(&mut f, |_, _| {}).unwrap();
    assert!(
        auto.theta().iter().all(|v| v.is_finite()),
        "{:?}",
        auto.theta()
    );
    assert!(auto.value().unwrap() <= f0);
}

/// Parameters of magnitude 1e8 (f64): the optimum is found to the precision the
/// magnitude allows, and the run ends on its own within the budget (converged, or — at
/// n = 2, where a restart's cascade of shortfalls from σ₀ to the resolution takes more
/// iterations than the patience — stagnated at the optimum).
#[test]
fn huge_parameters() {
    let c = 1e8;
    let mut f = |x: &[f64]| (x[0] - c).powi(2) + 10.0 * (x[1] + c).powi(2);
    let (theta, _, end) = descend(&mut f, &[c + 50.0, -c + 30.0], 10.0, 3000, 7);
    assert!(
        (theta[0] - c).abs() < 1e-4 && (theta[1] + c).abs() < 1e-4,
        "{theta:?}"
    );
    assert_ne!(end, AutoTermination::MaxEvaluations);
}

/// A rotated quadratic of condition 1e8 in 6 dimensions is solved to 1e-6 relative
/// parameter error.
#[test]
fn stiff_quadratic() {
    let n = 6;
    let kappa: f64 = 1e8;
    // Eigenvalues log-spaced in [1, κ] on axes mixed by plane rotations.
    let mix = |x: &[f64]| {
        let mut y = x.to_vec();
        for k in 0..n - 1 {
            let (c, s) = ((0.3 + k as f64).cos(), (0.3 + k as f64).sin());
            let (a, b) = (y[k], y[k + 1]);
            y[k] = c * a - s * b;
            y[k + 1] = s * a + c * b;
        }
        y
    };
    let mut f = |x: &[f64]| {
        let y = mix(&x.iter().map(|v| v - 1.0).collect::<Vec<_>>());
        y.iter()
            .enumerate()
            .map(|(i, v)| kappa.powf(i as f64 / (n - 1) as f64) * v * v)
            .sum::<f64>()
    };
    let (theta, _, _) = minimise(&mut f, &[0.0; 6], 1.0, None, 5000, 3);
    let err = theta.iter().map(|v| (v - 1.0).powi(2)).sum::<f64>().sqrt();
    assert!(err < 1e-6 * 6f64.sqrt(), "error {err:e}, θ = {theta:?}");
}

/// A constant function ends the descent (stagnated) with θ unchanged and finite; with
/// fresh starts, the run spends its budget and still returns x₀, the first of the points
/// that tie.
#[test]
fn flat_function_ends_the_run() {
    let mut f = |_: &[f64]| 1.0;
    let (theta, value, end) = descend(&mut f, &[0.5, -0.5], 1.0, 100_000, 0);
    assert_eq!(theta, vec![0.5, -0.5]);
    assert_eq!(value, Some(1.0));
    assert_eq!(end, AutoTermination::Stagnated);
    let (theta, value, end) = minimise(&mut f, &[0.5, -0.5], 1.0, None, 3000, 0);
    assert_eq!(theta, vec![0.5, -0.5]);
    assert_eq!(value, Some(1.0));
    assert_eq!(end, AutoTermination::MaxEvaluations);
}

/// An objective without a minimum ends the run [`AutoTermination::Diverged`] within a
/// few hundred evaluations, whatever the budget, with a finite θ and value: a slope
/// (f = Σxᵢ), where the spread grows 2⁶⁴-fold, and f = −exp(x₀) + Σxᵢ², whose values
/// outrun θ and pass −2⁻⁶⁴ of the largest float first. Before, a run without a budget on
/// the slope did not end (over 10 minutes in one coordinate) and −exp ended `Stagnated`
/// at −1.8e308. A property of every run, asserted of each. (In f32 from n = 5 the slope's
/// values at |θ| ≈ 10¹⁸ differ by rounding alone before either bound is reached: the run
/// ends as on a noisy plateau, so f32 is asserted at n = 1.)
#[test]
fn an_objective_unbounded_below_diverges() {
    fn run<T: Real>(n: usize, seed: u64, f: fn(&[T]) -> T, budget: Option<usize>) {
        let mut evaluations = 0;
        let mut counted = |x: &[T]| {
            evaluations += 1;
            f(x)
        };
        let mut options = AutoOptions::default();
        if let Some(b) = budget {
            options = options.with_max_evaluations(b).unwrap();
        }
        let x0 = vec![T::ZERO; n];
        let (theta, value, end) = minimise_with(&mut counted, &x0, T::ONE, None, options, seed);
        assert_eq!(end, AutoTermination::Diverged, "n {n}, seed {seed}");
        assert!(
            evaluations <= 200 * (n + 5),
            "n {n}, seed {seed}: {evaluations}"
        );
        assert!(theta.iter().all(|v| v.is_finite()));
        assert!(value.is_some_and(|v| v.is_finite()));
    }
    fn slope<T: Real>(x: &[T]) -> T {
        x.iter().fold(T::ZERO, |s, &v| s + v)
    }
    fn cliff(x: &[f64]) -> f64 {
        -x[0].exp() + x[1..].iter().map(|v| v * v).sum::<f64>()
    }
    for seed in 0..10 {
        for n in [1, 5, 20] {
            for budget in [None, Some(1_000_000)] {
                run::<f64>(n, seed, slope, budget);
            }
        }
        run::<f32>(1, seed, slope, None);
        for n in [1, 5] {
            run::<f64>(n, seed, cliff, None);
        }
    }
}

/// Objectives bounded below whose infimum lies at infinity along one coordinate, while
/// the others have a minimum (e^(−x₀) + Σ xᵢ², 1/(1 + x₀²) + Σ xᵢ²): each step gains, by
/// amounts that shrink too slowly for the patience, and the metric stretches along x₀ so
/// that its spread never converges. The run's values settle (the `creep` module) and,
/// without a fresh start to follow, it ends by itself, converged or stagnated, before
/// the cap that keeps this test from hanging if it did not (every seed), with f at the
/// rounding of the other coordinates' squares: below 10⁻²⁸ for e^(−x₀), whose samples far
/// along −x₀ overflow to ∞ (the runs end at 5·10⁻³²–2.7·10⁻³⁰ at n = 5), below 10⁻¹² for
/// the reciprocal.
#[test]
fn an_infimum_at_infinity_ends_the_run() {
    fn exponential(x: &[f64]) -> f64 {
        (-x[0]).exp() + x[1..].iter().map(|v| v * v).sum::<f64>()
    }
    fn reciprocal(x: &[f64]) -> f64 {
        1.0 / (1.0 + x[0] * x[0]) + x[1..].iter().map(|v| v * v).sum::<f64>()
    }
    for (f, floor) in [
        (exponential as fn(&[f64]) -> f64, 1e-28),
        (reciprocal, 1e-12),
    ] {
        for seed in 0..5 {
            for n in [2, 5] {
                let mut x0 = vec![1.0; n];
                x0[0] = 0.0;
                let mut f = f;
                let (theta, value, end) = descend(&mut f, &x0, 1.0, 5_000_000, seed);
                assert!(
                    matches!(end, AutoTermination::Converged | AutoTermination::Stagnated),
                    "n {n}, seed {seed}: {end:?}"
                );
                assert!(theta.iter().all(|v| v.is_finite()));
                assert!(
                    value.is_some_and(|v| v.is_finite() && v < floor),
                    "n {n}, seed {seed}: {value:?}"
                );
            }
        }
    }
}

/// A run without a budget ends by the evaluation cap ([`unbudgeted_cap`]) where nothing
/// else ends it: an infimum approached too slowly for the settled values, 1/(1 + |x₀|) +
/// (x₁ − 1)², whose metric cannot stretch along x₀ past its condition cap, so that θ
/// walks there at a pace that shrinks while the gains stay far above ε of the fall. It
/// ends within one iteration past the cap, below 10⁻⁶ (every seed).
#[test]
fn a_run_without_a_budget_ends_by_its_cap() {
    let cap = unbudgeted_cap(2);
    for seed in 0..5 {
        let mut count = 0usize;
        let mut f = |x: &[f64]| {
            count += 1;
            1.0 / (1.0 + x[0].abs()) + (x[1] - 1.0).powi(2)
        };
        let options = AutoOptions::default();
        let (theta, value, end) = minimise_with(&mut f, &[0.0, 0.0], 1.0, None, options, seed);
        assert_eq!(end, AutoTermination::EvaluationCap, "seed {seed}");
        assert!((cap..cap + 1000).contains(&count), "seed {seed}: {count}");
        assert!(theta.iter().all(|v| v.is_finite()));
        assert!(value.is_some_and(|v| v < 1e-6), "seed {seed}: {value:?}");
    }
}

/// Noise the objective does not declare ends a run without a budget by its patience:
/// q + sN, N drawn afresh at every call, s = 0.01 and 0.1, n = 2 and 5, from 0 to the
/// minimum at 1. A lucky draw lower than f(θ)'s by less than the noise counted as a gain,
/// so that the patience never ran out while θ wandered within the noise; every run went
/// on to the evaluation cap (10⁷ evaluations before it). Each run now ends stagnated
/// before a fifth of the cap, within 0.5 of the minimum (its start lies √n away): every
/// one of seeds 0–19, at most 1 852 evaluations at n = 2 and 3 002 at n = 5, at most
/// 0.38 away.
#[test]
fn undeclared_noise_ends_a_run_without_a_budget() {
    for n in [2, 5] {
        for s in [0.01, 0.1] {
            for seed in 0..10 {
                let mut unit = uniforms(7_000_000 + seed);
                let mut count = 0usize;
                let mut f = |x: &[f64]| {
                    count += 1;
                    let q: f64 = x.iter().map(|v| (v - 1.0).powi(2)).sum();
                    q + s * standard_normal(unit(), unit())
                };
                let x0 = vec![0.0; n];
                let options = AutoOptions::default();
                let (theta, _, end) = minimise_with(&mut f, &x0, 1.0, None, options, seed);
                let error = theta.iter().map(|v| (v - 1.0).powi(2)).sum::<f64>().sqrt();
                assert!(
                    matches!(end, AutoTermination::Stagnated | AutoTermination::Converged),
                    "n {n}, s {s}, seed {seed}: {end:?}"
                );
                assert!(
                    count < unbudgeted_cap(n) / 5,
                    "n {n}, s {s}, seed {seed}: {count}"
                );
                assert!(error < 0.5, "n {n}, s {s}, seed {seed}: {theta:?}");
            }
        }
    }
}

/// Noise the objective does not declare that grows with f — q(x)·e^(N/2), N drawn
/// afresh at every call, q = Σᵢ (i + 1)(xᵢ − cᵢ)² at n = 10, budget 5 000 — does not
/// walk θ uphill. Model steps whose draws were lower by a sliver of their promise were
/// accepted, the noise grew with every such step, and half the runs ended above their
/// start (seeds 0–19 of a throwaway trace on another noise stream: median q 80 from
/// q(x₀) = 63, the worst 2·10⁶; this test's first seed 9 165). Every run now ends below a
/// quarter of q(x₀) (that trace's seeds 0–19: at most 3.1).
#[test]
fn noise_that_grows_with_f_does_not_walk_uphill() {
    let n = 10;
    let c: Vec<f64> = (0..n).map(|i| [0.5, -1.0, 2.0, 0.3][i % 4]).collect();
    let q = |x: &[f64]| -> f64 {
        x.iter()
            .zip(&c)
            .enumerate()
            .map(|(i, (a, b))| (i + 1) as f64 * (a - b).powi(2))
            .sum()
    };
    let x0 = vec![0.0; n];
    for seed in 0..10 {
        let mut unit = uniforms(8_000_000 + seed);
        let mut f = |x: &[f64]| q(x) * (0.5 * standard_normal(unit(), unit())).exp();
        let options = AutoOptions::default().with_max_evaluations(5_000).unwrap();
        let (theta, _, _) = minimise_with(&mut f, &x0, 1.0, None, options, seed);
        assert!(
            q(&theta) < q(&x0) / 4.0,
            "seed {seed}: q(θ) = {}",
            q(&theta)
        );
    }
}

/// Additive noise an objective does not declare — N/100 drawn afresh at every call, which
/// does not vanish at the minimum, as a Monte Carlo render's does not — on q =
/// Σᵢ (i + 1)(xᵢ − cᵢ)² at n = 4, budget 2 000. Where the memory holds too few repeated
/// draws to give the noise's scale, the fit's scatter stands in for it, since the fit's
/// residuals do not grow with f: a trial within it widens σ instead of shrinking it until
/// every comparison is a coin toss. Runs ending within 0.01 of c, seeds 0–99 of a
/// throwaway trace on this test's streams: 37 of 100, against 3 of 100 before (52 of 100
/// since flat noise keeps the steps short; the bound is the earlier rate's).
/// Bound: P(X < 3 | p = 0.37, N = 20) = 0.008.
#[test]
fn additive_noise_is_measured_by_the_fits_scatter() {
    let solved = additive_noise_runs_within(4, 2_000, 20, 0.01);
    assert!(solved >= 3, "{solved} of 20 runs ended within 0.01 of c");
}

/// Flat noise — N/100 added at every call, of one scale wherever x lies — on q = (x₀ −
/// 0.5)² + 2(x₁ + 1)² from x₀ = 0, σ₀ = 1, budget 1 000: once θ's draws show the noise
/// flat (`Auto::flat_noise`), model steps stay within 0.3·√n·σ and a trial the noise
/// could have rejected widens σ whatever it promised. Runs ending within 0.005 of c,
/// seeds 0–399 of a throwaway trace on this test's streams: 176 of 400 (p = 0.44),
/// against 117 of 400 with steps to √n·σ. Bound: P(X < 30 | p = 0.44, N = 100) = 0.0015.
#[test]
fn flat_noise_keeps_model_steps_short() {
    let solved = additive_noise_runs_within(2, 1_000, 100, 0.005);
    assert!(solved >= 30, "{solved} of 100 runs ended within 0.005 of c");
}

/// How many of `runs` runs (seeds 0, 1, …) end within `within` of c on q =
/// Σᵢ (i + 1)(xᵢ − cᵢ)², c = (0.5, −1, 2, 0.3, 0.5, …), at `n` plus N/100 drawn afresh at
/// every call from a stream seeded by 8 000 000 + the seed (the noisy_closure bench's
/// additive case), from x₀ = 0 with σ₀ = 1 and `budget` evaluations.
fn additive_noise_runs_within(n: usize, budget: usize, runs: u64, within: f64) -> usize {
    let c: Vec<f64> = (0..n).map(|i| [0.5, -1.0, 2.0, 0.3][i % 4]).collect();
    let mut solved = 0;
    for seed in 0..runs {
        let mut unit = uniforms(8_000_000 + seed);
        let mut f = |x: &[f64]| {
            let q: f64 = x
                .iter()
                .zip(&c)
                .enumerate()
                .map(|(i, (a, b))| (i + 1) as f64 * (a - b).powi(2))
                .sum();
            q + 0.01 * standard_normal(unit(), unit())
        };
        let options = AutoOptions::default().with_max_evaluations(budget).unwrap();
        let (theta, _, _) = minimise_with(&mut f, &vec![0.0; n], 1.0, None, options, seed);
        let distance = theta
            .iter()
            .zip(&c)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        if distance < within {
            solved += 1;
        }
    }
    solved
}

/// Whether each evaluation in turn fails, with probability `p`: draws from a stream of
/// their own, seeded by 7 000 000 + `seed`.
fn random_failures(p: f64, seed: u64) -> impl FnMut() -> bool {
    use rand_xoshiro::rand_core::Rng;
    let mut draws = Xoshiro256PlusPlus::seed_from_u64(7_000_000 + seed);
    move || ((draws.next_u64() >> 11) as f64 / (1u64 << 53) as f64) < p
}

/// An objective that fails at random — NaN from one evaluation in five, wherever the point
/// lies, as a renderer or simulation that sometimes crashes — costs about 1/(1 − p) of
/// the evaluations it would without failures: a failed evaluation is repeated once the
/// check has seen a repeat succeed. The ellipsoid Σ 10^(3i/(n−1))(xᵢ − 1)² at n = 5 from
/// θ₀ = 0, σ₀ = 1, failures drawn from their own stream: read as a wall, the failures
/// left 5 of 100 runs within 10⁻⁸ of f* = 0 after 150 evaluations (median 275 to
/// 10⁻⁸); with repeats, 400 of 400 (median 34, 25 without failures; a throwaway trace,
/// seeds 0–399). Bound over 20 seeds: P(X < 18 | p = 0.99, N = 20) = 0.001.
#[test]
fn random_failures_cost_little() {
    let n = 5;
    let mut solved = 0;
    for seed in 0..20u64 {
        let mut fails = random_failures(0.2, seed);
        let mut f = |x: &[f64]| {
            if fails() {
                return f64::NAN;
            }
            x.iter()
                .enumerate()
                .map(|(i, v)| 10f64.powf(3.0 * i as f64 / (n - 1) as f64) * (v - 1.0).powi(2))
                .sum()
        };
        let (_, value, _) = minimise(&mut f, &vec![0.0; n], 1.0, None, 150, seed);
        if value.is_some_and(|v| v <= 1e-8) {
            solved += 1;
        }
    }
    assert!(solved >= 18, "{solved} of 20 runs came within 1e-8 of f*");
}

/// Failures that belong to their points (a wall) are repeated [`FAILURE_CHECKS`] times
/// in a run, and then once at each doubling of the failures from the 16th after those
/// checks: the check that tells them from random failures costs no more. The bowl and
/// wall of [`a_minimum_on_a_wall_of_failures_is_reached`] (∞ beyond), each run's failed
/// evaluations at the point just evaluated counted as repeats, the others as failures; a
/// property of every run, seeds 0–9.
#[test]
fn failures_at_a_wall_are_repeated_only_to_check() {
    let n = 4;
    let half = 0.5 * (n as f64).sqrt();
    for seed in 0..10u64 {
        let mut last: Vec<f64> = Vec::new();
        let (mut repeats, mut failures) = (0, 0u32);
        let mut f = |x: &[f64]| {
            let value = if x.iter().sum::<f64>() / (n as f64).sqrt() <= half {
                x.iter().map(|v| (v - 1.0).powi(2)).sum()
            } else {
                f64::INFINITY
            };
            if value.is_infinite() {
                if x == last.as_slice() {
                    repeats += 1;
                } else {
                    failures += 1;
                }
            }
            last = x.to_vec();
            value
        };
        let mut unit = uniforms(9_000_000 + seed);
        let x0: Vec<f64> = (0..n).map(|_| 6.0 * unit() - 3.0).collect();
        minimise(&mut f, &x0, 1.0, None, 4_000, seed);
        // Rechecks at the 16th, 32nd, … failure after the checks.
        let since = failures.saturating_sub(FAILURE_CHECKS as u32);
        let rechecks = if since >= 16 { since.ilog2() - 3 } else { 0 };
        assert!(
            repeats <= FAILURE_CHECKS + rechecks as usize,
            "seed {seed}: {repeats} repeated evaluations of {failures} failures"
        );
    }
}

/// Beside a wall, an objective that also fails at random costs a repeat or two per point
/// beyond the wall, not a fixed number of repeats for every failure. f(x) = Σ(xᵢ − 1)²
/// where Σxᵢ/√n ≤ ½√n, +∞ beyond, at n = 5, its minimum f* = n/4 on the wall; every
/// evaluation also returns NaN with probability 0.1 (draws from 7 000 000 + seed); x₀ =
/// 0, σ₀ = 1. Within 1 800 evaluations, 96 of 100 runs came within 10⁻⁸ of f* (seeds
/// 0–99; 871 evaluations in the median run without failures); with three fixed repeats,
/// the median run took 1 924 (a throwaway trace of the same runs). Bound over 20 seeds,
/// for p = 0.91 (the 95 % lower confidence bound of 96 of 100): P(X < 15 | p = 0.91,
/// N = 20) = 0.01; at the fixed repeats' rate, at most 0.5, P(X ≥ 15) = 0.02.
#[test]
fn a_wall_of_an_objective_that_also_fails_at_random_costs_little() {
    let n = 5;
    let half = 0.5 * (n as f64).sqrt();
    let mut solved = 0;
    for seed in 0..20u64 {
        let mut fails = random_failures(0.1, seed);
        let mut f = |x: &[f64]| {
            if fails() {
                f64::NAN
            } else if x.iter().sum::<f64>() / (n as f64).sqrt() <= half {
                x.iter().map(|v| (v - 1.0).powi(2)).sum()
            } else {
                f64::INFINITY
            }
        };
        let (_, value, _) = minimise(&mut f, &vec![0.0; n], 1.0, None, 1_800, seed);
        if value.is_some_and(|v| v <= 0.25 * n as f64 + 1e-8) {
            solved += 1;
        }
    }
    assert!(solved >= 15, "{solved} of 20 runs came within 1e-8 of f*");
}

/// A minimum on a wall the objective enforces by failing — a constraint a user writes
/// as "return ∞ (or NaN) where the parameters are not allowed" — is reached:
/// f(x) = Σ(xᵢ − 1)² where Σxᵢ/√n ≤ ½√n, ∞ (even seeds) or NaN (odd seeds) beyond, at
/// n = 4, whose minimum f* = n/4 lies on the wall at xᵢ = ½. Fitted to the finite values
/// alone, the model put its minimum beyond the wall, and 0 of 100 runs came within 10⁻⁶
/// of f* (median 9·10⁻³ above it); with failed points fitted at a floor from the nearest
/// finite value, 100 of 100 (starts uniform in [−3, 3]⁴, budget 4 000, f = ∞ beyond the
/// wall; a throwaway trace, seeds 0–99). Bound over 20 seeds, for p = 0.95 (below the 97 %
/// that 100 of 100 bounds from below at 95 % confidence): P(X < 17 | p = 0.95, N = 20) =
/// 0.016.
#[test]
fn a_minimum_on_a_wall_of_failures_is_reached() {
    let failure = |seed: u64, _| {
        if seed.is_multiple_of(2) {
            f64::INFINITY
        } else {
            f64::NAN
        }
    };
    let solved = runs_reaching_a_minimum_on_a_wall(failure);
    assert!(solved >= 17, "{solved} of 20 runs came within 1e-6 of f*");
}

/// σ does not widen, on a rough fit's word, to a scale at which every sample of an
/// iteration failed about the same θ: the wider samples fail again, and σ went back and
/// forth between the two scales (a throwaway trace of the first unseen set's +∞ wall:
/// about 180 evaluations of one run). f(x) = ‖x − c‖² inside the ball ‖x‖ < 10, +∞
/// outside, c = 9.5·e₀ half a unit inside its wall, n = 10, σ₀ = 3, starts uniform in
/// [−3, 3]¹⁰: after an iteration whose every sample failed (no trial), at σ_f with the best value
/// v, no later iteration with the same best value widens σ by the rough rule (a
/// `Plateau` step; the values never tie) to σ_f or more — a property of every iteration,
/// asserted of seeds 0–4 (with the rule absent, seed 0 broke it within 100 evaluations).
#[test]
fn sigma_does_not_widen_where_every_sample_failed() {
    use std::cell::Cell;
    let n = 10;
    for seed in 0..5u64 {
        let finite = Cell::new(0usize);
        let mut f = |x: &[f64]| {
            if x.iter().map(|v| v * v).sum::<f64>() >= 100.0 {
                return f64::INFINITY;
            }
            finite.set(finite.get() + 1);
            x.iter()
                .enumerate()
                .map(|(i, v)| (v - if i == 0 { 9.5 } else { 0.0 }).powi(2))
                .sum()
        };
        let mut unit = uniforms(5 + seed);
        let mut theta: Vec<f64> = (0..n).map(|_| 6.0 * unit() - 3.0).collect();
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
        let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut auto = Auto::new(&mut theta, 3.0, &mut buffer, rng)
            .unwrap()
            .with_options(AutoOptions::default().with_max_evaluations(600).unwrap());
        // (σ_f, v) of the last iteration whose evaluations all failed, and the counts
        // before the iteration.
        let mut failed: Option<(f64, Option<f64>)> = None;
        let (mut evaluations, mut finite_before) = (0, 0);
        auto.run(&mut f, |report, _| {
            let spent = report.evaluations - evaluations;
            let none_finite = finite.get() == finite_before;
            if report.kind == AutoStep::Plateau && report.next_sigma > report.sigma {
                if let Some((scale, value)) = failed {
                    assert!(
                        value != report.value || report.next_sigma < scale,
                        "seed {seed}: σ widened to {} after samples at {scale} all failed",
                        report.next_sigma
                    );
                }
            }
            // Samples, not a model step's trial: no ratio.
            if spent > 0 && none_finite && report.ratio.is_none() {
                failed = Some((report.sigma, report.value));
            }
            (evaluations, finite_before) = (report.evaluations, finite.get());
        })
        .unwrap();
    }
}

/// A minimum on a wall the objective enforces with a penalty that jumps there — "return
/// a big number where the parameters are not allowed" — is reached: the bowl and wall of
/// [`a_minimum_on_a_wall_of_failures_is_reached`], with 10¹⁰ (even seeds) or the bowl
/// plus 10¹⁰ (odd seeds) beyond the wall. Fitted across the jump, the model's slope was
/// the jump's, and 0 of 100 runs of either came within 10⁻⁶ of f*; with values beyond a
/// cliff fitted as floors (`Auto::cliff`), 100 of 100 of each (starts uniform in
/// [−3, 3]⁴, budget 4 000; a throwaway trace, seeds 0–99). Bound over 20 seeds, as
/// there: P(X < 17 | p = 0.95, N = 20) = 0.016.
#[test]
fn a_minimum_on_a_penalty_step_is_reached() {
    let penalty = |seed: u64, q: f64| {
        if seed.is_multiple_of(2) {
            1e10
        } else {
            q + 1e10
        }
    };
    let solved = runs_reaching_a_minimum_on_a_wall(penalty);
    assert!(solved >= 17, "{solved} of 20 runs came within 1e-6 of f*");
}

/// A small penalty step at the minimum is a cliff too: the bowl and wall of
/// [`a_minimum_on_a_wall_of_failures_is_reached`], with the bowl plus 100 (even seeds) or
/// plus 10 (odd seeds) beyond the wall. Within the fit's reach the bowl rises by a
/// sizeable share of such a step until σ is small, so the gap is far from 9 times the
/// spreads beside it; a gap of more than once the spreads is taken where the refit with
/// floors is smooth. Before, 87 of 100 runs with 100 and 68 of 100 with 10 came within
/// 10⁻⁶ of f*; with it, 100 of 100 of each (starts uniform in [−3, 3]⁴, budget 4 000; a
/// throwaway trace, seeds 0–99). Bound over 20 seeds, as there: P(X < 17 | p = 0.95,
/// N = 20) = 0.016.
#[test]
fn a_minimum_on_a_small_penalty_step_is_reached() {
    let penalty = |seed: u64, q: f64| {
        if seed.is_multiple_of(2) {
            q + 100.0
        } else {
            q + 10.0
        }
    };
    let solved = runs_reaching_a_minimum_on_a_wall(penalty);
    assert!(solved >= 17, "{solved} of 20 runs came within 1e-6 of f*");
}

/// Of seeds 0–19, the runs that come within 10⁻⁶ of f* = n/4 on the bowl
/// q(x) = Σ(xᵢ − 1)² at n = 4 where Σxᵢ/√n ≤ ½√n, `beyond(seed, q(x))` elsewhere: a wall
/// through the bowl's interior with the minimum on it at xᵢ = ½ (starts uniform in
/// [−3, 3]⁴, budget 4 000).
fn runs_reaching_a_minimum_on_a_wall(beyond: impl Fn(u64, f64) -> f64) -> usize {
    let n = 4;
    let half = 0.5 * (n as f64).sqrt();
    let f_star = n as f64 / 4.0;
    let mut solved = 0;
    for seed in 0..20u64 {
        let mut f = |x: &[f64]| {
            let q: f64 = x.iter().map(|v| (v - 1.0).powi(2)).sum();
            if x.iter().sum::<f64>() / (n as f64).sqrt() <= half {
                q
            } else {
                beyond(seed, q)
            }
        };
        let mut unit = uniforms(9_000_000 + seed);
        let x0: Vec<f64> = (0..n).map(|_| 6.0 * unit() - 3.0).collect();
        let (_, value, _) = minimise(&mut f, &x0, 1.0, None, 4_000, seed);
        if value.is_some_and(|v| v - f_star <= 1e-6) {
            solved += 1;
        }
    }
    solved
}

/// A descent that ends on a flat piece of f returns the piece's centre
/// ([`AutoOptions::centre`]): f(x) = Σᵢ (i + 1)·round(4(xᵢ − cᵢ))², whose least piece is
/// the open box |xᵢ − cᵢ| < 1/8. Each edge is bracketed to 1/16 of its distance and
/// taken at the bracket's midpoint, so every run that reaches f = 0 returns θ within
/// 1/32 of the piece's width (1/128) of c on every axis — a property of the search,
/// asserted of every such run. Every run of seeds 0–399 reached f = 0 (with fresh
/// starts, budget 1 500), all 400 within the tolerance; bound over seeds 0–19:
/// P(X < 17 | p = 0.99, N = 20) = 4.3e-5.
#[test]
fn a_flat_minimum_is_returned_at_its_centre() {
    let centre = [0.3, -1.1, 2.05];
    let mut f = |x: &[f64]| {
        x.iter()
            .zip(&centre)
            .enumerate()
            .map(|(i, (a, c))| (i + 1) as f64 * (4.0 * (a - c)).round().powi(2))
            .sum::<f64>()
    };
    let mut solved = 0;
    for seed in 0..20 {
        let (theta, value, _) = minimise(&mut f, &[2.0, 1.0, -1.0], 1.0, None, 1500, seed);
        if value != Some(0.0) {
            continue;
        }
        solved += 1;
        for (x, c) in theta.iter().zip(&centre) {
            assert!((x - c).abs() <= 0.25 / 32.0, "seed {seed}: θ = {theta:?}");
        }
    }
    assert!(solved >= 17, "{solved} of 20 runs reached f = 0");
}

/// The centre of a flat piece is searched only along axes where the piece has two
/// edges, a face of the box being one: f(x) = round(4(x₀ − 0.9))² for x₀ > 0.9, 0
/// below, in [0, 2] × ℝ: the least piece is 0 ≤ x₀ < 1.025, centre 0.5125, and along
/// x₁, which f ignores and no bound limits, θ keeps the value its descent left it with.
/// A smooth f whose minimum is 0 never ties, so there the option changes nothing (one whose
/// minimum is not 0 ties by rounding: `a_smooth_minimum_is_not_centred`).
#[test]
fn a_flat_piece_is_centred_between_its_edges_only() {
    let mut f = |x: &[f64]| (4.0 * (x[0] - 0.9).max(0.0)).round().powi(2);
    let (lower, upper) = ([0.0, f64::NEG_INFINITY], [2.0, f64::INFINITY]);
    for seed in 0..5 {
        let run = |mut f: &mut dyn FnMut(&[f64]) -> f64, centre: bool| {
            let options = AutoOptions::default()
                .with_max_evaluations(2000)
                .unwrap()
                .with_fresh_starts(false)
                .with_centre(centre);
            minimise_with(
                &mut f,
                &[1.8, 0.7],
                0.5,
                Some((&lower, &upper)),
                options,
                seed,
            )
        };
        let (centred, value, _) = run(&mut f, true);
        let (entered, _, _) = run(&mut f, false);
        assert_eq!(value, Some(0.0), "seed {seed}");
        assert!(
            (centred[0] - 0.5125).abs() <= 1.025 / 32.0,
            "seed {seed}: {centred:?}"
        );
        assert_eq!(
            centred[1], entered[1],
            "seed {seed}: the flat direction moved"
        );
        let mut smooth = |x: &[f64]| (x[0] - 0.3).powi(2) + 10.0 * (x[1] - 0.2).powi(4);
        assert_eq!(
            run(&mut smooth, true),
            run(&mut smooth, false),
            "seed {seed}"
        );
    }
}

/// A smooth f whose least value is not 0 ties with f(θ) near its minimum, where its
/// rise falls below its resolution (f = 10 + a convex quadratic in 3-D: ties within
/// about 10⁻⁸ of the minimiser). Those ties are rounding's, not a flat piece: with or
/// without [`AutoOptions::centre`] the run spends the same evaluations and ends at the
/// same θ. (Before the rounding test, every one of these seeds searched for a centre.)
#[test]
fn a_smooth_minimum_is_not_centred() {
    let c = [0.3, -0.2, 1.7];
    for seed in 0..10 {
        let run = |centre: bool| {
            let mut evaluations = 0;
            let mut f = |x: &[f64]| {
                evaluations += 1;
                let d: Vec<f64> = x.iter().zip(&c).map(|(a, b)| a - b).collect();
                10.0 + d[0] * d[0] + 3.0 * d[1] * d[1] + 0.5 * d[2] * d[2] + d[0] * d[1]
            };
            let options = AutoOptions::default().with_centre(centre);
            let (theta, value, end) =
                minimise_with(&mut f, &[1.0, 1.0, -1.0], 1.0, None, options, seed);
            (theta, value, end, evaluations)
        };
        let (centred, uncentred) = (run(true), run(false));
        assert_eq!(centred, uncentred, "seed {seed}");
    }
}

/// The data of Osborne's first problem (Moré, Garbow and Hillstrom 1981, problem 17):
/// 33 values of a sum of two decaying exponentials at t = 0, 10, …, 320.
const OSBORNE_Y: [f64; 33] = [
    0.844, 0.908, 0.932, 0.936, 0.925, 0.908, 0.881, 0.850, 0.818, 0.784, 0.751, 0.718, 0.685,
    0.658, 0.628, 0.603, 0.580, 0.558, 0.538, 0.522, 0.506, 0.490, 0.478, 0.467, 0.457, 0.448,
    0.438, 0.431, 0.424, 0.420, 0.414, 0.411, 0.406,
];

/// Osborne 1: f(x) = Σᵢ (yᵢ − x₁ − x₂e^(−tᵢx₄) − x₃e^(−tᵢx₅))², least value 5.46489e-5.
fn osborne1(x: &[f64]) -> f64 {
    OSBORNE_Y
        .iter()
        .enumerate()
        .map(|(i, y)| {
            let t = 10.0 * i as f64;
            (y - x[0] - x[1] * (-t * x[3]).exp() - x[2] * (-t * x[4]).exp()).powi(2)
        })
        .sum()
}

/// A prior the points refute is dropped. Osborne 1 from its published start
/// (0.5, 1.5, −1, 0.01, 0.02) with σ₀ = 0.1: its rates x₄, x₅ are 0.01–0.02, and a
/// sample that makes one negative meets a wall where f grows as e^(640|x₄|) (10³⁶ among
/// the first samples). The first models are fitted to the wall; once σ has shrunk past
/// it, such a model carried as the prior missed the points by 10¹⁴ times their own
/// spread, held every later fit with it and kept C round, so that the runs crawled along
/// the valley (condition 2·10⁹) at σ ≈ 10⁻⁷. Runs stop once f(θ) is within 10⁻⁷ of the
/// least value, or at 10 000 evaluations. Measured on 400 seeds: 391 of 400 (before, 0
/// of 100; with the prior dropped only where the fit from it left a residual above the
/// values' spread, 30 of 100). Bound: P(X < 35 | p = 0.9775, N = 40) = 2.6e-4.
#[test]
fn a_prior_the_points_refute_is_dropped() {
    let solved = (0..40)
        .filter(|&seed| {
            let mut theta = [0.5, 1.5, -1.0, 0.01, 0.02];
            let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(5)];
            let options = AutoOptions::default().with_max_evaluations(10_000).unwrap();
            let mut auto = Auto::new(
                &mut theta,
                0.1,
                &mut buffer,
                Xoshiro256PlusPlus::seed_from_u64(seed),
            )
            .unwrap()
            .with_options(options);
            let mut f = |x: &[f64]| osborne1(x);
            while auto.step(&mut f).unwrap().is_some() {
                if auto.value().is_some_and(|v| v < 5.46489e-5 + 1e-7) {
                    return true;
                }
            }
            false
        })
        .count();
    assert!(solved >= 35, "Osborne 1: {solved} of 40");
}

/// Fresh starts: where a descent ends in a local minimum, the budget's remainder goes to
/// new descents about the best point and the best point of all descents is returned;
/// a run without a budget is its first descent. Rastrigin's function
/// f(x) = Σ (xᵢ² − 10 cos 2πxᵢ + 10) in 2-D from (3.3, −2.2) with σ₀ = 1 in [−5.12, 5.12]²
/// (a local minimum at every integer point), to f < 1e-8 within 3 000 evaluations.
/// Measured on 400 seeds: 400 of 400 with fresh starts and the probes before them (the
/// same at the commit of [`hodr_core::optim::auto::UNRESOLVED_FITS`] and once a smooth
/// minimum's rounding ties were no longer centred; 393 while a later
/// descent polished a worse basin to the tolerance,
/// [`hodr_core::optim::auto::HOPELESS_FITS`]; before that, 394, and 396
/// while the probes drew about the best point rather than over the box; 398 while every
/// fresh descent also began at its jump's scale, whatever the earlier ones found; 395
/// while every one began at σ₀; 354
/// without the probes — Rastrigin is a sum of one-coordinate terms, and a probe moves one
/// coordinate to its next well; 340 while 8 more restarts came before each fresh start,
/// 343 while 2), 216 of 400 with the first descent only. Bound:
/// P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
#[test]
fn fresh_starts_leave_a_local_minimum() {
    let seeds = 40;
    let mut solved = 0;
    for seed in 0..seeds {
        let (theta, value, end) = rastrigin_run(Some(3000), true, seed);
        assert_eq!(end, AutoTermination::MaxEvaluations, "seed {seed}");
        assert_eq!(
            value,
            Some(rastrigin(&theta)),
            "seed {seed}: the best point's value"
        );
        solved += usize::from(value.is_some_and(|v| v < 1e-8));
    }
    assert!(
        solved >= 38,
        "Rastrigin with fresh starts: {solved} of {seeds}"
    );
    // Without a budget the run is the first descent alone, which ends on its own.
    for seed in 0..4 {
        let unbudgeted = rastrigin_run(None, true, seed);
        assert_ne!(unbudgeted.2, AutoTermination::MaxEvaluations);
        assert_eq!(unbudgeted, rastrigin_run(Some(1_000_000), false, seed));
    }
}

fn rastrigin(x: &[f64]) -> f64 {
    x.iter()
        .map(|v| v * v - 10.0 * (2.0 * std::f64::consts::PI * v).cos() + 10.0)
        .sum()
}

/// A scale stated far narrower than the box: two wells in [−5, 5]², the deeper
/// (f = 0) about (3, 3), the other (f = 1/2) about (−3, −3), where the run starts, with
/// σ₀ = 10⁻³ and a budget of 3 000 evaluations. Every fresh start but the widest of
/// each cycle jumps by at most 16σ₀ and stays in the start's well; the widest reaches
/// across the box. Measured on seeds 0–399: 392 of 400, the same once the widest
/// probes drew over the whole box too (0 of 400 while the widest jump was 16σ₀).
/// Bound: P(X < 34 | p = 0.98, N = 40) = 1.3e-5.
#[test]
fn the_widest_fresh_start_crosses_the_box() {
    let seeds = 40;
    let solved = (0..seeds).filter(|&seed| two_wells_run(seed)).count();
    assert!(solved >= 34, "two wells: {solved} of {seeds}");
}

/// Whether the run of [`the_widest_fresh_start_crosses_the_box`] on `seed` reaches the
/// deeper well's bottom (f < 10⁻⁸).
fn two_wells_run(seed: u64) -> bool {
    let mut f = |x: &[f64]| {
        let deep = (x[0] - 3.0).powi(2) + (x[1] - 3.0).powi(2);
        let shallow = 0.5 + (x[0] + 3.0).powi(2) + (x[1] + 3.0).powi(2);
        deep.min(shallow)
    };
    narrow_scale_run(&mut f, &[-3.0, -3.0], seed)
}

/// Whether a run from `x0` in [−5, 5]ⁿ with σ₀ = 10⁻³ and a budget of 3 000
/// evaluations reaches f < 10⁻⁸: the runs of the two tests of a scale far narrower than
/// the box.
fn narrow_scale_run<O: Objective<f64>>(f: &mut O, x0: &[f64], seed: u64) -> bool {
    let (lower, upper) = (vec![-5.0; x0.len()], vec![5.0; x0.len()]);
    let (_, value, _) = minimise(f, x0, 1e-3, Some((&lower, &upper)), 3000, seed);
    value.is_some_and(|v| v < 1e-8)
}

/// The widest probes draw over the whole box: six one-coordinate double wells in
/// [−5, 5]⁶, Σᵢ min((xᵢ − 3)², 1/2 + (xᵢ + 3)²), from every coordinate in its shallow
/// well, with σ₀ = 10⁻³ and a budget of 3 000 evaluations, to f < 10⁻⁸. A jump across
/// the box puts all six in their deep wells once in 64 draws; a probe moves one or two.
/// Measured on seeds 0–399: 381 of 400 (7 of 400 while every probe drew within 32
/// start scales of the best point). Bound: P(X < 31 | p = 0.9525, N = 40) = 1.3e-5.
#[test]
fn the_widest_probes_search_the_whole_box() {
    let seeds = 40;
    let solved = (0..seeds).filter(|&seed| double_wells_run(seed)).count();
    assert!(solved >= 31, "double wells: {solved} of {seeds}");
}

/// A scale stated a thousand times too wide: Rosenbrock's function at n = 10 from 0 with
/// σ₀ = 500, to f < 10⁻⁸ within 2 500 evaluations. At σ ≫ 0.01 the function's cubic and
/// quartic terms swamp the quadratic a model fits, every trial step fails, and σ
/// shrinks by blamed shortfalls for several patience spans before the first gain; a
/// descent that counted them as stagnation restarted at σ₀ and searched down again.
/// Measured on seeds 0–399: 400 of 400 (118 of 400 while the patience counted them).
/// Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
#[test]
fn an_overstated_scale_shrinks_without_restarting() {
    let solved = rosenbrock_from_zero_solved(500.0, 2500, 40);
    assert!(solved >= 38, "Rosenbrock-10 from σ₀ = 500: {solved} of 40");
}

/// A scale stated somewhat too wide: Rosenbrock's function at n = 10 from 0 with
/// σ₀ = 0.5, to f < 10⁻⁸ within 1 200 evaluations. At that scale the cubic terms swamp
/// the slope in a fit of the points about 0, every trial step extrapolates to the
/// trust region's boundary and fails, and before the first gain each such failure
/// shrinks σ (on seed 0 the first gain comes at evaluation 85; at 192 while σ waited
/// for 66 points within reach, a determined model).
/// Measured on seeds 0–399: 390 of 400 (236 of 400 while σ waited).
/// Bound: P(X < 34 | p = 0.975, N = 40) = 5.5e-5.
#[test]
fn an_overstated_scale_shrinks_before_the_first_gain() {
    let solved = rosenbrock_from_zero_solved(0.5, 1200, 40);
    assert!(solved >= 34, "Rosenbrock-10 from σ₀ = 0.5: {solved} of 40");
}

/// An objective computed in single precision, as a GPU renderer's loss is: the sphere
/// Σ(xᵢ − 0.3)² at n = 10 with x rounded to f32 on its way in and the value rounded to f32
/// on its way out, once as it is (f* = 0: f32's grid in x is the grain) and once plus 1
/// (values within 16 f32 ulps of 1 tie), each from 0 with σ₀ = 1 and no budget. The run
/// must end its descent as converged, within 1 000 evaluations. Before Auto read f's
/// precision from its values, σ shrank into f32's rounding and widened on the ties it
/// found there: the runs went on to 2 400–169 000 evaluations, most stagnating.
/// Measured on seeds 0–199: 200 of 200 as it is (at most 432 evaluations), 193 of 200
/// plus 1 (the other seven stagnate after 14 700–25 900 evaluations).
/// Bound: P(X < 35 | p = 0.9825, N = 40) = 6.6e-5.
#[test]
fn a_single_precision_objective_converges() {
    let single = |offset: f64| {
        move |x: &[f64]| {
            let sum: f64 = x.iter().map(|&v| (f64::from(v as f32) - 0.3).powi(2)).sum();
            f64::from((sum + offset) as f32)
        }
    };
    let mut converged = 0;
    for offset in [0.0, 1.0] {
        for seed in 0..20 {
            let mut f = single(offset);
            let mut theta = vec![0.0; 10];
            let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(10)];
            let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng).unwrap();
            let end = auto.run(&mut f, |_, _| {}).unwrap();
            let within = auto.evaluations() <= 1000;
            let near = auto.value().is_some_and(|v| v - offset < 1e-6);
            converged += usize::from(end == AutoTermination::Converged && within && near);
        }
    }
    assert!(converged >= 35, "single precision: {converged} of 40");
}

/// How many of seeds 0 to `seeds` − 1 take Rosenbrock's function at n = 10, from 0 with
/// scale `sigma0`, below f = 10⁻⁸ within `budget` evaluations.
fn rosenbrock_from_zero_solved(sigma0: f64, budget: usize, seeds: u64) -> usize {
    (0..seeds)
        .filter(|&seed| {
            let (_, v, _) = minimise(&mut rosenbrock, &[0.0; 10], sigma0, None, budget, seed);
            v.is_some_and(|v| v < 1e-8)
        })
        .count()
}

/// Whether the run of [`the_widest_probes_search_the_whole_box`] on `seed` reaches
/// f < 10⁻⁸.
fn double_wells_run(seed: u64) -> bool {
    let mut f = |x: &[f64]| {
        x.iter()
            .map(|&xi| ((xi - 3.0) * (xi - 3.0)).min(0.5 + (xi + 3.0) * (xi + 3.0)))
            .sum::<f64>()
    };
    narrow_scale_run(&mut f, &[-3.0; 6], seed)
}

/// A run of [`fresh_starts_leave_a_local_minimum`].
fn rastrigin_run(
    budget: Option<usize>,
    fresh_starts: bool,
    seed: u64,
) -> (Vec<f64>, Option<f64>, AutoTermination) {
    let (lower, upper) = ([-5.12, -5.12], [5.12, 5.12]);
    let mut options = AutoOptions::default().with_fresh_starts(fresh_starts);
    if let Some(budget) = budget {
        options = options.with_max_evaluations(budget).unwrap();
    }
    let mut f = rastrigin;
    minimise_with(
        &mut f,
        &[3.3, -2.2],
        1.0,
        Some((&lower, &upper)),
        options,
        seed,
    )
}

/// Fresh descents that start at the scale of their jump (σ₀·2^(k mod 5), continuation
/// allowed): Griewank's function 1 + ‖y‖²/4000 − Πᵢ cos(yᵢ/√i), y = Q(x − 1.3) with Q a
/// random rotation ([`hodr_host::suite::random::rotation`], seed 4), in 10-D — wells
/// all over a bowl, the deepest at its bottom, none in line with the axes — from starts
/// uniform in [−3, 3]¹⁰ (stream 3 000 000 + seed), σ₀ = 3, in the box [−10, 10]¹⁰, to
/// f < 1e-6 within 20 000 evaluations. Smoothed at σ ≳ 3 the product of cosines fades
/// and the bowl remains, so a descent that begins wide and follows the smoothed model
/// down reaches the bottom; one that begins at σ₀ ends in the first well with two
/// cosines at −1. Measured on seeds 0–399: 385 of 400 (352 while a descent whose model
/// promised less than f resolves went on until its patience,
/// [`hodr_core::optim::auto::UNRESOLVED_FITS`]; 343 while a later descent polished a
/// worse basin to the tolerance; before that, 341, and 349 while every fresh descent
/// began wide, whatever earlier ones found; 205 with every descent at σ₀). Bound over
/// seeds 0–39: P(X < 34 | p = 0.9625, N = 40) = 6.5e-4, while with every descent at σ₀
/// P(X ≥ 34 | p = 0.5125, N = 40) = 8.4e-6.
#[test]
fn wide_fresh_descents_see_the_bowl_under_the_wells() {
    let n = 10;
    let q = hodr_host::suite::random::rotation(n, 4);
    let griewank = |x: &[f64]| {
        let mut sum = 0.0;
        let mut product = 1.0;
        for i in 0..n {
            let y: f64 = (0..n).map(|j| q[i * n + j] * (x[j] - 1.3)).sum();
            sum += y * y;
            product *= (y / ((i + 1) as f64).sqrt()).cos();
        }
        1.0 + sum / 4000.0 - product
    };
    let (lower, upper) = (vec![-10.0; n], vec![10.0; n]);
    let seeds = 40;
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut unit = uniforms(3_000_000 + seed);
            let x0: Vec<f64> = (0..n).map(|_| 6.0 * unit() - 3.0).collect();
            let bounds = Some((&lower[..], &upper[..]));
            reaches(griewank, &x0, 3.0, bounds, 20_000, 1e-6, seed)
        })
        .count();
    assert!(solved >= 34, "rotated Griewank: {solved} of {seeds}");
}

/// A later descent that has found a basin worse than the record ends once its close,
/// confirmed model says so ([`hodr_core::optim::auto::HOPELESS_FITS`]) instead of
/// polishing that basin to the tolerance. Two quadratic wells in 2-D, the deeper at 0
/// (f = ‖x‖²) and the shallower at (3, 3) (f = 1 + ‖x − 3‖²), f the lower of the two;
/// from (0.5, 0.5) with σ₀ = 1 the first descent ends at 0, and the fresh starts about
/// it, which jump by 1–16, land in either well. Counted: the evaluations within 10⁻² of
/// the shallow well's bottom over runs of 4 000 evaluations, seeds 0–39. Measured over
/// the ten blocks of 40 seeds in 0–399: 1 587 to 2 821 with the rule, 18 697 to 22 633
/// without it (each descent there polished the bottom down to σ ~ 10⁻⁹). Bound: 6 000.
#[test]
fn a_descent_in_a_worse_basin_ends_unpolished() {
    let f = |x: &[f64]| {
        let deep = x[0] * x[0] + x[1] * x[1];
        let shallow = 1.0 + (x[0] - 3.0).powi(2) + (x[1] - 3.0).powi(2);
        deep.min(shallow)
    };
    let mut near = 0;
    for seed in 0..40 {
        for step in record_steps(f, &[0.5, 0.5], 1.0, None, 4000, seed) {
            near += step
                .points
                .iter()
                .filter(|x| ((x[0] - 3.0).powi(2) + (x[1] - 3.0).powi(2)).sqrt() < 1e-2)
                .count();
        }
    }
    assert!(
        near <= 6000,
        "{near} evaluations within 1e-2 of the shallow well's bottom"
    );
}

/// A descent at a minimum whose value is far from zero ends once f's arithmetic no
/// longer resolves what its model promises ([`hodr_core::optim::auto::UNRESOLVED_FITS`])
/// or its samples tie with f(θ) by rounding right after the model confirmed θ
/// (`Auto::ties_are_rounding`), rather than after its patience: f(x) = 10³ +
/// Σᵢ (i + 1)(xᵢ − 1)² in 10-D, one descent (fresh starts off, its restarts included) from
/// xᵢ = 0.3 with σ₀ = 1, seeds 0–39. Measured over blocks of 40 seeds in 0–359: 15 567 to
/// 16 192 evaluations in all with both rules and θ within 6.6·10⁻⁸ to 1.26·10⁻⁷ of the
/// minimum (f's 16-ulp resolution alone would allow 1.9·10⁻⁶); 24 389 to 26 175 and
/// 6.3·10⁻⁹ with the first rule only, 103 578 to 117 403 with neither (each descent's σ
/// went back and forth between scales where the ratio test compared rounding errors).
/// Bounds: 25 000 evaluations, 5·10⁻⁷.
#[test]
fn a_minimum_far_from_zero_ends_where_f_stops_resolving() {
    let n = 10;
    let mut evaluations = 0;
    for seed in 0..40 {
        let mut f = |x: &[f64]| {
            evaluations += 1;
            let bowl = x.iter().enumerate();
            1e3 + bowl
                .map(|(i, v)| (i + 1) as f64 * (v - 1.0).powi(2))
                .sum::<f64>()
        };
        let (theta, _, _) = descend(&mut f, &vec![0.3; n], 1.0, 100_000, seed);
        let error = theta.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max);
        assert!(error <= 5e-7, "seed {seed}: θ {error:.1e} from the minimum");
    }
    assert!(evaluations <= 25_000, "{evaluations} evaluations");
}

/// Once two wide fresh descents in a row have ended on the same value, later fresh
/// descents start at σ₀: the smoothed objective leads every wide descent to one point,
/// which is then known. On a bowl with one minimum, f(x) = 1 + ‖x − 0.3‖² in 3-D, every
/// descent ends on f = 1, so the k-th fresh start's descent begins at σ₀·2^k for
/// k = 1 and 2 (the first wide descent has no other to match; the run's first descent and
/// the 0th fresh start's are at σ₀) and at σ₀ from then on, where it would otherwise
/// cycle on through 8σ₀ and 16σ₀: of the run's descents and restarts (about a hundred in
/// 20 000 evaluations), at most eight begin above 1.5σ₀, where four in five fresh starts
/// would without the rule: the two wide fresh descents and a restart of each, and now and
/// then a descent's second restart, at 2σ₀ in the restarts' own cycle (seeds 0–39: two to
/// five wide starts of about a hundred, most runs two).
#[test]
fn wide_descents_that_end_alike_stop_widening() {
    let sigma0 = 0.5;
    let mut f = |x: &[f64]| 1.0 + x.iter().map(|v| (v - 0.3) * (v - 0.3)).sum::<f64>();
    for seed in 0..4 {
        let steps = record_steps(&mut f, &[2.0, -1.0, 1.5], sigma0, None, 20_000, seed);
        // σ of each descent's first iteration (a restart's too): where σ jumps up from a
        // converged descent.
        let mut starts = Vec::new();
        let mut last = f64::INFINITY;
        for step in &steps {
            if step.sigma >= sigma0 && last < 1e-3 * sigma0 {
                starts.push(step.sigma / sigma0);
            }
            last = step.sigma;
        }
        let wide = starts.iter().filter(|&&s| s > 1.5).count();
        assert!(
            starts.len() >= 20 && wide <= 8,
            "seed {seed}: {wide} of {} descents began wide",
            starts.len()
        );
    }
}

/// The probes before a fresh start (`AutoOptions::probes`) on the suite's disc plateau
/// with four discs (n = 8, `hodr_host::suite::plateau::discs`), whose descents end with a
/// disc hidden under another or stranded in a corner while the rest sit on their
/// targets, to its exact image within the problem's budget (8 000 evaluations), from the
/// suite's starts and run seeds. Measured over seeds 0–79 of each of its five instances:
/// 287 of 400 with the probes, 77 of 400 without (a fresh start moves every disc, the
/// placed ones too; each fresh descent then begins at its jump's scale, 2–3 times as long
/// as one at σ₀ here, where once a probe has succeeded they begin at σ₀); 272 while the
/// probes drew each coordinate about the best point rather than over the box, 251 while
/// every fresh descent also began at its jump's scale, 281 and 137 while every one
/// began at σ₀. Bound over seeds 0–15: P(X < 37 | p = 0.71, N = 80) = 1e-6; a run
/// without probes would pass it with probability 4e-8.
#[test]
fn probes_free_hidden_and_stranded_discs() {
    use hodr_host::suite::{plateau, problem, random};
    let mut solved = 0;
    for instance in 1..=5 {
        let p = plateau::discs(8, instance, 1000);
        let bounds = p.bounds.as_ref().unwrap();
        for index in 0..16 {
            let seed = problem::run_seed(&p.name, index);
            let options = AutoOptions::default()
                .with_max_evaluations(p.budget)
                .unwrap();
            let (_, value, _) = minimise_with(
                &mut |x: &[f64]| p.value(x),
                &p.start(seed),
                p.sigma0,
                Some((&bounds.lower, &bounds.upper)),
                options,
                random::seed_of("auto", &[seed]),
            );
            solved += usize::from(value == Some(0.0));
        }
    }
    assert!(solved >= 37, "four discs: {solved} of 80");
}

/// Every probe moves one contiguous block of the best point's coordinates, 2^j long
/// (j ≥ 0, at most n/2) and aligned to its length, and stays in the box; the probes
/// come only between descents, after the first has ended. A moved coordinate is uniform
/// over its box (which lies within 32 start scales of every point here): each quarter
/// of the box holds a quarter of them, to 4.5 binomial standard deviations (a
/// false failure has probability below 1e-4). Draws about the best point at its start
/// scale, 1 here, would crowd the middle quarters, where Rastrigin's runs end.
#[test]
fn probes_move_one_aligned_block() {
    let n = 8;
    let (lower, upper) = ([-5.12; 8], [5.12; 8]);
    let x0 = [3.3, -2.2, 1.1, 4.0, -3.7, 0.4, 2.6, -1.3];
    let steps = record_steps(rastrigin, &x0, 1.0, Some((&lower, &upper)), 6000, 3);
    let (mut probes, mut descents_before) = (0, 0);
    let mut quarters = [0usize; 4];
    for step in &steps {
        if step.kind != AutoStep::Probed {
            descents_before += usize::from(probes == 0);
            continue;
        }
        for x in &step.points {
            probes += 1;
            assert!(x.iter().zip(&lower).all(|(v, l)| v >= l));
            assert!(x.iter().zip(&upper).all(|(v, u)| v <= u));
            let moved: Vec<usize> = (0..n).filter(|&i| x[i] != step.best[i]).collect();
            for &i in &moved {
                let quarter = (x[i] - lower[i]) / (upper[i] - lower[i]) * 4.0;
                quarters[(quarter as usize).min(3)] += 1;
            }
            let (first, last) = (moved[0], *moved.last().unwrap());
            let mut length = 1;
            while first / length != last / length {
                length *= 2;
            }
            assert!(length <= n / 2, "a probe moved {moved:?}");
        }
    }
    assert!(probes > 0 && descents_before > 0);
    let moved: usize = quarters.iter().sum();
    let (mean, sd) = (moved as f64 / 4.0, (moved as f64 * 0.25 * 0.75).sqrt());
    assert!(
        quarters
            .iter()
            .all(|&q| (q as f64 - mean).abs() <= 4.5 * sd),
        "moved coordinates per quarter of the box: {quarters:?}"
    );
}

/// A box as wide as f64's range (its width overflows to ∞) around a problem at the
/// widest scale Auto takes (σ₀ = 10²⁸⁸, under [`Auto::max_scale`]): every point is
/// finite and inside the box, σ's cap included (half the box's side), and the probes
/// spread over the box rather than piling onto a face.
#[test]
fn probes_in_a_box_wider_than_f64_are_finite() {
    let (lower, upper) = ([-1e308; 2], [1e308; 2]);
    let f = |x: &[f64]| rastrigin(&[x[0] * 1e-288, x[1] * 1e-288]);
    let steps = record_steps(
        f,
        &[3.3e288, -2.2e288],
        1e288,
        Some((&lower, &upper)),
        2000,
        5,
    );
    let points = || steps.iter().flat_map(|step| &step.points);
    let outside: Vec<_> = points()
        .filter(|x| !x.iter().all(|v| (-1e308..=1e308).contains(v)))
        .collect();
    assert!(
        outside.is_empty(),
        "{} points, first {:?}",
        outside.len(),
        outside[0]
    );
    let probed = || {
        steps
            .iter()
            .filter(|step| step.kind == AutoStep::Probed)
            .flat_map(|step| &step.points)
    };
    let probes = probed().count();
    let on_a_face = probed()
        .filter(|x| x.iter().any(|v| v.abs() == 1e308))
        .count();
    assert!(
        probes > 0 && on_a_face * 10 < probes,
        "{on_a_face} of {probes} probes on a face"
    );
}

/// One iteration of [`record_steps`]: what it did, its σ, the best point before it and
/// the points it evaluated.
struct RecordedStep {
    kind: AutoStep,
    sigma: f64,
    best: Vec<f64>,
    points: Vec<Vec<f64>>,
}

/// Auto from `theta` (its start, then its best point) at scale `sigma0`, in the box
/// `bounds` if any, with a budget of `budget` evaluations and its random numbers from
/// `seed`; `buffer` holds [`Auto::buffer_len`] floats.
fn budgeted<'a>(
    theta: &'a mut [f64],
    buffer: &'a mut [f64],
    sigma0: f64,
    bounds: Option<(&[f64], &[f64])>,
    budget: usize,
    seed: u64,
) -> Auto<'a, f64, Xoshiro256PlusPlus> {
    let auto = Auto::new(
        theta,
        sigma0,
        buffer,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )
    .unwrap()
    .with_options(AutoOptions::default().with_max_evaluations(budget).unwrap());
    match bounds {
        Some((lower, upper)) => auto.with_bounds(lower, upper).unwrap(),
        None => auto,
    }
}

/// Every iteration of a run of Auto on `f` from `x0` at scale `sigma0` (in the box
/// `bounds`, if any), to `budget` evaluations, on `seed`.
fn record_steps(
    mut f: impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    sigma0: f64,
    bounds: Option<(&[f64], &[f64])>,
    budget: usize,
    seed: u64,
) -> Vec<RecordedStep> {
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(x0.len())];
    let mut theta = x0.to_vec();
    let mut auto = budgeted(&mut theta, &mut buffer, sigma0, bounds, budget, seed);
    let mut steps = Vec::new();
    loop {
        let best = auto.theta().to_vec();
        let mut points = Vec::new();
        let mut recorded = |x: &[f64]| {
            points.push(x.to_vec());
            f(x)
        };
        let Some(report) = auto.step(&mut recorded).unwrap() else {
            break;
        };
        steps.push(RecordedStep {
            kind: report.kind,
            sigma: report.sigma,
            best,
            points,
        });
    }
    steps
}

/// A saddle: the run only ever descends (f of the best point never rises) and leaves
/// along the negative curvature.
#[test]
fn saddle_is_left_downhill() {
    let mut f = |x: &[f64]| x[0] * x[0] - x[1] * x[1] + 0.01 * x[1].powi(4);
    let (theta, value, _) = minimise(&mut f, &[0.1, 1e-9], 1.0, None, 500, 4);
    assert!(theta.iter().all(|v| v.is_finite()));
    // Minima at x₁ = ±√50, f = −25.
    assert!(value.unwrap() < -24.9, "{theta:?} {value:?}");
}

/// A plateau start: the kernel finds the well that every nearby sample misses. The
/// run widens σ rather than stopping at once.
#[test]
fn plateau_start_widens_and_finds_the_well() {
    let mut widened = false;
    let mut theta = [4.0, 4.0];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
    let mut auto = Auto::new(
        &mut theta,
        0.5,
        &mut buffer,
        Xoshiro256PlusPlus::seed_from_u64(9),
    )
    .unwrap()
    .with_options(AutoOptions::default().with_max_evaluations(2000).unwrap());
    // A bowl of radius 2 around the origin, flat (1) outside.
    let mut f = |x: &[f64]| (x[0] * x[0] + x[1] * x[1]).min(4.0) / 4.0;
    auto.run(&mut f, |r, _| widened |= r.kind == AutoStep::Plateau)
        .unwrap();
    assert!(widened);
    assert!(
        auto.value().is_some_and(|v| v < 1e-10),
        "{:?}",
        auto.theta()
    );
}

/// A stochastic objective: Σᵢ (i + 1)(θᵢ − 1)², scaled by 1 ± 2.5 % and raised by up
/// to 100 per seed, plus a grain of 0.01·Σᵢ sin(7θᵢ + φᵢ) with phases φ from the seed.
struct SeedLevel;

impl SeedLevel {
    /// A uniform number in [0, 1) from `seed` and stream `k` (SplitMix64's finaliser).
    fn unit(seed: hodr_core::NoiseSeed, k: u64) -> f64 {
        let mut z = seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

impl Objective<f64> for SeedLevel {
    fn evaluate(&mut self, x: &[f64], seed: hodr_core::NoiseSeed) -> f64 {
        let mut signal = 0.0;
        let mut grain = 0.0;
        for (i, v) in x.iter().enumerate() {
            signal += (1.0 + i as f64) * (v - 1.0).powi(2);
            grain += (7.0 * v + 6.3 * Self::unit(seed, 3 + i as u64)).sin();
        }
        signal * (1.0 + 0.05 * (Self::unit(seed, 1) - 0.5))
            + 100.0 * Self::unit(seed, 2)
            + 0.01 * grain
    }
}

/// Success rates over 40 seeds, asserted as lower bounds that a binomial variable with
/// the rate measured over 400 seeds (seeds 0–399, at the commit that last changed
/// this test) stays above with probability ≥ 0.999. "Before" figures are of the commit
/// before the memory of twice the model's coefficients.
#[test]
fn convergence_rates_hold() {
    let seeds = 40;
    // Rosenbrock in 5-D from (−1.5, …), to f < 1e-8 within 2 000 evaluations.
    // Measured: 400 of 400 (393 while 8 more restarts came before a fresh start).
    // Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let solved = runs_below_1e8(rosenbrock, &[-1.5; 5], 2000, seeds);
    assert!(solved >= 38, "Rosenbrock-5: {solved} of {seeds}");
    // An attractive sector (BBOB f06's shape): (Σ (sᵢzᵢ)²)^0.9 with z = ΛH(x − x*), H a
    // Householder reflection, Λ of condition 10, and sᵢ = 100 where zᵢ > 0: the
    // curvature jumps 10⁴-fold across every hyperplane zᵢ = 0 through x*. In 5-D from
    // (3, …), to f < 1e-8 within 4 000 evaluations. With σ halved after steps whose
    // decrease the model overstated (before 1841090), about 78 of 100; with the metric
    // learnt only from steps the model predicted, 355 of 400. Measured: 400 of 400 (400
    // before). Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let sector = |x: &[f64]| {
        rotated(x)
            .iter()
            .map(|&z| (if z > 0.0 { 100.0 * z } else { z }).powi(2))
            .sum::<f64>()
            .powf(0.9)
    };
    let solved = runs_below_1e8(sector, &[3.0; 5], 4000, seeds);
    assert!(solved >= 38, "attractive sector: {solved} of {seeds}");
    // A sharp ridge (BBOB f13's shape, a cone as an L1 loss makes): z₁² + 100‖z₂..ₙ‖ with
    // z as for the sector, in 5-D from (3, …), to f < 1e-8 within 5 000 evaluations.
    // With the metric learnt only from steps the model predicted, 104 of 400; 202 before
    // the evolution path. Measured: 400 of 400 (391 before).
    // Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let ridge = |x: &[f64]| {
        let z = rotated(x);
        z[0] * z[0] + 100.0 * z[1..].iter().map(|v| v * v).sum::<f64>().sqrt()
    };
    let solved = runs_below_1e8(ridge, &[3.0; 5], 5000, seeds);
    assert!(solved >= 38, "sharp ridge: {solved} of {seeds}");
    // A rounded 2-D quadratic (an integer plateau) to its exact minimum within 300.
    // Measured: 400 of 400 (399 before). Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut f =
                |x: &[f64]| (x[0].round() - 2.0).powi(2) + 3.0 * (x[1].round() + 1.0).powi(2);
            let (_, v, _) = minimise(&mut f, &[-4.0, 4.0], 2.0, None, 300, seed);
            v == Some(0.0)
        })
        .count();
    assert!(solved >= 38, "rounded quadratic: {solved} of {seeds}");
    // Two wells: a shallow one (f = 0.5) at the start, the deep one (f = 0) 6σ₀ away,
    // to f < 1e-8 within 1 000 evaluations; only restarts at widening σ leave the
    // first, or a fresh start after them (before fresh starts, with `restarts` 0: 0 of
    // 400; restarts back at σ₀ after every gain, before the cycle of scales: 311 of 400;
    // 395 of 400; 397 while 8 more restarts came before a fresh start, 399 while 2; 400
    // before the probes, which move one coordinate at a time and cannot reach a well
    // that lies diagonally off: here they only cost budget; 394 with every fresh
    // descent at σ₀). Measured: 400 of 400. Bound: P(X < 36 | p = 0.995, N = 40) = 1.8e-6.
    let (lower, upper) = ([-10.0, -10.0], [10.0, 10.0]);
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut f = |x: &[f64]| {
                let shallow = (x[0] - 0.5).powi(2) + x[1].powi(2) + 0.5;
                let deep = 0.2 * ((x[0] - 6.0).powi(2) + (x[1] - 3.0).powi(2));
                shallow.min(deep)
            };
            let bounds = Some((&lower[..], &upper[..]));
            let (_, v, _) = minimise(&mut f, &[0.0, 0.0], 1.0, bounds, 1000, seed);
            v.is_some_and(|v| v < 1e-8)
        })
        .count();
    assert!(solved >= 36, "two wells: {solved} of {seeds}");
    // A noisy objective like a Monte Carlo render: a 3-D quadratic whose level moves by
    // up to 100 from seed to seed (a hundred times the signal near the optimum) with a
    // small grain along θ, to ‖θ − θ*‖ < 0.05 within 600 evaluations. Values compare
    // only on a common seed (without noise groups in the fit: 0 of 400). Measured: 399
    // of 400 (397 at an earlier commit). Bound: P(X < 37 | p = 0.9925, N = 40) = 2.3e-4.
    let solved = (0..seeds)
        .filter(|&seed| {
            let (theta, _, _) = minimise(&mut SeedLevel, &[4.0, -2.0, 3.0], 1.0, None, 600, seed);
            theta.iter().map(|v| (v - 1.0).powi(2)).sum::<f64>().sqrt() < 0.05
        })
        .count();
    assert!(solved >= 37, "noisy quadratic: {solved} of {seeds}");
    // A point-sampled disc of radius 6 on a 64×64 grid (f: the fraction of pixels whose
    // coverage differs from the target's) from a start that shares no pixel with the
    // target, in the box [0, 64]², to its exact image within 2 000 evaluations. With
    // samples clamped into the box instead of mirrored, and plateaus read only from
    // unanimous ties, 35 of 400; with σ free to fall back to where the samples tied
    // (so that it cycled between the pixels' scale and the next), 293 of 400.
    // Before fresh starts, 383 of 400; 399 while 8 more restarts came before a fresh start.
    // Measured: 400 of 400. Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let inside = |c: &[f64], px: f64, py: f64| (px - c[0]).powi(2) + (py - c[1]).powi(2) < 36.0;
    let (lower, upper) = ([0.0, 0.0], [64.0, 64.0]);
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut f = |x: &[f64]| {
                let differ = (0..64 * 64)
                    .filter(|p| {
                        let (px, py) = ((p % 64) as f64 + 0.5, (p / 64) as f64 + 0.5);
                        inside(x, px, py) != inside(&[20.0, 44.0], px, py)
                    })
                    .count();
                differ as f64 / 4096.0
            };
            let bounds = Some((&lower[..], &upper[..]));
            let (_, v, _) = minimise(&mut f, &[50.0, 12.0], 10.0, bounds, 2000, seed);
            v == Some(0.0)
        })
        .count();
    assert!(solved >= 38, "disc on a grid: {solved} of {seeds}");
    // A 100-D ellipsoid of condition 100, which the separability test (18 evaluations)
    // hands to the diagonal model, whose memory (128 points) holds fewer points than its
    // 201 coefficients, from 0 to a tenth of the start's parameter error within 800
    // evaluations. Measured: 400 of 400 (400 before, and without the test).
    // Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let n = 100;
    let centre: Vec<f64> = (0..n).map(|i| 0.5 + 0.25 * (i as f64).sin()).collect();
    let start_error = centre.iter().map(|c| c * c).sum::<f64>().sqrt();
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut f = |x: &[f64]| {
                x.iter()
                    .zip(&centre)
                    .enumerate()
                    .map(|(i, (v, c))| 10f64.powf(2.0 * i as f64 / 99.0) * (v - c).powi(2))
                    .sum::<f64>()
            };
            let (theta, _, _) = minimise(&mut f, &vec![0.0; n], 0.5, None, 800, seed);
            let error = theta
                .iter()
                .zip(&centre)
                .map(|(v, c)| (v - c).powi(2))
                .sum::<f64>();
            error.sqrt() < 0.1 * start_error
        })
        .count();
    assert!(solved >= 38, "ellipsoid-100: {solved} of {seeds}");
    // Noise the objective does not declare (a plain closure drawing fresh noise at every
    // call, as a renderer whose seed is not passed on): the 3-D quadratic of the noisy
    // case above, to ‖θ − θ*‖ < 0.01 within 1 500 evaluations.
    // Sparse Cauchy outliers on a constant offset, q + 1 + 𝟙{U < 0.2}·C: a lucky draw
    // of f(θ) rejected every later step before Auto checked for undeclared noise (10 of
    // 400), and often still when a single draw of θ set the bar (248 of 400, before θ
    // was drawn again after rejections; 373 before the check drew θ a third time; 361
    // before sparse outliers were voted out; 395 while the vote drew its third and later
    // draws one row at a time; 393 before the memory of twice the model's coefficients;
    // 383 before the probes ahead of fresh starts). Measured: 393 of 400.
    // Bound: P(X < 36 | p = 0.9825, N = 40) = 6.5e-4.
    let solved = (0..seeds)
        .filter(|&seed| unseeded_noise_solved(seed, UnseededNoise::Cauchy))
        .count();
    assert!(solved >= 36, "Cauchy outliers: {solved} of {seeds}");
    // Multiplicative noise q·exp(N/2), which vanishes at the optimum: 397 of 400 before
    // the check, 352 before θ was drawn again after rejections, 338 before a rejection
    // within the noise kept σ. Measured: 400 of 400 (400 before). Bound:
    // P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let solved = (0..seeds)
        .filter(|&seed| unseeded_noise_solved(seed, UnseededNoise::LogNormal))
        .count();
    assert!(solved >= 38, "multiplicative noise: {solved} of {seeds}");
    // Additive noise, q + 0.01·N, which does not vanish at the optimum (a Monte Carlo
    // render's variance), on q(x) = Σᵢ (i + 1)(xᵢ − 1)² in 6-D from 0, to q(θ) < 0.005
    // (q's own value, at the point returned) within 3 000 evaluations: 154 of 400 while
    // θ moved to any sample whose single draw came below f(θ)'s, following the noise's
    // lowest draws (median q 0.0081); 263 of 400 (median 0.0032) while the memory kept
    // the points nearest θ, draws at the smaller σ the noise swamps. Measured: 316 of
    // 400. Bound: P(X < 24 | p = 0.79, N = 40) = 1.7e-3.
    let solved = (0..seeds)
        .filter(|&seed| additive_noise_solved(seed))
        .count();
    assert!(solved >= 24, "additive noise: {solved} of {seeds}");
    // Rosenbrock's valley at n = 5 under 1 % multiplicative noise, to f < 1e-8 within
    // 5 000 evaluations: 2 of 200 while every rejection halved σ (the steps shrank until
    // each comparison was the noise's), 164 of 200 while a rejection within twice the
    // noise's scale kept σ, 200 of 200 within NOISE_MARGIN (10) times it. Measured: 400
    // of 400 (400 before). Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let solved = (0..seeds).filter(|&seed| noisy_valley_solved(seed)).count();
    assert!(solved >= 38, "noisy valley: {solved} of {seeds}");
    // The same valley under the sparse outliers of the Cauchy case above (BBOB f112's
    // kind): 0 of 400 while the model interpolated the outliers, 392 of 400 with every
    // point drawn until two draws agree (also with the draws batched in rounds; 394
    // before the memory of twice the model's coefficients; 385 before the probes ahead
    // of fresh starts). Measured: 375 of 400. Bound: P(X < 32 | p = 0.935, N = 40) = 8.9e-4.
    let solved = (0..seeds)
        .filter(|&seed| sparse_valley_solved(seed))
        .count();
    assert!(solved >= 32, "valley under outliers: {solved} of {seeds}");
    // An integer plateau like the suite's (a rotated ellipsoid of condition 100 seen only
    // at integer points) in 5-D, in the box [−5, 5]⁵ with σ₀ = 2 from a start uniform in
    // [−4, 4]⁵, to its exact minimum within 150 evaluations: 237 of 400 with a memory of
    // p + n + 1 points. Measured: 279 of 400. Bound: P(X < 18 | p = 0.695, N = 40) = 3.6e-4.
    let solved = (0..seeds)
        .filter(|&seed| integer_plateau_solved(seed))
        .count();
    assert!(solved >= 18, "integer plateau: {solved} of {seeds}");
    // A start where the objective fails (NaN outside the ball of radius 2, as a renderer
    // fails off its scene), from 1.87 (3.7σ₀) outside the ball: 171 of 400 while each
    // fresh start jumped from where the last had ended, wandering off in a random walk;
    // 380 of 400 jumping from x₀ while each descent waited out its patience at 16σ₀.
    // Measured: 400 of 400. Bound: P(X < 38 | p = 0.99875, N = 40) = 1.9e-5.
    let solved = (0..seeds)
        .filter(|&seed| failing_start_solved(seed))
        .count();
    assert!(solved >= 38, "failing start: {solved} of {seeds}");
}

/// Whether Auto reaches f < 1e-8 within 4 000 evaluations from x₀ = (3, −1, 2, 1) with
/// σ₀ = ½ on f(x) = (x₁ − 1.3)² + (x₂ − 1.3)² + x₃² + x₄², NaN where ‖x‖ > 2: the start,
/// 1.87 from the ball, sees NaN all around.
fn failing_start_solved(seed: u64) -> bool {
    let mut f = |x: &[f64]| {
        if x.iter().map(|v| v * v).sum::<f64>() > 4.0 {
            f64::NAN
        } else {
            (x[0] - 1.3).powi(2) + (x[1] - 1.3).powi(2) + x[2] * x[2] + x[3] * x[3]
        }
    };
    let (_, v, _) = minimise(&mut f, &[3.0, -1.0, 2.0, 1.0], 0.5, None, 4000, seed);
    v.is_some_and(|v| v < 1e-8)
}

/// Whether Auto reaches the exact minimum of a 5-D integer plateau within 150
/// evaluations: f(x) = Σᵢ 100^(i/4)·zᵢ², z = H(round(x) − x*) ([`reflected`]),
/// x* = (1, −2, 0, 3, −1); the start is uniform in [−4, 4]⁵ from a stream seeded with
/// `seed`.
fn integer_plateau_solved(seed: u64) -> bool {
    let n = 5;
    let target = [1.0, -2.0, 0.0, 3.0, -1.0];
    let mut f = |x: &[f64]| {
        let d: Vec<f64> = x.iter().zip(&target).map(|(a, b)| a.round() - b).collect();
        reflected(&d)
            .iter()
            .enumerate()
            .map(|(i, z)| 100f64.powf(i as f64 / (n - 1) as f64) * z * z)
            .sum::<f64>()
    };
    let mut u = uniforms(seed ^ 0x5eed);
    let x0: Vec<f64> = (0..n).map(|_| -4.0 + 8.0 * u()).collect();
    let (lower, upper) = ([-5.0; 5], [5.0; 5]);
    let bounds = Some((&lower[..], &upper[..]));
    let (_, v, _) = minimise(&mut f, &x0, 2.0, bounds, 150, seed);
    v == Some(0.0)
}

/// Where no fit is determined (a full model at n = 20: 160 remembered points against 231
/// coefficients) a stiff direction that stalls the run is learnt by the metric from the
/// stalled models ([`hodr_core::optim::auto::STALLED_ANISOTROPY`]). BBOB's discus shape,
/// 10⁶·T_osz(z₁)² + Σᵢ₌₂ T_osz(zᵢ)² with z = ΛH(x − x*) as [`rotated`], whose oscillation
/// T_osz makes the curvature along z₁ swing to about ±1.7·10⁷ at every scale: in
/// 20-D from (3, …), to f < 1e-8 within 20 000 evaluations. Before the rule, 0 of seeds
/// 0–11. Measured: 100 of seeds 0–99 (rate ≥ 0.97 at 95 % confidence). Bound, over seeds
/// 0–11: P(X < 9 | p = 0.97, N = 12) = 3.3e-4.
#[test]
fn a_stiff_direction_is_learnt_where_no_fit_is_determined() {
    let seeds = 12;
    let discus = |x: &[f64]| {
        let z = hodr_host::suite::bbob::t_osz(&rotated(x));
        1e6 * z[0] * z[0] + z[1..].iter().map(|v| v * v).sum::<f64>()
    };
    let solved = (0..seeds)
        .filter(|&seed| reaches_1e8(discus, &[3.0; 20], 20_000, seed))
        .count();
    assert!(solved >= 9, "20-D discus: {solved} of {seeds}");
}

/// A valley that runs along no parameter axis, above n = 20: the rotated ellipsoid of
/// condition 10³ ([`rotated_ellipsoid`]) in 30-D from (3, …), σ₀ = 1, to f < 1e-8 within
/// 3 000 evaluations. Only a full model and metric represent it
/// (n ≤ [`hodr_core::optim::auto::FULL_MODEL_MAX_DIM`]); with the diagonal ones used
/// above n = 20 before, 0 of seeds 0–19 (and 0 of 5 within 30 000).
/// Measured: 100 of seeds 0–99 (99 with 128 remembered points; rate ≥ 0.95 at 95 %
/// confidence). Bound, over seeds 0–15: P(X < 12 | p = 0.95, N = 16) = 8.6e-4.
#[test]
fn a_rotated_valley_is_learnt_above_twenty_dimensions() {
    let n = 30;
    let seeds = 16;
    let solved = (0..seeds)
        .filter(|&seed| reaches_1e8(rotated_ellipsoid(n, 1e3), &vec![3.0; n], 3_000, seed))
        .count();
    assert!(solved >= 12, "30-D rotated ellipsoid: {solved} of {seeds}");
}

/// The rotated ellipsoid Σᵢ 10^(6i/(n − 1))·zᵢ², z = Q(x − x*) ([`rotated_ellipsoid`]), at
/// n = 40: its 861 coefficients are learnt fit after fit from the remembered points, and
/// a memory that does not grow with n ([`hodr_core::optim::auto::FULL_MEMORY_PER_DIM`])
/// learns them too slowly for a valley of condition 10⁶. From (3, …), σ₀ = 1, to
/// f < 1e-8 within 12 000 evaluations: with 128 points, 0 of seeds 0–39; with 8n = 320,
/// measured 39 of 40 (rate ≥ 0.88 at 95 % confidence). Bound, over seeds 0–7:
/// P(X < 4 | p = 0.88, N = 8) = 7.7e-4.
#[test]
fn a_stiff_rotated_valley_is_learnt_at_forty_dimensions() {
    let n = 40;
    let seeds = 8;
    let solved = (0..seeds)
        .filter(|&seed| reaches_1e8(rotated_ellipsoid(n, 1e6), &vec![3.0; n], 12_000, seed))
        .count();
    assert!(solved >= 4, "40-D rotated ellipsoid: {solved} of {seeds}");
}

/// A kink in every direction where no fit is determined: the max norm
/// max|xᵢ − 0.3| at n = 20, from a start uniform in [−3, 3]²⁰ (drawn from a stream
/// seeded with 1000 + the run's seed), σ₀ = 1, to f < 1e-6 within 40 000 evaluations. Its smoothed curvature grows as
/// σ shrinks, so every scale's fit mispredicts its steps alike; while each poor step of
/// a validated model shrank σ, σ fell to 10⁻⁵ with f still near 0.02, and no run got
/// there. Measured: 40 of seeds 0–39 (rate ≥ 0.93 at 95 % confidence). Bound, over seeds
/// 0–9: P(X < 6 | p = 0.93, N = 10) = 3.6e-4.
#[test]
fn a_max_norm_is_solved_where_no_fit_is_determined() {
    let n = 20;
    let seeds = 10;
    let solved = (0..seeds)
        .filter(|&seed| {
            let mut draw = uniforms(1000 + seed);
            let x0: Vec<f64> = (0..n).map(|_| 6.0 * draw() - 3.0).collect();
            let max_norm = |x: &[f64]| x.iter().fold(0.0, |m: f64, v| m.max((v - 0.3).abs()));
            reaches(max_norm, &x0, 1.0, None, 40_000, 1e-6, seed)
        })
        .count();
    assert!(solved >= 6, "20-D max norm: {solved} of {seeds}");
}

/// Σᵢ κ^(i/(n − 1))·zᵢ², z = Q(x − x*), Q the suite's random rotation
/// ([`hodr_host::suite::random::rotation`], seed 7) and x*ᵢ = 0.1(i + 1): a valley of
/// condition κ along no parameter axis.
fn rotated_ellipsoid(n: usize, condition: f64) -> impl Fn(&[f64]) -> f64 {
    let q = hodr_host::suite::random::rotation(n, 7);
    move |x: &[f64]| {
        (0..n)
            .map(|i| {
                let z: f64 = (0..n)
                    .map(|j| q[i * n + j] * (x[j] - 0.1 * (j as f64 + 1.0)))
                    .sum();
                condition.powf(i as f64 / (n as f64 - 1.0)) * z * z
            })
            .sum::<f64>()
    }
}

/// One object fitted, another still on its plateau: f = 1000·(|x₀| + |x₁|) +
/// min(1, ‖(x₂, x₃) − (3.5, 3.5)‖²), a sharp cone in the first pair and, in the second,
/// a bowl of radius 1 four units from the start, flat outside it. Once the cone is
/// solved, samples wide enough to reach the bowl throw the cone's coordinates off by far
/// more than the bowl can gain, unless the metric is wider along the flat pair: a
/// restart's survey along the axes finds x₂ and x₃ flat and x₀, x₁ not, and stretches
/// the metric along the former ([`hodr_core::optim::auto::FLAT_STRETCH`]). From
/// (0.1, −0.1, 0, 0), σ₀ = 1, to f < 1e-8 within 4 000 evaluations: 163 of seeds 0–999
/// (rate ≥ 0.143 at 95 % confidence), 35 of seeds 0–199 (106 since the probes and the
/// fresh descents at their jump's scale until a probe succeeds or two end alike, 124
/// before the interior trust-region steps by Cholesky, which change the runs only by
/// rounding — 447 of seeds 200–999 both; 125 with every fresh
/// descent at its jump's scale, 118 with every one at σ₀); 31 of 1 000 with restarts'
/// surveys along random frames and no stretch. Bound, over seeds 0–199:
/// P(X < 13 | p = 0.143, N = 200) = 1.8e-4, while without the stretch
/// P(X ≥ 13 | p = 0.031, N = 200) = 0.010.
#[test]
fn a_flat_pair_of_coordinates_widens_the_metric() {
    let seeds = 200;
    let cone_and_bowl = |x: &[f64]| {
        let bowl = (x[2] - 3.5).powi(2) + (x[3] - 3.5).powi(2);
        1000.0 * (x[0].abs() + x[1].abs()) + bowl.min(1.0)
    };
    let solved = (0..seeds)
        .filter(|&seed| reaches_1e8(cone_and_bowl, &[0.1, -0.1, 0.0, 0.0], 4000, seed))
        .count();
    assert!(solved >= 13, "cone and bowl: {solved} of {seeds}");
}

/// A render on the caller's seed with a local minimum in the box's corner: the suite's
/// rendered discs (`hodr suite --families rendered`), a disc on a 64×64 image drawn
/// with 4 random samples per pixel, whose start shares no pixel with the target's; a
/// disc pushed into a corner of the image leaves three quarters of it out of view, so
/// the loss there is lower than anywhere else off the target. Auto draws θ again beside
/// each iteration's samples; counted as points around θ, those draws let σ shrink on a
/// model that had seen nothing else, and runs ended at the corner after some fifty
/// evaluations. From the corner, a restart's survey keeps the random frame: pairs along
/// the axes would fold onto the image's two edges. Runs of seeds 0–15 on instances 1–5
/// (as the suite seeds them), to a 99 % parameter-error reduction within 2 000
/// evaluations. Measured over seeds 0–79: 348 of 400 (rate ≥ 0.84 at 95 % confidence;
/// 354 before the interior trust-region steps by Cholesky, 356 while the probes drew about the best point rather than over the box, 355 while a
/// pair folded onto one point at the corner was drawn twice); 303 with surveys along the
/// axes from the corner, 176 with θ's draws counted too.
/// Bound: P(X < 58 | p = 0.84, N = 80) = 2.9e-3, while with θ's draws counted
/// P(X ≥ 58 | p = 0.44, N = 80) = 2.3e-7.
#[test]
fn a_render_s_corner_minimum_does_not_end_the_search() {
    use hodr_host::suite::{BUDGET_PER_DIM, methods::Method, problem::run_seed, rendered};
    let mut solved = 0;
    for instance in 1..=5 {
        let problem = rendered::discs(2, instance, BUDGET_PER_DIM);
        for index in 0..16 {
            let seed = run_seed(&problem.name, index);
            let trace = Method::Auto.run(&problem, &problem.start(seed), seed);
            solved += usize::from(trace.reaching_param(0.99).is_some());
        }
    }
    assert!(solved >= 58, "rendered disc: {solved} of 80");
}

/// Sparse outliers on a 5-D Rosenbrock valley (as `sparse_valley_solved`), counting the
/// objective's batches: the vote draws each point twice in one batch and the points
/// still undecided in one batch per round, so that a batch renderer is called for
/// several rows at a time. Measured over seeds 0–19 at 5 000 evaluations: 2.24 rows per
/// call (1.41 while the vote drew the second draws after the first and the later ones
/// one row at a time; 1.40 on seed 0); over seeds 0–4, 2.23–2.26.
#[test]
fn the_vote_batches_its_draws() {
    /// An objective that counts its batches and their rows.
    struct Counted<F> {
        f: F,
        calls: usize,
        rows: usize,
    }
    impl<F: FnMut(&[f64]) -> f64> Objective<f64> for Counted<F> {
        fn evaluate(&mut self, x: &[f64], _seed: u64) -> f64 {
            (self.f)(x)
        }
        fn evaluate_batch(&mut self, batch: &hodr_core::Batch<'_, f64>, out: &mut [f64]) {
            self.calls += 1;
            self.rows += out.len();
            for (k, v) in out.iter_mut().enumerate() {
                *v = self.evaluate(batch.point(k), batch.seed(k));
            }
        }
        fn deterministic(&self) -> bool {
            true
        }
    }
    for seed in 0..5 {
        let mut f = Counted {
            f: spiky_valley(1000 + seed),
            calls: 0,
            rows: 0,
        };
        minimise(&mut f, &[-1.5; 5], 1.0, None, 5000, seed);
        let per_call = f.rows as f64 / f.calls as f64;
        assert!(per_call >= 1.8, "seed {seed}: {per_call:.2} rows per call");
    }
}

/// Whether a run of Auto from `x0` with σ₀ = 1 reaches f < 1e-8 within `budget`
/// evaluations; it stops there, since the rest of a solved run proves nothing.
fn reaches_1e8(f: impl FnMut(&[f64]) -> f64, x0: &[f64], budget: usize, seed: u64) -> bool {
    reaches(f, x0, 1.0, None, budget, 1e-8, seed)
}

/// Whether Auto, from `x0` at scale `sigma0` in `bounds`, evaluates a point below
/// `target` within `budget` evaluations.
fn reaches(
    mut f: impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    sigma0: f64,
    bounds: Option<(&[f64], &[f64])>,
    budget: usize,
    target: f64,
    seed: u64,
) -> bool {
    let mut theta = x0.to_vec();
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(x0.len())];
    let mut auto = budgeted(&mut theta, &mut buffer, sigma0, bounds, budget, seed);
    while let Ok(Some(_)) = auto.step(&mut f) {
        if auto.value().is_some_and(|v| v < target) {
            return true;
        }
    }
    false
}

/// How many runs of Auto on `f` from `x0` (σ₀ = 1, no bounds, `budget` evaluations), one
/// per seed in 0..`seeds`, reach f < 1e-8.
fn runs_below_1e8(f: impl Fn(&[f64]) -> f64, x0: &[f64], budget: usize, seeds: u64) -> usize {
    (0..seeds)
        .filter(|&seed| {
            let (_, v, _) = minimise(&mut |x: &[f64]| f(x), x0, 1.0, None, budget, seed);
            v.is_some_and(|v| v < 1e-8)
        })
        .count()
}

/// z = ΛH(x − x*) for BBOB-like test functions: x*ᵢ = 0.1(i + 1), H the Householder
/// reflection along v = (1, 2, …, n) (H = I − 2vvᵀ/vᵀv), Λ = diag(10^(i/(n − 1))) of
/// condition 10.
fn rotated(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    let d: Vec<f64> = (0..n).map(|i| x[i] - 0.1 * (i as f64 + 1.0)).collect();
    reflected(&d)
        .iter()
        .enumerate()
        .map(|(i, z)| z * 10f64.powf(i as f64 / (n as f64 - 1.0)))
        .collect()
}

/// Hd, H = I − 2vvᵀ/vᵀv the Householder reflection along v = (1, 2, …, n).
fn reflected(d: &[f64]) -> Vec<f64> {
    let v: Vec<f64> = (1..=d.len()).map(|i| i as f64).collect();
    let vd =
        v.iter().zip(d).map(|(a, b)| a * b).sum::<f64>() / v.iter().map(|a| a * a).sum::<f64>();
    d.iter()
        .zip(&v)
        .map(|(di, vi)| di - 2.0 * vi * vd)
        .collect()
}

/// The noise of [`unseeded_noise_solved`].
#[derive(Clone, Copy)]
enum UnseededNoise {
    Cauchy,
    LogNormal,
}

/// Whether Auto brings q(θ) = Σᵢ (i + 1)(θᵢ − 1)², observed through `noise` drawn
/// afresh at every call, from (4, −2, 3) to within 0.01 of θ* = (1, 1, 1) in 1 500
/// evaluations (run seed `seed`).
fn unseeded_noise_solved(seed: u64, noise: UnseededNoise) -> bool {
    let mut unit = uniforms(1_000_000 + seed);
    let mut f = |x: &[f64]| {
        let q: f64 = x
            .iter()
            .enumerate()
            .map(|(i, v)| (1.0 + i as f64) * (v - 1.0).powi(2))
            .sum();
        let (a, b, c) = (unit(), unit(), unit());
        match noise {
            UnseededNoise::Cauchy => {
                let outlier = if a < 0.2 {
                    (std::f64::consts::PI * (b - 0.5)).tan()
                } else {
                    0.0
                };
                q + 1.0 + outlier
            }
            UnseededNoise::LogNormal => q * (0.5 * standard_normal(b, c)).exp(),
        }
    };
    let (theta, _, _) = minimise(&mut f, &[4.0, -2.0, 3.0], 1.0, None, 1500, seed);
    theta.iter().map(|v| (v - 1.0).powi(2)).sum::<f64>().sqrt() < 0.01
}

/// Whether Auto brings q(x) = Σᵢ (i + 1)(xᵢ − 1)² in 6-D, observed as q + 0.01·N with N
/// a standard normal drawn afresh at every call, from 0 to q(θ) < 0.005 within 3 000
/// evaluations (run seed `seed`).
fn additive_noise_solved(seed: u64) -> bool {
    let mut unit = uniforms(4_000_000 + seed);
    let q = |x: &[f64]| -> f64 {
        x.iter()
            .enumerate()
            .map(|(i, v)| (1.0 + i as f64) * (v - 1.0).powi(2))
            .sum()
    };
    let mut f = |x: &[f64]| {
        let (b, c) = (unit(), unit());
        q(x) + 0.01 * standard_normal(b, c)
    };
    let (theta, _, _) = minimise(&mut f, &[0.0; 6], 1.0, None, 3000, seed);
    q(&theta) < 0.005
}

/// Rosenbrock's function, Σᵢ 100(xᵢ₊₁ − xᵢ²)² + (1 − xᵢ)².
fn rosenbrock(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| 100.0 * (w[1] - w[0] * w[0]).powi(2) + (1.0 - w[0]).powi(2))
        .sum()
}

/// Whether Auto brings Rosenbrock's function at n = 5, observed as f·exp(0.01·N) with N
/// a standard normal drawn afresh at every call, from 0 to f < 1e-8 (its noiseless value
/// at the best point) within 5 000 evaluations (run seed `seed`).
fn noisy_valley_solved(seed: u64) -> bool {
    let mut unit = uniforms(2_000_000 + seed);
    let mut f = |x: &[f64]| {
        let (b, c) = (unit(), unit());
        rosenbrock(x) * (0.01 * standard_normal(b, c)).exp()
    };
    let (theta, _, _) = minimise(&mut f, &[0.0; 5], 1.0, None, 5000, seed);
    rosenbrock(&theta) < 1e-8
}

/// Whether Auto brings Rosenbrock's function at n = 5, observed as f + 1 + 𝟙{U < 0.2}·C
/// with C a standard Cauchy variate, U and C drawn afresh at every call, from 0 to
/// f < 1e-8 (its noiseless value at the best point) within 5 000 evaluations (run seed
/// `seed`).
fn sparse_valley_solved(seed: u64) -> bool {
    let mut f = spiky_valley(3_000_000 + seed);
    let (theta, _, _) = minimise(&mut f, &[0.0; 5], 1.0, None, 5000, seed);
    rosenbrock(&theta) < 1e-8
}

/// Rosenbrock's function observed as f + 1 + 𝟙{U < 0.2}·C, C a standard Cauchy variate,
/// U and C drawn afresh at every call from the stream [`uniforms`]`(seed)`.
fn spiky_valley(seed: u64) -> impl FnMut(&[f64]) -> f64 {
    let mut unit = uniforms(seed);
    move |x: &[f64]| {
        let (a, b) = (unit(), unit());
        let outlier = if a < 0.2 {
            (std::f64::consts::PI * (b - 0.5)).tan()
        } else {
            0.0
        };
        rosenbrock(x) + 1.0 + outlier
    }
}

/// Uniform draws in [0, 1) from a stream seeded with `seed`: the noise of the unseeded
/// objectives above, drawn afresh at every call.
fn uniforms(seed: u64) -> impl FnMut() -> f64 {
    use rand_xoshiro::rand_core::Rng;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// A standard normal from two uniforms in [0, 1) (Box–Muller).
fn standard_normal(b: f64, c: f64) -> f64 {
    (-2.0 * (b + 1e-300).ln()).sqrt() * (std::f64::consts::TAU * c).cos()
}

/// A cancelling objective stops Auto within one batch, θ keeps the best point so far,
/// and the run can be resumed.
#[test]
fn cancellation_stops_within_one_batch_and_keeps_theta() {
    struct StopAfter {
        evaluations: usize,
        limit: usize,
    }
    impl Objective<f64> for StopAfter {
        fn evaluate(&mut self, x: &[f64], _seed: hodr_core::NoiseSeed) -> f64 {
            self.evaluations += 1;
            x.iter().map(|v| (v - 1.0).powi(2)).sum()
        }
        fn deterministic(&self) -> bool {
            true
        }
        fn cancelled(&mut self) -> bool {
            self.evaluations >= self.limit
        }
    }
    let n = 40;
    let mut theta = vec![0.0; n];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        &mut buffer,
        Xoshiro256PlusPlus::seed_from_u64(2),
    )
    .unwrap();
    let mut f = StopAfter {
        evaluations: 0,
        limit: 30,
    };
    let mut ended = None;
    for _ in 0..1000 {
        match auto.step(&mut f) {
            Ok(Some(_)) => {}
            Ok(None) => break,
            Err(e) => {
                ended = Some(e);
                break;
            }
        }
    }
    assert_eq!(ended, Some(Error::Cancelled));
    assert!(f.evaluations < 30 + 64, "{} evaluations", f.evaluations);
    assert!(auto.theta().iter().all(|v| v.is_finite()));
    f.limit = usize::MAX;
    assert!(
        auto.step(&mut f).is_ok(),
        "the run goes on after a cancellation"
    );
}

/// f = ‖Dz‖² + (0.1 − x₀) in 20-D, z as in [`rotated`] and D = diag(10^(2i/19))
/// (condition 10⁶ with Λ), in the box [−5, 5]²⁰ but x₀ ≤ 0.1: its minimum f = 0 is
/// x* = (0.1, 0.2, …) on the face x₀ = 0.1, where f's slope (−1 along x₀) pushes out of
/// the box. The ill-conditioned valley leads θ close to the face, where trial steps cross
/// it; a step cut off there by the projection into the box is no longer the model's
/// minimiser, and σ used to shrink while θ crept towards the face.
fn face_solved(seed: u64) -> bool {
    let n = 20;
    let lower = vec![-5.0; n];
    let mut upper = vec![5.0; n];
    upper[0] = 0.1;
    let mut f = |x: &[f64]| {
        let valley: f64 = rotated(x)
            .iter()
            .enumerate()
            .map(|(i, v)| (v * 10f64.powf(2.0 * i as f64 / (n as f64 - 1.0))).powi(2))
            .sum();
        valley + (0.1 - x[0])
    };
    let (_, v, _) = minimise(&mut f, &[-3.0; 20], 1.0, Some((&lower, &upper)), 5000, seed);
    v.is_some_and(|v| v < 1e-8)
}

/// A minimum on a face of the box is reached within 5 000 evaluations ([`face_solved`]).
/// With steps projected into the box as they were (before the held coordinates of the
/// trust step), 36 of 100 seeds. Measured: 100 of 100.
/// Bound: P(X < 18 | p = 0.995, N = 20) = 1.3e-4.
#[test]
fn a_minimum_on_a_face_is_reached() {
    let solved = (0..20).filter(|&seed| face_solved(seed)).count();
    assert!(solved >= 18, "{solved} of 20");
}

/// Each coordinate's scale starts the run: σ₀ is their geometric mean, after each is cut
/// to a quarter of its side of the box; equal scales are σ₀ itself, and the run is the
/// one [`Auto::new`]'s common σ₀ gives, evaluation for evaluation.
#[test]
fn per_coordinate_scales_set_sigma0() {
    let n = 5;
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
    let rng = || Xoshiro256PlusPlus::seed_from_u64(0);
    let (lower, upper) = ([0.0, 0.0, 0.0, 0.0, -5.0], [1.0, 3.0, 7.0, 15.0, 5.0]);
    let cut = [0.25, 0.75, 1.75, 2.0, 2.0];
    let mean = cut.iter().map(|s: &f64| s.ln()).sum::<f64>() / 5.0;
    for bounds_first in [false, true] {
        let mut theta = [0.5; 5];
        let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng()).unwrap();
        if bounds_first {
            auto = auto.with_bounds(&lower, &upper).unwrap();
        }
        auto = auto.with_scales(&[2.0; 5]).unwrap();
        if !bounds_first {
            auto = auto.with_bounds(&lower, &upper).unwrap();
        }
        let sigma = auto.sigma();
        assert!(
            (sigma.ln() - mean).abs() < 1e-12,
            "{sigma} against {}",
            mean.exp()
        );
    }
    let log = |scales: Option<&[f64]>| {
        let mut points: Vec<Vec<f64>> = Vec::new();
        let mut f = |x: &[f64]| {
            points.push(x.to_vec());
            x.iter().map(|v| (v * 3.0).floor()).sum::<f64>().abs()
        };
        let mut theta = vec![1.3; n];
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
        let options = AutoOptions::default().with_max_evaluations(300).unwrap();
        let mut auto = Auto::new(&mut theta, 0.7, &mut buffer, rng())
            .unwrap()
            .with_options(options);
        if let Some(scales) = scales {
            auto = auto.with_scales(scales).unwrap();
        }
        assert_eq!(auto.sigma(), 0.7);
        auto.run(&mut f, |_, _| {}).unwrap();
        points
    };
    assert_eq!(log(None), log(Some(&[0.7; 5])));
}

/// Whether f reaches its minimum 0 within 30 evaluations on a staircase over a
/// correlated quadratic in three units — a position (scale 100), a colour (scale 0.1)
/// and a fine offset (scale 0.001) — from 5, 5 and 3 scales away, the scales stated
/// with [`Auto::with_scales`].
fn mixed_units_solved(seed: u64) -> bool {
    let mut f = |x: &[f64]| {
        let z = [
            (x[0] - 600.0) / 100.0,
            (x[1] - 0.7) / 0.1,
            (x[2] + 3.0) / 0.001,
        ];
        let q = z[0] * z[0] + z[1] * z[1] + z[2] * z[2] + 0.9 * z[0] * z[1];
        (q * 20.0).floor() / 20.0
    };
    let mut theta = vec![100.0, 0.2, -3.003];
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(3)];
    let options = AutoOptions::default().with_max_evaluations(30).unwrap();
    let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng)
        .unwrap()
        .with_options(options)
        .with_scales(&[100.0, 0.1, 0.001])
        .unwrap();
    auto.run(&mut f, |_, _| {}).unwrap();
    auto.value().is_some_and(|v| v <= 0.0)
}

/// Parameters in different units: stated per coordinate, the scales make the staircase of
/// [`mixed_units_solved`] look round from the first survey, which finds its minimum
/// within 30 evaluations; one common σ₀ of 100, 0.1 or 0.001 does so in 204, 218 and 0
/// of 400 seeds (the metric has to learn the units first). Measured with the scales: 400
/// of 400. Bound: P(X < 18 | p = 0.9925, N = 20) = 4.8e-4.
#[test]
fn per_coordinate_scales_state_the_units() {
    let solved = (0..20).filter(|&seed| mixed_units_solved(seed)).count();
    assert!(solved >= 18, "{solved} of 20");
}

/// Continuation moves θ, the search centre, above the best point (`AutoStep::Continued`);
/// the best point stays what [`Auto::theta`] and [`Auto::value`] report at every
/// iteration, and what the caller's θ holds once the run has ended. On a 2-D Rastrigin
/// function, whose restarts at wide σ follow the smoothed bowl past its wells.
#[test]
fn continuation_keeps_the_best_point() {
    let rastrigin = |x: &[f64]| {
        x.iter()
            .map(|v| {
                let z = v - 0.7;
                z * z + 10.0 * (1.0 - (std::f64::consts::TAU * z).cos())
            })
            .sum::<f64>()
    };
    let mut continued = 0;
    for seed in 0..10 {
        let mut lowest = f64::INFINITY;
        let mut f = |x: &[f64]| {
            let v = rastrigin(x);
            lowest = lowest.min(v);
            v
        };
        let mut theta = [3.3, -2.4];
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
        let options = AutoOptions::default().with_max_evaluations(1500).unwrap();
        let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng)
            .unwrap()
            .with_options(options)
            .with_bounds(&[-5.0, -5.0], &[5.0, 5.0])
            .unwrap();
        let mut reports = Vec::new();
        while let Some(r) = auto.step(&mut f).unwrap() {
            reports.push((r.kind, auto.value(), rastrigin(auto.theta())));
        }
        let best = auto.value().unwrap();
        assert_eq!(
            rastrigin(&theta),
            best,
            "seed {seed}: θ holds the best point"
        );
        for (kind, value, at_theta) in reports {
            continued += usize::from(kind == AutoStep::Continued);
            assert_eq!(value, Some(at_theta), "seed {seed}: value() is f(theta())");
        }
        assert_eq!(
            best, lowest,
            "seed {seed}: the best point is the lowest evaluated"
        );
    }
    assert!(continued > 0, "no continuation move in 10 runs");
}

/// Values a run of `model` evaluates on `f` from `x0` (σ₀ = 1, seed 5) within `budget`.
fn values_of(
    model: AutoModel,
    f: &mut impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    budget: usize,
) -> Result<(Vec<f64>, AutoModel), Error> {
    values_in(model.buffer_len(x0.len()), model, f, x0, budget)
}

/// [`values_of`] with a buffer of `len` floats.
fn values_in(
    len: usize,
    model: AutoModel,
    f: &mut impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    budget: usize,
) -> Result<(Vec<f64>, AutoModel), Error> {
    let mut theta = x0.to_vec();
    let mut buffer = vec![0.0; len];
    let rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let mut auto = Auto::with_model(&mut theta, 1.0, &mut buffer, rng, model)?
        .with_options(AutoOptions::default().with_max_evaluations(budget)?);
    let mut values = Vec::new();
    let mut record = |x: &[f64]| {
        let v = f(x);
        values.push(v);
        v
    };
    auto.run(&mut record, |_, _| {})?;
    let used = auto.model();
    Ok((values, used))
}

/// A model's own buffer length ([`AutoModel::buffer_len`]) is enough for its run and one
/// float fewer is a typed error; at n = 100 the diagonal model's is a small part of the
/// default's, and its run on that buffer is the run on the default's, value for value.
#[test]
fn a_model_runs_in_its_own_buffer_length() {
    let n = 100;
    let x0: Vec<f64> = (0..n).map(|i| (i % 7) as f64 - 3.0).collect();
    let mut l1 = |x: &[f64]| x.iter().map(|v| (v - 0.3).abs()).sum::<f64>();
    for model in [AutoModel::Diagonal, AutoModel::Full, AutoModel::ByDimension] {
        let len = model.buffer_len(n);
        assert_eq!(
            values_in(len - 1, model, &mut l1, &x0, 500).unwrap_err(),
            Error::WorkspaceTooSmall {
                needed: len,
                available: len - 1
            },
            "{model:?}"
        );
    }
    let default = Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n);
    assert!(10 * AutoModel::Diagonal.buffer_len(n) < default);
    let (own, _) = values_of(AutoModel::Diagonal, &mut l1, &x0, 500).unwrap();
    let (in_default, _) = values_in(default, AutoModel::Diagonal, &mut l1, &x0, 500).unwrap();
    assert_eq!(own, in_default);
}

/// The dense kernels' AVX2 copies give the run the baseline copies give, value for value
/// bit for bit ([`hodr_core::set_wide_kernels`]): a rotated ellipsoid at n = 40 (the full
/// model: fits, factorisations, metric updates and their eigen-decompositions) and the
/// L1 norm at n = 100 (the separability test, then the diagonal model). On a CPU without
/// AVX2 both runs take the baseline copies.
#[test]
fn wide_kernels_change_no_bit() {
    let n = 40;
    // Qx for the Householder reflection Q = I − 2vvᵀ/‖v‖², v = (1, 2, …, n): f is not
    // separable, so the separability test keeps the full model.
    let reflect = |x: &[f64]| {
        let vv: f64 = (1..=x.len()).map(|i| (i * i) as f64).sum();
        let vx: f64 = x
            .iter()
            .enumerate()
            .map(|(i, xi)| (i + 1) as f64 * xi)
            .sum();
        x.iter()
            .enumerate()
            .map(|(i, xi)| xi - 2.0 * vx / vv * (i + 1) as f64)
            .collect::<Vec<f64>>()
    };
    let mut ellipsoid = |x: &[f64]| {
        reflect(x)
            .iter()
            .enumerate()
            .map(|(i, y)| 10f64.powf(3.0 * i as f64 / (n - 1) as f64) * y * y)
            .sum::<f64>()
    };
    let mut l1 = |x: &[f64]| x.iter().map(|v| (v - 0.3).abs()).sum::<f64>();
    same_with_and_without_wide_kernels(&mut ellipsoid, 40, 1_500);
    same_with_and_without_wide_kernels(&mut l1, 100, 800);
}

/// Runs Auto on `f` from a fixed x₀ in dimension n for `budget` evaluations with the wide
/// kernels and without, and asserts that the values match bit for bit.
fn same_with_and_without_wide_kernels(
    mut f: &mut dyn FnMut(&[f64]) -> f64,
    n: usize,
    budget: usize,
) {
    let x0: Vec<f64> = (0..n).map(|i| (i % 5) as f64 - 2.0).collect();
    let [wide, baseline] = [true, false].map(|wide| {
        hodr_core::set_wide_kernels(wide);
        let (values, _) = values_of(AutoModel::ByDimension, &mut f, &x0, budget).unwrap();
        values.iter().map(|v| v.to_bits()).collect::<Vec<u64>>()
    });
    hodr_core::set_wide_kernels(true);
    assert_eq!(wide.len(), budget, "n = {n}");
    assert!(wide == baseline, "n = {n}: the runs differ");
}

/// The default model's separability test (n = 15–127) keeps the full model where it can
/// tell nothing — a plateau, where every value ties, and a declared-noisy objective,
/// which it does not test — and its points count: a run that ends within the test
/// returns the lowest of them.
#[test]
fn the_separability_test_keeps_what_it_cannot_tell() {
    let x0 = vec![0.0; 20];
    let (_, used) = values_of(AutoModel::ByDimension, &mut |_: &[f64]| 1.0, &x0, 100).unwrap();
    assert_eq!(used, AutoModel::Full);
    let mut theta = x0.clone();
    let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(20)];
    let rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let mut auto = Auto::with_model(&mut theta, 1.0, &mut buffer, rng, AutoModel::ByDimension)
        .unwrap()
        .with_options(AutoOptions::default().with_max_evaluations(100).unwrap());
    auto.run(&mut SeedLevel, |_, _| {}).unwrap();
    assert_eq!(auto.model(), AutoModel::Full);
    // From x₀ = 0 the test's point θ + d, every coordinate moved by σ₀ = 1, is the
    // minimum of Σ(xᵢ − 1)².
    let mut theta = x0.clone();
    let rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let mut auto = Auto::with_model(&mut theta, 1.0, &mut buffer, rng, AutoModel::ByDimension)
        .unwrap()
        .with_options(AutoOptions::default().with_max_evaluations(14).unwrap());
    let mut bowl = sphere(1.0, 1.0);
    auto.run(&mut bowl, |_, _| {}).unwrap();
    assert_eq!(auto.model(), AutoModel::Diagonal);
    assert_eq!(auto.value(), Some(0.0));
    assert_eq!(auto.theta(), &[1.0; 20][..]);
}

/// A model named ([`Auto::with_model`]), and the one the default picks. Above n = 127 the
/// default's run is the diagonal model's, point for point; from n = 15 its first
/// 4 + 2⌈log₂ n⌉ = 14 evaluations (n = 20) test whether f is separable, θ first, and the
/// run after them is the model the test picked, point for point but for θ, which it does
/// not evaluate again: the diagonal one on the L1 norm
/// Σ|xᵢ − 0.3|, the full one where terms in s = Σᵢ(xᵢ − 0.3), s² and s⁴, couple the
/// coordinates. The quartic keeps f off a quadratic along the test's line, so the full
/// model keeps its axis prior, as a named one does; on an exact quadratic coupled the same
/// way the test's line check drops the prior, and the run departs from the named model's.
/// The full model above n = 127 is a typed error, though its buffer is long enough; the
/// default takes the 20-D L1 norm to 10⁻⁶ within 8 000 evaluations.
#[test]
fn a_model_chosen_by_name() {
    let mut l1 = |x: &[f64]| x.iter().map(|v| (v - 0.3).abs()).sum::<f64>();
    let mut coupled = |x: &[f64]| {
        let sum: f64 = x.iter().map(|v| v - 0.3).sum();
        x.iter().map(|v| (v - 0.3).abs()).sum::<f64>() + 0.1 * sum * sum + 1e-3 * sum.powi(4)
    };
    let start = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| -2.0 + 4.0 * i as f64 / (n - 1) as f64)
            .collect()
    };
    let (by_dimension, used) =
        values_of(AutoModel::ByDimension, &mut l1, &start(128), 300).unwrap();
    assert_eq!(used, AutoModel::Diagonal);
    let (named, _) = values_of(AutoModel::Diagonal, &mut l1, &start(128), 300).unwrap();
    assert_eq!(by_dimension, named);
    let test = 14;
    for (f, picked) in [
        (
            &mut l1 as &mut dyn FnMut(&[f64]) -> f64,
            AutoModel::Diagonal,
        ),
        (&mut coupled, AutoModel::Full),
    ] {
        let mut f = |x: &[f64]| f(x);
        let (by_dimension, used) =
            values_of(AutoModel::ByDimension, &mut f, &start(20), test + 299).unwrap();
        assert_eq!(used, picked);
        let (named, used) = values_of(picked, &mut f, &start(20), 300).unwrap();
        assert_eq!(used, picked);
        assert_eq!(by_dimension[0], named[0]);
        assert_eq!(by_dimension[test..], named[1..], "{picked:?}");
    }
    let mut quadratic = |x: &[f64]| {
        let sum: f64 = x.iter().map(|v| v - 0.3).sum();
        let bowl: f64 = x
            .iter()
            .enumerate()
            .map(|(i, v)| (i + 1) as f64 * (v - 0.3).powi(2))
            .sum();
        bowl + 0.1 * sum * sum
    };
    let (by_dimension, used) = values_of(
        AutoModel::ByDimension,
        &mut quadratic,
        &start(20),
        test + 299,
    )
    .unwrap();
    assert_eq!(used, AutoModel::Full);
    let (named, _) = values_of(AutoModel::Full, &mut quadratic, &start(20), 300).unwrap();
    assert_eq!(by_dimension[0], named[0]);
    assert_ne!(by_dimension[test..], named[1..]);
    assert_eq!(
        values_of(AutoModel::Full, &mut l1, &[0.0; 128], 300).unwrap_err(),
        Error::InvalidSetting { name: "model" }
    );
    let (values, _) = values_of(AutoModel::ByDimension, &mut l1, &start(20), 8_000).unwrap();
    let best = values.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    assert!(best < 1e-6, "best {best:e} in {} evaluations", values.len());
}
