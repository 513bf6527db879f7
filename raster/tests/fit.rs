//! Image-to-shapes fitting: every added shape lowers the RMSE, results are
//! deterministic, PNG and SVG are written, and bad options are typed errors.

use hodr_raster::fit::{FitOptions, fit, fit_observed};
use hodr_raster::{Error, ShapeKind, Target, test_image};

/// A small budget so the debug-build test stays fast.
fn quick(shapes: usize, kind: ShapeKind) -> FitOptions {
    FitOptions {
        candidates: 48,
        restarts: 1,
        iterations: 6,
        ..FitOptions::new(shapes, kind)
    }
}

#[test]
fn every_added_shape_lowers_the_rmse() {
    let target = test_image::landscape(32).unwrap();
    for (kind, n) in [
        (ShapeKind::Triangle, 10),
        (ShapeKind::Rect, 5),
        (ShapeKind::Ellipse, 5),
        (ShapeKind::Circle, 3),
    ] {
        let result = fit(&target, &quick(n, kind)).unwrap();
        let history = result.rmse_history();
        assert_eq!(history.len(), n + 1, "{kind:?}");
        assert_eq!(result.scene().shapes().len(), n);
        for pair in history.windows(2) {
            assert!(pair[1] < pair[0], "{kind:?}: {history:?}");
        }
        // The history ends at the RMSE of the rendered scene.
        let rendered = Target::from_scene(result.scene());
        assert_eq!(rendered.rmse(&target).unwrap(), result.rmse());
        assert!(result.scene().shapes().iter().all(|s| s.kind() == kind));
    }
}

/// The observer hears of every placed shape, in order, with the RMSE the history
/// records.
#[test]
fn the_observer_sees_each_shape() {
    let target = test_image::landscape(24).unwrap();
    let mut seen = Vec::new();
    let stop = std::sync::atomic::AtomicBool::new(false);
    let result = fit_observed(&target, &quick(4, ShapeKind::Rect), &stop, &mut |k, e| {
        seen.push((k, e))
    })
    .unwrap();
    let history = result.rmse_history();
    let expected: Vec<(usize, f64)> = (1..history.len()).map(|k| (k, history[k])).collect();
    assert_eq!(seen, expected);
}

#[test]
fn fitting_is_deterministic() {
    let target = test_image::landscape(24).unwrap();
    let options = quick(4, ShapeKind::Triangle);
    let (a, b) = (
        fit(&target, &options).unwrap(),
        fit(&target, &options).unwrap(),
    );
    assert_eq!(a, b);
    let other = fit(&target, &FitOptions { seed: 9, ..options }).unwrap();
    assert_ne!(a.scene(), other.scene());
}

#[test]
fn png_and_svg_are_written() {
    let dir = std::env::temp_dir().join(format!("hodr-raster-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = dir.join("target.png");
    test_image::landscape(24)
        .unwrap()
        .save_png(&source)
        .unwrap();
    let (png, svg) = (dir.join("fit.png"), dir.join("fit.svg"));
    let result =
        hodr_raster::fit::fit_file(&source, &quick(3, ShapeKind::Ellipse), &png, Some(&svg))
            .unwrap();
    let written = Target::open(&png).unwrap();
    assert_eq!(written, Target::from_scene(result.scene()));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.matches("<ellipse").count() == 3);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_options_are_typed_errors() {
    let target = test_image::landscape(16).unwrap();
    let bad = [
        FitOptions::new(0, ShapeKind::Triangle),
        FitOptions::new(2, ShapeKind::Polygon),
        FitOptions {
            alpha: f32::NAN,
            ..FitOptions::new(2, ShapeKind::Rect)
        },
        FitOptions {
            restarts: 0,
            ..FitOptions::new(2, ShapeKind::Rect)
        },
        FitOptions {
            sigma_end: 1.0,
            sigma_start: 0.5,
            ..FitOptions::new(2, ShapeKind::Rect)
        },
    ];
    for options in bad {
        assert!(
            matches!(fit(&target, &options), Err(Error::InvalidOption { .. })),
            "{options:?}"
        );
    }
    let missing = hodr_raster::fit::fit_file(
        "/nonexistent/target.png",
        &FitOptions::new(1, ShapeKind::Triangle),
        "/tmp/never.png",
        None,
    );
    assert!(matches!(missing, Err(Error::ImageRead { .. })));
}
