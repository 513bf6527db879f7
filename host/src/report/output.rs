//! The report's files: `results.csv`, `traces.csv`, `results.json`, `report.md`, plots
//! and strips.

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use anyhow::{Context, Result};
use image::RgbImage;
use image::imageops::{self, FilterType};
use serde::Serialize;

use super::method::Run;
use super::summary::{ErrorKind, Row, samples};
use super::task::Task;
use crate::metrics::{REDUCTIONS, first_reaching, format_seconds};

/// Side of each panel of an init / result / target strip, pixels.
const PANEL: u32 = 160;

/// `results.csv`: one row per task × method × seed.
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(path: &Path, runs: &[Run]) -> Result<()> {
    let mut csv = String::from(
        "task,method,seed,evaluations,time_s,final_param_error,final_image_error,stopped",
    );
    for kind in ErrorKind::BOTH {
        for r in REDUCTIONS {
            let pct = format!("{}", r * 100.0).replace('.', "_");
            let _ = write!(csv, ",{0}{1}_time_s,{0}{1}_evaluations", kind.label(), pct);
        }
    }
    csv.push('\n');
    for run in runs {
        let last = run.points.last();
        let _ = write!(
            csv,
            "{},{},{},{},{},{},{},{}",
            run.task,
            run.method,
            run.seed,
            last.map_or(0, |p| p.evaluations),
            last.map_or(0.0, |p| p.time),
            last.map_or(f64::NAN, |p| p.param_error),
            last.map_or(f64::NAN, |p| p.image_error),
            run.stopped.as_deref().unwrap_or("").replace(',', ";"),
        );
        for kind in ErrorKind::BOTH {
            let s = samples(run, kind);
            for r in REDUCTIONS {
                match first_reaching(&s, r) {
                    Some(x) => {
                        let _ = write!(csv, ",{},{}", x.time, x.evaluations);
                    }
                    None => csv.push_str(",,"),
                }
            }
        }
        csv.push('\n');
    }
    fs::write(path, csv).with_context(|| format!("writing {}", path.display()))
}

/// `traces.csv`: every recorded point of every run, one row each (the start is
/// iteration 0; `sigma` is empty there): time in seconds to the microsecond, errors and
/// σ to 7 significant digits.
///
/// # Errors
/// When the file cannot be written.
pub fn write_traces(path: &Path, runs: &[Run]) -> Result<()> {
    let mut csv = String::from(
        "task,method,seed,iteration,time_s,evaluations,param_error,image_error,sigma\n",
    );
    for run in runs {
        for (k, p) in run.points.iter().enumerate() {
            let _ = write!(
                csv,
                "{},{},{},{k},{:.6},{},{:.6e},{:.6e},",
                run.task, run.method, run.seed, p.time, p.evaluations, p.param_error, p.image_error
            );
            if let Some(sigma) = p.sigma {
                let _ = write!(csv, "{sigma:.6e}");
            }
            csv.push('\n');
        }
    }
    fs::write(path, csv).with_context(|| format!("writing {}", path.display()))
}

/// `results.json`: the settings, whether a signal interrupted the report, the summary
/// rows and every run's outcome (final θ, why it stopped); the per-iteration points are
/// in `traces.csv`.
///
/// # Errors
/// When the file cannot be written.
pub fn write_json<C: Serialize>(
    path: &Path,
    config: &C,
    runs: &[Run],
    rows: &[Row],
    interrupted: bool,
) -> Result<()> {
    #[derive(Serialize)]
    struct Doc<'a, C> {
        config: &'a C,
        /// True when a signal stopped the report: `runs` holds the finished ones.
        interrupted: bool,
        summary: &'a [Row],
        runs: &'a [Run],
    }
    let text = serde_json::to_string_pretty(&Doc {
        config,
        interrupted,
        summary: rows,
        runs,
    })?;
    fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// A panel: the image scaled to fit PANEL×PANEL (nearest neighbour keeps pixels crisp).
fn panel(img: &RgbImage) -> RgbImage {
    let mut out = RgbImage::from_pixel(PANEL, PANEL, image::Rgb([255, 255, 255]));
    let scale = (PANEL as f64 / img.width().max(img.height()) as f64).min(8.0);
    let (w, h) = (
        (img.width() as f64 * scale) as u32,
        (img.height() as f64 * scale) as u32,
    );
    let filter = if scale >= 1.0 {
        FilterType::Nearest
    } else {
        FilterType::Triangle
    };
    let resized = imageops::resize(img, w.max(1), h.max(1), filter);
    imageops::overlay(
        &mut out,
        &resized,
        ((PANEL - w.min(PANEL)) / 2) as i64,
        ((PANEL - h.min(PANEL)) / 2) as i64,
    );
    out
}

/// Writes the init / result / target strip of `task` to `path`, if the task has images.
/// Returns whether a file was written.
///
/// # Errors
/// When rendering or writing fails.
pub fn write_strip(path: &Path, task: &dyn Task, init: &[f64], result: &[f64]) -> Result<bool> {
    let (Some(a), Some(b), Some(c)) = (
        task.image(init)?,
        task.image(result)?,
        task.image(&task.optimum())?,
    ) else {
        return Ok(false);
    };
    let mut strip = RgbImage::from_pixel(3 * PANEL + 20, PANEL, image::Rgb([255, 255, 255]));
    for (k, img) in [a, b, c].iter().enumerate() {
        imageops::overlay(&mut strip, &panel(img), (k as u32 * (PANEL + 10)) as i64, 0);
    }
    strip
        .save(path)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(true)
}

/// File-name form of a task name.
pub fn slug(name: &str) -> String {
    name.to_ascii_lowercase()
        .replace(|c: char| !c.is_ascii_alphanumeric(), "_")
}

/// The Markdown table of one task's rows.
pub fn table(rows: &[Row]) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "| method | image 90 % | image 99 % | image 99.9 % | param 90 % | param 99 % | param 99.9 % | final param error | ×best (param 99 %) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|");
    for row in rows {
        let _ = write!(md, "| {} |", row.method);
        if row.skipped {
            let _ = writeln!(md, "{}", " skipped |".repeat(8));
            continue;
        }
        for kind in ErrorKind::BOTH {
            for r in REDUCTIONS {
                let cell = row.cell(kind, r);
                let time = format_seconds(cell.and_then(|c| c.time));
                let evals = cell
                    .and_then(|c| c.evaluations)
                    .map_or("—".into(), |e| format!("{e:.0}"));
                let _ = write!(md, " {time} / {evals} |");
            }
        }
        let fin = row
            .final_param_error
            .map_or("—".into(), |e| format!("{e:.2e}"));
        let ratio = row.ratio_to_best.map_or("—".into(), |r| format!("{r:.2}"));
        let _ = writeln!(md, " {fin} | {ratio} |");
    }
    md
}
