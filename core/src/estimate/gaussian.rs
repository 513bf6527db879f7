//! Plain Gaussian ("Stein") estimators with shared samples (docs/design.md §1.4).
//!
//! t ~ N(0, I) and the kernels divided by N are the weights:
//! gradient −tₑ (×1/σ), Hessian tᵢtⱼ − δᵢⱼ (×1/σ²), HVP tᵢ(t·v) − vᵢ (×1/σ²).
//! One sample set serves the gradient, the Hessian and any HVP at once.

use rand_core::Rng;

use super::driver::{Pair, Scheme};
use crate::real::Real;
use crate::sample::place;

#[cfg(feature = "gaussian")]
pub(super) struct Gradient<'o, T> {
    pairs: usize,
    sign: T,
    out: &'o mut [T],
}

#[cfg(feature = "gaussian")]
impl<'o, T: Real> Gradient<'o, T> {
    pub(super) fn new(pairs: usize, sign: T, out: &'o mut [T]) -> Self {
        Gradient { pairs, sign, out }
    }
}

#[cfg(feature = "gaussian")]
impl<T: Real> Scheme<T> for Gradient<'_, T> {
    fn groups(&self) -> usize {
        self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gaussian(rng, t);
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        let w = self.sign * pair.odd;
        for (g, &te) in self.out.iter_mut().zip(t) {
            *g -= te * w;
        }
    }
}

#[cfg(feature = "hessian")]
pub(super) struct Hessian<'o, T> {
    n: usize,
    pairs: usize,
    out: &'o mut [T],
}

#[cfg(feature = "hessian")]
impl<'o, T: Real> Hessian<'o, T> {
    pub(super) fn new(n: usize, pairs: usize, out: &'o mut [T]) -> Self {
        Hessian { n, pairs, out }
    }
}

#[cfg(feature = "hessian")]
impl<T: Real> Scheme<T> for Hessian<'_, T> {
    fn groups(&self) -> usize {
        self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gaussian(rng, t);
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        super::add_rank_one(self.out, self.n, t, pair.even);
    }
}

/// Gradient and HVP from the same samples.
#[cfg(all(feature = "hvp", feature = "gaussian"))]
pub(super) struct Hvp<'o, T> {
    pairs: usize,
    v: &'o [T],
    grad: &'o mut [T],
    hv: &'o mut [T],
}

#[cfg(all(feature = "hvp", feature = "gaussian"))]
impl<'o, T: Real> Hvp<'o, T> {
    pub(super) fn new(pairs: usize, v: &'o [T], grad: &'o mut [T], hv: &'o mut [T]) -> Self {
        Hvp { pairs, v, grad, hv }
    }
}

#[cfg(all(feature = "hvp", feature = "gaussian"))]
impl<T: Real> Scheme<T> for Hvp<'_, T> {
    fn groups(&self) -> usize {
        self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gaussian(rng, t);
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        let tv = t.iter().zip(self.v).fold(T::ZERO, |s, (&a, &b)| s + a * b);
        for (((h, g), &ti), &vi) in self
            .hv
            .iter_mut()
            .zip(self.grad.iter_mut())
            .zip(t)
            .zip(self.v)
        {
            *h += pair.even * (ti * tv - vi);
            *g -= pair.odd * ti;
        }
    }
}
