//! # hodr-raster
//!
//! The 2D vector backend of hodr (tiny-skia): shape and colour inverse problems and
//! image-to-shapes fitting. Not yet implemented; see the project's issue tracker.
