//! Cholesky factorisation: plain, for the regression estimators' sample moment matrix,
//! and with a growing diagonal shift, for Newton steps on estimated (noisy, possibly
//! indefinite) Hessians.

use crate::real::Real;

/// Most shifts tried before giving up; λ grows ×10 per try, so 40 tries span 40 decades.
#[cfg(feature = "hessian")]
pub const MAX_SHIFTS: usize = 40;

/// Relative eigenvalue floor: A + λI is accepted only if A + λI − δI is positive
/// definite, δ = `FLOOR`·‖A‖_F, so no eigenvalue of the system solved is below δ. An
/// estimated Hessian whose softest direction is noise would otherwise be shifted to the
/// edge of singularity and send the step to the trust boundary.
#[cfg(feature = "hessian")]
pub const FLOOR: f64 = 1e-2;

/// Factors A + λI = LLᵀ into `l` (row-major n×n, lower triangle) for the smallest λ in
/// {0, λ₀, 10λ₀, 100λ₀, …} with A + (λ − δ)I positive definite (see [`FLOOR`]),
/// λ₀ = δ + 1e-6·‖A‖_F (or 1e-6 for A = 0). `a` is read-only. Returns λ, or `None`
/// after [`MAX_SHIFTS`] tries.
#[cfg(feature = "hessian")]
pub(crate) fn factor_shifted<T: Real>(a: &[T], l: &mut [T], n: usize) -> Option<T> {
    let frobenius = crate::optim::vector::norm(&a[..n * n]);
    if !frobenius.is_finite() {
        return None;
    }
    let floor = T::from_f64(FLOOR) * frobenius;
    let first = if frobenius > T::ZERO {
        floor + T::from_f64(1e-6) * frobenius
    } else {
        T::from_f64(1e-6)
    };
    let mut lambda = T::ZERO;
    for _ in 0..MAX_SHIFTS {
        if factor(a, l, n, lambda - floor) {
            factor(a, l, n, lambda);
            return Some(lambda);
        }
        lambda = if lambda == T::ZERO {
            first
        } else {
            lambda * T::from_f64(10.0)
        };
        if !lambda.is_finite() {
            return None;
        }
    }
    None
}

/// A + λI = LLᵀ into `l` (lower triangle of a row-major n×n matrix); false if a pivot is
/// not positive and finite.
#[cfg(feature = "hessian")]
fn factor<T: Real>(a: &[T], l: &mut [T], n: usize, lambda: T) -> bool {
    for i in 0..n {
        l[i * n..i * n + i + 1].copy_from_slice(&a[i * n..i * n + i + 1]);
    }
    factor_in_place(l, n, lambda)
}

/// A + λI = LLᵀ in place: reads the lower triangle of the row-major n×n `a` (the upper
/// one is ignored) and overwrites it with L. False if a pivot is not positive and finite
/// (then `a` holds no meaningful values).
pub(crate) fn factor_in_place<T: Real>(a: &mut [T], n: usize, lambda: T) -> bool {
    for i in 0..n {
        for j in 0..=i {
            let mut s = a[i * n + j];
            if i == j {
                s += lambda;
            }
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            if i == j {
                if !(s > T::ZERO && s.is_finite()) {
                    return false;
                }
                a[i * n + i] = s.sqrt();
            } else {
                a[i * n + j] = s / a[j * n + j];
            }
        }
    }
    true
}

/// Solves LLᵀx = b in place (`x` holds b on entry).
pub(crate) fn solve<T: Real>(l: &[T], n: usize, x: &mut [T]) {
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i * n + k] * x[k];
        }
        x[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s -= l[k * n + i] * x[k];
        }
        x[i] = s / l[i * n + i];
    }
}

#[cfg(all(test, feature = "hessian"))]
mod tests {
    use super::*;

    #[test]
    fn solves_spd_and_shifts_indefinite() {
        let a = [4.0, 1.0, 1.0, 3.0];
        let mut l = [0.0; 4];
        assert_eq!(factor_shifted(&a, &mut l, 2), Some(0.0));
        let mut x = [1.0, 2.0];
        solve(&l, 2, &mut x);
        assert!((4.0 * x[0] + x[1] - 1.0).abs() < 1e-14 && (x[0] + 3.0 * x[1] - 2.0).abs() < 1e-14);
        let saddle = [1.0, 0.0, 0.0, -1.0];
        let lambda = factor_shifted(&saddle, &mut l, 2).unwrap();
        assert!(lambda > 1.0 + FLOOR * 2f64.sqrt() && lambda <= 1e1);
        // A soft direction below the floor is lifted to it.
        let soft = [1.0, 0.0, 0.0, 1e-9];
        let lambda = factor_shifted(&soft, &mut l, 2).unwrap();
        assert!(lambda >= FLOOR);
        let nan = [f64::NAN, 0.0, 0.0, 1.0];
        assert_eq!(factor_shifted(&nan, &mut l, 2), None);
    }
}
