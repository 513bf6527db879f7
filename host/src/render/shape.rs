//! Shapes: spheres, parallelogram quads, oriented boxes and transformed triangle meshes.
//!
//! Each shape answers three questions: the closest hit along a ray ([`Shape::intersect`],
//! cheap, no shading data), whether a segment is blocked ([`Shape::occluded`]), and the
//! surface data at a hit ([`Shape::surface`]: point, normals, texture coordinates),
//! computed only for the one hit that is shaded.

use super::error::RenderError;
use super::math::{Aabb, Ray, Vec3};
use super::mesh::Mesh;
use super::transform::Transform;

/// A sphere ‖p − c‖ = r. Its geometric normal points outwards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre c.
    pub center: Vec3,
    /// Radius r > 0.
    pub radius: f32,
}

impl Sphere {
    /// Closest root of ‖o + t·d − c‖² = r² in (0, `t_max`), via the numerically stable
    /// form of the quadratic (the root of larger magnitude first, the other as c/(a·t₁)).
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let oc = ray.origin - self.center;
        let half_b = oc.dot(ray.dir);
        let c = oc.length_squared() - self.radius * self.radius;
        // Outside and moving away: no root ahead (the common case for rays that pass
        // behind, e.g. every camera ray of SHADOW).
        if c > 0.0 && half_b > 0.0 {
            return None;
        }
        let a = ray.dir.length_squared();
        // Discriminant as r² − ‖oc − (oc·d̂)d̂‖², which keeps precision far from the sphere.
        let perp = oc - ray.dir * (half_b / a);
        let disc = a * (self.radius * self.radius - perp.length_squared());
        if disc < 0.0 {
            return None;
        }
        let q = -(half_b + half_b.signum() * disc.sqrt());
        let (mut t0, mut t1) = (q / a, c / q);
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        if t0 > 0.0 && t0 < t_max {
            Some(t0)
        } else if t1 > 0.0 && t1 < t_max {
            Some(t1)
        } else {
            None
        }
    }

    /// Surface area 4πr².
    pub fn area(&self) -> f32 {
        4.0 * std::f32::consts::PI * self.radius * self.radius
    }
}

/// A parallelogram {corner + a·edge_u + b·edge_v : a, b ∈ [0, 1]} with geometric normal
/// n = edge_u × edge_v / ‖edge_u × edge_v‖ and texture coordinates (a, b).
///
/// Intersection: t = (n·corner − n·o)/(n·d), then (a, b) = (q·u*, q·v*) for q = p − corner,
/// with the dual basis u* = (edge_v × n)/A, v* = (n × edge_u)/A (A the area), which
/// satisfies u*·edge_u = v*·edge_v = 1, u*·edge_v = v*·edge_u = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    normal: Vec3,
    /// n·corner, the plane offset.
    offset: f32,
    dual_u: Vec3,
    dual_v: Vec3,
    area: f32,
}

impl Quad {
    /// The parallelogram spanned by `edge_u`, `edge_v` at `corner`.
    ///
    /// # Errors
    /// [`RenderError::InvalidGeometry`] if an input is not finite or the area is zero.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Result<Quad, RenderError> {
        if !(corner.is_finite() && edge_u.is_finite() && edge_v.is_finite()) {
            return Err(RenderError::InvalidGeometry("non-finite quad"));
        }
        let cross = edge_u.cross(edge_v);
        let area = cross.length();
        if area <= 0.0 || !area.is_finite() {
            return Err(RenderError::InvalidGeometry("zero-area quad"));
        }
        let normal = cross / area;
        Ok(Quad {
            corner,
            edge_u,
            edge_v,
            normal,
            offset: normal.dot(corner),
            dual_u: edge_v.cross(normal) / area,
            dual_v: normal.cross(edge_u) / area,
            area,
        })
    }

    /// An axis-aligned rectangle centred at `center`, spanning `size.0` along `u_dir` and
    /// `size.1` along `v_dir` (unit vectors); the normal is u_dir × v_dir.
    ///
    /// # Errors
    /// As [`Quad::new`].
    pub fn centered(
        center: Vec3,
        u_dir: Vec3,
        v_dir: Vec3,
        size: (f32, f32),
    ) -> Result<Quad, RenderError> {
        let eu = u_dir * size.0;
        let ev = v_dir * size.1;
        Quad::new(center - eu * 0.5 - ev * 0.5, eu, ev)
    }

    /// Unit geometric normal.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// Area ‖edge_u × edge_v‖.
    pub fn area(&self) -> f32 {
        self.area
    }

    /// The point with quad coordinates (a, b) ∈ [0, 1]².
    #[inline]
    pub fn point(&self, a: f32, b: f32) -> Vec3 {
        self.corner + self.edge_u * a + self.edge_v * b
    }

    /// Distance to the plane hit inside the parallelogram, in (0, `t_max`).
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let denom = self.normal.dot(ray.dir);
        let num = self.offset - self.normal.dot(ray.origin);
        // t = num/denom ∈ (0, t_max) needs equal signs and |num| < t_max·|denom|: most
        // misses are rejected before the division (whose latency dominates this test).
        // The sign test also rejects denom = 0 and NaN.
        let same_sign = num * denom > 0.0;
        if !same_sign || num.abs() >= t_max * denom.abs() {
            return None;
        }
        let t = num / denom;
        if t >= t_max {
            return None;
        }
        let (a, b) = self.coords(ray.at(t));
        if (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) {
            Some(t)
        } else {
            None
        }
    }

    /// Quad coordinates (a, b) of a point on the plane.
    #[inline]
    fn coords(&self, p: Vec3) -> (f32, f32) {
        let q = p - self.corner;
        (q.dot(self.dual_u), q.dot(self.dual_v))
    }

    fn bounds(&self) -> Aabb {
        Aabb::EMPTY
            .include(self.corner)
            .include(self.corner + self.edge_u)
            .include(self.corner + self.edge_v)
            .include(self.corner + self.edge_u + self.edge_v)
    }
}

/// The box [−half, half]³ (per axis) mapped to the world by a transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    /// Half extents along the object axes (all > 0).
    pub half: Vec3,
    /// Object-to-world transform.
    pub transform: Transform,
}

impl Cuboid {
    /// Entry distance (or exit distance from inside) and the object-space axis crossed,
    /// signed (±1, ±2, ±3 for ±x, ±y, ±z).
    #[inline]
    fn hit(&self, ray: &Ray, t_max: f32) -> Option<(f32, i8)> {
        // Affine maps preserve the ray parameter, so t is the same in both spaces.
        let o = self.transform.inverse_point(ray.origin);
        let d = self.transform.inverse_vector(ray.dir);
        let inv = d.recip();
        let mut enter = (f32::NEG_INFINITY, 0i8);
        let mut exit = (f32::INFINITY, 0i8);
        for axis in 0..3 {
            let mut t0 = (-self.half[axis] - o[axis]) * inv[axis];
            let mut t1 = (self.half[axis] - o[axis]) * inv[axis];
            let mut s0 = -(axis as i8 + 1);
            let mut s1 = axis as i8 + 1;
            if t0 > t1 {
                std::mem::swap(&mut t0, &mut t1);
                std::mem::swap(&mut s0, &mut s1);
            }
            if t0 > enter.0 {
                enter = (t0, s0);
            }
            if t1 < exit.0 {
                exit = (t1, s1);
            }
        }
        // Written to reject NaN slabs (0·∞) too.
        if enter.0.partial_cmp(&exit.0) == Some(std::cmp::Ordering::Greater)
            || enter.0.is_nan()
            || exit.0.is_nan()
        {
            return None;
        }
        if enter.0 > 0.0 && enter.0 < t_max {
            Some(enter)
        } else if enter.0 <= 0.0 && exit.0 > 0.0 && exit.0 < t_max {
            Some(exit)
        } else {
            None
        }
    }

    fn local_bounds(&self) -> Aabb {
        Aabb {
            min: -self.half,
            max: self.half,
        }
    }
}

/// A mesh placed by an object-to-world transform.
#[derive(Clone, Debug)]
pub struct MeshInstance {
    /// The mesh, in object space.
    pub mesh: Mesh,
    /// Object-to-world transform.
    pub transform: Transform,
}

/// Any shape the renderer knows.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// A parallelogram.
    Quad(Quad),
    /// An oriented box.
    Cuboid(Cuboid),
    /// A transformed triangle mesh.
    Mesh(Box<MeshInstance>),
}

/// The result of a closest-hit query: distance plus what is needed to rebuild the
/// surface data later.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter t.
    pub t: f32,
    /// Index of the object hit in its scene.
    pub object: u32,
    /// Triangle index (meshes) or signed face axis (cuboids); 0 otherwise.
    pub prim: i32,
    /// First barycentric coordinate (meshes).
    pub u: f32,
    /// Second barycentric coordinate (meshes).
    pub v: f32,
}

/// Surface data at a hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Position.
    pub p: Vec3,
    /// Unit geometric normal (the shape's outward orientation).
    pub ng: Vec3,
    /// Unit shading normal, in the same hemisphere as `ng`.
    pub ns: Vec3,
    /// Texture coordinates (quads: the quad coordinates; spheres: longitude/latitude
    /// fractions; others: 0).
    pub uv: (f32, f32),
}

impl Shape {
    /// Checks the shape's numbers (finite, positive sizes, usable transforms).
    ///
    /// # Errors
    /// [`RenderError::InvalidGeometry`] or [`RenderError::InvalidTransform`].
    pub fn validate(&self) -> Result<(), RenderError> {
        match self {
            Shape::Sphere(s) => {
                if !(s.center.is_finite() && s.radius.is_finite() && s.radius > 0.0) {
                    return Err(RenderError::InvalidGeometry(
                        "sphere needs a finite centre and radius > 0",
                    ));
                }
            }
            Shape::Quad(_) => {}
            Shape::Cuboid(c) => {
                if !(c.half.is_finite() && c.half.x > 0.0 && c.half.y > 0.0 && c.half.z > 0.0) {
                    return Err(RenderError::InvalidGeometry(
                        "box half extents must be finite and > 0",
                    ));
                }
                if !c.transform.is_finite() {
                    return Err(RenderError::InvalidTransform);
                }
            }
            Shape::Mesh(m) => {
                if !m.transform.is_finite() {
                    return Err(RenderError::InvalidTransform);
                }
            }
        }
        Ok(())
    }

    /// World-space bounds.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => Aabb {
                min: s.center - Vec3::splat(s.radius),
                max: s.center + Vec3::splat(s.radius),
            },
            Shape::Quad(q) => q.bounds(),
            Shape::Cuboid(c) => c.transform.bounds(&c.local_bounds()),
            Shape::Mesh(m) => m.transform.bounds(&m.mesh.bounds()),
        }
    }

    /// The closest hit in (0, `t_max`), tagged with `object`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32, object: u32) -> Option<Hit> {
        let plain = |t| Hit {
            t,
            object,
            prim: 0,
            u: 0.0,
            v: 0.0,
        };
        match self {
            Shape::Sphere(s) => s.hit(ray, t_max).map(plain),
            Shape::Quad(q) => q.hit(ray, t_max).map(plain),
            Shape::Cuboid(c) => c.hit(ray, t_max).map(|(t, face)| Hit {
                prim: i32::from(face),
                ..plain(t)
            }),
            Shape::Mesh(m) => {
                let o = m.transform.inverse_point(ray.origin);
                let d = m.transform.inverse_vector(ray.dir);
                m.mesh.intersect(o, d, t_max).map(|h| Hit {
                    t: h.t,
                    object,
                    prim: h.triangle as i32,
                    u: h.u,
                    v: h.v,
                })
            }
        }
    }

    /// True if the shape blocks the ray within (0, `t_max`).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        match self {
            Shape::Sphere(s) => s.hit(ray, t_max).is_some(),
            Shape::Quad(q) => q.hit(ray, t_max).is_some(),
            Shape::Cuboid(c) => c.hit(ray, t_max).is_some(),
            Shape::Mesh(m) => {
                let o = m.transform.inverse_point(ray.origin);
                let d = m.transform.inverse_vector(ray.dir);
                m.mesh.occluded(o, d, t_max)
            }
        }
    }

    /// True when a ray leaving this shape's surface point with outward geometric normal
    /// `ng` along `dir` cannot meet the shape again: always for a plane, on the outer
    /// side for convex solids (spheres, boxes), never assumed for meshes.
    #[inline]
    pub fn cannot_rehit(&self, ng: Vec3, dir: Vec3) -> bool {
        match self {
            Shape::Quad(_) => true,
            Shape::Sphere(_) | Shape::Cuboid(_) => ng.dot(dir) > 0.0,
            Shape::Mesh(_) => false,
        }
    }

    /// Surface data at `hit` (from [`Shape::intersect`] with the same `ray`).
    /// `want_uv` = false skips the texture coordinates.
    #[inline]
    pub fn surface(&self, ray: &Ray, hit: &Hit, want_uv: bool) -> Surface {
        let p = ray.at(hit.t);
        match self {
            Shape::Sphere(s) => {
                let n = ((p - s.center) * (1.0 / s.radius)).normalized();
                let uv = if want_uv {
                    let u = 0.5 + n.y.atan2(n.x) * (0.5 / std::f32::consts::PI);
                    let v = 0.5 + n.z.clamp(-1.0, 1.0).asin() / std::f32::consts::PI;
                    (u, v)
                } else {
                    (0.0, 0.0)
                };
                Surface {
                    p,
                    ng: n,
                    ns: n,
                    uv,
                }
            }
            Shape::Quad(q) => {
                let uv = if want_uv { q.coords(p) } else { (0.0, 0.0) };
                Surface {
                    p,
                    ng: q.normal,
                    ns: q.normal,
                    uv,
                }
            }
            Shape::Cuboid(c) => {
                let axis = (hit.prim.unsigned_abs() - 1) as usize;
                let mut local = Vec3::ZERO;
                let sign = if hit.prim > 0 { 1.0 } else { -1.0 };
                match axis {
                    0 => local.x = sign,
                    1 => local.y = sign,
                    _ => local.z = sign,
                }
                let n = c.transform.normal(local).normalized();
                Surface {
                    p,
                    ng: n,
                    ns: n,
                    uv: (0.0, 0.0),
                }
            }
            Shape::Mesh(m) => {
                let h = super::mesh::MeshHit {
                    t: hit.t,
                    triangle: hit.prim as u32,
                    u: hit.u,
                    v: hit.v,
                };
                let (ng, ns) = m.mesh.normals_at(&h);
                let ng = m.transform.normal(ng).normalized();
                let ns = m.transform.normal(ns).normalized();
                let ns = if ns.dot(ng) < 0.0 { -ns } else { ns };
                Surface {
                    p,
                    ng,
                    ns,
                    uv: (hit.u, hit.v),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_hits_from_outside_and_inside() {
        let s = Sphere {
            center: Vec3::new(0.0, 0.0, 5.0),
            radius: 1.0,
        };
        let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0));
        assert!((s.hit(&ray, 100.0).unwrap() - 4.0).abs() < 1e-5);
        let inside = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, 1.0));
        assert!((s.hit(&inside, 100.0).unwrap() - 1.0).abs() < 1e-5);
        let miss = Ray::new(Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
        assert!(s.hit(&miss, 100.0).is_none());
    }

    #[test]
    fn quad_hit_and_coordinates() {
        let q = Quad::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        )
        .unwrap();
        assert_eq!(q.normal(), Vec3::new(0.0, 0.0, 1.0));
        let ray = Ray::new(Vec3::new(1.5, 0.25, 3.0), Vec3::new(0.0, 0.0, -1.0));
        let t = q.hit(&ray, 10.0).unwrap();
        assert!((t - 3.0).abs() < 1e-6);
        let (a, b) = q.coords(ray.at(t));
        assert!((a - 0.75).abs() < 1e-6 && (b - 0.25).abs() < 1e-6);
        assert!(Quad::new(Vec3::ZERO, Vec3::ONE, Vec3::ONE * 2.0).is_err());
    }

    #[test]
    fn rotated_cuboid_normal() {
        let c = Shape::Cuboid(Cuboid {
            half: Vec3::splat(0.5),
            transform: Transform::rotation_z(0.3)
                .then(&Transform::translation(Vec3::new(0.0, 0.0, 2.0))),
        });
        let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), Vec3::new(0.0, 0.0, -1.0));
        let hit = c.intersect(&ray, 100.0, 0).unwrap();
        assert!((hit.t - 7.5).abs() < 1e-5);
        let s = c.surface(&ray, &hit, false);
        assert!((s.ng - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-6);
    }
}
