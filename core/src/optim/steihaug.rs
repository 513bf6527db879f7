//! Newton-CG with a Steihaug trust region (beyond the paper).
//!
//! Each iteration estimates ĝ, then runs conjugate gradient on Ĥp = −ĝ with one HVP per
//! inner step, starting from p = 0 (Steihaug 1983): it stops at the trust boundary
//! ‖p‖ = Δ·σ, when the residual has fallen to `inner_tolerance`·‖ĝ‖, after `max_inner`
//! steps, or at non-positive curvature dᵀĤd ≤ 0. The first inner step is a
//! curvature-scaled steepest-descent (Cauchy) step.
//!
//! Where the gradient's samples (and f(θ), when known) all lie within
//! [`PLATEAU_MARGIN`] of each other the iteration has seen a plateau at this σ: its
//! estimates hold nothing but the objective's rounding (a shape drawn at sub-pixel
//! offsets on a pixel grid), so it takes no step and estimates no curvature, and the adaptive
//! schedule widens σ. Samples that tie above a lower f(θ) are no plateau: θ sits in a
//! basin narrower than σ, and with [`NewtonCg::pair_curvature`] the iteration reports a
//! model minimum at θ, so that σ shrinks.
//!
//! Noise changes one classical choice: Steihaug steps to the boundary along d at
//! negative curvature, but estimated curvature turns negative under noise far more
//! often than the smoothed loss does. Here, negative curvature after the first inner
//! step keeps the CG iterate reached so far; at the first inner step it takes the
//! gradient-descent-like step −ĝ/κ̄, κ̄ the running mean of the positive curvatures this
//! run has measured (one σ along −ĝ before any is known), capped at Δ·σ. With
//! [`NegativeCurvature::TwoSided`] the step so kept (the CG iterate p, or the
//! gradient-like step) competes with the two points where the line p + τd meets the
//! boundary, τ > 0 and τ < 0, and the objective picks the lowest of the three. The radius
//! follows σ rather than an actual-versus-predicted ratio test, since the loss itself is
//! only known up to noise.

use rand_core::Rng;

use super::oracle::Oracle;
use super::vector::{axpy, dot, norm, to_boundary};
use super::{NegativeCurvature, Outcome, check_positive};
use crate::error::Error;
use crate::estimate::{GradientMethod, HvpMethod};
use crate::objective::Objective;
use crate::real::Real;

/// The relative margin of [`NewtonCg::compare_samples`]: a value wins a comparison only
/// when it is lower by more than this × the larger magnitude of the two; smaller
/// differences are ties, which go to the model step. The comparison is there to catch
/// the model's gross failures, not to polish its steps: objectives that render a
/// smooth shape on a pixel grid differ by small amounts between positions that the
/// task cannot tell apart, and a margin of √ε let those differences reject model steps
/// until σ collapsed on a plateau (docs/notes/2026-11-23-benchmarks-before-auto.md).
pub const COMPARISON_MARGIN: f64 = 1e-3;

/// The relative spread below which an iteration's samples are a plateau (Newton-CG takes
/// no step; [`COMPARISON_MARGIN`]'s scale, the larger magnitude of the two values):
/// a rasterised shape's loss at plateau points far apart differs only by its pixel
/// sums at sub-pixel offsets, a small fraction of its value. The margin is relative to |f|: an
/// objective whose values near its minimum differ by less than this fraction of their
/// size (a large constant offset, f = 100 + x²) stops where they do — subtract the
/// offset.
pub const PLATEAU_MARGIN: f64 = 1e-4;

/// Newton-CG (Steihaug) with HVPs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonCg<T> {
    /// The gradient estimator.
    pub gradient: GradientMethod,
    /// The HVP estimator.
    pub hvp: HvpMethod,
    /// Δ: steps are at most Δ·σ long.
    pub trust_radius: T,
    /// Inner CG steps per iteration (≥ 1; each one HVP), capped at 2n (exact CG ends
    /// within n steps; the rest allows for rounding). Presets with fresh noisy HVPs use
    /// 3: longer inner runs lose conjugacy and wander to the boundary.
    pub max_inner: usize,
    /// Inner CG stops when ‖r‖ ≤ this × ‖ĝ‖. Default in presets: 0.1.
    pub inner_tolerance: T,
    /// Reuse one sample set for every estimate of an iteration (gradient, HVPs, line
    /// search): the RNG is rewound to its state at the iteration's start before each
    /// estimate, so all of them see the same offsets and noise seeds. The iteration then
    /// works on one fixed sample-average approximation of f̄: with central- or
    /// forward-difference HVPs of the same gradient estimator, Ĥv = M·∇²f̄·v and
    /// ĝ = M·∇f̄ share the random matrix M, which cancels from the Newton step on
    /// quadratics; a forward difference then reuses ĝ(θ) itself
    /// ([`HvpMethod::ForwardDifference`]). Fresh samples come with each new iteration.
    pub reuse_samples: bool,
    /// Keep the inner residuals mutually orthogonal, as they are in exact arithmetic:
    /// each new residual is Gram–Schmidt-orthogonalised against normalised copies of the
    /// earlier ones. Finite-precision CG loses this on ill-conditioned systems and then
    /// needs many times n steps (an ill-conditioned quadratic, κ = 1e8 at n = 50). Worth
    /// it
    /// only when the HVPs are exact enough to resolve that accuracy (least-squares
    /// estimates with reused samples). Costs n·min(max_inner + 1, n) buffer floats and
    /// O(jn) per inner step j.
    pub reorthogonalize: bool,
    /// The step where dᵀĤd ≤ 0. Presets: [`NegativeCurvature::Fallback`].
    pub negative_curvature: NegativeCurvature,
    /// End each iteration with a comparison on f itself: the current θ, the model step
    /// θ + p, and the lowest sample the iteration's estimates evaluated, θ and θ + p at
    /// that sample's noise seed (2 evaluations); θ moves to the lowest (ties: θ + p,
    /// then θ). A rejected model step shrinks σ under [`super::Schedule::Adaptive`]
    /// ([`super::StepKind::Rejected`]).
    ///
    /// The estimates evaluate f at points ≈ σ from θ anyway; this keeps what they found.
    /// From a plateau the first sample that sees the target's basin is taken at once
    /// rather than averaged into a gradient, and where f̄_σ's minimum is not f's (a
    /// narrow well beside a wide plateau or wall, which the kernel averages away), the
    /// model's step out of the well is refused and σ shrinks until the model agrees.
    /// Costs n buffer floats, which keep the lowest sample's point.
    pub compare_samples: bool,
    /// Where the iteration's gradient came from one antithetic pair θ ± σt and lies
    /// along t ([`GradientMethod::along_offset`]) in n ≥ 2 dimensions, the first inner
    /// step's curvature along t is the pair's second difference
    /// (f(θ + σt) + f(θ − σt) − 2f(θ))/(σ‖t‖)² instead of an HVP: f(θ) is the value
    /// remembered for a deterministic objective (no evaluation) or f at θ with the
    /// pair's noise seed (one evaluation, which [`NewtonCg::compare_samples`] then
    /// reuses), where the HVP costs a gradient estimate (two). The pair's samples see f along t only,
    /// so the curvature along t is all an estimate from them can hold; the difference is
    /// the mean curvature of f over [θ − σt, θ + σt], as the forward-difference HVP is
    /// that of f̄ over [θ, θ + εu]. In one dimension the HVP stays: it finds a narrow
    /// well beside a wall more often.
    pub pair_curvature: bool,
    /// Where [`NewtonCg::pair_curvature`] does not apply, the first inner step's
    /// curvature along ĝ is the second difference of f on the line θ ± σ√n·ĝ/‖ĝ‖
    /// (`Oracle::line_curvature`: 2 evaluations, 3 where f(θ) is not known), instead of
    /// an HVP (one gradient estimate, 2P evaluations for P pairs): the step is the
    /// minimum of the parabola through the three values, capped by the trust radius.
    /// σ√n is how far an estimator's sample θ + σt sits from θ. Where the line does
    /// not fall along −ĝ the fallback step is taken. Worth it where pairs are many and
    /// the landscape along a line shows the kernel's; with few pairs on a plateau the
    /// kernel's curvature is worth its cost (docs/notes/2026-11-23-benchmarks-before-auto.md, "BOX10: curvature from a line").
    pub line_curvature: bool,
}

impl<T: Real> NewtonCg<T> {
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_positive(self.trust_radius, "trust_radius")?;
        if self.max_inner == 0 {
            return Err(Error::InvalidSetting { name: "max_inner" });
        }
        if !(self.inner_tolerance.is_finite() && self.inner_tolerance >= T::ZERO) {
            return Err(Error::InvalidSetting {
                name: "inner_tolerance",
            });
        }
        Ok(())
    }

    /// Buffer floats needed: ĝ, p, r, d, Ĥd, and the orthonormal residual basis.
    pub(crate) fn buffer_len(&self, n: usize) -> usize {
        5 * n + n * self.basis_capacity(n)
    }

    /// Residuals kept for reorthogonalisation: at most n can be orthogonal and nonzero.
    fn basis_capacity(&self, n: usize) -> usize {
        if self.reorthogonalize {
            (self.max_inner + 1).min(n)
        } else {
            0
        }
    }

    pub(crate) fn step<R: Rng + Clone, O: Objective<T> + ?Sized>(
        &self,
        oracle: &mut Oracle<'_, '_, T, R, O>,
        theta: &mut [T],
        buf: &mut [T],
        mean_curvature: &mut Option<T>,
        tolerance: Option<T>,
    ) -> Result<Outcome<T>, Error> {
        let n = theta.len();
        let (g, rest) = buf.split_at_mut(n);
        let (p, rest) = rest.split_at_mut(n);
        let (r, rest) = rest.split_at_mut(n);
        let (d, rest) = rest.split_at_mut(n);
        let (hd, rest) = rest.split_at_mut(n);
        let basis = &mut rest[..n * self.basis_capacity(n)];
        let mut basis_len = 0;

        let estimate = oracle.gradient(self.gradient, theta, g)?;
        let gradient_norm = norm(g);
        if let Some(done) = Outcome::converged(gradient_norm, tolerance) {
            return Ok(done);
        }
        let mut outcome = Outcome {
            gradient_norm,
            ..Outcome::default()
        };
        // Nothing seen (samples and any known f(θ) all tie): no step, no curvature to
        // estimate.
        if !gradient_norm.is_finite() || oracle.flat() {
            return Ok(outcome);
        }
        let pair = if self.pair_curvature {
            oracle.pair_curvature(self.gradient, &estimate, theta, g)?
        } else {
            None
        };
        if gradient_norm == T::ZERO {
            // A vanishing gradient is a model minimum at θ where the pair's curvature is
            // positive (both samples above f(θ) by the same amount: the basin lies
            // within σ), else nothing seen.
            outcome.curvature = pair;
            return Ok(outcome);
        }
        let first = match pair {
            None if self.line_curvature => Some(oracle.line_curvature(theta, g)?),
            first => first,
        };
        let radius = self.trust_radius * oracle.sigma();
        p.fill(T::ZERO);
        r.copy_from_slice(g);
        for (di, &gi) in d.iter_mut().zip(g.iter()) {
            *di = -gi;
        }
        let mut rr = dot(r, r);
        keep(basis, &mut basis_len, r, rr);
        for j in 0..self.max_inner.min(2 * n) {
            match (j, first) {
                // d = −ĝ lies along the pair's offset or the line.
                (0, Some(c)) => {
                    for (h, &di) in hd.iter_mut().zip(d.iter()) {
                        *h = c * di;
                    }
                }
                _ => oracle.hvp(self.hvp, theta, (self.gradient, g), d, hd)?,
            }
            let kappa = dot(d, hd);
            let dd = dot(d, d);
            outcome.curvature = Some(kappa / dd);
            if !(kappa > T::ZERO && kappa.is_finite()) {
                outcome.fallback = true;
                // The kept step is p + τ₀d: p itself after the first inner step; at the
                // first (p = 0, d = −ĝ) a gradient step of the length the data can justify.
                let kept = if j == 0 {
                    let length = match *mean_curvature {
                        Some(k) => gradient_norm / k,
                        None => oracle.sigma(),
                    };
                    length.min(radius) / gradient_norm
                } else {
                    T::ZERO
                };
                let tau = if self.negative_curvature == NegativeCurvature::TwoSided {
                    // ‖p + τd‖ = Δ has one root of each sign (‖p‖ < Δ); their product
                    // is (‖p‖² − Δ²)/‖d‖².
                    let ahead = to_boundary(p, d, radius);
                    let behind = if ahead > T::ZERO {
                        (dot(p, p) - radius.sq()) / (dd * ahead)
                    } else {
                        T::ZERO
                    };
                    let candidates = [kept, ahead, behind];
                    let (origin, p): (&[T], &[T]) = (theta, p);
                    let best = oracle.lowest::<3>(|k, x| {
                        for (((xi, &o), &pi), &di) in x.iter_mut().zip(origin).zip(p).zip(d.iter())
                        {
                            *xi = o + pi + candidates[k] * di;
                        }
                    })?;
                    candidates[best]
                } else {
                    kept
                };
                axpy(tau, d, p);
                break;
            }
            let rayleigh = kappa / dd;
            *mean_curvature = Some(match *mean_curvature {
                Some(m) => T::HALF * (m + rayleigh),
                None => rayleigh,
            });
            let alpha = rr / kappa;
            // Would p + αd leave the trust region?
            let pd = dot(p, d);
            let pp = dot(p, p);
            if pp + T::TWO * alpha * pd + alpha.sq() * dd >= radius.sq() {
                let tau = to_boundary(p, d, radius);
                axpy(tau, d, p);
                outcome.at_boundary = true;
                break;
            }
            axpy(alpha, d, p);
            axpy(alpha, hd, r);
            for q in basis[..basis_len * n].chunks_exact(n) {
                axpy(-dot(q, r), q, r);
            }
            let rr_new = dot(r, r);
            keep(basis, &mut basis_len, r, rr_new);
            if rr_new.sqrt() <= self.inner_tolerance * gradient_norm {
                break;
            }
            let beta = rr_new / rr;
            for (di, &ri) in d.iter_mut().zip(r.iter()) {
                *di = -ri + beta * *di;
            }
            rr = rr_new;
        }
        if self.compare_samples {
            (outcome.verdict, outcome.step_length) = oracle.settle(theta, p)?;
        } else {
            axpy(T::ONE, p, theta);
            outcome.step_length = norm(p);
        }
        Ok(outcome)
    }
}

/// Appends r/‖r‖ (`rr` = ‖r‖²) to the first `len` vectors of `basis`, if there is room
/// and r ≠ 0.
fn keep<T: Real>(basis: &mut [T], len: &mut usize, r: &[T], rr: T) {
    let n = r.len();
    if (*len + 1) * n > basis.len() || !(rr > T::ZERO && rr.is_finite()) {
        return;
    }
    let scale = T::ONE / rr.sqrt();
    for (q, &ri) in basis[*len * n..(*len + 1) * n].iter_mut().zip(r) {
        *q = scale * ri;
    }
    *len += 1;
}
