//! The optimisation methods the firmware runs: hodr-core's default optimiser Auto
//! (feature `auto`) and the paper's presets of those names.
//!
//! OurHVPA is built field by field rather than through hodr-core's `Preset`, because the
//! preset module needs the `hessian` feature, which the `ncg` firmware leaves out; a test
//! (with every feature) checks that both constructions agree.

use hodr_core::GradientMethod;
#[cfg(feature = "ncg")]
use hodr_core::HvpMethod;
use hodr_core::optim::{Adam, Method, Schedule};
#[cfg(feature = "ncg")]
use hodr_core::optim::{Curvature, Ncg, NegativeCurvature};

use crate::problem::Settings;

/// An optimiser with its estimators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algorithm {
    /// Adam + FR22 gradient (the paper's baseline).
    Fr22,
    /// NCG + aggregate gradient + central-difference HVP of aggregate gradients, drawn
    /// independently (the paper's OurHVPA).
    #[cfg(feature = "ncg")]
    OurHvpa,
    /// NCG + per-element gradient, line-search curvature from a full per-element Hessian
    /// estimate (the paper's OurH).
    #[cfg(feature = "hessian")]
    OurH,
    /// hodr-core's default optimiser ([`hodr_core::optim::Auto`]) with the problem's
    /// scale σ₀ (its `sigma_start`) and budget, nothing else.
    #[cfg(feature = "auto")]
    Auto,
}

impl Algorithm {
    /// Every compiled-in algorithm, in report order.
    pub const ALL: &'static [Algorithm] = &[
        Algorithm::Fr22,
        #[cfg(feature = "ncg")]
        Algorithm::OurHvpa,
        #[cfg(feature = "hessian")]
        Algorithm::OurH,
        #[cfg(feature = "auto")]
        Algorithm::Auto,
    ];

    /// Name in the report: hodr-core's preset name.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Fr22 => "FR22",
            #[cfg(feature = "ncg")]
            Algorithm::OurHvpa => "OurHVPA",
            #[cfg(feature = "hessian")]
            Algorithm::OurH => "OurH",
            #[cfg(feature = "auto")]
            Algorithm::Auto => "Auto",
        }
    }

    /// The optimiser settings of a preset for these hyper-parameters; `None` for Auto,
    /// which takes none.
    pub fn method(self, s: &Settings) -> Option<Method<f32>> {
        Some(match self {
            Algorithm::Fr22 => Method::Adam(Adam::new(GradientMethod::Fr22, s.learning_rate)),
            #[cfg(feature = "ncg")]
            Algorithm::OurHvpa => Method::Ncg(Ncg {
                gradient: GradientMethod::Aggregate,
                curvature: Curvature::Hvp(HvpMethod::CentralDifference {
                    gradient: GradientMethod::Aggregate,
                    draws: hodr_core::Draws::Independent,
                }),
                trust_radius: s.trust_radius,
                line_search_iterations: s.line_search_iterations,
                line_search_tolerance: s.line_search_tolerance,
                recompute: s.recompute,
                reuse_samples: false,
                negative_curvature: NegativeCurvature::Fallback,
            }),
            #[cfg(feature = "hessian")]
            Algorithm::OurH => hodr_core::optim::preset::Preset::OurH.method(&s.hyper()),
            #[cfg(feature = "auto")]
            Algorithm::Auto => return None,
        })
    }

    /// σ annealed linearly from `sigma_start` to `sigma_end` over the budget (every
    /// preset's schedule).
    pub fn schedule(self, s: &Settings) -> Schedule<f32> {
        Schedule::Linear {
            start: s.sigma_start,
            end: s.sigma_end,
        }
    }
}

#[cfg(all(test, feature = "hessian"))]
mod tests {
    use hodr_core::optim::preset::Preset;

    use super::*;
    use crate::problem::PROBLEMS;

    #[test]
    fn algorithms_are_the_presets_of_their_names() {
        for p in PROBLEMS {
            let h = p.settings.hyper();
            for &a in Algorithm::ALL {
                let Some(method) = a.method(&p.settings) else {
                    continue;
                };
                let preset = Preset::from_name(a.name()).expect("a preset name");
                assert_eq!(method, preset.method(&h), "{}", a.name());
                assert_eq!(a.schedule(&p.settings), preset.schedule(&h));
            }
        }
    }
}
