//! Least-squares ("regression") gradients from Gaussian samples.
//!
//! With t ~ N(0, I) and the antithetic differences yₖ = (f(θ + σtₖ) − f(θ − σtₖ))/(2σ),
//! the plain Gaussian estimator is (1/P) Σ tₖyₖ. Its error has a part that is linear in
//! the sample moments: for a linear f, yₖ = tₖᵀg exactly and the estimate is M g with
//! M = (1/P) Σ tₖtₖᵀ, which is I only on average. Fitting y by a linear model instead,
//!
//! ĝ = (Σ tₖtₖᵀ)⁻¹ Σ tₖyₖ,
//!
//! removes that part: ĝ is exact (zero variance) when f is quadratic within reach of the
//! samples — antithetic pairs cancel the even terms — and, since M → I, it converges to
//! the smoothed gradient ∇f̄ as P grows, like the Gaussian estimator; for finite P it is
//! a ratio estimator, biased by O(1/P). Equivalently it is the Gaussian estimator with
//! the known E(ttᵀ) = I used as a control variate.
//!
//! Costs beyond the Gaussian estimator: O(n²) per sample for Σttᵀ and one O(n³/6)
//! Cholesky solve per estimate, in the workspace's moment region. It draws
//! max(P, 2n + 2) pairs: E[(Σttᵀ)⁻¹] is finite only from n + 2 samples on, and with
//! about twice as many samples as unknowns the fit amplifies the noise that is not
//! linear in t by P/(P − n − 1) ≈ 2 at most, in mean.
//!
//! With a central-difference HVP under common random numbers, the same regression is
//! applied to the differenced values, so on a quadratic Ĥv = ∇²f̄·v exactly.

use rand_core::Rng;

use super::driver::{Pair, Scheme};
use crate::cholesky::{factor_in_place, solve};
use crate::error::Error;
use crate::real::Real;
use crate::sample::place;

/// Pairs drawn in dimension `n` when the caller asks for `pairs`: max(P, 2n + 2).
pub(super) fn pairs(n: usize, pairs: usize) -> usize {
    pairs.max(2 * n + 2)
}

/// Accumulates Σ tₖ(−oddₖ) and the lower triangle of Σ tₖtₖᵀ.
pub(super) struct Gradient<'o, T> {
    n: usize,
    /// P as the caller scales the sum (it divides by σP).
    pairs: usize,
    /// Pairs drawn, [`pairs`]`(n, P)`.
    drawn: usize,
    sum: &'o mut [T],
    moments: &'o mut [T],
}

impl<'o, T: Real> Gradient<'o, T> {
    /// `region` is the workspace's moment region (at least n² + n floats); zeroed here.
    pub(super) fn new(n: usize, pairs: usize, region: &'o mut [T]) -> Self {
        let (moments, rest) = region.split_at_mut(n * n);
        let sum = &mut rest[..n];
        moments.fill(T::ZERO);
        sum.fill(T::ZERO);
        Gradient {
            n,
            pairs,
            drawn: self::pairs(n, pairs),
            sum,
            moments,
        }
    }

    /// Adds `sign`·P·(Σttᵀ)⁻¹ Σ t(−odd) to `acc`: the fitted gradient times σP, the scale
    /// of the other gradient sums (the caller divides by σP, P the pairs it asked for).
    ///
    /// # Errors
    /// [`Error::NonFiniteEstimate`] if Σttᵀ is not numerically positive definite.
    pub(super) fn finish(self, sign: T, acc: &mut [T]) -> Result<(), Error> {
        if !factor_in_place(self.moments, self.n, T::ZERO) {
            return Err(Error::NonFiniteEstimate { index: 0 });
        }
        solve(self.moments, self.n, self.sum);
        let scale = sign * T::from_usize(self.pairs);
        for (a, &s) in acc.iter_mut().zip(self.sum.iter()) {
            *a += scale * s;
        }
        Ok(())
    }
}

impl<T: Real> Scheme<T> for Gradient<'_, T> {
    fn groups(&self) -> usize {
        self.drawn
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gaussian(rng, t);
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        let n = self.n;
        for (i, &ti) in t.iter().enumerate() {
            self.sum[i] -= ti * pair.odd;
            let row = &mut self.moments[i * n..i * n + i + 1];
            for (m, &tj) in row.iter_mut().zip(t) {
                *m += ti * tj;
            }
        }
    }
}
