//! The task definitions: zero loss at the truth, exactly flat plateaus, starts that do
//! not overlap their targets, reproducible starts.

use hodr_raster::tasks::{self, NAMES, Task};
use hodr_raster::{Caching, RasterObjective};

#[test]
fn every_task_has_zero_loss_at_the_truth() {
    for task in tasks::all() {
        let mut objective = task.objective().unwrap();
        assert_eq!(
            objective.loss(task.theta_true()).unwrap(),
            0.0,
            "{}",
            task.name()
        );
        assert_eq!(objective.dim(), task.dim());
    }
    assert_eq!(tasks::all().len(), NAMES.len());
    assert_eq!(tasks::by_name("box10").unwrap().dim(), 10);
    assert!(tasks::by_name("shapes").unwrap().dim() >= 18);
}

#[test]
fn unknown_task_and_bad_sizes_are_errors() {
    assert!(matches!(
        tasks::by_name("box3"),
        Err(hodr_raster::Error::UnknownTask(_))
    ));
    assert!(Task::new("box2", 0).is_err());
    assert!(Task::new("box2", 1 << 20).is_err());
    assert_eq!(Task::new("BOX2", 128).unwrap().size(), 128);
}

#[test]
fn box2_loss_is_exactly_flat_when_the_squares_do_not_overlap() {
    let task = tasks::by_name("box2").unwrap();
    let mut objective = task.objective().unwrap();
    let plateau = objective.loss(&task.start(0)).unwrap();
    assert!(plateau > 0.0);
    // A grid of sub-pixel positions, all at least one side (1.5) away on some axis.
    let mut checked = 0;
    for i in 0..40 {
        for j in 0..40 {
            let (x, y) = (0.8 + 0.161 * f64::from(i), 0.8 + 0.161 * f64::from(j));
            if (x - 2.5).abs() < 1.5 + 1e-9 && (y - 2.5).abs() < 1.5 + 1e-9 {
                continue;
            }
            let loss = objective.loss(&[x, y]).unwrap();
            assert_eq!(loss.to_bits(), plateau.to_bits(), "at ({x}, {y})");
            checked += 1;
        }
    }
    assert!(checked > 1000);
    // Overlapping lowers it.
    assert!(objective.loss(&[3.0, 3.2]).unwrap() < plateau);
}

#[test]
fn starts_are_on_the_plateau_and_reproducible() {
    for task in tasks::all() {
        let mut objective = task.objective().unwrap();
        for seed in 0..20 {
            let start = task.start(seed);
            assert_eq!(start, task.start(seed));
            assert_eq!(start.len(), task.dim());
            let loss = objective.loss(&start).unwrap();
            // Nudging any coordinate by a small step leaves position losses unchanged
            // for the hard-edged tasks: the start is on a plateau.
            if task.name() != "shapes" {
                for k in 0..start.len() {
                    let mut moved = start.clone();
                    moved[k] += 0.05;
                    let nudged = objective.loss(&moved).unwrap();
                    assert!(
                        (nudged - loss).abs() <= 1e-12 || task.name() == "box10",
                        "{} seed {seed} coordinate {k}: {loss} -> {nudged}",
                        task.name()
                    );
                }
            }
        }
        assert_ne!(task.start(1), task.start(2));
    }
}

#[test]
fn start_shapes_do_not_overlap_their_targets() {
    // BOX10: each square is displaced by more than its side on both axes.
    let task = tasks::by_name("box10").unwrap();
    for seed in 0..50 {
        let start = task.start(seed);
        for (s, t) in start.iter().zip(task.theta_true()) {
            assert!((s - t).abs() > 1.0, "seed {seed}");
            assert!((0.75..=7.25).contains(s));
        }
    }
    // SHAPES: centre distance exceeds the sum of radii.
    let task = tasks::by_name("shapes").unwrap();
    for seed in 0..50 {
        let start = task.start(seed);
        for (s, t) in start.chunks(6).zip(task.theta_true().chunks(6)) {
            let d = ((s[0] - t[0]).powi(2) + (s[1] - t[1]).powi(2)).sqrt();
            assert!(d > (s[2] + t[2]) / 2.0, "seed {seed}");
        }
    }
}

#[test]
fn caching_does_not_change_any_task_loss() {
    for task in tasks::all() {
        let mut on = RasterObjective::new(task.problem(Caching::On)).unwrap();
        let mut off = RasterObjective::new(task.problem(Caching::Off)).unwrap();
        for seed in 0..10 {
            let theta = task.start(seed);
            assert_eq!(on.loss(&theta).unwrap(), off.loss(&theta).unwrap());
        }
    }
}

#[test]
fn tri1d_loss_is_exactly_flat_away_from_the_target() {
    let task = tasks::by_name("tri1d").unwrap();
    let mut objective = task.objective().unwrap();
    let plateau = objective.loss(&[5.0]).unwrap();
    for i in 0..400 {
        let x = 4.55 + 0.0049 * f64::from(i);
        assert_eq!(
            objective.loss(&[x]).unwrap().to_bits(),
            plateau.to_bits(),
            "x = {x}"
        );
    }
    assert!(objective.loss(&[2.5]).unwrap() < plateau);
}

/// SHAPES's circles render the target in any order, and its parameter error is zero at
/// every ordering; BOX10's squares keep their colours, so swapping two is an error.
#[test]
fn the_parameter_error_is_zero_exactly_where_the_render_is_the_target() {
    let shapes = tasks::by_name("shapes").unwrap();
    let mut objective = shapes.objective().unwrap();
    let truth = shapes.theta_true();
    for order in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let permuted: Vec<f64> = order
            .iter()
            .flat_map(|&c| truth[6 * c..6 * c + 6].iter().copied())
            .collect();
        assert_eq!(objective.loss(&permuted).unwrap(), 0.0, "{order:?}");
        assert_eq!(shapes.parameter_error(&permuted), 0.0, "{order:?}");
    }
    // One circle moved by 0.5 in x: √(0.25 / n) whatever the ordering.
    let mut moved: Vec<f64> = [2, 0, 1]
        .iter()
        .flat_map(|&c| truth[6 * c..6 * c + 6].iter().copied())
        .collect();
    moved[6] += 0.5;
    let expected = (0.25 / truth.len() as f64).sqrt();
    assert!((shapes.parameter_error(&moved) - expected).abs() < 1e-12);
    assert!((shapes.parameter_distance(&moved) - 0.5).abs() < 1e-12);

    let box10 = tasks::by_name("box10").unwrap();
    let mut swapped = box10.theta_true().to_vec();
    swapped.swap(0, 2);
    swapped.swap(1, 3);
    assert!(box10.objective().unwrap().loss(&swapped).unwrap() > 0.0);
    assert!(box10.parameter_distance(&swapped) > 1.0);
}
