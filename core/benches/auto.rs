//! Auto's own cost per objective evaluation: whole runs on functions whose evaluation
//! costs nanoseconds, so the time is the optimiser's (model fit, metric, trust-region
//! step, memory) — the sphere f(θ) = θ·θ; the separable ellipsoid
//! f(θ) = Σᵢ 10^(6i/(n−1)) (θᵢ − 0.3)², on which Auto takes many short iterations (a fit
//! each) while its metric learns the condition of 10⁶; and the same ellipsoid of Qθ for
//! the reflection Q = I − 2vvᵀ/‖v‖², v = (1, 2, …, n), which is not separable, so that
//! from n = 15 on, where the separability test hands the other two to the diagonal
//! model, it runs on the full model (to n = 127) with its metric's eigen-decompositions.
//!
//! Each measured run starts at θ₀ = (1, …, 1) with σ₀ = 1 and a budget of 100·n
//! evaluations (20·n for the rotated ellipsoid, whose iterations at n = 100 take
//! milliseconds); throughput is in evaluations, so criterion's "elem/s" inverts to the
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

/// The benchmark's objectives.
#[derive(Clone, Copy)]
enum Function {
    Sphere,
    Ellipsoid,
    RotatedEllipsoid,
}

impl Function {
    fn value(self, x: &[f64]) -> f64 {
        let ellipsoid = |y: &mut dyn Iterator<Item = f64>| -> f64 {
            let last = (x.len() - 1).max(1) as f64;
            y.enumerate()
                .map(|(i, v)| 10f64.powf(6.0 * i as f64 / last) * (v - 0.3) * (v - 0.3))
                .sum()
        };
        match self {
            Function::Sphere => x.iter().map(|v| v * v).sum(),
            Function::Ellipsoid => ellipsoid(&mut x.iter().copied()),
            Function::RotatedEllipsoid => {
                // Qx = x − 2v(v·x)/(v·v), v = (1, 2, …, n).
                let vv: f64 = (1..=x.len()).map(|i| (i * i) as f64).sum();
                let vx: f64 = x.iter().enumerate().map(|(i, v)| (i + 1) as f64 * v).sum();
                let factor = 2.0 * vx / vv;
                ellipsoid(
                    &mut x
                        .iter()
                        .enumerate()
                        .map(|(i, v)| v - factor * (i + 1) as f64),
                )
            }
        }
    }

    /// Evaluations per coordinate of a measured run.
    fn budget_per_dim(self) -> usize {
        match self {
            Function::RotatedEllipsoid => 20,
            _ => 100,
        }
    }
}

/// One run: evaluations spent.
fn run(function: Function, n: usize, buffer: &mut [f64]) -> usize {
    let mut theta = vec![1.0; n];
    let options = AutoOptions::default()
        .with_max_evaluations(function.budget_per_dim() * n)
        .unwrap();
    let mut auto = Auto::new(
        &mut theta,
        1.0,
        buffer,
        Xoshiro256PlusPlus::seed_from_u64(1),
    )
    .unwrap()
    .with_options(options);
    let mut f = |x: &[f64]| function.value(x);
    let mut evaluations = 0;
    while let Ok(Some(report)) = auto.step(&mut f) {
        evaluations = report.evaluations;
    }
    evaluations
}

fn auto(c: &mut Criterion) {
    for (name, function) in [
        ("auto/sphere", Function::Sphere),
        ("auto/ellipsoid", Function::Ellipsoid),
        ("auto/rotated-ellipsoid", Function::RotatedEllipsoid),
    ] {
        let mut group = c.benchmark_group(name);
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(3))
            .sample_size(10);
        for n in [2usize, 5, 10, 20, 30, 40, 50, 100] {
            let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(n)];
            let evaluations = run(function, n, &mut buffer);
            group.throughput(Throughput::Elements(evaluations as u64));
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
                b.iter(|| black_box(run(function, n, &mut buffer)))
            });
        }
        group.finish();
    }
}

criterion_group!(benches, auto);
criterion_main!(benches);
