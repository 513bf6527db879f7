//! The parameter map: which shape attributes θ drives, and at what scale.
//!
//! Coordinate k of θ sets one attribute of one shape to `offset + scale·θₖ` (pixels,
//! radians or colour units), so that with a suitable scale every θ coordinate is of
//! order one and a single smoothing width σ suits all of them. A binding may clamp the
//! value to a range (as the paper's BOX2 clamps positions), so that a shape cannot
//! leave the image, where hiding it would lower the loss. Bindings are applied in
//! order to a fresh copy of the scene's shape on every evaluation.

use crate::error::Error;
use crate::scene::Scene;
use crate::shape::{Geometry, Point, Shape};

/// A shape attribute that a θ coordinate can drive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Attribute {
    /// Centre x of a rect, circle or ellipse; for triangles, polygons and cubic paths a
    /// horizontal translation of the shape as given in the scene. Pixels.
    X,
    /// As [`Attribute::X`], vertically.
    Y,
    /// Rect width, pixels.
    Width,
    /// Rect height, pixels.
    Height,
    /// Circle radius, pixels.
    Radius,
    /// Ellipse semi-axis along x before rotation, pixels.
    RadiusX,
    /// Ellipse semi-axis along y before rotation, pixels.
    RadiusY,
    /// Rect or ellipse rotation, radians.
    Rotation,
    /// Fill red, [0, 1].
    Red,
    /// Fill green, [0, 1].
    Green,
    /// Fill blue, [0, 1].
    Blue,
    /// Fill opacity, [0, 1].
    Alpha,
    /// x of vertex i of a triangle or polygon, or of point i of a cubic path (the start,
    /// then each segment's two controls and end), pixels.
    VertexX(usize),
    /// y of vertex i, as [`Attribute::VertexX`].
    VertexY(usize),
}

/// θ coordinate ↦ `offset + scale·θ`, optionally clamped, written to `attribute` of
/// shape `shape`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Binding {
    /// Index of the shape in the scene.
    pub shape: usize,
    /// The attribute set.
    pub attribute: Attribute,
    /// Units of the attribute per unit of θ. Finite and non-zero.
    pub scale: f64,
    /// The attribute's value at θ = 0. Finite. Default: 0.
    pub offset: f64,
    /// `Some([lo, hi])` clamps the value to [lo, hi] (finite, lo ≤ hi). Default: `None`.
    pub clamp: Option<[f64; 2]>,
}

impl Binding {
    /// A binding with offset 0.
    pub fn new(shape: usize, attribute: Attribute, scale: f64) -> Self {
        Binding {
            shape,
            attribute,
            scale,
            offset: 0.0,
            clamp: None,
        }
    }

    /// The same binding with its value clamped to [lo, hi].
    pub fn with_clamp(mut self, lo: f64, hi: f64) -> Self {
        self.clamp = Some([lo, hi]);
        self
    }

    /// The same binding with `offset`.
    pub fn with_offset(mut self, offset: f64) -> Self {
        self.offset = offset;
        self
    }

    /// The interval of θ coordinate values over which the attribute changes: where the
    /// binding clamps, the θ range mapping onto [lo, hi]; for a colour or opacity, the
    /// θ range mapping onto [0, 1]; otherwise (−∞, ∞).
    pub fn domain(&self) -> [f64; 2] {
        let range = match (self.clamp, self.attribute) {
            (Some(c), _) => c,
            (None, Attribute::Red | Attribute::Green | Attribute::Blue | Attribute::Alpha) => {
                [0.0, 1.0]
            }
            (None, _) => return [f64::NEG_INFINITY, f64::INFINITY],
        };
        let a = (range[0] - self.offset) / self.scale;
        let b = (range[1] - self.offset) / self.scale;
        [a.min(b), a.max(b)]
    }

    /// The attribute value for θ coordinate `t`.
    #[inline]
    pub fn value(&self, t: f64) -> f64 {
        let v = self.offset + self.scale * t;
        match self.clamp {
            Some([lo, hi]) => v.clamp(lo, hi),
            None => v,
        }
    }
}

/// The bindings of θ, one per coordinate, checked against a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamMap {
    bindings: Vec<Binding>,
}

impl ParamMap {
    /// Checks every binding against `scene`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] for no bindings; [`Error::NoSuchShape`],
    /// [`Error::NoSuchAttribute`], [`Error::InvalidScale`] naming the first bad binding.
    pub fn new(bindings: Vec<Binding>, scene: &Scene) -> Result<Self, Error> {
        if bindings.is_empty() {
            return Err(Error::InvalidOption {
                name: "bindings",
                reason: "at least one θ coordinate is needed",
            });
        }
        let shapes = scene.shapes();
        for (k, b) in bindings.iter().enumerate() {
            let shape = shapes.get(b.shape).ok_or(Error::NoSuchShape {
                binding: k,
                shape: b.shape,
                shapes: shapes.len(),
            })?;
            if !applies(b.attribute, &shape.geometry) {
                return Err(Error::NoSuchAttribute {
                    binding: k,
                    shape: b.shape,
                    attribute: format!("{:?}", b.attribute),
                });
            }
            let clamp_ok = b
                .clamp
                .is_none_or(|[lo, hi]| lo.is_finite() && hi.is_finite() && lo <= hi);
            if !(b.scale.is_finite() && b.scale != 0.0 && b.offset.is_finite() && clamp_ok) {
                return Err(Error::InvalidScale {
                    binding: k,
                    scale: b.scale,
                    offset: b.offset,
                });
            }
        }
        Ok(ParamMap { bindings })
    }

    /// The bindings, in θ order.
    pub fn bindings(&self) -> &[Binding] {
        &self.bindings
    }

    /// n, the dimension of θ.
    pub fn dim(&self) -> usize {
        self.bindings.len()
    }

    /// Lower and upper bounds of θ: each binding's [`Binding::domain`].
    pub fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.bindings
            .iter()
            .map(|b| b.domain())
            .map(|[a, b]| (a, b))
            .unzip()
    }

    /// The θ that reproduces `scene`'s attribute values (translations read as 0).
    ///
    /// `scene` must be the scene the map was checked against (or share its shape kinds).
    pub fn read(&self, scene: &Scene) -> Vec<f64> {
        self.bindings
            .iter()
            .map(|b| {
                let value = scene
                    .shapes()
                    .get(b.shape)
                    .map_or(0.0, |s| get(b.attribute, s));
                (value - b.offset) / b.scale
            })
            .collect()
    }

    /// A copy of `scene` with θ applied.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`], [`Error::NonFiniteParameter`], or
    /// [`Error::NonFiniteShape`] if θ drives an attribute out of f32 range.
    pub fn apply_to(&self, scene: &Scene, theta: &[f64]) -> Result<Scene, Error> {
        check_theta(self.dim(), theta.iter().copied())?;
        let mut shapes: Vec<Shape> = scene.shapes().to_vec();
        for (b, &t) in self.bindings.iter().zip(theta) {
            if let Some(shape) = shapes.get_mut(b.shape) {
                set(b.attribute, shape, b.value(t));
            }
        }
        let mut out = Scene::new(scene.width(), scene.height(), scene.background())?;
        for shape in shapes {
            out.push(shape)?;
        }
        Ok(out)
    }
}

/// Checks θ's length and finiteness.
pub(crate) fn check_theta(
    dim: usize,
    theta: impl ExactSizeIterator<Item = f64>,
) -> Result<(), Error> {
    if theta.len() != dim {
        return Err(Error::DimensionMismatch {
            expected: dim,
            found: theta.len(),
        });
    }
    let mut theta = theta;
    match theta.position(|t| !t.is_finite()) {
        Some(index) => Err(Error::NonFiniteParameter { index }),
        None => Ok(()),
    }
}

fn vertex_count(g: &Geometry) -> usize {
    match g {
        Geometry::Triangle(_) => 3,
        Geometry::Polygon(v) => v.len(),
        Geometry::CubicPath { segments, .. } => 1 + 3 * segments.len(),
        _ => 0,
    }
}

fn applies(a: Attribute, g: &Geometry) -> bool {
    use Attribute::*;
    match a {
        X | Y | Red | Green | Blue | Alpha => true,
        Width | Height => matches!(g, Geometry::Rect { .. }),
        Radius => matches!(g, Geometry::Circle { .. }),
        RadiusX | RadiusY => matches!(g, Geometry::Ellipse { .. }),
        Rotation => matches!(g, Geometry::Rect { .. } | Geometry::Ellipse { .. }),
        VertexX(i) | VertexY(i) => i < vertex_count(g),
    }
}

/// Vertex i of a vertex shape (`None` for other kinds or out of range).
fn vertex_mut(g: &mut Geometry, i: usize) -> Option<&mut Point> {
    match g {
        Geometry::Triangle(v) => v.get_mut(i),
        Geometry::Polygon(v) => v.get_mut(i),
        Geometry::CubicPath { start, segments } => match i {
            0 => Some(start),
            _ => segments.get_mut((i - 1) / 3).map(|s| &mut s[(i - 1) % 3]),
        },
        _ => None,
    }
}

fn translate(g: &mut Geometry, dx: f32, dy: f32) {
    let shift = |p: &mut Point| {
        p.x += dx;
        p.y += dy;
    };
    match g {
        Geometry::Rect { center, .. }
        | Geometry::Circle { center, .. }
        | Geometry::Ellipse { center, .. } => shift(center),
        Geometry::Triangle(v) => v.iter_mut().for_each(shift),
        Geometry::Polygon(v) => v.iter_mut().for_each(shift),
        Geometry::CubicPath { start, segments } => {
            shift(start);
            segments.iter_mut().flatten().for_each(shift);
        }
    }
}

/// Writes `value` to attribute `a` of `shape`. Attributes that do not apply are ignored
/// (the map checked them at construction).
pub(crate) fn set(a: Attribute, shape: &mut Shape, value: f64) {
    let v = value as f32;
    let g = &mut shape.geometry;
    match a {
        Attribute::X | Attribute::Y => {
            let centre = match g {
                Geometry::Rect { center, .. }
                | Geometry::Circle { center, .. }
                | Geometry::Ellipse { center, .. } => Some(center),
                _ => None,
            };
            match (centre, a) {
                (Some(c), Attribute::X) => c.x = v,
                (Some(c), _) => c.y = v,
                (None, Attribute::X) => translate(g, v, 0.0),
                (None, _) => translate(g, 0.0, v),
            }
        }
        Attribute::Width => {
            if let Geometry::Rect { width, .. } = g {
                *width = v;
            }
        }
        Attribute::Height => {
            if let Geometry::Rect { height, .. } = g {
                *height = v;
            }
        }
        Attribute::Radius => {
            if let Geometry::Circle { radius, .. } = g {
                *radius = v;
            }
        }
        Attribute::RadiusX => {
            if let Geometry::Ellipse { radius_x, .. } = g {
                *radius_x = v;
            }
        }
        Attribute::RadiusY => {
            if let Geometry::Ellipse { radius_y, .. } = g {
                *radius_y = v;
            }
        }
        Attribute::Rotation => {
            if let Geometry::Rect { rotation, .. } | Geometry::Ellipse { rotation, .. } = g {
                *rotation = v;
            }
        }
        Attribute::Red => shape.fill.r = v,
        Attribute::Green => shape.fill.g = v,
        Attribute::Blue => shape.fill.b = v,
        Attribute::Alpha => shape.fill.a = v,
        Attribute::VertexX(i) => {
            if let Some(p) = vertex_mut(g, i) {
                p.x = v;
            }
        }
        Attribute::VertexY(i) => {
            if let Some(p) = vertex_mut(g, i) {
                p.y = v;
            }
        }
    }
}

/// Vertex i of a vertex shape (`None` for other kinds or out of range).
fn vertex(g: &Geometry, i: usize) -> Option<Point> {
    match g {
        Geometry::Triangle(v) => v.get(i).copied(),
        Geometry::Polygon(v) => v.get(i).copied(),
        Geometry::CubicPath { start, segments } => match i {
            0 => Some(*start),
            _ => segments.get((i - 1) / 3).map(|s| s[(i - 1) % 3]),
        },
        _ => None,
    }
}

/// Reads attribute `a` of `shape` (translations read as 0).
fn get(a: Attribute, shape: &Shape) -> f64 {
    let g = &shape.geometry;
    let centre = match g {
        Geometry::Rect { center, .. }
        | Geometry::Circle { center, .. }
        | Geometry::Ellipse { center, .. } => Some(*center),
        _ => None,
    };
    let v = match (a, g) {
        (Attribute::X, _) => centre.map_or(0.0, |c| c.x),
        (Attribute::Y, _) => centre.map_or(0.0, |c| c.y),
        (Attribute::Width, Geometry::Rect { width, .. }) => *width,
        (Attribute::Height, Geometry::Rect { height, .. }) => *height,
        (Attribute::Radius, Geometry::Circle { radius, .. }) => *radius,
        (Attribute::RadiusX, Geometry::Ellipse { radius_x, .. }) => *radius_x,
        (Attribute::RadiusY, Geometry::Ellipse { radius_y, .. }) => *radius_y,
        (
            Attribute::Rotation,
            Geometry::Rect { rotation, .. } | Geometry::Ellipse { rotation, .. },
        ) => *rotation,
        (Attribute::Red, _) => shape.fill.r,
        (Attribute::Green, _) => shape.fill.g,
        (Attribute::Blue, _) => shape.fill.b,
        (Attribute::Alpha, _) => shape.fill.a,
        (Attribute::VertexX(i), _) => vertex(g, i).map_or(0.0, |p| p.x),
        (Attribute::VertexY(i), _) => vertex(g, i).map_or(0.0, |p| p.y),
        _ => 0.0,
    };
    f64::from(v)
}
