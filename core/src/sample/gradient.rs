//! The gradient-kernel density: |N₁′| normalised, in standardised units (σ = 1).
//!
//! p_G(t) = |t|/2 · e^{−t²/2}, the density of a signed Rayleigh variable. Its CDF is
//! ½e^{−t²/2} for t < 0 and 1 − ½e^{−t²/2} for t ≥ 0, with the closed-form inverse
//! t = −√(−2 ln 2ξ) (ξ ≤ ½), t = +√(−2 ln 2(1 − ξ)) (ξ > ½). Multiply by σ for τ.

use crate::real::Real;

use super::normal::clamp_open;

/// The inverse CDF of p_G (σ = 1).
///
/// ξ is clamped to the open unit interval (NaN is treated as 0), so the result is finite:
/// about ±38.6 at the ends in `f64`. Near ξ = ½, ln 2ξ is evaluated by
/// [`Real::ln_near_one`] (in `f64` as ln_1p(2ξ − 1), whose argument is exact), so small |t|
/// keeps full relative precision.
#[inline]
pub fn quantile<T: Real>(xi: T) -> T {
    let xi = clamp_open(xi);
    let (tail, sign) = if xi <= T::HALF {
        (xi, -T::ONE)
    } else {
        (T::ONE - xi, T::ONE)
    };
    let two_tail = T::TWO * tail;
    let ln = if two_tail >= T::HALF {
        two_tail.ln_near_one()
    } else {
        two_tail.ln()
    };
    sign * (-T::TWO * ln).sqrt()
}

/// The CDF of p_G (σ = 1).
#[inline]
pub fn cdf<T: Real>(t: T) -> T {
    let half_e = T::HALF * (-T::HALF * t.sq()).exp();
    if t < T::ZERO { half_e } else { T::ONE - half_e }
}

/// The density p_G(t) = |t|/2 · e^{−t²/2} (σ = 1).
#[inline]
pub fn pdf<T: Real>(t: T) -> T {
    T::HALF * t.abs() * (-T::HALF * t.sq()).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_monotone_finite() {
        let mut prev = f64::NEG_INFINITY;
        for i in 1..20_000 {
            let xi = i as f64 / 20_000.0;
            let t = quantile(xi);
            assert!(t >= prev);
            prev = t;
            assert!((cdf(t) - xi).abs() < 1e-12, "f64 ξ={xi}");
            let xf = xi as f32;
            assert!((cdf(quantile(xf)) - xf).abs() < 1e-5, "f32 ξ={xf}");
        }
        for xi in [
            0.0,
            f64::MIN_POSITIVE,
            0.5 - f64::EPSILON,
            0.5,
            0.5 + f64::EPSILON,
            1.0 - f64::EPSILON,
            1.0,
        ] {
            assert!(quantile(xi).is_finite(), "ξ={xi}");
        }
        for xi in [
            0.0f32,
            f32::MIN_POSITIVE,
            0.5 - f32::EPSILON,
            0.5,
            0.5 + f32::EPSILON,
            1.0 - f32::EPSILON,
            1.0,
        ] {
            assert!(quantile(xi).is_finite(), "ξ={xi}");
        }
        assert!(quantile(0.0f64) < quantile(f64::MIN_POSITIVE * 2.0));
    }

    #[test]
    fn small_t_keeps_relative_precision() {
        // ξ = ½ − δ: −½t² ≈ ln(1 − 2δ) so t ≈ −2√δ.
        let d = 1e-12f64;
        let t = quantile(0.5 - d);
        let exact = -libm::sqrt(-2.0 * libm::log1p(-2.0 * (0.5 - (0.5 - d))));
        assert!(((t - exact) / exact).abs() < 1e-12);
    }
}
