//! Every estimator against closed-form smoothed derivatives (hodr_host::problems).
//!
//! Each check repeats an estimate `REPEATS` times from a fixed seed and compares the mean
//! with the closed form, allowing `Z_TOLERANCE` standard errors (estimated from the
//! repetitions) plus a floor of 1e-9 relative for elements without variance. With fixed
//! seeds every test is deterministic. What these checks can resolve is limited by their
//! standard errors (a few per cent of an element); exact identities (weight × density =
//! kernel, mixture densities) are checked to rounding in hodr-core's unit tests.

use hodr_core::{Draws, Estimator, GradientMethod, HessianMethod, HvpMethod, Workspace};
use hodr_host::problems::Problem;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// Allowed deviation of a mean from its expectation, in standard errors.
const Z_TOLERANCE: f64 = 5.0;
/// Repetitions per check.
const REPEATS: usize = 1000;
/// Smoothing width for all checks.
const SIGMA: f64 = 0.5;
/// Antithetic pairs per estimate.
const PAIRS: usize = 8;

struct Stats {
    mean: Vec<f64>,
    se: Vec<f64>,
}

fn repeat(len: usize, mut one: impl FnMut(&mut [f64])) -> Stats {
    let (mut sum, mut sum2, mut x) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
    for _ in 0..REPEATS {
        one(&mut x);
        for k in 0..len {
            sum[k] += x[k];
            sum2[k] += x[k] * x[k];
        }
    }
    let m = REPEATS as f64;
    let mean: Vec<f64> = sum.iter().map(|s| s / m).collect();
    let se = (0..len)
        .map(|k| ((sum2[k] / m - mean[k] * mean[k]).max(0.0) / (m - 1.0)).sqrt())
        .collect();
    Stats { mean, se }
}

fn assert_matches(stats: &Stats, expected: &[f64], label: &str) {
    let scale = expected.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
    for (k, (&m, &e)) in stats.mean.iter().zip(expected).enumerate() {
        let tol = Z_TOLERANCE * stats.se[k] + 1e-9 * scale;
        assert!(
            (m - e).abs() <= tol,
            "{label}: element {k}: mean {m} vs {e} (tolerance {tol})"
        );
    }
}

struct Memory {
    buffer: Vec<f64>,
    seeds: Vec<u64>,
}

impl Memory {
    fn new(n: usize, rows: usize) -> Self {
        Memory {
            buffer: vec![0.0; Workspace::<f64>::buffer_len(n, rows)],
            seeds: vec![0; rows],
        }
    }
    /// With the moment region least-squares estimates need.
    fn with_moments(n: usize, rows: usize) -> Self {
        Memory {
            buffer: vec![
                0.0;
                Workspace::<f64>::buffer_len(n, rows) + Workspace::<f64>::moments_len(n)
            ],
            seeds: vec![0; rows],
        }
    }
    fn ws(&mut self, n: usize) -> Workspace<'_, f64> {
        Workspace::new(n, &mut self.buffer, &mut self.seeds).unwrap()
    }
}

fn problems(n: usize) -> [Problem; 3] {
    [
        Problem::sin_cos(n, 1),
        Problem::quadratic(n, 2),
        Problem::step(n, 3, 0.3),
    ]
}

const GRADIENTS: [GradientMethod; 3] = [
    GradientMethod::PerElement,
    GradientMethod::Aggregate,
    GradientMethod::Gaussian,
];

fn check_gradient(p: &Problem, method: GradientMethod, seed: u64) -> Stats {
    let n = p.dim();
    let mut mem = Memory::new(n, 16);
    let mut ws = mem.ws(n);
    let mut est = Estimator::new(SIGMA, PAIRS, Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(n, |g| {
        let r = est.gradient(method, &mut f, p.theta(), &mut ws, g).unwrap();
        assert_eq!(r.evaluations, method.evaluations(n, PAIRS));
    });
    assert_matches(
        &stats,
        &p.gradient(p.theta(), SIGMA),
        &format!("{method:?} gradient n={n}"),
    );
    stats
}

#[test]
fn gradients_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in problems(n).iter().enumerate() {
            for m in GRADIENTS {
                check_gradient(p, m, 17 + k as u64);
            }
        }
    }
}

#[test]
fn fr22_matches_closed_forms_where_it_is_exact() {
    for n in [1, 3, 10] {
        for p in [
            Problem::separable(n, 4),
            Problem::quadratic(n, 5),
            Problem::axis_step(n, 6, 0.2),
        ] {
            check_gradient(&p, GradientMethod::Fr22, 23);
        }
    }
}

/// Aggregate and per-element sampling estimate the same gradient.
#[test]
fn aggregate_and_per_element_agree_in_mean() {
    for p in problems(3) {
        let a = check_gradient(&p, GradientMethod::Aggregate, 80);
        let e = check_gradient(&p, GradientMethod::PerElement, 81);
        for k in 0..3 {
            let both = (a.se[k].powi(2) + e.se[k].powi(2)).sqrt();
            assert!((a.mean[k] - e.mean[k]).abs() <= Z_TOLERANCE * both + 1e-12);
        }
    }
}

#[test]
fn hessians_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in problems(n).iter().enumerate() {
            for method in [
                HessianMethod::PerElement,
                HessianMethod::Aggregate,
                HessianMethod::Gaussian,
            ] {
                let mut mem = Memory::new(n, 32);
                let mut ws = mem.ws(n);
                let mut est = Estimator::new(
                    SIGMA,
                    PAIRS,
                    Xoshiro256PlusPlus::seed_from_u64(31 + k as u64),
                )
                .unwrap();
                let mut f = |x: &[f64]| p.value(x);
                let stats = repeat(n * n, |h| {
                    let r = est.hessian(method, &mut f, p.theta(), &mut ws, h).unwrap();
                    assert_eq!(r.evaluations, method.evaluations(n, PAIRS));
                    assert_eq!(r.centre_value, Some(p.value(p.theta())));
                    for i in 0..n {
                        for j in 0..i {
                            assert_eq!(h[i * n + j], h[j * n + i]);
                        }
                    }
                });
                let label = format!("{method:?} Hessian n={n} problem {k}");
                assert_matches(&stats, &p.hessian(p.theta(), SIGMA), &label);
            }
        }
    }
}

fn check_hvp(p: &Problem, method: HvpMethod, seed: u64) -> Stats {
    let n = p.dim();
    let v = p.direction(7);
    let mut mem = Memory::new(n, 8);
    let mut ws = mem.ws(n);
    let mut est = Estimator::new(SIGMA, PAIRS, Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(n, |hv| {
        let r = est.hvp(method, &mut f, p.theta(), &v, &mut ws, hv).unwrap();
        assert_eq!(r.evaluations, method.evaluations(n, PAIRS));
    });
    let expected = match method {
        HvpMethod::Kernel => p.hvp(p.theta(), &v, SIGMA),
        HvpMethod::ForwardDifference { .. } => p.hvp_forward(p.theta(), &v, SIGMA),
        _ => p.hvp_central(p.theta(), &v, SIGMA),
    };
    assert_matches(&stats, &expected, &format!("{method:?} HVP n={n}"));
    stats
}

#[test]
fn hvps_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in problems(n).iter().enumerate() {
            check_hvp(p, HvpMethod::Kernel, 50 + k as u64);
            for gradient in GRADIENTS {
                for draws in [Draws::Independent, Draws::Common] {
                    check_hvp(
                        p,
                        HvpMethod::CentralDifference { gradient, draws },
                        60 + k as u64,
                    );
                }
                check_hvp(p, HvpMethod::ForwardDifference { gradient }, 65 + k as u64);
            }
        }
    }
}

/// Given g(θ) from the draws the stream repeats, a forward-difference HVP evaluates only
/// around θ + εu, and is exactly the estimate that differences both gradients itself.
#[test]
fn forward_difference_given_the_gradient_halves_the_cost() {
    let p = Problem::sin_cos(3, 1);
    let n = p.dim();
    let v = p.direction(7);
    let mut mem = Memory::new(n, 8);
    let mut ws = mem.ws(n);
    let mut f = |x: &[f64]| p.value(x);
    for gradient in GRADIENTS {
        let method = HvpMethod::ForwardDifference { gradient };
        let rng = Xoshiro256PlusPlus::seed_from_u64(90);
        let mut est = Estimator::new(SIGMA, PAIRS, rng.clone()).unwrap();
        let mut both = vec![0.0; n];
        est.hvp(method, &mut f, p.theta(), &v, &mut ws, &mut both)
            .unwrap();
        let mut g = vec![0.0; n];
        let mut est = Estimator::new(SIGMA, PAIRS, rng.clone()).unwrap();
        est.gradient(gradient, &mut f, p.theta(), &mut ws, &mut g)
            .unwrap();
        let mut est = Estimator::new(SIGMA, PAIRS, rng).unwrap();
        let mut given = vec![0.0; n];
        let r = est
            .hvp_given_gradient(method, &mut f, p.theta(), Some(&g), &v, &mut ws, &mut given)
            .unwrap();
        assert_eq!(r.evaluations, method.evaluations(n, PAIRS) / 2);
        for k in 0..n {
            let scale = both[k].abs().max(1.0);
            assert!(
                (both[k] - given[k]).abs() <= 1e-9 * scale,
                "{gradient:?}: {both:?} vs {given:?}"
            );
        }
    }
}

/// A direction of subnormal length (‖v‖ ≈ 1e-320, so ε/‖v‖ overflows) still steps by ε
/// along v/‖v‖: every point the estimate evaluates is finite, and so is Hv.
#[test]
fn a_subnormal_direction_gives_finite_points() {
    let p = Problem::sin_cos(3, 1);
    let n = p.dim();
    let mut mem = Memory::new(n, 8);
    let mut ws = mem.ws(n);
    let v = [1e-320, 0.0, -5e-321];
    for gradient in GRADIENTS {
        for method in [
            HvpMethod::CentralDifference {
                gradient,
                draws: Draws::Common,
            },
            HvpMethod::ForwardDifference { gradient },
        ] {
            let mut non_finite = 0;
            let mut f = |x: &[f64]| {
                non_finite += usize::from(!x.iter().all(|v| v.is_finite()));
                p.value(x)
            };
            let mut est =
                Estimator::new(SIGMA, PAIRS, Xoshiro256PlusPlus::seed_from_u64(5)).unwrap();
            let mut hv = vec![0.0; n];
            est.hvp(method, &mut f, p.theta(), &v, &mut ws, &mut hv)
                .unwrap();
            assert_eq!(non_finite, 0, "{method:?}");
            assert!(hv.iter().all(|h| h.is_finite()), "{method:?}: {hv:?}");
        }
    }
}

/// Common random numbers and independent draws estimate the same thing; on a smooth
/// objective the common ones have far smaller variance.
#[test]
fn common_random_numbers_agree_in_mean_and_cut_variance() {
    let p = Problem::sin_cos(3, 1);
    for gradient in GRADIENTS {
        let ind = check_hvp(
            &p,
            HvpMethod::CentralDifference {
                gradient,
                draws: Draws::Independent,
            },
            70,
        );
        let crn = check_hvp(
            &p,
            HvpMethod::CentralDifference {
                gradient,
                draws: Draws::Common,
            },
            71,
        );
        for k in 0..3 {
            let both = (ind.se[k].powi(2) + crn.se[k].powi(2)).sqrt();
            assert!((ind.mean[k] - crn.mean[k]).abs() <= Z_TOLERANCE * both);
            assert!(
                crn.se[k] < 0.2 * ind.se[k],
                "{gradient:?}: CRN se {} vs independent {}",
                crn.se[k],
                ind.se[k]
            );
        }
    }
}

#[test]
fn gradient_and_hvp_share_samples() {
    let p = Problem::sin_cos(3, 1);
    let v = p.direction(8);
    let mut mem = Memory::new(3, 8);
    let mut ws = mem.ws(3);
    let mut est = Estimator::new(SIGMA, PAIRS, Xoshiro256PlusPlus::seed_from_u64(5)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(6, |out| {
        let (g, h) = out.split_at_mut(3);
        let r = est
            .gradient_and_hvp(&mut f, p.theta(), &v, &mut ws, g, h)
            .unwrap();
        assert_eq!(r.evaluations, 2 * PAIRS + 1);
    });
    let mut expected = p.gradient(p.theta(), SIGMA);
    expected.extend(p.hvp(p.theta(), &v, SIGMA));
    assert_matches(&stats, &expected, "gradient_and_hvp");
}

#[test]
fn f32_estimates_match_closed_forms() {
    let p = Problem::sin_cos(3, 1);
    let theta: Vec<f32> = p.theta().iter().map(|&x| x as f32).collect();
    let theta64: Vec<f64> = theta.iter().map(|&x| x as f64).collect();
    let mut buffer = vec![0.0f32; Workspace::<f32>::buffer_len(3, 8)];
    let mut seeds = vec![0; 8];
    let mut ws = Workspace::new(3, &mut buffer, &mut seeds).unwrap();
    let mut f = |x: &[f32]| {
        let x64: Vec<f64> = x.iter().map(|&v| v as f64).collect();
        p.value(&x64) as f32
    };
    for m in GRADIENTS {
        let mut est =
            Estimator::new(SIGMA as f32, PAIRS, Xoshiro256PlusPlus::seed_from_u64(3)).unwrap();
        let mut g32 = [0.0f32; 3];
        let stats = repeat(3, |g| {
            est.gradient(m, &mut f, &theta, &mut ws, &mut g32).unwrap();
            for k in 0..3 {
                g[k] = g32[k] as f64;
            }
        });
        assert_matches(
            &stats,
            &p.gradient(&theta64, SIGMA),
            &format!("f32 {m:?} gradient"),
        );
    }
    let mut est =
        Estimator::new(SIGMA as f32, PAIRS, Xoshiro256PlusPlus::seed_from_u64(4)).unwrap();
    let mut h32 = [0.0f32; 9];
    let stats = repeat(9, |h| {
        est.hessian(HessianMethod::Aggregate, &mut f, &theta, &mut ws, &mut h32)
            .unwrap();
        for k in 0..9 {
            h[k] = h32[k] as f64;
        }
    });
    assert_matches(&stats, &p.hessian(&theta64, SIGMA), "f32 aggregate Hessian");
}

/// Least squares on Gaussian samples fits a linear model to the antithetic differences,
/// which are exactly linear for a quadratic: every single estimate (gradient, and
/// central-difference HVP with common random numbers) is the closed form to rounding.
#[test]
fn regression_is_exact_on_quadratics() {
    for n in [1, 3, 10] {
        let p = Problem::quadratic(n, 2);
        let pairs = 1;
        let mut mem = Memory::with_moments(n, 8);
        let mut ws = mem.ws(n);
        let mut est = Estimator::new(SIGMA, pairs, Xoshiro256PlusPlus::seed_from_u64(9)).unwrap();
        let mut f = |x: &[f64]| p.value(x);
        let (g_true, v) = (p.gradient(p.theta(), SIGMA), p.direction(7));
        let hv_true = p.hvp(p.theta(), &v, SIGMA);
        let scale = |x: &[f64]| x.iter().fold(0.0f64, |m, y| m.max(y.abs()));
        let hvp = HvpMethod::CentralDifference {
            gradient: GradientMethod::Regression,
            draws: Draws::Common,
        };
        for _ in 0..20 {
            let mut g = vec![0.0; n];
            let r = est
                .gradient(
                    GradientMethod::Regression,
                    &mut f,
                    p.theta(),
                    &mut ws,
                    &mut g,
                )
                .unwrap();
            assert_eq!(r.evaluations, 2 * (2 * n + 2));
            for k in 0..n {
                assert!(
                    (g[k] - g_true[k]).abs() <= 1e-9 * scale(&g_true),
                    "n={n} g[{k}]"
                );
            }
            let mut hv = vec![0.0; n];
            est.hvp(hvp, &mut f, p.theta(), &v, &mut ws, &mut hv)
                .unwrap();
            for k in 0..n {
                assert!(
                    (hv[k] - hv_true[k]).abs() <= 1e-8 * scale(&hv_true),
                    "n={n} hv[{k}]"
                );
            }
        }
    }
}

/// On objectives that are not quadratic the least-squares gradient is a ratio estimator,
/// consistent for ∇f̄ with a bias of O(1/P): its mean is within the standard error plus
/// a bias allowance of max|∇f̄|/P of the closed form (P = 16n), and on the smooth
/// problem its spread is below the plain Gaussian estimator's at equal evaluations.
#[test]
fn regression_gradient_matches_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in problems(n).iter().enumerate() {
            let pairs = 16 * n;
            let spread = |method| {
                let mut mem = Memory::with_moments(n, 16);
                let mut ws = mem.ws(n);
                let mut est = Estimator::new(
                    SIGMA,
                    pairs,
                    Xoshiro256PlusPlus::seed_from_u64(40 + k as u64),
                )
                .unwrap();
                let mut f = |x: &[f64]| p.value(x);
                repeat(n, |g| {
                    est.gradient(method, &mut f, p.theta(), &mut ws, g).unwrap();
                })
            };
            let fitted = spread(GradientMethod::Regression);
            let expected = p.gradient(p.theta(), SIGMA);
            let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (j, (&m, &e)) in fitted.mean.iter().zip(&expected).enumerate() {
                let tol = Z_TOLERANCE * fitted.se[j] + scale / pairs as f64;
                assert!(
                    (m - e).abs() <= tol,
                    "regression n={n} problem {k} element {j}: mean {m} vs {e} (tolerance {tol})"
                );
            }
            if k == 0 {
                let plain = spread(GradientMethod::Gaussian);
                let (a, b) = (fitted.se.iter().sum::<f64>(), plain.se.iter().sum::<f64>());
                assert!(a < b, "n={n}: regression se {a} vs Gaussian {b}");
            }
        }
    }
}

/// The fit draws at least 2n + 2 pairs, and needs the workspace's moment region.
#[test]
fn regression_draws_enough_pairs_and_needs_a_moment_region() {
    let p = Problem::quadratic(3, 2);
    let mut f = |x: &[f64]| p.value(x);
    let mut g = [0.0; 3];
    let m = GradientMethod::Regression;
    assert_eq!((m.evaluations(3, 1), m.evaluations(3, 20)), (16, 40));
    let mut est = Estimator::new(SIGMA, 1, Xoshiro256PlusPlus::seed_from_u64(1)).unwrap();
    let mut plain = Memory::new(3, 8);
    assert_eq!(
        est.gradient(m, &mut f, p.theta(), &mut plain.ws(3), &mut g),
        Err(hodr_core::Error::WorkspaceTooSmall {
            needed: 12,
            available: 0
        })
    );
    let mut mem = Memory::with_moments(3, 8);
    let r = est.gradient(m, &mut f, p.theta(), &mut mem.ws(3), &mut g);
    assert_eq!(r.map(|r| r.evaluations), Ok(16));
}

/// An estimate's report names its lowest sample (value, noise seed, evaluation number,
/// point), its highest value and, for a lone antithetic pair around θ, both values:
/// checked against a log of every evaluation the estimate made.
#[test]
fn reports_carry_the_extremes_of_their_samples() {
    use hodr_core::Seeded;
    let n = 3;
    let p = Problem::sin_cos(n, 1);
    let mut mem = Memory::new(n, 16);
    let mut ws = mem.ws(n);
    for (pairs, method) in [
        (PAIRS, GradientMethod::Aggregate),
        (PAIRS, GradientMethod::Gaussian),
        (1, GradientMethod::Gaussian),
    ] {
        let mut est = Estimator::new(SIGMA, pairs, Xoshiro256PlusPlus::seed_from_u64(4)).unwrap();
        let mut log: Vec<(Vec<f64>, u64, f64)> = Vec::new();
        let mut f = Seeded(|x: &[f64], seed: u64| {
            let v = p.value(x);
            log.push((x.to_vec(), seed, v));
            v
        });
        let mut g = vec![0.0; n];
        let r = est
            .gradient(method, &mut f, p.theta(), &mut ws, &mut g)
            .unwrap();
        assert_eq!(log.len(), r.evaluations);
        let low = r.lowest.expect("samples were drawn");
        let (k, lowest) =
            log.iter().enumerate().fold(
                (0, &log[0]),
                |b, (k, e)| if e.2 < b.1.2 { (k, e) } else { b },
            );
        assert_eq!((low.value, low.seed, low.sample), (lowest.2, lowest.1, k));
        assert_eq!(ws.lowest_point(), &lowest.0[..]);
        let highest = log.iter().fold(f64::NEG_INFINITY, |m, e| m.max(e.2));
        assert_eq!(r.highest, Some(highest));
        assert_eq!(r.spread(), Some(highest - lowest.2));
        match r.pair {
            Some(pair) => {
                assert_eq!(pairs, 1);
                assert_eq!((pair.minus, pair.plus), (log[0].2, log[1].2));
                assert_eq!(pair.seed, log[0].1);
            }
            None => assert!(pairs > 1, "{method:?}: one pair, no pair values"),
        }
    }
}

/// An objective that counts its evaluations and asks to stop once it has made `limit`.
struct StopAfter {
    evaluations: usize,
    limit: usize,
}

impl hodr_core::Objective<f64> for StopAfter {
    fn evaluate(&mut self, x: &[f64], _seed: hodr_core::NoiseSeed) -> f64 {
        self.evaluations += 1;
        x.iter().map(|v| v * v).sum()
    }

    fn cancelled(&mut self) -> bool {
        self.evaluations >= self.limit
    }
}

/// A cancelling objective ends an estimate of 10⁶ pairs within one batch of its request.
#[test]
fn cancellation_ends_an_estimate_within_one_batch() {
    let rows = 16;
    let mut mem = Memory::new(3, rows);
    let mut ws = mem.ws(3);
    for m in GRADIENTS {
        let mut f = StopAfter {
            evaluations: 0,
            limit: 100,
        };
        let mut est = Estimator::new(0.5, 1_000_000, Xoshiro256PlusPlus::seed_from_u64(1)).unwrap();
        let mut g = [0.0; 3];
        let r = est.gradient(m, &mut f, &[1.0, 2.0, 3.0], &mut ws, &mut g);
        assert_eq!(r.err(), Some(hodr_core::Error::Cancelled), "{m:?}");
        assert!(
            (100..100 + rows).contains(&f.evaluations),
            "{m:?}: {} evaluations",
            f.evaluations
        );
    }
}
