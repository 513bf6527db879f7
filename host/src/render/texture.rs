//! Image textures: a grid of linear RGB texels, looked up with nearest-texel filtering.
//!
//! Nearest filtering makes each texel an independent parameter that owns a block of the
//! surface (the TEXTURE task optimises them directly) and keeps the rendered radiance
//! linear in every texel value.

use super::error::RenderError;
use super::math::Rgb;

/// A `width` × `height` texture. Texel (i, j) — column i, row j, row 0 at the top —
/// covers u ∈ [i/width, (i+1)/width), v ∈ (1 − (j+1)/height, 1 − j/height].
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    texels: Vec<Rgb>,
}

impl Texture {
    /// A texture from row-major texels (row 0 at the top).
    ///
    /// # Errors
    /// [`RenderError::InvalidTexture`] if a side is zero, the count is not
    /// `width * height`, or a texel is not finite.
    pub fn new(width: u32, height: u32, texels: Vec<Rgb>) -> Result<Texture, RenderError> {
        if width == 0 || height == 0 {
            return Err(RenderError::InvalidTexture("zero-sized texture"));
        }
        if texels.len() != width as usize * height as usize {
            return Err(RenderError::InvalidTexture(
                "texel count differs from width × height",
            ));
        }
        let texture = Texture {
            width,
            height,
            texels,
        };
        texture.validate()?;
        Ok(texture)
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texels, row-major, row 0 at the top; writable so that parameters can be
    /// copied in without allocating. Non-finite values are caught by
    /// [`crate::render::Scene::commit`].
    pub fn texels_mut(&mut self) -> &mut [Rgb] {
        &mut self.texels
    }

    /// The texels, row-major, row 0 at the top.
    pub fn texels(&self) -> &[Rgb] {
        &self.texels
    }

    /// Checks that every texel is finite.
    ///
    /// # Errors
    /// [`RenderError::InvalidTexture`].
    pub fn validate(&self) -> Result<(), RenderError> {
        if self.texels.iter().all(|t| t.is_finite()) {
            Ok(())
        } else {
            Err(RenderError::InvalidTexture("non-finite texel"))
        }
    }

    /// The texel covering (u, v); coordinates outside [0, 1] clamp to the border.
    #[inline]
    pub fn lookup(&self, u: f32, v: f32) -> Rgb {
        let i = ((u * self.width as f32) as i64).clamp(0, i64::from(self.width) - 1) as usize;
        let j =
            (((1.0 - v) * self.height as f32) as i64).clamp(0, i64::from(self.height) - 1) as usize;
        self.texels[j * self.width as usize + i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookup_orientation_and_clamping() {
        let texels = (0..6).map(|k| Rgb::splat(k as f32)).collect();
        let t = Texture::new(3, 2, texels).unwrap();
        assert_eq!(t.lookup(0.1, 0.9).x, 0.0); // top-left
        assert_eq!(t.lookup(0.9, 0.9).x, 2.0); // top-right
        assert_eq!(t.lookup(0.1, 0.1).x, 3.0); // bottom-left
        assert_eq!(t.lookup(-5.0, -5.0).x, 3.0);
        assert_eq!(t.lookup(f32::NAN, 2.0).x, 0.0);
        assert!(Texture::new(0, 2, vec![]).is_err());
        assert!(Texture::new(1, 1, vec![Rgb::splat(f32::NAN)]).is_err());
    }
}
