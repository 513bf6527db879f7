//! # hodr-web
//!
//! hodr's 2D inverse-graphics demo in the browser: hodr-core and hodr-raster compiled to
//! `wasm32-unknown-unknown` and bound to JavaScript with wasm-bindgen.
//!
//! * [`run`]: one optimisation run (Auto, FR22, OurH, CMA-ES) on TRI1D, BOX2 or BOX10 as
//!   an `async fn` that yields after every iteration. The page races several such runs,
//!   one frame's work at a time; the native `reference` binary runs the very same
//!   function with a seed so the browser test can check the page's numbers.
//! * [`cma`]: CMA-ES as an ask/tell step machine (the `cmaes` crate reads the clock,
//!   which wasm32-unknown-unknown lacks).
//! * [`fit`]: image to shapes — the dropped file checked, scaled down and fitted.
//! * `bindings` (wasm32 only): the functions the page calls; each returns
//!   `Result<_, JsError>` with a one-line message, so bad input never kills the page.

pub mod cma;
mod error;
pub mod fit;
pub mod run;

#[cfg(target_arch = "wasm32")]
mod bindings;

pub use error::Error;
