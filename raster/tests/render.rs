//! Rendering expectations: coverage, colours, anti-aliased edges, and the cached
//! evaluation's equality with a full render.

use hodr_raster::{
    Attribute, Binding, Caching, Geometry, ParamMap, Point, Problem, RasterObjective, Rgba, Scene,
    Shape, Target,
};

fn rect(x: f32, y: f32, w: f32, h: f32, fill: Rgba) -> Shape {
    Shape::new(
        Geometry::Rect {
            center: Point::new(x + w / 2.0, y + h / 2.0),
            width: w,
            height: h,
            rotation: 0.0,
        },
        fill,
    )
}

const BLACK: Rgba = Rgba::rgb(0.0, 0.0, 0.0);
const WHITE: Rgba = Rgba::rgb(1.0, 1.0, 1.0);

#[test]
fn pixel_aligned_square_covers_exactly_its_pixels() {
    for aa in [true, false] {
        let scene = Scene::new(16, 16, BLACK)
            .unwrap()
            .with(rect(4.0, 5.0, 6.0, 6.0, WHITE).with_anti_alias(aa))
            .unwrap();
        let image = Target::from_scene(&scene);
        for y in 0..16 {
            for x in 0..16 {
                let inside = (4..10).contains(&x) && (5..11).contains(&y);
                let expected = if inside { [255; 3] } else { [0; 3] };
                assert_eq!(image.pixel(x, y), Some(expected), "aa={aa} ({x},{y})");
            }
        }
    }
}

#[test]
fn known_pixel_has_the_fill_colour_and_alpha_blends() {
    let red = Rgba::rgb(1.0, 0.0, 0.0);
    let half_blue = Rgba::new(0.0, 0.0, 1.0, 0.5);
    let scene = Scene::new(8, 8, Rgba::rgb(0.0, 1.0, 0.0))
        .unwrap()
        .with(Shape::new(
            Geometry::Circle {
                center: Point::new(3.0, 3.0),
                radius: 2.5,
            },
            red,
        ))
        .unwrap()
        .with(rect(4.0, 4.0, 4.0, 4.0, half_blue))
        .unwrap();
    let image = Target::from_scene(&scene);
    assert_eq!(image.pixel(3, 3), Some([255, 0, 0]));
    assert_eq!(image.pixel(0, 7), Some([0, 255, 0]));
    // 50 % blue over green: each channel within one step of the exact blend.
    let [r, g, b] = image.pixel(6, 6).unwrap();
    assert_eq!(r, 0);
    assert!(g.abs_diff(128) <= 1 && b.abs_diff(128) <= 1, "{g} {b}");
}

#[test]
fn anti_aliased_edge_lies_between_the_two_colours() {
    // A white square whose left edge sits at x = 4.5: column 4 is half covered.
    let make = |aa: bool| {
        let scene = Scene::new(16, 16, BLACK)
            .unwrap()
            .with(rect(4.5, 4.0, 6.0, 8.0, WHITE).with_anti_alias(aa))
            .unwrap();
        Target::from_scene(&scene)
    };
    let [v, ..] = make(true).pixel(4, 8).unwrap();
    assert!((100..=155).contains(&v), "half-covered pixel = {v}");
    assert_eq!(make(true).pixel(5, 8), Some([255; 3]));
    assert_eq!(make(true).pixel(3, 8), Some([0; 3]));
    // Without anti-aliasing every pixel is one colour or the other.
    let hard = make(false);
    assert!(hard.rgb().iter().all(|&c| c == 0 || c == 255));
}

/// A scene of mixed shapes where two in the middle of the stack move.
fn mixed_problem(caching: Caching) -> (RasterObjective, Vec<f64>) {
    let p = Point::new;
    let mut scene = Scene::new(48, 40, Rgba::rgb(0.2, 0.3, 0.4)).unwrap();
    let shapes = [
        rect(2.0, 2.0, 20.0, 14.0, Rgba::new(0.9, 0.1, 0.1, 0.7)),
        Shape::new(
            Geometry::Ellipse {
                center: p(30.0, 20.0),
                radius_x: 9.0,
                radius_y: 5.0,
                rotation: 0.4,
            },
            Rgba::new(0.1, 0.8, 0.2, 0.8),
        ),
        Shape::new(
            Geometry::Triangle([p(5.0, 30.0), p(20.0, 38.0), p(12.0, 22.0)]),
            Rgba::rgb(0.9, 0.9, 0.1),
        ),
        Shape::new(
            Geometry::Polygon(vec![
                p(35.0, 2.0),
                p(46.0, 6.0),
                p(44.0, 14.0),
                p(33.0, 10.0),
            ]),
            Rgba::new(0.5, 0.1, 0.9, 0.6),
        )
        .with_anti_alias(false),
        Shape::new(
            Geometry::CubicPath {
                start: p(20.0, 25.0),
                segments: vec![
                    [p(30.0, 20.0), p(40.0, 30.0), p(35.0, 38.0)],
                    [p(30.0, 42.0), p(20.0, 36.0), p(22.0, 30.0)],
                ],
            },
            Rgba::new(0.1, 0.9, 0.9, 0.5),
        ),
        Shape::new(
            Geometry::Circle {
                center: p(24.0, 12.0),
                radius: 6.0,
            },
            Rgba::new(1.0, 1.0, 1.0, 0.4),
        ),
    ];
    for s in shapes {
        scene.push(s).unwrap();
    }
    let target = Target::from_scene(&scene);
    let map = ParamMap::new(
        vec![
            Binding::new(1, Attribute::X, 8.0),
            Binding::new(1, Attribute::Rotation, 1.0),
            Binding::new(2, Attribute::VertexX(2), 8.0),
            Binding::new(2, Attribute::Y, 8.0),
            Binding::new(2, Attribute::Red, 1.0),
        ],
        &scene,
    )
    .unwrap();
    let theta = map.read(&scene);
    let problem = Problem::new(scene, map, target)
        .unwrap()
        .with_caching(caching);
    (RasterObjective::with_threads(problem, 2).unwrap(), theta)
}

#[test]
fn cached_evaluation_equals_full_render_bit_for_bit() {
    let (mut cached, theta) = mixed_problem(Caching::On);
    let (mut full, _) = mixed_problem(Caching::Off);
    assert_eq!(cached.loss(&theta).unwrap(), 0.0);
    let mut state = 0x1234_5678_u64;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..200 {
        let t: Vec<f64> = theta.iter().map(|&t| t + 3.0 * (uniform() - 0.5)).collect();
        let (a, b) = (cached.loss(&t).unwrap(), full.loss(&t).unwrap());
        assert_eq!(a.to_bits(), b.to_bits(), "θ = {t:?}");
    }
}
