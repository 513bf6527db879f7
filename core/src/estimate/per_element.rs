//! Per-element importance sampling (docs/design.md §1.2).
//!
//! Each element gets its own P pairs drawn from its own kernel density, so each weight
//! collapses to a constant times a sign:
//!
//! * gradient element i: tᵢ ~ p_G, weight −sign(tᵢ)·z (z = √(2/π); ×1/σ at the end);
//! * Hessian diagonal i: tᵢ ~ p_D, weight sign(tᵢ² − 1)·c (c = 4e^{−½}/√(2π); ×1/σ²);
//! * Hessian off-diagonal (i, j): tᵢ, tⱼ ~ p_G, weight sign(tᵢtⱼ)·z² (×1/σ²),
//!
//! other coordinates N₁. The Hessian uses symmetry: n(n+1)/2 elements i ≤ j.

use rand_core::Rng;

use super::driver::{Pair, Scheme};
#[cfg(feature = "per-element")]
use crate::kernel::gradient_element_weight;
use crate::real::Real;
use crate::sample::place;

#[cfg(feature = "per-element")]
pub(super) struct Gradient<'o, T> {
    n: usize,
    pairs: usize,
    sign: T,
    out: &'o mut [T],
}

#[cfg(feature = "per-element")]
impl<'o, T: Real> Gradient<'o, T> {
    pub(super) fn new(n: usize, pairs: usize, sign: T, out: &'o mut [T]) -> Self {
        Gradient {
            n,
            pairs,
            sign,
            out,
        }
    }
}

#[cfg(feature = "per-element")]
impl<T: Real> Scheme<T> for Gradient<'_, T> {
    fn groups(&self) -> usize {
        self.n * self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, group: usize, rng: &mut R, t: &mut [T]) {
        place::gradient_element(rng, t, group / self.pairs);
    }

    fn accumulate(&mut self, group: usize, t: &[T], pair: Pair<T>) {
        let e = group / self.pairs;
        self.out[e] += gradient_element_weight(t[e]) * self.sign * pair.odd;
    }
}

#[cfg(feature = "hessian")]
pub(super) use hessian::Hessian;

#[cfg(feature = "hessian")]
mod hessian {
    use super::*;
    use crate::estimate::upper_triangle;
    use crate::kernel::{hessian_diagonal_weight, hessian_off_diagonal_weight};

    pub(in crate::estimate) struct Hessian<'o, T> {
        n: usize,
        pairs: usize,
        /// Upper triangle accumulates at (i, j), i ≤ j, row-major n×n.
        out: &'o mut [T],
    }

    impl<'o, T: Real> Hessian<'o, T> {
        pub(in crate::estimate) fn new(n: usize, pairs: usize, out: &'o mut [T]) -> Self {
            Hessian { n, pairs, out }
        }
    }

    impl<T: Real> Scheme<T> for Hessian<'_, T> {
        fn groups(&self) -> usize {
            self.n * (self.n + 1) / 2 * self.pairs
        }

        fn draw<R: Rng + ?Sized>(&mut self, group: usize, rng: &mut R, t: &mut [T]) {
            let (i, j) = upper_triangle(group / self.pairs, self.n);
            if i == j {
                place::hessian_diagonal(rng, t, i);
            } else {
                place::hessian_off_diagonal(rng, t, i, j);
            }
        }

        fn accumulate(&mut self, group: usize, t: &[T], pair: Pair<T>) {
            let (i, j) = upper_triangle(group / self.pairs, self.n);
            let w = if i == j {
                hessian_diagonal_weight(t[i])
            } else {
                hessian_off_diagonal_weight(t[i], t[j])
            };
            self.out[i * self.n + j] += w * pair.even;
        }
    }
}
