//! A scene: an opaque background and an ordered list of shapes, painted back to front.

use std::path::Path;

use tiny_skia::Pixmap;

use crate::color::Rgba;
use crate::error::Error;
use crate::shape::{PathScratch, Shape};
use crate::target::{Target, write_file};

/// The largest width or height accepted, in pixels (a 4096² RGBA pixmap is 64 MiB).
pub const MAX_SIDE: u32 = 4096;

/// Background plus shapes, composited source-over in order (later shapes on top).
///
/// The background is always opaque (its alpha is ignored), so every rendered pixel is
/// opaque and its premultiplied and straight colours agree.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    width: u32,
    height: u32,
    background: Rgba,
    shapes: Vec<Shape>,
}

impl Scene {
    /// An empty `width` × `height` scene.
    ///
    /// # Errors
    /// [`Error::InvalidSize`] unless 1 ≤ width, height ≤ [`MAX_SIDE`];
    /// [`Error::NonFiniteShape`] (shape 0 stands for the background) for a non-finite colour.
    pub fn new(width: u32, height: u32, background: Rgba) -> Result<Self, Error> {
        check_size(width, height)?;
        if !background.is_finite() {
            return Err(Error::NonFiniteShape { shape: 0 });
        }
        Ok(Scene {
            width,
            height,
            background: Rgba {
                a: 1.0,
                ..background
            },
            shapes: Vec::new(),
        })
    }

    /// Appends `shape` on top and returns its index.
    ///
    /// # Errors
    /// As [`Shape::validate`].
    pub fn push(&mut self, shape: Shape) -> Result<usize, Error> {
        let index = self.shapes.len();
        shape.validate(index)?;
        self.shapes.push(shape);
        Ok(index)
    }

    /// Builder form of [`Scene::push`].
    ///
    /// # Errors
    /// As [`Shape::validate`].
    pub fn with(mut self, shape: Shape) -> Result<Self, Error> {
        self.push(shape)?;
        Ok(self)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The opaque background colour.
    pub fn background(&self) -> Rgba {
        self.background
    }

    /// The shapes, bottom first.
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// Renders into a new pixmap.
    pub fn render(&self) -> Pixmap {
        let mut pixmap = new_pixmap(self.width, self.height);
        self.paint(&mut pixmap, &mut PathScratch::default());
        pixmap
    }

    /// Renders into `pixmap`, reusing it.
    ///
    /// # Errors
    /// [`Error::TargetSize`] if `pixmap` is not the scene's size.
    pub fn render_into(&self, pixmap: &mut Pixmap) -> Result<(), Error> {
        if (pixmap.width(), pixmap.height()) != (self.width, self.height) {
            return Err(Error::TargetSize {
                width: self.width,
                height: self.height,
                found_width: pixmap.width(),
                found_height: pixmap.height(),
            });
        }
        self.paint(pixmap, &mut PathScratch::default());
        Ok(())
    }

    pub(crate) fn paint(&self, pixmap: &mut Pixmap, scratch: &mut PathScratch) {
        pixmap.fill(self.background.to_skia());
        let mut canvas = pixmap.as_mut();
        for shape in &self.shapes {
            shape.draw(&mut canvas, scratch);
        }
    }

    /// The scene as an SVG document (see [`crate::svg`]).
    pub fn to_svg(&self) -> String {
        crate::svg::scene_to_svg(self)
    }

    /// Renders and writes a PNG.
    ///
    /// # Errors
    /// [`Error::Encode`] or [`Error::Write`].
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        Target::from_pixmap(&self.render()).save_png(path)
    }

    /// Writes the SVG of [`Scene::to_svg`].
    ///
    /// # Errors
    /// [`Error::Write`].
    pub fn save_svg(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        write_file(path.as_ref(), self.to_svg().as_bytes())
    }
}

/// Rejects sizes outside 1..=MAX_SIDE.
pub(crate) fn check_size(width: u32, height: u32) -> Result<(), Error> {
    if (1..=MAX_SIDE).contains(&width) && (1..=MAX_SIDE).contains(&height) {
        Ok(())
    } else {
        Err(Error::InvalidSize { width, height })
    }
}

/// A pixmap of a size already checked by [`check_size`].
pub(crate) fn new_pixmap(width: u32, height: u32) -> Pixmap {
    // Within MAX_SIDE the byte count cannot overflow, so creation cannot fail.
    Pixmap::new(width, height).unwrap_or_else(|| unreachable!("size checked against MAX_SIDE"))
}
