//! Renders per second with and without the cached static layer and dirty regions.
//!
//! `cargo bench -p hodr-raster --bench render`. Each iteration is one loss evaluation
//! (render + score) on one thread, at a point that moves every moving shape (the
//! sequence of points cycles through the task's start distribution).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use hodr_raster::tasks::{self, Task};
use hodr_raster::{
    Attribute, Binding, Caching, Geometry, ParamMap, Point, Problem, RasterObjective, Rgba, Scene,
    Shape, Target,
};

fn bench_problem(
    c: &mut Criterion,
    name: &str,
    problem: &dyn Fn(Caching) -> Problem,
    points: &[Vec<f64>],
) {
    let mut group = c.benchmark_group(name);
    for (label, caching) in [("cached", Caching::On), ("full", Caching::Off)] {
        let mut objective = RasterObjective::with_threads(problem(caching), 1).unwrap();
        let mut k = 0;
        group.bench_function(label, |b| {
            b.iter(|| {
                k = (k + 1) % points.len();
                black_box(objective.loss(&points[k]).unwrap())
            })
        });
    }
    group.finish();
}

fn task_points(task: &Task) -> Vec<Vec<f64>> {
    (0..64).map(|s| task.start(s)).collect()
}

fn tasks_64(c: &mut Criterion) {
    for name in ["box2", "box10", "shapes"] {
        let task = tasks::by_name(name).unwrap();
        let points = task_points(&task);
        bench_problem(c, name, &|caching| task.problem(caching), &points);
    }
}

/// 200 random semi-transparent shapes on 128×128; the top 3 move (x, y each).
fn scene_200() -> (Scene, ParamMap, Vec<Vec<f64>>) {
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let mut u = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f32 / (1u64 << 53) as f32
    };
    let mut scene = Scene::new(128, 128, Rgba::rgb(0.5, 0.5, 0.5)).unwrap();
    for i in 0..200 {
        let (x, y, r) = (128.0 * u(), 128.0 * u(), 3.0 + 12.0 * u());
        let fill = Rgba::new(u(), u(), u(), 0.3 + 0.6 * u());
        let geometry = match i % 4 {
            0 => Geometry::Circle {
                center: Point::new(x, y),
                radius: r,
            },
            1 => Geometry::Triangle([
                Point::new(x, y - r),
                Point::new(x - r, y + r),
                Point::new(x + r * u(), y + r),
            ]),
            2 => Geometry::Rect {
                center: Point::new(x, y),
                width: 2.0 * r,
                height: r,
                rotation: u(),
            },
            _ => Geometry::Ellipse {
                center: Point::new(x, y),
                radius_x: r,
                radius_y: 0.6 * r,
                rotation: u(),
            },
        };
        scene.push(Shape::new(geometry, fill)).unwrap();
    }
    let bindings = (197..200)
        .flat_map(|s| {
            [
                Binding::new(s, Attribute::X, 16.0),
                Binding::new(s, Attribute::Y, 16.0),
            ]
        })
        .collect();
    let map = ParamMap::new(bindings, &scene).unwrap();
    let base = map.read(&scene);
    let points = (0..64)
        .map(|k| {
            base.iter()
                .map(|t| t + 0.5 * ((k as f64 * 0.7 + t).sin()))
                .collect()
        })
        .collect();
    (scene, map, points)
}

fn shapes_200(c: &mut Criterion) {
    let (scene, map, points) = scene_200();
    let target = Target::from_scene(&scene);
    bench_problem(
        c,
        "scene200_move3",
        &|caching| {
            Problem::new(scene.clone(), map.clone(), target.clone())
                .unwrap()
                .with_caching(caching)
        },
        &points,
    );
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20)
}

criterion_group! {
    name = benches;
    config = config();
    targets = tasks_64, shapes_200
}
criterion_main!(benches);
