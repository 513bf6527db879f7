//! Wall time of one 128×128, 16-spp render per task, with the scene's specialised
//! [`Plan`] against the unspecialised [`Plan::general`] (scene specialisation, issue 5
//! item 5).
//!
//! `cargo bench -p hodr-host --bench render`

use criterion::{Criterion, criterion_group, criterion_main};
use hodr_host::render::{Film, Plan, render_with_plan};
use hodr_host::tasks;

const SIZE: u32 = 128;
const SPP: u32 = 16;

fn specialisation(c: &mut Criterion) {
    for name in ["SHADOW", "CBOX", "MUG", "TEXTURE"] {
        let task = tasks::by_name(name).expect("task exists");
        let scene = task.scene().expect("task scene");
        let specialised = scene.scene().plan();
        let mut film = Film::new(SIZE, SIZE).expect("film");
        let mut group = c.benchmark_group(format!("render/{name}_{SIZE}x{SIZE}_{SPP}spp"));
        group.sample_size(10);
        group.warm_up_time(std::time::Duration::from_millis(500));
        group.measurement_time(std::time::Duration::from_secs(3));
        for (label, plan) in [("specialised", specialised), ("general", Plan::general())] {
            group.bench_function(label, |b| {
                b.iter(|| {
                    render_with_plan(scene.scene(), &plan, &mut film, SPP, 1).expect("render")
                });
            });
        }
        group.finish();
    }
}

criterion_group!(benches, specialisation);
criterion_main!(benches);
