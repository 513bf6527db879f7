//! Auto's own cost per objective evaluation: whole runs on the sphere f(θ) = θ·θ, whose
//! evaluation costs nanoseconds, so the time is the optimiser's (model fit, metric,
//! trust-region step, memory).
//!
//! Each measured run starts at θ₀ = (1, …, 1) with σ₀ = 1 and a budget of 100·n
//! evaluations; throughput is in evaluations, so criterion's "elem/s" inverts to the
//! time per evaluation.
//!
//! Run: `cargo bench -p hodr-core --bench auto`

#![allow(missing_docs)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hodr_core::optim::{Auto, AutoOptions};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// One run: evaluations spent.
fn run(n: usize, buffer: &mut [f64]) -> usize {
    let mut theta = vec![1.0; n];
    let options = AutoOptions::default()
        .with_max_evaluations(100 * n)
        .unwrap();
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        buffer,
        Xoshiro256PlusPlus::seed_from_u64(1),
    )
    .unwrap()
    .with_options(options);
    let mut sphere = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>();
    let mut evaluations = 0;
    while let Ok(Some(report)) = auto.step(&mut sphere) {
        evaluations = report.evaluations;
    }
    evaluations
}

fn auto(c: &mut Criterion) {
    let mut group = c.benchmark_group("auto/sphere");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for n in [2usize, 5, 10, 20, 50, 100] {
        let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
        let evaluations = run(n, &mut buffer);
        group.throughput(Throughput::Elements(evaluations as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| black_box(run(n, &mut buffer)))
        });
    }
    group.finish();
}

criterion_group!(benches, auto);
criterion_main!(benches);
