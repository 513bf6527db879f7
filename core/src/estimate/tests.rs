//! The estimators against closed-form smoothed derivatives.
//!
//! Each check repeats an estimate M times at a fixed seed and compares the mean with the
//! closed form, allowing [`Z_TOLERANCE`] standard errors (the standard error estimated
//! from the M repetitions) plus a floor for elements whose estimate has no variance.
//!
//! Test functions, with Φ/φ the normal CDF/density and e_a = exp(−σ²|a|²/2):
//! * sin/cos: f = sin(a·x) + 0.3 cos(b·x); ∇f̄ = e_a cos(a·θ) a − 0.3 e_b sin(b·θ) b,
//!   ∇²f̄ = −e_a sin(a·θ) aaᵀ − 0.3 e_b cos(b·θ) bbᵀ;
//! * quadratic: f = ½xᵀAx + cᵀx; ∇f̄ = Aθ + c, ∇²f̄ = A (smoothing adds a constant);
//! * step along a unit u: f = 1[u·x > s]; with z = (u·θ − s)/σ, f̄ = Φ(z),
//!   ∇f̄ = φ(z)/σ·u, ∇²f̄ = −zφ(z)/σ²·uuᵀ.

use std::vec;
use std::vec::Vec;

use rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::*;
use crate::sample::normal;
use crate::workspace::Workspace;

/// Allowed deviation of a mean from its expectation, in standard errors. With fixed
/// seeds a test is deterministic; 5 SE makes a false alarm across all elements of all
/// tests (~10⁴) improbable when choosing seeds.
const Z_TOLERANCE: f64 = 5.0;

/// Repetitions per check.
const REPEATS: usize = 1000;

#[derive(Clone)]
struct Problem {
    n: usize,
    theta: Vec<f64>,
    kind: Kind,
}

#[derive(Clone)]
enum Kind {
    SinCos {
        a: Vec<f64>,
        b: Vec<f64>,
    },
    Quadratic {
        a: Vec<f64>,
        c: Vec<f64>,
    },
    Step {
        u: Vec<f64>,
        s: f64,
    },
    /// Σₖ sin(aₖxₖ) + 0.3 cos(bₖxₖ): separable, so FR22 is exact.
    Separable {
        a: Vec<f64>,
        b: Vec<f64>,
    },
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

impl Problem {
    fn value(&self, x: &[f64]) -> f64 {
        match &self.kind {
            Kind::SinCos { a, b } => libm::sin(dot(a, x)) + 0.3 * libm::cos(dot(b, x)),
            Kind::Quadratic { a, c } => {
                let n = self.n;
                let mut q = 0.0;
                for i in 0..n {
                    for j in 0..n {
                        q += 0.5 * x[i] * a[i * n + j] * x[j];
                    }
                }
                q + dot(c, x)
            }
            Kind::Step { u, s } => {
                if dot(u, x) > *s {
                    1.0
                } else {
                    0.0
                }
            }
            Kind::Separable { a, b } => (0..self.n)
                .map(|k| libm::sin(a[k] * x[k]) + 0.3 * libm::cos(b[k] * x[k]))
                .sum(),
        }
    }

    fn gradient(&self, theta: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        match &self.kind {
            Kind::SinCos { a, b } => {
                let ea = libm::exp(-0.5 * sigma * sigma * dot(a, a));
                let eb = libm::exp(-0.5 * sigma * sigma * dot(b, b));
                let (ca, sb) = (libm::cos(dot(a, theta)), libm::sin(dot(b, theta)));
                (0..n)
                    .map(|i| ea * ca * a[i] - 0.3 * eb * sb * b[i])
                    .collect()
            }
            Kind::Quadratic { a, c } => (0..n)
                .map(|i| (0..n).map(|j| a[i * n + j] * theta[j]).sum::<f64>() + c[i])
                .collect(),
            Kind::Step { u, s } => {
                let z = (dot(u, theta) - s) / sigma;
                u.iter().map(|ui| normal::pdf(z) / sigma * ui).collect()
            }
            Kind::Separable { a, b } => (0..n)
                .map(|k| {
                    let ea = libm::exp(-0.5 * sigma * sigma * a[k] * a[k]);
                    let eb = libm::exp(-0.5 * sigma * sigma * b[k] * b[k]);
                    ea * a[k] * libm::cos(a[k] * theta[k])
                        - 0.3 * eb * b[k] * libm::sin(b[k] * theta[k])
                })
                .collect(),
        }
    }

    fn hessian(&self, theta: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        let mut h = vec![0.0; n * n];
        match &self.kind {
            Kind::SinCos { a, b } => {
                let ea = libm::exp(-0.5 * sigma * sigma * dot(a, a));
                let eb = libm::exp(-0.5 * sigma * sigma * dot(b, b));
                let (sa, cb) = (libm::sin(dot(a, theta)), libm::cos(dot(b, theta)));
                for i in 0..n {
                    for j in 0..n {
                        h[i * n + j] = -ea * sa * a[i] * a[j] - 0.3 * eb * cb * b[i] * b[j];
                    }
                }
            }
            Kind::Quadratic { a, .. } => h.copy_from_slice(a),
            Kind::Step { u, s } => {
                let z = (dot(u, theta) - s) / sigma;
                for i in 0..n {
                    for j in 0..n {
                        h[i * n + j] = -z * normal::pdf(z) / (sigma * sigma) * u[i] * u[j];
                    }
                }
            }
            Kind::Separable { a, b } => {
                for k in 0..n {
                    let ea = libm::exp(-0.5 * sigma * sigma * a[k] * a[k]);
                    let eb = libm::exp(-0.5 * sigma * sigma * b[k] * b[k]);
                    h[k * n + k] = -ea * a[k] * a[k] * libm::sin(a[k] * theta[k])
                        - 0.3 * eb * b[k] * b[k] * libm::cos(b[k] * theta[k]);
                }
            }
        }
        h
    }

    fn hvp(&self, theta: &[f64], v: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        let h = self.hessian(theta, sigma);
        (0..n).map(|i| dot(&h[i * n..(i + 1) * n], v)).collect()
    }

    /// The expectation of the central-difference HVP: the exact central difference of
    /// the smoothed gradient with ε = σ/3.
    fn hvp_central(&self, theta: &[f64], v: &[f64], sigma: f64) -> Vec<f64> {
        let norm = libm::sqrt(dot(v, v));
        let eps = sigma / 3.0;
        let shift = |s: f64| -> Vec<f64> {
            theta
                .iter()
                .zip(v)
                .map(|(t, d)| t + s * eps * d / norm)
                .collect()
        };
        let gp = self.gradient(&shift(1.0), sigma);
        let gm = self.gradient(&shift(-1.0), sigma);
        gp.iter()
            .zip(&gm)
            .map(|(p, m)| (p - m) / (2.0 * eps) * norm)
            .collect()
    }
}

/// Deterministic pseudo-random problem data.
fn data(n: usize, salt: u64, scale: f64) -> Vec<f64> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1000 + salt);
    (0..n)
        .map(|_| scale * (2.0 * f64::uniform_open(&mut rng) - 1.0))
        .collect()
}

fn sincos(n: usize) -> Problem {
    Problem {
        n,
        theta: data(n, 1, 1.0),
        kind: Kind::SinCos {
            a: data(n, 2, 1.2),
            b: data(n, 3, 0.9),
        },
    }
}

fn separable(n: usize) -> Problem {
    Problem {
        n,
        theta: data(n, 4, 1.0),
        kind: Kind::Separable {
            a: data(n, 5, 1.5),
            b: data(n, 6, 1.0),
        },
    }
}

fn quadratic(n: usize) -> Problem {
    // A = MᵀM + I (symmetric positive definite) plus a symmetric indefinite part.
    let m = data(n * n, 7, 1.0);
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            a[i * n + j] = (0..n).map(|k| m[k * n + i] * m[k * n + j]).sum::<f64>() / n as f64
                + if i == j { 1.0 } else { 0.0 };
        }
    }
    Problem {
        n,
        theta: data(n, 8, 1.0),
        kind: Kind::Quadratic {
            a,
            c: data(n, 9, 1.0),
        },
    }
}

fn step(n: usize) -> Problem {
    let raw = data(n, 10, 1.0);
    let norm = libm::sqrt(dot(&raw, &raw));
    let u: Vec<f64> = raw.iter().map(|x| x / norm).collect();
    // θ so that u·θ − s = 0.6σ at σ = 0.5: inside the smoothed ramp.
    let theta = data(n, 11, 1.0);
    let s = dot(&u, &theta) - 0.3;
    Problem {
        n,
        theta,
        kind: Kind::Step { u, s },
    }
}

struct Stats {
    mean: Vec<f64>,
    se: Vec<f64>,
}

/// Mean and standard error of `REPEATS` estimates of length `len`.
fn repeat(len: usize, mut one: impl FnMut(&mut [f64])) -> Stats {
    let mut sum = vec![0.0; len];
    let mut sum2 = vec![0.0; len];
    let mut x = vec![0.0; len];
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
        .map(|k| libm::sqrt(((sum2[k] / m - mean[k] * mean[k]).max(0.0)) / (m - 1.0)))
        .collect();
    Stats { mean, se }
}

fn assert_matches(stats: &Stats, expected: &[f64], label: &str) {
    let scale = expected.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
    for (k, (&m, &e)) in stats.mean.iter().zip(expected).enumerate() {
        let tol = Z_TOLERANCE * stats.se[k] + 1e-9 * scale;
        assert!(
            (m - e).abs() <= tol,
            "{label}: element {k}: mean {m} vs expected {e} (tolerance {tol}, se {})",
            stats.se[k]
        );
    }
}

struct Bench {
    buffer: Vec<f64>,
    seeds: Vec<u64>,
}

impl Bench {
    fn new(n: usize, rows: usize) -> Self {
        Bench {
            buffer: vec![0.0; Workspace::<f64>::buffer_len(n, rows)],
            seeds: vec![0; rows],
        }
    }
    fn ws(&mut self, n: usize) -> Workspace<'_, f64> {
        Workspace::new(n, &mut self.buffer, &mut self.seeds).unwrap()
    }
}

const SIGMA: f64 = 0.5;

fn gradient_methods() -> Vec<GradientMethod> {
    let mut m = vec![GradientMethod::PerElement, GradientMethod::Gaussian];
    #[cfg(feature = "aggregate")]
    m.push(GradientMethod::Aggregate);
    m
}

fn check_gradient(p: &Problem, method: GradientMethod, pairs: usize, seed: u64) {
    let n = p.n;
    let mut bench = Bench::new(n, 16);
    let mut ws = bench.ws(n);
    let mut est = Estimator::new(SIGMA, pairs, Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(n, |g| {
        let r = est.gradient(method, &mut f, &p.theta, &mut ws, g).unwrap();
        assert_eq!(r.evaluations, method.evaluations(n, pairs));
    });
    assert_matches(
        &stats,
        &p.gradient(&p.theta, SIGMA),
        &std::format!("{method:?} gradient n={n}"),
    );
}

#[test]
fn gradients_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in [sincos(n), quadratic(n), step(n)].iter().enumerate() {
            for m in gradient_methods() {
                check_gradient(p, m, 8, 17 + k as u64);
            }
        }
    }
}

#[test]
fn fr22_matches_closed_forms_where_it_is_exact() {
    for n in [1, 3, 10] {
        let axis_step = {
            let mut u = vec![0.0; n];
            u[n - 1] = 1.0;
            let theta = data(n, 12, 1.0);
            let s = theta[n - 1] - 0.2;
            Problem {
                n,
                theta,
                kind: Kind::Step { u, s },
            }
        };
        for p in [separable(n), quadratic(n), axis_step] {
            check_gradient(&p, GradientMethod::Fr22, 8, 23);
        }
    }
}

#[cfg(feature = "hessian")]
fn hessian_methods() -> Vec<HessianMethod> {
    let mut m = vec![HessianMethod::PerElement, HessianMethod::Gaussian];
    #[cfg(feature = "aggregate")]
    m.push(HessianMethod::Aggregate);
    m
}

#[cfg(feature = "hessian")]
#[test]
fn hessians_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in [sincos(n), quadratic(n), step(n)].iter().enumerate() {
            for method in hessian_methods() {
                let pairs = 8;
                let mut bench = Bench::new(n, 32);
                let mut ws = bench.ws(n);
                let mut est = Estimator::new(
                    SIGMA,
                    pairs,
                    Xoshiro256PlusPlus::seed_from_u64(31 + k as u64),
                )
                .unwrap();
                let mut f = |x: &[f64]| p.value(x);
                let stats = repeat(n * n, |h| {
                    let r = est.hessian(method, &mut f, &p.theta, &mut ws, h).unwrap();
                    assert_eq!(r.evaluations, method.evaluations(n, pairs));
                    assert_eq!(r.centre_value, Some(p.value(&p.theta)));
                    for i in 0..n {
                        for j in 0..n {
                            assert_eq!(h[i * n + j], h[j * n + i]);
                        }
                    }
                });
                assert_matches(
                    &stats,
                    &p.hessian(&p.theta, SIGMA),
                    &std::format!("{method:?} Hessian n={n} problem {k}"),
                );
            }
        }
    }
}

#[cfg(feature = "hvp")]
fn check_hvp(p: &Problem, method: HvpMethod, seed: u64) -> Stats {
    let n = p.n;
    let pairs = 8;
    let v = data(n, 40, 2.0);
    let mut bench = Bench::new(n, 8);
    let mut ws = bench.ws(n);
    let mut est = Estimator::new(SIGMA, pairs, Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(n, |hv| {
        let r = est.hvp(method, &mut f, &p.theta, &v, &mut ws, hv).unwrap();
        assert_eq!(r.evaluations, method.evaluations(n, pairs));
    });
    let expected = match method {
        HvpMethod::Kernel => p.hvp(&p.theta, &v, SIGMA),
        _ => p.hvp_central(&p.theta, &v, SIGMA),
    };
    assert_matches(&stats, &expected, &std::format!("{method:?} HVP n={n}"));
    stats
}

#[cfg(feature = "hvp")]
#[test]
fn hvps_match_closed_forms() {
    for n in [1, 3, 10] {
        for (k, p) in [sincos(n), quadratic(n), step(n)].iter().enumerate() {
            check_hvp(p, HvpMethod::Kernel, 50 + k as u64);
            for gradient in gradient_methods() {
                for draws in [Draws::Independent, Draws::Common] {
                    check_hvp(
                        p,
                        HvpMethod::CentralDifference { gradient, draws },
                        60 + k as u64,
                    );
                }
            }
        }
    }
}

/// Common random numbers and independent draws estimate the same thing; on a smooth
/// objective the common ones have far smaller variance.
#[cfg(feature = "hvp")]
#[test]
fn common_random_numbers_agree_in_mean_and_cut_variance() {
    let p = sincos(3);
    for gradient in gradient_methods() {
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
            let both = libm::sqrt(ind.se[k] * ind.se[k] + crn.se[k] * crn.se[k]);
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

#[cfg(feature = "hvp")]
#[test]
fn gradient_and_hvp_share_samples() {
    let p = sincos(3);
    let v = data(3, 41, 1.0);
    let mut bench = Bench::new(3, 8);
    let mut ws = bench.ws(3);
    let mut est = Estimator::new(SIGMA, 8, Xoshiro256PlusPlus::seed_from_u64(5)).unwrap();
    let mut f = |x: &[f64]| p.value(x);
    let stats = repeat(6, |out| {
        let (g, h) = out.split_at_mut(3);
        let r = est
            .gradient_and_hvp(&mut f, &p.theta, &v, &mut ws, g, h)
            .unwrap();
        assert_eq!(r.evaluations, 17);
    });
    let mut expected = p.gradient(&p.theta, SIGMA);
    expected.extend(p.hvp(&p.theta, &v, SIGMA));
    assert_matches(&stats, &expected, "gradient_and_hvp");
}

#[test]
fn f32_gradient_matches_closed_form() {
    let p = sincos(3);
    let theta: Vec<f32> = p.theta.iter().map(|&x| x as f32).collect();
    let mut buffer = vec![0.0f32; Workspace::<f32>::buffer_len(3, 8)];
    let mut seeds = vec![0; 8];
    let mut ws = Workspace::new(3, &mut buffer, &mut seeds).unwrap();
    let mut est = Estimator::new(SIGMA as f32, 8, Xoshiro256PlusPlus::seed_from_u64(3)).unwrap();
    let mut f = |x: &[f32]| {
        let x64: Vec<f64> = x.iter().map(|&v| v as f64).collect();
        p.value(&x64) as f32
    };
    let mut g32 = [0.0f32; 3];
    let stats = repeat(3, |g| {
        est.gradient(GradientMethod::Gaussian, &mut f, &theta, &mut ws, &mut g32)
            .unwrap();
        for k in 0..3 {
            g[k] = g32[k] as f64;
        }
    });
    let theta64: Vec<f64> = theta.iter().map(|&x| x as f64).collect();
    assert_matches(
        &stats,
        &p.gradient(&theta64, SIGMA),
        "f32 Gaussian gradient",
    );
}

#[test]
fn same_seed_same_numbers_whatever_the_batch_capacity() {
    let p = sincos(10);
    let mut f = |x: &[f64]| p.value(x);
    let mut results = Vec::new();
    for rows in [4, 6, 64, 1000] {
        let mut bench = Bench::new(10, rows);
        let mut ws = bench.ws(10);
        let mut est = Estimator::new(SIGMA, 5, Xoshiro256PlusPlus::seed_from_u64(99)).unwrap();
        let mut out = vec![0.0; 10];
        for m in gradient_methods() {
            est.gradient(m, &mut f, &p.theta, &mut ws, &mut out)
                .unwrap();
            results.push(out.clone());
        }
        results.push(vec![f64::NAN]); // separator
    }
    let per = results.len() / 4;
    for r in 1..4 {
        assert_eq!(results[..per - 1], results[r * per..(r + 1) * per - 1]);
    }
}

#[test]
fn errors_are_values() {
    let mut bench = Bench::new(2, 4);
    let mut ws = bench.ws(2);
    let rng = || Xoshiro256PlusPlus::seed_from_u64(1);
    assert_eq!(
        Estimator::new(0.0, 1, rng()).err(),
        Some(Error::InvalidSigma)
    );
    assert_eq!(
        Estimator::new(-1.0, 1, rng()).err(),
        Some(Error::InvalidSigma)
    );
    assert_eq!(
        Estimator::new(f64::NAN, 1, rng()).err(),
        Some(Error::InvalidSigma)
    );
    assert_eq!(
        Estimator::new(f64::INFINITY, 1, rng()).err(),
        Some(Error::InvalidSigma)
    );
    assert_eq!(Estimator::new(1.0, 0, rng()).err(), Some(Error::NoSamples));
    let mut est = Estimator::new(1.0, 2, rng()).unwrap();
    assert_eq!(est.set_sigma(-2.0), Err(Error::InvalidSigma));
    assert_eq!(est.sigma(), 1.0);

    let mut g = [0.0; 2];
    let mut ok = |x: &[f64]| x[0];
    assert_eq!(
        est.gradient(
            GradientMethod::Gaussian,
            &mut ok,
            &[1.0, 2.0, 3.0],
            &mut ws,
            &mut g
        ),
        Err(Error::DimensionMismatch {
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        est.gradient(
            GradientMethod::Gaussian,
            &mut ok,
            &[1.0, f64::NAN],
            &mut ws,
            &mut g
        ),
        Err(Error::NonFiniteInput { index: 1 })
    );
    // NaN on the far side: sample index and point are reported.
    let mut bad = |x: &[f64]| if x[0] > 3.0 { f64::NAN } else { 0.0 };
    let err = est.gradient(
        GradientMethod::Gaussian,
        &mut bad,
        &[2.5, 0.0],
        &mut ws,
        &mut g,
    );
    match err {
        Err(Error::NonFiniteObjective { .. }) => {
            let p = ws.failed_point().unwrap();
            assert!(p[0] > 3.0 && bad(p).is_nan());
        }
        other => panic!("expected NonFiniteObjective, got {other:?}"),
    }
    let mut buf = [0.0; 4];
    let mut seeds = [0u64; 4];
    assert!(matches!(
        Workspace::new(2, &mut buf, &mut seeds),
        Err(Error::WorkspaceTooSmall { .. })
    ));
    let mut seeds3 = [0u64; 3];
    let mut big = [0.0; 100];
    assert_eq!(
        Workspace::new(2, &mut big, &mut seeds3).err(),
        Some(Error::WorkspaceTooSmall {
            needed: 4,
            available: 3
        })
    );
}

#[cfg(feature = "hessian")]
#[test]
fn nan_centre_is_reported_as_sample_zero() {
    let mut bench = Bench::new(2, 4);
    let mut ws = bench.ws(2);
    let mut est = Estimator::new(1.0, 2, Xoshiro256PlusPlus::seed_from_u64(1)).unwrap();
    let mut f = |_: &[f64]| f64::INFINITY;
    let mut h = [0.0; 4];
    assert_eq!(
        est.hessian(
            HessianMethod::Gaussian,
            &mut f,
            &[4.0, 5.0],
            &mut ws,
            &mut h
        ),
        Err(Error::NonFiniteObjective { sample: 0 })
    );
    assert_eq!(ws.failed_point(), Some(&[4.0, 5.0][..]));
}

#[cfg(feature = "hessian")]
#[test]
fn upper_triangle_numbering() {
    for n in [1, 2, 3, 7, 64, 1024] {
        let mut c = 0;
        for i in 0..n {
            for j in i..n {
                assert_eq!(upper_triangle(c, n), (i, j), "n={n} c={c}");
                c += 1;
            }
        }
    }
}

#[test]
fn extreme_sigmas_stay_finite() {
    for sigma in [1e-12, 1e-6, 1.0, 1e6, 1e12] {
        let p = quadratic(3);
        let mut f = |x: &[f64]| p.value(x);
        let mut bench = Bench::new(3, 8);
        let mut ws = bench.ws(3);
        let mut est = Estimator::new(sigma, 4, Xoshiro256PlusPlus::seed_from_u64(2)).unwrap();
        let mut g = [0.0; 3];
        for m in gradient_methods() {
            est.gradient(m, &mut f, &p.theta, &mut ws, &mut g).unwrap();
            assert!(g.iter().all(|x| x.is_finite()), "σ={sigma} {m:?}");
        }
        #[cfg(feature = "hessian")]
        {
            let mut h = [0.0; 9];
            for m in hessian_methods() {
                est.hessian(m, &mut f, &p.theta, &mut ws, &mut h).unwrap();
                assert!(h.iter().all(|x| x.is_finite()), "σ={sigma} {m:?}");
            }
        }
        let mut g32 = [0.0f32; 3];
        let theta32 = [0.5f32, -0.25, 1.0];
        let mut b32 = vec![0.0f32; Workspace::<f32>::buffer_len(3, 8)];
        let mut s32 = vec![0; 8];
        let mut ws32 = Workspace::new(3, &mut b32, &mut s32).unwrap();
        let mut est32 =
            Estimator::new(sigma as f32, 4, Xoshiro256PlusPlus::seed_from_u64(2)).unwrap();
        let mut f32q = |x: &[f32]| x.iter().map(|v| v * v).sum::<f32>();
        for m in gradient_methods() {
            match est32.gradient(m, &mut f32q, &theta32, &mut ws32, &mut g32) {
                Ok(_) => assert!(g32.iter().all(|x| x.is_finite())),
                Err(e) => assert!(matches!(e, Error::NonFiniteEstimate { .. })),
            }
        }
    }
}
