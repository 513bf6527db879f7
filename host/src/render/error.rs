//! Errors of scene construction and rendering.

/// What can go wrong when building or rendering a scene.
///
/// Rendering itself never fails on a valid, committed scene: a sample whose radiance is
/// not finite is dropped (counted as black), so no pixel is ever NaN.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A parameter vector had the wrong length.
    #[error("expected {expected} parameters, got {found}")]
    DimensionMismatch {
        /// Length the task expects.
        expected: usize,
        /// Length given.
        found: usize,
    },
    /// A parameter was NaN or infinite.
    #[error("parameter {index} is not finite")]
    NonFiniteParameter {
        /// Position of the first bad parameter.
        index: usize,
    },
    /// Zero samples per pixel were asked for.
    #[error("samples per pixel must be at least 1")]
    ZeroSamples,
    /// An image with a zero side, or too many pixels to index.
    #[error("invalid resolution {width}×{height}")]
    InvalidResolution {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// The film's resolution differs from the one asked for.
    #[error("film is {found_width}×{found_height}, expected {width}×{height}")]
    FilmMismatch {
        /// Expected width.
        width: u32,
        /// Expected height.
        height: u32,
        /// Film width.
        found_width: u32,
        /// Film height.
        found_height: u32,
    },
    /// A mesh with no triangle of positive area (after dropping degenerate ones).
    #[error("mesh has no triangle of positive area")]
    DegenerateMesh,
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle vertex index {index} out of range ({vertices} vertices)")]
    MeshIndexOutOfRange {
        /// The bad index.
        index: u32,
        /// Vertex count.
        vertices: usize,
    },
    /// A shape, light or camera with a NaN/infinite coordinate, a non-positive radius
    /// or size, or a zero-area quad.
    #[error("invalid geometry: {0}")]
    InvalidGeometry(&'static str),
    /// A transform that is singular or not finite.
    #[error("transform is singular or not finite")]
    InvalidTransform,
    /// A texture whose size is zero or whose texel count does not match its size, or a
    /// material that refers to a missing texture.
    #[error("invalid texture: {0}")]
    InvalidTexture(&'static str),
    /// A material parameter out of range (e.g. a non-positive index of refraction), or an
    /// object that refers to a missing material.
    #[error("invalid material: {0}")]
    InvalidMaterial(&'static str),
    /// Area emission on a shape that cannot be sampled as a light (meshes, boxes).
    #[error("only quads and spheres can be area emitters")]
    UnsupportedEmitter,
    /// The scene was changed after [`crate::render::Scene::commit`] and not committed
    /// again.
    #[error("scene changed since the last commit")]
    NotCommitted,
    /// Writing an image failed.
    #[error("image output failed: {0}")]
    Image(#[from] image::ImageError),
}
