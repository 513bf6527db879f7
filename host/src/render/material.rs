//! Materials and their scattering: Lambertian diffuse, perfect mirror, smooth dielectric.
//!
//! Conventions: `wo` points away from the surface towards where the light goes (the
//! previous path vertex), `wi` away from the surface towards where it comes from; both
//! are unit vectors. Scattering functions are pure functions of their uniform numbers.
//!
//! * Lambert: f = ρ/π on both sides of the surface; `wi` ~ cos θ/π about the normal
//!   facing `wo` (Malley's method), so the sample weight f·cos/pdf = ρ.
//! * Mirror: wi = 2(n·wo)n − wo, weight = reflectance (a Dirac delta).
//! * Dielectric: reflect with the exact Fresnel reflectance F (unpolarised), else refract
//!   by Snell's law; choosing by F makes the weight 1 for reflection and 1/η² for
//!   refraction (η = η_t/η_i), the radiance scaling across an interface. Total internal
//!   reflection has F = 1.

use std::f32::consts::PI;

use super::error::RenderError;
use super::math::{Frame, Rgb, Vec3};

/// Where a diffuse albedo comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Albedo {
    /// A constant reflectance ρ (per channel, in [0, 1] for energy conservation).
    Constant(Rgb),
    /// Texture number `.0` of the scene, looked up at the hit's texture coordinates.
    Texture(usize),
}

/// A surface's scattering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// Absorbs everything (used for area emitters, which only emit).
    Black,
    /// Lambertian reflection with albedo ρ.
    Diffuse(Albedo),
    /// Perfect specular reflection scaled by a reflectance.
    Mirror(Rgb),
    /// Smooth dielectric interface with index of refraction `ior` (inside) against 1
    /// (outside, on the side the geometric normal points to).
    Dielectric {
        /// Index of refraction η > 0 of the inside.
        ior: f32,
    },
}

impl Material {
    /// A constant-albedo Lambertian material.
    pub fn diffuse(albedo: Rgb) -> Material {
        Material::Diffuse(Albedo::Constant(albedo))
    }

    /// True for materials whose scattering is a Dirac delta (no light sampling there).
    pub fn is_specular(&self) -> bool {
        matches!(self, Material::Mirror(_) | Material::Dielectric { .. })
    }

    /// Checks the material's numbers; `textures` is the scene's texture count.
    ///
    /// # Errors
    /// [`RenderError::InvalidMaterial`] or [`RenderError::InvalidTexture`].
    pub fn validate(&self, textures: usize) -> Result<(), RenderError> {
        match *self {
            Material::Black => Ok(()),
            Material::Diffuse(Albedo::Constant(rho)) | Material::Mirror(rho) => {
                if rho.is_finite() {
                    Ok(())
                } else {
                    Err(RenderError::InvalidMaterial("non-finite reflectance"))
                }
            }
            Material::Diffuse(Albedo::Texture(k)) => {
                if k < textures {
                    Ok(())
                } else {
                    Err(RenderError::InvalidTexture(
                        "material refers to a missing texture",
                    ))
                }
            }
            Material::Dielectric { ior } => {
                if ior.is_finite() && ior > 0.0 {
                    Ok(())
                } else {
                    Err(RenderError::InvalidMaterial(
                        "index of refraction must be finite and > 0",
                    ))
                }
            }
        }
    }
}

/// A cosine-distributed direction about `n` from (u₁, u₂) ∈ [0, 1)², and its solid-angle
/// density cos θ/π. Malley's method: a uniform point on the unit disc lifted to the
/// hemisphere.
#[inline]
pub fn sample_cosine(n: Vec3, u1: f32, u2: f32) -> (Vec3, f32) {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (s, c) = phi.sin_cos();
    let z = (1.0 - u1).max(0.0).sqrt();
    let local = Vec3::new(r * c, r * s, z);
    (Frame::from_normal(n).to_world(local), z * (1.0 / PI))
}

/// Mirror reflection of `wo` about the unit normal `n`.
#[inline]
pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    n * (2.0 * n.dot(wo)) - wo
}

/// Unpolarised Fresnel reflectance of a smooth interface for incident cosine `cos_i`
/// (> 0) and relative index η = η_t/η_i, with the refracted cosine; F = 1 and cos_t = 0
/// on total internal reflection.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> (f32, f32) {
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// A sampled specular bounce: the new direction and the path-throughput factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularSample {
    /// The incident direction wi (unit).
    pub wi: Vec3,
    /// Throughput factor (reflectance, or the dielectric weight 1 or 1/η²).
    pub weight: Rgb,
}

/// Samples a smooth dielectric at a surface with unit shading normal `ns` (outward) for
/// outgoing direction `wo`, choosing reflection with probability F using `u`.
#[inline]
pub fn sample_dielectric(wo: Vec3, ns: Vec3, ior: f32, u: f32) -> SpecularSample {
    let cos_o = ns.dot(wo);
    // The side `wo` lies on decides which index is on which side.
    let (n, eta, cos_i) = if cos_o >= 0.0 {
        (ns, ior, cos_o)
    } else {
        (-ns, 1.0 / ior, -cos_o)
    };
    let (f, cos_t) = fresnel_dielectric(cos_i.max(1e-7), eta);
    if u < f {
        SpecularSample {
            wi: reflect(wo, n),
            weight: Rgb::ONE,
        }
    } else {
        let wi = (-wo / eta + n * (cos_i / eta - cos_t)).normalized();
        SpecularSample {
            wi,
            weight: Rgb::splat(1.0 / (eta * eta)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_limits() {
        // Normal incidence: ((η − 1)/(η + 1))².
        let (f, _) = fresnel_dielectric(1.0, 1.5);
        assert!((f - 0.04).abs() < 1e-6);
        // Grazing: → 1. Total internal reflection from inside glass.
        assert!(fresnel_dielectric(1e-4, 1.5).0 > 0.99);
        assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5).0, 1.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::new(0.0, 0.0, 1.0);
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = sample_dielectric(wo, n, 1.5, 0.999);
        // sin θ_t = sin θ_i / η, on the far side.
        assert!(s.wi.z < 0.0);
        assert!((s.wi.x.abs() - 0.6 / 1.5).abs() < 1e-6);
        assert!((s.weight.x - 1.0 / 2.25).abs() < 1e-6);
        let r = sample_dielectric(wo, n, 1.5, 0.0);
        assert!((r.wi - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
    }

    #[test]
    fn cosine_samples_lie_in_the_hemisphere() {
        let n = Vec3::new(0.0, 1.0, 0.0);
        for k in 0..64 {
            let (wi, pdf) = sample_cosine(n, (k as f32 + 0.5) / 64.0, (k * 37 % 64) as f32 / 64.0);
            assert!(wi.dot(n) >= 0.0 && (wi.length() - 1.0).abs() < 1e-5);
            assert!((pdf - wi.dot(n) / PI).abs() < 1e-5);
        }
    }
}
