//! Bad input gets a typed error, never a panic.

use hodr_core::{Batch, Objective};
use hodr_raster::{
    Attribute, Binding, Error, Geometry, ParamMap, Point, Problem, RasterObjective, Rgba, Scene,
    Shape, Target, tasks,
};

fn disc() -> Shape {
    Shape::new(
        Geometry::Circle {
            center: Point::new(4.0, 4.0),
            radius: 2.0,
        },
        Rgba::rgb(1.0, 1.0, 1.0),
    )
}

fn scene() -> Scene {
    Scene::new(8, 8, Rgba::rgb(0.0, 0.0, 0.0))
        .unwrap()
        .with(disc())
        .unwrap()
}

#[test]
fn sizes_out_of_range() {
    let black = Rgba::rgb(0.0, 0.0, 0.0);
    for (w, h) in [
        (0, 8),
        (8, 0),
        (hodr_raster::MAX_SIDE + 1, 8),
        (u32::MAX, u32::MAX),
    ] {
        assert!(matches!(
            Scene::new(w, h, black),
            Err(Error::InvalidSize { .. })
        ));
    }
    assert!(matches!(
        Target::from_rgb8(2, 2, vec![0; 11]),
        Err(Error::BufferSize {
            expected: 12,
            found: 11
        })
    ));
    assert!(matches!(
        Target::from_rgb8(0, 2, vec![]),
        Err(Error::InvalidSize { .. })
    ));
}

#[test]
fn unreadable_missing_and_corrupt_images() {
    assert!(matches!(
        Target::open("/nonexistent/image.png"),
        Err(Error::ImageRead { .. })
    ));
    let dir = std::env::temp_dir().join(format!("hodr-raster-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let junk = dir.join("junk.png");
    std::fs::write(&junk, b"\x89PNG but not really").unwrap();
    assert!(matches!(Target::open(&junk), Err(Error::ImageRead { .. })));
    assert!(matches!(
        Target::decode(b"neither png nor jpeg"),
        Err(Error::ImageDecode(_))
    ));
    // Writing into a missing directory.
    let target = Target::from_scene(&scene());
    assert!(matches!(
        target.save_png(dir.join("missing/x.png")),
        Err(Error::Encode { .. })
    ));
    assert!(matches!(
        scene().save_svg(dir.join("missing/x.svg")),
        Err(Error::Write { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn png_and_jpeg_decode() {
    let target = Target::from_scene(&scene());
    let mut png = Vec::new();
    image::write_buffer_with_format(
        &mut std::io::Cursor::new(&mut png),
        target.rgb(),
        8,
        8,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .unwrap();
    assert_eq!(Target::decode(&png).unwrap(), target);
    let mut jpeg = Vec::new();
    image::write_buffer_with_format(
        &mut std::io::Cursor::new(&mut jpeg),
        target.rgb(),
        8,
        8,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Jpeg,
    )
    .unwrap();
    let decoded = Target::decode(&jpeg).unwrap();
    assert_eq!((decoded.width(), decoded.height()), (8, 8));
}

#[test]
fn wrong_target_size() {
    let small = Target::from_rgb8(4, 4, vec![0; 48]).unwrap();
    let map = ParamMap::new(vec![Binding::new(0, Attribute::X, 1.0)], &scene()).unwrap();
    assert!(matches!(
        Problem::new(scene(), map, small),
        Err(Error::TargetSize { .. })
    ));
}

#[test]
fn bad_bindings() {
    let s = scene();
    let err = |b: Binding| ParamMap::new(vec![b], &s).unwrap_err();
    assert!(matches!(
        err(Binding::new(3, Attribute::X, 1.0)),
        Error::NoSuchShape { shape: 3, .. }
    ));
    assert!(matches!(
        err(Binding::new(0, Attribute::Width, 1.0)),
        Error::NoSuchAttribute { .. }
    ));
    assert!(matches!(
        err(Binding::new(0, Attribute::VertexX(0), 1.0)),
        Error::NoSuchAttribute { .. }
    ));
    assert!(matches!(
        err(Binding::new(0, Attribute::X, 0.0)),
        Error::InvalidScale { .. }
    ));
    assert!(matches!(
        err(Binding::new(0, Attribute::X, f64::NAN)),
        Error::InvalidScale { .. }
    ));
    assert!(matches!(
        err(Binding::new(0, Attribute::X, 1.0).with_clamp(2.0, 1.0)),
        Error::InvalidScale { .. }
    ));
    assert!(matches!(
        ParamMap::new(vec![], &s),
        Err(Error::InvalidOption { .. })
    ));
}

#[test]
fn bad_shapes() {
    let mut s = Scene::new(8, 8, Rgba::rgb(0.0, 0.0, 0.0)).unwrap();
    let nan = Shape::new(
        Geometry::Circle {
            center: Point::new(f32::NAN, 1.0),
            radius: 1.0,
        },
        Rgba::rgb(1.0, 0.0, 0.0),
    );
    assert!(matches!(
        s.push(nan),
        Err(Error::NonFiniteShape { shape: 0 })
    ));
    let line = Shape::new(
        Geometry::Polygon(vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0)]),
        Rgba::rgb(1.0, 0.0, 0.0),
    );
    assert!(matches!(
        s.push(line),
        Err(Error::DegenerateShape { shape: 0 })
    ));
    assert!(matches!(
        Scene::new(8, 8, Rgba::rgb(f32::INFINITY, 0.0, 0.0)),
        Err(Error::NonFiniteShape { .. })
    ));
    assert!(s.shapes().is_empty());
}

#[test]
fn bad_parameters() {
    let task = tasks::by_name("box2").unwrap();
    let mut objective: RasterObjective = task.objective().unwrap();
    assert!(matches!(
        objective.loss(&[1.0, f64::NAN]),
        Err(Error::NonFiniteParameter { index: 1 })
    ));
    assert!(matches!(
        objective.loss(&[1.0]),
        Err(Error::DimensionMismatch {
            expected: 2,
            found: 1
        })
    ));
    assert!(matches!(
        objective.scene_at(&[f64::INFINITY, 0.0]),
        Err(Error::NonFiniteParameter { index: 0 })
    ));
    // Through the trait, a bad point is NaN (the estimators report it).
    assert!(Objective::<f64>::evaluate(&mut objective, &[f64::NAN, 0.0], 0).is_nan());
    // Huge but finite values render (clamped) without panicking.
    for theta in [[1e300, -1e300], [f64::MAX, f64::MIN_POSITIVE], [-1e12, 3.0]] {
        assert!(objective.loss(&theta).unwrap().is_finite());
    }
    let shapes = tasks::by_name("shapes").unwrap();
    let mut objective = shapes.objective().unwrap();
    let wild: Vec<f64> = (0..shapes.dim())
        .map(|k| if k % 2 == 0 { 1e30 } else { -1e30 })
        .collect();
    assert!(objective.loss(&wild).unwrap().is_finite());
}

/// Whatever the thread count, and whether a batch runs on the calling thread (the first
/// batch, before any cost is measured, and small ones) or is split across the pool (a
/// later batch of 200 64×64 renders, far above `PARALLEL_WORK`), batch values equal
/// single evaluations.
#[test]
fn batches_equal_single_evaluations_for_any_thread_count() {
    let task = tasks::by_name("shapes").unwrap();
    let count = 200;
    let points: Vec<f64> = (0..count).flat_map(|s| task.start(s as u64)).collect();
    let seeds = vec![0; count];
    let batch = Batch::new(&points, &seeds, task.dim()).unwrap();
    let mut results = Vec::new();
    for threads in [1, 2, 3, 8] {
        let mut objective =
            RasterObjective::with_threads(task.problem(hodr_raster::Caching::On), threads).unwrap();
        for _ in 0..2 {
            let mut out = vec![0.0; count];
            objective.evaluate_batch(&batch, &mut out);
            results.push(out);
        }
    }
    let mut single = task.objective().unwrap();
    let expected: Vec<f64> = (0..count)
        .map(|k| single.loss(batch.point(k)).unwrap())
        .collect();
    for out in results {
        assert_eq!(out, expected);
    }
    assert!(matches!(
        RasterObjective::with_threads(task.problem(hodr_raster::Caching::On), 0),
        Err(Error::InvalidOption { .. })
    ));
}
