//! The black box being smoothed: θ ↦ f(θ).
//!
//! An [`Objective`] evaluates one point, or a [`Batch`] of points so that a host can
//! spread the evaluations over threads. Each evaluation carries a [`NoiseSeed`]: a
//! stochastic objective (a Monte Carlo renderer) derives all of its randomness from it,
//! and the estimators give both halves of an antithetic pair (and, for common random
//! numbers, both central-difference gradients) the same seed, so renderer noise cancels
//! in their difference instead of adding to it.

use crate::real::Real;

/// Seed for an objective's own randomness. Equal seeds must give equal noise.
pub type NoiseSeed = u64;

/// A function to smooth and differentiate.
///
/// Implemented for every closure `FnMut(&[T]) -> T` (which ignores the seed) and for
/// [`Seeded`] closures `FnMut(&[T], NoiseSeed) -> T`.
///
/// Returning NaN or ±∞ is allowed; the estimators stop with
/// [`crate::Error::NonFiniteObjective`] and keep the point.
pub trait Objective<T: Real> {
    /// f(θ), with renderer noise drawn from `seed`. `theta.len()` is the dimension n.
    fn evaluate(&mut self, theta: &[T], seed: NoiseSeed) -> T;

    /// f at every point of `batch`, written to `out` (`out.len() == batch.len()`).
    ///
    /// The default evaluates the points in order. Override it to evaluate in parallel;
    /// results must not depend on how the work is split.
    fn evaluate_batch(&mut self, batch: &Batch<'_, T>, out: &mut [T]) {
        for (k, value) in out.iter_mut().enumerate() {
            *value = self.evaluate(batch.point(k), batch.seed(k));
        }
    }

    /// True when f(θ) depends on θ alone — the seed is ignored and every evaluation of
    /// a point gives the same value — so an optimiser may remember values instead of
    /// evaluating a point again. Default: `false`.
    fn deterministic(&self) -> bool {
        false
    }

    /// Asked after every batch: `true` stops the work in progress with
    /// [`crate::Error::Cancelled`] (an interrupt, a deadline), so a long estimate ends
    /// within one batch instead of one iteration. Default: `false`.
    fn cancelled(&mut self) -> bool {
        false
    }
}

/// A plain closure cannot see the seed and is taken to be a function of θ alone:
/// wrap one with randomness of its own in [`Seeded`].
impl<T: Real, F: FnMut(&[T]) -> T> Objective<T> for F {
    #[inline]
    fn evaluate(&mut self, theta: &[T], _seed: NoiseSeed) -> T {
        self(theta)
    }

    fn deterministic(&self) -> bool {
        true
    }
}

/// Adapts a closure that takes the noise seed: `Seeded(|theta, seed| render(theta, seed))`.
#[derive(Clone, Copy, Debug)]
pub struct Seeded<F>(pub F);

impl<T: Real, F: FnMut(&[T], NoiseSeed) -> T> Objective<T> for Seeded<F> {
    #[inline]
    fn evaluate(&mut self, theta: &[T], seed: NoiseSeed) -> T {
        (self.0)(theta, seed)
    }
}

/// Points to evaluate: `len()` rows of `dim()` coordinates, each with a noise seed.
#[derive(Clone, Copy, Debug)]
pub struct Batch<'a, T> {
    points: &'a [T],
    seeds: &'a [NoiseSeed],
    dim: usize,
}

impl<'a, T: Real> Batch<'a, T> {
    /// A batch over row-major `points` (`seeds.len()` rows of `dim` coordinates).
    ///
    /// # Errors
    /// [`crate::Error::DimensionMismatch`] when `points.len() != seeds.len() * dim`.
    pub fn new(points: &'a [T], seeds: &'a [NoiseSeed], dim: usize) -> Result<Self, crate::Error> {
        if points.len() != seeds.len() * dim {
            return Err(crate::Error::DimensionMismatch {
                expected: seeds.len() * dim,
                found: points.len(),
            });
        }
        Ok(Batch { points, seeds, dim })
    }

    /// Number of points.
    #[inline]
    pub fn len(&self) -> usize {
        self.seeds.len()
    }

    /// True when there are no points.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.seeds.is_empty()
    }

    /// Coordinates per point, n.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Point `k` (panics if `k >= len()`, like slice indexing).
    #[inline]
    pub fn point(&self, k: usize) -> &'a [T] {
        &self.points[k * self.dim..(k + 1) * self.dim]
    }

    /// The noise seed of point `k`.
    #[inline]
    pub fn seed(&self, k: usize) -> NoiseSeed {
        self.seeds[k]
    }

    /// All points, row-major.
    #[inline]
    pub fn points(&self) -> &'a [T] {
        self.points
    }

    /// All seeds.
    #[inline]
    pub fn seeds(&self) -> &'a [NoiseSeed] {
        self.seeds
    }
}
