//! Eigen-decomposition of a small dense symmetric matrix, A = V diag(λ) Vᵀ.
//!
//! Two stages, both orthogonal transformations and so backward stable:
//!
//! 1. **Householder tridiagonalisation.** For k = 0 … n − 3 the reflector
//!    Pₖ = I − βuuᵀ (β = 2/uᵀu) maps column k below the diagonal onto its first entry,
//!    so that T = Qᵀ A Q is tridiagonal with Q = P₀P₁⋯Pₙ₋₃. Applied to the trailing block
//!    B as B ← B − uwᵀ − wuᵀ with p = βBu, w = p − (βuᵀp/2)u: O(n³) with a small constant.
//! 2. **Implicit QL iterations** on T with Wilkinson's shift (the eigenvalue of the
//!    leading 2×2 block nearer its corner), chasing the bulge by plane rotations that
//!    are accumulated into the columns of Q; an off-diagonal entry counts as zero once
//!    it is below ε(|dᵢ| + |dᵢ₊₁|). Convergence is cubic for almost every matrix; a
//!    matrix that has not converged after [`MAX_ITERATIONS`] per eigenvalue keeps the
//!    finite estimates reached.
//!
//! Cost: about 3n³ multiplications (Jacobi rotations need ~6n³ per sweep, and several
//! sweeps); [`eigenvalues`] alone, without the eigenvectors, about n³.

use crate::real::Real;

/// QL iterations per eigenvalue before its estimate is accepted as it stands.
const MAX_ITERATIONS: usize = 60;

/// Eigen-decomposes the symmetric row-major n×n `a` (its whole square is read; it is
/// overwritten): on return `a[..n]` holds the eigenvalues, unordered, and `v` (n×n,
/// row-major) the orthonormal eigenvectors as columns, column j belonging to `a[j]`.
/// Non-finite entries give non-finite results.
///
/// Compiled for the build's target only, and never inlined, so that the AVX2 copies of
/// the kernels that call it ([`crate::wide`]) do not take it in: its AVX2 copy ran
/// several times slower (BENCHMARKS.md, "Auto's own cost in Rust").
#[inline(never)]
pub(super) fn symmetric<T: Real>(a: &mut [T], v: &mut [T], n: usize) {
    if n == 1 {
        v[0] = T::ONE;
        return;
    }
    if n == 0 {
        return;
    }
    v[..n * n].copy_from_slice(&a[..n * n]);
    let (d, rest) = a.split_at_mut(n);
    let e = &mut rest[..n];
    reduce(v, n, d, e);
    form_q(v, n);
    // QL rotates pairs of Q's columns: they are rows of Qᵀ, contiguous.
    transpose(v, n);
    ql(Some(v), n, d, e);
    transpose(v, n);
}

/// The eigenvalues of the symmetric row-major n×n `a` (its whole square is read and
/// overwritten), unordered, in `a[..n]`: [`symmetric`]'s, bit for bit, without the
/// eigenvectors, whose accumulation is most of its cost: the reduction to tridiagonal
/// form, about n³ multiplications of its 3n³, and QL iterations of O(n²). `work` holds
/// at least n² floats. Non-finite entries give non-finite results. Never inlined, for
/// [`symmetric`]'s reason.
#[inline(never)]
pub(super) fn eigenvalues<T: Real>(a: &mut [T], work: &mut [T], n: usize) {
    if n <= 1 {
        return;
    }
    work[..n * n].copy_from_slice(&a[..n * n]);
    let (d, rest) = a.split_at_mut(n);
    let e = &mut rest[..n];
    reduce(work, n, d, e);
    ql(None, n, d, e);
}

/// Transposes the row-major n×n `m` in place.
fn transpose<T: Real>(m: &mut [T], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            m.swap(i * n + j, j * n + i);
        }
    }
}

/// Reduces the symmetric `q` (n ≥ 2) to tridiagonal form T = Qᵀ A Q: on return `d` holds
/// T's diagonal, `e[i]` (i ≥ 1) its entry `T[i][i−1]` (`e[0]` = 0), and column k of `q`
/// below the diagonal the reflector Pₖ's vector uₖ, from which [`form_q`] builds Q.
#[inline(always)]
fn reduce<T: Real>(q: &mut [T], n: usize, d: &mut [T], e: &mut [T]) {
    // Reflectors: uₖ is stored in column k below the diagonal (rows k + 1 …), unscaled;
    // β is recomputed from it. The work vector p lives in `d` (its entries k + 1 … are
    // not yet final).
    for k in 0..n.saturating_sub(2) {
        let scale = (k + 1..n).fold(T::ZERO, |s, i| s.max(q[i * n + k].abs()));
        d[k] = q[k * n + k];
        if scale == T::ZERO || !scale.is_finite() {
            e[k + 1] = q[(k + 1) * n + k];
            for i in k + 1..n {
                q[i * n + k] = T::ZERO;
            }
            continue;
        }
        for i in k + 1..n {
            q[i * n + k] /= scale;
        }
        let norm = (k + 1..n)
            .fold(T::ZERO, |s, i| s + q[i * n + k].sq())
            .sqrt();
        let head = q[(k + 1) * n + k];
        // u = x − αe₁ with α = −sign(x₁)‖x‖: no cancellation in u₁ = x₁ + sign(x₁)‖x‖.
        let alpha = if head < T::ZERO { norm } else { -norm };
        q[(k + 1) * n + k] = head - alpha;
        e[k + 1] = alpha * scale;
        // uᵀu = 2‖x‖(‖x‖ + |x₁|).
        let beta = T::ONE / (norm * (norm + head.abs()));
        // A copy of u in row k (columns k + 1 …), which no later stage reads, so that the
        // products below run along rows.
        for i in k + 1..n {
            q[k * n + i] = q[i * n + k];
        }
        let (upper, trailing) = q[..n * n].split_at_mut((k + 1) * n);
        let u = &upper[k * n + k + 1..];
        // p = βBu over the trailing block B (rows and columns k + 1 …).
        for (i, row) in trailing.chunks_exact(n).enumerate() {
            let row = &row[k + 1..];
            d[k + 1 + i] = beta * row.iter().zip(u).fold(T::ZERO, |s, (&b, &x)| s + b * x);
        }
        let w = &mut d[k + 1..n];
        let half = T::HALF
            * beta
            * u.iter()
                .zip(w.iter())
                .fold(T::ZERO, |s, (&x, &p)| s + x * p);
        for (wi, &ui) in w.iter_mut().zip(u) {
            *wi -= half * ui;
        }
        // B ← B − uwᵀ − wuᵀ, w now in d.
        for (row, (&ui, &wi)) in trailing.chunks_exact_mut(n).zip(u.iter().zip(w.iter())) {
            for (b, (&uj, &wj)) in row[k + 1..].iter_mut().zip(u.iter().zip(w.iter())) {
                *b -= ui * wj + wi * uj;
            }
        }
    }
    d[n - 2] = q[(n - 2) * n + n - 2];
    d[n - 1] = q[(n - 1) * n + n - 1];
    e[n - 1] = q[(n - 1) * n + n - 2];
    e[0] = T::ZERO;
}

/// Overwrites `q`, as [`reduce`] left it (n ≥ 2), with the orthogonal Q = P₀P₁⋯Pₙ₋₃ of
/// A = Q T Qᵀ.
#[inline(always)]
fn form_q<T: Real>(q: &mut [T], n: usize) {
    // Q = P₀(P₁(⋯Pₙ₋₃)), built from the last reflector back: before Pₖ is applied, Q
    // differs from I only in rows and columns ≥ k + 2, and uₖ (column k) is outside that.
    q[(n - 1) * n + n - 1] = T::ONE;
    for k in (0..n.saturating_sub(2)).rev() {
        let c = k + 1;
        q[c * n + c] = T::ONE;
        for j in c + 1..n {
            q[c * n + j] = T::ZERO;
            q[j * n + c] = T::ZERO;
        }
        let uu = (c..n).fold(T::ZERO, |s, i| s + q[i * n + k].sq());
        if uu == T::ZERO {
            continue;
        }
        let beta = T::TWO / uu;
        // t = βuᵀQ over columns c …, summed down the rows in row k (columns c …), which
        // held u's copy and is reset to I's row before it is read again.
        let (upper, trailing) = q[..n * n].split_at_mut(c * n);
        let t = &mut upper[k * n + c..];
        t.fill(T::ZERO);
        for i in c..n {
            let ui = trailing[(i - c) * n + k];
            for (tj, &x) in t
                .iter_mut()
                .zip(&trailing[(i - c) * n + c..(i - c + 1) * n])
            {
                *tj += ui * x;
            }
        }
        for tj in t.iter_mut() {
            *tj *= beta;
        }
        for row in trailing.chunks_exact_mut(n) {
            let ui = row[k];
            for (x, &tj) in row[c..].iter_mut().zip(t.iter()) {
                *x -= tj * ui;
            }
        }
    }
    q[0] = T::ONE;
    for j in 1..n {
        q[j] = T::ZERO;
        q[j * n] = T::ZERO;
    }
}

/// Diagonalises the symmetric tridiagonal T (diagonal `d`, sub-diagonal `e[1..]`) by
/// implicit QL iterations, rotating the rows of `qt` (Qᵀ), where given, along: on return
/// `d` holds the eigenvalues and the rows of `qt` the eigenvectors of Q T Qᵀ. The
/// rotations applied to `d` and `e` do not depend on `qt`.
#[inline(always)]
fn ql<T: Real>(mut qt: Option<&mut [T]>, n: usize, d: &mut [T], e: &mut [T]) {
    // e[i] = T[i+1][i] from here on.
    for i in 1..n {
        e[i - 1] = e[i];
    }
    e[n - 1] = T::ZERO;
    for l in 0..n {
        for _ in 0..MAX_ITERATIONS {
            // The first negligible off-diagonal entry at or after l splits T there.
            let Some(m) = (l..n - 1)
                .find(|&m| e[m].abs() <= T::EPSILON * (d[m].abs() + d[m + 1].abs()))
                .or(Some(n - 1))
                .filter(|&m| m != l)
            else {
                break;
            };
            // Wilkinson's shift from the 2×2 block at l.
            let g = (d[l + 1] - d[l]) / (T::TWO * e[l]);
            let r = hypot(g, T::ONE);
            let root = if g < T::ZERO { -r } else { r };
            let mut g = d[m] - d[l] + e[l] / (g + root);
            let (mut s, mut c, mut p) = (T::ONE, T::ONE, T::ZERO);
            let mut deflated = false;
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                let r = hypot(f, g);
                e[i + 1] = r;
                if r == T::ZERO {
                    // An exact zero split T: undo the shift's remainder and start over.
                    d[i + 1] -= p;
                    e[m] = T::ZERO;
                    deflated = true;
                    break;
                }
                s = f / r;
                c = g / r;
                let h = d[i + 1] - p;
                let t = (d[i] - h) * s + T::TWO * c * b;
                p = s * t;
                d[i + 1] = h + p;
                g = c * t - b;
                if let Some(qt) = qt.as_deref_mut() {
                    let (first, second) = qt[i * n..(i + 2) * n].split_at_mut(n);
                    for (x, y) in first.iter_mut().zip(second.iter_mut()) {
                        (*x, *y) = (c * *x - s * *y, s * *x + c * *y);
                    }
                }
            }
            if !deflated {
                d[l] -= p;
                e[l] = g;
                e[m] = T::ZERO;
            }
        }
    }
}

/// √(x² + y²) without overflow or underflow in the squares.
#[inline(always)]
fn hypot<T: Real>(x: T, y: T) -> T {
    let (x, y) = (x.abs(), y.abs());
    let big = x.max(y);
    if big == T::ZERO || !big.is_finite() {
        return big + x.min(y);
    }
    let small = x.min(y) / big;
    big * (T::ONE + small.sq()).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest n tested.
    const N: usize = 24;

    /// A = V diag(λ) Vᵀ and VᵀV = I, to `tol` relative to max |Aᵢⱼ|.
    fn check(a: &[f64], n: usize, tol: f64) {
        let mut w = [0.0; N * N];
        w[..n * n].copy_from_slice(&a[..n * n]);
        let mut v = [0.0; N * N];
        symmetric(&mut w, &mut v, n);
        let scale = a[..n * n]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        for i in 0..n {
            for j in 0..n {
                let back: f64 = (0..n).map(|k| v[i * n + k] * w[k] * v[j * n + k]).sum();
                assert!(
                    (back - a[i * n + j]).abs() <= tol * scale,
                    "n {n} A[{i}][{j}] {} rebuilt {back}",
                    a[i * n + j]
                );
                let dot: f64 = (0..n).map(|k| v[k * n + i] * v[k * n + j]).sum();
                let id = if i == j { 1.0 } else { 0.0 };
                assert!((dot - id).abs() <= tol, "n {n} VᵀV[{i}][{j}] = {dot}");
            }
        }
    }

    /// A symmetric n×n matrix of uniform entries times 10^(spread·uniform).
    fn random_symmetric(n: usize, mut state: u64, spread: f64) -> [f64; N * N] {
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut a = [0.0; N * N];
        for i in 0..n {
            for j in 0..=i {
                let x = next() * libm::pow(10.0, spread * next());
                a[i * n + j] = x;
                a[j * n + i] = x;
            }
        }
        a
    }

    /// The n×n matrix with `diagonal` on its diagonal and `off` beside it.
    fn tridiagonal(n: usize, diagonal: f64, off: f64) -> [f64; N * N] {
        let mut a = [0.0; N * N];
        for i in 0..n {
            a[i * n + i] = diagonal;
            if i + 1 < n {
                a[i * n + i + 1] = off;
                a[(i + 1) * n + i] = off;
            }
        }
        a
    }

    #[test]
    fn decomposes_random_matrices() {
        for n in 1..=N {
            for seed in 1..6u64 {
                check(&random_symmetric(n, seed * 977 + n as u64, 0.0), n, 1e-12);
                check(&random_symmetric(n, seed * 131 + n as u64, 8.0), n, 1e-12);
            }
        }
    }

    #[test]
    fn decomposes_degenerate_and_extreme_matrices() {
        let n = 6;
        let mut rank_one = [0.0; N * N];
        let mut diagonal = [0.0; N * N];
        for i in 0..n {
            diagonal[i * n + i] = -(i as f64);
            for j in 0..n {
                rank_one[i * n + j] = ((i + 1) * (j + 1)) as f64;
            }
        }
        let mut huge = random_symmetric(n, 7, 0.0);
        let mut tiny = huge;
        for (h, t) in huge.iter_mut().zip(tiny.iter_mut()) {
            *h *= 1e150;
            *t *= 1e-150;
        }
        let cases = [
            [0.0; N * N],
            tridiagonal(n, 1.0, 0.0),
            tridiagonal(n, 2.0, -1.0),
            rank_one,
            diagonal,
            huge,
            tiny,
        ];
        for a in &cases {
            check(a, n, 1e-12);
        }
    }

    /// [`eigenvalues`] gives [`symmetric`]'s eigenvalues bit for bit.
    #[test]
    fn eigenvalues_alone_are_the_decompositions() {
        for n in 1..=N {
            for (seed, spread) in [(3u64, 0.0), (5, 8.0)] {
                let a = random_symmetric(n, seed * 613 + n as u64, spread);
                let (mut full, mut alone) = (a, a);
                let (mut v, mut work) = ([0.0; N * N], [0.0; N * N]);
                symmetric(&mut full, &mut v, n);
                eigenvalues(&mut alone, &mut work, n);
                for (x, y) in full[..n].iter().zip(&alone[..n]) {
                    assert_eq!(x.to_bits(), y.to_bits(), "n {n}: {x} against {y}");
                }
            }
        }
    }

    #[test]
    fn eigenvalues_of_a_known_matrix() {
        // The second-difference matrix: λₖ = 2 − 2cos(kπ/(n + 1)), k = 1 … n.
        let n = 9;
        let mut a = tridiagonal(n, 2.0, -1.0);
        let mut v = [0.0; N * N];
        symmetric(&mut a, &mut v, n);
        for k in 1..=n {
            let want = 2.0 - 2.0 * libm::cos(k as f64 * core::f64::consts::PI / (n + 1) as f64);
            let closest = a[..n]
                .iter()
                .fold(f64::MAX, |m, &l| m.min((l - want).abs()));
            assert!(closest < 1e-13, "λ{k} = {want} missing from {:?}", &a[..n]);
        }
    }
}
