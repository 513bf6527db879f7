//! The suite's ECDF plot: for each method, the fraction of (problem, seed, f-target)
//! triples reached within a budget of x·n evaluations, against x on a log axis — the
//! runtime distribution of COCO's reports, averaged over seeds so that each
//! (problem, target) pair weighs the same.
//!
//! Text needs a TrueType font, registered as the report's plots register it; without
//! one the plot is drawn without text (suite.md holds the same results).

use std::path::Path;

use anyhow::{Result, anyhow};
use plotters::prelude::*;

use super::methods::Method;
use super::problem::Problem;
use super::summary::{F_TARGETS, Run};
use crate::report::plot::{font_available, log_ticks};

/// The colour of a method's line: fixed per method, so plots of different runs agree.
pub fn colour(method: Method) -> RGBColor {
    match method {
        Method::Auto => RGBColor(214, 39, 40),
        Method::CmaEs => RGBColor(31, 119, 180),
        Method::Bobyqa => RGBColor(44, 160, 44),
        Method::Fr22 => RGBColor(255, 127, 14),
    }
}

/// One method's ECDF: the sorted evaluations/n of every reached triple, and the number
/// of triples.
fn ecdf(problems: &[Problem], runs: &[Run], method: Method) -> (Vec<f64>, usize) {
    let mut hits = Vec::new();
    let mut total = 0;
    for r in runs.iter().filter(|r| r.method == method) {
        let n = problems[r.problem].n as f64;
        for e in r.reached().into_iter().take(F_TARGETS.len()) {
            total += 1;
            if let Some(e) = e {
                hits.push(e.evaluation as f64 / n);
            }
        }
    }
    hits.sort_by(f64::total_cmp);
    (hits, total)
}

/// Draws the ECDF of each method's runs to `path` (PNG), x from the smallest
/// evaluations/n reached to `x_max` (the largest budget/n).
///
/// # Errors
/// When the PNG cannot be written.
pub fn ecdf_plot(
    path: &Path,
    problems: &[Problem],
    methods: &[Method],
    runs: &[Run],
    x_max: f64,
) -> Result<()> {
    let curves: Vec<(Method, Vec<f64>, usize)> = methods
        .iter()
        .map(|&m| {
            let (hits, total) = ecdf(problems, runs, m);
            (m, hits, total)
        })
        .collect();
    let smallest = curves
        .iter()
        .filter_map(|(_, h, _)| h.first().copied())
        .fold(f64::INFINITY, f64::min);
    let x_lo = if smallest.is_finite() {
        10f64.powf(smallest.log10().floor())
    } else {
        0.01
    };
    let x_hi = x_max.max(x_lo * 10.0);
    let text = font_available();
    let root = BitMapBackend::new(path, (1000, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (left, legend) = root.split_horizontally(780);
    let mut builder = ChartBuilder::on(&left);
    builder.margin(20);
    if text {
        builder
            .caption(
                "fraction of (problem, seed, target) triples reached",
                ("sans-serif", 22),
            )
            .x_label_area_size(45)
            .y_label_area_size(60);
    }
    let mut chart = builder
        .build_cartesian_2d(
            {
                let (labelled, light) = log_ticks(x_lo, x_hi);
                (x_lo..x_hi)
                    .log_scale()
                    .with_key_points(labelled)
                    .with_light_points(light)
            },
            0.0..1.0,
        )
        .map_err(|e| anyhow!("{e}"))?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("evaluations / n")
            .y_desc("fraction reached")
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17));
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw().map_err(|e| anyhow!("{e}"))?;
    for (m, hits, total) in &curves {
        if *total == 0 {
            continue;
        }
        let mut points = vec![(x_lo, 0.0)];
        for (k, &x) in hits.iter().enumerate() {
            let y_before = k as f64 / *total as f64;
            points.push((x.max(x_lo), y_before));
            points.push((x.max(x_lo), (k + 1) as f64 / *total as f64));
        }
        points.push((x_hi, hits.len() as f64 / *total as f64));
        chart
            .draw_series(LineSeries::new(points, colour(*m).stroke_width(3)))
            .map_err(|e| anyhow!("{e}"))?;
    }
    // The legend in its own panel to the right, clear of every curve.
    for (k, (m, hits, total)) in curves.iter().enumerate() {
        let y = 70 + 34 * k as i32;
        legend
            .draw(&PathElement::new(
                vec![(10, y), (50, y)],
                colour(*m).stroke_width(3),
            ))
            .map_err(|e| anyhow!("{e}"))?;
        if text {
            let share = if *total > 0 {
                100.0 * hits.len() as f64 / *total as f64
            } else {
                0.0
            };
            legend
                .draw(&Text::new(
                    format!("{} ({share:.0} %)", m.name()),
                    (58, y - 9),
                    ("sans-serif", 18),
                ))
                .map_err(|e| anyhow!("{e}"))?;
        }
    }
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}
