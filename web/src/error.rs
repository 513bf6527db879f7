//! The demo's one error type: every message is one line that names the culprit, so the
//! page can show it as it is.

use std::fmt;

/// What went wrong in a demo call.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// hodr-core refused a setting or an estimate failed.
    Core(hodr_core::Error),
    /// hodr-raster refused a scene, a task or an image.
    Raster(hodr_raster::Error),
    /// A setting of the page is out of range.
    Setting {
        /// The setting, as the page labels it.
        name: &'static str,
        /// What it must be.
        expected: &'static str,
    },
    /// The dropped file is not a PNG or JPEG image.
    NotAnImage(String),
    /// The image is larger than the demo accepts.
    ImageTooLarge {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Core(e) => write!(f, "hodr-core: {e}"),
            Error::Raster(e) => write!(f, "hodr-raster: {e}"),
            Error::Setting { name, expected } => write!(f, "{name} must be {expected}"),
            Error::NotAnImage(why) => write!(f, "the file is not a PNG or JPEG image ({why})"),
            Error::ImageTooLarge { width, height } => write!(
                f,
                "the image is {width}×{height} pixels; the demo takes at most {0}×{0}",
                crate::fit::MAX_INPUT_SIDE
            ),
        }
    }
}

impl std::error::Error for Error {}

impl From<hodr_core::Error> for Error {
    fn from(e: hodr_core::Error) -> Self {
        Error::Core(e)
    }
}

impl From<hodr_raster::Error> for Error {
    fn from(e: hodr_raster::Error) -> Self {
        Error::Raster(e)
    }
}
