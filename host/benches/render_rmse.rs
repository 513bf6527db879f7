//! Samples per second and RMSE against a 1024-spp reference at 4, 16 and 64 spp, for
//! SHADOW, CBOX and CAUSTIC at 128×128 (θ = θ*), as a Markdown table. The reference is
//! rendered with the task's own (specialised) plan: CAUSTIC's, with its light pass,
//! filters the caustic with a tent where the general plan's path tracer uses the
//! pixel's box, so the general plan's RMSE there includes that difference.
//!
//! `cargo bench -p hodr-host --bench render_rmse` (all cores; set `RAYON_NUM_THREADS`
//! to pin the thread count, `RENDER_TASKS=SHADOW` to measure one task,
//! `RENDER_SEQUENCES=PaddedSobol` to measure one sequence with the specialised plan). Each
//! configuration renders once to warm up, then at least `MIN_REPEATS` times and for at
//! least `MIN_SECONDS`. Reported: the fastest wall time of a frame (the machine is
//! shared, and the fastest run is the least disturbed one), samples per second from it,
//! samples per CPU-second (process user + system time from `/proc/self/stat`, which
//! does not count time the threads waited for a core), and the RMSE over all renders
//! against the reference, which uses a different frame seed.

use std::time::Instant;

use hodr_host::render::{Film, Plan, Sequence, render_with_plan};
use hodr_host::tasks::{self, Task3d};

const SIZE: u32 = 128;
const REFERENCE_SPP: u32 = 1024;
const MIN_REPEATS: usize = 5;
const MIN_SECONDS: f64 = 1.0;

fn main() {
    println!(
        "| task | plan | sequence | spp | ms / frame | M samples/s | M samples / CPU-s | RMSE |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let only = std::env::var("RENDER_TASKS")
        .unwrap_or_default()
        .to_uppercase();
    for name in ["SHADOW", "CBOX", "CAUSTIC"] {
        if !only.is_empty() && !only.contains(name) {
            continue;
        }
        let task = tasks::by_name(name).expect("task exists");
        measure(task.as_ref());
    }
}

fn measure(task: &dyn Task3d) {
    let sequences = std::env::var("RENDER_SEQUENCES").unwrap_or_default();
    let mut scene = task.scene().expect("task scene");
    scene
        .set_params(&task.true_params())
        .expect("true parameters");
    let specialised = scene.scene().plan();
    let mut reference = Film::new(SIZE, SIZE).expect("film");
    render_with_plan(
        scene.scene(),
        &specialised,
        &mut reference,
        REFERENCE_SPP,
        0xBEEF,
    )
    .expect("reference");
    let mut film = Film::new(SIZE, SIZE).expect("film");
    for (plan_name, plan) in [("specialised", specialised), ("general", Plan::general())] {
        for sequence in [
            Sequence::Kronecker,
            Sequence::PaddedR2,
            Sequence::PaddedSobol,
            Sequence::Independent,
        ] {
            // Only the specialised plan is shown with every sequence.
            if plan_name == "general" && sequence != Sequence::Independent {
                continue;
            }
            if !sequences.is_empty()
                && (plan_name == "general" || !sequences.contains(&format!("{sequence:?}")))
            {
                continue;
            }
            for spp in [4u32, 16, 64] {
                let mut owned = task.scene().expect("task scene");
                owned
                    .set_params(&task.true_params())
                    .expect("true parameters");
                // The sequence is a render setting, not part of the task.
                let mut scene = owned.scene().clone();
                scene.set_sequence(sequence);
                render_with_plan(&scene, &plan, &mut film, spp, 1).expect("warm-up");
                let mut fastest = f64::INFINITY;
                let mut sq = 0.0;
                let (mut renders, cpu0, start) = (0usize, cpu_seconds(), Instant::now());
                while renders < MIN_REPEATS || start.elapsed().as_secs_f64() < MIN_SECONDS {
                    let t0 = Instant::now();
                    render_with_plan(&scene, &plan, &mut film, spp, 1 + renders as u64)
                        .expect("render");
                    fastest = fastest.min(t0.elapsed().as_secs_f64());
                    sq += film.mse(&reference).expect("same size");
                    renders += 1;
                }
                let cpu = (cpu_seconds() - cpu0) / renders as f64;
                let samples = f64::from(SIZE * SIZE * spp);
                println!(
                    "| {} | {plan_name} | {sequence:?} | {spp} | {:.2} | {:.2} | {:.2} | {:.4} |",
                    task.name(),
                    fastest * 1e3,
                    samples / fastest * 1e-6,
                    samples / cpu * 1e-6,
                    (sq / renders as f64).sqrt()
                );
            }
        }
    }
}

/// User + system CPU time of this process so far, in seconds (Linux; 0 elsewhere).
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // Clock ticks are 1/100 s on Linux (USER_HZ).
    (ticks(11) + ticks(12)) / 100.0
}
