//! The pinhole camera.
//!
//! Raster position (x, y) ∈ [0, W) × [0, H), y downwards, maps to the direction
//! forward + (2x/W − 1)·tan(fov/2)·right + (1 − 2y/H)·tan(fov/2)·(H/W)·up, normalised:
//! the field of view `fov` spans the image width (Mitsuba's default `fov_axis = "x"`).
//! For square images the axis does not matter.

use super::error::RenderError;
use super::math::{Ray, Vec3};

/// A perspective pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    origin: Vec3,
    forward: Vec3,
    /// Unit right vector scaled by tan(fov/2).
    right: Vec3,
    /// Unit up vector scaled by tan(fov/2) (the aspect ratio is applied per image).
    up: Vec3,
}

impl Camera {
    /// A camera at `origin` looking at `target`, with `up` giving the image's upward
    /// direction (projected to be orthogonal to the view) and horizontal field of view
    /// `fov_degrees` in (0, 180).
    ///
    /// Image right is forward × up: looking down −z with up = +y, right is +x.
    ///
    /// # Errors
    /// [`RenderError::InvalidGeometry`] for non-finite inputs, `target == origin`, `up`
    /// parallel to the view direction, or a field of view outside (0, 180).
    pub fn look_at(
        origin: Vec3,
        target: Vec3,
        up: Vec3,
        fov_degrees: f32,
    ) -> Result<Camera, RenderError> {
        if !(origin.is_finite() && target.is_finite() && up.is_finite()) {
            return Err(RenderError::InvalidGeometry("non-finite camera"));
        }
        if !(fov_degrees > 0.0 && fov_degrees < 180.0) {
            return Err(RenderError::InvalidGeometry(
                "field of view must be in (0°, 180°)",
            ));
        }
        let forward = (target - origin).normalized();
        let right = forward.cross(up).normalized();
        if forward.is_black() || right.is_black() {
            return Err(RenderError::InvalidGeometry("degenerate camera frame"));
        }
        let true_up = right.cross(forward);
        let tan_half = (fov_degrees.to_radians() * 0.5).tan();
        Ok(Camera {
            origin,
            forward,
            right: right * tan_half,
            up: true_up * tan_half,
        })
    }

    /// The camera position.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The ray through raster position (`x`, `y`) of a `width` × `height` image; the
    /// direction is unit length.
    #[inline]
    pub fn ray(&self, x: f32, y: f32, width: u32, height: u32) -> Ray {
        let sx = 2.0 * x / width as f32 - 1.0;
        let sy = (1.0 - 2.0 * y / height as f32) * (height as f32 / width as f32);
        let dir = (self.forward + self.right * sx + self.up * sy).normalized();
        Ray::new(self.origin, dir)
    }

    /// Where the ray leaving the camera along the unit direction `dir` crosses a
    /// `width` × `height` image, the inverse of [`Camera::ray`]: the raster position
    /// (x, y) and the importance W = 1/(A·cos³θ) of the pixel it falls in, θ the angle
    /// between `dir` and the view axis and A = (2·tan(fov/2)/width)² a pixel's area on
    /// the image plane at unit distance. A surface point at distance d along `dir`,
    /// sending radiance L towards the camera at cosine cos θₓ to its normal, adds
    /// L·cos θₓ·W/d² per unit of its area to that pixel's value (the mean radiance over
    /// the pixel). `None` when `dir` points behind the camera; the position may lie off
    /// the image.
    #[inline]
    pub fn raster(&self, dir: Vec3, width: u32, height: u32) -> Option<(f32, f32, f32)> {
        let cos = dir.dot(self.forward);
        if cos <= 0.0 {
            return None;
        }
        // |right|² = |up|² = tan²(fov/2).
        let tan2 = self.right.length_squared();
        let (w, h) = (width as f32, height as f32);
        let sx = dir.dot(self.right) / (cos * tan2);
        let sy = dir.dot(self.up) / (cos * tan2);
        let x = (sx + 1.0) * 0.5 * w;
        let y = (h - sy * w) * 0.5;
        let area = 4.0 * tan2 / (w * w);
        Some((x, y, 1.0 / (area * cos * cos * cos)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn looking_down_maps_right_to_plus_x() {
        let c = Camera::look_at(
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            90.0,
        )
        .unwrap();
        let centre = c.ray(1.0, 1.0, 2, 2);
        assert!((centre.dir - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
        // Right edge, middle row: 45° towards +x.
        let right = c.ray(2.0, 1.0, 2, 2);
        assert!((right.dir - Vec3::new(1.0, 0.0, -1.0).normalized()).length() < 1e-6);
        // Top edge: towards +y.
        let top = c.ray(1.0, 0.0, 2, 2);
        assert!(top.dir.y > 0.0);
        assert!(Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 40.0).is_err());
        assert!(Camera::look_at(Vec3::ZERO, Vec3::ONE, Vec3::ONE, 40.0).is_err());
    }

    /// `raster` inverts `ray`, and its importance integrates to one over a pixel: the
    /// solid angle a pixel subtends, Σ over its area of dω = cos³θ·dA, times W is 1.
    #[test]
    fn raster_inverts_ray() {
        let c = Camera::look_at(
            Vec3::new(0.3, -3.5, 1.8),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 1.0),
            45.0,
        )
        .unwrap();
        let (w, h) = (64, 48);
        for &(x, y) in &[(0.5f32, 0.5f32), (31.2, 20.7), (63.9, 47.9), (10.0, 40.25)] {
            let ray = c.ray(x, y, w, h);
            let (rx, ry, importance) = c.raster(ray.dir, w, h).unwrap();
            assert!((rx - x).abs() < 1e-3 && (ry - y).abs() < 1e-3, "{x} {y}");
            // The solid angle of a small square of side s pixels about (x, y).
            let s = 1e-2f32;
            let a = c.ray(x - s / 2.0, y - s / 2.0, w, h).dir;
            let b = c.ray(x + s / 2.0, y - s / 2.0, w, h).dir;
            let d = c.ray(x - s / 2.0, y + s / 2.0, w, h).dir;
            let solid = (b - a).cross(d - a).length();
            assert!((solid * importance / (s * s) - 1.0).abs() < 1e-2, "{x} {y}");
        }
        assert!(c.raster(-c.ray(5.0, 5.0, w, h).dir, w, h).is_none());
        let (x, _, _) = c.raster(c.ray(-1.0, 5.0, w, h).dir, w, h).unwrap();
        assert!((x + 1.0).abs() < 1e-3);
    }
}
