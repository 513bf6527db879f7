//! Small dense vector helpers for the optimisers.

// The curvature-based optimisers (feature `cg`) use all of them; smaller builds some.
#![cfg_attr(not(feature = "newton-cg"), allow(dead_code))]

use crate::real::Real;
use crate::wide::avx2_twin;

/// xᵀy.
#[inline]
pub(crate) fn dot<T: Real>(x: &[T], y: &[T]) -> T {
    x.iter().zip(y).fold(T::ZERO, |s, (&a, &b)| s + a * b)
}

/// xᵀy summed in four interleaved partial sums, (s₀ + s₁) + (s₂ + s₃) plus the tail:
/// independent sums the compiler keeps in vector registers, where [`dot`]'s single
/// running sum is a chain of dependent additions. For the long products of O(m³)
/// kernels (Auto's model fit); its rounding differs from [`dot`]'s.
#[inline(always)]
pub(crate) fn dot_lanes<T: Real>(x: &[T], y: &[T]) -> T {
    let mut lanes = [T::ZERO; 4];
    let (xs, ys) = (x.chunks_exact(4), y.chunks_exact(4));
    let tail = xs
        .remainder()
        .iter()
        .zip(ys.remainder())
        .fold(T::ZERO, |s, (&a, &b)| s + a * b);
    for (a, b) in xs.zip(ys) {
        for k in 0..4 {
            lanes[k] += a[k] * b[k];
        }
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

/// The R slices `data[start + b·stride ..][..len]`, b = 0 … R − 1: the rows a blocked
/// kernel reads together. Filled in a loop, as the blocked kernels fill their arrays of R
/// results: closures of `core::array::from_fn` were not inlined into the kernels' AVX2
/// copies and cost a call per entry.
#[inline(always)]
pub(crate) fn row_block<T, const R: usize>(
    data: &[T],
    start: usize,
    stride: usize,
    len: usize,
) -> [&[T]; R] {
    let mut rows: [&[T]; R] = [&[]; R];
    for (b, row) in rows.iter_mut().enumerate() {
        let first = start + b * stride;
        *row = &data[first..first + len];
    }
    rows
}

/// [`dot_lanes`] of the first `len` elements of each of R vectors `xs` with `y`'s, in
/// one pass over y. Each product is summed in the same lanes and order whatever R, so
/// its result does not depend on the block it is computed in, while each element of y
/// is loaded once for R products instead of R times.
#[inline(always)]
pub(crate) fn dot_lanes_many<T: Real, const R: usize>(
    xs: [&[T]; R],
    y: &[T],
    len: usize,
) -> [T; R] {
    let mut lanes = [[T::ZERO; 4]; R];
    let full = len - len % 4;
    for c in (0..full).step_by(4) {
        let b = &y[c..c + 4];
        for (acc, x) in lanes.iter_mut().zip(xs.iter()) {
            let a = &x[c..c + 4];
            for k in 0..4 {
                acc[k] += a[k] * b[k];
            }
        }
    }
    let mut out = [T::ZERO; R];
    for ((o, acc), x) in out.iter_mut().zip(lanes.iter()).zip(xs.iter()) {
        let tail = x[full..len]
            .iter()
            .zip(&y[full..len])
            .fold(T::ZERO, |s, (&a, &b)| s + a * b);
        *o = (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail;
    }
    out
}

avx2_twin! {
/// out = Md for the n×n row-major M given its transpose `mt` = Mᵀ (n = `d.len()`),
/// accumulated column by column: each entry is the sum Σⱼ Mᵢⱼdⱼ in the order j = 0, 1, …
/// that a row-by-row product takes, while the loop runs over M's contiguous columns and
/// vectorises.
pub(crate) fn mat_vec_by_columns<T: Real>(mt: &[T], d: &[T], out: &mut [T]) {
    let n = d.len();
    out[..n].fill(T::ZERO);
    for (&dj, column) in d.iter().zip(mt.chunks_exact(n)) {
        axpy(dj, column, &mut out[..n]);
    }
}
}

/// out = Mᵀ for the n×n row-major M.
pub(crate) fn transpose<T: Real>(m: &[T], n: usize, out: &mut [T]) {
    for i in 0..n {
        for j in 0..n {
            out[j * n + i] = m[i * n + j];
        }
    }
}

/// ‖x‖₂, scaled by max |xᵢ| so that it neither overflows nor underflows.
pub(crate) fn norm<T: Real>(x: &[T]) -> T {
    let big = x.iter().fold(T::ZERO, |m, &v| m.max(v.abs()));
    if big == T::ZERO || !big.is_finite() {
        return big;
    }
    big * x.iter().fold(T::ZERO, |s, &v| s + (v / big).sq()).sqrt()
}

/// y ← y + a·x.
#[inline(always)]
pub(crate) fn axpy<T: Real>(a: T, x: &[T], y: &mut [T]) {
    for (yi, &xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// Removes from row `k` of the row-major `rows` (rows of `n`) its components along the
/// k rows before it, which must be orthonormal: Gram–Schmidt, `passes` times (a second
/// pass restores the orthogonality rounding loses where the row nearly lies in their
/// span), adding each coefficient along row p to `coefficients[p]` when given. Returns
/// the length of what remains; the row is not normalised.
#[cfg(feature = "auto")]
pub(crate) fn orthogonalise<T: Real>(
    rows: &mut [T],
    k: usize,
    n: usize,
    passes: usize,
    mut coefficients: Option<&mut [T]>,
) -> T {
    let (done, rest) = rows.split_at_mut(k * n);
    let row = &mut rest[..n];
    for _ in 0..passes {
        for p in 0..k {
            let b = &done[p * n..(p + 1) * n];
            let c = dot(row, b);
            axpy(-c, b, row);
            if let Some(sums) = coefficients.as_deref_mut() {
                sums[p] += c;
            }
        }
    }
    norm(row)
}

/// ‖x − y‖₂.
pub(crate) fn distance<T: Real>(x: &[T], y: &[T]) -> T {
    let big = x
        .iter()
        .zip(y)
        .fold(T::ZERO, |m, (&a, &b)| m.max((a - b).abs()));
    if big == T::ZERO || !big.is_finite() {
        return big;
    }
    big * x
        .iter()
        .zip(y)
        .fold(T::ZERO, |s, (&a, &b)| s + ((a - b) / big).sq())
        .sqrt()
}

/// The τ ≥ 0 with ‖z + τd‖ = Δ, for ‖z‖ ≤ Δ and d ≠ 0 (the trust-region boundary).
/// Uses the cancellation-free root of aτ² + bτ + c = 0 with c ≤ 0.
pub(crate) fn to_boundary<T: Real>(z: &[T], d: &[T], radius: T) -> T {
    let a = dot(d, d);
    if a == T::ZERO {
        return T::ZERO;
    }
    let b = T::TWO * dot(z, d);
    let c = (dot(z, z) - radius.sq()).min(T::ZERO);
    let disc = (b.sq() - T::from_f64(4.0) * a * c).max(T::ZERO).sqrt();
    if b <= T::ZERO {
        (disc - b) / (T::TWO * a)
    } else {
        // τ = 2c/(−b − √disc), the same root without subtracting near-equal numbers.
        let den = -b - disc;
        if den == T::ZERO {
            T::ZERO
        } else {
            T::TWO * c / den
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundary_step_lands_on_the_sphere() {
        let z = [0.3, -0.2];
        for d in [[1.0, 0.5], [-1.0, 0.1], [0.0, -2.0]] {
            let tau = to_boundary(&z, &d, 1.5);
            let p = [z[0] + tau * d[0], z[1] + tau * d[1]];
            assert!(tau >= 0.0);
            assert!((norm(&p) - 1.5).abs() < 1e-12);
        }
        assert!((norm(&[3e200f64, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
        assert!((norm(&[3e-200f64, 4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
    }

    /// A product computed in a block is the one computed alone, bit for bit, at every
    /// length (whole lanes, a tail, both), and matches the plain sum to rounding.
    #[test]
    fn products_in_a_block_are_the_products_alone() {
        let x: [f64; 23] = core::array::from_fn(|i| libm::sin(i as f64 * 1.7) * 1e3);
        let rows: [[f64; 23]; 3] =
            core::array::from_fn(|r| core::array::from_fn(|i| libm::cos((i * (r + 2)) as f64)));
        for len in [0, 1, 3, 4, 7, 8, 21, 23] {
            let block = dot_lanes_many([&rows[0][..], &rows[1][..], &rows[2][..]], &x, len);
            for (r, row) in rows.iter().enumerate() {
                let alone = dot_lanes(&row[..len], &x[..len]);
                assert_eq!(block[r].to_bits(), alone.to_bits(), "len {len}, row {r}");
                assert!((alone - dot(&row[..len], &x[..len])).abs() <= 1e-9 * 2e4);
            }
        }
    }
}
