//! Wall time of one BOX2-REF loss evaluation where each method spends its evaluations:
//! on the plateau (no overlap: θ's box and the target's precomputed energy), at a
//! partial overlap, and near the target (both boxes over the same pixels).
//!
//! `cargo bench -p hodr-host --bench box2ref`

use criterion::{Criterion, criterion_group, criterion_main};
use hodr_host::box2ref::Box2Ref;
use std::hint::black_box;

fn loss(c: &mut Criterion) {
    let objective = Box2Ref::new();
    let mut group = c.benchmark_group("box2ref/loss");
    for (label, theta) in [
        ("plateau", [300.3, 320.7]),
        ("partial", [190.3, 170.7]),
        ("near", [151.3, 149.6]),
    ] {
        group.bench_function(label, |b| b.iter(|| objective.loss(black_box(&theta))));
    }
    group.finish();
}

criterion_group!(benches, loss);
criterion_main!(benches);
