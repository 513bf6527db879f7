//! Sampling: uniform numbers to kernel-distributed offsets, by inverse CDFs.
//!
//! All warps are pure functions of a uniform ξ ∈ (0, 1) in standardised units (σ = 1);
//! estimators multiply by σ. A sample is a monotone function of its ξ, so the antithetic
//! partner of τ is exactly −τ (ξ ↦ 1 − ξ, every density here being symmetric) and
//! low-discrepancy sequences can replace the random stream.
//!
//! * [`normal`]: N₁ for the coordinates that are not differentiated;
//! * [`gradient`]: p_G ∝ |N₁′|, for a differentiated coordinate (closed form);
//! * [`hessian_diag`]: p_D ∝ |N₁″|, for a twice-differentiated coordinate (Newton);
//! * [`place`]: an n-dimensional standardised offset with the kernel coordinate(s) among
//!   Gaussian ones (exact, as the Gaussian is separable).

pub mod gradient;
#[cfg(feature = "hessian")]
pub mod hessian_diag;
pub mod normal;
pub mod place;
