//! The trust-region subproblem: minimise gᵀs + ½sᵀHs over ‖s‖ ≤ Δ, for any symmetric H.
//!
//! H = VΛVᵀ (the `eigen` module) (a diagonal H is its own decomposition), γ = Vᵀg.
//! The minimiser is s(μ) = −V(Λ + μI)⁻¹γ with the smallest μ ≥ max(0, −λ_min) for which
//! ‖s(μ)‖ ≤ Δ, and ‖s(μ)‖ = Δ whenever μ > 0 (Moré & Sorensen's characterisation). ‖s(μ)‖
//! falls monotonically in μ, so μ is found by bisection. In the hard case — γ has no
//! component along the lowest eigenvector and ‖s(−λ_min)‖ < Δ — that eigenvector is
//! added to reach the boundary. A non-positive-definite H (noise, a ridge, a saddle)
//! therefore gives a step to the boundary along the descending curvature, never a
//! division by a non-positive number.

use super::eigen;
use super::model::Shape;
use crate::real::Real;

/// Bisection steps on μ: each halves the bracket, so 200 reach any precision of T.
const MAX_BISECTIONS: usize = 200;

/// Buffers of [`solve`]: `a` and `v` n² floats each (full shape only), `gamma` and
/// `lambda` n floats.
pub(super) struct Scratch<'a, T> {
    pub a: &'a mut [T],
    pub v: &'a mut [T],
    pub gamma: &'a mut [T],
    pub lambda: &'a mut [T],
}

/// Writes the minimiser of gᵀs + ½sᵀHs over ‖s‖ ≤ `radius` to `s`. Returns false (s = 0)
/// when g or H is not finite.
pub(super) fn solve<T: Real>(
    shape: Shape,
    g: &[T],
    h: &[T],
    radius: T,
    scratch: Scratch<'_, T>,
    s: &mut [T],
) -> bool {
    let n = g.len();
    s.fill(T::ZERO);
    if g.iter().chain(h).any(|x| !x.is_finite()) || radius <= T::ZERO || !radius.is_finite() {
        return false;
    }
    let Scratch {
        a,
        v,
        gamma,
        lambda,
    } = scratch;
    match shape {
        Shape::Full => {
            a[..n * n].copy_from_slice(&h[..n * n]);
            eigen::symmetric(a, v, n);
            for i in 0..n {
                lambda[i] = a[i];
                gamma[i] = (0..n).fold(T::ZERO, |acc, k| acc + v[k * n + i] * g[k]);
            }
        }
        Shape::Diagonal => {
            lambda[..n].copy_from_slice(&h[..n]);
            gamma[..n].copy_from_slice(g);
        }
    }
    let (gamma, lambda) = (&gamma[..n], &lambda[..n]);
    let (low_index, low) =
        lambda.iter().enumerate().fold(
            (0, T::MAX),
            |(bi, b), (i, &l)| if l < b { (i, l) } else { (bi, b) },
        );
    let scale = lambda.iter().fold(T::ZERO, |m, &l| m.max(l.abs()));
    let gnorm = gamma.iter().fold(T::ZERO, |acc, &x| acc + x.sq()).sqrt();
    // Eigenvalues within this of the lowest count as equal to it (the hard case).
    let tie = T::from_f64(64.0) * T::EPSILON * scale.max(T::MIN_POSITIVE);
    let coefficient = |i: usize, mu: T| {
        let d = lambda[i] + mu;
        if d > tie { -gamma[i] / d } else { T::ZERO }
    };
    let length = |mu: T| {
        (0..n)
            .fold(T::ZERO, |acc, i| acc + coefficient(i, mu).sq())
            .sqrt()
    };
    let floor = (-low).max(T::ZERO);
    // The interior Newton step, when H is positive definite and it fits.
    let mu = if low > tie && length(T::ZERO) <= radius {
        T::ZERO
    } else {
        // Does γ reach along the low eigenvectors? Then ‖s(μ)‖ → ∞ as μ → floor.
        let reaches = (0..n).any(|i| {
            lambda[i] - low <= tie
                && gamma[i].abs() > T::EPSILON.sqrt() * gnorm.max(T::MIN_POSITIVE)
        });
        let at_floor = length(floor + tie);
        if !reaches && at_floor < radius {
            // The hard case: s(floor) plus the lowest eigenvector to the boundary.
            let extra = (radius.sq() - at_floor.sq()).max(T::ZERO).sqrt();
            write_step(
                shape,
                v,
                n,
                |i| {
                    if i == low_index {
                        extra
                    } else {
                        coefficient(i, floor + tie)
                    }
                },
                s,
            );
            return true;
        }
        let mut lo = floor;
        let mut hi = floor + gnorm / radius + tie;
        for _ in 0..MAX_BISECTIONS {
            let mid = T::HALF * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if length(mid) > radius {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    };
    write_step(shape, v, n, |i| coefficient(i, mu), s);
    true
}

/// s = Σᵢ cᵢ vᵢ (the eigenvectors of a full H) or cᵢ eᵢ (diagonal H).
fn write_step<T: Real>(shape: Shape, v: &[T], n: usize, c: impl Fn(usize) -> T, s: &mut [T]) {
    match shape {
        Shape::Full => {
            for i in 0..n {
                let ci = c(i);
                for k in 0..n {
                    s[k] += ci * v[k * n + i];
                }
            }
        }
        Shape::Diagonal => {
            for (i, sk) in s.iter_mut().enumerate() {
                *sk = c(i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step for a 2-D model (fixed arrays: no heap here).
    fn run(shape: Shape, g: &[f64; 2], h: &[f64], radius: f64) -> [f64; 2] {
        let (mut a, mut v, mut gamma, mut lambda) = ([0.0; 4], [0.0; 4], [0.0; 2], [0.0; 2]);
        let mut s = [0.0; 2];
        let scratch = Scratch {
            a: &mut a,
            v: &mut v,
            gamma: &mut gamma,
            lambda: &mut lambda,
        };
        assert!(solve(shape, g, h, radius, scratch, &mut s));
        s
    }

    fn norm(s: &[f64]) -> f64 {
        libm::sqrt(s.iter().map(|x| x * x).sum::<f64>())
    }

    #[test]
    fn interior_newton_step() {
        let s = run(Shape::Full, &[2.0, -1.0], &[2.0, 0.0, 0.0, 1.0], 10.0);
        assert!(
            (s[0] + 1.0).abs() < 1e-12 && (s[1] - 1.0).abs() < 1e-12,
            "{s:?}"
        );
    }

    #[test]
    fn boundary_and_negative_curvature() {
        let s = run(Shape::Full, &[1.0, 0.0], &[1.0, 0.0, 0.0, -1.0], 2.0);
        assert!((norm(&s) - 2.0).abs() < 1e-9, "{s:?}");
        // The hard case: no gradient along the negative direction, which is still taken.
        assert!(s[1].abs() > 1.0, "{s:?}");
        let s = run(Shape::Diagonal, &[0.0, 0.0], &[1.0, -3.0], 0.5);
        assert!((norm(&s) - 0.5).abs() < 1e-9 && s[0] == 0.0, "{s:?}");
        let s = run(Shape::Diagonal, &[3.0, 4.0], &[0.0, 0.0], 1.0);
        assert!(
            (s[0] + 0.6).abs() < 1e-9 && (s[1] + 0.8).abs() < 1e-9,
            "{s:?}"
        );
    }
}
