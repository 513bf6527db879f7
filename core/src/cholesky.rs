//! Cholesky factorisation: plain, for the regression estimators' sample moment matrix,
//! and with a growing diagonal shift, for Newton steps on estimated (noisy, possibly
//! indefinite) Hessians.

use crate::optim::vector::{axpy, dot_lanes, dot_lanes_many, row_block};
use crate::real::Real;
use crate::wide::avx2_twin;

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
    factor_rows(a, n, 0, n, lambda)
}

/// Rows from which [`factor_rows`] runs its AVX2 copy (where the CPU has it): the
/// dot products of shorter rows are too short for the wider lanes to repay their
/// set-up, and the baseline copy is the faster one there. Both copies give the same
/// factor, bit for bit, so the choice changes no result.
const WIDE_MIN_ROWS: usize = 192;

avx2_twin! {
wide_when(to >= WIDE_MIN_ROWS);
/// Rows `from..to` of [`factor_in_place`]'s factor, for a lower triangle stored by rows
/// `stride` floats apart, whose rows before `from` already hold L's: row i of L depends
/// only on A's rows up to i, so a factor extended by rows is the one factored whole, bit
/// for bit. False if a pivot is not positive and finite (then rows `from..to` hold no
/// meaningful values). Its AVX2 copy runs from [`WIDE_MIN_ROWS`] rows on.
pub(crate) fn factor_rows<T: Real>(
    a: &mut [T],
    stride: usize,
    from: usize,
    to: usize,
    lambda: T,
) -> bool {
    // Rows are taken BLOCK at a time: their entries left of the block need the same
    // finished rows of L, so each of those is read once for the whole block
    // ([`dot_lanes_many`]); every entry is computed exactly as row by row.
    let mut start = from;
    while start + BLOCK <= to {
        let (done, rest) = a.split_at_mut(start * stride);
        for j in 0..start {
            let lj = &done[j * stride..j * stride + j + 1];
            let dots = dot_lanes_many(row_block::<T, BLOCK>(rest, 0, stride, j), lj, j);
            for (b, d) in dots.into_iter().enumerate() {
                let x = &mut rest[b * stride + j];
                *x = (*x - d) / lj[j];
            }
        }
        for i in start..start + BLOCK {
            if !finish_row(a, stride, i, start, lambda) {
                return false;
            }
        }
        start += BLOCK;
    }
    (start..to).all(|i| finish_row(a, stride, i, 0, lambda))
}
}

/// Rows factored together by [`factor_rows`].
const BLOCK: usize = 4;

/// Row i of [`factor_rows`]'s L from entry `from` on (those before it done), and its
/// pivot; false if the pivot is not positive and finite.
#[inline(always)]
fn finish_row<T: Real>(a: &mut [T], stride: usize, i: usize, from: usize, lambda: T) -> bool {
    let (done, rest) = a.split_at_mut(i * stride);
    let row = &mut rest[..=i];
    for j in from..i {
        let lj = &done[j * stride..j * stride + j + 1];
        row[j] = (row[j] - dot_lanes(&row[..j], &lj[..j])) / lj[j];
    }
    let s = row[i] + lambda - dot_lanes(&row[..i], &row[..i]);
    if !(s > T::ZERO && s.is_finite()) {
        return false;
    }
    row[i] = s.sqrt();
    true
}

/// Solves LLᵀx = b in place (`x` holds b on entry): [`forward`], then [`backward`].
pub(crate) fn solve<T: Real>(l: &[T], n: usize, x: &mut [T]) {
    forward(l, n, n, x);
    backward(l, n, n, x);
}

/// Solves Lx = b in place, by rows of the n×n L stored `stride` floats apart.
pub(crate) fn forward<T: Real>(l: &[T], n: usize, stride: usize, x: &mut [T]) {
    for i in 0..n {
        let row = &l[i * stride..i * stride + i + 1];
        x[i] = (x[i] - dot_lanes(&row[..i], &x[..i])) / row[i];
    }
}

/// Solves Lᵀx = b in place, by rows of L too (columns of Lᵀ), so that L is read
/// contiguously (rows `stride` floats apart).
pub(crate) fn backward<T: Real>(l: &[T], n: usize, stride: usize, x: &mut [T]) {
    for i in (0..n).rev() {
        let row = &l[i * stride..i * stride + i + 1];
        let xi = x[i] / row[i];
        x[i] = xi;
        axpy(-xi, &row[..i], &mut x[..i]);
    }
}

avx2_twin! {
/// Solves LX = B in place for the n×k row-major `x` (B on entry), L's rows `stride`
/// floats apart: [`forward`] for k right-hand sides at once, each row of L read once and
/// each update a row operation on k contiguous values. Rows of X before `from` must
/// already hold the solution's (row i depends only on rows up to i); they are kept.
#[cfg(feature = "auto")]
pub(crate) fn forward_many<T: Real>(
    l: &[T],
    n: usize,
    stride: usize,
    from: usize,
    x: &mut [T],
    k: usize,
) {
    for i in from..n {
        let row = &l[i * stride..i * stride + i + 1];
        let (done, rest) = x.split_at_mut(i * k);
        let xi = &mut rest[..k];
        for (j, &lij) in row[..i].iter().enumerate() {
            axpy(-lij, &done[j * k..(j + 1) * k], xi);
        }
        for v in xi.iter_mut() {
            *v /= row[i];
        }
    }
}
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The factor of an SPD matrix whose size is not a multiple of the row block
    /// reproduces it (LLᵀ = A), so the blocked rows and the rows after them are right.
    #[test]
    fn factors_past_whole_blocks() {
        const N: usize = 11;
        // A = BBᵀ + I for a fixed B.
        let b: [f64; N * N] = core::array::from_fn(|k| libm::sin(k as f64 * 0.37 + 0.1));
        let mut a = [0.0; N * N];
        for i in 0..N {
            for j in 0..N {
                let s: f64 = (0..N).map(|k| b[i * N + k] * b[j * N + k]).sum();
                a[i * N + j] = s + if i == j { 1.0 } else { 0.0 };
            }
        }
        let mut l = a;
        assert!(factor_in_place(&mut l, N, 0.0));
        for i in 0..N {
            for j in 0..=i {
                let s: f64 = (0..=j).map(|k| l[i * N + k] * l[j * N + k]).sum();
                assert!((s - a[i * N + j]).abs() < 1e-12 * 20.0, "({i}, {j})");
            }
        }
        let mut indefinite = a;
        indefinite[5 * N + 5] = -100.0;
        assert!(!factor_in_place(&mut indefinite, N, 0.0));
    }

    #[test]
    #[cfg(feature = "hessian")]
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
