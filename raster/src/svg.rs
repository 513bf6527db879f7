//! SVG output: the same scene as the PNG, as resolution-independent vector shapes.
//!
//! Circles and ellipses are written as SVG circles and ellipses (tiny-skia draws them
//! as four cubics; they differ by under 0.03 % of the radius). Shapes with
//! anti-aliasing off get `shape-rendering="crispEdges"`.

use std::fmt::Write;

use crate::scene::Scene;
use crate::shape::{Geometry, Point, Shape};

/// The SVG document of `scene`: a `width` × `height` canvas in pixels, a background
/// rectangle, then every shape in order.
pub fn scene_to_svg(scene: &Scene) -> String {
    let (w, h) = (scene.width(), scene.height());
    let mut out = String::new();
    let [r, g, b] = scene.background().to_rgb8();
    // Writing to a String cannot fail.
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(
        out,
        r#"<rect width="{w}" height="{h}" fill="rgb({r},{g},{b})"/>"#
    );
    for shape in scene.shapes() {
        write_shape(&mut out, shape);
    }
    out.push_str("</svg>\n");
    out
}

fn write_shape(out: &mut String, shape: &Shape) {
    let c = shape.fill.clamped();
    let [r, g, b] = c.to_rgb8();
    let mut style = format!(r#"fill="rgb({r},{g},{b})""#);
    if c.a < 1.0 {
        let _ = write!(style, r#" fill-opacity="{}""#, num(c.a));
    }
    if !shape.anti_alias {
        style.push_str(r#" shape-rendering="crispEdges""#);
    }
    let _ = match &shape.geometry {
        Geometry::Rect {
            center,
            width,
            height,
            rotation,
        } => {
            let (w, h) = (width.max(0.0), height.max(0.0));
            writeln!(
                out,
                r#"<rect x="{}" y="{}" width="{}" height="{}"{} {style}/>"#,
                num(center.x - w / 2.0),
                num(center.y - h / 2.0),
                num(w),
                num(h),
                rotate(*rotation, *center),
            )
        }
        Geometry::Circle { center, radius } => writeln!(
            out,
            r#"<circle cx="{}" cy="{}" r="{}" {style}/>"#,
            num(center.x),
            num(center.y),
            num(radius.max(0.0)),
        ),
        Geometry::Ellipse {
            center,
            radius_x,
            radius_y,
            rotation,
        } => writeln!(
            out,
            r#"<ellipse cx="{}" cy="{}" rx="{}" ry="{}"{} {style}/>"#,
            num(center.x),
            num(center.y),
            num(radius_x.max(0.0)),
            num(radius_y.max(0.0)),
            rotate(*rotation, *center),
        ),
        Geometry::Triangle(v) => writeln!(out, r#"<polygon points="{}" {style}/>"#, points(v)),
        Geometry::Polygon(v) => writeln!(out, r#"<polygon points="{}" {style}/>"#, points(v)),
        Geometry::CubicPath { start, segments } => {
            let mut d = format!("M{} {}", num(start.x), num(start.y));
            for [a, b, c] in segments {
                let _ = write!(
                    d,
                    " C{} {} {} {} {} {}",
                    num(a.x),
                    num(a.y),
                    num(b.x),
                    num(b.y),
                    num(c.x),
                    num(c.y)
                );
            }
            d.push_str(" Z");
            writeln!(out, r#"<path d="{d}" {style}/>"#)
        }
    };
}

fn rotate(radians: f32, about: Point) -> String {
    if radians == 0.0 {
        String::new()
    } else {
        format!(
            r#" transform="rotate({} {} {})""#,
            num(radians.to_degrees()),
            num(about.x),
            num(about.y)
        )
    }
}

fn points(v: &[Point]) -> String {
    let mut s = String::new();
    for (i, p) in v.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{},{}", num(p.x), num(p.y));
    }
    s
}

/// At most three decimals, trailing zeros dropped.
fn num(v: f32) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgba;

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(1.23456), "1.235");
    }

    #[test]
    fn every_shape_kind_is_written() {
        let p = Point::new;
        let scene = Scene::new(10, 10, Rgba::rgb(1.0, 1.0, 1.0))
            .and_then(|s| {
                s.with(Shape::new(
                    Geometry::Rect {
                        center: p(5.0, 5.0),
                        width: 2.0,
                        height: 4.0,
                        rotation: 0.5,
                    },
                    Rgba::new(1.0, 0.0, 0.0, 0.5),
                ))
            })
            .and_then(|s| {
                s.with(Shape::new(
                    Geometry::Triangle([p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)]),
                    Rgba::rgb(0.0, 0.0, 1.0),
                ))
            })
            .and_then(|s| {
                s.with(
                    Shape::new(
                        Geometry::CubicPath {
                            start: p(0.0, 0.0),
                            segments: vec![[p(1.0, 0.0), p(2.0, 1.0), p(2.0, 2.0)]],
                        },
                        Rgba::rgb(0.0, 1.0, 0.0),
                    )
                    .with_anti_alias(false),
                )
            })
            .unwrap();
        let svg = scene_to_svg(&scene);
        assert!(svg.starts_with("<svg"));
        assert!(svg.contains(r#"<rect x="4" y="3" width="2" height="4" transform="rotate(28.648 5 5)" fill="rgb(255,0,0)" fill-opacity="0.5"/>"#));
        assert!(svg.contains(r#"<polygon points="0,0 1,0 0,1" fill="rgb(0,0,255)"/>"#));
        assert!(svg.contains(
            r#"<path d="M0 0 C1 0 2 1 2 2 Z" fill="rgb(0,255,0)" shape-rendering="crispEdges"/>"#
        ));
        assert!(svg.trim_end().ends_with("</svg>"));
    }
}
