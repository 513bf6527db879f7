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
pub(crate) fn font_available() -> bool {
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

/// Ten colours told apart by most readers, colour-blind ones included (Okabe–Ito's
/// eight and two darker tones); methods beyond them repeat the colours dashed.
const COLOURS: [RGBColor; 10] = [
    RGBColor(0, 0, 0),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(204, 121, 167),
    RGBColor(140, 110, 20),
    RGBColor(110, 110, 110),
    RGBColor(120, 40, 140),
];

/// Colour and dashing of the k-th method's curve.
fn line_style(k: usize) -> (RGBColor, bool) {
    (COLOURS[k % COLOURS.len()], (k / COLOURS.len()) % 2 == 1)
}

/// [lo, hi] widened to whole decades.
fn decades(lo: f64, hi: f64) -> (f64, f64) {
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
    )
}

/// The error axis for errors in [lo, hi]: whole decades ([`decades`]) unless they span
/// under one, then [lo, hi] widened by a fifth of its log-width (at least 1.1× each way).
fn error_range(lo: f64, hi: f64) -> (f64, f64) {
    if hi >= 10.0 * lo {
        return decades(lo, hi);
    }
    let pad = (hi / lo).powf(0.2).max(1.1);
    (lo / pad, hi * pad)
}

/// Labelled and light ticks of a log axis over [lo, hi]: the powers of ten and, light,
/// their multiples 2–9 where it spans a decade or more; else the multiples of the
/// largest step 1, 2 or 5 × 10ᵏ that puts at least three labels in it (plotters labels
/// no point of a log axis narrower than a decade).
pub(crate) fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    let within = |v: &f64| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9);
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    if hi >= 10.0 * lo {
        let powers = (first..=last)
            .map(|k| 10f64.powi(k))
            .filter(within)
            .collect();
        let light = (first..=last)
            .flat_map(|k| (2..10).map(move |m| f64::from(m) * 10f64.powi(k)))
            .filter(within)
            .collect();
        return (powers, light);
    }
    let multiples = |step: f64| -> Vec<f64> {
        let start = (lo / step).ceil() as i64;
        let end = (hi / step).floor() as i64;
        (start..=end).map(|k| k as f64 * step).collect()
    };
    for k in (first - 2..=last).rev() {
        for m in [5.0, 2.0, 1.0] {
            let points = multiples(m * 10f64.powi(k));
            if points.len() >= 3 {
                return (points, Vec::new());
            }
        }
    }
    (vec![lo, hi], Vec::new())
}

/// A log axis' tick label: "10⁻⁴" at a power of ten, "3·10⁻⁴" elsewhere.
fn power_of_ten(v: f64) -> String {
    if !(v > 0.0 && v.is_finite()) {
        return String::new();
    }
    let exponent = v.log10().floor();
    let mantissa = v / 10f64.powf(exponent);
    let (mantissa, exponent) = if mantissa >= 9.995 {
        (1.0, exponent + 1.0)
    } else {
        (mantissa, exponent)
    };
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut power = String::from("10");
    if exponent < 0.0 {
        power.push('⁻');
    }
    for d in format!("{}", exponent.abs() as u64).bytes() {
        power.push(DIGITS[usize::from(d - b'0')]);
    }
    if exponent == 0.0 {
        power = "1".into();
    }
    if (mantissa - 1.0).abs() < 5e-3 {
        power
    } else if exponent == 0.0 {
        format!("{mantissa:.2}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    } else {
        let m = format!("{mantissa:.1}");
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{m}·{power}")
    }
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
    // A method with no curve says why in the legend: its runs were all skipped, or an
    // interrupt came before any of them on this task.
    let curves: Vec<(&str, Vec<f64>, &str)> = methods
        .iter()
        .map(|&m| {
            let mine: Vec<&Run> = runs.iter().filter(|r| r.method == m).collect();
            if mine.is_empty() {
                (m, Vec::new(), "not run")
            } else if mine.iter().all(|r| r.skipped()) {
                (m, Vec::new(), "skipped")
            } else {
                (m, median_curve(&mine, kind, &grid), "")
            }
        })
        .collect();
    let positive = curves
        .iter()
        .flat_map(|(_, c, _)| c.iter().copied())
        .filter(|&e| e > 0.0 && e.is_finite());
    let (e_lo, e_hi) = positive.fold((f64::INFINITY, 0.0f64), |(lo, hi), e| {
        (lo.min(e), hi.max(e))
    });
    if !(e_lo.is_finite() && e_hi > 0.0) {
        return Ok(());
    }
    // Whole decades on both axes, so that every axis has labelled ticks; errors that
    // stay within one decade get the range they span instead, or they would be drawn as
    // flat lines in one corner of an empty decade.
    let (t_lo, t_hi) = decades(t_lo, t_hi);
    let (e_lo, e_hi) = error_range(e_lo.max(e_hi * 1e-12), e_hi);
    let text = font_available();
    let root = BitMapBackend::new(path, (1060, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    // The legend gets its own column right of the axes, so it hides no curve.
    let (plot_area, legend_area) = root.split_horizontally(if text { 790 } else { 1060 });
    let mut builder = ChartBuilder::on(&plot_area);
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
        .build_cartesian_2d((t_lo..t_hi).log_scale(), {
            let (labelled, light) = log_ticks(e_lo, e_hi);
            (e_lo..e_hi)
                .log_scale()
                .with_key_points(labelled)
                .with_light_points(light)
        })
        .map_err(|e| anyhow!("{e}"))?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("wall time [s]")
            .y_desc(format!("{} error", kind.label()))
            .x_label_formatter(&|v| power_of_ten(*v))
            .y_label_formatter(&|v| power_of_ten(*v));
    } else {
        mesh.disable_x_axis().disable_y_axis();
    }
    mesh.draw().map_err(|e| anyhow!("{e}"))?;
    for (k, (_, curve, _)) in curves.iter().enumerate() {
        let (colour, dashed) = line_style(k);
        let points: Vec<(f64, f64)> = grid
            .iter()
            .zip(curve)
            .filter(|(_, e)| e.is_finite() && **e > 0.0)
            .map(|(&t, &e)| (t, e.max(e_lo)))
            .collect();
        let style = colour.stroke_width(2);
        if dashed {
            chart
                .draw_series(DashedLineSeries::new(points, 9, 5, style))
                .map_err(|e| anyhow!("{e}"))?;
        } else {
            chart
                .draw_series(LineSeries::new(points, style))
                .map_err(|e| anyhow!("{e}"))?;
        }
    }
    if text {
        for (k, (name, curve, why)) in curves.iter().enumerate() {
            let (colour, dashed) = line_style(k);
            let y = 70 + 24 * k as i32;
            if curve.is_empty() {
                legend_area
                    .draw(&Text::new(
                        format!("{name} ({why})"),
                        (42, y - 8),
                        ("sans-serif", 16)
                            .into_font()
                            .color(&RGBColor(140, 140, 140)),
                    ))
                    .map_err(|e| anyhow!("{e}"))?;
                continue;
            }
            let style = colour.stroke_width(2);
            if dashed {
                legend_area
                    .draw(&plotters::element::DashedPathElement::new(
                        vec![(0, y), (34, y)],
                        9,
                        5,
                        style,
                    ))
                    .map_err(|e| anyhow!("{e}"))?;
            } else {
                legend_area
                    .draw(&PathElement::new(vec![(0, y), (34, y)], style))
                    .map_err(|e| anyhow!("{e}"))?;
            }
            legend_area
                .draw(&Text::new(
                    name.to_string(),
                    (42, y - 8),
                    ("sans-serif", 16).into_font(),
                ))
                .map_err(|e| anyhow!("{e}"))?;
        }
    }
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_read_as_powers_of_ten() {
        for (v, label) in [
            (1e-7, "10⁻⁷"),
            (1e-5, "10⁻⁵"),
            (0.1, "10⁻¹"),
            (1.0, "1"),
            (10.0, "10¹"),
            (1e3, "10³"),
            (3e-4, "3·10⁻⁴"),
            (2.5, "2.5"),
            (20.0, "2·10¹"),
            (0.30000000000000004, "3·10⁻¹"),
            (9.999999e-8, "10⁻⁷"),
        ] {
            assert_eq!(power_of_ten(v), label, "{v}");
        }
        assert_eq!(power_of_ten(0.0), "");
        assert_eq!(power_of_ten(f64::NAN), "");
    }

    /// A log axis always has labelled ticks inside it: powers of ten over a decade or
    /// more, evenly spaced values over less (where plotters would label none).
    #[test]
    fn log_axes_have_labels_inside_them() {
        let (labels, light) = log_ticks(1e-6, 0.1);
        assert_eq!(labels.len(), 6);
        assert!(
            labels
                .iter()
                .all(|&v| (v.log10() - v.log10().round()).abs() < 1e-12)
        );
        assert_eq!(light.len(), 5 * 8);
        for (lo, hi) in [(0.045, 0.072), (0.0601, 0.0605), (3.0, 7.0), (1.0, 1.2)] {
            let (labels, _) = log_ticks(lo, hi);
            assert!(labels.len() >= 3, "{lo}..{hi}: {labels:?}");
            let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
            assert!(labels.iter().all(|&v| inside(v)), "{labels:?}");
        }
        let (lo, hi) = error_range(0.045, 0.072);
        assert!(lo < 0.045 && lo > 0.035 && hi > 0.072 && hi < 0.09);
        assert_eq!(error_range(1e-6, 0.07), (1e-6, 0.1));
    }

    #[test]
    fn axes_span_whole_decades() {
        assert_eq!(decades(0.3, 0.7), (0.1, 1.0));
        assert_eq!(decades(12.0, 19.0), (10.0, 100.0));
        let (lo, hi) = decades(2e-7, 3e-3);
        assert!((lo - 1e-7).abs() < 1e-20 && (hi - 1e-2).abs() < 1e-15);
        let (lo, hi) = decades(1.0, 1.0);
        assert!(lo == 1.0 && hi == 10.0);
    }
}
