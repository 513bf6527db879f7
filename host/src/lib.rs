//! # hodr-host
//!
//! hodr on a host (std): the estimator variance study, and later the path tracer, the
//! task suite, the report harness and the `hodr` command line.

pub mod render;
pub mod tasks;
