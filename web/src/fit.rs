//! Image to shapes in the page: the dropped file checked and scaled down, then
//! hodr-raster's fit, reporting each shape as it is placed.

use std::io::Cursor;
use std::sync::atomic::AtomicBool;

use hodr_raster::fit::{self, Fit, FitOptions};
use hodr_raster::{Scene, ShapeKind, Target};
use image::imageops::FilterType;
use image::{ImageReader, RgbImage};

use crate::error::Error;

/// The largest side of an image the page accepts (hodr-raster's limit): the header is
/// read first, so a larger image is refused before any pixel is decoded.
pub const MAX_INPUT_SIDE: u32 = hodr_raster::MAX_SIDE;

/// The longer side the fit works at: an image is scaled down to it, so a shape takes
/// tens of milliseconds whatever the file.
pub const FIT_SIDE: u32 = 128;

/// The most shapes the page places.
pub const MAX_DEMO_SHAPES: usize = 1000;

/// Decodes a PNG or JPEG and scales it to at most [`FIT_SIDE`] on its longer side.
///
/// # Errors
/// [`Error::NotAnImage`] for bytes that are not a PNG or JPEG (or do not decode);
/// [`Error::ImageTooLarge`] above [`MAX_INPUT_SIDE`] on either side.
pub fn load(bytes: &[u8]) -> Result<Target, Error> {
    let reader = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| Error::NotAnImage(e.to_string()))?;
    match reader.format() {
        Some(image::ImageFormat::Png | image::ImageFormat::Jpeg) => {}
        _ => return Err(Error::NotAnImage("unknown format".into())),
    }
    let (width, height) = reader
        .into_dimensions()
        .map_err(|e| Error::NotAnImage(e.to_string()))?;
    if width > MAX_INPUT_SIDE || height > MAX_INPUT_SIDE {
        return Err(Error::ImageTooLarge { width, height });
    }
    let image = image::load_from_memory(bytes)
        .map_err(|e| Error::NotAnImage(e.to_string()))?
        .to_rgb8();
    Ok(scale_down(image)?)
}

fn scale_down(image: RgbImage) -> Result<Target, hodr_raster::Error> {
    let (width, height) = image.dimensions();
    let longer = width.max(height);
    let image = if longer > FIT_SIDE {
        let scale =
            |side: u32| ((u64::from(side) * u64::from(FIT_SIDE)) / u64::from(longer)).max(1) as u32;
        image::imageops::resize(&image, scale(width), scale(height), FilterType::Triangle)
    } else {
        image
    };
    let (width, height) = image.dimensions();
    Target::from_rgb8(width, height, image.into_raw())
}

/// The shipped landscape test image at [`FIT_SIDE`], the page's default target.
///
/// # Errors
/// None in practice (the size is valid).
pub fn landscape() -> Result<Target, Error> {
    Ok(hodr_raster::test_image::landscape(FIT_SIDE)?)
}

/// The fit's options for `shapes` shapes of kind `kind` (`triangle`, `rect`, `ellipse`
/// or `circle`) with `seed`, checked before any image is decoded.
///
/// # Errors
/// [`Error::Setting`] for a count outside 1..=[`MAX_DEMO_SHAPES`] or another kind.
pub fn options(kind: &str, shapes: usize, seed: u64) -> Result<FitOptions, Error> {
    if !(1..=MAX_DEMO_SHAPES).contains(&shapes) {
        return Err(Error::Setting {
            name: "shape count",
            expected: "between 1 and 1000",
        });
    }
    let kind = match kind.parse::<ShapeKind>() {
        Ok(
            k @ (ShapeKind::Triangle | ShapeKind::Rect | ShapeKind::Ellipse | ShapeKind::Circle),
        ) => k,
        _ => {
            return Err(Error::Setting {
                name: "shape kind",
                expected: "triangle, rect, ellipse or circle",
            });
        }
    };
    let mut options = FitOptions::new(shapes, kind);
    options.seed = seed;
    Ok(options)
}

/// Fits `target`, calling `placed(scene, rmse, evaluations)` after each shape.
///
/// # Errors
/// The fit's own errors.
pub fn shapes(
    target: &Target,
    options: &FitOptions,
    placed: &mut dyn FnMut(&Scene, f64, u64),
) -> Result<Fit, Error> {
    Ok(fit::fit_watched(
        target,
        options,
        &AtomicBool::new(false),
        placed,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32) -> Vec<u8> {
        let mut bytes = Vec::new();
        RgbImage::new(width, height)
            .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
            .unwrap();
        bytes
    }

    #[test]
    fn bad_files_are_named() {
        let text = load(b"hello, not an image").unwrap_err();
        assert!(text.to_string().contains("not a PNG or JPEG"), "{text}");
        let truncated = load(&png(8, 8)[..40]).unwrap_err();
        assert!(
            truncated.to_string().contains("not a PNG or JPEG"),
            "{truncated}"
        );
        let huge = load(&png(10_000, 1)).unwrap_err();
        assert!(huge.to_string().contains("10000×1"), "{huge}");
    }

    #[test]
    fn images_are_scaled_to_the_fit_side() {
        let target = load(&png(512, 256)).unwrap();
        assert_eq!((target.width(), target.height()), (128, 64));
        let small = load(&png(20, 10)).unwrap();
        assert_eq!((small.width(), small.height()), (20, 10));
    }

    #[test]
    fn fits_report_each_shape_and_refuse_zero() {
        let target = landscape().unwrap();
        let mut seen = Vec::new();
        let options = options("triangle", 3, 1).unwrap();
        let fit = shapes(&target, &options, &mut |scene, rmse, _| {
            seen.push((scene.shapes().len(), rmse))
        })
        .unwrap();
        assert_eq!(seen.len(), fit.scene().shapes().len());
        let zero = super::options("triangle", 0, 1).unwrap_err();
        assert!(zero.to_string().starts_with("shape count"), "{zero}");
        assert!(super::options("polygon", 3, 1).is_err());
    }
}
