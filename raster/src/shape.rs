//! Shapes: geometry in pixel coordinates, a fill colour, and anti-aliasing on or off.
//!
//! Every shape is turned into one closed path in pixel space and filled with the
//! non-zero winding rule. Transforms (rotation, translation) are applied by us to the
//! path's points rather than handed to tiny-skia, which would copy the path on every
//! fill: building in place lets a [`PathScratch`] reuse one allocation for every
//! evaluation. Circles and ellipses are four cubic Béziers (the usual κ = 0.5523
//! construction, radial error below 0.03 %).
//!
//! Coordinates are pixels, x right and y down, with pixel (i, j) covering
//! [i, i+1) × [j, j+1). Rotations are radians: a point (u, v) relative to the centre goes
//! to (u cos φ − v sin φ, u sin φ + v cos φ), which turns clockwise on screen because y
//! points down (as SVG's `rotate()`).

use tiny_skia::{FillRule, Paint, Path, PathBuilder, PixmapMut, Shader, Transform};

use crate::color::Rgba;
use crate::error::Error;
use crate::region::PixelRect;

/// Coordinates are clamped to ±`COORD_LIMIT` pixels before rasterising, so that a wild
/// parameter vector draws nothing (or a clipped shape) instead of overflowing the
/// rasteriser's fixed-point arithmetic.
pub const COORD_LIMIT: f32 = 1.0e5;

/// The Bézier handle length of a quarter circle of radius 1.
const KAPPA: f32 = 0.552_284_8;

/// A point in pixel coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Point {
    /// x, pixels to the right of the left edge.
    pub x: f32,
    /// y, pixels down from the top edge.
    pub y: f32,
}

impl Point {
    /// The point (x, y).
    pub const fn new(x: f32, y: f32) -> Self {
        Point { x, y }
    }
}

/// The outline of a shape. Sizes are pixels, rotations radians about the centre.
///
/// Negative sizes are rendered as zero (nothing drawn), so a parameter vector can cross
/// zero without failing.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A rectangle of `width` × `height` centred on `center`, rotated by `rotation`.
    Rect {
        /// Centre.
        center: Point,
        /// Width before rotation.
        width: f32,
        /// Height before rotation.
        height: f32,
        /// Rotation in radians.
        rotation: f32,
    },
    /// A circle.
    Circle {
        /// Centre.
        center: Point,
        /// Radius.
        radius: f32,
    },
    /// An ellipse with semi-axes `radius_x`, `radius_y` before rotation.
    Ellipse {
        /// Centre.
        center: Point,
        /// Semi-axis along x before rotation.
        radius_x: f32,
        /// Semi-axis along y before rotation.
        radius_y: f32,
        /// Rotation in radians.
        rotation: f32,
    },
    /// A triangle.
    Triangle([Point; 3]),
    /// A closed polygon of at least 3 vertices.
    Polygon(Vec<Point>),
    /// A closed path of cubic Bézier segments: from `start`, each segment is
    /// (control 1, control 2, end); a straight edge closes the last end back to `start`.
    CubicPath {
        /// First point.
        start: Point,
        /// At least one segment.
        segments: Vec<[Point; 3]>,
    },
}

/// The kinds of [`Geometry`], for choosing what a fit places and for naming.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShapeKind {
    /// [`Geometry::Rect`].
    Rect,
    /// [`Geometry::Circle`].
    Circle,
    /// [`Geometry::Ellipse`].
    Ellipse,
    /// [`Geometry::Triangle`].
    Triangle,
    /// [`Geometry::Polygon`].
    Polygon,
    /// [`Geometry::CubicPath`].
    CubicPath,
}

impl ShapeKind {
    /// Lower-case name: `rect`, `circle`, `ellipse`, `triangle`, `polygon`, `cubic`.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::Rect => "rect",
            ShapeKind::Circle => "circle",
            ShapeKind::Ellipse => "ellipse",
            ShapeKind::Triangle => "triangle",
            ShapeKind::Polygon => "polygon",
            ShapeKind::CubicPath => "cubic",
        }
    }
}

impl std::str::FromStr for ShapeKind {
    type Err = Error;

    /// Parses the names of [`ShapeKind::name`] (and `rectangle`).
    fn from_str(s: &str) -> Result<Self, Error> {
        Ok(match s {
            "rect" | "rectangle" => ShapeKind::Rect,
            "circle" => ShapeKind::Circle,
            "ellipse" => ShapeKind::Ellipse,
            "triangle" => ShapeKind::Triangle,
            "polygon" => ShapeKind::Polygon,
            "cubic" => ShapeKind::CubicPath,
            _ => {
                return Err(Error::InvalidOption {
                    name: "shape kind",
                    reason: "one of rect, circle, ellipse, triangle, polygon, cubic",
                });
            }
        })
    }
}

/// A filled shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// Outline.
    pub geometry: Geometry,
    /// Fill colour (straight alpha); composited source-over.
    pub fill: Rgba,
    /// Anti-aliased edges (coverage-weighted) when true; pixel-centre sampling when false.
    pub anti_alias: bool,
}

impl Shape {
    /// A shape with anti-aliasing on.
    pub fn new(geometry: Geometry, fill: Rgba) -> Self {
        Shape {
            geometry,
            fill,
            anti_alias: true,
        }
    }

    /// The same shape with anti-aliasing set to `on`.
    pub fn with_anti_alias(mut self, on: bool) -> Self {
        self.anti_alias = on;
        self
    }

    /// The kind of its geometry.
    pub fn kind(&self) -> ShapeKind {
        match self.geometry {
            Geometry::Rect { .. } => ShapeKind::Rect,
            Geometry::Circle { .. } => ShapeKind::Circle,
            Geometry::Ellipse { .. } => ShapeKind::Ellipse,
            Geometry::Triangle(_) => ShapeKind::Triangle,
            Geometry::Polygon(_) => ShapeKind::Polygon,
            Geometry::CubicPath { .. } => ShapeKind::CubicPath,
        }
    }

    /// Checks that every number is finite and that polygons and paths have enough points.
    ///
    /// # Errors
    /// [`Error::NonFiniteShape`] or [`Error::DegenerateShape`], naming shape `index`.
    pub fn validate(&self, index: usize) -> Result<(), Error> {
        let finite = |p: &Point| p.x.is_finite() && p.y.is_finite();
        let ok = self.fill.is_finite()
            && match &self.geometry {
                Geometry::Rect {
                    center,
                    width,
                    height,
                    rotation,
                } => {
                    finite(center)
                        && width.is_finite()
                        && height.is_finite()
                        && rotation.is_finite()
                }
                Geometry::Circle { center, radius } => finite(center) && radius.is_finite(),
                Geometry::Ellipse {
                    center,
                    radius_x,
                    radius_y,
                    rotation,
                } => {
                    finite(center)
                        && radius_x.is_finite()
                        && radius_y.is_finite()
                        && rotation.is_finite()
                }
                Geometry::Triangle(v) => v.iter().all(finite),
                Geometry::Polygon(v) => v.iter().all(finite),
                Geometry::CubicPath { start, segments } => {
                    finite(start) && segments.iter().flatten().all(finite)
                }
            };
        if !ok {
            return Err(Error::NonFiniteShape { shape: index });
        }
        let degenerate = match &self.geometry {
            Geometry::Polygon(v) => v.len() < 3,
            Geometry::CubicPath { segments, .. } => segments.is_empty(),
            _ => false,
        };
        if degenerate {
            return Err(Error::DegenerateShape { shape: index });
        }
        Ok(())
    }

    /// Conservative bounds `[x0, y0, x1, y1]` in pixels of everything the shape can
    /// cover (the control hull for curves), or `None` when it covers nothing (a zero
    /// or negative size). Coordinates are clamped as for rendering.
    pub fn bounds(&self) -> Option<[f32; 4]> {
        let mut b = Extent::EMPTY;
        match &self.geometry {
            Geometry::Rect {
                center,
                width,
                height,
                rotation,
            } => {
                let (hw, hh) = (size(*width) / 2.0, size(*height) / 2.0);
                if hw <= 0.0 || hh <= 0.0 {
                    return None;
                }
                let (s, c) = rotation.sin_cos();
                let (ex, ey) = (hw * c.abs() + hh * s.abs(), hw * s.abs() + hh * c.abs());
                let p = clamp_point(*center);
                b.add(Point::new(p.x - ex, p.y - ey));
                b.add(Point::new(p.x + ex, p.y + ey));
            }
            Geometry::Circle { center, radius } => {
                let r = size(*radius);
                if r <= 0.0 {
                    return None;
                }
                let p = clamp_point(*center);
                b.add(Point::new(p.x - r, p.y - r));
                b.add(Point::new(p.x + r, p.y + r));
            }
            Geometry::Ellipse {
                center,
                radius_x,
                radius_y,
                rotation,
            } => {
                let (rx, ry) = (size(*radius_x), size(*radius_y));
                if rx <= 0.0 || ry <= 0.0 {
                    return None;
                }
                // The control hull of the four cubics is the rotated box [−rx, rx]×[−ry, ry].
                let (s, c) = rotation.sin_cos();
                let (ex, ey) = (rx * c.abs() + ry * s.abs(), rx * s.abs() + ry * c.abs());
                let p = clamp_point(*center);
                b.add(Point::new(p.x - ex, p.y - ey));
                b.add(Point::new(p.x + ex, p.y + ey));
            }
            Geometry::Triangle(v) => v.iter().for_each(|&p| b.add(clamp_point(p))),
            Geometry::Polygon(v) => v.iter().for_each(|&p| b.add(clamp_point(p))),
            Geometry::CubicPath { start, segments } => {
                b.add(clamp_point(*start));
                segments
                    .iter()
                    .flatten()
                    .for_each(|&p| b.add(clamp_point(p)));
            }
        }
        b.finish()
    }

    /// The pixels the shape can touch in a `width` × `height` image: its bounds grown
    /// by one pixel for anti-aliasing and rounding, clipped to the image; `None` if empty.
    pub(crate) fn pixel_rect(&self, width: u32, height: u32) -> Option<PixelRect> {
        let [x0, y0, x1, y1] = self.bounds()?;
        let lo = |v: f32, max: u32| (v.floor() - 1.0).clamp(0.0, max as f32) as u32;
        let hi = |v: f32, max: u32| (v.ceil() + 1.0).clamp(0.0, max as f32) as u32;
        PixelRect::new(lo(x0, width), lo(y0, height), hi(x1, width), hi(y1, height))
    }

    /// Builds the outline into a path in pixel space (`None` if it covers nothing).
    pub(crate) fn path(&self, scratch: &mut PathScratch) -> Option<Path> {
        self.bounds()?;
        let mut pb = scratch.begin();
        match &self.geometry {
            Geometry::Rect {
                center,
                width,
                height,
                rotation,
            } => {
                let (hw, hh) = (size(*width) / 2.0, size(*height) / 2.0);
                let frame = Frame::new(clamp_point(*center), *rotation);
                let corners = [(-hw, -hh), (hw, -hh), (hw, hh), (-hw, hh)];
                polygon(&mut pb, corners.iter().map(|&(u, v)| frame.map(u, v)));
            }
            Geometry::Circle { center, radius } => {
                let r = size(*radius);
                oval(&mut pb, &Frame::new(clamp_point(*center), 0.0), r, r);
            }
            Geometry::Ellipse {
                center,
                radius_x,
                radius_y,
                rotation,
            } => {
                let frame = Frame::new(clamp_point(*center), *rotation);
                oval(&mut pb, &frame, size(*radius_x), size(*radius_y));
            }
            Geometry::Triangle(v) => polygon(&mut pb, v.iter().map(|&p| clamp_point(p))),
            Geometry::Polygon(v) => polygon(&mut pb, v.iter().map(|&p| clamp_point(p))),
            Geometry::CubicPath { start, segments } => {
                let s = clamp_point(*start);
                pb.move_to(s.x, s.y);
                for seg in segments {
                    let [a, b, c] = seg.map(clamp_point);
                    pb.cubic_to(a.x, a.y, b.x, b.y, c.x, c.y);
                }
                pb.close();
            }
        }
        scratch.finish(pb)
    }

    /// Fills the shape into `pixmap`, source-over.
    pub(crate) fn draw(&self, pixmap: &mut PixmapMut<'_>, scratch: &mut PathScratch) {
        if let Some(path) = self.path(scratch) {
            let paint = Paint {
                shader: Shader::SolidColor(self.fill.to_skia()),
                anti_alias: self.anti_alias,
                ..Paint::default()
            };
            pixmap.fill_path(
                &path,
                &paint,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
            scratch.recycle(path);
        }
    }

    /// Makes `self` equal to `other`, reusing `self`'s vertex storage where the kinds
    /// match (so resetting a moving shape each evaluation does not allocate).
    pub(crate) fn copy_from(&mut self, other: &Shape) {
        match (&mut self.geometry, &other.geometry) {
            (Geometry::Polygon(a), Geometry::Polygon(b)) => {
                a.clear();
                a.extend_from_slice(b);
            }
            (
                Geometry::CubicPath {
                    start: s,
                    segments: a,
                },
                Geometry::CubicPath {
                    start: t,
                    segments: b,
                },
            ) => {
                *s = *t;
                a.clear();
                a.extend_from_slice(b);
            }
            (g, o) => *g = o.clone(),
        }
        self.fill = other.fill;
        self.anti_alias = other.anti_alias;
    }
}

/// A reusable path allocation: build, fill, recycle.
#[derive(Debug, Default)]
pub(crate) struct PathScratch {
    builder: Option<PathBuilder>,
}

impl PathScratch {
    fn begin(&mut self) -> PathBuilder {
        let mut pb = self.builder.take().unwrap_or_default();
        pb.clear();
        pb
    }

    fn finish(&mut self, pb: PathBuilder) -> Option<Path> {
        pb.finish()
    }

    pub(crate) fn recycle(&mut self, path: Path) {
        self.builder = Some(path.clear());
    }
}

/// Rotation by φ then translation to `origin`.
struct Frame {
    origin: Point,
    cos: f32,
    sin: f32,
}

impl Frame {
    fn new(origin: Point, rotation: f32) -> Self {
        let (sin, cos) = if rotation == 0.0 {
            (0.0, 1.0)
        } else {
            rotation.sin_cos()
        };
        Frame { origin, cos, sin }
    }

    fn map(&self, u: f32, v: f32) -> Point {
        Point::new(
            self.origin.x + u * self.cos - v * self.sin,
            self.origin.y + u * self.sin + v * self.cos,
        )
    }
}

fn polygon(pb: &mut PathBuilder, mut points: impl Iterator<Item = Point>) {
    if let Some(p) = points.next() {
        pb.move_to(p.x, p.y);
        for p in points {
            pb.line_to(p.x, p.y);
        }
        pb.close();
    }
}

/// Four cubics through (±rx, 0), (0, ±ry) in `frame`.
fn oval(pb: &mut PathBuilder, frame: &Frame, rx: f32, ry: f32) {
    let (kx, ky) = (KAPPA * rx, KAPPA * ry);
    let start = frame.map(rx, 0.0);
    pb.move_to(start.x, start.y);
    let quarters = [
        [(rx, ky), (kx, ry), (0.0, ry)],
        [(-kx, ry), (-rx, ky), (-rx, 0.0)],
        [(-rx, -ky), (-kx, -ry), (0.0, -ry)],
        [(kx, -ry), (rx, -ky), (rx, 0.0)],
    ];
    for q in quarters {
        let [a, b, c] = q.map(|(u, v)| frame.map(u, v));
        pb.cubic_to(a.x, a.y, b.x, b.y, c.x, c.y);
    }
    pb.close();
}

/// A size rendered: negative and NaN become 0, huge values are capped.
fn size(v: f32) -> f32 {
    if v > 0.0 { v.min(COORD_LIMIT) } else { 0.0 }
}

fn clamp_coord(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(-COORD_LIMIT, COORD_LIMIT)
    }
}

fn clamp_point(p: Point) -> Point {
    Point::new(clamp_coord(p.x), clamp_coord(p.y))
}

/// A growing axis-aligned box.
struct Extent([f32; 4]);

impl Extent {
    const EMPTY: Extent = Extent([f32::INFINITY, f32::INFINITY, -f32::INFINITY, -f32::INFINITY]);

    fn add(&mut self, p: Point) {
        let b = &mut self.0;
        b[0] = b[0].min(p.x);
        b[1] = b[1].min(p.y);
        b[2] = b[2].max(p.x);
        b[3] = b[3].max(p.y);
    }

    fn finish(self) -> Option<[f32; 4]> {
        let b = self.0;
        (b[0] < b[2] && b[1] < b[3]).then_some(b)
    }
}
