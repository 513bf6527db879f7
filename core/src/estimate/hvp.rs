//! Hessian-vector products as differences of gradient estimates (DESIGN §1.5), u = v/‖v‖,
//! ε = σ/3, each g a gradient estimate with P pairs:
//!
//! * central: Hv ≈ (g(θ + εu) − g(θ − εu)) / (2ε) · ‖v‖;
//! * forward: Hv ≈ (g(θ + εu) − g(θ)) / ε · ‖v‖, always with common random numbers.
//!
//! With [`Draws::Common`] both gradients use the same offsets and noise seeds — one
//! scheme run over the two centres, whose antithetic combinations are differenced per
//! sample — so what they share cancels. With [`Draws::Independent`] (the reference
//! code's choice) they are two separate runs. A forward difference given g(θ) from the
//! same draws ([`forward_difference`]'s `base`) evaluates only around θ + εu.

use rand_core::Rng;

use super::{
    Draws, Estimator, GradientMethod, HVP_STEP_RATIO, Report, check_len, check_vector,
    scale_checked,
};
use crate::error::Error;
use crate::objective::Objective;
use crate::real::Real;
use crate::workspace::Workspace;

#[allow(clippy::too_many_arguments)]
pub(super) fn central_difference<T: Real, R: Rng, O: Objective<T> + ?Sized>(
    estimator: &mut Estimator<T, R>,
    gradient: GradientMethod,
    draws: Draws,
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
    ws.batch.begin();
    hv.fill(T::ZERO);
    let norm = norm2(v);
    if norm == T::ZERO {
        return Ok(Report {
            evaluations: 0,
            centre_value: None,
            mean_value: None,
        });
    }
    let sigma = estimator.sigma();
    let eps = T::from_f64(HVP_STEP_RATIO) * sigma;

    // θ ± εu into scratch; the workspace's batch is borrowed separately below.
    let scratch = core::mem::take(&mut ws.scratch);
    let (plus, rest) = scratch.split_at_mut(n);
    let minus = &mut rest[..n];
    let step = eps / norm;
    for (((p, m), &x), &d) in plus.iter_mut().zip(minus.iter_mut()).zip(theta).zip(v) {
        *p = x + step * d;
        *m = x - step * d;
    }
    let result = match draws {
        Draws::Common => {
            estimator.gradient_sum(gradient, objective, &[&*plus, &*minus], T::ONE, ws, hv, 0)
        }
        Draws::Independent => estimator
            .gradient_sum(gradient, objective, &[&*plus], T::ONE, ws, hv, 0)
            .and_then(|first| {
                estimator
                    .gradient_sum(gradient, objective, &[&*minus], -T::ONE, ws, hv, first)
                    .map(|second| first + second)
            }),
    };
    ws.scratch = scratch;
    let evaluations = result?;
    // (S₊ − S₋)/(σP) is the gradient difference; divide by 2ε, multiply by ‖v‖.
    let pairs = T::from_usize(estimator.pairs());
    scale_checked(hv, norm / (T::TWO * eps * sigma * pairs))?;
    Ok(Report {
        evaluations,
        centre_value: None,
        mean_value: ws.batch.mean_value(),
    })
}

/// The forward difference (g(θ + εu) − g(θ))/ε·‖v‖ with common random numbers. With
/// `base` = g(θ), estimated by `gradient` from the draws the estimator's stream is about
/// to repeat, only g(θ + εu) is estimated (half the evaluations); without, both are.
#[allow(clippy::too_many_arguments)]
pub(super) fn forward_difference<T: Real, R: Rng, O: Objective<T> + ?Sized>(
    estimator: &mut Estimator<T, R>,
    gradient: GradientMethod,
    objective: &mut O,
    theta: &[T],
    v: &[T],
    base: Option<&[T]>,
    ws: &mut Workspace<'_, T>,
    hv: &mut [T],
) -> Result<Report<T>, Error> {
    let n = ws.dim;
    check_vector(n, theta)?;
    check_vector(n, v)?;
    check_len(n, hv.len())?;
    if let Some(b) = base {
        check_vector(n, b)?;
    }
    ws.batch.begin();
    hv.fill(T::ZERO);
    let norm = norm2(v);
    if norm == T::ZERO {
        return Ok(Report {
            evaluations: 0,
            centre_value: None,
            mean_value: None,
        });
    }
    let sigma = estimator.sigma();
    let eps = T::from_f64(HVP_STEP_RATIO) * sigma;
    let scratch = core::mem::take(&mut ws.scratch);
    let plus = &mut scratch[..n];
    let step = eps / norm;
    for ((p, &x), &d) in plus.iter_mut().zip(theta).zip(v) {
        *p = x + step * d;
    }
    let result = match base {
        Some(_) => estimator.gradient_sum(gradient, objective, &[&*plus], T::ONE, ws, hv, 0),
        None => estimator.gradient_sum(gradient, objective, &[&*plus, theta], T::ONE, ws, hv, 0),
    };
    ws.scratch = scratch;
    let evaluations = result?;
    let pairs = T::from_usize(estimator.pairs());
    match base {
        // S₊/(σP) − g(θ), over ε, times ‖v‖.
        Some(b) => {
            let to_gradient = T::ONE / (sigma * pairs);
            for (h, &g) in hv.iter_mut().zip(b) {
                *h = *h * to_gradient - g;
            }
            scale_checked(hv, norm / eps)?;
        }
        // (S₊ − S₀)/(σP), over ε, times ‖v‖.
        None => scale_checked(hv, norm / (eps * sigma * pairs))?,
    }
    Ok(Report {
        evaluations,
        centre_value: None,
        mean_value: ws.batch.mean_value(),
    })
}

/// ‖v‖₂ without overflow or underflow: scaled by max |vᵢ|.
fn norm2<T: Real>(v: &[T]) -> T {
    let big = v.iter().fold(T::ZERO, |m, &x| m.max(x.abs()));
    if big == T::ZERO {
        return T::ZERO;
    }
    let sum = v.iter().fold(T::ZERO, |s, &x| s + (x / big).sq());
    big * sum.sqrt()
}
