//! Per task × method: medians over seeds of the time and evaluations to 90 / 99 / 99.9 %
//! reduction of the image and the parameter error, and ratios to the best method.

use serde::Serialize;

use super::method::{Point, Run};
use crate::metrics::{REDUCTIONS, Sample, first_reaching, median};

/// Which error a threshold refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ErrorKind {
    /// The loss at a fixed noise seed.
    Image,
    /// ‖θ − θ*‖.
    Param,
}

impl ErrorKind {
    /// Both kinds, image first.
    pub const BOTH: [ErrorKind; 2] = [ErrorKind::Image, ErrorKind::Param];

    /// Lower-case label.
    pub fn label(self) -> &'static str {
        match self {
            ErrorKind::Image => "image",
            ErrorKind::Param => "param",
        }
    }

    /// This error of a point.
    pub fn of(self, p: &Point) -> f64 {
        match self {
            ErrorKind::Image => p.image_error,
            ErrorKind::Param => p.param_error,
        }
    }
}

/// The samples of one error kind of a run.
pub fn samples(run: &Run, kind: ErrorKind) -> Vec<Sample> {
    run.points
        .iter()
        .map(|p| Sample {
            time: p.time,
            evaluations: p.evaluations,
            error: kind.of(p),
        })
        .collect()
}

/// Median time and evaluations to one reduction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// Error kind.
    pub kind: ErrorKind,
    /// Reduction (0.9, 0.99, 0.999).
    pub reduction: f64,
    /// Median seconds, `None` = not reached by at least half the seeds.
    pub time: Option<f64>,
    /// Median evaluations.
    pub evaluations: Option<f64>,
    /// Seeds that reached it.
    pub reached: usize,
}

/// One method's row for one task.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Task.
    pub task: String,
    /// Method.
    pub method: String,
    /// Seeds run.
    pub seeds: usize,
    /// Cells for image then parameter error, 90 / 99 / 99.9 %.
    pub cells: Vec<Cell>,
    /// Median final parameter error.
    pub final_param_error: Option<f64>,
    /// Median final image error.
    pub final_image_error: Option<f64>,
    /// This method's median time to 99 % parameter-error reduction over the best
    /// method's (1 for the best; `None` when it never gets there).
    pub ratio_to_best: Option<f64>,
    /// Every run was skipped ([`Run::skipped`]): the row has no figures.
    pub skipped: bool,
}

impl Row {
    /// The cell for `kind` and `reduction`.
    pub fn cell(&self, kind: ErrorKind, reduction: f64) -> Option<&Cell> {
        self.cells
            .iter()
            .find(|c| c.kind == kind && c.reduction == reduction)
    }
}

/// Rows for the runs of one task (grouped by method, in the order given).
pub fn rows(task: &str, methods: &[&str], runs: &[Run]) -> Vec<Row> {
    let mut rows: Vec<Row> = methods
        .iter()
        .map(|&method| {
            let mine: Vec<&Run> = runs
                .iter()
                .filter(|r| r.task == task && r.method == method)
                .collect();
            let mut cells = Vec::new();
            for kind in ErrorKind::BOTH {
                for reduction in REDUCTIONS {
                    let reached: Vec<_> = mine
                        .iter()
                        .map(|r| first_reaching(&samples(r, kind), reduction))
                        .collect();
                    cells.push(Cell {
                        kind,
                        reduction,
                        time: median(
                            &reached
                                .iter()
                                .map(|x| x.map(|x| x.time))
                                .collect::<Vec<_>>(),
                        ),
                        evaluations: median(
                            &reached
                                .iter()
                                .map(|x| x.map(|x| x.evaluations as f64))
                                .collect::<Vec<_>>(),
                        ),
                        reached: reached.iter().filter(|x| x.is_some()).count(),
                    });
                }
            }
            let skipped = !mine.is_empty() && mine.iter().all(|r| r.skipped());
            let last = |kind: ErrorKind| {
                if skipped {
                    return None;
                }
                median(
                    &mine
                        .iter()
                        .map(|r| r.points.last().map(|p| kind.of(p)))
                        .collect::<Vec<_>>(),
                )
            };
            Row {
                task: task.to_string(),
                method: method.to_string(),
                seeds: mine.len(),
                cells,
                final_param_error: last(ErrorKind::Param),
                final_image_error: last(ErrorKind::Image),
                ratio_to_best: None,
                skipped,
            }
        })
        .collect();
    let key = |r: &Row| r.cell(ErrorKind::Param, 0.99).and_then(|c| c.time);
    let best = rows.iter().filter_map(key).fold(f64::INFINITY, f64::min);
    for r in &mut rows {
        r.ratio_to_best = key(r).map(|t| if best > 0.0 { t / best } else { 1.0 });
    }
    rows
}

/// The median error over runs at each time of `grid`: each run contributes the error of
/// its last point at or before the time (its start before its first iteration).
pub fn median_curve(runs: &[&Run], kind: ErrorKind, grid: &[f64]) -> Vec<f64> {
    grid.iter()
        .map(|&t| {
            let values: Vec<Option<f64>> = runs
                .iter()
                .map(|r| {
                    r.points
                        .iter()
                        .take_while(|p| p.time <= t)
                        .last()
                        .or(r.points.first())
                        .map(|p| kind.of(p))
                })
                .collect();
            median(&values).unwrap_or(f64::NAN)
        })
        .collect()
}
