//! Indexed triangle meshes under a [`Bvh`], with optional per-vertex shading normals.
//!
//! Triangles are intersected with the Möller–Trumbore algorithm (JGT 1997): with
//! e₁ = p₁ − p₀, e₂ = p₂ − p₀, the hit o + t·d = (1 − u − v)p₀ + u·p₁ + v·p₂ solves
//! [−d e₁ e₂](t u v)ᵀ = o − p₀ by Cramer's rule; a hit needs u, v ≥ 0, u + v ≤ 1 and
//! t in (0, t_max).
//!
//! Zero-area triangles are dropped on construction (they can never be hit and would give
//! an undefined normal); a mesh with none left is [`RenderError::DegenerateMesh`].

use super::bvh::Bvh;
use super::error::RenderError;
use super::math::{Aabb, Vec3};

/// Triangles whose area is below this fraction of the squared bounding-box diagonal are
/// treated as degenerate.
const DEGENERATE_AREA: f32 = 1e-12;

/// A triangle mesh in its own (object) space.
#[derive(Clone, Debug)]
pub struct Mesh {
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    /// Every triangle given.
    all_triangles: Vec<[u32; 3]>,
    /// The triangles of positive area (the ones intersected).
    triangles: Vec<[u32; 3]>,
    /// Per triangle: p₀, e₁, e₂ (precomputed for intersection).
    edges: Vec<[Vec3; 3]>,
    /// Build scratch: per-triangle boxes.
    boxes: Vec<Aabb>,
    bvh: Bvh,
    dropped: usize,
}

/// Where a ray meets a mesh: distance, triangle and barycentrics (u, v) of p₁ and p₂.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Ray parameter t.
    pub t: f32,
    /// Triangle index.
    pub triangle: u32,
    /// Barycentric weight of the second vertex.
    pub u: f32,
    /// Barycentric weight of the third vertex.
    pub v: f32,
}

impl Mesh {
    /// A mesh from vertex `positions`, counter-clockwise `triangles` (the geometric
    /// normal is (p₁ − p₀) × (p₂ − p₀)) and optional per-vertex shading `normals`.
    ///
    /// # Errors
    /// [`RenderError::InvalidGeometry`] for a non-finite position or normal, or a normals
    /// array of the wrong length; [`RenderError::MeshIndexOutOfRange`];
    /// [`RenderError::DegenerateMesh`] when no triangle has positive area.
    pub fn new(
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        normals: Option<Vec<Vec3>>,
    ) -> Result<Mesh, RenderError> {
        let mut mesh = Mesh {
            positions,
            normals,
            all_triangles: triangles,
            triangles: Vec::new(),
            edges: Vec::new(),
            boxes: Vec::new(),
            bvh: Bvh::new(),
            dropped: 0,
        };
        if let Some(n) = &mesh.normals
            && n.len() != mesh.positions.len()
        {
            return Err(RenderError::InvalidGeometry(
                "normals and positions differ in length",
            ));
        }
        for tri in &mesh.all_triangles {
            for &i in tri {
                if i as usize >= mesh.positions.len() {
                    return Err(RenderError::MeshIndexOutOfRange {
                        index: i,
                        vertices: mesh.positions.len(),
                    });
                }
            }
        }
        mesh.refresh()?;
        Ok(mesh)
    }

    /// Moves the vertices (same count) and optionally replaces the shading normals, then
    /// rebuilds the BVH in place. Allocation-free when the triangle count is unchanged.
    ///
    /// # Errors
    /// As [`Mesh::new`]; on error the mesh keeps the new positions but must not be
    /// rendered (the scene stays uncommitted).
    pub fn update(
        &mut self,
        positions: &[Vec3],
        normals: Option<&[Vec3]>,
    ) -> Result<(), RenderError> {
        if positions.len() != self.positions.len() {
            return Err(RenderError::InvalidGeometry("vertex count changed"));
        }
        self.positions.copy_from_slice(positions);
        match (normals, &mut self.normals) {
            (Some(src), Some(dst)) if src.len() == dst.len() => dst.copy_from_slice(src),
            (None, _) => {}
            _ => {
                return Err(RenderError::InvalidGeometry(
                    "normals and positions differ in length",
                ));
            }
        }
        self.refresh()
    }

    /// Validates positions, drops degenerate triangles, refreshes edges and the BVH.
    fn refresh(&mut self) -> Result<(), RenderError> {
        if !self.positions.iter().all(|p| p.is_finite()) {
            return Err(RenderError::InvalidGeometry("non-finite mesh vertex"));
        }
        if let Some(n) = &self.normals
            && !n.iter().all(|v| v.is_finite())
        {
            return Err(RenderError::InvalidGeometry("non-finite mesh normal"));
        }
        let bounds = self
            .positions
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.include(p));
        let diag2 = (bounds.max - bounds.min).length_squared();
        let positions = &self.positions;
        self.triangles.clear();
        self.triangles.extend(self.all_triangles.iter().filter(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            (b - a).cross(c - a).length() > DEGENERATE_AREA * diag2
        }));
        self.dropped = self.all_triangles.len() - self.triangles.len();
        if self.triangles.is_empty() {
            return Err(RenderError::DegenerateMesh);
        }
        self.edges.clear();
        self.boxes.clear();
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            self.edges.push([a, b - a, c - a]);
            self.boxes
                .push(Aabb::EMPTY.include(a).include(b).include(c));
        }
        self.bvh.build(&self.boxes);
        Ok(())
    }

    /// Object-space bounds.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// Number of (non-degenerate) triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Degenerate triangles dropped at the last build.
    pub fn dropped_triangles(&self) -> usize {
        self.dropped
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// The triangles of positive area (vertex indices).
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Per-vertex shading normals; zero vectors (meaning "use the geometric normal")
    /// when the mesh has none.
    pub fn vertex_normals(&self) -> Vec<Vec3> {
        match &self.normals {
            Some(n) => n.clone(),
            None => vec![Vec3::ZERO; self.positions.len()],
        }
    }

    /// Closest hit in (0, `t_max`).
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<MeshHit> {
        let mut best = None;
        self.bvh.closest(origin, dir, t_max, |tri, t_max| {
            let hit = triangle_hit(&self.edges[tri as usize], origin, dir, t_max)?;
            best = Some(MeshHit {
                t: hit.0,
                triangle: tri,
                u: hit.1,
                v: hit.2,
            });
            Some(hit.0)
        })?;
        best
    }

    /// True if any triangle is hit in (0, `t_max`).
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        self.bvh.any(origin, dir, t_max, |tri| {
            triangle_hit(&self.edges[tri as usize], origin, dir, t_max).is_some()
        })
    }

    /// Unit geometric normal and unit shading normal (the interpolated vertex normal,
    /// flipped into the geometric normal's hemisphere; the geometric normal when the
    /// mesh has no normals) at a hit.
    #[inline]
    pub fn normals_at(&self, hit: &MeshHit) -> (Vec3, Vec3) {
        let [_, e1, e2] = self.edges[hit.triangle as usize];
        let ng = e1.cross(e2).normalized();
        let ns = match &self.normals {
            Some(n) => {
                let [a, b, c] = self.triangles[hit.triangle as usize].map(|i| n[i as usize]);
                let s = (a * (1.0 - hit.u - hit.v) + b * hit.u + c * hit.v).normalized();
                if s.is_black() {
                    ng
                } else if s.dot(ng) < 0.0 {
                    -s
                } else {
                    s
                }
            }
            None => ng,
        };
        (ng, ns)
    }
}

/// Möller–Trumbore: (t, u, v) of the hit in (0, `t_max`), if any.
#[inline]
fn triangle_hit(tri: &[Vec3; 3], origin: Vec3, dir: Vec3, t_max: f32) -> Option<(f32, f32, f32)> {
    let [p0, e1, e2] = *tri;
    let pvec = dir.cross(e2);
    let det = e1.dot(pvec);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv_det = 1.0 / det;
    let tvec = origin - p0;
    let u = tvec.dot(pvec) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let v = dir.dot(qvec) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(qvec) * inv_det;
    if t > 0.0 && t < t_max {
        Some((t, u, v))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_triangles_are_dropped() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
        ];
        let mesh = Mesh::new(p.clone(), vec![[0, 1, 2], [0, 1, 3]], None).unwrap();
        assert_eq!(mesh.triangle_count(), 1);
        assert_eq!(mesh.dropped_triangles(), 1);
        assert!(matches!(
            Mesh::new(p.clone(), vec![[0, 1, 3]], None),
            Err(RenderError::DegenerateMesh)
        ));
        assert!(matches!(
            Mesh::new(p, vec![[0, 1, 7]], None),
            Err(RenderError::MeshIndexOutOfRange { index: 7, .. })
        ));
    }

    #[test]
    fn triangle_hit_and_normal() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let mesh = Mesh::new(p, vec![[0, 1, 2]], None).unwrap();
        let hit = mesh
            .intersect(
                Vec3::new(0.25, 0.25, 2.0),
                Vec3::new(0.0, 0.0, -1.0),
                f32::INFINITY,
            )
            .unwrap();
        assert!((hit.t - 2.0).abs() < 1e-6);
        assert!((hit.u - 0.25).abs() < 1e-6 && (hit.v - 0.25).abs() < 1e-6);
        assert_eq!(mesh.normals_at(&hit).0, Vec3::new(0.0, 0.0, 1.0));
        assert!(
            mesh.intersect(Vec3::new(0.75, 0.75, 2.0), Vec3::new(0.0, 0.0, -1.0), 10.0)
                .is_none()
        );
        assert!(mesh.occluded(Vec3::new(0.25, 0.25, 2.0), Vec3::new(0.0, 0.0, -1.0), 3.0));
        assert!(!mesh.occluded(Vec3::new(0.25, 0.25, 2.0), Vec3::new(0.0, 0.0, -1.0), 1.0));
    }
}
