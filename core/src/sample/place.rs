//! Standardised n-dimensional offsets: kernel-distributed coordinate(s) among Gaussian ones.
//!
//! Each function consumes exactly one uniform number per coordinate, in coordinate order,
//! so a stream of random numbers maps to offsets the same way on every target.

use rand_core::Rng;

use crate::real::Real;

use super::{gradient, normal};

/// t ~ N(0, I): every coordinate from N₁.
#[inline]
pub fn gaussian<T: Real, R: Rng + ?Sized>(rng: &mut R, t: &mut [T]) {
    for x in t.iter_mut() {
        *x = normal::quantile(T::uniform_open(rng));
    }
}

/// tᵢ ~ p_G, every other coordinate ~ N₁ (per-element gradient, docs/design.md §1.2).
#[inline]
pub fn gradient_element<T: Real, R: Rng + ?Sized>(rng: &mut R, t: &mut [T], i: usize) {
    for (k, x) in t.iter_mut().enumerate() {
        let xi = T::uniform_open(rng);
        *x = if k == i {
            gradient::quantile(xi)
        } else {
            normal::quantile(xi)
        };
    }
}

/// Every coordinate ~ p_G (the FR22 baseline, docs/design.md §1.6).
#[inline]
pub fn gradient_all<T: Real, R: Rng + ?Sized>(rng: &mut R, t: &mut [T]) {
    for x in t.iter_mut() {
        *x = gradient::quantile(T::uniform_open(rng));
    }
}

/// tᵢ ~ p_D, every other coordinate ~ N₁ (Hessian diagonal element i).
#[cfg(feature = "hessian")]
#[inline]
pub fn hessian_diagonal<T: Real, R: Rng + ?Sized>(rng: &mut R, t: &mut [T], i: usize) {
    for (k, x) in t.iter_mut().enumerate() {
        let xi = T::uniform_open(rng);
        *x = if k == i {
            super::hessian_diag::quantile(xi)
        } else {
            normal::quantile(xi)
        };
    }
}

/// tᵢ, tⱼ ~ p_G independently (i ≠ j), every other coordinate ~ N₁ (Hessian
/// off-diagonal element (i, j): ∂ᵢ∂ⱼN factorises into N₁′(tᵢ)·N₁′(tⱼ)).
#[cfg(feature = "hessian")]
#[inline]
pub fn hessian_off_diagonal<T: Real, R: Rng + ?Sized>(
    rng: &mut R,
    t: &mut [T],
    i: usize,
    j: usize,
) {
    for (k, x) in t.iter_mut().enumerate() {
        let xi = T::uniform_open(rng);
        *x = if k == i || k == j {
            gradient::quantile(xi)
        } else {
            normal::quantile(xi)
        };
    }
}
