//! # hodr-host
//!
//! hodr on a host (std): the CPU path tracer ([`render`]) and its 3D tasks ([`tasks`]),
//! the report harness ([`report`]) behind the `hodr` command line, BOX2-REF, closed-form
//! test problems, the estimator and optimiser studies ([`variance`], [`runtime`]), and the
//! generalisation suite ([`suite`]).

#![deny(missing_docs)]

pub mod box2ref;
pub mod metrics;
pub mod problems;
pub mod render;
pub mod report;
pub mod runtime;
pub mod suite;
pub mod tasks;
pub mod variance;
