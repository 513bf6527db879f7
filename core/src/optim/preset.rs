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
//! | `NewtonCg(recipe)` | Newton-CG (Steihaug) | the [`Recipe`]'s | the [`Recipe`]'s |
//!
//! The first six are the paper's methods (docs/design.md §4). Newton-CG is not a list of named
//! variants but a [`Recipe`]: gradient × curvature × σ control × step comparison.
//!
//! Every preset anneals σ linearly from `sigma_start` to `sigma_end` over the budget (the
//! paper's schedule) except a recipe with [`SigmaControl::Adaptive`] (the default one),
//! whose σ shrinks by `sigma_shrink` after each short step to a model minimum
//! ([`Schedule::Adaptive`]).
//!
//! The paper's HVP presets draw the two gradients of a central difference independently
//! (as its code does); [`Hyper::common_random_numbers`] switches them to common random
//! numbers.

use core::fmt;

use super::recipe::{Recipe, SigmaControl};
use super::{Adam, Curvature, Method, Ncg, NegativeCurvature, Newton, Schedule};
use crate::error::Error;
use crate::estimate::{Draws, GradientMethod, HessianMethod, HvpMethod};
use crate::real::Real;

/// Per-task hyper-parameters (docs/design.md §3: pairs / σ start → end / trust region /
/// line-search iterations / recompute; Adam's learning rate).
///
/// [`Hyper::default`] holds the values below, common among the paper's tasks; a task
/// states its own by changing what differs, with the validating `with_*` setters or
/// struct-update syntax (then [`Hyper::validate`] checks the ranges the setters check):
///
/// ```
/// use hodr_core::optim::preset::Hyper;
///
/// let box2 = Hyper::<f64>::default().with_pairs(6)?.with_sigma(100.0, 0.01)?;
/// assert_eq!((box2.trust_radius, box2.recompute), (2.0, 10));
/// assert!(Hyper::<f64>::default().with_sigma(0.01, 1.0).is_err());
/// # Ok::<(), hodr_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyper<T> {
    /// Antithetic pairs per estimate (per element for per-element estimators), ≥ 1.
    /// Default: 4.
    pub pairs: usize,
    /// σ at the start of the run, finite and > 0. Default: 1.
    pub sigma_start: T,
    /// σ at the end of the budget, finite, > 0 and ≤ `sigma_start`. Default: 0.01.
    pub sigma_end: T,
    /// Δ, in units of σ, finite and > 0. Default: 2.
    pub trust_radius: T,
    /// NCG line-search steps, ≥ 1. Default: 3.
    pub line_search_iterations: usize,
    /// NCG line-search tolerance on α²·dᵀd, finite and ≥ 0. Default: 1e-3 (the paper's
    /// value for its 2-D box task).
    pub line_search_tolerance: T,
    /// NCG restart period, ≥ 1. Default: 10.
    pub recompute: usize,
    /// Adam's learning rate, finite and > 0. Default: 0.1.
    pub learning_rate: T,
    /// Central-difference HVPs of the paper's presets with common random numbers.
    /// Default: `false` (the paper's choice).
    pub common_random_numbers: bool,
    /// The step NCG and Newton-CG take where the estimated curvature is not positive.
    /// Default: [`NegativeCurvature::Fallback`].
    pub negative_curvature: NegativeCurvature,
    /// Factor in (0, 1) by which the adaptive schedule shrinks σ after a step shorter
    /// than σ ([`Schedule::Adaptive`]; used only by recipes with
    /// [`SigmaControl::Adaptive`]).
    /// Default: [`SIGMA_SHRINK`].
    pub sigma_shrink: T,
    /// Inner CG steps per iteration of Newton-CG ([`Recipe`]; with the least-squares
    /// gradient it takes [`super::recipe::REGRESSION_INNER_STEPS`]), ≥ 1; 1 makes the
    /// step the model minimum along the gradient, capped by the trust radius.
    /// Default: [`NEWTON_CG_INNER_STEPS`].
    pub inner_steps: usize,
    /// Newton-CG with curvature from the iteration's samples
    /// ([`super::recipe::CurvatureSource::Samples`]) takes its first inner step's
    /// curvature from f on a line along ĝ rather than an HVP
    /// ([`super::NewtonCg::line_curvature`]). Default: `false`.
    pub line_curvature: bool,
}

impl<T: Real> Default for Hyper<T> {
    fn default() -> Self {
        Hyper {
            pairs: 4,
            sigma_start: T::ONE,
            sigma_end: T::from_f64(0.01),
            trust_radius: T::TWO,
            line_search_iterations: 3,
            line_search_tolerance: T::from_f64(1e-3),
            recompute: 10,
            learning_rate: T::from_f64(0.1),
            common_random_numbers: false,
            negative_curvature: NegativeCurvature::Fallback,
            sigma_shrink: T::from_f64(SIGMA_SHRINK),
            inner_steps: NEWTON_CG_INNER_STEPS,
            line_curvature: false,
        }
    }
}

/// `Ok(n)` for n ≥ 1, else [`Error::InvalidSetting`] naming `name`.
fn at_least_one(n: usize, name: &'static str) -> Result<usize, Error> {
    if n == 0 {
        Err(Error::InvalidSetting { name })
    } else {
        Ok(n)
    }
}

/// `Ok(x)` for finite x > 0, else [`Error::InvalidSetting`] naming `name`.
fn positive<T: Real>(x: T, name: &'static str) -> Result<T, Error> {
    if x.is_finite() && x > T::ZERO {
        Ok(x)
    } else {
        Err(Error::InvalidSetting { name })
    }
}

impl<T: Real> Hyper<T> {
    /// Sets [`Hyper::pairs`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_pairs(mut self, pairs: usize) -> Result<Self, Error> {
        self.pairs = at_least_one(pairs, "pairs")?;
        Ok(self)
    }

    /// Sets [`Hyper::sigma_start`] and [`Hyper::sigma_end`] together, so that no order
    /// of calls can pass through an invalid pair.
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] naming the field that is not finite and > 0, or
    /// `sigma_end` when it exceeds `sigma_start`.
    pub fn with_sigma(mut self, start: T, end: T) -> Result<Self, Error> {
        self.sigma_start = positive(start, "sigma_start")?;
        self.sigma_end = positive(end, "sigma_end")?;
        if end > start {
            return Err(Error::InvalidSetting { name: "sigma_end" });
        }
        Ok(self)
    }

    /// Sets [`Hyper::trust_radius`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] unless finite and > 0.
    pub fn with_trust_radius(mut self, trust_radius: T) -> Result<Self, Error> {
        self.trust_radius = positive(trust_radius, "trust_radius")?;
        Ok(self)
    }

    /// Sets [`Hyper::line_search_iterations`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_line_search_iterations(mut self, iterations: usize) -> Result<Self, Error> {
        self.line_search_iterations = at_least_one(iterations, "line_search_iterations")?;
        Ok(self)
    }

    /// Sets [`Hyper::line_search_tolerance`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] unless finite and ≥ 0.
    pub fn with_line_search_tolerance(mut self, tolerance: T) -> Result<Self, Error> {
        if !(tolerance.is_finite() && tolerance >= T::ZERO) {
            return Err(Error::InvalidSetting {
                name: "line_search_tolerance",
            });
        }
        self.line_search_tolerance = tolerance;
        Ok(self)
    }

    /// Sets [`Hyper::recompute`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_recompute(mut self, recompute: usize) -> Result<Self, Error> {
        self.recompute = at_least_one(recompute, "recompute")?;
        Ok(self)
    }

    /// Sets [`Hyper::learning_rate`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] unless finite and > 0.
    pub fn with_learning_rate(mut self, learning_rate: T) -> Result<Self, Error> {
        self.learning_rate = positive(learning_rate, "learning_rate")?;
        Ok(self)
    }

    /// Sets [`Hyper::common_random_numbers`].
    pub fn with_common_random_numbers(mut self, common: bool) -> Self {
        self.common_random_numbers = common;
        self
    }

    /// Sets [`Hyper::negative_curvature`].
    pub fn with_negative_curvature(mut self, policy: NegativeCurvature) -> Self {
        self.negative_curvature = policy;
        self
    }

    /// Sets [`Hyper::sigma_shrink`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] unless 0 < `shrink` < 1.
    pub fn with_sigma_shrink(mut self, shrink: T) -> Result<Self, Error> {
        if !(shrink > T::ZERO && shrink < T::ONE) {
            return Err(Error::InvalidSetting {
                name: "sigma_shrink",
            });
        }
        self.sigma_shrink = shrink;
        Ok(self)
    }

    /// Sets [`Hyper::inner_steps`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_inner_steps(mut self, steps: usize) -> Result<Self, Error> {
        self.inner_steps = at_least_one(steps, "inner_steps")?;
        Ok(self)
    }

    /// Sets [`Hyper::line_curvature`].
    pub fn with_line_curvature(mut self, line: bool) -> Self {
        self.line_curvature = line;
        self
    }

    /// Checks every field against the range the `with_*` setters enforce (for settings
    /// built with struct-update syntax).
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), Error> {
        Hyper::default()
            .with_pairs(self.pairs)?
            .with_sigma(self.sigma_start, self.sigma_end)?
            .with_trust_radius(self.trust_radius)?
            .with_line_search_iterations(self.line_search_iterations)?
            .with_line_search_tolerance(self.line_search_tolerance)?
            .with_recompute(self.recompute)?
            .with_learning_rate(self.learning_rate)?
            .with_sigma_shrink(self.sigma_shrink)?
            .with_inner_steps(self.inner_steps)
            .map(|_| ())
    }
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
    /// Newton-CG (Steihaug) as a [`Recipe`] puts it together.
    NewtonCg(Recipe),
}

impl Preset {
    /// Every preset, the paper's first, then NCG-kernel and the default [`Recipe`].
    pub const ALL: [Preset; 8] = [
        Preset::Fr22,
        Preset::OurG,
        Preset::OurH,
        Preset::OurHNewton,
        Preset::OurHvp,
        Preset::OurHvpa,
        Preset::NcgKernel,
        Preset::NewtonCg(Recipe::DEFAULT),
    ];

    /// The preset named `name` (case-insensitive; a recipe in its text form, see
    /// [`super::recipe`]), if any.
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL
            .into_iter()
            .filter(|p| !matches!(p, Preset::NewtonCg(_)))
            .find(|p| p.paper_name().is_some_and(|n| n.eq_ignore_ascii_case(name)))
            .or_else(|| Recipe::parse(name).ok().map(Preset::NewtonCg))
    }

    /// The name of a preset that is not a recipe.
    fn paper_name(self) -> Option<&'static str> {
        Some(match self {
            Preset::Fr22 => "FR22",
            Preset::OurG => "OurG",
            Preset::OurH => "OurH",
            Preset::OurHNewton => "OurH-Newton",
            Preset::OurHvp => "OurHVP",
            Preset::OurHvpa => "OurHVPA",
            Preset::NcgKernel => "NCG-kernel",
            Preset::NewtonCg(_) => return None,
        })
    }

    /// The gradient estimator of the preset's iterations.
    pub fn gradient(self) -> GradientMethod {
        match self {
            Preset::Fr22 => GradientMethod::Fr22,
            Preset::OurG | Preset::OurH | Preset::OurHNewton | Preset::OurHvp => {
                GradientMethod::PerElement
            }
            Preset::OurHvpa => GradientMethod::Aggregate,
            Preset::NcgKernel => GradientMethod::Gaussian,
            Preset::NewtonCg(r) => r.gradient,
        }
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
            Preset::NewtonCg(recipe) => recipe.method(h),
        }
    }

    /// True for a recipe whose σ follows the run ([`SigmaControl::Adaptive`]).
    pub fn adaptive(self) -> bool {
        matches!(self, Preset::NewtonCg(r) if r.sigma == SigmaControl::Adaptive)
    }

    /// The σ schedule of this preset with these hyper-parameters: the recipe's, linear
    /// for the others.
    pub fn schedule<T: Real>(self, h: &Hyper<T>) -> Schedule<T> {
        match self {
            Preset::NewtonCg(recipe) => recipe.schedule(h),
            _ => Schedule::Linear {
                start: h.sigma_start,
                end: h.sigma_end,
            },
        }
    }
}

impl fmt::Display for Preset {
    /// The name used in reports and on the command line (a recipe's text form).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Preset::NewtonCg(recipe) => recipe.fmt(f),
            named => f.write_str(named.paper_name().unwrap_or_default()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn invalid<T>(result: Result<T, Error>) -> &'static str {
        match result {
            Err(Error::InvalidSetting { name }) => name,
            Err(other) => panic!("expected InvalidSetting, got {other:?}"),
            Ok(_) => panic!("expected InvalidSetting, got Ok"),
        }
    }

    fn defaults_are_documented<T: Real>() {
        let h = Hyper::<T>::default();
        assert_eq!(h.pairs, 4);
        assert_eq!(h.sigma_start, T::ONE);
        assert_eq!(h.sigma_end, T::from_f64(0.01));
        assert_eq!(h.trust_radius, T::from_f64(2.0));
        assert_eq!(h.line_search_iterations, 3);
        assert_eq!(h.line_search_tolerance, T::from_f64(1e-3));
        assert_eq!(h.recompute, 10);
        assert_eq!(h.learning_rate, T::from_f64(0.1));
        assert!(!h.common_random_numbers);
        assert_eq!(h.negative_curvature, NegativeCurvature::Fallback);
        assert_eq!(h.sigma_shrink, T::from_f64(SIGMA_SHRINK));
        assert_eq!(h.inner_steps, NEWTON_CG_INNER_STEPS);
        assert!(!h.line_curvature);
        assert_eq!(h.validate(), Ok(()));
    }

    #[test]
    fn defaults_are_the_documented_values() {
        defaults_are_documented::<f64>();
        defaults_are_documented::<f32>();
        assert_eq!(SIGMA_SHRINK, 0.5);
        assert_eq!(NEWTON_CG_INNER_STEPS, 3);
    }

    #[test]
    fn setters_set_what_they_name() -> Result<(), Error> {
        let h = Hyper::<f64>::default()
            .with_pairs(6)?
            .with_sigma(100.0, 100.0)?
            .with_trust_radius(3.0)?
            .with_line_search_iterations(2)?
            .with_line_search_tolerance(0.0)?
            .with_recompute(5)?
            .with_learning_rate(0.5)?
            .with_common_random_numbers(true)
            .with_negative_curvature(NegativeCurvature::TwoSided)
            .with_sigma_shrink(0.8)?
            .with_inner_steps(1)?
            .with_line_curvature(true);
        let expected = Hyper {
            pairs: 6,
            sigma_start: 100.0,
            sigma_end: 100.0,
            trust_radius: 3.0,
            line_search_iterations: 2,
            line_search_tolerance: 0.0,
            recompute: 5,
            learning_rate: 0.5,
            common_random_numbers: true,
            negative_curvature: NegativeCurvature::TwoSided,
            sigma_shrink: 0.8,
            inner_steps: 1,
            line_curvature: true,
        };
        assert_eq!(h, expected);
        assert_eq!(h.validate(), Ok(()));
        Ok(())
    }

    fn setters_reject_out_of_range<T: Real>() {
        let h = Hyper::<T>::default();
        let bad_reals = [
            T::ZERO,
            -T::ONE,
            T::from_f64(f64::NAN),
            T::from_f64(f64::INFINITY),
        ];
        assert_eq!(invalid(h.with_pairs(0)), "pairs");
        for bad in bad_reals {
            assert_eq!(invalid(h.with_sigma(bad, T::from_f64(0.01))), "sigma_start");
            assert_eq!(invalid(h.with_sigma(T::ONE, bad)), "sigma_end");
            assert_eq!(invalid(h.with_trust_radius(bad)), "trust_radius");
            assert_eq!(invalid(h.with_learning_rate(bad)), "learning_rate");
        }
        assert_eq!(invalid(h.with_sigma(T::ONE, T::TWO)), "sigma_end");
        assert_eq!(
            invalid(h.with_line_search_iterations(0)),
            "line_search_iterations"
        );
        for bad in [-T::ONE, T::from_f64(f64::NAN), T::from_f64(f64::INFINITY)] {
            assert_eq!(
                invalid(h.with_line_search_tolerance(bad)),
                "line_search_tolerance"
            );
        }
        assert_eq!(invalid(h.with_recompute(0)), "recompute");
        for bad in [T::ZERO, T::ONE, T::TWO, -T::HALF, T::from_f64(f64::NAN)] {
            assert_eq!(invalid(h.with_sigma_shrink(bad)), "sigma_shrink");
        }
        assert_eq!(invalid(h.with_inner_steps(0)), "inner_steps");
    }

    #[test]
    fn setters_reject_out_of_range_values() {
        setters_reject_out_of_range::<f64>();
        setters_reject_out_of_range::<f32>();
    }

    #[test]
    fn validate_names_the_first_bad_field_of_a_literal() {
        let bad = |change: fn(&mut Hyper<f64>)| {
            let mut h = Hyper::default();
            change(&mut h);
            invalid(h.validate())
        };
        assert_eq!(bad(|h| h.pairs = 0), "pairs");
        assert_eq!(bad(|h| h.sigma_start = f64::NAN), "sigma_start");
        assert_eq!(bad(|h| h.sigma_end = 2.0), "sigma_end");
        assert_eq!(bad(|h| h.trust_radius = -1.0), "trust_radius");
        assert_eq!(
            bad(|h| h.line_search_iterations = 0),
            "line_search_iterations"
        );
        assert_eq!(
            bad(|h| h.line_search_tolerance = -1.0),
            "line_search_tolerance"
        );
        assert_eq!(bad(|h| h.recompute = 0), "recompute");
        assert_eq!(bad(|h| h.learning_rate = 0.0), "learning_rate");
        assert_eq!(bad(|h| h.sigma_shrink = 1.0), "sigma_shrink");
        assert_eq!(bad(|h| h.inner_steps = 0), "inner_steps");
        assert_eq!(
            bad(|h| {
                h.pairs = 0;
                h.inner_steps = 0;
            }),
            "pairs"
        );
    }
}
