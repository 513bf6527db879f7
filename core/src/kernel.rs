//! Kernel weights: the derivatives of the smoothing Gaussian (docs/design.md §1).
//!
//! With N(τ) = Π N₁(τᵢ), N₁ the 1-D normal density of standard deviation σ, the smoothed
//! objective f̄(θ) = ∫ N(τ) f(θ − τ) dτ has derivatives D f̄(θ) = ∫ Dκ(τ) f(θ − τ) dτ with
//!
//! | quantity | kernel Dκ(τ) |
//! |---|---|
//! | gradient gᵢ | −(τᵢ/σ²) N(τ) |
//! | Hessian Hᵢⱼ | (τᵢτⱼ/σ⁴ − δᵢⱼ/σ²) N(τ) |
//! | Hessian-vector product (Hv)ᵢ | (τᵢ(τ·v)/σ⁴ − vᵢ/σ²) N(τ) |
//!
//! The functions here give the kernels divided by N(τ) (the weights of the plain Gaussian
//! estimator), in terms of the standardised offset t = τ/σ, and the normalising constants
//! of the importance-sampling densities. Working in t keeps σ from 1e-12 to 1e12 (and so
//! σ⁴ up to 1e48) out of intermediate results: only the final 1/σ or 1/σ² scale touches it.

use crate::real::Real;

/// z = ∫|N₁′(t)| dt at σ = 1, i.e. √(2/π). For general σ the constant is Z = z/σ.
pub const GRADIENT_NORM: f64 = 0.797_884_560_802_865_4;

/// z² = 2/π: the off-diagonal Hessian constant Z² at σ = 1 (Z² = z²/σ² in general).
pub const OFF_DIAGONAL_NORM: f64 = core::f64::consts::FRAC_2_PI;

/// c = ∫|N₁″(t)| dt at σ = 1, i.e. 4e^{−½}/√(2π). For general σ, C = c/σ².
pub const DIAGONAL_NORM: f64 = 0.967_882_898_076_573_5;

/// The 1-D normal density N₁(τ) of standard deviation σ.
#[inline]
pub fn gaussian<T: Real>(tau: T, sigma: T) -> T {
    let t = tau / sigma;
    (-T::HALF * t.sq()).exp() * T::from_f64(0.398_942_280_401_432_7) / sigma
}

/// ∂ᵢN/N at offset t = τ/σ: −tᵢ/σ.
#[inline]
pub fn gradient<T: Real>(t: &[T], i: usize, sigma: T) -> T {
    -t[i] / sigma
}

/// ∂ᵢ∂ⱼN/N at offset t = τ/σ: (tᵢtⱼ − δᵢⱼ)/σ².
#[inline]
pub fn hessian<T: Real>(t: &[T], i: usize, j: usize, sigma: T) -> T {
    let delta = if i == j { T::ONE } else { T::ZERO };
    (t[i] * t[j] - delta) / sigma.sq()
}

/// (Σⱼ ∂ᵢ∂ⱼN vⱼ)/N at offset t = τ/σ: (tᵢ(t·v) − vᵢ)/σ².
#[inline]
pub fn hessian_vector<T: Real>(t: &[T], v: &[T], i: usize, sigma: T) -> T {
    let tv = t.iter().zip(v).fold(T::ZERO, |acc, (&a, &b)| acc + a * b);
    (t[i] * tv - v[i]) / sigma.sq()
}

/// Per-element gradient weight ∂ₑN/(p_G(tₑ)·Π_{k≠e}N₁(t_k)) at σ = 1: −sign(tₑ)·z.
#[inline]
pub fn gradient_element_weight<T: Real>(te: T) -> T {
    -te.sign() * T::from_f64(GRADIENT_NORM)
}

/// Per-element Hessian-diagonal weight at σ = 1: sign(tᵢ² − 1)·c.
#[inline]
pub fn hessian_diagonal_weight<T: Real>(ti: T) -> T {
    (ti.sq() - T::ONE).sign() * T::from_f64(DIAGONAL_NORM)
}

/// Per-element Hessian off-diagonal weight at σ = 1: sign(tᵢtⱼ)·z².
#[inline]
pub fn hessian_off_diagonal_weight<T: Real>(ti: T, tj: T) -> T {
    (ti * tj).sign() * T::from_f64(OFF_DIAGONAL_NORM)
}

/// The aggregate gradient mixture density over N at σ = 1: q/N = ‖t‖₁/(n·z), the mean
/// of the n element densities p_G(tₑ)·Π_{k≠e}N₁(t_k), each divided by N(t).
#[inline]
pub fn aggregate_gradient_density<T: Real>(t: &[T]) -> T {
    let l1 = t.iter().fold(T::ZERO, |s, &x| s + x.abs());
    l1 / (T::from_usize(t.len()) * T::from_f64(GRADIENT_NORM))
}

/// The aggregate Hessian mixture density over N at σ = 1, in O(n):
/// q/N = (1/K)·[Σᵢ|tᵢ² − 1|/c + (‖t‖₁² − ‖t‖₂²)/(2z²)], K = n(n+1)/2.
#[inline]
pub fn aggregate_hessian_density<T: Real>(t: &[T]) -> T {
    let (mut diag, mut l1, mut l2) = (T::ZERO, T::ZERO, T::ZERO);
    for &x in t {
        let x2 = x.sq();
        diag += (x2 - T::ONE).abs();
        l1 += x.abs();
        l2 += x2;
    }
    // Σ_{i<j}|tᵢtⱼ| ≥ 0; rounding in ‖t‖₁² − ‖t‖₂² must not make it negative.
    let off = (T::HALF * (l1.sq() - l2)).max(T::ZERO);
    let n = t.len();
    (diag / T::from_f64(DIAGONAL_NORM) + off / T::from_f64(OFF_DIAGONAL_NORM))
        / T::from_usize(n * (n + 1) / 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sample::{gradient as pg, normal};

    /// Importance sampling is unbiased iff weight × density = kernel pointwise.
    #[test]
    fn weights_times_densities_are_the_kernels() {
        for k in -60..60 {
            let t = k as f64 * 0.1 + 0.031;
            // Gradient: w·p_G(t) = N₁′(t) = −t·φ(t).
            let lhs = gradient_element_weight(t) * pg::pdf(t);
            assert!((lhs + t * normal::pdf(t)).abs() < 1e-15, "t={t}");
            #[cfg(feature = "hessian")]
            {
                use crate::sample::hessian_diag as pd;
                // Diagonal: w·p_D(t) = N₁″(t) = (t² − 1)·φ(t).
                let lhs = hessian_diagonal_weight(t) * pd::pdf(t);
                assert!(
                    (lhs - (t * t - 1.0) * normal::pdf(t)).abs() < 1e-15,
                    "t={t}"
                );
                // Off-diagonal: w·p_G(t)·p_G(s) = N₁′(t)·N₁′(s).
                let s = 0.7 - t * 0.3;
                let lhs = hessian_off_diagonal_weight(t, s) * pg::pdf(t) * pg::pdf(s);
                let rhs = t * normal::pdf(t) * s * normal::pdf(s);
                assert!((lhs - rhs).abs() < 1e-15, "t={t}");
            }
        }
    }

    /// The O(n) mixture densities equal the mean of the component densities.
    #[test]
    fn aggregate_densities_are_mixtures() {
        let t = [0.3, -1.7, 0.05, 2.2, -0.9];
        let n = t.len();
        let phi = |x: f64| normal::pdf(x);
        let big_n: f64 = t.iter().map(|&x| phi(x)).product();
        let q = t
            .iter()
            .map(|&te| pg::pdf(te) * big_n / phi(te))
            .sum::<f64>()
            / n as f64;
        assert!((aggregate_gradient_density(&t) - q / big_n).abs() < 1e-14);
        #[cfg(feature = "hessian")]
        {
            use crate::sample::hessian_diag as pd;
            let mut q = 0.0;
            for i in 0..n {
                q += pd::pdf(t[i]) * big_n / phi(t[i]);
                for j in i + 1..n {
                    q += pg::pdf(t[i]) * pg::pdf(t[j]) * big_n / (phi(t[i]) * phi(t[j]));
                }
            }
            q /= (n * (n + 1) / 2) as f64;
            assert!((aggregate_hessian_density(&t) - q / big_n).abs() < 1e-14);
        }
    }

    /// The kernels against finite differences of the Gaussian itself.
    #[test]
    fn kernels_are_derivatives_of_the_gaussian() {
        let sigma = 0.7f64;
        let tau = [0.3, -0.45, 0.9];
        let n = |x: &[f64]| x.iter().map(|&a| gaussian(a, sigma)).product::<f64>();
        let t: [f64; 3] = core::array::from_fn(|k| tau[k] / sigma);
        let h = 1e-5;
        for i in 0..3 {
            let mut p = tau;
            let mut m = tau;
            p[i] += h;
            m[i] -= h;
            let fd = (n(&p) - n(&m)) / (2.0 * h);
            assert!((fd - gradient(&t, i, sigma) * n(&tau)).abs() < 1e-8);
            for j in 0..3 {
                let shifted = |di: f64, dj: f64| {
                    let mut x = tau;
                    x[i] += di;
                    x[j] += dj;
                    n(&x)
                };
                let fd2 = (shifted(h, h) - shifted(h, -h) - shifted(-h, h) + shifted(-h, -h))
                    / (4.0 * h * h);
                assert!(
                    (fd2 - hessian(&t, i, j, sigma) * n(&tau)).abs() < 1e-4,
                    "H{i}{j}"
                );
            }
        }
        let v = [1.0, -2.0, 0.5];
        for i in 0..3 {
            let direct: f64 = (0..3).map(|j| hessian(&t, i, j, sigma) * v[j]).sum();
            assert!((direct - hessian_vector(&t, &v, i, sigma)).abs() < 1e-12);
        }
    }

    #[test]
    fn normalising_constants() {
        let pi = core::f64::consts::PI;
        assert!((GRADIENT_NORM - libm::sqrt(2.0 / pi)).abs() < 1e-16);
        assert!((OFF_DIAGONAL_NORM - GRADIENT_NORM * GRADIENT_NORM).abs() < 1e-16);
        assert!((DIAGONAL_NORM - 4.0 * libm::exp(-0.5) / libm::sqrt(2.0 * pi)).abs() < 1e-16);
    }
}
