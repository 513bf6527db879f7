//! # hodr-core
//!
//! Smoothed first- and second-order derivatives of black-box, discontinuous objectives,
//! estimated by Monte Carlo sampling of Gaussian-derivative kernels (Wang, Fischer &
//! Ritschel, *Stochastic Gradient Estimation for Higher-order Differentiable Rendering*,
//! ICCV 2025). The objective f is only point-sampled; its convolution with a Gaussian of
//! width σ, f̄, is C^∞ whatever f is, and
//!
//! ∇f̄(θ) = E[∂N(τ)/p(τ) · f(θ − τ)],  ∇²f̄(θ) = E[∂²N(τ)/p(τ) · f(θ − τ)],  τ ~ p.
//!
//! `#![no_std]`, no allocation: every buffer is the caller's ([`Workspace`]), every
//! failure an [`Error`] value, every random number from the caller's `rand_core::Rng`.
//!
//! ```
//! # #[cfg(all(feature = "hvp", feature = "aggregate"))] {
//! use hodr_core::{Estimator, GradientMethod, HvpMethod, Draws, Workspace};
//! use rand_xoshiro::{Xoshiro256PlusPlus, rand_core::SeedableRng};
//!
//! // A discontinuous objective: 1 inside the unit disc, 0 outside.
//! let mut f = |x: &[f64]| if x[0] * x[0] + x[1] * x[1] < 1.0 { 1.0 } else { 0.0 };
//! let theta = [1.5, 0.0];
//!
//! let (mut buffer, mut seeds) = (vec![0.0; Workspace::<f64>::buffer_len(2, 64)], vec![0; 64]);
//! let mut ws = Workspace::new(2, &mut buffer, &mut seeds)?;
//! let mut est = Estimator::new(0.5, 256, Xoshiro256PlusPlus::seed_from_u64(7))?;
//!
//! let mut grad = [0.0; 2];
//! est.gradient(GradientMethod::Aggregate, &mut f, &theta, &mut ws, &mut grad)?;
//! assert!(grad[0] < 0.0); // the disc lies towards −x
//!
//! let mut hv = [0.0; 2];
//! let method = HvpMethod::CentralDifference { gradient: GradientMethod::Aggregate, draws: Draws::Common };
//! let report = est.hvp(method, &mut f, &theta, &[1.0, 0.0], &mut ws, &mut hv)?;
//! assert_eq!(report.evaluations, 2 * 2 * 256);
//! # }
//! # Ok::<(), hodr_core::Error>(())
//! ```
//!
//! ## Layout
//! * [`real`]: the float trait over `f32`/`f64` (libm);
//! * [`kernel`]: the Gaussian-derivative kernels and normalising constants;
//! * [`sample`]: inverse CDFs of the sampling densities, and offset placement;
//! * [`estimate`]: the estimators, behind one [`Estimator`];
//! * [`optim`]: gradient descent, Adam, Newton, NCG and Newton-CG as step machines, σ
//!   schedules, budgets, and the paper's method presets;
//! * [`trace`]: a fixed-memory convergence trace;
//! * [`log_scale`]: coordinates searched in log₁₀ (a parameter whose box spans decades);
//! * [`Objective`], [`Workspace`], [`Error`];
//! * [`set_wide_kernels`]: on x86, the dense kernels of Auto's fit (Gram matrix,
//!   factorisations, metric products) run an AVX2 copy where the CPU has it (detected
//!   at run time, no std needed), with results identical bit for bit to the baseline
//!   copy's.
//!
//! ## Features
//! The minimal build (no default features) has the FR22 gradient with Adam;
//! `gradient-descent` adds plain gradient descent. `per-element`, `gaussian`, `aggregate` and `regression` add the other
//! gradient estimators; `hessian` (Hessians, Newton), `hvp`, `cg` (NCG; implies `hvp`)
//! and `newton-cg` (Newton-CG; implies `cg`) the second-order methods; all are on by
//! default. Each estimator is an
//! enum variant chosen at run time, so a variant that is compiled in is linked whether a
//! program uses it or not: leaving features out is how a firmware sheds the code.

#![no_std]
#![deny(missing_docs)]

#[cfg(any(feature = "hessian", feature = "regression", feature = "auto"))]
mod cholesky;
mod error;
pub mod estimate;
pub mod kernel;
pub mod log_scale;
mod objective;
pub mod optim;
pub mod real;
pub mod sample;
pub mod trace;
mod wide;
mod workspace;

pub use error::Error;
#[cfg(feature = "hessian")]
pub use estimate::HessianMethod;
#[cfg(feature = "hvp")]
pub use estimate::{Draws, HvpMethod};
pub use estimate::{Estimator, GradientMethod, Report};
#[cfg(feature = "newton-cg")]
pub use estimate::{Lowest, PairValues};
pub use objective::{Batch, NoiseSeed, Objective, Seeded};
pub use real::Real;
pub use wide::set_wide_kernels;
pub use workspace::{FixedWorkspace, MIN_ROWS, Workspace};
