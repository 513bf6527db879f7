//! Every failure of hodr-raster, as one typed value.

use std::path::PathBuf;

/// Why a scene, target, objective, task or fit could not be built or evaluated.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Width or height is 0 or above [`crate::MAX_SIDE`].
    #[error("image size {width}×{height} is outside 1..={max} pixels per side", max = crate::MAX_SIDE)]
    InvalidSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
    /// The target image's size differs from the scene's.
    #[error("target is {found_width}×{found_height}, scene is {width}×{height}")]
    TargetSize {
        /// Scene width.
        width: u32,
        /// Scene height.
        height: u32,
        /// Target width.
        found_width: u32,
        /// Target height.
        found_height: u32,
    },
    /// A raw pixel buffer does not hold width × height × channels bytes.
    #[error("pixel buffer holds {found} bytes, {expected} expected")]
    BufferSize {
        /// Bytes required.
        expected: usize,
        /// Bytes given.
        found: usize,
    },
    /// An image file could not be opened or decoded.
    #[error("cannot read image {path}: {source}")]
    ImageRead {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: image::ImageError,
    },
    /// In-memory image bytes could not be decoded (not PNG or JPEG, or corrupt).
    #[error("cannot decode image: {0}")]
    ImageDecode(#[source] image::ImageError),
    /// An output file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
    /// An image could not be encoded.
    #[error("cannot encode {path}: {source}")]
    Encode {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: image::ImageError,
    },
    /// θ has the wrong number of coordinates.
    #[error("θ has {found} coordinates, {expected} expected")]
    DimensionMismatch {
        /// Coordinates required.
        expected: usize,
        /// Coordinates given.
        found: usize,
    },
    /// A coordinate of θ is NaN or infinite.
    #[error("parameter {index} is not finite")]
    NonFiniteParameter {
        /// Index of the first offending coordinate.
        index: usize,
    },
    /// A shape or colour holds NaN or an infinite number.
    #[error("shape {shape} has a non-finite coordinate, size or colour")]
    NonFiniteShape {
        /// Index of the shape in the scene (or in the list being built).
        shape: usize,
    },
    /// A polygon with fewer than 3 vertices or a cubic path with no segment.
    #[error("shape {shape} has too few vertices or segments")]
    DegenerateShape {
        /// Index of the shape.
        shape: usize,
    },
    /// A parameter binding names a shape that does not exist.
    #[error("binding {binding} names shape {shape}, the scene has {shapes}")]
    NoSuchShape {
        /// Index of the binding (= θ coordinate).
        binding: usize,
        /// The shape index named.
        shape: usize,
        /// Shapes in the scene.
        shapes: usize,
    },
    /// A parameter binding's attribute does not exist on its shape (e.g. a circle's
    /// width, or vertex 5 of a triangle).
    #[error("binding {binding}: attribute {attribute} does not apply to shape {shape}")]
    NoSuchAttribute {
        /// Index of the binding.
        binding: usize,
        /// The shape index.
        shape: usize,
        /// The attribute, as text.
        attribute: String,
    },
    /// A parameter binding's scale is 0 or not finite, or its offset is not finite.
    #[error(
        "binding {binding} has scale {scale} and offset {offset}; the scale must be finite and non-zero, the offset finite"
    )]
    InvalidScale {
        /// Index of the binding.
        binding: usize,
        /// The scale.
        scale: f64,
        /// The offset.
        offset: f64,
    },
    /// No task of that name exists.
    #[error("unknown task {0:?}; known tasks: tri1d, box2, box10, shapes")]
    UnknownTask(String),
    /// An option is out of its documented range.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// Its contract.
        reason: &'static str,
    },
    /// The smoothed estimators refused (a non-finite estimate, a bad σ).
    #[error("estimator failed: {0}")]
    Estimator(#[from] hodr_core::Error),
}
