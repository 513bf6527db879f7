//! The estimator plumbing through the public API: errors, determinism across batch
//! capacities, extreme σ. (hodr-core's own sources stay free of std, so these live here;
//! the statistical checks against closed forms are in the hodr-tests crate.)

#[cfg(feature = "hessian")]
use hodr_core::HessianMethod;
#[cfg(feature = "hvp")]
use hodr_core::{Draws, HvpMethod};
use hodr_core::{Error, Estimator, GradientMethod, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

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

fn gradient_methods() -> Vec<GradientMethod> {
    [
        GradientMethod::Fr22,
        #[cfg(feature = "per-element")]
        GradientMethod::PerElement,
        #[cfg(feature = "gaussian")]
        GradientMethod::Gaussian,
        #[cfg(feature = "aggregate")]
        GradientMethod::Aggregate,
    ]
    .to_vec()
}

#[cfg(feature = "hessian")]
fn hessian_methods() -> Vec<HessianMethod> {
    [
        HessianMethod::PerElement,
        HessianMethod::Gaussian,
        #[cfg(feature = "aggregate")]
        HessianMethod::Aggregate,
    ]
    .to_vec()
}

/// A smooth non-separable objective: sin(a·x) + x₀x₁.
fn wave(x: &[f64]) -> f64 {
    let a = x
        .iter()
        .enumerate()
        .fold(0.0, |s, (k, v)| s + (0.3 + 0.1 * k as f64) * v);
    libm::sin(a) + x[0] * x[x.len() - 1]
}

/// ½|x|² + Σ x.
fn bowl(x: &[f64]) -> f64 {
    x.iter().map(|v| 0.5 * v * v + v).sum()
}

/// Offsets are drawn in group order whatever the batch capacity, so the capacity never
/// changes an estimate.
#[test]
fn same_seed_same_numbers_whatever_the_batch_capacity() {
    let theta: Vec<f64> = (0..10).map(|k| 0.1 * k as f64 - 0.4).collect();
    let mut f: fn(&[f64]) -> f64 = wave;
    let run = |rows: usize, f: &mut fn(&[f64]) -> f64| {
        let mut bench = Bench::new(10, rows);
        let mut ws = bench.ws(10);
        let mut est = Estimator::new(0.5, 5, Xoshiro256PlusPlus::seed_from_u64(99)).unwrap();
        let mut all = Vec::new();
        let mut out = vec![0.0; 10];
        for m in gradient_methods() {
            est.gradient(m, f, &theta, &mut ws, &mut out).unwrap();
            all.extend_from_slice(&out);
        }
        #[cfg(feature = "hessian")]
        for m in hessian_methods() {
            let mut h = vec![0.0; 100];
            est.hessian(m, f, &theta, &mut ws, &mut h).unwrap();
            all.extend_from_slice(&h);
        }
        #[cfg(feature = "hvp")]
        for draws in [Draws::Independent, Draws::Common] {
            let m = HvpMethod::CentralDifference {
                gradient: GradientMethod::Fr22,
                draws,
            };
            est.hvp(m, f, &theta, &theta, &mut ws, &mut out).unwrap();
            all.extend_from_slice(&out);
        }
        all
    };
    let reference = run(4, &mut f);
    for rows in [5, 6, 64, 1000] {
        assert_eq!(reference, run(rows, &mut f), "rows = {rows}");
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
            GradientMethod::Fr22,
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
            GradientMethod::Fr22,
            &mut ok,
            &[1.0, f64::NAN],
            &mut ws,
            &mut g
        ),
        Err(Error::NonFiniteInput { index: 1 })
    );
    // NaN on the far side: sample index and point are reported.
    let mut bad = |x: &[f64]| if x[0] > 3.0 { f64::NAN } else { 0.0 };
    let err = est.gradient(GradientMethod::Fr22, &mut bad, &[2.5, 0.0], &mut ws, &mut g);
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

#[test]
fn extreme_sigmas_stay_finite() {
    for sigma in [1e-12, 1e-6, 1.0, 1e6, 1e12] {
        let theta = [0.5, -0.25, 1.0];
        let mut f = bowl;
        let mut bench = Bench::new(3, 8);
        let mut ws = bench.ws(3);
        let mut est = Estimator::new(sigma, 4, Xoshiro256PlusPlus::seed_from_u64(2)).unwrap();
        let mut g = [0.0; 3];
        for m in gradient_methods() {
            est.gradient(m, &mut f, &theta, &mut ws, &mut g).unwrap();
            assert!(g.iter().all(|x| x.is_finite()), "σ={sigma} {m:?}");
        }
        #[cfg(feature = "hessian")]
        {
            let mut h = [0.0; 9];
            for m in hessian_methods() {
                est.hessian(m, &mut f, &theta, &mut ws, &mut h).unwrap();
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
        // θ's largest coordinate is 1: σ at or below 8ε resolves nothing there.
        let unresolved = sigma as f32 <= 8.0 * f32::EPSILON;
        for m in gradient_methods() {
            match est32.gradient(m, &mut f32q, &theta32, &mut ws32, &mut g32) {
                Ok(_) => assert!(!unresolved && g32.iter().all(|x| x.is_finite())),
                Err(Error::InvalidSigma) => assert!(unresolved, "σ={sigma} {m:?}"),
                Err(e) => assert!(matches!(e, Error::NonFiniteEstimate { .. })),
            }
        }
    }
}
