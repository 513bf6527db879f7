//! θ ↔ shape geometry for the kinds a fit can place.
//!
//! Lengths are in units of `unit` pixels (an eighth of the image's longer side), so
//! θ is of order one; rotations are radians.
//!
//! | kind | θ |
//! |---|---|
//! | triangle | x₀, y₀, x₁, y₁, x₂, y₂ |
//! | rect (axis-aligned) | centre x, centre y, width, height |
//! | ellipse | centre x, centre y, semi-axis x, semi-axis y, rotation |
//! | circle | centre x, centre y, radius |

use crate::error::Error;
use crate::shape::{Geometry, Point, ShapeKind};

/// θ's dimension for `kind`.
///
/// # Errors
/// [`Error::InvalidOption`] for kinds a fit does not place (polygon, cubic path).
pub(crate) fn dim(kind: ShapeKind) -> Result<usize, Error> {
    match kind {
        ShapeKind::Triangle => Ok(6),
        ShapeKind::Rect => Ok(4),
        ShapeKind::Ellipse => Ok(5),
        ShapeKind::Circle => Ok(3),
        ShapeKind::Polygon | ShapeKind::CubicPath => Err(Error::InvalidOption {
            name: "kind",
            reason: "a fit places triangles, rects, ellipses or circles",
        }),
    }
}

/// The geometry at θ (coordinate k read by `t(k)`).
pub(crate) fn geometry(kind: ShapeKind, unit: f64, t: impl Fn(usize) -> f64) -> Geometry {
    let px = |k: usize| (t(k) * unit) as f32;
    match kind {
        ShapeKind::Triangle => Geometry::Triangle([
            Point::new(px(0), px(1)),
            Point::new(px(2), px(3)),
            Point::new(px(4), px(5)),
        ]),
        ShapeKind::Rect => Geometry::Rect {
            center: Point::new(px(0), px(1)),
            width: px(2),
            height: px(3),
            rotation: 0.0,
        },
        ShapeKind::Ellipse => Geometry::Ellipse {
            center: Point::new(px(0), px(1)),
            radius_x: px(2),
            radius_y: px(3),
            rotation: t(4) as f32,
        },
        _ => Geometry::Circle {
            center: Point::new(px(0), px(1)),
            radius: px(2),
        },
    }
}

/// A random shape of `kind` centred on pixel centre (`cx`, `cy`) with size about `r`
/// pixels, from uniform numbers `u()` in [0, 1), written as θ into `theta`.
pub(crate) fn random(
    kind: ShapeKind,
    unit: f64,
    (cx, cy): (f64, f64),
    r: f64,
    u: &mut impl FnMut() -> f64,
    theta: &mut [f64],
) {
    let tau = std::f64::consts::TAU;
    match kind {
        ShapeKind::Triangle => {
            let phi = u() * tau;
            for (k, v) in theta.chunks_exact_mut(2).enumerate() {
                let a = phi + tau * k as f64 / 3.0 + (u() - 0.5) * 1.2;
                let rr = r * (0.5 + u());
                v[0] = (cx + rr * a.cos()) / unit;
                v[1] = (cy + rr * a.sin()) / unit;
            }
        }
        ShapeKind::Rect => {
            theta[0] = cx / unit;
            theta[1] = cy / unit;
            theta[2] = 2.0 * r * (0.4 + 1.2 * u()) / unit;
            theta[3] = 2.0 * r * (0.4 + 1.2 * u()) / unit;
        }
        ShapeKind::Ellipse => {
            theta[0] = cx / unit;
            theta[1] = cy / unit;
            theta[2] = r * (0.4 + 1.2 * u()) / unit;
            theta[3] = r * (0.4 + 1.2 * u()) / unit;
            theta[4] = u() * std::f64::consts::PI;
        }
        _ => {
            theta[0] = cx / unit;
            theta[1] = cy / unit;
            theta[2] = r / unit;
        }
    }
}
