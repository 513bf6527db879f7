//! # hodr-raster
//!
//! The 2D vector backend of hodr: shape and colour inverse problems rendered with
//! tiny-skia, and image-to-shapes fitting.
//!
//! * A [`Scene`] is an opaque background plus ordered [`Shape`]s (rect, circle,
//!   ellipse, triangle, polygon, closed cubic path), each with an [`Rgba`] fill and
//!   anti-aliasing on or off.
//! * A [`ParamMap`] binds each θ coordinate to one shape attribute with a scale, so θ
//!   is of order one.
//! * A [`Problem`] (scene, map, [`Target`], [`Loss`]) becomes a hodr-core
//!   [`hodr_core::Objective`] as a [`RasterObjective`]: one reused pixmap per thread,
//!   a cached static layer and dirty-region re-rendering ([`Caching`]), parallel batches.
//! * [`tasks`] defines TRI1D, BOX2, BOX10 and SHAPES (docs/design.md §3); [`fit`] approximates
//!   an image by N shapes; [`test_image`] draws the shipped photograph-like test image.
//!
//! Losses are exact integer sums over 8-bit pixels divided by a constant, so a cached
//! evaluation equals a full render bit for bit and a plateau is exactly flat.
//!
//! ```
//! use hodr_raster::{Attribute, Binding, Geometry, ParamMap, Point, Problem, RasterObjective,
//!                   Rgba, Scene, Shape, Target};
//! let square = |x: f32| Shape::new(
//!     Geometry::Rect { center: Point::new(x, 16.0), width: 8.0, height: 8.0, rotation: 0.0 },
//!     Rgba::rgb(1.0, 1.0, 1.0),
//! );
//! let truth = Scene::new(32, 32, Rgba::rgb(0.0, 0.0, 0.0))?.with(square(10.0))?;
//! let scene = Scene::new(32, 32, Rgba::rgb(0.0, 0.0, 0.0))?.with(square(22.0))?;
//! let map = ParamMap::new(vec![Binding::new(0, Attribute::X, 4.0)], &scene)?;
//! let problem = Problem::new(scene, map, Target::from_scene(&truth))?;
//! let mut objective = RasterObjective::new(problem)?;
//! assert_eq!(objective.loss(&[2.5])?, 0.0); // x = 4 · 2.5 = 10 px
//! assert!(objective.loss(&[5.5])? > 0.0);
//! # Ok::<(), hodr_raster::Error>(())
//! ```

#![deny(missing_docs)]

mod cache;
mod color;
mod error;
pub mod fit;
mod loss;
mod objective;
mod params;
mod region;
mod scene;
mod shape;
pub mod svg;
mod target;
pub mod tasks;
pub mod test_image;

pub use color::Rgba;
pub use error::Error;
pub use loss::Loss;
pub use objective::{Caching, Problem, RasterObjective};
pub use params::{Attribute, Binding, ParamMap};
pub use scene::{MAX_SIDE, Scene};
pub use shape::{COORD_LIMIT, Geometry, Point, Shape, ShapeKind};
pub use target::Target;
pub use tiny_skia::Pixmap;
