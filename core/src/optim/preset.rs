//! The paper's methods (and ours) as ready-made optimiser settings.
//!
//! | preset | optimiser | gradient | curvature |
//! |---|---|---|---|
//! | `Fr22` | Adam | FR22 | — |
//! | `OurG` | Adam | per-element IS | — |
//! | `OurH` | NCG | per-element IS | per-element IS Hessian |
//! | `OurHNewton` | Newton | per-element IS | per-element IS Hessian |
//! | `OurHvp` | NCG | per-element IS | central-difference HVP of per-element gradients |
//! | `OurHvpa` | NCG | aggregate IS | central-difference HVP of aggregate gradients |
//! | `NcgKernel` | NCG | Gaussian | kernel HVP, samples shared with the gradient |
//! | `NewtonCgKernel` | Newton-CG (Steihaug) | Gaussian | kernel HVP |
//! | `NewtonCgAggregate` | Newton-CG (Steihaug), one sample set per iteration | aggregate IS | CRN forward-difference HVP |
//! | `NewtonCgRegression` | Newton-CG (Steihaug), one sample set per iteration | least squares | CRN forward-difference HVP |
//! | `NewtonCgAdaptive` | `NewtonCgAggregate` with the adaptive σ schedule | aggregate IS | CRN forward-difference HVP |
//! | `NewtonCgCompare` | `NewtonCgAdaptive`, steps compared on f with θ and the lowest sample | aggregate IS | CRN forward-difference HVP |
//! | `NewtonCgFr22` | `NewtonCgAdaptive` on FR22 gradients | FR22 | CRN forward-difference HVP of FR22 gradients |
//!
//! Every preset anneals σ linearly from `sigma_start` to `sigma_end` over the budget (the
//! paper's schedule) except `NewtonCgAdaptive`, `NewtonCgCompare` and `NewtonCgFr22`,
//! whose σ shrinks by `sigma_shrink` after each short step to a model minimum
//! ([`Schedule::Adaptive`]; [`Preset::adaptive`]).
//!
//! The paper's HVP presets draw the two gradients of a central difference independently
//! (as its code does); [`Hyper::common_random_numbers`] switches them to common random
//! numbers. Our Newton-CG presets difference the gradient at θ + εu with the
//! iteration's own ĝ(θ) from the same samples ([`HvpMethod::ForwardDifference`]): each
//! HVP costs one gradient estimate instead of two. Measured (20 seeds, evaluations to
//! 99 % parameter-error reduction, central → forward): BOX2-REF NewtonCG-A 396 → 216,
//! QUAD-far NewtonCG-AS 294 → 196, BOX2 NewtonCG-FR 84 → 64 (BENCHMARKS.md). Where an
//! iteration's gradient is one antithetic pair along its offset (the aggregate
//! estimator with one pair, any estimator in one dimension), they take the curvature
//! along it from the pair and f(θ) instead ([`NewtonCg::pair_curvature`]): QUAD-far
//! NewtonCG-ASC 246 → 148, BOX2-REF 48 → 41. With [`Hyper::line_curvature`] the
//! first curvature of an iteration with several pairs comes from f on a line along ĝ
//! ([`NewtonCg::line_curvature`]): BOX10 NewtonCG-FR 1 536 → 918.

use super::{Adam, Curvature, Method, Ncg, NegativeCurvature, Newton, NewtonCg, Schedule};
use crate::estimate::{Draws, GradientMethod, HessianMethod, HvpMethod};
use crate::real::Real;

/// Per-task hyper-parameters (DESIGN §3: pairs / σ start → end / trust region /
/// line-search iterations / recompute; Adam's learning rate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyper<T> {
    /// Antithetic pairs per estimate (per element for per-element estimators).
    pub pairs: usize,
    /// σ at the start of the run.
    pub sigma_start: T,
    /// σ at the end of the budget.
    pub sigma_end: T,
    /// Δ, in units of σ.
    pub trust_radius: T,
    /// NCG line-search steps.
    pub line_search_iterations: usize,
    /// NCG line-search tolerance on α²·dᵀd. Default: 1e-3 (the paper's BOX2 value).
    pub line_search_tolerance: T,
    /// NCG restart period.
    pub recompute: usize,
    /// Adam's learning rate.
    pub learning_rate: T,
    /// Central-difference HVPs of the paper's presets with common random numbers.
    /// Default: `false` (the paper's choice).
    pub common_random_numbers: bool,
    /// The step NCG and Newton-CG take where the estimated curvature is not positive.
    /// Default: [`NegativeCurvature::Fallback`].
    pub negative_curvature: NegativeCurvature,
    /// Factor in (0, 1) by which the adaptive schedule shrinks σ after a step shorter
    /// than σ ([`Schedule::Adaptive`]; used only by the presets that are
    /// [`Preset::adaptive`]).
    /// Default: [`SIGMA_SHRINK`].
    pub sigma_shrink: T,
    /// Inner CG steps per iteration of the Newton-CG presets (not
    /// [`Preset::NewtonCgRegression`], which takes [`REGRESSION_INNER_STEPS`]); 1 makes
    /// the step the model minimum along the gradient, capped by the trust radius.
    /// Default: [`NEWTON_CG_INNER_STEPS`].
    pub inner_steps: usize,
    /// The reusing Newton-CG presets (NewtonCG-A, -AS, -ASC, -FR, -LS) take their first
    /// inner step's curvature from f on a line along ĝ rather than an HVP
    /// ([`NewtonCg::line_curvature`]). Default: `false`.
    pub line_curvature: bool,
}

/// Default [`Hyper::sigma_shrink`].
pub const SIGMA_SHRINK: f64 = 0.5;

/// Default [`Hyper::inner_steps`].
pub const NEWTON_CG_INNER_STEPS: usize = 3;

/// A named method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Preset {
    /// Adam + FR22 gradient (the baseline).
    Fr22,
    /// Adam + per-element IS gradient.
    OurG,
    /// NCG + per-element IS gradient and Hessian.
    OurH,
    /// Newton + per-element IS gradient and Hessian.
    OurHNewton,
    /// NCG + per-element IS gradient + central-difference HVP.
    OurHvp,
    /// NCG + aggregate gradient + aggregate central-difference HVP.
    OurHvpa,
    /// NCG + Gaussian gradient + kernel HVP from shared samples.
    NcgKernel,
    /// Newton-CG (Steihaug) + Gaussian gradient + kernel HVP.
    NewtonCgKernel,
    /// Newton-CG (Steihaug) + aggregate gradient + CRN forward-difference HVP of
    /// aggregate gradients, every estimate of an iteration from the same samples
    /// ([`Hyper::inner_steps`] inner steps).
    NewtonCgAggregate,
    /// Newton-CG (Steihaug) + least-squares gradient + CRN forward-difference HVP of
    /// least-squares gradients, every estimate of an iteration from the same samples
    /// (up to [`REGRESSION_INNER_STEPS`] inner steps). Exact Newton steps on quadratics
    /// whatever their conditioning.
    NewtonCgRegression,
    /// [`Preset::NewtonCgAggregate`] with σ following the run ([`Schedule::Adaptive`])
    /// rather than the budget.
    NewtonCgAdaptive,
    /// [`Preset::NewtonCgAdaptive`] whose iterations end with a comparison on f of the
    /// current θ, the model step and the iteration's lowest sample
    /// ([`NewtonCg::compare_samples`]).
    NewtonCgCompare,
    /// [`Preset::NewtonCgAdaptive`] with the FR22 gradient (DESIGN §1.6) and the CRN
    /// forward difference of FR22 gradients as its HVP. FR22 blurs the coordinates it
    /// does not differentiate with p_G, which vanishes at 0, rather than N₁; where
    /// several shapes move at once (BOX10) Newton-CG on these estimates converges and
    /// on the aggregate ones it does not (shapes settle on one another).
    NewtonCgFr22,
}

/// Inner CG steps per iteration of [`Preset::NewtonCgRegression`] (Newton-CG caps them at
/// 2n): its HVPs are exact on quadratics, so long inner runs stay conjugate and pay off
/// on stiff problems.
pub const REGRESSION_INNER_STEPS: usize = 100;

/// Inner CG tolerance of [`Preset::NewtonCgRegression`]: on a stiff problem the soft
/// directions dominate the parameter error but barely show in the residual, so the
/// inner solve runs to near-exactness.
pub const REGRESSION_INNER_TOLERANCE: f64 = 1e-8;

impl Preset {
    /// Every preset, the paper's first.
    pub const ALL: [Preset; 13] = [
        Preset::Fr22,
        Preset::OurG,
        Preset::OurH,
        Preset::OurHNewton,
        Preset::OurHvp,
        Preset::OurHvpa,
        Preset::NcgKernel,
        Preset::NewtonCgKernel,
        Preset::NewtonCgAggregate,
        Preset::NewtonCgRegression,
        Preset::NewtonCgAdaptive,
        Preset::NewtonCgCompare,
        Preset::NewtonCgFr22,
    ];

    /// The name used in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Fr22 => "FR22",
            Preset::OurG => "OurG",
            Preset::OurH => "OurH",
            Preset::OurHNewton => "OurH-Newton",
            Preset::OurHvp => "OurHVP",
            Preset::OurHvpa => "OurHVPA",
            Preset::NcgKernel => "NCG-kernel",
            Preset::NewtonCgKernel => "NewtonCG-kernel",
            Preset::NewtonCgAggregate => "NewtonCG-A",
            Preset::NewtonCgRegression => "NewtonCG-LS",
            Preset::NewtonCgAdaptive => "NewtonCG-AS",
            Preset::NewtonCgCompare => "NewtonCG-ASC",
            Preset::NewtonCgFr22 => "NewtonCG-FR",
        }
    }

    /// The preset with this name (case-insensitive), if any.
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(name))
    }

    /// True for the first-order presets (Adam).
    pub fn is_first_order(self) -> bool {
        matches!(self, Preset::Fr22 | Preset::OurG)
    }

    /// The optimiser settings for these hyper-parameters.
    pub fn method<T: Real>(self, h: &Hyper<T>) -> Method<T> {
        let paper_draws = if h.common_random_numbers {
            Draws::Common
        } else {
            Draws::Independent
        };
        let ncg = |gradient, curvature| {
            Method::Ncg(Ncg {
                gradient,
                curvature,
                trust_radius: h.trust_radius,
                line_search_iterations: h.line_search_iterations,
                line_search_tolerance: h.line_search_tolerance,
                recompute: h.recompute,
                reuse_samples: false,
                negative_curvature: h.negative_curvature,
            })
        };
        // Newton-CG with fresh samples per estimate.
        let newton_cg = |gradient, hvp| NewtonCg {
            gradient,
            hvp,
            trust_radius: h.trust_radius,
            max_inner: h.inner_steps,
            inner_tolerance: T::from_f64(0.1),
            reuse_samples: false,
            reorthogonalize: false,
            negative_curvature: h.negative_curvature,
            compare_samples: false,
            pair_curvature: false,
            line_curvature: false,
        };
        // Newton-CG on one sample set per iteration, CRN forward-difference HVPs of the
        // same gradient estimator (from the iteration's ĝ(θ)).
        let reusing = |gradient| NewtonCg {
            reuse_samples: true,
            pair_curvature: true,
            line_curvature: h.line_curvature,
            ..newton_cg(gradient, HvpMethod::ForwardDifference { gradient })
        };
        match self {
            Preset::Fr22 => Method::Adam(Adam::new(GradientMethod::Fr22, h.learning_rate)),
            Preset::OurG => Method::Adam(Adam::new(GradientMethod::PerElement, h.learning_rate)),
            Preset::OurH => ncg(
                GradientMethod::PerElement,
                Curvature::Hessian(HessianMethod::PerElement),
            ),
            Preset::OurHNewton => Method::Newton(Newton {
                gradient: GradientMethod::PerElement,
                hessian: HessianMethod::PerElement,
                trust_radius: h.trust_radius,
            }),
            Preset::OurHvp => ncg(
                GradientMethod::PerElement,
                Curvature::Hvp(HvpMethod::CentralDifference {
                    gradient: GradientMethod::PerElement,
                    draws: paper_draws,
                }),
            ),
            Preset::OurHvpa => ncg(
                GradientMethod::Aggregate,
                Curvature::Hvp(HvpMethod::CentralDifference {
                    gradient: GradientMethod::Aggregate,
                    draws: paper_draws,
                }),
            ),
            Preset::NcgKernel => ncg(GradientMethod::Gaussian, Curvature::Hvp(HvpMethod::Kernel)),
            Preset::NewtonCgKernel => {
                Method::NewtonCg(newton_cg(GradientMethod::Gaussian, HvpMethod::Kernel))
            }
            Preset::NewtonCgAggregate | Preset::NewtonCgAdaptive => {
                Method::NewtonCg(reusing(GradientMethod::Aggregate))
            }
            Preset::NewtonCgCompare => Method::NewtonCg(NewtonCg {
                compare_samples: true,
                ..reusing(GradientMethod::Aggregate)
            }),
            Preset::NewtonCgFr22 => Method::NewtonCg(reusing(GradientMethod::Fr22)),
            Preset::NewtonCgRegression => Method::NewtonCg(NewtonCg {
                max_inner: REGRESSION_INNER_STEPS,
                inner_tolerance: T::from_f64(REGRESSION_INNER_TOLERANCE),
                reorthogonalize: true,
                ..reusing(GradientMethod::Regression)
            }),
        }
    }

    /// True for the presets whose σ follows the run ([`Schedule::Adaptive`]):
    /// [`Preset::NewtonCgAdaptive`], [`Preset::NewtonCgCompare`] and
    /// [`Preset::NewtonCgFr22`].
    pub fn adaptive(self) -> bool {
        matches!(
            self,
            Preset::NewtonCgAdaptive | Preset::NewtonCgCompare | Preset::NewtonCgFr22
        )
    }

    /// The σ schedule of this preset with these hyper-parameters: adaptive where
    /// [`Preset::adaptive`], linear otherwise.
    pub fn schedule<T: Real>(self, h: &Hyper<T>) -> Schedule<T> {
        if self.adaptive() {
            Schedule::Adaptive {
                start: h.sigma_start,
                end: h.sigma_end,
                shrink: h.sigma_shrink,
            }
        } else {
            Schedule::Linear {
                start: h.sigma_start,
                end: h.sigma_end,
            }
        }
    }
}
