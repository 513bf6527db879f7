//! Errors as values: every failure of hodr-core is one of these, never a panic or NaN.

use core::fmt;

/// Why an estimator (or a workspace) refused to produce a result.
///
/// Small and `Copy`, with no heap payloads. Where an error concerns a sample point, the
/// point itself stays in the workspace ([`crate::Workspace::failed_point`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// σ was ≤ 0, NaN or infinite; an estimate's σ at or below θ's float resolution
    /// (8ε·max|θᵢ|) or so large that θ ± 16σ overflows; or Auto's σ₀ above
    /// `Auto::max_scale`.
    InvalidSigma,
    /// The number of antithetic pairs was 0.
    NoSamples,
    /// A slice's length does not match the problem dimension.
    DimensionMismatch {
        /// The length required.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A caller-provided buffer is too small for the requested work.
    WorkspaceTooSmall {
        /// Elements needed.
        needed: usize,
        /// Elements available.
        available: usize,
    },
    /// A parameter (θ or a direction v) holds NaN or ±∞.
    NonFiniteInput {
        /// Index of the first offending coordinate.
        index: usize,
    },
    /// The objective returned NaN or ±∞. The point is kept in the workspace.
    NonFiniteObjective {
        /// Which evaluation of this estimate (0-based, in evaluation order).
        sample: usize,
    },
    /// A setting is out of its documented range (named by its field).
    InvalidSetting {
        /// The field's name.
        name: &'static str,
    },
    /// One entry of a per-coordinate setting (bounds, scales) is out of its documented
    /// range.
    InvalidEntry {
        /// The setting's name.
        name: &'static str,
        /// The coordinate.
        index: usize,
    },
    /// The estimate itself overflowed (e.g. f ≈ 1e30 with σ ≈ 1e-12 in `f32`).
    NonFiniteEstimate {
        /// Index of the first non-finite output element.
        index: usize,
    },
    /// The objective asked to stop ([`crate::Objective::cancelled`]) after a batch.
    Cancelled,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::InvalidSigma => write!(
                f,
                "smoothing width σ must be finite, > 0 and, in an estimate, above 8ε·max|θᵢ| with θ ± 16σ finite (Auto's σ₀ at most 2⁻⁶⁴ of the largest float)"
            ),
            Error::NoSamples => write!(f, "at least one antithetic pair is needed"),
            Error::DimensionMismatch { expected, found } => {
                write!(
                    f,
                    "dimension mismatch: expected length {expected}, found {found}"
                )
            }
            Error::WorkspaceTooSmall { needed, available } => {
                write!(
                    f,
                    "workspace too small: {needed} elements needed, {available} available"
                )
            }
            Error::NonFiniteInput { index } => {
                write!(f, "input coordinate {index} is not finite")
            }
            Error::NonFiniteObjective { sample } => {
                write!(
                    f,
                    "objective returned a non-finite value at sample {sample}"
                )
            }
            Error::InvalidSetting { name } => write!(f, "setting `{name}` is out of range"),
            Error::InvalidEntry { name, index } => {
                write!(f, "setting `{name}` is out of range at coordinate {index}")
            }
            Error::NonFiniteEstimate { index } => {
                write!(
                    f,
                    "estimate element {index} overflowed to a non-finite value"
                )
            }
            Error::Cancelled => write!(f, "cancelled by the objective"),
        }
    }
}

impl core::error::Error for Error {}
