//! Aggregate importance sampling (docs/design.md §1.3): a mixture of all element densities.
//!
//! Each sample picks a component k of the mixture q = (1/K)·Σₖ pₖ, draws t from pₖ, and
//! weights *every* element e by Dκₑ/q (the balance heuristic), so one evaluation serves
//! all elements and the estimate stays unbiased. Instead of picking k independently, the
//! samples cycle through the components from a uniformly random start: every sample is
//! still marginally distributed as q, and the components are covered evenly.
//!
//! Gradient (K = n): q/N = ‖t‖₁/(n·z·σ), so wₑ = −n·z·tₑ/‖t‖₁ (×1/σ): bounded by n·z.
//!
//! Hessian (K = n(n+1)/2): with t standardised,
//! q/N = (1/K)·[Σᵢ |tᵢ² − 1|/c + Σ_{i<j} |tᵢtⱼ|/z²] / σ², and
//! Σ_{i<j} |tᵢtⱼ| = (‖t‖₁² − ‖t‖₂²)/2, so the density costs O(n), and
//! wᵢⱼ = (tᵢtⱼ − δᵢⱼ)/(σ²·q̃), q̃ = σ²·q/N.

use rand_core::Rng;

use super::driver::{Pair, Scheme};
use super::uniform_index;
use crate::kernel::aggregate_gradient_density;
use crate::real::Real;
use crate::sample::place;

pub(super) struct Gradient<'o, T> {
    n: usize,
    pairs: usize,
    /// The component of the next group: (start + group) mod n, advanced by one per draw
    /// (the driver draws groups in order), so no division is needed.
    component: usize,
    sign: T,
    out: &'o mut [T],
}

impl<'o, T: Real> Gradient<'o, T> {
    pub(super) fn new<R: Rng + ?Sized>(
        n: usize,
        pairs: usize,
        sign: T,
        out: &'o mut [T],
        rng: &mut R,
    ) -> Self {
        Gradient {
            n,
            pairs,
            component: uniform_index(rng, n),
            sign,
            out,
        }
    }
}

impl<T: Real> Scheme<T> for Gradient<'_, T> {
    fn groups(&self) -> usize {
        self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gradient_element(rng, t, self.component);
        self.component += 1;
        if self.component == self.n {
            self.component = 0;
        }
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        let q = aggregate_gradient_density(t);
        if q == T::ZERO {
            return;
        }
        // Weight of element e: (∂ₑN/N)/(q/N) = −tₑ/q at σ = 1.
        let s = self.sign * pair.odd / q;
        for (g, &te) in self.out.iter_mut().zip(t) {
            *g -= te * s;
        }
    }
}

#[cfg(feature = "hessian")]
pub(super) use hessian::Hessian;

#[cfg(feature = "hessian")]
mod hessian {
    use super::*;
    use crate::estimate::upper_triangle;
    use crate::kernel::aggregate_hessian_density;

    pub(in crate::estimate) struct Hessian<'o, T> {
        n: usize,
        components: usize,
        pairs: usize,
        start: usize,
        out: &'o mut [T],
    }

    impl<'o, T: Real> Hessian<'o, T> {
        pub(in crate::estimate) fn new<R: Rng + ?Sized>(
            n: usize,
            pairs: usize,
            out: &'o mut [T],
            rng: &mut R,
        ) -> Self {
            let components = n * (n + 1) / 2;
            Hessian {
                n,
                components,
                pairs,
                start: uniform_index(rng, components),
                out,
            }
        }
    }

    impl<T: Real> Scheme<T> for Hessian<'_, T> {
        fn groups(&self) -> usize {
            self.pairs
        }

        fn draw<R: Rng + ?Sized>(&mut self, group: usize, rng: &mut R, t: &mut [T]) {
            let (i, j) = upper_triangle((self.start + group) % self.components, self.n);
            if i == j {
                place::hessian_diagonal(rng, t, i);
            } else {
                place::hessian_off_diagonal(rng, t, i, j);
            }
        }

        fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
            let q = aggregate_hessian_density(t);
            if q == T::ZERO {
                return;
            }
            crate::estimate::add_rank_one(self.out, self.n, t, pair.even / q);
        }
    }
}
