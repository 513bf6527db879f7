//! Runs of a preset on a report task, exactly as `hodr report` makes them.

use std::sync::atomic::AtomicBool;

use hodr_core::optim::preset::Preset;
use hodr_host::report::{Method, Settings, run, task};

/// Seeds out of `0..seeds` whose parameter error falls to 1 % of the start's (the
/// report's "param 99 %" threshold) when `preset` runs on the report task `name` within
/// `budget` evaluations (`None`: the task's own budget).
pub fn seeds_reaching_99(name: &str, preset: Preset, seeds: u64, budget: Option<usize>) -> usize {
    let task = task::select(&[name.to_string()], false).unwrap().remove(0);
    let settings = Settings {
        budget,
        ..Settings::default()
    };
    let interrupt = AtomicBool::new(false);
    (0..seeds)
        .filter(|&seed| {
            let r = run(&*task, Method::Preset(preset), seed, &settings, &interrupt).unwrap();
            let start = r.points[0].param_error;
            r.points.iter().any(|p| p.param_error <= 0.01 * start)
        })
        .count()
}
