//! Light sources and their sampling for next-event estimation.
//!
//! * Area emitters are quads or spheres with an [`Emitter`]: constant radiance Le on the
//!   side the geometric normal points to (or both sides). A point y is drawn uniformly
//!   by area (density 1/A) and converted to solid angle at the shading point x:
//!   p_ω = p_A·‖y − x‖²/|cos θ_y|.
//! * Point lights have intensity I (W/sr); the irradiance they give is I·cos θ/‖y − x‖²
//!   and they cannot be hit by rays (a delta light, no MIS).
//!
//! The integrator picks one light uniformly, so every density above is multiplied by
//! 1/(number of lights).

use std::f32::consts::PI;

use super::math::{Rgb, Vec3};
use super::shape::Shape;

/// Area emission attached to an object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emitter {
    /// Emitted radiance Le (W·sr⁻¹·m⁻² per channel, ≥ 0).
    pub radiance: Rgb,
    /// Emit on both sides (else only where the geometric normal points).
    pub two_sided: bool,
}

impl Emitter {
    /// One-sided emission of radiance `radiance`.
    pub fn new(radiance: Rgb) -> Emitter {
        Emitter {
            radiance,
            two_sided: false,
        }
    }

    /// The radiance leaving towards `w` (unit, pointing away from the surface) from a
    /// surface point with geometric normal `ng`.
    #[inline]
    pub fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Rgb {
        if self.two_sided || ng.dot(w) > 0.0 {
            self.radiance
        } else {
            Rgb::ZERO
        }
    }
}

/// An isotropic point light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Position.
    pub position: Vec3,
    /// Radiant intensity I (W/sr per channel, ≥ 0).
    pub intensity: Rgb,
}

/// A light the integrator can sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// The emitting object with this index.
    Area {
        /// Object index in the scene.
        object: u32,
        /// Its area A.
        area: f32,
    },
    /// A point light.
    Point(PointLight),
}

/// A uniform-by-area point on an emitting shape from (u₁, u₂) ∈ [0, 1)², with its unit
/// geometric normal. Only quads and spheres are area emitters (checked at commit).
#[inline]
pub fn sample_area(shape: &Shape, u1: f32, u2: f32) -> (Vec3, Vec3) {
    match shape {
        Shape::Quad(q) => (q.point(u1, u2), q.normal()),
        Shape::Sphere(s) => {
            let n = uniform_sphere(u1, u2);
            (s.center + n * s.radius, n)
        }
        // Unreachable for committed scenes; a harmless point with no normal gives zero
        // contribution (cos θ_y = 0).
        Shape::Cuboid(_) | Shape::Mesh(_) => (Vec3::ZERO, Vec3::ZERO),
    }
}

/// A unit direction uniform over the sphere from (u₁, u₂) ∈ [0, 1)²: z = 1 − 2u₁,
/// azimuth 2πu₂ (density 1/(4π)).
#[inline]
pub fn uniform_sphere(u1: f32, u2: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u1;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin, cos) = (2.0 * PI * u2).sin_cos();
    Vec3::new(r * cos, r * sin, z)
}

/// Power-heuristic (Veach, exponent 2) weight of the technique with density `a` against
/// one with density `b`: a²/(a² + b²). Returns 0 when both are 0.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::shape::{Quad, Sphere};

    #[test]
    fn area_samples_lie_on_the_shape() {
        let s = Shape::Sphere(Sphere {
            center: Vec3::new(1.0, 2.0, 3.0),
            radius: 2.0,
        });
        let q = Shape::Quad(
            Quad::new(
                Vec3::ZERO,
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            )
            .unwrap(),
        );
        for k in 0..16 {
            let (u1, u2) = (k as f32 / 16.0, (k * 5 % 16) as f32 / 16.0);
            let (p, n) = sample_area(&s, u1, u2);
            assert!(((p - Vec3::new(1.0, 2.0, 3.0)).length() - 2.0).abs() < 1e-5);
            assert!((n.length() - 1.0).abs() < 1e-5);
            let (p, n) = sample_area(&q, u1, u2);
            assert!(p.z == 0.0 && n == Vec3::new(0.0, 0.0, 1.0));
        }
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        assert!((power_heuristic(1.0, 1.0) - 0.5).abs() < 1e-7);
    }
}
