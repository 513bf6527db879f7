//! Target images: 8-bit RGB, loaded with `image` (PNG, JPEG) or rendered from a scene.

use std::path::Path;

use tiny_skia::Pixmap;

use crate::error::Error;
use crate::scene::{Scene, check_size};

/// An RGB image to match, 8 bits per channel, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Target {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Target {
    /// Loads a PNG or JPEG file (the format is detected from the content). Alpha, if
    /// any, is dropped.
    ///
    /// # Errors
    /// [`Error::ImageRead`] for a missing, unreadable or undecodable file;
    /// [`Error::InvalidSize`] if a side exceeds [`crate::MAX_SIDE`].
    pub fn open(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let image = image::ImageReader::open(path)
            .map_err(|e| Error::ImageRead {
                path: path.to_path_buf(),
                source: image::ImageError::IoError(e),
            })?
            .with_guessed_format()
            .map_err(|e| Error::ImageRead {
                path: path.to_path_buf(),
                source: image::ImageError::IoError(e),
            })?
            .decode()
            .map_err(|source| Error::ImageRead {
                path: path.to_path_buf(),
                source,
            })?;
        Self::from_dynamic(image)
    }

    /// Decodes PNG or JPEG bytes.
    ///
    /// # Errors
    /// [`Error::ImageDecode`]; [`Error::InvalidSize`] as for [`Target::open`].
    pub fn decode(bytes: &[u8]) -> Result<Self, Error> {
        let image = image::load_from_memory(bytes).map_err(Error::ImageDecode)?;
        Self::from_dynamic(image)
    }

    fn from_dynamic(image: image::DynamicImage) -> Result<Self, Error> {
        let rgb = image.to_rgb8();
        let (width, height) = rgb.dimensions();
        Self::from_rgb8(width, height, rgb.into_raw())
    }

    /// Wraps `width × height × 3` bytes of RGB.
    ///
    /// # Errors
    /// [`Error::InvalidSize`]; [`Error::BufferSize`] if `rgb` has the wrong length.
    pub fn from_rgb8(width: u32, height: u32, rgb: Vec<u8>) -> Result<Self, Error> {
        check_size(width, height)?;
        let expected = width as usize * height as usize * 3;
        if rgb.len() != expected {
            return Err(Error::BufferSize {
                expected,
                found: rgb.len(),
            });
        }
        Ok(Target { width, height, rgb })
    }

    /// The RGB of an opaque pixmap (as every scene renders).
    pub fn from_pixmap(pixmap: &Pixmap) -> Self {
        let rgb = pixmap
            .data()
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        Target {
            width: pixmap.width(),
            height: pixmap.height(),
            rgb,
        }
    }

    /// Renders `scene` (the ground truth) as the target.
    pub fn from_scene(scene: &Scene) -> Self {
        Self::from_pixmap(&scene.render())
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, `width × height × 3` bytes, row-major.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// Pixel (x, y), or `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Some([self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]])
    }

    /// Root-mean-square difference to `other` over pixels and RGB channels, in [0, 1]
    /// units.
    ///
    /// # Errors
    /// [`Error::TargetSize`] if the sizes differ.
    pub fn rmse(&self, other: &Target) -> Result<f64, Error> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(Error::TargetSize {
                width: self.width,
                height: self.height,
                found_width: other.width,
                found_height: other.height,
            });
        }
        let sum: u64 = self
            .rgb
            .iter()
            .zip(&other.rgb)
            .map(|(&a, &b)| u64::from(a.abs_diff(b)).pow(2))
            .sum();
        Ok((sum as f64 / self.rgb.len() as f64).sqrt() / 255.0)
    }

    /// Writes the image as PNG.
    ///
    /// # Errors
    /// [`Error::Encode`] (which includes I/O failures while writing).
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let path = path.as_ref();
        image::save_buffer_with_format(
            path,
            &self.rgb,
            self.width,
            self.height,
            image::ExtendedColorType::Rgb8,
            image::ImageFormat::Png,
        )
        .map_err(|source| Error::Encode {
            path: path.to_path_buf(),
            source,
        })
    }
}

/// Writes `bytes` to `path`.
pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    std::fs::write(path, bytes).map_err(|source| Error::Write {
        path: path.to_path_buf(),
        source,
    })
}
