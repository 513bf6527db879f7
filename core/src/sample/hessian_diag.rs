//! The Hessian-diagonal kernel density: |N₁″| normalised, in standardised units (σ = 1).
//!
//! p_D(t) = |t² − 1|·e^{(1−t²)/2}/4, C = ∫|N₁″| = 4e^{−½}/√(2π) (times 1/σ² for general σ).
//! Its CDF is piecewise (docs/design.md §1.1), with h(s) = s·e^{½−s²/2}/4:
//!
//! P(t) = h(−t) for t < −1,  ½ − h(−t) for −1 ≤ t ≤ 0,  and P(t) = 1 − P(−t) for t > 0,
//!
//! so P(−1) = ¼, P(0) = ½, P(1) = ¾. h rises on [0, 1] to ¼ and falls on [1, ∞), so
//! inverting P means solving h(s) = y on one monotone branch; with L = ln 4y that is
//!
//! ψ(s) := ln s + ½ − s²/2 = L.
//!
//! There is no elementary inverse. The paper tabulates P on ±10σ and interpolates
//! linearly, which is wrong by up to a table step. We solve the equation to full
//! precision instead, in whichever variable keeps it well conditioned, from an
//! asymptotically exact start and with at most [`MAX_NEWTON`] safeguarded Newton steps
//! (bisection whenever a step leaves the bracket):
//!
//! * inner branch, s ≤ 1, far from 1 (L < −½): in r = ln s, G(r) = r + ½ − e^{2r}/2 − L,
//!   start r₀ = L − ½ + e^{2L−1}/2, bracket [L − ½, L]; keeps relative precision for
//!   s down to the smallest normal number;
//! * near s = 1 (|L| ≤ ½, where ψ′ vanishes): in δ = s − 1, F(δ) = ln(1+δ) − δ − δ²/2 − L,
//!   start δ₀ = w + w²/6 with w = ±√(−L) from −L = δ² − δ³/3 + …, bracket [−0.9, 0] or
//!   [0, 1];
//! * outer branch, s ≥ 1, far from 1: in s, start s₀ = √(a + ln a), a = 1 − 2L, bracket
//!   [√a, √(2a)].
//!
//! Rejected: the table-plus-Newton scheme of docs/design.md §1.1. These analytic starts are
//! already within a few ulps after two or three steps and need no table in flash.

use crate::real::Real;

use super::normal::clamp_open;

/// Newton steps allowed per inversion; two or three suffice from the analytic starts.
pub const MAX_NEWTON: usize = 12;

/// The inverse CDF of p_D (σ = 1).
///
/// ξ is clamped to the open unit interval (NaN is treated as 0), so the result is finite
/// for every input (about ±38.7 at the ends in `f64`). Odd symmetry is exact:
/// `quantile(1 − ξ) == −quantile(ξ)` whenever 1 − ξ is exact.
pub fn quantile<T: Real>(xi: T) -> T {
    let xi = clamp_open(xi);
    let (y, sign) = if xi <= T::HALF {
        (xi, -T::ONE)
    } else {
        (T::ONE - xi, T::ONE)
    };
    let quarter = T::HALF * T::HALF;
    let magnitude = if y < quarter {
        // Outer branch: h(s) = y, s > 1. 4y − 1 is exact when 4y ≥ ½.
        outer(ln_4y(y, T::from_f64(4.0) * y - T::ONE))
    } else {
        // Inner branch: h(s) = ½ − y ∈ [0, ¼], s ≤ 1. 4(½ − y) − 1 = 1 − 4y exactly.
        let y_inner = T::HALF - y;
        if y_inner <= T::ZERO {
            return T::ZERO;
        }
        inner(ln_4y(y_inner, T::ONE - T::from_f64(4.0) * y))
    };
    sign * magnitude
}

/// The CDF P(t) of p_D (σ = 1).
pub fn cdf<T: Real>(t: T) -> T {
    let h = -t * (T::HALF - T::HALF * t.sq()).exp() / T::from_f64(4.0);
    if t < -T::ONE {
        h
    } else if t <= T::ONE {
        T::HALF - h
    } else {
        T::ONE + h
    }
}

/// The density p_D(t) = |t² − 1|·e^{(1−t²)/2}/4 (σ = 1).
pub fn pdf<T: Real>(t: T) -> T {
    (t.sq() - T::ONE).abs() * (T::HALF - T::HALF * t.sq()).exp() / T::from_f64(4.0)
}

/// ln 4y, using ln_1p(4y − 1) where 4y − 1 is exact and small.
#[inline]
fn ln_4y<T: Real>(y: T, four_y_minus_one: T) -> T {
    if four_y_minus_one >= -T::HALF {
        four_y_minus_one.ln_1p()
    } else {
        (T::from_f64(4.0) * y).ln()
    }
}

/// s ≥ 1 with ψ(s) = L.
fn outer<T: Real>(l: T) -> T {
    if l >= -T::HALF {
        return T::ONE + near_one(l, T::ONE);
    }
    let a = T::ONE - T::TWO * l;
    let lo = a.sqrt();
    let hi = (T::TWO * a).sqrt();
    let start = (a + a.ln()).sqrt().max(lo).min(hi);
    safeguarded_newton(start, lo, hi, false, |s| {
        let f = s.ln() + T::HALF - T::HALF * s.sq() - l;
        let df = (T::ONE - s) * (T::ONE + s) / s;
        (f, df)
    })
}

/// s ∈ [0, 1] with ψ(s) = L.
fn inner<T: Real>(l: T) -> T {
    if l >= -T::HALF {
        return T::ONE + near_one(l, -T::ONE);
    }
    // In r = ln s the equation is nearly linear for small s.
    let lo = l - T::HALF;
    let hi = l;
    let start = (lo + T::HALF * (T::TWO * lo).exp()).max(lo).min(hi);
    let r = safeguarded_newton(start, lo, hi, true, |r| {
        let e2r = (T::TWO * r).exp();
        (r + T::HALF - T::HALF * e2r - l, T::ONE - e2r)
    });
    r.exp()
}

/// δ = s − 1 with ψ(1 + δ) = L, for |L| ≤ ½; `side` is +1 (outer) or −1 (inner).
fn near_one<T: Real>(l: T, side: T) -> T {
    if l >= T::ZERO {
        return T::ZERO;
    }
    let w = side * (-l).sqrt();
    let start = w + w.sq() / T::from_f64(6.0);
    let (lo, hi, increasing) = if side > T::ZERO {
        (T::ZERO, T::ONE, false)
    } else {
        (T::from_f64(-0.9), T::ZERO, true)
    };
    safeguarded_newton(start.max(lo).min(hi), lo, hi, increasing, |d| {
        let f = d.ln_1p() - d - T::HALF * d.sq() - l;
        let df = -d * (T::TWO + d) / (T::ONE + d);
        (f, df)
    })
}

/// Newton's method for a root of a monotone `f` bracketed by [lo, hi], falling back to
/// bisection when a step is not finite or leaves the bracket. `increasing` states the
/// direction of `f`. Stops when a step is below 2ε relative or after [`MAX_NEWTON`].
fn safeguarded_newton<T: Real>(
    mut x: T,
    mut lo: T,
    mut hi: T,
    increasing: bool,
    f: impl Fn(T) -> (T, T),
) -> T {
    for _ in 0..MAX_NEWTON {
        let (fx, dfx) = f(x);
        if fx == T::ZERO {
            return x;
        }
        if (fx > T::ZERO) == increasing {
            hi = x;
        } else {
            lo = x;
        }
        let mut next = x - fx / dfx;
        if !(next >= lo && next <= hi) {
            next = T::HALF * (lo + hi);
        }
        let step = (next - x).abs();
        x = next;
        if step <= T::TWO * T::EPSILON * x.abs().max(T::MIN_POSITIVE) {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cdf_landmarks() {
        assert!((cdf(-1.0f64) - 0.25).abs() < 1e-16);
        assert_eq!(cdf(0.0f64), 0.5);
        assert!((cdf(1.0f64) - 0.75).abs() < 1e-16);
        assert!(cdf(-40.0f64) >= 0.0 && cdf(40.0f64) <= 1.0);
    }

    #[test]
    fn round_trip_f64_to_1e12() {
        let mut prev = f64::NEG_INFINITY;
        for i in 1..200_000 {
            let xi = i as f64 / 200_000.0;
            let t = quantile(xi);
            assert!(t.is_finite() && t >= prev, "ξ={xi}");
            prev = t;
            assert!((cdf(t) - xi).abs() < 1e-12, "ξ={xi}: P(t)={}", cdf(t));
        }
        // Relative accuracy deep in the tails and right at the branch points.
        let mut xi = 1e-300;
        while xi < 0.2 {
            let back = cdf(quantile(xi));
            assert!(((back - xi) / xi).abs() < 1e-12, "tail ξ={xi}: {back}");
            xi *= 3.7;
        }
        for xi in [
            0.25,
            0.25 - 1e-15,
            0.25 + 1e-15,
            0.5 - 1e-17,
            0.75,
            0.75 + 1e-14,
        ] {
            assert!((cdf(quantile(xi)) - xi).abs() < 1e-14, "ξ={xi}");
        }
    }

    #[test]
    fn round_trip_f32_to_1e5() {
        for i in 1..100_000 {
            let xi = i as f32 / 100_000.0;
            let t = quantile(xi);
            assert!((cdf(t) - xi).abs() < 1e-5, "ξ={xi}");
        }
    }

    #[test]
    fn finite_and_monotone_at_special_points() {
        let p64 = [
            0.0,
            f64::MIN_POSITIVE,
            0.25 - f64::EPSILON,
            0.25,
            0.25 + f64::EPSILON,
            0.5 - f64::EPSILON,
            0.5,
            0.5 + f64::EPSILON,
            0.75,
            1.0 - f64::EPSILON,
            1.0,
        ];
        let mut prev = f64::NEG_INFINITY;
        for xi in p64 {
            let t = quantile(xi);
            assert!(t.is_finite() && t >= prev, "ξ={xi} → {t}");
            prev = t;
        }
        let p32 = [
            0.0f32,
            f32::MIN_POSITIVE,
            0.25,
            0.5 - f32::EPSILON,
            0.5,
            0.5 + f32::EPSILON,
            0.75,
            1.0 - f32::EPSILON,
            1.0,
        ];
        let mut prev = f32::NEG_INFINITY;
        for xi in p32 {
            let t = quantile(xi);
            assert!(t.is_finite() && t >= prev, "ξ={xi} → {t}");
            prev = t;
        }
        assert_eq!(quantile(0.5f64), 0.0);
        assert_eq!(quantile(0.25f64), -1.0);
    }

    #[test]
    fn odd_symmetry() {
        for i in 1..1000 {
            let xi = i as f64 / 1024.0; // exact, so 1 − ξ is exact
            assert_eq!(quantile(1.0 - xi), -quantile(xi));
        }
    }

    #[test]
    fn density_is_the_cdf_derivative() {
        for i in -80..80 {
            let t = i as f64 * 0.05 + 0.013;
            let h = 1e-6;
            let numeric = (cdf(t + h) - cdf(t - h)) / (2.0 * h);
            assert!((numeric - pdf(t)).abs() < 1e-8, "t={t}");
        }
    }
}
