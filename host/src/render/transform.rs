//! Affine transforms x ↦ M·x + t, stored with their inverse.
//!
//! Objects whose placement θ drives (the MUG's rotation, the CBOX's small box) keep
//! their geometry and acceleration structure in object space and carry a transform:
//! changing θ changes twelve numbers, never a mesh or a BVH.

use super::error::RenderError;
use super::math::{Aabb, Vec3};

/// An invertible affine map x ↦ M·x + t (row-major M) and its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    m: [[f32; 3]; 3],
    t: Vec3,
    inv_m: [[f32; 3]; 3],
    inv_t: Vec3,
}

fn mat_vec(m: &[[f32; 3]; 3], v: Vec3) -> Vec3 {
    Vec3::new(
        m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
        m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
        m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
    )
}

fn transpose_vec(m: &[[f32; 3]; 3], v: Vec3) -> Vec3 {
    Vec3::new(
        m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
        m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
        m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z,
    )
}

fn mat_mul(a: &[[f32; 3]; 3], b: &[[f32; 3]; 3]) -> [[f32; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

const IDENTITY3: [[f32; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

impl Transform {
    /// x ↦ x.
    pub const IDENTITY: Transform = Transform {
        m: IDENTITY3,
        t: Vec3::ZERO,
        inv_m: IDENTITY3,
        inv_t: Vec3::ZERO,
    };

    /// x ↦ x + `offset`.
    pub fn translation(offset: Vec3) -> Transform {
        Transform {
            t: offset,
            inv_t: -offset,
            ..Transform::IDENTITY
        }
    }

    /// Rotation by `angle` radians about the +z axis (counter-clockwise seen from +z).
    pub fn rotation_z(angle: f32) -> Transform {
        let (s, c) = angle.sin_cos();
        let m = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let inv_m = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]];
        Transform {
            m,
            t: Vec3::ZERO,
            inv_m,
            inv_t: Vec3::ZERO,
        }
    }

    /// Scaling by `factors` along x, y, z.
    ///
    /// # Errors
    /// [`RenderError::InvalidTransform`] if a factor is zero or not finite.
    pub fn scale(factors: Vec3) -> Result<Transform, RenderError> {
        let ok = |f: f32| f.is_finite() && f != 0.0;
        if !(ok(factors.x) && ok(factors.y) && ok(factors.z)) {
            return Err(RenderError::InvalidTransform);
        }
        Ok(Transform {
            m: [
                [factors.x, 0.0, 0.0],
                [0.0, factors.y, 0.0],
                [0.0, 0.0, factors.z],
            ],
            t: Vec3::ZERO,
            inv_m: [
                [1.0 / factors.x, 0.0, 0.0],
                [0.0, 1.0 / factors.y, 0.0],
                [0.0, 0.0, 1.0 / factors.z],
            ],
            inv_t: Vec3::ZERO,
        })
    }

    /// `self` followed by `next`: x ↦ next(self(x)).
    pub fn then(&self, next: &Transform) -> Transform {
        let m = mat_mul(&next.m, &self.m);
        let t = mat_vec(&next.m, self.t) + next.t;
        let inv_m = mat_mul(&self.inv_m, &next.inv_m);
        let inv_t = mat_vec(&self.inv_m, next.inv_t) + self.inv_t;
        Transform { m, t, inv_m, inv_t }
    }

    /// M·p + t.
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        mat_vec(&self.m, p) + self.t
    }

    /// M·v (a direction).
    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        mat_vec(&self.m, v)
    }

    /// M⁻ᵀ·n (a surface normal; not renormalised).
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        transpose_vec(&self.inv_m, n)
    }

    /// M⁻¹·(p − t).
    #[inline]
    pub fn inverse_point(&self, p: Vec3) -> Vec3 {
        mat_vec(&self.inv_m, p) + self.inv_t
    }

    /// M⁻¹·v.
    #[inline]
    pub fn inverse_vector(&self, v: Vec3) -> Vec3 {
        mat_vec(&self.inv_m, v)
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        let rows_ok = |m: &[[f32; 3]; 3]| m.iter().flatten().all(|v| v.is_finite());
        rows_ok(&self.m) && rows_ok(&self.inv_m) && self.t.is_finite() && self.inv_t.is_finite()
    }

    /// The world-space box bounding the image of the object-space box `b`.
    pub fn bounds(&self, b: &Aabb) -> Aabb {
        let mut out = Aabb::EMPTY;
        for corner in 0..8 {
            let p = Vec3::new(
                if corner & 1 == 0 { b.min.x } else { b.max.x },
                if corner & 2 == 0 { b.min.y } else { b.max.y },
                if corner & 4 == 0 { b.min.z } else { b.max.z },
            );
            out = out.include(self.point(p));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_and_inverse() {
        let a = Transform::rotation_z(0.7)
            .then(&Transform::scale(Vec3::new(2.0, 1.0, 0.5)).unwrap())
            .then(&Transform::translation(Vec3::new(1.0, -2.0, 3.0)));
        let p = Vec3::new(0.3, -0.4, 1.1);
        let q = a.inverse_point(a.point(p));
        assert!((q - p).length() < 1e-5);
        let r = Transform::rotation_z(std::f32::consts::FRAC_PI_2).point(Vec3::new(1.0, 0.0, 0.0));
        assert!((r - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-6);
        assert!(Transform::scale(Vec3::new(0.0, 1.0, 1.0)).is_err());
    }
}
