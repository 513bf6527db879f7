//! The sampling metric: a shape C = LLᵀ (det C = 1) that Auto learns from its models'
//! curvature, as CMA-ES learns its covariance from its population.
//!
//! Auto samples, measures reach and bounds its steps in whitened coordinates
//! u = L⁻¹(x − θ)/σ. With C ∝ |H|⁻¹ — H the model's Hessian in parameter units, its
//! eigenvalues taken by magnitude and floored at [`floor`] of the largest — an
//! ill-conditioned valley looks round in u: samples spread along its floor, the trust
//! region stretches along it, and the isotropic σ that fits the valley's width no
//! longer limits the steps along it.
//!
//! C has the model's [`Shape`]: a full model learns a full C (n×n row-major, L = Q√E
//! from C = QEQᵀ), a diagonal model a diagonal one (n floats, L = √C), which whitens
//! scales that differ per coordinate but not rotated valleys. C moves towards its target
//! by a fraction [`rate`] per update and is renormalised to det C = 1, so σ alone
//! carries the scale. A full C also follows the direction of θ's accepted steps, as
//! CMA-ES's rank-one update follows its evolution path ([`rank_one`]): a direction that
//! steps keep taking, such as a ridge's, whose precision no fitted curvature gives.

use super::eigen;
use super::model::Shape;
use crate::optim::vector::{axpy, row_block, transpose};
use crate::real::Real;
use crate::wide::avx2_twin;

/// Fraction of the way C moves towards the target of one update in dimension n:
/// 1/(2n), at most 0.3. A full C has n(n+1)/2 entries and each model's curvature is a
/// noisy view of them (a rough f's local curvature changes along the path), so like
/// CMA-ES's covariance it averages over more updates as n grows. A diagonal C has only
/// n entries, but a diagonal model's curvatures are noisier still — on a rotated f they
/// absorb the off-diagonal curvature along whatever directions were sampled — so it
/// averages at the same rate.
pub fn rate(n: usize) -> f64 {
    (0.5 / n as f64).min(0.3)
}

/// Smallest |eigenvalue| of the target's H relative to its largest, and of C relative to
/// its largest: ε^⅞ of T (2.0e-14 for f64, 8.7e-7 for f32), so that L's axes differ by
/// at most ε^(−7/16) (7.1e6 in f64) and whitening x − θ by L⁻¹ keeps all but a fraction
/// ε^(9/16) of T's precision. A sharp ridge needs the stretch: approaching its optimum,
/// the samples must run along it ever farther than across it (BBOB's f13 stalled at
/// ε^¾, whose 7.8e5 : 1 CMA-ES's covariance passes).
pub fn floor<T: Real>() -> T {
    let root = T::EPSILON.sqrt();
    root * root.sqrt() * root.sqrt().sqrt()
}

/// Sets C = diag(r²), L = diag(r) and L⁻¹ = diag(1/r) (each of [`Shape::hessian_len`]
/// floats): a shape that stretches coordinate i by rᵢ. The caller keeps Πᵢ rᵢ = 1
/// (det C = 1), so that σ alone carries the scale; r = 1 is no shape learnt.
pub fn axes<T: Real>(shape: Shape, r: &[T], c: &mut [T], l: &mut [T], li: &mut [T]) {
    let n = r.len();
    for (m, power) in [(c, 2), (l, 1), (li, -1)] {
        let entry = |x: T| match power {
            2 => x * x,
            1 => x,
            _ => T::ONE / x,
        };
        match shape {
            Shape::Full => {
                m.fill(T::ZERO);
                for (i, &x) in r.iter().enumerate() {
                    m[i * (n + 1)] = entry(x);
                }
            }
            Shape::Diagonal => {
                for (o, &x) in m.iter_mut().zip(r) {
                    *o = entry(x);
                }
            }
        }
    }
}

/// out = Md for M = L or L⁻¹ (`m`).
pub fn apply<T: Real>(shape: Shape, m: &[T], d: &[T], out: &mut [T]) {
    let n = d.len();
    match shape {
        Shape::Full => {
            for (i, o) in out.iter_mut().enumerate().take(n) {
                *o = (0..n).fold(T::ZERO, |s, j| s + m[i * n + j] * d[j]);
            }
        }
        Shape::Diagonal => {
            for ((o, &a), &b) in out.iter_mut().zip(m).zip(d) {
                *o = a * b;
            }
        }
    }
}

/// out = Mᵀd for M = L or L⁻¹ (`m`).
pub fn apply_transposed<T: Real>(shape: Shape, m: &[T], d: &[T], out: &mut [T]) {
    let n = d.len();
    match shape {
        Shape::Full => {
            for (i, o) in out.iter_mut().enumerate().take(n) {
                *o = (0..n).fold(T::ZERO, |s, k| s + m[k * n + i] * d[k]);
            }
        }
        Shape::Diagonal => apply(shape, m, d, out),
    }
}

/// out = L⁻¹(x − y), each entry a sum over j in four interleaved partial sums.
pub fn whiten<T: Real>(shape: Shape, li: &[T], x: &[T], y: &[T], out: &mut [T]) {
    let n = x.len();
    match shape {
        Shape::Full => {
            for (o, row) in out[..n].iter_mut().zip(li[..n * n].chunks_exact(n)) {
                *o = row_times_difference(row, x, y);
            }
        }
        Shape::Diagonal => {
            for (((o, &l), &xi), &yi) in out[..n].iter_mut().zip(li).zip(x).zip(y) {
                *o = l * (xi - yi);
            }
        }
    }
}

avx2_twin! {
/// Row k of `out` = L⁻¹(x_k − y) for the first `count` rows x_k of `xs` (n = `y.len()`
/// floats each): [`whiten`] of each, bit for bit, with a full L⁻¹'s rows read once for
/// [`WHITEN_BLOCK`] points.
pub fn whiten_rows<T: Real>(
    shape: Shape,
    li: &[T],
    xs: &[T],
    count: usize,
    y: &[T],
    out: &mut [T],
) {
    let n = y.len();
    let mut k0 = 0;
    if shape == Shape::Full {
        while k0 + WHITEN_BLOCK <= count {
            let x = row_block::<T, WHITEN_BLOCK>(xs, k0 * n, n, n);
            for (i, row) in li[..n * n].chunks_exact(n).enumerate() {
                let sums = rows_times_difference(row, x, y);
                for (b, &s) in sums.iter().enumerate() {
                    out[(k0 + b) * n + i] = s;
                }
            }
            k0 += WHITEN_BLOCK;
        }
    }
    for k in k0..count {
        whiten(shape, li, &xs[k * n..(k + 1) * n], y, &mut out[k * n..(k + 1) * n]);
    }
}
}

/// Points [`whiten_rows`] whitens in one pass over L⁻¹.
const WHITEN_BLOCK: usize = 4;

/// Σⱼ aⱼ(xⱼ − yⱼ) for each of R vectors `x` (n = `a.len()` floats each), in one pass over
/// `a` and `y`: four interleaved partial sums over the whole groups of four,
/// (s₀ + s₁) + (s₂ + s₃), plus the tail summed in order; each x's sum is the same
/// whatever R.
#[inline(always)]
fn rows_times_difference<T: Real, const R: usize>(a: &[T], x: [&[T]; R], y: &[T]) -> [T; R] {
    let n = a.len();
    let full = n - n % 4;
    let mut lanes = [[T::ZERO; 4]; R];
    for c in (0..full).step_by(4) {
        let (ac, yc) = (&a[c..c + 4], &y[c..c + 4]);
        for (acc, xr) in lanes.iter_mut().zip(x.iter()) {
            let xc = &xr[c..c + 4];
            for k in 0..4 {
                acc[k] += ac[k] * (xc[k] - yc[k]);
            }
        }
    }
    let mut out = [T::ZERO; R];
    for ((o, l), xr) in out.iter_mut().zip(&lanes).zip(x) {
        let tail = (full..n).fold(T::ZERO, |s, j| s + a[j] * (xr[j] - y[j]));
        *o = (l[0] + l[1]) + (l[2] + l[3]) + tail;
    }
    out
}

/// Σⱼ aⱼ(xⱼ − yⱼ) in four interleaved partial sums (as
/// [`dot_lanes`](crate::optim::vector::dot_lanes)): [`rows_times_difference`] for one x.
#[inline(always)]
fn row_times_difference<T: Real>(a: &[T], x: &[T], y: &[T]) -> T {
    rows_times_difference(a, [x], y)[0]
}

avx2_twin! {
/// out = Lᵀ H L (or L⁻ᵀ H L⁻¹ with `li`): the Hessian `h` of the same shape seen
/// through `l`, with `tmp` (n², full only) as scratch.
pub fn congruence<T: Real>(shape: Shape, l: &[T], h: &[T], n: usize, tmp: &mut [T], out: &mut [T]) {
    match shape {
        Shape::Full => {
            // tmp = H L and out = Lᵀ tmp, each row accumulated from rows of the right
            // factor (contiguous), every entry summed over k in order.
            for i in 0..n {
                let row = &mut tmp[i * n..(i + 1) * n];
                row.fill(T::ZERO);
                for k in 0..n {
                    axpy(h[i * n + k], &l[k * n..(k + 1) * n], row);
                }
            }
            for i in 0..n {
                let row = &mut out[i * n..(i + 1) * n];
                row.fill(T::ZERO);
                for k in 0..n {
                    axpy(l[k * n + i], &tmp[k * n..(k + 1) * n], row);
                }
            }
        }
        Shape::Diagonal => {
            for i in 0..n {
                out[i] = l[i] * h[i] * l[i];
            }
        }
    }
}
}

/// Scratch of [`update`] (full metrics only; empty for diagonal): `a` and `v` n×n, `w`
/// n floats.
pub struct Scratch<'a, T> {
    pub a: &'a mut [T],
    pub v: &'a mut [T],
    pub w: &'a mut [T],
}

avx2_twin! {
/// Moves C towards the shape of the curvature `h` (the model's Hessian of the same
/// shape, in parameter units, any scale) by `weight` × [`rate`] (weight in (0, 1]: how
/// far the caller trusts this curvature) and refreshes L and L⁻¹. Leaves everything
/// unchanged when `h` has no finite, non-zero curvature.
#[allow(clippy::too_many_arguments)]
pub fn update<T: Real>(
    shape: Shape,
    c: &mut [T],
    l: &mut [T],
    li: &mut [T],
    h: &[T],
    n: usize,
    weight: f64,
    scratch: Scratch<'_, T>,
) {
    let len = shape.hessian_len(n);
    if h[..len].iter().any(|x| !x.is_finite()) {
        return;
    }
    let rate = T::from_f64(rate(n) * weight);
    if shape == Shape::Diagonal {
        let Some(Targets { top, low, mean }) = Targets::of(n, |i| h[i]) else {
            return;
        };
        for i in 0..n {
            let target = top / h[i].abs().max(low);
            c[i] = (T::ONE - rate) * c[i] + rate * target / mean;
        }
        refresh_diagonal(c, l, li, n);
        return;
    }
    let Scratch { a, v, w } = scratch;
    a[..n * n].copy_from_slice(&h[..n * n]);
    eigen::symmetric(a, v, n);
    let Some(Targets { top, low, mean }) = Targets::of(n, |i| a[i]) else {
        return;
    };
    // Target C ∝ V diag(1/|λ|) Vᵀ with det 1: divide by the geometric mean.
    for i in 0..n {
        w[i] = T::ONE / a[i].abs().max(low) * top;
    }
    // Row i of the target, Σₖ (vᵢₖwₖ)vⱼₖ over k in order, accumulated from Vᵀ's rows
    // (in `a`), which are contiguous in j, in L's first row (`refresh` rewrites L).
    transpose(v, n, a);
    let target = &mut l[..n];
    for i in 0..n {
        target.fill(T::ZERO);
        for k in 0..n {
            axpy(v[i * n + k] * w[k], &a[k * n..(k + 1) * n], target);
        }
        for (cij, &t) in c[i * n..(i + 1) * n].iter_mut().zip(target.iter()) {
            *cij = (T::ONE - rate) * *cij + rate * t / mean;
        }
    }
    refresh(c, l, li, n, a, v);
}
}

/// A full C ← (1 − w)C + w·ppᵀ for a direction p (n floats) and a weight w in (0, 1),
/// then renormalised to det C = 1 with L and L⁻¹ refreshed (`a`, `v`: n² floats of
/// scratch each). Leaves everything unchanged when p is not finite.
pub fn rank_one<T: Real>(
    c: &mut [T],
    l: &mut [T],
    li: &mut [T],
    p: &[T],
    w: f64,
    a: &mut [T],
    v: &mut [T],
) {
    let n = p.len();
    if p.iter().any(|x| !x.is_finite()) {
        return;
    }
    let w = T::from_f64(w);
    for i in 0..n {
        for j in 0..n {
            c[i * n + j] = (T::ONE - w) * c[i * n + j] + w * p[i] * p[j];
        }
    }
    refresh(c, l, li, n, a, v);
}

/// A full C ← SCS for S = diag(`factors`), then renormalised to det C = 1 with L and L⁻¹
/// refreshed (`a`, `v`: n² floats of scratch each): the scale along each coordinate i
/// grows by `factors[i]` (n positive, finite floats).
pub fn stretch<T: Real>(
    c: &mut [T],
    l: &mut [T],
    li: &mut [T],
    factors: &[T],
    a: &mut [T],
    v: &mut [T],
) {
    let n = factors.len();
    for (i, &si) in factors.iter().enumerate() {
        for (j, &sj) in factors.iter().enumerate() {
            c[i * n + j] = si * c[i * n + j] * sj;
        }
    }
    refresh(c, l, li, n, a, v);
}

/// What an update's target axes top/max(|λᵢ|, low) share, for curvatures λᵢ.
struct Targets<T> {
    /// maxᵢ |λᵢ|.
    top: T,
    /// [`floor`]·top.
    low: T,
    /// The axes' geometric mean, which normalises the target to det 1.
    mean: T,
}

impl<T: Real> Targets<T> {
    /// For λᵢ = `lambda(i)`, i < n; `None` when top is zero or not finite.
    fn of(n: usize, lambda: impl Fn(usize) -> T) -> Option<Targets<T>> {
        let top = (0..n).fold(T::ZERO, |m, i| m.max(lambda(i).abs()));
        if top <= T::ZERO || !top.is_finite() {
            return None;
        }
        let low = floor::<T>() * top;
        let log_mean = (0..n).fold(T::ZERO, |s, i| {
            s + (T::ONE / lambda(i).abs().max(low) * top).ln()
        });
        Some(Targets {
            top,
            low,
            mean: (log_mean / T::from_usize(n)).exp(),
        })
    }
}

avx2_twin! {
/// Renormalises C to det 1 and sets L = Q diag(√e), L⁻¹ = diag(1/√e) Qᵀ from C = Q
/// diag(e) Qᵀ.
fn refresh<T: Real>(c: &mut [T], l: &mut [T], li: &mut [T], n: usize, a: &mut [T], v: &mut [T]) {
    a[..n * n].copy_from_slice(&c[..n * n]);
    eigen::symmetric(a, v, n);
    let top = a[..n].iter().fold(T::ZERO, |m, &x| m.max(x));
    let low = floor::<T>() * top;
    let mut log_mean = T::ZERO;
    for e in a[..n].iter_mut() {
        *e = e.max(low);
        log_mean += e.ln();
    }
    let mean = (log_mean / T::from_usize(n)).exp();
    for i in 0..n {
        let e = a[i] / mean;
        let root = e.sqrt();
        for k in 0..n {
            l[k * n + i] = v[k * n + i] * root;
            li[i * n + k] = v[k * n + i] / root;
        }
    }
    // C = LLᵀ, row i the sum Σₖ lᵢₖlⱼₖ over k in order, accumulated from Lᵀ's rows (in
    // `v`, no longer needed), which are contiguous in j.
    transpose(l, n, v);
    for i in 0..n {
        let row = &mut c[i * n..(i + 1) * n];
        row.fill(T::ZERO);
        for k in 0..n {
            axpy(l[i * n + k], &v[k * n..(k + 1) * n], row);
        }
    }
}
}

/// The diagonal [`refresh`]: C's entries floored at [`floor`] of the largest and
/// divided by their geometric mean; L = √C, L⁻¹ = 1/√C.
fn refresh_diagonal<T: Real>(c: &mut [T], l: &mut [T], li: &mut [T], n: usize) {
    let top = c[..n].iter().fold(T::ZERO, |m, &x| m.max(x));
    let low = floor::<T>() * top;
    let log_mean = c[..n].iter().fold(T::ZERO, |s, &x| s + x.max(low).ln());
    let mean = (log_mean / T::from_usize(n)).exp();
    for i in 0..n {
        c[i] = c[i].max(low) / mean;
        l[i] = c[i].sqrt();
        li[i] = T::ONE / l[i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn learns_an_ellipse_and_whitens_it() {
        let n = 2;
        // H = diag(100, 1) rotated by 30°.
        let (c30, s30) = (libm::cos(core::f64::consts::FRAC_PI_6), 0.5);
        let r = [c30, -s30, s30, c30];
        let d = [100.0, 1.0];
        let mut h = [0.0; 4];
        for i in 0..2 {
            for j in 0..2 {
                h[i * 2 + j] = (0..2).map(|k| r[i * 2 + k] * d[k] * r[j * 2 + k]).sum();
            }
        }
        let (mut c, mut l, mut li) = ([1.0, 0.0, 0.0, 1.0], [0.0; 4], [0.0; 4]);
        let (mut a, mut v, mut w) = ([0.0; 4], [0.0; 4], [0.0; 4]);
        for _ in 0..60 {
            let s = Scratch {
                a: &mut a,
                v: &mut v,
                w: &mut w,
            };
            update(Shape::Full, &mut c, &mut l, &mut li, &h, n, 1.0, s);
        }
        // LᵀHL ∝ I once C ∝ H⁻¹.
        let mut tmp = [0.0; 4];
        let mut out = [0.0; 4];
        congruence(Shape::Full, &l, &h, n, &mut tmp, &mut out);
        assert!((out[0] - out[3]).abs() < 1e-6 * out[0], "{out:?}");
        assert!(out[1].abs() < 1e-6 * out[0], "{out:?}");
        // det C = 1 and L⁻¹L = I.
        assert!((c[0] * c[3] - c[1] * c[2] - 1.0).abs() < 1e-9);
        for i in 0..2 {
            for j in 0..2 {
                let p: f64 = (0..2).map(|k| li[i * 2 + k] * l[k * 2 + j]).sum();
                assert!((p - f64::from(u8::from(i == j))).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_diagonal_metric_whitens_separable_scales() {
        let n = 4;
        let h = [1e4, 1.0, -100.0, 0.01];
        let (mut c, mut l, mut li) = ([0.0; 4], [0.0; 4], [0.0; 4]);
        axes(Shape::Diagonal, &[1.0; 4], &mut c, &mut l, &mut li);
        for _ in 0..400 {
            let s = Scratch {
                a: &mut [],
                v: &mut [],
                w: &mut [],
            };
            update(Shape::Diagonal, &mut c, &mut l, &mut li, &h, n, 1.0, s);
        }
        // LᵀHL ∝ I by magnitude once C ∝ |H|⁻¹.
        let mut out = [0.0; 4];
        congruence(Shape::Diagonal, &l, &h, n, &mut [], &mut out);
        for x in out {
            assert!((x.abs() - out[0]).abs() < 1e-6 * out[0], "{out:?}");
        }
        // det C = 1, L⁻¹L = I, and the flattest coordinate is the one L stretches most.
        assert!((c.iter().product::<f64>() - 1.0).abs() < 1e-9);
        for i in 0..n {
            assert!((l[i] * li[i] - 1.0).abs() < 1e-12);
        }
        assert_eq!(l.iter().copied().fold(0.0, f64::max), l[3]);
    }

    /// Stretching coordinates 1 and 2 of three by 2 from C = I: C ← SCS = diag(1, 4, 4),
    /// renormalised to det 1, is diag(4^(−2/3), 4^(1/3), 4^(1/3)); L Lᵀ = C, L⁻¹L = I.
    #[test]
    fn stretches_coordinates_and_keeps_det_one() {
        let n = 3;
        let (mut c, mut l, mut li) = ([0.0; 9], [0.0; 9], [0.0; 9]);
        axes(Shape::Full, &[1.0; 3], &mut c, &mut l, &mut li);
        let (mut a, mut v) = ([0.0; 9], [0.0; 9]);
        stretch(&mut c, &mut l, &mut li, &[1.0, 2.0, 2.0], &mut a, &mut v);
        let expected = [libm::pow(4.0, -2.0 / 3.0), libm::cbrt(4.0), libm::cbrt(4.0)];
        for i in 0..n {
            for j in 0..n {
                let want = if i == j { expected[i] } else { 0.0 };
                assert!((c[i * n + j] - want).abs() < 1e-12, "C = {c:?}");
                let llt: f64 = (0..n).map(|k| l[i * n + k] * l[j * n + k]).sum();
                assert!((llt - want).abs() < 1e-12, "L = {l:?}");
                let p: f64 = (0..n).map(|k| li[i * n + k] * l[k * n + j]).sum();
                assert!((p - f64::from(u8::from(i == j))).abs() < 1e-12);
            }
        }
    }

    /// From C = I, (1 − w)I + w·ppᵀ has eigenvalue 1 − w + w‖p‖² along p and 1 − w
    /// across it; divided by their geometric mean, det C = 1.
    #[test]
    fn a_rank_one_update_stretches_along_the_direction_and_keeps_det_one() {
        let n = 3;
        let (mut c, mut l, mut li) = ([0.0; 9], [0.0; 9], [0.0; 9]);
        axes(Shape::Full, &[1.0; 3], &mut c, &mut l, &mut li);
        let (mut a, mut v) = ([0.0; 9], [0.0; 9]);
        let p = [0.0, 3.0, 4.0];
        let w = 0.2;
        rank_one(&mut c, &mut l, &mut li, &p, w, &mut a, &mut v);
        let (along, across) = (1.0 - w + w * 25.0, 1.0 - w);
        let mean = libm::cbrt(along * across * across);
        let unit = [0.0, 0.6, 0.8];
        for i in 0..n {
            for j in 0..n {
                let identity = f64::from(u8::from(i == j));
                let want = (across * identity + (along - across) * unit[i] * unit[j]) / mean;
                assert!((c[i * n + j] - want).abs() < 1e-12, "C = {c:?}");
                let llt: f64 = (0..n).map(|k| l[i * n + k] * l[j * n + k]).sum();
                assert!((llt - want).abs() < 1e-12, "L = {l:?}");
            }
        }
        let before = c;
        rank_one(
            &mut c,
            &mut l,
            &mut li,
            &[f64::NAN, 0.0, 0.0],
            w,
            &mut a,
            &mut v,
        );
        assert_eq!(c, before);
    }
}
