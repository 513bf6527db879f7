//! Log–log plots of median error against time, drawn with plotters.
//!
//! Text needs a font. plotters' pure-Rust `ab_glyph` backend draws with a TrueType font
//! registered at run time from the first of [`FONT_PATHS`] found; without one the plots
//! are drawn without text (the report's tables carry the same information).

use std::path::Path;
use std::sync::OnceLock;

use anyhow::{Result, anyhow};
use plotters::prelude::*;

use super::method::Run;
use super::summary::{ErrorKind, median_curve};

/// Fonts tried, in order.
pub const FONT_PATHS: [&str; 4] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
];

/// True once a font is registered (tried once per process).
fn font_available() -> bool {
    static FONT: OnceLock<bool> = OnceLock::new();
    *FONT.get_or_init(|| {
        for path in FONT_PATHS {
            if let Ok(bytes) = std::fs::read(path) {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                if plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                    return true;
                }
            }
        }
        false
    })
}

/// Draws the median `kind` error of each method's runs against time to `path` (PNG).
///
/// # Errors
/// When the PNG cannot be written.
pub fn error_against_time(
    path: &Path,
    task: &str,
    kind: ErrorKind,
    methods: &[&str],
    runs: &[Run],
) -> Result<()> {
    let times = runs
        .iter()
        .flat_map(|r| r.points.iter().map(|p| p.time))
        .filter(|&t| t > 0.0);
    let (t_lo, t_hi) = times.fold((f64::INFINITY, 0.0f64), |(lo, hi), t| {
        (lo.min(t), hi.max(t))
    });
    if !(t_lo.is_finite() && t_hi > t_lo) {
        return Ok(()); // nothing timed to draw
    }
    let grid: Vec<f64> = (0..=60)
        .map(|k| t_lo * (t_hi / t_lo).powf(k as f64 / 60.0))
        .collect();
    let curves: Vec<(&str, Vec<f64>)> = methods
        .iter()
        .map(|&m| {
            let mine: Vec<&Run> = runs.iter().filter(|r| r.method == m).collect();
            (m, median_curve(&mine, kind, &grid))
        })
        .collect();
    let positive = curves
        .iter()
        .flat_map(|(_, c)| c.iter().copied())
        .filter(|&e| e > 0.0 && e.is_finite());
    let (e_lo, e_hi) = positive.fold((f64::INFINITY, 0.0f64), |(lo, hi), e| {
        (lo.min(e), hi.max(e))
    });
    if !(e_lo.is_finite() && e_hi > 0.0) {
        return Ok(());
    }
    let e_lo = e_lo.max(e_hi * 1e-12);
    let text = font_available();
    let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let mut builder = ChartBuilder::on(&root);
    builder.margin(20);
    if text {
        builder
            .caption(
                format!("{task}: median {} error", kind.label()),
                ("sans-serif", 24),
            )
            .x_label_area_size(45)
            .y_label_area_size(70);
    }
    let mut chart = builder
        .build_cartesian_2d(
            (t_lo..t_hi).log_scale(),
            (e_lo * 0.8..e_hi * 1.25).log_scale(),
        )
        .map_err(|e| anyhow!("{e}"))?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("wall time [s]")
            .y_desc(format!("{} error", kind.label()));
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw().map_err(|e| anyhow!("{e}"))?;
    for (k, (name, curve)) in curves.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let points = grid
            .iter()
            .zip(curve)
            .filter(|(_, e)| e.is_finite() && **e > 0.0)
            .map(|(&t, &e)| (t, e.max(e_lo)));
        let series = chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(|e| anyhow!("{e}"))?;
        if text {
            let name = name.to_string();
            series.label(name).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        }
    }
    if text {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| anyhow!("{e}"))?;
    }
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}
