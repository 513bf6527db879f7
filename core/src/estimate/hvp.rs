//! Hessian-vector products as differences of gradient estimates (docs/design.md §1.5), u = v/‖v‖,
//! ε = σ/3, each g a gradient estimate with P pairs:
//!
//! * central: Hv ≈ (g(θ + εu) − g(θ − εu)) / (2ε) · ‖v‖;
//! * forward: Hv ≈ (g(θ + εu) − g(θ)) / ε · ‖v‖, always with common random numbers.
//!
//! With [`Draws::Common`] both gradients use the same offsets and noise seeds — one
//! scheme run over the two centres, whose antithetic combinations are differenced per
//! sample — so what they share cancels. With [`Draws::Independent`] (the reference
//! code's choice) they are two separate runs. A forward difference given g(θ) from the
//! same draws ([`Stencil::Forward`]) evaluates only around θ + εu.

use rand_core::Rng;

use super::{
    Draws, Estimator, GradientMethod, HVP_STEP_RATIO, Report, check_len, check_vector, report,
    scale_checked,
};
use crate::error::Error;
use crate::objective::Objective;
use crate::real::Real;
use crate::workspace::Workspace;

/// Which two gradients are differenced.
#[derive(Clone, Copy)]
pub(super) enum Stencil<'g, T> {
    /// g(θ + εu) − g(θ − εu), over 2ε.
    Central(Draws),
    /// g(θ + εu) − g(θ), over ε, with common random numbers; g(θ) given (estimated by
    /// the same method from the draws the stream repeats) or estimated here.
    Forward(Option<&'g [T]>),
}

/// Hv by `stencil` from gradient estimates of `gradient` (docs/design.md §1.5).
#[allow(clippy::too_many_arguments)]
pub(super) fn difference<T: Real, R: Rng, O: Objective<T> + ?Sized>(
    estimator: &mut Estimator<T, R>,
    gradient: GradientMethod,
    stencil: Stencil<'_, T>,
    objective: &mut O,
    theta: &[T],
    v: &[T],
    ws: &mut Workspace<'_, T>,
    hv: &mut [T],
) -> Result<Report<T>, Error> {
    let n = ws.dim;
    check_vector(n, theta)?;
    check_vector(n, v)?;
    check_len(n, hv.len())?;
    if let Stencil::Forward(Some(base)) = stencil {
        check_vector(n, base)?;
    }
    ws.batch.begin();
    hv.fill(T::ZERO);
    let (big, scaled) = norm2(v);
    if big == T::ZERO {
        return Ok(report(&ws.batch, 0, None, false));
    }
    let norm = big * scaled;
    let sigma = estimator.sigma();
    let eps = T::from_f64(HVP_STEP_RATIO) * sigma;

    // θ ± εu into scratch; the workspace's batch is borrowed separately below.
    let scratch = core::mem::take(&mut ws.scratch);
    let (plus, rest) = scratch.split_at_mut(n);
    let minus = &mut rest[..n];
    // The unit direction v/‖v‖ as (v/max|vᵢ|)/(‖v‖/max|vᵢ|): finite for a subnormal v,
    // whose ‖v‖ would turn ε/‖v‖ infinite.
    for (((p, m), &x), &d) in plus.iter_mut().zip(minus.iter_mut()).zip(theta).zip(v) {
        let step = eps * (d / big / scaled);
        *p = x + step;
        *m = x - step;
    }
    let (plus, minus): (&[T], &[T]) = (plus, minus);
    let mut sum = |centres: &[&[T]], sign, ws: &mut Workspace<'_, T>, hv: &mut [T], first| {
        estimator.gradient_sum(gradient, objective, centres, sign, ws, hv, first)
    };
    let result = match stencil {
        Stencil::Central(Draws::Common) => sum(&[plus, minus], T::ONE, ws, hv, 0),
        Stencil::Central(Draws::Independent) => sum(&[plus], T::ONE, ws, hv, 0)
            .and_then(|first| sum(&[minus], -T::ONE, ws, hv, first).map(|second| first + second)),
        Stencil::Forward(Some(_)) => sum(&[plus], T::ONE, ws, hv, 0),
        Stencil::Forward(None) => sum(&[plus, theta], T::ONE, ws, hv, 0),
    };
    ws.scratch = scratch;
    let evaluations = result?;
    // S/(σP) is a gradient (difference); over the stencil's width, times ‖v‖.
    let pairs = T::from_usize(estimator.pairs());
    match stencil {
        Stencil::Central(_) => scale_checked(hv, norm / (T::TWO * eps * sigma * pairs))?,
        Stencil::Forward(None) => scale_checked(hv, norm / (eps * sigma * pairs))?,
        Stencil::Forward(Some(base)) => {
            let to_gradient = T::ONE / (sigma * pairs);
            for (h, &g) in hv.iter_mut().zip(base) {
                *h = *h * to_gradient - g;
            }
            scale_checked(hv, norm / eps)?;
        }
    }
    Ok(report(&ws.batch, evaluations, None, false))
}

/// ‖v‖₂ as (max |vᵢ|, ‖v‖/max |vᵢ|), whose product is ‖v‖ and whose parts neither
/// overflow nor underflow; (0, 0) for v = 0.
fn norm2<T: Real>(v: &[T]) -> (T, T) {
    let big = v.iter().fold(T::ZERO, |m, &x| m.max(x.abs()));
    if big == T::ZERO {
        return (T::ZERO, T::ZERO);
    }
    let sum = v.iter().fold(T::ZERO, |s, &x| s + (x / big).sq());
    (big, sum.sqrt())
}
