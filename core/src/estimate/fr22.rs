//! The FR22 baseline gradient (Fischer & Ritschel 2023; docs/design.md §1.6).
//!
//! One sample set for all n coordinates: every coordinate of t is drawn from p_G, and
//! coordinate e is weighted −sign(tₑ)·Z. Each coordinate is blurred by the Gaussian only
//! in the direction differentiated; the others see p_G.

use rand_core::Rng;

use super::driver::{Pair, Scheme};
use crate::kernel::gradient_element_weight;
use crate::real::Real;
use crate::sample::place;

pub(super) struct Gradient<'o, T> {
    pairs: usize,
    sign: T,
    out: &'o mut [T],
}

impl<'o, T: Real> Gradient<'o, T> {
    pub(super) fn new(pairs: usize, sign: T, out: &'o mut [T]) -> Self {
        Gradient { pairs, sign, out }
    }
}

impl<T: Real> Scheme<T> for Gradient<'_, T> {
    fn groups(&self) -> usize {
        self.pairs
    }

    fn draw<R: Rng + ?Sized>(&mut self, _group: usize, rng: &mut R, t: &mut [T]) {
        place::gradient_all(rng, t);
    }

    fn accumulate(&mut self, _group: usize, t: &[T], pair: Pair<T>) {
        let s = self.sign * pair.odd;
        for (g, &te) in self.out.iter_mut().zip(t) {
            *g += gradient_element_weight(te) * s;
        }
    }
}
