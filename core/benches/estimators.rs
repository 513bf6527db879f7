//! Estimator overhead per objective evaluation, with a trivial objective f(θ) = θ₀.
//!
//! Throughput is reported in objective evaluations per second, so criterion's
//! "elem/s" inverts to the overhead per evaluation: drawing the offsets (inverse CDFs),
//! placing the points, and accumulating the weights.
//!
//! Run: `cargo bench -p hodr-core --bench estimators`

#![allow(missing_docs)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hodr_core::{Draws, Estimator, GradientMethod, HessianMethod, HvpMethod, Real, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

const PAIRS: usize = 8;
const ROWS: usize = 64;

fn bench_precision<T: Real>(c: &mut Criterion, label: &str) {
    let mut group = c.benchmark_group(format!("estimate/{label}"));
    group
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(20);
    for n in [2usize, 10, 1024] {
        let theta = vec![T::HALF; n];
        let v = vec![T::ONE; n];
        let mut buffer = vec![T::ZERO; Workspace::<T>::buffer_len(n, ROWS)];
        let mut seeds = vec![0u64; ROWS];
        let mut ws = Workspace::new(n, &mut buffer, &mut seeds).unwrap();
        let mut est = Estimator::new(T::HALF, PAIRS, Xoshiro256PlusPlus::seed_from_u64(1)).unwrap();
        let mut f = |x: &[T]| x[0];
        let mut out = vec![T::ZERO; n];

        let gradients = [
            ("fr22", GradientMethod::Fr22),
            ("per-element", GradientMethod::PerElement),
            ("aggregate", GradientMethod::Aggregate),
            ("gaussian", GradientMethod::Gaussian),
        ];
        for (name, m) in gradients {
            group.throughput(Throughput::Elements(m.evaluations(n, PAIRS) as u64));
            group.bench_function(BenchmarkId::new(format!("gradient/{name}"), n), |b| {
                b.iter(|| {
                    est.gradient(m, &mut f, black_box(&theta), &mut ws, &mut out)
                        .unwrap()
                })
            });
        }

        let hvps = [
            (
                "cd-aggregate-crn",
                HvpMethod::CentralDifference {
                    gradient: GradientMethod::Aggregate,
                    draws: Draws::Common,
                },
            ),
            ("kernel", HvpMethod::Kernel),
        ];
        for (name, m) in hvps {
            group.throughput(Throughput::Elements(m.evaluations(n, PAIRS) as u64));
            group.bench_function(BenchmarkId::new(format!("hvp/{name}"), n), |b| {
                b.iter(|| {
                    est.hvp(m, &mut f, black_box(&theta), &v, &mut ws, &mut out)
                        .unwrap()
                })
            });
        }

        let mut hess = vec![T::ZERO; n * n];
        let mut hessians = vec![
            ("aggregate", HessianMethod::Aggregate),
            ("gaussian", HessianMethod::Gaussian),
        ];
        if n <= 10 {
            hessians.push(("per-element", HessianMethod::PerElement));
        }
        for (name, m) in hessians {
            group.throughput(Throughput::Elements(m.evaluations(n, PAIRS) as u64));
            group.bench_function(BenchmarkId::new(format!("hessian/{name}"), n), |b| {
                b.iter(|| {
                    est.hessian(m, &mut f, black_box(&theta), &mut ws, &mut hess)
                        .unwrap()
                })
            });
        }
    }
    group.finish();
}

fn estimators(c: &mut Criterion) {
    bench_precision::<f64>(c, "f64");
    bench_precision::<f32>(c, "f32");
}

criterion_group!(benches, estimators);
criterion_main!(benches);
