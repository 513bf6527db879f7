//! Small linear algebra: 3-vectors (also used as linear RGB triples), rays, orthonormal
//! frames and axis-aligned boxes.
//!
//! The renderer computes in `f32`: a 24-bit mantissa resolves 1e-7 of the scene size,
//! far below the smallest smoothing width σ the optimisers use (1e-2 scene units), and
//! halves the memory traffic of `f64`. Losses are accumulated in `f64` by the callers.

use std::ops::{Add, AddAssign, Div, Index, Mul, MulAssign, Neg, Sub};

/// A 3-vector of `f32`: a point, a direction, or a linear RGB colour.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3 {
    /// First component (x, or red).
    pub x: f32,
    /// Second component (y, or green).
    pub y: f32,
    /// Third component (z, or blue).
    pub z: f32,
}

/// A linear RGB triple (radiance in W·sr⁻¹·m⁻² per channel, or a reflectance in [0, 1]).
pub type Rgb = Vec3;

impl Vec3 {
    /// (0, 0, 0).
    pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);
    /// (1, 1, 1).
    pub const ONE: Vec3 = Vec3::new(1.0, 1.0, 1.0);

    /// (x, y, z).
    #[inline]
    pub const fn new(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3 { x, y, z }
    }

    /// (v, v, v).
    #[inline]
    pub const fn splat(v: f32) -> Vec3 {
        Vec3::new(v, v, v)
    }

    /// Dot product a·b.
    #[inline]
    pub fn dot(self, b: Vec3) -> f32 {
        self.x * b.x + self.y * b.y + self.z * b.z
    }

    /// Cross product a × b (right-handed).
    #[inline]
    pub fn cross(self, b: Vec3) -> Vec3 {
        Vec3::new(
            self.y * b.z - self.z * b.y,
            self.z * b.x - self.x * b.z,
            self.x * b.y - self.y * b.x,
        )
    }

    /// Squared Euclidean length.
    #[inline]
    pub fn length_squared(self) -> f32 {
        self.dot(self)
    }

    /// Euclidean length.
    #[inline]
    pub fn length(self) -> f32 {
        self.length_squared().sqrt()
    }

    /// The unit vector along `self`; the zero vector stays zero (never NaN).
    #[inline]
    pub fn normalized(self) -> Vec3 {
        let len2 = self.length_squared();
        if len2 > 0.0 {
            self * (1.0 / len2.sqrt())
        } else {
            Vec3::ZERO
        }
    }

    /// Component-wise minimum.
    #[inline]
    pub fn min(self, b: Vec3) -> Vec3 {
        Vec3::new(self.x.min(b.x), self.y.min(b.y), self.z.min(b.z))
    }

    /// Component-wise maximum.
    #[inline]
    pub fn max(self, b: Vec3) -> Vec3 {
        Vec3::new(self.x.max(b.x), self.y.max(b.y), self.z.max(b.z))
    }

    /// The largest component.
    #[inline]
    pub fn max_component(self) -> f32 {
        self.x.max(self.y).max(self.z)
    }

    /// The largest absolute component.
    #[inline]
    pub fn max_abs_component(self) -> f32 {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// Mean of the three components (luminance-free brightness for Russian roulette).
    #[inline]
    pub fn mean(self) -> f32 {
        (self.x + self.y + self.z) * (1.0 / 3.0)
    }

    /// Component-wise reciprocal; zero components map to ±∞ (used for slab tests,
    /// where ∞ is the correct limit).
    #[inline]
    pub fn recip(self) -> Vec3 {
        Vec3::new(1.0 / self.x, 1.0 / self.y, 1.0 / self.z)
    }

    /// True when every component is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// True when every component is zero.
    #[inline]
    pub fn is_black(self) -> bool {
        self.x == 0.0 && self.y == 0.0 && self.z == 0.0
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline]
    fn add(self, b: Vec3) -> Vec3 {
        Vec3::new(self.x + b.x, self.y + b.y, self.z + b.z)
    }
}

impl AddAssign for Vec3 {
    #[inline]
    fn add_assign(&mut self, b: Vec3) {
        *self = *self + b;
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline]
    fn sub(self, b: Vec3) -> Vec3 {
        Vec3::new(self.x - b.x, self.y - b.y, self.z - b.z)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f32> for Vec3 {
    type Output = Vec3;
    #[inline]
    fn mul(self, s: f32) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

/// Component-wise (Hadamard) product, as for colours.
impl Mul for Vec3 {
    type Output = Vec3;
    #[inline]
    fn mul(self, b: Vec3) -> Vec3 {
        Vec3::new(self.x * b.x, self.y * b.y, self.z * b.z)
    }
}

impl MulAssign for Vec3 {
    #[inline]
    fn mul_assign(&mut self, b: Vec3) {
        *self = *self * b;
    }
}

impl MulAssign<f32> for Vec3 {
    #[inline]
    fn mul_assign(&mut self, s: f32) {
        *self = *self * s;
    }
}

impl Div<f32> for Vec3 {
    type Output = Vec3;
    #[inline]
    fn div(self, s: f32) -> Vec3 {
        self * (1.0 / s)
    }
}

impl Index<usize> for Vec3 {
    type Output = f32;
    /// Component `axis` (0 = x, 1 = y, 2 = z); panics otherwise, like slice indexing.
    #[inline]
    fn index(&self, axis: usize) -> &f32 {
        match axis {
            0 => &self.x,
            1 => &self.y,
            2 => &self.z,
            _ => panic!("Vec3 axis {axis} out of range"),
        }
    }
}

/// A ray o + t·d, t ≥ 0. `d` need not be unit length unless a caller says so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Origin o.
    pub origin: Vec3,
    /// Direction d.
    pub dir: Vec3,
}

impl Ray {
    /// The ray from `origin` along `dir`.
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir }
    }

    /// The point o + t·d.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// An orthonormal frame (s, t, n): `n` is the given unit normal.
///
/// Built with the branch-free construction of Duff et al., *Building an Orthonormal Basis,
/// Revisited* (JCGT 2017), which is continuous except at n = −z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent, n × s.
    pub t: Vec3,
    /// Normal.
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n`.
    #[inline]
    pub fn from_normal(n: Vec3) -> Frame {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// Local coordinates (x, y, z) → world x·s + y·t + z·n.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// An axis-aligned bounding box; the empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The smallest box holding both boxes.
    #[inline]
    pub fn union(self, b: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(b.min),
            max: self.max.max(b.max),
        }
    }

    /// The smallest box holding `self` and the point `p`.
    #[inline]
    pub fn include(self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The centre point.
    #[inline]
    pub fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Surface area 2(xy + yz + zx); 0 for the empty box.
    #[inline]
    pub fn surface_area(&self) -> f32 {
        let d = self.max - self.min;
        if d.x < 0.0 || d.y < 0.0 || d.z < 0.0 {
            return 0.0;
        }
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Slab test: the entry distance when the ray (with `inv_dir` = 1/d) crosses the box
    /// within (0, `t_max`), else `None`.
    #[inline]
    pub fn hit(&self, origin: Vec3, inv_dir: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1);
        let far = t0.max(t1);
        let enter = near.x.max(near.y).max(near.z).max(0.0);
        let exit = far.x.min(far.y).min(far.z).min(t_max);
        // NaN (0·∞ on a slab boundary) compares false and so counts as a miss.
        if enter <= exit { Some(enter) } else { None }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal() {
        for n in [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(1.0, 2.0, -3.0).normalized(),
            Vec3::new(-0.3, 0.1, 0.9).normalized(),
        ] {
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-6);
            assert!((f.t.length() - 1.0).abs() < 1e-6);
            assert!(f.s.dot(f.n).abs() < 1e-6 && f.t.dot(f.n).abs() < 1e-6);
            assert!(f.s.dot(f.t).abs() < 1e-6);
        }
    }

    #[test]
    fn slab_test() {
        let b = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        let d = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(b.hit(Vec3::new(-3.0, 0.0, 0.0), d.recip(), 10.0), Some(2.0));
        assert_eq!(b.hit(Vec3::new(-3.0, 2.0, 0.0), d.recip(), 10.0), None);
        assert_eq!(b.hit(Vec3::new(-3.0, 0.0, 0.0), d.recip(), 1.0), None);
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
    }
}
