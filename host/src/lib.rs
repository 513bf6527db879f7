//! # hodr-host
//!
//! hodr on a host (std): closed-form test problems, the estimator variance study, and
//! (as they land) the path tracer, the task suite, the report harness and the `hodr`
//! command line.

#![deny(missing_docs)]

pub mod box2ref;
pub mod metrics;
pub mod problems;
pub mod render;
pub mod runtime;
pub mod tasks;
pub mod variance;
