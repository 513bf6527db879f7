//! The trust-region subproblem: minimise gᵀs + ½sᵀHs over ‖s‖ ≤ Δ, for any symmetric H.
//!
//! H = VΛVᵀ (the `eigen` module) (a diagonal H is its own decomposition), γ = Vᵀg.
//! The minimiser is s(μ) = −V(Λ + μI)⁻¹γ with the smallest μ ≥ max(0, −λ_min) for which
//! ‖s(μ)‖ ≤ Δ, and ‖s(μ)‖ = Δ whenever μ > 0 (Moré & Sorensen's characterisation). ‖s(μ)‖
//! falls monotonically in μ, so μ is found by bisection. In the hard case — γ has no
//! component along the lowest eigenvector and ‖s(−λ_min)‖ < Δ — that eigenvector is
//! added to reach the boundary. A non-positive-definite H (noise, a ridge, a saddle)
//! therefore gives a step to the boundary along the descending curvature, never a
//! division by a non-positive number. A full H whose Cholesky factor shows it positive
//! definite and far from singular, and whose Newton step fits, gives that step from the
//! factor, about a sixth of the decomposition's work ([`newton_inside`]).

use super::eigen;
use super::model::Shape;
use crate::cholesky;
use crate::optim::vector::norm;
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

/// The share of H's largest |eigenvalue| below which [`solve`] reflects a negative
/// eigenvalue (λ → |λ|) when asked to ([`Curvature::Reflect`]).
pub(super) const FAINT_NEGATIVE: f64 = 0.1;

/// How [`solve`] reads H's negative eigenvalues.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Curvature {
    /// As they are: the step goes to the boundary along the descending curvature.
    AsFitted,
    /// Those of magnitude below [`FAINT_NEGATIVE`] times the largest |λ| become |λ|, so
    /// that the step along such a direction is at most |γᵢ/λᵢ|, as along a positive one
    /// of the same magnitude. For a fit with fewer points than coefficients, whose faint
    /// negative curvature is mostly what the least change left along directions no point
    /// has tested: where f is flat along them (a low-rank f), steps to the boundary along
    /// them learn nothing and damp (through μ ≥ −λ_min) the step along the directions
    /// that matter.
    Reflect,
}

/// Writes the minimiser of gᵀs + ½sᵀHs over ‖s‖ ≤ `radius` to `s`, H's negative
/// eigenvalues read as `curvature` says. Returns false (s = 0) when g or H is not finite.
pub(super) fn solve<T: Real>(
    shape: Shape,
    curvature: Curvature,
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
            if newton_inside(g, h, radius, a, s) {
                return true;
            }
            s.fill(T::ZERO);
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
    if curvature == Curvature::Reflect {
        let faint =
            T::from_f64(FAINT_NEGATIVE) * lambda[..n].iter().fold(T::ZERO, |m, &l| m.max(l.abs()));
        for l in lambda[..n]
            .iter_mut()
            .filter(|l| **l < T::ZERO && -**l < faint)
        {
            *l = -*l;
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

/// The interior Newton step s = −H⁻¹g of a full H by its Cholesky factor (in `a`, n²
/// floats), about a sixth of the eigen-decomposition's work: written to `s` when every
/// pivot's square exceeds √ε times H's largest diagonal entry (H positive definite and
/// not nearly singular, so the eigen-decomposition would find the same step) and
/// ‖s‖ ≤ `radius`; false otherwise, `s` then holding no meaningful values.
fn newton_inside<T: Real>(g: &[T], h: &[T], radius: T, a: &mut [T], s: &mut [T]) -> bool {
    let n = g.len();
    a[..n * n].copy_from_slice(&h[..n * n]);
    let top = (0..n).fold(T::ZERO, |m, i| m.max(h[i * (n + 1)]));
    if !cholesky::factor_in_place(a, n, T::ZERO)
        || (0..n).any(|i| a[i * (n + 1)].sq() <= T::EPSILON.sqrt() * top)
    {
        return false;
    }
    for (si, &gi) in s.iter_mut().zip(g) {
        *si = -gi;
    }
    cholesky::solve(a, n, s);
    norm(s) <= radius
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

    /// The step for an N-dimensional model, N ≤ 6 (fixed arrays: no heap here).
    fn run<const N: usize>(shape: Shape, g: &[f64; N], h: &[f64], radius: f64) -> [f64; N] {
        run_reading(shape, Curvature::AsFitted, g, h, radius)
    }

    /// As [`run`], H's negative eigenvalues read as `curvature` says.
    fn run_reading<const N: usize>(
        shape: Shape,
        curvature: Curvature,
        g: &[f64; N],
        h: &[f64],
        radius: f64,
    ) -> [f64; N] {
        let (mut a, mut v, mut gamma, mut lambda) = ([0.0; 36], [0.0; 36], [0.0; 6], [0.0; 6]);
        let mut s = [0.0; N];
        let scratch = Scratch {
            a: &mut a,
            v: &mut v,
            gamma: &mut gamma,
            lambda: &mut lambda,
        };
        assert!(solve(shape, curvature, g, h, radius, scratch, &mut s));
        s
    }

    #[test]
    fn interior_newton_step() {
        let s = run(Shape::Full, &[2.0, -1.0], &[2.0, 0.0, 0.0, 1.0], 10.0);
        assert!(
            (s[0] + 1.0).abs() < 1e-12 && (s[1] - 1.0).abs() < 1e-12,
            "{s:?}"
        );
    }

    /// H = Q diag(λ) Qᵀ (6×6) with Q = I − 2vvᵀ/vᵀv, so that H⁻¹g is known in closed
    /// form; also Q's first column, λ₀'s eigenvector.
    fn reflected(lambda: &[f64; 6]) -> ([f64; 36], [f64; 36], [f64; 6]) {
        let v = [1.0, -2.0, 0.5, 3.0, -1.0, 2.0];
        let vv: f64 = v.iter().map(|x| x * x).sum();
        let q = |i: usize, j: usize| f64::from(u8::from(i == j)) - 2.0 * v[i] * v[j] / vv;
        let (mut h, mut inverse) = ([0.0; 36], [0.0; 36]);
        for i in 0..6 {
            for j in 0..6 {
                h[i * 6 + j] = (0..6).map(|k| q(i, k) * lambda[k] * q(j, k)).sum();
                inverse[i * 6 + j] = (0..6).map(|k| q(i, k) / lambda[k] * q(j, k)).sum();
            }
        }
        (h, inverse, core::array::from_fn(|i| q(i, 0)))
    }

    /// A positive definite H whose Newton step fits gives −H⁻¹g (by its Cholesky
    /// factor); one whose step does not fit, a step to the boundary; a nearly singular
    /// H (κ = 1e14, its soft eigenvalue below 64ε of the largest) with g off its soft
    /// direction, the hard case's step to the boundary along that direction, not the
    /// interior step the factor would give.
    #[test]
    fn interior_steps_by_cholesky_and_the_rest_by_eigenvalues() {
        let g = [0.3, -1.0, 2.0, 0.5, -0.7, 1.1];
        let (h, inverse, _) = reflected(&[1.0, 3.0, 0.5, 10.0, 2.0, 7.0]);
        let newton: [f64; 6] =
            core::array::from_fn(|i| -(0..6).map(|j| inverse[i * 6 + j] * g[j]).sum::<f64>());
        let s = run(Shape::Full, &g, &h, 2.0 * norm(&newton));
        for i in 0..6 {
            assert!(
                (s[i] - newton[i]).abs() < 1e-12 * norm(&newton),
                "{s:?} {newton:?}"
            );
        }
        let s = run(Shape::Full, &g, &h, 0.5 * norm(&newton));
        assert!((norm(&s) - 0.5 * norm(&newton)).abs() < 1e-9, "{s:?}");
        // λ = 1e-13 along Q's first column; g orthogonal to it.
        let (h, _, soft) = reflected(&[1e-13, 3.0, 0.5, 10.0, 2.0, 7.0]);
        let along = g.iter().zip(&soft).map(|(a, b)| a * b).sum::<f64>();
        let g: [f64; 6] = core::array::from_fn(|i| g[i] - along * soft[i]);
        let s = run(Shape::Full, &g, &h, 100.0);
        assert!((norm(&s) - 100.0).abs() < 1e-6, "{s:?}");
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

    /// Reflected, a faint negative eigenvalue (a hundredth of the largest) bounds the
    /// step along its direction by |γᵢ/λᵢ| and the step is the interior one of |H|; as
    /// fitted, it sends the step to the boundary. A strong one (half the largest) is
    /// read as fitted either way.
    #[test]
    fn reflects_faint_negative_curvature_only() {
        let (g, radius) = ([1.0, 1e-3, 0.5], 10.0);
        let faint = [1.0, 0.0, 0.0, 0.0, -0.01, 0.0, 0.0, 0.0, 2.0];
        let s = run_reading(Shape::Full, Curvature::Reflect, &g, &faint, radius);
        let expected = [-1.0, -0.1, -0.25];
        for i in 0..3 {
            assert!((s[i] - expected[i]).abs() < 1e-12, "{s:?}");
        }
        let s = run_reading(Shape::Full, Curvature::AsFitted, &g, &faint, radius);
        assert!((norm(&s) - radius).abs() < 1e-9, "{s:?}");
        let strong = [1.0, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, 0.0, 2.0];
        let s = run_reading(Shape::Full, Curvature::Reflect, &g, &strong, radius);
        assert!((norm(&s) - radius).abs() < 1e-9, "{s:?}");
        let s = run_reading(
            Shape::Diagonal,
            Curvature::Reflect,
            &g,
            &[1.0, -0.01, 2.0],
            radius,
        );
        for i in 0..3 {
            assert!((s[i] - expected[i]).abs() < 1e-12, "{s:?}");
        }
    }
}
