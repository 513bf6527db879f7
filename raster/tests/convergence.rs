//! BOX2 and BOX10 converge from plateau starts with OurHVPA (hodr-core's preset: NCG +
//! aggregate gradient + aggregate central-difference HVP) and the tasks' settings.
//!
//! Seeds are fixed, so each test is deterministic: a change in the counts is a change
//! in behaviour, not bad luck. Stated fractions (measured with these budgets):
//!
//! * BOX2, 60 iterations: 10 of 10 seeds end within 0.1 units (0.8 px) of θ*;
//!   asserted ≥ 9 of 10.
//! * BOX10, 100 iterations: all five squares within 0.1 units in 1 of 8 seeds, and
//!   23 of 40 squares (57 %); asserted ≥ 1 seed and ≥ 50 % of squares. The usual
//!   failure is a square hiding under another square that sits on its own target:
//!   that removes the hidden square's own error, a genuine local minimum of the task.

use hodr_core::optim::preset::Preset;
use hodr_core::optim::{Budget, Optimiser};
use hodr_core::{Estimator, Workspace};
use hodr_raster::tasks::{self, Task};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// Runs OurHVPA on `task` from start `seed` for `iterations` iterations; returns the
/// final θ.
fn run(task: &Task, seed: u64, iterations: usize) -> Vec<f64> {
    let hyper = task.settings().hyper();
    let preset = Preset::OurHvpa;
    let method = preset.method(&hyper);
    let mut objective = task.objective().unwrap();
    let mut theta = task.start(seed);
    let start_loss = objective.loss(&theta).unwrap();
    let n = theta.len();
    let rows = 64;
    let mut buffer = vec![0.0; method.workspace_len(n, rows)];
    let mut seeds = vec![0; rows];
    let mut ws = Workspace::new(n, &mut buffer, &mut seeds).unwrap();
    let estimator = Estimator::new(
        hyper.sigma_start,
        hyper.pairs,
        Xoshiro256PlusPlus::seed_from_u64(1000 + seed),
    )
    .unwrap();
    let mut memory = vec![0.0; method.buffer_len(n)];
    let mut optimiser = Optimiser::new(
        method,
        preset.schedule(&hyper),
        Budget::iterations(iterations),
        estimator,
        &mut theta,
        &mut memory,
    )
    .unwrap();
    optimiser
        .run(&mut objective, &mut ws, || 0.0, |_, _| {})
        .unwrap();
    let theta = optimiser.theta().to_vec();
    let end_loss = objective.loss(&theta).unwrap();
    eprintln!(
        "{} seed {seed}: loss {start_loss:.5} -> {end_loss:.5}, |θ − θ*| {:.4}",
        task.name(),
        task.parameter_error(&theta)
    );
    theta
}

/// Per square: is its centre within `tolerance` of its target?
fn squares_converged(task: &Task, theta: &[f64], tolerance: f64) -> Vec<bool> {
    theta
        .chunks(2)
        .zip(task.theta_true().chunks(2))
        .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt() < tolerance)
        .collect()
}

#[test]
fn box2_converges_from_plateau_starts_with_ourhvpa() {
    let task = tasks::by_name("box2").unwrap();
    let passed = (0..10)
        .filter(|&seed| squares_converged(&task, &run(&task, seed, 60), 0.1)[0])
        .count();
    eprintln!("box2: {passed}/10 seeds converged");
    assert!(passed >= 9, "{passed}/10 seeds converged");
}

#[test]
fn box10_converges_from_plateau_starts_with_ourhvpa() {
    let task = tasks::by_name("box10").unwrap();
    let (mut all, mut squares) = (0, 0);
    for seed in 0..8 {
        let ok = squares_converged(&task, &run(&task, seed, 100), 0.1);
        squares += ok.iter().filter(|&&b| b).count();
        all += usize::from(ok.iter().all(|&b| b));
    }
    eprintln!("box10: {all}/8 seeds fully converged, {squares}/40 squares");
    assert!(
        all >= 1 && squares >= 20,
        "{all}/8 seeds, {squares}/40 squares"
    );
}
