//! # hodr-embedded
//!
//! The workload of hodr's microcontroller firmware (`firmware/`), as a `no_std`, heap-free
//! library, so that the firmware and its host reference run *the same code*: the same
//! problems, settings, seeds and float type (`f32`), and the same report format.
//!
//! * [`problem`]: QUAD (f = 5x₀² + 5x₁² + 7.5x₀x₁) and PLATEAU (a 1-D well of zero loss
//!   in a plateau of one), with their settings;
//! * [`algorithm`]: FR22 (Adam), OurHVPA (NCG + aggregate HVP, feature `ncg`),
//!   OurH (NCG + per-element Hessian, feature `hessian`) and Auto, hodr-core's default
//!   optimiser (feature `auto`);
//! * [`run_all`]: every problem with every compiled-in algorithm, in static memory
//!   ([`Storage`]), one report line per run to an [`Output`];
//! * [`report`]: writing those lines without `core::fmt` (θ as the bit patterns of its
//!   `f32`s, counts by repeated subtraction), and parsing and comparing them (the
//!   firmware-against-host check);
//! * [`softfloat`]: `f32` arithmetic, comparisons and conversions in integer
//!   instructions, which the firmware links in place of compiler-builtins' on the
//!   targets without an FPU.
//!
//! Features select the algorithms and, through them, the hodr-core features the firmware
//! links: none (gradient estimators + Adam), `ncg` (+ hvp, aggregate, cg), `hessian`
//! (every hodr-core feature). Results of an algorithm do not depend on which others are
//! compiled in.
//!
//! ```
//! let mut storage = hodr_embedded::Storage::new();
//! let mut report = Vec::new();
//! hodr_embedded::run_all(&mut |bytes: &[u8]| report.extend_from_slice(bytes), &mut storage);
//! assert!(report.starts_with(b"run QUAD FR22 evaluations=3000 "));
//! ```

#![no_std]
#![deny(missing_docs)]

#[cfg(test)]
extern crate std;

pub mod algorithm;
pub mod problem;
pub mod report;
mod run;
pub mod softfloat;

pub use report::Output;
#[cfg(feature = "auto")]
pub use run::AUTO_FLOATS;
pub use run::{MAX_DIM, OPTIMISER_FLOATS, ROWS, Storage, run_all, run_one};
