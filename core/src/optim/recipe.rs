//! Newton-CG put together from independent choices: a [`Recipe`] is gradient ×
//! curvature × σ control × step comparison, each with a default, instead of one named
//! preset per combination.
//!
//! Its text form, for command lines and reports, is `NewtonCG` followed by one `/token`
//! per choice that differs from the default, in the order below (`NewtonCG/fr22/compare`):
//!
//! | choice | tokens (default first) | field |
//! |---|---|---|
//! | gradient estimator | `aggregate`, `fr22`, `ls`, `gaussian`, `per-element` | [`Recipe::gradient`] |
//! | curvature | `samples`, `kernel` | [`Recipe::curvature`] |
//! | σ control | `adaptive`, `linear` | [`Recipe::sigma`] |
//! | step comparison | (none), `compare` | [`Recipe::compare`] |

use core::fmt;

use super::{Method, NewtonCg, Schedule};
use crate::error::Error;
use crate::estimate::{GradientMethod, HvpMethod};
use crate::optim::preset::Hyper;
use crate::real::Real;

/// Inner CG steps per iteration with the least-squares gradient (Newton-CG caps them at
/// 2n): its HVPs are exact on quadratics, so long inner runs stay conjugate and pay off
/// on stiff problems.
pub const REGRESSION_INNER_STEPS: usize = 100;

/// Inner CG tolerance with the least-squares gradient: on a stiff problem the soft
/// directions dominate the parameter error but barely show in the residual, so the
/// inner solve runs to near-exactness.
pub const REGRESSION_INNER_TOLERANCE: f64 = 1e-8;

/// Inner CG tolerance otherwise: ‖r‖ ≤ 0.1‖ĝ‖.
pub const INNER_TOLERANCE: f64 = 0.1;

/// Where Newton-CG's Hessian-vector products come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CurvatureSource {
    /// The forward difference of the gradient estimator on the iteration's own samples
    /// ([`HvpMethod::ForwardDifference`], [`NewtonCg::reuse_samples`]): one sample set
    /// per iteration, each HVP one gradient estimate, and the curvature along a single
    /// pair from the pair itself ([`NewtonCg::pair_curvature`]). The default.
    Samples,
    /// The Gaussian kernel HVP ([`HvpMethod::Kernel`]), fresh samples per estimate.
    Kernel,
}

/// How σ moves during a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SigmaControl {
    /// σ follows the run: it shrinks by [`Hyper::sigma_shrink`] after a short or
    /// rejected step, from [`Hyper::sigma_start`] down to [`Hyper::sigma_end`], never
    /// above the linear schedule's σ ([`Schedule::Adaptive`]). The default.
    Adaptive,
    /// σ falls linearly from [`Hyper::sigma_start`] to [`Hyper::sigma_end`] over the
    /// budget ([`Schedule::Linear`], the paper's schedule).
    Linear,
}

/// Newton-CG (Steihaug) built from four choices; [`Recipe::DEFAULT`] takes the first
/// of each.
///
/// ```
/// use hodr_core::GradientMethod;
/// use hodr_core::optim::recipe::Recipe;
///
/// let fr = Recipe::DEFAULT.with_gradient(GradientMethod::Fr22).with_compare(true);
/// assert_eq!(fr.to_string(), "NewtonCG/fr22/compare");
/// assert_eq!(Recipe::parse("newtoncg/FR22/compare"), Ok(fr));
/// assert_eq!(Recipe::parse("NewtonCG"), Ok(Recipe::DEFAULT));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Recipe {
    /// The gradient estimator. Default: [`GradientMethod::Aggregate`].
    pub gradient: GradientMethod,
    /// Where the curvature comes from. Default: [`CurvatureSource::Samples`].
    pub curvature: CurvatureSource,
    /// How σ moves. Default: [`SigmaControl::Adaptive`].
    pub sigma: SigmaControl,
    /// End each iteration with a comparison on f of θ, the model step and the
    /// iteration's lowest sample ([`NewtonCg::compare_samples`]). Default: `false`.
    pub compare: bool,
}

impl Default for Recipe {
    fn default() -> Self {
        Recipe::DEFAULT
    }
}

/// Every gradient estimator with its token.
const GRADIENTS: [(GradientMethod, &str); 5] = [
    (GradientMethod::Aggregate, "aggregate"),
    (GradientMethod::Fr22, "fr22"),
    (GradientMethod::Regression, "ls"),
    (GradientMethod::Gaussian, "gaussian"),
    (GradientMethod::PerElement, "per-element"),
];

/// The text form's prefix.
pub const NAME: &str = "NewtonCG";

impl Recipe {
    /// Aggregate gradient, curvature from the iteration's samples, adaptive σ, no
    /// comparison.
    pub const DEFAULT: Recipe = Recipe {
        gradient: GradientMethod::Aggregate,
        curvature: CurvatureSource::Samples,
        sigma: SigmaControl::Adaptive,
        compare: false,
    };

    /// Sets [`Recipe::gradient`].
    pub const fn with_gradient(mut self, gradient: GradientMethod) -> Self {
        self.gradient = gradient;
        self
    }

    /// Sets [`Recipe::curvature`].
    pub const fn with_curvature(mut self, curvature: CurvatureSource) -> Self {
        self.curvature = curvature;
        self
    }

    /// Sets [`Recipe::sigma`].
    pub const fn with_sigma(mut self, sigma: SigmaControl) -> Self {
        self.sigma = sigma;
        self
    }

    /// Sets [`Recipe::compare`].
    pub const fn with_compare(mut self, compare: bool) -> Self {
        self.compare = compare;
        self
    }

    /// The recipe written `text` (case-insensitive; see the module docs).
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] naming `method` when `text` does not start with
    /// `NewtonCG`, or naming the choice (`gradient`, `curvature`, `sigma`) a token
    /// repeats; `recipe` for a token that is no choice's.
    pub fn parse(text: &str) -> Result<Recipe, Error> {
        let mut tokens = text.split('/');
        if !tokens
            .next()
            .is_some_and(|head| head.eq_ignore_ascii_case(NAME))
        {
            return Err(Error::InvalidSetting { name: "method" });
        }
        let mut recipe = Recipe::DEFAULT;
        let mut seen = [false; 4];
        let mut set = |k: usize, name: &'static str| {
            if core::mem::replace(&mut seen[k], true) {
                Err(Error::InvalidSetting { name })
            } else {
                Ok(())
            }
        };
        for token in tokens {
            let is = |t: &str| token.eq_ignore_ascii_case(t);
            if let Some(&(g, _)) = GRADIENTS.iter().find(|(_, t)| is(t)) {
                set(0, "gradient")?;
                recipe.gradient = g;
            } else if is("samples") || is("kernel") {
                set(1, "curvature")?;
                recipe.curvature = if is("kernel") {
                    CurvatureSource::Kernel
                } else {
                    CurvatureSource::Samples
                };
            } else if is("adaptive") || is("linear") {
                set(2, "sigma")?;
                recipe.sigma = if is("linear") {
                    SigmaControl::Linear
                } else {
                    SigmaControl::Adaptive
                };
            } else if is("compare") {
                set(3, "compare")?;
                recipe.compare = true;
            } else {
                return Err(Error::InvalidSetting { name: "recipe" });
            }
        }
        Ok(recipe)
    }

    /// The optimiser for these hyper-parameters: trust radius Δ = [`Hyper::trust_radius`]
    /// σ, [`Hyper::inner_steps`] inner CG steps to ‖r‖ ≤ [`INNER_TOLERANCE`]·‖ĝ‖
    /// ([`REGRESSION_INNER_STEPS`] to [`REGRESSION_INNER_TOLERANCE`], reorthogonalised,
    /// with the least-squares gradient, whose HVPs are exact on quadratics), and
    /// [`Hyper::line_curvature`] and [`Hyper::negative_curvature`] as given.
    pub fn method<T: Real>(self, h: &Hyper<T>) -> Method<T> {
        let samples = self.curvature == CurvatureSource::Samples;
        let regression = self.gradient == GradientMethod::Regression;
        Method::NewtonCg(NewtonCg {
            gradient: self.gradient,
            hvp: if samples {
                HvpMethod::ForwardDifference {
                    gradient: self.gradient,
                }
            } else {
                HvpMethod::Kernel
            },
            trust_radius: h.trust_radius,
            max_inner: if regression {
                REGRESSION_INNER_STEPS
            } else {
                h.inner_steps
            },
            inner_tolerance: T::from_f64(if regression {
                REGRESSION_INNER_TOLERANCE
            } else {
                INNER_TOLERANCE
            }),
            reuse_samples: samples,
            reorthogonalize: regression,
            negative_curvature: h.negative_curvature,
            compare_samples: self.compare,
            pair_curvature: samples,
            line_curvature: samples && h.line_curvature,
        })
    }

    /// The σ schedule for these hyper-parameters ([`Recipe::sigma`]).
    pub fn schedule<T: Real>(self, h: &Hyper<T>) -> Schedule<T> {
        match self.sigma {
            SigmaControl::Adaptive => Schedule::Adaptive {
                start: h.sigma_start,
                end: h.sigma_end,
                shrink: h.sigma_shrink,
            },
            SigmaControl::Linear => Schedule::Linear {
                start: h.sigma_start,
                end: h.sigma_end,
            },
        }
    }
}

impl fmt::Display for Recipe {
    /// `NewtonCG` and a `/token` for each choice that is not the default.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(NAME)?;
        if self.gradient != Recipe::DEFAULT.gradient
            && let Some((_, t)) = GRADIENTS.iter().find(|(g, _)| *g == self.gradient)
        {
            write!(f, "/{t}")?;
        }
        if self.curvature == CurvatureSource::Kernel {
            f.write_str("/kernel")?;
        }
        if self.sigma == SigmaControl::Linear {
            f.write_str("/linear")?;
        }
        if self.compare {
            f.write_str("/compare")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every combination prints as a text that parses back to it.
    #[test]
    fn every_recipe_round_trips_through_its_text() {
        let mut text = heapless::String::<64>::new();
        for (g, _) in GRADIENTS {
            for c in [CurvatureSource::Samples, CurvatureSource::Kernel] {
                for s in [SigmaControl::Adaptive, SigmaControl::Linear] {
                    for compare in [false, true] {
                        let r = Recipe {
                            gradient: g,
                            curvature: c,
                            sigma: s,
                            compare,
                        };
                        text.clear();
                        fmt::write(&mut text, format_args!("{r}")).unwrap();
                        assert_eq!(Recipe::parse(&text), Ok(r), "{text}");
                    }
                }
            }
        }
    }

    #[test]
    fn bad_texts_name_what_is_wrong() {
        let name = |t| match Recipe::parse(t) {
            Err(Error::InvalidSetting { name }) => name,
            other => panic!("{t}: {other:?}"),
        };
        assert_eq!(name("Newton"), "method");
        assert_eq!(name("NewtonCG/fr22/ls"), "gradient");
        assert_eq!(name("NewtonCG/linear/adaptive"), "sigma");
        assert_eq!(name("NewtonCG/fast"), "recipe");
        assert_eq!(name("NewtonCG/"), "recipe");
    }
}
