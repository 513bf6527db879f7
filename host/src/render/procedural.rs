//! Procedural meshes: surfaces of revolution, tori, the mug, and a glass height field.
//!
//! All meshes are built counter-clockwise so that the geometric normal points out of
//! the solid (which the dielectric needs to tell inside from outside).

use std::f32::consts::{PI, TAU};

use super::error::RenderError;
use super::math::Vec3;
use super::mesh::Mesh;

/// Revolves the polyline `profile` of (radius, height) points about the z axis in
/// `segments` steps.
///
/// Each profile segment becomes a band of quads (two triangles each) with its own ring
/// of vertices, shaded smoothly around the axis and flat along the profile. A profile
/// that runs upwards on the outside (or inwards on a top face) gets outward normals.
/// Points on the axis (radius 0) give degenerate triangles, which are dropped.
///
/// # Errors
/// [`RenderError::InvalidGeometry`] for fewer than 2 profile points, fewer than 3
/// segments or non-finite points; errors of [`Mesh::new`].
pub fn lathe(profile: &[(f32, f32)], segments: u32) -> Result<Mesh, RenderError> {
    if profile.len() < 2 || segments < 3 {
        return Err(RenderError::InvalidGeometry(
            "lathe needs ≥ 2 profile points and ≥ 3 segments",
        ));
    }
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut triangles = Vec::new();
    let ring = segments as usize + 1;
    for pair in profile.windows(2) {
        let ((r0, z0), (r1, z1)) = (pair[0], pair[1]);
        // 2-D normal of the segment direction (dr, dz), turned clockwise: (dz, −dr).
        let (dr, dz) = (r1 - r0, z1 - z0);
        let len = (dr * dr + dz * dz).sqrt();
        let (nr, nz) = if len > 0.0 {
            (dz / len, -dr / len)
        } else {
            (0.0, 0.0)
        };
        let first = positions.len() as u32;
        for (r, z) in [(r0, z0), (r1, z1)] {
            for k in 0..ring {
                let phi = TAU * k as f32 / segments as f32;
                let (s, c) = phi.sin_cos();
                positions.push(Vec3::new(r * c, r * s, z));
                normals.push(Vec3::new(nr * c, nr * s, nz));
            }
        }
        for k in 0..segments {
            let a = first + k;
            let b = a + 1;
            let d = a + ring as u32;
            let c = d + 1;
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles, Some(normals))
}

/// A torus arc: tube radius `minor` swept along the circle of radius `major` about
/// `center` in the x–z plane, for ring angles u ∈ [−`arc`, `arc`] (u = 0 towards +x,
/// u = π/2 towards +z); `arc` = π closes the ring. Smooth normals, outward.
///
/// # Errors
/// [`RenderError::InvalidGeometry`] for non-positive radii or too few segments.
pub fn torus_arc(
    center: Vec3,
    major: f32,
    minor: f32,
    arc: f32,
    ring_segments: u32,
    tube_segments: u32,
) -> Result<Mesh, RenderError> {
    if !(major > 0.0 && minor > 0.0 && arc > 0.0) || ring_segments < 2 || tube_segments < 3 {
        return Err(RenderError::InvalidGeometry(
            "torus needs positive radii and enough segments",
        ));
    }
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut triangles = Vec::new();
    let tube = tube_segments as usize + 1;
    for i in 0..=ring_segments {
        let u = -arc + 2.0 * arc * i as f32 / ring_segments as f32;
        let (su, cu) = u.sin_cos();
        let radial = Vec3::new(cu, 0.0, su);
        let ring_center = center + radial * major;
        for j in 0..tube {
            let v = TAU * j as f32 / tube_segments as f32;
            let (sv, cv) = v.sin_cos();
            let n = radial * cv + Vec3::new(0.0, sv, 0.0);
            positions.push(ring_center + n * minor);
            normals.push(n);
        }
    }
    for i in 0..ring_segments {
        for j in 0..tube_segments {
            let a = i * tube as u32 + j;
            let b = a + tube as u32;
            let c = b + 1;
            let d = a + 1;
            triangles.push([a, d, c]);
            triangles.push([a, c, b]);
        }
    }
    Mesh::new(positions, triangles, Some(normals))
}

/// Concatenates meshes into one (their shading normals are kept; meshes without
/// normals use their geometric normals).
///
/// # Errors
/// Errors of [`Mesh::new`].
pub fn merge(parts: &[Mesh]) -> Result<Mesh, RenderError> {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut triangles = Vec::new();
    for part in parts {
        let offset = positions.len() as u32;
        positions.extend_from_slice(part.positions());
        normals.extend_from_slice(&part.vertex_normals());
        triangles.extend(part.triangles().iter().map(|t| t.map(|i| i + offset)));
    }
    Mesh::new(positions, triangles, Some(normals))
}

/// Mug dimensions (scene units): the body's outer radius and height.
pub const MUG_RADIUS: f32 = 0.4;
/// Mug height.
pub const MUG_HEIGHT: f32 = 1.0;

/// The mug: a lathed cup (outer radius [`MUG_RADIUS`], height [`MUG_HEIGHT`], wall 0.04,
/// floor 0.08 thick, rounded rim) standing on z = 0 around the z axis, with a torus
/// handle (ring radius 0.25, tube radius 0.05) on the +x side in the x–z plane. About
/// 2 000 triangles.
///
/// # Errors
/// Never for these constants; propagates [`Mesh::new`] errors.
pub fn mug() -> Result<Mesh, RenderError> {
    let (r, h, wall, floor) = (MUG_RADIUS, MUG_HEIGHT, 0.04, 0.08);
    let rim = wall * 0.5;
    let mut profile = vec![(0.0, 0.0), (r - 0.02, 0.0), (r, 0.02), (r, h)];
    // Half-round rim from the outer to the inner wall.
    for k in 1..6 {
        let a = PI * k as f32 / 6.0;
        profile.push((r - rim + rim * a.cos(), h + rim * a.sin()));
    }
    profile.extend([
        (r - wall, h),
        (r - wall, floor + 0.02),
        (r - wall - 0.02, floor),
        (0.0, floor),
    ]);
    let body = lathe(&profile, 64)?;
    // The arc stops where the tube enters the wall, so nothing pokes into the cup.
    let handle_center = Vec3::new(r + 0.02, 0.0, 0.5 * h);
    let arc = 0.5 * PI + 0.12;
    let handle = torus_arc(handle_center, 0.25, 0.05, arc, 24, 12)?;
    merge(&[body, handle])
}

/// A glass slab whose top surface is a height field over a grid of control heights.
///
/// The slab covers [cx − sx/2, cx + sx/2] × [cy − sy/2, cy + sy/2]; its bottom is flat at
/// `bottom`, its top at `top + h(i, j)` over the `cols` × `rows` control points (column i
/// along x, row j along y, row-major). Heights are clamped to [−(top − bottom)/2,
/// `max_height`] so the solid never inverts. The top is shaded with normals from
/// central differences of the heights, which makes the caustic smooth although the
/// surface is a coarse triangle grid; sides and bottom are flat.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightField {
    /// Control points along x (≥ 2).
    pub cols: usize,
    /// Control points along y (≥ 2).
    pub rows: usize,
    /// Centre (x, y) of the slab.
    pub center: (f32, f32),
    /// Size (x, y) of the slab.
    pub size: (f32, f32),
    /// Height of the flat bottom.
    pub bottom: f32,
    /// Height of the top surface where h = 0 (> `bottom`).
    pub top: f32,
    /// Largest allowed h.
    pub max_height: f32,
}

impl HeightField {
    /// Vertices: top grid, bottom grid, then four side strips of top/bottom pairs.
    fn vertex_count(&self) -> usize {
        2 * self.cols * self.rows + 4 * (self.cols + self.rows)
    }

    /// The clamped height at control point (i, j).
    fn height(&self, heights: &[f32], i: usize, j: usize) -> f32 {
        let lo = -0.5 * (self.top - self.bottom);
        heights[j * self.cols + i].clamp(lo, self.max_height)
    }

    fn xy(&self, i: usize, j: usize) -> (f32, f32) {
        let x = self.center.0 - 0.5 * self.size.0 + self.size.0 * i as f32 / (self.cols - 1) as f32;
        let y = self.center.1 - 0.5 * self.size.1 + self.size.1 * j as f32 / (self.rows - 1) as f32;
        (x, y)
    }

    /// Writes vertex positions and normals for `heights` into the buffers (cleared
    /// first; no allocation once they have the capacity).
    ///
    /// # Errors
    /// [`RenderError::DimensionMismatch`] if `heights.len() != cols * rows`;
    /// [`RenderError::NonFiniteParameter`] for a NaN height.
    pub fn vertices(
        &self,
        heights: &[f32],
        positions: &mut Vec<Vec3>,
        normals: &mut Vec<Vec3>,
    ) -> Result<(), RenderError> {
        let (cols, rows) = (self.cols, self.rows);
        if heights.len() != cols * rows {
            return Err(RenderError::DimensionMismatch {
                expected: cols * rows,
                found: heights.len(),
            });
        }
        if let Some(index) = heights.iter().position(|h| h.is_nan()) {
            return Err(RenderError::NonFiniteParameter { index });
        }
        positions.clear();
        normals.clear();
        let dx = self.size.0 / (cols - 1) as f32;
        let dy = self.size.1 / (rows - 1) as f32;
        for j in 0..rows {
            for i in 0..cols {
                let (x, y) = self.xy(i, j);
                positions.push(Vec3::new(x, y, self.top + self.height(heights, i, j)));
                let (i0, i1) = (i.saturating_sub(1), (i + 1).min(cols - 1));
                let (j0, j1) = (j.saturating_sub(1), (j + 1).min(rows - 1));
                let hx = (self.height(heights, i1, j) - self.height(heights, i0, j))
                    / ((i1 - i0) as f32 * dx);
                let hy = (self.height(heights, i, j1) - self.height(heights, i, j0))
                    / ((j1 - j0) as f32 * dy);
                normals.push(Vec3::new(-hx, -hy, 1.0).normalized());
            }
        }
        for j in 0..rows {
            for i in 0..cols {
                let (x, y) = self.xy(i, j);
                positions.push(Vec3::new(x, y, self.bottom));
                normals.push(Vec3::new(0.0, 0.0, -1.0));
            }
        }
        // Sides: y = min (−y), y = max (+y), x = min (−x), x = max (+x).
        let sides: [(bool, usize, Vec3); 4] = [
            (true, 0, Vec3::new(0.0, -1.0, 0.0)),
            (true, rows - 1, Vec3::new(0.0, 1.0, 0.0)),
            (false, 0, Vec3::new(-1.0, 0.0, 0.0)),
            (false, cols - 1, Vec3::new(1.0, 0.0, 0.0)),
        ];
        for (along_x, fixed, n) in sides {
            let count = if along_x { cols } else { rows };
            for k in 0..count {
                let (i, j) = if along_x { (k, fixed) } else { (fixed, k) };
                let (x, y) = self.xy(i, j);
                positions.push(Vec3::new(x, y, self.top + self.height(heights, i, j)));
                normals.push(n);
                positions.push(Vec3::new(x, y, self.bottom));
                normals.push(n);
            }
        }
        debug_assert_eq!(positions.len(), self.vertex_count());
        Ok(())
    }

    /// The closed slab mesh for `heights`.
    ///
    /// # Errors
    /// [`RenderError::InvalidGeometry`] for fewer than 2×2 control points, a size that is
    /// not positive or `top ≤ bottom`; errors of [`HeightField::vertices`].
    pub fn mesh(&self, heights: &[f32]) -> Result<Mesh, RenderError> {
        if self.cols < 2
            || self.rows < 2
            || !(self.size.0 > 0.0 && self.size.1 > 0.0)
            || self.top <= self.bottom
        {
            return Err(RenderError::InvalidGeometry(
                "height field needs ≥ 2×2 points, positive size, top > bottom",
            ));
        }
        let (mut positions, mut normals) = (Vec::new(), Vec::new());
        self.vertices(heights, &mut positions, &mut normals)?;
        let (cols, rows) = (self.cols as u32, self.rows as u32);
        let top = |i: u32, j: u32| j * cols + i;
        let bottom = |i: u32, j: u32| cols * rows + j * cols + i;
        let mut triangles = Vec::new();
        for j in 0..rows - 1 {
            for i in 0..cols - 1 {
                let (a, b, c, d) = (top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
                let (a, b, c, d) = (
                    bottom(i, j),
                    bottom(i + 1, j),
                    bottom(i + 1, j + 1),
                    bottom(i, j + 1),
                );
                triangles.push([a, c, b]);
                triangles.push([a, d, c]);
            }
        }
        // Side strips: vertex 2k is on the top edge, 2k + 1 on the bottom, at step k.
        let mut start = 2 * cols * rows;
        for (count, flip) in [(cols, false), (cols, true), (rows, true), (rows, false)] {
            for k in 0..count - 1 {
                let (t0, b0) = (start + 2 * k, start + 2 * k + 1);
                let (t1, b1) = (t0 + 2, b0 + 2);
                if flip {
                    triangles.push([b0, t1, b1]);
                    triangles.push([b0, t0, t1]);
                } else {
                    triangles.push([b0, b1, t1]);
                    triangles.push([b0, t1, t0]);
                }
            }
            start += 2 * count;
        }
        Mesh::new(positions, triangles, Some(normals))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::math::Ray;
    use crate::render::shape::{MeshInstance, Shape};
    use crate::render::transform::Transform;

    /// Outward normals: a ray from far outside towards the centre meets a surface whose
    /// geometric normal faces it.
    fn assert_outward(mesh: Mesh, center: Vec3) {
        let shape = Shape::Mesh(Box::new(MeshInstance {
            mesh,
            transform: Transform::IDENTITY,
        }));
        for k in 0..24 {
            let a = TAU * k as f32 / 24.0;
            let dir = Vec3::new(a.cos(), a.sin(), 0.3 * (k as f32 - 12.0) / 12.0).normalized();
            let ray = Ray::new(center + dir * 10.0, -dir);
            if let Some(hit) = shape.intersect(&ray, f32::INFINITY, 0) {
                let s = shape.surface(&ray, &hit, false);
                assert!(s.ng.dot(dir) > 0.0, "inward normal at {:?}", s.p);
            }
        }
    }

    #[test]
    fn mug_is_outward_and_reasonable() {
        let mug = mug().unwrap();
        assert!(mug.triangle_count() > 1500 && mug.triangle_count() < 6000);
        let b = mug.bounds();
        assert!(b.min.z >= -1e-6 && b.max.z <= MUG_HEIGHT + 0.03);
        assert!(b.max.x > MUG_RADIUS + 0.2);
        assert_outward(mug, Vec3::new(0.0, 0.0, 0.5));
    }

    #[test]
    fn height_field_is_closed_and_outward() {
        let hf = HeightField {
            cols: 4,
            rows: 3,
            center: (0.0, 0.0),
            size: (2.0, 1.0),
            bottom: 0.0,
            top: 0.2,
            max_height: 0.3,
        };
        let heights: Vec<f32> = (0..12).map(|k| 0.02 * k as f32).collect();
        let mesh = hf.mesh(&heights).unwrap();
        assert_eq!(mesh.triangle_count(), 2 * 2 * 3 * 2 + 2 * 2 * 3 + 2 * 2 * 2);
        assert_outward(mesh, Vec3::new(0.0, 0.0, 0.1));
        assert!(hf.mesh(&heights[..5]).is_err());
    }
}
