//! The film: a linear RGB `f32` image, and its sRGB PNG encoding.
//!
//! Pixel values are radiance estimates (the box-filtered mean of the pixel's samples),
//! stored interleaved R, G, B, row-major, row 0 at the top. Losses read the raw `f32`
//! data; only PNG output applies the sRGB transfer curve and 8-bit quantisation.

use std::path::Path;

use super::error::RenderError;

/// A `width` × `height` linear RGB image. Two films are equal when their sizes and
/// pixels are.
#[derive(Clone, Debug)]
pub struct Film {
    width: u32,
    height: u32,
    data: Vec<f32>,
    /// The integrator's scratch (the light pass's partial images), sized on first use
    /// and kept, so that rendering into the same film again allocates nothing.
    scratch: Vec<f32>,
}

impl PartialEq for Film {
    fn eq(&self, other: &Film) -> bool {
        self.width == other.width && self.height == other.height && self.data == other.data
    }
}

impl Film {
    /// A black film.
    ///
    /// # Errors
    /// [`RenderError::InvalidResolution`] if a side is 0 or the pixel count overflows
    /// 2³².
    pub fn new(width: u32, height: u32) -> Result<Film, RenderError> {
        let pixels = u64::from(width) * u64::from(height);
        if pixels == 0 || pixels > u64::from(u32::MAX) {
            return Err(RenderError::InvalidResolution { width, height });
        }
        Ok(Film {
            width,
            height,
            data: vec![0.0; 3 * pixels as usize],
            scratch: Vec::new(),
        })
    }

    /// The raw data and `len` floats of scratch, grown (allocating) only when the film
    /// has had less.
    pub(super) fn data_and_scratch(&mut self, len: usize) -> (&mut [f32], &mut [f32]) {
        if self.scratch.len() < len {
            self.scratch.resize(len, 0.0);
        }
        (&mut self.data, &mut self.scratch[..len])
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The raw data: R, G, B per pixel, row-major, row 0 at the top.
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    /// The raw data, writable (the integrator fills it).
    pub fn data_mut(&mut self) -> &mut [f32] {
        &mut self.data
    }

    /// The linear RGB value of pixel (`x`, `y`) (panics outside the image).
    pub fn pixel(&self, x: u32, y: u32) -> [f32; 3] {
        let k = 3 * (y as usize * self.width as usize + x as usize);
        [self.data[k], self.data[k + 1], self.data[k + 2]]
    }

    /// Mean over pixels and channels of the squared difference to `other`, in `f64`.
    ///
    /// # Errors
    /// [`RenderError::FilmMismatch`] if the resolutions differ.
    pub fn mse(&self, other: &Film) -> Result<f64, RenderError> {
        if self.width != other.width || self.height != other.height {
            return Err(RenderError::FilmMismatch {
                width: self.width,
                height: self.height,
                found_width: other.width,
                found_height: other.height,
            });
        }
        Ok(mse(&self.data, &other.data))
    }

    /// 8-bit sRGB bytes (R, G, B per pixel): each linear value is clamped to [0, 1],
    /// encoded with the sRGB transfer curve and rounded.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.data.iter().map(|&v| encode_srgb(v)).collect()
    }

    /// Writes the film as an 8-bit sRGB PNG.
    ///
    /// # Errors
    /// [`RenderError::Image`] when encoding or writing fails.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        image::save_buffer_with_format(
            path,
            &self.to_srgb8(),
            self.width,
            self.height,
            image::ExtendedColorType::Rgb8,
            image::ImageFormat::Png,
        )?;
        Ok(())
    }
}

/// Mean of (aᵢ − bᵢ)² over two equally long slices, accumulated in `f64`
/// (0 for empty slices).
pub fn mse(a: &[f32], b: &[f32]) -> f64 {
    if a.is_empty() {
        return 0.0;
    }
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| {
            let d = f64::from(x) - f64::from(y);
            d * d
        })
        .sum();
    sum / a.len() as f64
}

/// The sRGB transfer curve (IEC 61966-2-1) applied to a linear value clamped to [0, 1],
/// as an 8-bit code; NaN encodes as 0.
pub fn encode_srgb(linear: f32) -> u8 {
    let v = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    let encoded = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (encoded * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding() {
        assert_eq!(encode_srgb(0.0), 0);
        assert_eq!(encode_srgb(1.0), 255);
        assert_eq!(encode_srgb(7.0), 255);
        assert_eq!(encode_srgb(f32::NAN), 0);
        // Linear 0.5 is sRGB 0.73536 (code 187.52 → 188).
        assert_eq!(encode_srgb(0.5), 188);
    }

    #[test]
    fn resolution_and_mse() {
        assert!(Film::new(0, 4).is_err());
        let mut a = Film::new(2, 1).unwrap();
        let b = Film::new(2, 1).unwrap();
        a.data_mut()[0] = 1.0;
        assert!((a.mse(&b).unwrap() - 1.0 / 6.0).abs() < 1e-12);
        assert!(a.mse(&Film::new(1, 2).unwrap()).is_err());
    }
}
