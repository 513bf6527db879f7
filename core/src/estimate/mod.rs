//! Monte Carlo estimators of the smoothed gradient, Hessian and Hessian-vector product.
//!
//! Every estimator draws standardised offsets t from a density p, evaluates the objective
//! at antithetic points θ ∓ σt, and weights the values by Dκ/p (docs/design.md §1.2–1.6):
//!
//! * gradients use the odd combination (f(θ−τ) − f(θ+τ))/2 — the f(θ) part cancels;
//! * Hessians and kernel HVPs use the even combination (f(θ−τ) + f(θ+τ))/2 − f(θ), with
//!   f(θ) evaluated once per estimate as a control variate (the weights have zero mean).
//!
//! | method | density of t | evaluations |
//! |---|---|---|
//! | [`GradientMethod::Fr22`] | every coordinate p_G | 2P |
//! | [`GradientMethod::PerElement`] | element i: tᵢ ~ p_G, rest N₁ | 2nP |
//! | [`GradientMethod::Aggregate`] | mixture of the n element densities | 2P |
//! | [`GradientMethod::Gaussian`] | N(0, I) | 2P |
//! | [`GradientMethod::Regression`] | N(0, I), least-squares fit | 2·max(P, 2n + 2) |
//! | [`HessianMethod::PerElement`] | element (i, j), i ≤ j: p_D or p_G×p_G | n(n+1)P + 1 |
//! | [`HessianMethod::Aggregate`] | mixture of the n(n+1)/2 element densities | 2P + 1 |
//! | [`HessianMethod::Gaussian`] | N(0, I) | 2P + 1 |
//! | [`HvpMethod::CentralDifference`] | two gradient estimates at θ ± εv/‖v‖ | 2× gradient |
//! | [`HvpMethod::ForwardDifference`] | gradient estimates at θ + εv/‖v‖ and θ | 2× gradient (1× given g(θ)) |
//! | [`HvpMethod::Kernel`] (`gaussian`) | N(0, I), shared with the gradient | 2P + 1 |
//!
//! P is [`Estimator::pairs`]. All randomness comes from the estimator's RNG, in a fixed
//! order, so a seed fixes the estimate.

mod driver;
mod fr22;
#[cfg(any(feature = "gaussian", feature = "hessian"))]
mod gaussian;
#[cfg(any(feature = "per-element", feature = "hessian"))]
mod per_element;

#[cfg(feature = "aggregate")]
mod aggregate;
#[cfg(feature = "hvp")]
mod hvp;
#[cfg(feature = "regression")]
mod regression;

use rand_core::Rng;

use crate::error::Error;
#[cfg(feature = "newton-cg")]
use crate::objective::NoiseSeed;
use crate::objective::Objective;
use crate::real::Real;
use crate::workspace::{BatchBuffers, Workspace};

/// How to estimate the smoothed gradient.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum GradientMethod {
    /// The FR22 baseline (docs/design.md §1.6): every coordinate drawn from p_G at once, element i
    /// weighted −sign(τᵢ)·Z. Exactly the Gaussian-smoothed gradient only for objectives
    /// that are separable or quadratic; otherwise it smooths the other coordinates with
    /// p_G instead of N₁.
    Fr22,
    /// Per-element importance sampling (docs/design.md §1.2): P pairs per element, tᵢ ~ p_G,
    /// other coordinates N₁, weight −sign(τᵢ)·Z.
    #[cfg(feature = "per-element")]
    PerElement,
    /// Aggregate importance sampling (docs/design.md §1.3): each pair serves every element; the
    /// differentiated coordinate cycles through the elements from a random start, and
    /// weights are −nZτₑ/‖τ‖₁·σ (bounded).
    #[cfg(feature = "aggregate")]
    Aggregate,
    /// Plain Gaussian ("Stein") sampling (docs/design.md §1.4): τ ~ N(0, σ²I), weight −τₑ/σ².
    #[cfg(feature = "gaussian")]
    Gaussian,
    /// Least squares on Gaussian samples: ĝ = (Σ ttᵀ)⁻¹ Σ t·(f(θ+σt) − f(θ−σt))/(2σ),
    /// t ~ N(0, I) — the Gaussian estimator with E(ttᵀ) = I as a control variate. Exact
    /// for quadratics; consistent for ∇f̄ (bias O(1/P)). Draws max(P, 2n + 2) pairs (a
    /// well-conditioned fit needs about twice as many samples as unknowns) and needs a
    /// workspace with a moment region ([`Workspace::moments_len`]).
    #[cfg(feature = "regression")]
    Regression,
}

impl GradientMethod {
    /// True when an estimate from one antithetic pair, offsets ±σt, is a multiple of t
    /// (the aggregate and Gaussian weights are proportional to t; FR22's and the
    /// per-element ones to sign(t)).
    pub fn along_offset(self) -> bool {
        match self {
            #[cfg(feature = "aggregate")]
            GradientMethod::Aggregate => true,
            #[cfg(feature = "gaussian")]
            GradientMethod::Gaussian => true,
            _ => false,
        }
    }

    /// Objective evaluations for one estimate in dimension `n` with `pairs` pairs.
    #[cfg_attr(
        not(any(feature = "per-element", feature = "regression")),
        allow(unused_variables)
    )]
    pub fn evaluations(self, n: usize, pairs: usize) -> usize {
        match self {
            #[cfg(feature = "per-element")]
            GradientMethod::PerElement => 2 * n * pairs,
            #[cfg(feature = "regression")]
            GradientMethod::Regression => 2 * regression::pairs(n, pairs),
            _ => 2 * pairs,
        }
    }
}

/// How to estimate the smoothed Hessian.
#[cfg(feature = "hessian")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum HessianMethod {
    /// Per-element importance sampling using symmetry: P pairs for each of the n(n+1)/2
    /// elements i ≤ j; diagonal tᵢ ~ p_D with weight sign(τᵢ² − σ²)·C, off-diagonal
    /// tᵢ, tⱼ ~ p_G with weight sign(τᵢτⱼ)·Z².
    PerElement,
    /// Aggregate importance sampling over the n(n+1)/2 element densities (docs/design.md §1.3);
    /// the mixture density costs O(n) per sample.
    #[cfg(feature = "aggregate")]
    Aggregate,
    /// Plain Gaussian sampling: weight ττᵀ/σ⁴ − I/σ².
    Gaussian,
}

#[cfg(feature = "hessian")]
impl HessianMethod {
    /// Objective evaluations for one estimate in dimension `n` with `pairs` pairs
    /// (including the control-variate evaluation of f(θ)).
    #[cfg_attr(
        not(any(feature = "per-element", feature = "regression")),
        allow(unused_variables)
    )]
    pub fn evaluations(self, n: usize, pairs: usize) -> usize {
        match self {
            HessianMethod::PerElement => n * (n + 1) * pairs + 1,
            _ => 2 * pairs + 1,
        }
    }
}

/// How to draw the two gradient estimates of a central-difference HVP.
#[cfg(feature = "hvp")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Draws {
    /// Independent offsets and noise seeds for the two gradients (the paper's code).
    Independent,
    /// Common random numbers: the same offsets and noise seeds for both gradients, so
    /// their shared noise cancels in the difference.
    Common,
}

/// How to estimate a Hessian-vector product Hv.
#[cfg(feature = "hvp")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum HvpMethod {
    /// (g(θ + εu) − g(θ − εu))/(2ε)·‖v‖ with u = v/‖v‖, ε = σ/3 (docs/design.md §1.5), each g
    /// from `gradient` with P pairs. Biased by O(ε²) third derivatives of f̄.
    CentralDifference {
        /// The gradient estimator differenced.
        gradient: GradientMethod,
        /// Independent or common random numbers.
        draws: Draws,
    },
    /// (g(θ + εu) − g(θ))/ε·‖v‖ with u = v/‖v‖, ε = σ/3, both g from `gradient` with the
    /// same draws (common random numbers). Biased by O(ε) third derivatives of f̄ — it
    /// is the mean curvature of f̄ along [θ, θ + εu] — but given g(θ) from the same
    /// draws ([`Estimator::hvp_given_gradient`]), as an optimiser that repeats one
    /// sample set per iteration has it, it costs one gradient estimate, not two.
    ForwardDifference {
        /// The gradient estimator differenced.
        gradient: GradientMethod,
    },
    /// The Gaussian kernel (τ(τ·v)/σ⁴ − v/σ²) with τ ~ N(0, σ²I) and the f(θ) control
    /// variate (docs/design.md §1.4): unbiased, and the same samples give the gradient too
    /// ([`Estimator::gradient_and_hvp`]). With the `gaussian` feature.
    #[cfg(feature = "gaussian")]
    Kernel,
}

#[cfg(feature = "hvp")]
impl HvpMethod {
    /// Objective evaluations for one estimate in dimension `n` with `pairs` pairs.
    #[cfg_attr(
        not(any(feature = "per-element", feature = "regression")),
        allow(unused_variables)
    )]
    pub fn evaluations(self, n: usize, pairs: usize) -> usize {
        match self {
            HvpMethod::CentralDifference { gradient, .. }
            | HvpMethod::ForwardDifference { gradient } => 2 * gradient.evaluations(n, pairs),
            #[cfg(feature = "gaussian")]
            HvpMethod::Kernel => 2 * pairs + 1,
        }
    }

    /// The gradient estimator this method differences, if it differences one.
    pub fn differenced(self) -> Option<GradientMethod> {
        match self {
            HvpMethod::CentralDifference { gradient, .. }
            | HvpMethod::ForwardDifference { gradient } => Some(gradient),
            #[cfg(feature = "gaussian")]
            HvpMethod::Kernel => None,
        }
    }
}

/// The ratio ε/σ of the central-difference HVP step (the paper's ε = σ/3).
#[cfg(feature = "hvp")]
pub const HVP_STEP_RATIO: f64 = 1.0 / 3.0;

/// What an estimate cost, and what it learnt on the way.
///
/// "Samples" are the points θ ∓ σt the estimate drew (around θ, or around θ ± εu for a
/// difference HVP), not the control-variate evaluation of f(θ). Values are objective
/// values, in the objective's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Report<T> {
    /// Objective evaluations used.
    pub evaluations: usize,
    /// f(θ) when the estimate evaluated it (the control variate), else `None`.
    pub centre_value: Option<T>,
    /// Mean of every objective value the estimate saw (`None` if it evaluated nothing).
    /// For Gaussian sampling an unbiased estimate of f̄(θ); for importance sampling only
    /// a diagnostic of the loss near θ.
    pub mean_value: Option<T>,
    /// The sample with the lowest value (the earliest among equals); its point is
    /// [`Workspace::lowest_point`] until the next estimate. `None` when the estimate
    /// drew no samples (an HVP along v = 0). This and the next two fields come with the
    /// `newton-cg` feature (the optimiser that compares samples): tracking them costs a
    /// comparison per sample, and code the minimal build leaves out.
    #[cfg(feature = "newton-cg")]
    pub lowest: Option<Lowest<T>>,
    /// The highest value among the samples; `None` when there were none.
    #[cfg(feature = "newton-cg")]
    pub highest: Option<T>,
    /// The values of the one antithetic pair θ ∓ σt around θ itself, when that is all
    /// the estimate sampled (2 evaluations besides f(θ) in the table above: P = 1, and
    /// n = 1 for the per-element methods); its offset t is [`Workspace::pair_offset`]
    /// until the next estimate. `None` otherwise, and always for difference HVPs (their
    /// samples lie around θ ± εu).
    #[cfg(feature = "newton-cg")]
    pub pair: Option<PairValues<T>>,
}

#[cfg(feature = "newton-cg")]
impl<T: Real> Report<T> {
    /// The spread of the sample values, highest − lowest (≥ 0, in the objective's
    /// units); `None` when there were no samples.
    pub fn spread(&self) -> Option<T> {
        Some(self.highest? - self.lowest?.value)
    }
}

/// The lowest-valued sample of an estimate ([`Report::lowest`]).
#[cfg(feature = "newton-cg")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lowest<T> {
    /// Its objective value.
    pub value: T,
    /// The noise seed it was evaluated with (shared by its antithetic partner).
    pub seed: NoiseSeed,
    /// Its number among the estimate's evaluations, counted from 0 in evaluation order
    /// with f(θ), when evaluated, as number 0 (the numbering of
    /// [`Error::NonFiniteObjective`]).
    pub sample: usize,
}

/// The values of one antithetic pair θ ∓ σt ([`Report::pair`]).
#[cfg(feature = "newton-cg")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairValues<T> {
    /// f(θ − σt).
    pub minus: T,
    /// f(θ + σt).
    pub plus: T,
    /// The noise seed both were evaluated with.
    pub seed: NoiseSeed,
}

/// The report of an estimate that used `evaluations` evaluations, read from the batch
/// it has just filled. `pair_around_theta`: its samples were drawn around θ itself, so
/// a lone pair is one of θ ∓ σt.
fn report<T: Real>(
    batch: &BatchBuffers<'_, T>,
    evaluations: usize,
    centre_value: Option<T>,
    pair_around_theta: bool,
) -> Report<T> {
    #[cfg(not(feature = "newton-cg"))]
    let _ = pair_around_theta;
    Report {
        evaluations,
        centre_value,
        mean_value: batch.mean_value(),
        #[cfg(feature = "newton-cg")]
        lowest: batch.lowest,
        #[cfg(feature = "newton-cg")]
        highest: batch.highest,
        #[cfg(feature = "newton-cg")]
        pair: {
            let sampled = evaluations - usize::from(centre_value.is_some());
            (pair_around_theta && sampled == 2).then(|| PairValues {
                minus: batch.values[0],
                plus: batch.values[1],
                seed: batch.seeds[0],
            })
        },
    }
}

/// Smoothing width σ, number of antithetic pairs P, and the random stream.
///
/// The estimator owns its RNG so that a sequence of estimates (an optimisation) is a
/// deterministic function of the seed it was created with.
#[derive(Clone, Debug)]
pub struct Estimator<T, R> {
    sigma: T,
    pairs: usize,
    rng: R,
}

impl<T: Real, R: Rng> Estimator<T, R> {
    /// An estimator with smoothing σ (`sigma`) and P = `pairs` antithetic pairs.
    ///
    /// # Errors
    /// [`Error::InvalidSigma`] unless σ is finite and > 0; [`Error::NoSamples`] if
    /// `pairs == 0`.
    pub fn new(sigma: T, pairs: usize, rng: R) -> Result<Self, Error> {
        check_sigma(sigma)?;
        if pairs == 0 {
            return Err(Error::NoSamples);
        }
        Ok(Estimator { sigma, pairs, rng })
    }

    /// σ, the standard deviation of the smoothing Gaussian.
    #[inline]
    pub fn sigma(&self) -> T {
        self.sigma
    }

    /// Changes σ (for an annealing schedule).
    ///
    /// # Errors
    /// [`Error::InvalidSigma`] unless σ is finite and > 0; σ is then unchanged.
    pub fn set_sigma(&mut self, sigma: T) -> Result<(), Error> {
        check_sigma(sigma)?;
        self.sigma = sigma;
        Ok(())
    }

    /// P, the antithetic pairs per estimate (per element for per-element methods).
    #[inline]
    pub fn pairs(&self) -> usize {
        self.pairs
    }

    /// Changes P.
    ///
    /// # Errors
    /// [`Error::NoSamples`] if `pairs == 0`; P is then unchanged.
    pub fn set_pairs(&mut self, pairs: usize) -> Result<(), Error> {
        if pairs == 0 {
            return Err(Error::NoSamples);
        }
        self.pairs = pairs;
        Ok(())
    }

    /// The random stream.
    pub fn rng_mut(&mut self) -> &mut R {
        &mut self.rng
    }

    /// Smoothed gradient ∇f̄(θ) into `grad` (length n).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] if `theta` or `grad` is not of the workspace's length;
    /// [`Error::NonFiniteInput`] for a non-finite θ; [`Error::InvalidSigma`] where σ is at
    /// or below θ's float resolution, 8ε·max|θᵢ| (every sample would round to θ or its
    /// neighbours), or θ ± 16σ overflows; [`Error::NonFiniteObjective`] (the point stays
    /// in the workspace); [`Error::NonFiniteEstimate`] on overflow;
    /// [`Error::WorkspaceTooSmall`] for [`GradientMethod::Regression`] without a moment
    /// region; [`Error::Cancelled`] when the objective asks to stop. On error `grad`
    /// holds no meaningful values.
    pub fn gradient<O: Objective<T> + ?Sized>(
        &mut self,
        method: GradientMethod,
        objective: &mut O,
        theta: &[T],
        ws: &mut Workspace<'_, T>,
        grad: &mut [T],
    ) -> Result<Report<T>, Error> {
        check_centre(ws.dim, self.sigma, theta)?;
        check_len(ws.dim, grad.len())?;
        ws.batch.begin();
        grad.fill(T::ZERO);
        let evaluations = self.gradient_sum(method, objective, &[theta], T::ONE, ws, grad, 0)?;
        let scale = T::ONE / (self.sigma * T::from_usize(self.pairs));
        scale_checked(grad, scale)?;
        Ok(report(&ws.batch, evaluations, None, true))
    }

    /// Smoothed Hessian ∇²f̄(θ) into `hess` (n×n, row-major, exactly symmetric).
    ///
    /// # Errors
    /// As [`Estimator::gradient`], with `hess.len()` required to be n².
    #[cfg(feature = "hessian")]
    pub fn hessian<O: Objective<T> + ?Sized>(
        &mut self,
        method: HessianMethod,
        objective: &mut O,
        theta: &[T],
        ws: &mut Workspace<'_, T>,
        hess: &mut [T],
    ) -> Result<Report<T>, Error> {
        let n = ws.dim;
        check_centre(n, self.sigma, theta)?;
        check_len(n * n, hess.len())?;
        ws.batch.begin();
        hess.fill(T::ZERO);
        let centre = driver::evaluate_centre(objective, theta, &mut self.rng, &mut ws.batch, 0)?;
        let placement = driver::Placement {
            centres: &[theta],
            sigma: self.sigma,
            baseline: centre,
            first_sample: 1,
        };
        let evaluations = 1 + match method {
            HessianMethod::PerElement => {
                let mut scheme = per_element::Hessian::new(n, self.pairs, hess);
                driver::run(
                    &mut scheme,
                    objective,
                    &placement,
                    &mut self.rng,
                    &mut ws.batch,
                    n,
                )?
            }
            #[cfg(feature = "aggregate")]
            HessianMethod::Aggregate => {
                let mut scheme = aggregate::Hessian::new(n, self.pairs, hess, &mut self.rng);
                driver::run(
                    &mut scheme,
                    objective,
                    &placement,
                    &mut self.rng,
                    &mut ws.batch,
                    n,
                )?
            }
            HessianMethod::Gaussian => {
                let mut scheme = gaussian::Hessian::new(n, self.pairs, hess);
                driver::run(
                    &mut scheme,
                    objective,
                    &placement,
                    &mut self.rng,
                    &mut ws.batch,
                    n,
                )?
            }
        };
        for i in 0..n {
            for j in 0..i {
                hess[i * n + j] = hess[j * n + i];
            }
        }
        let scale = T::ONE / (self.sigma.sq() * T::from_usize(self.pairs));
        scale_checked(hess, scale)?;
        Ok(report(&ws.batch, evaluations, Some(centre), true))
    }

    /// Smoothed Hessian-vector product ∇²f̄(θ)·v into `hv` (length n).
    ///
    /// v = 0 gives 0 without evaluating anything.
    ///
    /// # Errors
    /// As [`Estimator::gradient`]; `v` must be finite and of length n too.
    #[cfg(feature = "hvp")]
    pub fn hvp<O: Objective<T> + ?Sized>(
        &mut self,
        method: HvpMethod,
        objective: &mut O,
        theta: &[T],
        v: &[T],
        ws: &mut Workspace<'_, T>,
        hv: &mut [T],
    ) -> Result<Report<T>, Error> {
        self.hvp_given_gradient(method, objective, theta, None, v, ws, hv)
    }

    /// [`Estimator::hvp`], told the gradient estimate at θ: with
    /// [`HvpMethod::ForwardDifference`] and `gradient_at_theta` = Some(g), g(θ) is not
    /// re-estimated. The caller guarantees that g is what that method's gradient
    /// estimator gives at θ from the draws this estimator's stream produces next (an
    /// optimiser that rewinds its stream before every estimate of an iteration); the
    /// other methods ignore it.
    ///
    /// # Errors
    /// As [`Estimator::hvp`]; `gradient_at_theta` must be finite and of length n too.
    #[allow(clippy::too_many_arguments)]
    #[cfg(feature = "hvp")]
    pub fn hvp_given_gradient<O: Objective<T> + ?Sized>(
        &mut self,
        method: HvpMethod,
        objective: &mut O,
        theta: &[T],
        gradient_at_theta: Option<&[T]>,
        v: &[T],
        ws: &mut Workspace<'_, T>,
        hv: &mut [T],
    ) -> Result<Report<T>, Error> {
        match method {
            HvpMethod::CentralDifference { gradient, draws } => hvp::difference(
                self,
                gradient,
                hvp::Stencil::Central(draws),
                objective,
                theta,
                v,
                ws,
                hv,
            ),
            HvpMethod::ForwardDifference { gradient } => hvp::difference(
                self,
                gradient,
                hvp::Stencil::Forward(gradient_at_theta),
                objective,
                theta,
                v,
                ws,
                hv,
            ),
            #[cfg(feature = "gaussian")]
            HvpMethod::Kernel => self.kernel_hvp(objective, theta, v, ws, None, hv),
        }
    }

    /// Smoothed gradient and Hessian-vector product from one shared set of Gaussian
    /// samples (docs/design.md §1.4): 2P + 1 evaluations for both.
    ///
    /// # Errors
    /// As [`Estimator::hvp`].
    #[cfg(all(feature = "hvp", feature = "gaussian"))]
    pub fn gradient_and_hvp<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        theta: &[T],
        v: &[T],
        ws: &mut Workspace<'_, T>,
        grad: &mut [T],
        hv: &mut [T],
    ) -> Result<Report<T>, Error> {
        self.kernel_hvp(objective, theta, v, ws, Some(grad), hv)
    }

    #[cfg(all(feature = "hvp", feature = "gaussian"))]
    fn kernel_hvp<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        theta: &[T],
        v: &[T],
        ws: &mut Workspace<'_, T>,
        mut grad: Option<&mut [T]>,
        hv: &mut [T],
    ) -> Result<Report<T>, Error> {
        let n = ws.dim;
        check_centre(n, self.sigma, theta)?;
        check_vector(n, v)?;
        check_len(n, hv.len())?;
        if let Some(g) = grad.as_deref() {
            check_len(n, g.len())?;
        }
        ws.batch.begin();
        hv.fill(T::ZERO);
        let centre = driver::evaluate_centre(objective, theta, &mut self.rng, &mut ws.batch, 0)?;
        let placement = driver::Placement {
            centres: &[theta],
            sigma: self.sigma,
            baseline: centre,
            first_sample: 1,
        };
        let grad_acc: &mut [T] = match grad.as_deref_mut() {
            Some(g) => g,
            None => &mut ws.scratch[..n],
        };
        grad_acc.fill(T::ZERO);
        let mut scheme = gaussian::Hvp::new(self.pairs, v, grad_acc, hv);
        let evaluations = 1 + driver::run(
            &mut scheme,
            objective,
            &placement,
            &mut self.rng,
            &mut ws.batch,
            n,
        )?;
        let pairs = T::from_usize(self.pairs);
        scale_checked(hv, T::ONE / (self.sigma.sq() * pairs))?;
        if let Some(g) = grad {
            scale_checked(g, T::ONE / (self.sigma * pairs))?;
        }
        Ok(report(&ws.batch, evaluations, Some(centre), true))
    }

    /// Adds `sign` × Σ (gradient weight × odd combination) over `method`'s samples around
    /// `centres` to `acc`, unscaled (the caller divides by σP). Returns evaluations.
    #[allow(clippy::too_many_arguments)]
    fn gradient_sum<O: Objective<T> + ?Sized>(
        &mut self,
        method: GradientMethod,
        objective: &mut O,
        centres: &[&[T]],
        sign: T,
        ws: &mut Workspace<'_, T>,
        acc: &mut [T],
        first_sample: usize,
    ) -> Result<usize, Error> {
        let n = ws.dim;
        let placement = driver::Placement {
            centres,
            sigma: self.sigma,
            baseline: T::ZERO,
            first_sample,
        };
        let (rng, batch) = (&mut self.rng, &mut ws.batch);
        match method {
            GradientMethod::Fr22 => {
                let mut scheme = fr22::Gradient::new(self.pairs, sign, acc);
                driver::run(&mut scheme, objective, &placement, rng, batch, n)
            }
            #[cfg(feature = "per-element")]
            GradientMethod::PerElement => {
                let mut scheme = per_element::Gradient::new(n, self.pairs, sign, acc);
                driver::run(&mut scheme, objective, &placement, rng, batch, n)
            }
            #[cfg(feature = "aggregate")]
            GradientMethod::Aggregate => {
                let mut scheme = aggregate::Gradient::new(n, self.pairs, sign, acc, rng);
                driver::run(&mut scheme, objective, &placement, rng, batch, n)
            }
            #[cfg(feature = "gaussian")]
            GradientMethod::Gaussian => {
                let mut scheme = gaussian::Gradient::new(self.pairs, sign, acc);
                driver::run(&mut scheme, objective, &placement, rng, batch, n)
            }
            #[cfg(feature = "regression")]
            GradientMethod::Regression => {
                let needed = Workspace::<T>::moments_len(n);
                if ws.moments.len() < needed {
                    return Err(Error::WorkspaceTooSmall {
                        needed,
                        available: ws.moments.len(),
                    });
                }
                let mut scheme = regression::Gradient::new(n, self.pairs, ws.moments);
                let evaluations = driver::run(&mut scheme, objective, &placement, rng, batch, n)?;
                scheme.finish(sign, acc)?;
                Ok(evaluations)
            }
        }
    }
}

fn check_sigma<T: Real>(sigma: T) -> Result<(), Error> {
    if sigma.is_finite() && sigma > T::ZERO {
        Ok(())
    } else {
        Err(Error::InvalidSigma)
    }
}

/// θ is a finite vector of length `n` ([`Error::DimensionMismatch`],
/// [`Error::NonFiniteInput`]) at which σ resolves and its samples stay finite:
/// 8ε·max|θᵢ| < σ (below it θ ± σt rounds to θ or to its neighbouring floats, and the
/// estimate is zero or rounding) and max|θᵢ| + 16σ finite (the samples' reach, far past
/// any normal draw); else [`Error::InvalidSigma`]. One pass over θ.
fn check_centre<T: Real>(n: usize, sigma: T, theta: &[T]) -> Result<(), Error> {
    check_len(n, theta.len())?;
    let mut largest = T::ZERO;
    for (index, x) in theta.iter().enumerate() {
        if !x.is_finite() {
            return Err(Error::NonFiniteInput { index });
        }
        let a = x.abs();
        if a > largest {
            largest = a;
        }
    }
    let resolution = T::from_f64(8.0) * T::EPSILON * largest;
    if sigma > resolution && (largest + T::from_f64(16.0) * sigma).is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidSigma)
    }
}

fn check_len(expected: usize, found: usize) -> Result<(), Error> {
    if expected == found {
        Ok(())
    } else {
        Err(Error::DimensionMismatch { expected, found })
    }
}

#[cfg(feature = "hvp")]
fn check_vector<T: Real>(n: usize, x: &[T]) -> Result<(), Error> {
    check_len(n, x.len())?;
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFiniteInput { index }),
        None => Ok(()),
    }
}

/// Multiplies by `scale` and reports the first non-finite result.
fn scale_checked<T: Real>(x: &mut [T], scale: T) -> Result<(), Error> {
    for (index, v) in x.iter_mut().enumerate() {
        *v *= scale;
        if !v.is_finite() {
            return Err(Error::NonFiniteEstimate { index });
        }
    }
    Ok(())
}

/// A uniform index in 0..k (k ≥ 1) by Lemire's multiply-shift, for the random start of
/// an aggregate estimator's cycle through its mixture components.
#[cfg(feature = "aggregate")]
fn uniform_index<R: Rng + ?Sized>(rng: &mut R, k: usize) -> usize {
    ((rng.next_u64() as u128 * k as u128) >> 64) as usize
}

/// The (i, j), i ≤ j, of component `c` when the upper triangle of an n×n matrix is
/// numbered row by row: row i starts at c = i·n − i(i−1)/2. O(1) by an integer square
/// root, corrected by at most a step either way.
#[cfg(feature = "hessian")]
pub(crate) fn upper_triangle(c: usize, n: usize) -> (usize, usize) {
    let start = |i: usize| i * n - i * i.saturating_sub(1) / 2;
    let b = 2 * n as u64 + 1;
    let disc = (b * b).saturating_sub(8 * c as u64);
    let mut i = ((b - disc.isqrt()) / 2) as usize;
    i = i.min(n - 1);
    while i + 1 < n && start(i + 1) <= c {
        i += 1;
    }
    while start(i) > c {
        i -= 1;
    }
    (i, i + (c - start(i)))
}

/// Adds s·(ttᵀ − I) to the upper triangle (i ≤ j) of the row-major n×n matrix `out`.
#[cfg(feature = "hessian")]
pub(crate) fn add_rank_one<T: Real>(out: &mut [T], n: usize, t: &[T], s: T) {
    for (i, &ti) in t.iter().enumerate() {
        let row = &mut out[i * n..(i + 1) * n];
        let sti = s * ti;
        row[i] += sti * ti - s;
        for (h, &tj) in row[i + 1..].iter_mut().zip(&t[i + 1..]) {
            *h += sti * tj;
        }
    }
}

#[cfg(all(test, feature = "hessian"))]
mod tests {
    use super::*;

    #[test]
    fn upper_triangle_numbering() {
        for n in [1, 2, 3, 7, 64, 1024] {
            let mut c = 0;
            for i in 0..n {
                for j in i..n {
                    assert_eq!(upper_triangle(c, n), (i, j), "n={n} c={c}");
                    c += 1;
                }
            }
        }
    }
}
