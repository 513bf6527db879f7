//! The local quadratic model: a kernel ridge regression of f on the remembered points.
//!
//! In standardised offsets u = (x − θ)/σ, with values v = (f(x) − f(θ))/F scaled by the
//! spread F of the nearby values, the model is
//!
//! m(u) = c + gᵀu + ½uᵀHu,
//!
//! fitted by weighted least squares with its coefficients drawn towards a prior model m₀
//! (the previous iteration's, moved to the current θ and σ):
//!
//! minimise Σᵢ wᵢ (m(uᵢ) − vᵢ)² + λ_H ‖H − H₀‖_F², with c and g free
//!
//! (for a diagonal H, a penalty on g's change and a split of H's, below).
//!
//! Where the points determine the model, the data decide; where they do not (fewer
//! points than the model's coefficients), the model changes least from the prior: the
//! least-change principle of Powell's NEWUOA, so curvature learnt on earlier iterations is
//! kept. With the weights wᵢ, a Gaussian of the distance to θ at the scale of σ, an
//! overdetermined fit is a local polynomial regression whose linear and quadratic
//! coefficients estimate the smoothed function's gradient and Hessian: points averaged
//! over the kernel, as hodr's estimators average samples.
//!
//! The fit is solved in its dual (kernel) form, an m×m system for m points, so that its
//! cost does not depend on the number of coefficients: with ψᵢ the weighted penalised
//! features, K = ΨΨᵀ/λ_H + I and P the weighted free features, the saddle system
//! K α + P β = r, Pᵀα = 0 ([`fit`]).
//!
//! * **Full Hessian** (n ≤ [`super::FULL_MODEL_MAX_DIM`]): H = h̄I + diag(d) + D, a
//!   common curvature h̄ (feature ½‖u‖²), per-axis deviations d (features ½uⱼ², weighted
//!   by ω) and a full symmetric deviation D (the quadratic features), so ψ's inner
//!   product is (‖a‖²‖b‖² + ωΣⱼ aⱼ²bⱼ² + (a·b)²)/4, and P = √wᵢ(1, uᵢ). Every point
//!   informs h̄, so a few points fix the curvature's scale in all directions — where the
//!   metric has made f round, nearly all of H — while D keeps what was learnt along the
//!   directions not sampled. Where the memory determines the model (n ≤ 14) ω = 0;
//!   above, ω = n, so that a fit with fewer points than coefficients puts the
//!   curvature it finds on the whitened axes first and spreads it across them only as
//!   far as its points demand: a separable f's curvatures, which differ by 10⁶ on an
//!   ellipsoid, are then learnt from as few points as the diagonal model needs, where D
//!   alone learnt them direction by direction (the whitened axes are C's eigenvectors,
//!   so once C fits f they are f's own). The Hessian moves by
//!   (1/(2λ_H)) Σᵢ √wᵢ αᵢ (uᵢuᵢᵀ + ‖uᵢ‖²I + ω diag(uᵢ²)).
//! * **Diagonal Hessian** (large n): H = h̄I + diag(d), a common curvature h̄ (feature
//!   ½‖u‖²) and per-coordinate deviations d (features ½uⱼ², weighted by ω), and the
//!   gradient is penalised too (features u), so that P = √wᵢ is one column and the cost
//!   is O(m²n + m³) whatever n. ψ's inner product is (‖a‖²‖b‖² + ωΣⱼ aⱼ²bⱼ²)/4 + a·b.
//!   The memory holds at most [`super::MAX_MEMORY`] points, fewer than the model's
//!   2n + 1 coefficients for large n: a fit then corrects g only along the directions
//!   the points were drawn in, as a subspace method does, and the curvature mostly
//!   through h̄, which every point informs. The deviations d, each seen only through
//!   sums over random directions, are learnt in proportion to how far the memory
//!   determines them, ω = min(1, m/(2n + 1))²: without that damping their errors
//!   accumulate from fit to fit and the carried model diverges. H moves by
//!   (1/(2λ_H)) Σᵢ √wᵢ αᵢ (‖uᵢ‖² + ω uᵢ²) (elementwise square), g by (1/λ_H) Σᵢ √wᵢ αᵢ uᵢ.

use crate::cholesky;
use crate::optim::vector::{axpy, dot, dot_lanes_many, mat_vec_by_columns, row_block};
use crate::real::Real;
use crate::wide::avx2_twin;

/// Which Hessian the model has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    /// A full symmetric n×n Hessian (n ≤ [`super::FULL_MODEL_MAX_DIM`]).
    Full,
    /// A diagonal Hessian: 2n + 1 coefficients, for large n; the gradient is penalised
    /// as the curvature is.
    Diagonal,
}

impl Shape {
    /// The shape used in dimension n.
    pub(super) const fn for_dim(n: usize) -> Shape {
        if n <= super::FULL_MODEL_MAX_DIM {
            Shape::Full
        } else {
            Shape::Diagonal
        }
    }

    /// Columns of the fit's free features: (1, u) for a full Hessian, 1 for a diagonal.
    pub(super) const fn free_columns(self, n: usize) -> usize {
        match self {
            Shape::Full => n + 1,
            Shape::Diagonal => 1,
        }
    }

    /// Floats of a Hessian of this shape.
    pub(super) const fn hessian_len(self, n: usize) -> usize {
        match self {
            Shape::Full => n * n,
            Shape::Diagonal => n,
        }
    }

    /// Coefficients of the model: 1 + n + n(n+1)/2 (full) or 1 + 2n (diagonal).
    pub(super) const fn coefficients(self, n: usize) -> usize {
        match self {
            Shape::Full => 1 + n + n * (n + 1) / 2,
            Shape::Diagonal => 1 + 2 * n,
        }
    }

    /// ½uᵀHu.
    pub(super) fn half_quadratic<T: Real>(self, h: &[T], u: &[T]) -> T {
        let n = u.len();
        let mut s = T::ZERO;
        match self {
            Shape::Full => {
                for i in 0..n {
                    let mut row = T::ZERO;
                    for j in 0..n {
                        row += h[i * n + j] * u[j];
                    }
                    s += u[i] * row;
                }
            }
            Shape::Diagonal => {
                for i in 0..n {
                    s += h[i] * u[i].sq();
                }
            }
        }
        T::HALF * s
    }

    /// ½uᵀHu of a full H given its transpose `ht`, with n floats of scratch `rows`: the
    /// same sums in the same order as [`Shape::half_quadratic`]'s, H·u accumulated by
    /// H's contiguous columns ([`mat_vec_by_columns`]).
    pub(super) fn half_quadratic_by_columns<T: Real>(ht: &[T], u: &[T], rows: &mut [T]) -> T {
        mat_vec_by_columns(ht, u, rows);
        let s = u
            .iter()
            .zip(rows.iter())
            .fold(T::ZERO, |s, (&ui, &ri)| s + ui * ri);
        T::HALF * s
    }

    /// y ← H·x.
    pub(super) fn apply<T: Real>(self, h: &[T], x: &[T], y: &mut [T]) {
        let n = x.len();
        match self {
            Shape::Full => {
                for i in 0..n {
                    y[i] = (0..n).fold(T::ZERO, |s, j| s + h[i * n + j] * x[j]);
                }
            }
            Shape::Diagonal => {
                for i in 0..n {
                    y[i] = h[i] * x[i];
                }
            }
        }
    }
}

/// The curvature penalty λ_H for precision T: 16√ε, so that the fit is close to
/// interpolation where the points determine it and the system stays well within T's
/// precision.
fn curvature_penalty<T: Real>() -> T {
    T::from_f64(16.0) * T::EPSILON.sqrt()
}

/// How firmly a fit holds its free part (c, g) at the prior's: the ridge of the Schur
/// complement S = PᵀK⁻¹P relative to its mean diagonal ([`fit`]).
///
/// S is nearly singular whenever the remembered points lie at one distance from θ (a
/// survey of antithetic pairs): there the common curvature's feature ½‖u‖² is nearly the
/// constant one, and the pair (c, h̄) is fixed only by θ's own value, through an
/// eigenvalue of S some 10⁻⁷ of its mean diagonal (K⁻¹ shrinks every direction the
/// penalised features span by ~λ_H). A ridge of √ε there bent the fitted curvature by a
/// few per cent, so that a round bowl's model from a survey of 2n + 1 points was not
/// exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Ridge {
    /// ε^⅞: a full model's first fit after a survey where later fits cannot determine
    /// the model (n = 15–40), so that whatever error it leaves in H is carried by every
    /// later least-change fit. It has no prior to hold g at: the survey's pairs fix g
    /// and the curvature along their lines, so the smallest ridge that still factors
    /// makes a round bowl's first step land closest to its minimum (√ε left a few per
    /// cent in H that later fits never removed; ε^¾, a step short of the minimum by
    /// about 10⁻⁵ of its length).
    Survey,
    /// ε^¾: a fit whose memory can determine the full model (n ≤ 14). It leaves such
    /// directions within a few ppm of the data and still keeps the pivots of directions
    /// the points leave undetermined far above the rounding of S.
    Determined,
    /// √ε: a fit that leans on its prior (a full model from n = 15 after its first fit,
    /// fewer remembered points than its (n + 1)(n + 2)/2 coefficients; the diagonal
    /// model, whose S is 1×1, the constant's), which keeps g's weakly determined part
    /// near the prior's.
    Prior,
}

impl Ridge {
    /// The ridge relative to S's mean diagonal in precision T: ε^⅞, ε^¾ or √ε.
    fn fraction<T: Real>(self) -> T {
        let root = T::EPSILON.sqrt();
        let quarter = root.sqrt();
        match self {
            Ridge::Survey => root * quarter * quarter.sqrt(),
            Ridge::Determined => root * quarter,
            Ridge::Prior => root,
        }
    }
}

/// ω, the weight of the per-axis deviations of H from its common curvature (features
/// ½uⱼ² in whitened coordinates; see the module's header):
/// * a diagonal model: ω = min(1, m/(2n + 1))² for a memory of m points;
/// * a full model: 0 where its memory determines it (n ≤ 14), n above, where each fit
///   has fewer points than coefficients. Each diagonal entry of H then has a prior
///   variance n + 1 against 1 for each entry of D, about as much as its row's n entries
///   together: the least change puts the curvature the points show on the axes first,
///   as a diagonal model does, and learns a rotation only as far as the points demand.
///   Where the curvature changes as θ moves (BBOB's oscillating coordinates, a
///   least-squares problem's quartic), that leaves less stale curvature in H; on a
///   quadratic, whose H is one matrix everywhere, it only slows learning the rotation.
///   So a full model on f found `quadratic` (the separability test's line check) takes
///   ω = 0 at every n — while θ lies inside the box. On a face, f as the steps see it is
///   the quadratic cut by the box's faces, which lie along the axes: which coordinates
///   a step may move, and the curvature left in them, change as θ moves from face to
///   face, and the caller passes `quadratic` false there.
pub(super) fn deviation_share(shape: Shape, n: usize, quadratic: bool) -> f64 {
    match shape {
        Shape::Full if quadratic || super::memory_determines_model(shape, n) => 0.0,
        Shape::Full => n as f64,
        Shape::Diagonal => {
            let determined = super::history_len(shape, n) as f64 / (2 * n + 1) as f64;
            let share = determined.min(1.0);
            share * share
        }
    }
}

/// (Σⱼ (aⱼbⱼ)², Σⱼ aⱼbⱼ) for each of R vectors `rows` (their first n floats) with `b`'s,
/// in one pass over b. Each sum runs in four interleaved partial sums,
/// (s₀ + s₁) + (s₂ + s₃) plus the tail, so that the compiler can vectorise the loop;
/// Σⱼ aⱼbⱼ is [`dot_lanes`](crate::optim::vector::dot_lanes)'s (and `dot_lanes_many`'s),
/// bit for bit, and neither sum depends on the block it is computed in.
#[inline(always)]
fn products<T: Real, const R: usize>(rows: [&[T]; R], b: &[T], n: usize) -> [(T, T); R] {
    let mut quad = [[T::ZERO; 4]; R];
    let mut lin = [[T::ZERO; 4]; R];
    let full = n - n % 4;
    for c in (0..full).step_by(4) {
        let y = &b[c..c + 4];
        for ((q, l), row) in quad.iter_mut().zip(lin.iter_mut()).zip(rows.iter()) {
            let x = &row[c..c + 4];
            for k in 0..4 {
                let p = x[k] * y[k];
                q[k] += p * p;
                l[k] += p;
            }
        }
    }
    let mut out = [(T::ZERO, T::ZERO); R];
    for ((o, (q, l)), row) in out.iter_mut().zip(quad.iter().zip(&lin)).zip(rows) {
        let (tq, tl) =
            row[full..n]
                .iter()
                .zip(&b[full..n])
                .fold((T::ZERO, T::ZERO), |(sq, sl), (&x, &y)| {
                    let p = x * y;
                    (sq + p * p, sl + p)
                });
        *o = (
            (q[0] + q[1]) + (q[2] + q[3]) + tq,
            (l[0] + l[1]) + (l[2] + l[3]) + tl,
        );
    }
    out
}

/// ‖a‖² in four interleaved partial sums, (s₀ + s₁) + (s₂ + s₃), the tail's squares
/// added to the first lanes.
#[inline(always)]
fn norm_sq<T: Real>(a: &[T]) -> T {
    let mut lanes = [T::ZERO; 4];
    let chunks = a.chunks_exact(4);
    let tail = chunks.remainder();
    for x in chunks {
        for k in 0..4 {
            lanes[k] += x[k] * x[k];
        }
    }
    for (lane, &x) in tail.iter().enumerate() {
        lanes[lane] += x * x;
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3])
}

/// 4ψ(uᵢ)·ψ(u_k) for the R points k = k0, …, k0 + R − 1 (rows of `u`, n floats each;
/// `norms` their ‖u‖²), in one pass over uᵢ: (uᵢ·u_k)² + ‖uᵢ‖²‖u_k‖² + ωΣⱼ(uᵢⱼu_kⱼ)²
/// for a full Hessian, ωΣⱼ(uᵢⱼu_kⱼ)² + ‖uᵢ‖²‖u_k‖² + 4uᵢ·u_k for a diagonal one
/// (`share` = ω, [`deviation_share`]).
#[inline(always)]
fn kernel_block<T: Real, const R: usize>(
    shape: Shape,
    share: T,
    u: &[T],
    norms: &[T],
    n: usize,
    i: usize,
    k0: usize,
) -> [T; R] {
    let ui = &u[i * n..(i + 1) * n];
    let rows = row_block::<T, R>(u, k0 * n, n, n);
    let common = |b: usize| norms[i] * norms[k0 + b];
    let mut out = [T::ZERO; R];
    if shape == Shape::Full && share == T::ZERO {
        // No per-axis features (a determined full model): the dot products alone, summed
        // as `products` sums them.
        let dots = dot_lanes_many(rows, ui, n);
        for (b, (o, dot)) in out.iter_mut().zip(dots).enumerate() {
            *o = dot.sq() + common(b);
        }
        return out;
    }
    let sums = products(rows, ui, n);
    for (b, (o, (quad, lin))) in out.iter_mut().zip(sums).enumerate() {
        *o = match shape {
            Shape::Full => lin.sq() + common(b) + share * quad,
            Shape::Diagonal => quad * share + common(b) + T::from_f64(4.0) * lin,
        };
    }
    out
}

/// Points whose Gram entries with one point [`fit`] computes in one pass.
const GRAM_BLOCK: usize = 4;

/// Scratch of [`fit`] for p = [`Shape::free_columns`] and at most `rows` points: `gram`
/// rows² floats (K's factor, its rows `rows` floats apart), `kp` rows·p, `norms` rows,
/// `schur` p², `beta` p. `gram`'s and `kp`'s leading rows are the fit's cache: see
/// [`fit`]'s `reuse`.
pub(super) struct Scratch<'a, T> {
    pub gram: &'a mut [T],
    pub kp: &'a mut [T],
    pub norms: &'a mut [T],
    pub schur: &'a mut [T],
    pub beta: &'a mut [T],
    pub rows: usize,
}

/// Floats of [`Scratch`] for m points in dimension n: (gram, kp, norms, schur, beta).
pub(super) const fn scratch_lens(shape: Shape, m: usize, n: usize) -> [usize; 5] {
    let p = shape.free_columns(n);
    [m * m, m * p, m, p * p, p]
}

/// Dimensions from which [`fit`] runs its AVX2 copy (where the CPU has it): below, the
/// kernel's inner products over n coordinates are too short for the wider lanes to repay
/// their set-up, and the baseline copy is the faster one. Both copies give the same fit,
/// bit for bit, so the choice changes no result.
const FIT_WIDE_MIN_DIM: usize = 13;

avx2_twin! {
wide_when(n >= FIT_WIDE_MIN_DIM);
/// Fits the model's change from its prior, `share` the axis weight ω
/// ([`deviation_share`]). On entry `u` holds m rows of n standardised
/// offsets, `sw` the m square-root weights √wᵢ, `r` the m weighted residuals of the prior
/// √wᵢ(vᵢ − m₀(uᵢ)); `g` and `h` hold the prior's g₀ and H₀ (H in `shape`'s layout).
///
/// The free part (c and, for a full Hessian, g) is unpenalised and the rest pays λ_H per
/// squared change, as in Powell's NEWUOA: with K = ΨΨᵀ/λ_H + I over the penalised
/// features ψᵢ and P the weighted free features (see the module's header), the saddle
/// system K α + P β = r, Pᵀα = 0 is solved through K's Cholesky factor and the Schur
/// complement PᵀK⁻¹P, given a small ridge relative to its mean diagonal that `ridge`
/// sets ([`Ridge`]). On success `g` and `h` hold the fitted coefficients; `r`, `schur`
/// and `beta` are overwritten, and `gram` and `kp` hold K's factor and L⁻¹P for the m
/// rows.
///
/// K and P depend on the rows (u, √w, group) alone, not on the values or the prior, and
/// row i of K's factor and of L⁻¹P on rows up to i. With `reuse` = k, the caller
/// vouches that the first k rows are those of the last successful fit, bit for bit, and
/// that `gram` and `kp` are as that fit left them: their first k rows are kept, and only
/// the rows after them are computed — O(m²n) rather than O(m³) work where a fit adds a
/// few points to the last one's (a rejected trial, a resample at the same θ and σ), with
/// the very numbers a fit from scratch gives.
///
/// With `groups` (one id per row), rows with equal ids share an unknown offset: the
/// values of a noisy objective evaluated on one noise seed, whose level moves from seed to
/// seed (a Monte Carlo render's mean brightness) while their differences are exact. Each
/// group's offset o is a further coefficient, as free as the curvature (penalty λ_H o²):
/// K gains √wᵢ√wₖ/λ_H wherever rows i and k share a group, so that only differences
/// within a group inform g and H, and a group of one row informs nothing.
///
/// Returns the fit's noise level η — the root-mean-square weighted residual
/// √(Σᵢ (√wᵢ·resᵢ)² / Σᵢ wᵢ · m/(m − p)) for m points and p coefficients (G − 1 more for
/// G groups), 0 when m ≤ p (the points are interpolated, their roughness unseen) — or
/// `None`, leaving `g` and `h` at the prior, when the system cannot be factored
/// (non-finite inputs).
///
/// Its AVX2 copy runs from [`FIT_WIDE_MIN_DIM`] dimensions on.
#[allow(clippy::too_many_arguments)]
pub(super) fn fit<T: Real>(
    shape: Shape,
    share: T,
    n: usize,
    m: usize,
    u: &[T],
    sw: &[T],
    groups: Option<&[T]>,
    r: &mut [T],
    scratch: Scratch<'_, T>,
    g: &mut [T],
    h: &mut [T],
    ridge: Ridge,
    reuse: usize,
) -> Option<T> {
    if m == 0 {
        return Some(T::ZERO);
    }
    let Scratch {
        gram,
        kp,
        norms,
        schur,
        beta,
        rows: stride,
    } = scratch;
    let reuse = reuse.min(m);
    let lh = curvature_penalty::<T>();
    let quarter_lh = T::ONE / (T::from_f64(4.0) * lh);
    for (i, norm) in norms[..m].iter_mut().enumerate() {
        *norm = norm_sq(&u[i * n..(i + 1) * n]);
    }
    // Rows `reuse..m` of the lower triangle of K, row i at i·stride.
    for i in reuse..m {
        // Points k ≤ i, GRAM_BLOCK at a time while a block is left (each element of uᵢ
        // loaded once per block), then one by one.
        let mut k0 = 0;
        while k0 <= i {
            let mut q = [T::ZERO; GRAM_BLOCK];
            let block = if k0 + GRAM_BLOCK <= i + 1 {
                q = kernel_block::<T, GRAM_BLOCK>(shape, share, u, norms, n, i, k0);
                GRAM_BLOCK
            } else {
                q[0] = kernel_block::<T, 1>(shape, share, u, norms, n, i, k0)[0];
                1
            };
            for (b, &qk) in q[..block].iter().enumerate() {
                let k = k0 + b;
                let shared = groups.is_some_and(|id| id[i] == id[k]);
                let offset = if shared { T::from_f64(4.0) } else { T::ZERO };
                let mut kik = sw[i] * sw[k] * (qk + offset) * quarter_lh;
                if i == k {
                    kik += T::ONE;
                }
                gram[i * stride + k] = kik;
            }
            k0 += block;
        }
    }
    if !cholesky::factor_rows(gram, stride, reuse, m, T::ZERO) {
        return None;
    }
    // With K = LLᵀ: W = L⁻¹P (P's row i being √wᵢ·(1, uᵢ), or √wᵢ; m×cols, row-major)
    // and w = L⁻¹r, so that the Schur complement PᵀK⁻¹P = WᵀW and PᵀK⁻¹r = Wᵀw.
    let cols = shape.free_columns(n);
    let w = &mut kp[..m * cols];
    for (i, row) in w.chunks_exact_mut(cols).enumerate().skip(reuse) {
        row[0] = sw[i];
        for (j, wij) in row[1..].iter_mut().enumerate() {
            *wij = sw[i] * u[i * n + j];
        }
    }
    cholesky::forward_many(gram, m, stride, reuse, w, cols);
    let y = &mut r[..m];
    cholesky::forward(gram, m, stride, y);
    // S β = Wᵀw, ridged so that it factors where the points leave the linear part free.
    schur[..cols * cols].fill(T::ZERO);
    beta[..cols].fill(T::ZERO);
    for (wi, &yi) in w.chunks_exact(cols).zip(y.iter()) {
        for a in 0..cols {
            axpy(wi[a], &wi[..=a], &mut schur[a * cols..a * cols + a + 1]);
            beta[a] += wi[a] * yi;
        }
    }
    let diag = (0..cols).fold(T::ZERO, |s, a| s + schur[a * cols + a]);
    let shift = ridge.fraction::<T>() * (diag / T::from_usize(cols)).max(T::MIN_POSITIVE);
    if !cholesky::factor_in_place(&mut schur[..cols * cols], cols, shift) {
        return None;
    }
    cholesky::solve(schur, cols, &mut beta[..cols]);
    // α = K⁻¹(r − Pβ) = L⁻ᵀ(w − Wβ): the weighted residuals of the fit.
    for (yi, wi) in y.iter_mut().zip(w.chunks_exact(cols)) {
        *yi -= dot(wi, &beta[..cols]);
    }
    cholesky::backward(gram, m, stride, y);
    let alpha = &*y;
    if alpha
        .iter()
        .chain(beta[..cols].iter())
        .any(|a| !a.is_finite())
    {
        return None;
    }
    let offsets = groups.map_or(0, |id| {
        (0..m)
            .filter(|&i| (0..i).all(|k| id[k] != id[i]))
            .count()
            .saturating_sub(1)
    });
    let p = shape.coefficients(n) + offsets;
    let noise = noise_level(&sw[..m], alpha.iter().fold(T::ZERO, |s, &a| s + a.sq()), p);
    for j in 1..cols {
        g[j - 1] += beta[j];
    }
    let half_lh = T::ONE / (T::TWO * lh);
    match shape {
        Shape::Full => {
            let mut first = 0;
            while first + HESSIAN_BLOCK <= m {
                update_block::<T, HESSIAN_BLOCK>(
                    &u[first * n..],
                    &sw[first..],
                    &alpha[first..],
                    n,
                    share,
                    half_lh,
                    h,
                );
                first += HESSIAN_BLOCK;
            }
            for i in first..m {
                update_block::<T, 1>(&u[i * n..], &sw[i..], &alpha[i..], n, share, half_lh, h);
            }
        }
        Shape::Diagonal => {
            for i in 0..m {
                let c = sw[i] * alpha[i];
                let ui = &u[i * n..(i + 1) * n];
                let common = c * ui.iter().fold(T::ZERO, |s, &x| s + x * x) * half_lh;
                for j in 0..n {
                    h[j] += share * c * ui[j].sq() * half_lh + common;
                    g[j] += T::TWO * c * ui[j] * half_lh;
                }
            }
        }
    }
    g.iter()
        .chain(h.iter())
        .all(|x| x.is_finite())
        .then_some(noise)
}
}

/// Points whose terms [`fit`] adds to a full Hessian in one pass over it ([`update_block`]).
const HESSIAN_BLOCK: usize = 4;

/// A full H's update by the R points in the first rows of `u` (n floats each), with
/// square-root weights `sw` and residuals `alpha`: for each point in turn,
/// H += cuuᵀ/(2λ_H) and diag(H) += c(‖u‖² + ωu²)/(2λ_H), c = √w·α (`half_lh` = 1/(2λ_H),
/// `share` = ω), every entry summed over the points in order, so that it is the same bit
/// for bit whatever R, while H is read and written once for the R points.
#[inline(always)]
fn update_block<T: Real, const R: usize>(
    u: &[T],
    sw: &[T],
    alpha: &[T],
    n: usize,
    share: T,
    half_lh: T,
    h: &mut [T],
) {
    let us = row_block::<T, R>(u, 0, n, n);
    let mut c = [T::ZERO; R];
    let mut common = [T::ZERO; R];
    for b in 0..R {
        c[b] = sw[b] * alpha[b];
        common[b] = c[b] * us[b].iter().fold(T::ZERO, |s, &x| s + x * x) * half_lh;
    }
    for (j, row) in h[..n * n].chunks_exact_mut(n).enumerate() {
        let mut a = [T::ZERO; R];
        for b in 0..R {
            a[b] = c[b] * us[b][j] * half_lh;
        }
        // The diagonal entry takes each point's axis terms right after its product.
        let mut diagonal = row[j];
        for b in 0..R {
            diagonal += a[b] * us[b][j];
            diagonal += common[b] + share * c[b] * us[b][j].sq() * half_lh;
        }
        for (k, x) in row.iter_mut().enumerate() {
            for b in 0..R {
                *x += a[b] * us[b][k];
            }
        }
        row[j] = diagonal;
    }
}

/// The noise level η of a fit to the m = `sw.len()` points with square-root weights `sw`,
/// whose weighted residuals √wᵢ·resᵢ have the sum of squares `sum`, for p coefficients:
/// √(sum / Σᵢ wᵢ · m/(m − p)), or 0 when m ≤ p (the points are interpolated).
pub(super) fn noise_level<T: Real>(sw: &[T], sum: T, p: usize) -> T {
    let m = sw.len();
    if m <= p {
        return T::ZERO;
    }
    let weight = sw.iter().fold(T::ZERO, |s, &x| s + x.sq());
    (sum / weight * T::from_usize(m) / T::from_usize(m - p)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Scratch for up to 20 points in up to 3 dimensions (fixed arrays: no heap here).
    struct Buffers {
        gram: [f64; 400],
        kp: [f64; 80],
        norms: [f64; 20],
        schur: [f64; 16],
        beta: [f64; 4],
    }

    impl Buffers {
        fn new() -> Self {
            Buffers {
                gram: [0.0; 400],
                kp: [0.0; 80],
                norms: [0.0; 20],
                schur: [0.0; 16],
                beta: [0.0; 4],
            }
        }

        fn as_mut(&mut self, shape: Shape, m: usize, n: usize) -> Scratch<'_, f64> {
            let [gram, kp, norms, schur, beta] = scratch_lens(shape, m, n);
            Scratch {
                gram: &mut self.gram[..gram],
                kp: &mut self.kp[..kp],
                norms: &mut self.norms[..norms],
                schur: &mut self.schur[..schur],
                beta: &mut self.beta[..beta],
                rows: m,
            }
        }
    }

    /// 20 pseudo-random points in [−2, 2)³ (a linear congruential stream from `seed`).
    fn points(mut state: u64) -> [f64; 60] {
        let mut u = [0.0; 60];
        for x in u.iter_mut() {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *x = (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0;
        }
        u
    }

    /// A Gram entry computed in a block of points is the one computed alone, bit for bit
    /// (what keeps a run's numbers independent of how the fit is blocked), for both
    /// shapes.
    #[test]
    fn kernel_entries_do_not_depend_on_the_block() {
        let n = 3;
        let u = points(4242);
        let mut norms = [0.0; 20];
        for (i, norm) in norms.iter_mut().enumerate() {
            *norm = norm_sq(&u[i * n..(i + 1) * n]);
        }
        for (shape, share) in [
            (Shape::Full, 0.0),
            (Shape::Full, 0.5),
            (Shape::Diagonal, 0.5),
        ] {
            let four = kernel_block::<f64, 4>(shape, share, &u, &norms, n, 9, 2);
            let two = kernel_block::<f64, 2>(shape, share, &u, &norms, n, 9, 4);
            for (b, entry) in four.iter().enumerate() {
                let alone = kernel_block::<f64, 1>(shape, share, &u, &norms, n, 9, 2 + b)[0];
                assert_eq!(
                    entry.to_bits(),
                    alone.to_bits(),
                    "{shape:?}, point {}",
                    2 + b
                );
            }
            assert_eq!(two[0].to_bits(), four[2].to_bits());
            assert_eq!(two[1].to_bits(), four[3].to_bits());
        }
    }

    /// A fit that extends the last one's system by rows (`reuse`) gives the numbers of a
    /// fit from scratch, bit for bit, with and without noise groups and for both shapes,
    /// when the rows it keeps were factored at a different number of points.
    #[test]
    fn an_extended_fit_is_the_fit_from_scratch() {
        let n = 3;
        let u = points(777);
        let mut sw = [0.0; 20];
        let mut values = [0.0; 20];
        let mut ids = [0.0; 20];
        for i in 0..20 {
            sw[i] = 0.5 + 0.4 * libm::sin(i as f64);
            let x = &u[i * n..(i + 1) * n];
            values[i] = 1.0 + x[0] - 2.0 * x[1] * x[2] + x[2].sq() + 0.1 * libm::cos(7.0 * x[0]);
            ids[i] = (i % 3) as f64;
        }
        for shape in [Shape::Full, Shape::Diagonal] {
            for groups in [None, Some(&ids[..])] {
                let mut fitted = [([0.0; 3], [0.0; 9], 0.0); 2];
                for (case, (g, h, noise)) in fitted.iter_mut().enumerate() {
                    let mut buffers = Buffers::new();
                    let mut reuse = 0;
                    if case == 1 {
                        // 13 rows first, and their factor kept for the 20-row fit.
                        let (mut g13, mut h13) = ([0.0; 3], [0.0; 9]);
                        let mut r = values;
                        assert!(
                            fit(
                                shape,
                                deviation_share(shape, n, false),
                                n,
                                13,
                                &u,
                                &sw,
                                groups,
                                &mut r,
                                buffers.as_mut(shape, 20, n),
                                &mut g13,
                                &mut h13,
                                Ridge::Prior,
                                0,
                            )
                            .is_some()
                        );
                        reuse = 13;
                    }
                    let mut r = values;
                    *noise = fit(
                        shape,
                        deviation_share(shape, n, false),
                        n,
                        20,
                        &u,
                        &sw,
                        groups,
                        &mut r,
                        buffers.as_mut(shape, 20, n),
                        g,
                        h,
                        Ridge::Prior,
                        reuse,
                    )
                    .unwrap();
                }
                let bits = |(g, h, noise): &([f64; 3], [f64; 9], f64)| {
                    let mut all = [0u64; 13];
                    for (b, x) in all.iter_mut().zip(g.iter().chain(h).chain([noise])) {
                        *b = x.to_bits();
                    }
                    all
                };
                assert_eq!(bits(&fitted[0]), bits(&fitted[1]), "{shape:?}, {groups:?}");
            }
        }
    }

    /// A quadratic is recovered from enough points, whatever the prior.
    #[test]
    fn recovers_a_quadratic_from_enough_points() {
        let n = 3;
        let g_true = [1.0, -2.0, 0.5];
        let h_true = [4.0, 1.0, 0.0, 1.0, 3.0, -0.5, 0.0, -0.5, 2.0];
        let f = |u: &[f64]| {
            let lin: f64 = u.iter().zip(&g_true).map(|(a, b)| a * b).sum();
            lin + Shape::Full.half_quadratic(&h_true, u)
        };
        // 20 pseudo-random points (more than the 10 coefficients).
        let m = 20;
        let u = points(12345);
        let sw = [1.0; 20];
        let mut r = [0.0; 20];
        for (i, ri) in r.iter_mut().enumerate() {
            *ri = f(&u[i * n..(i + 1) * n]);
        }
        let (mut g, mut h) = ([0.0; 3], [0.0; 9]);
        assert!(
            fit(
                Shape::Full,
                deviation_share(Shape::Full, n, false),
                n,
                m,
                &u,
                &sw,
                None,
                &mut r,
                Buffers::new().as_mut(Shape::Full, m, n),
                &mut g,
                &mut h,
                Ridge::Determined,
                0,
            )
            .is_some()
        );
        for j in 0..n {
            assert!((g[j] - g_true[j]).abs() < 1e-5, "g = {g:?}");
        }
        for k in 0..n * n {
            assert!((h[k] - h_true[k]).abs() < 1e-5, "H = {h:?}");
        }
    }

    /// The diagonal model (common curvature, deviations, penalised gradient) recovers a
    /// separable quadratic from more points than its 2n + 1 coefficients.
    #[test]
    fn the_diagonal_model_recovers_a_separable_quadratic() {
        let n = 3;
        let g_true = [0.5, -1.0, 2.0];
        let h_true = [1.0, 4.0, 0.25];
        let f = |u: &[f64]| {
            let lin: f64 = u.iter().zip(&g_true).map(|(a, b)| a * b).sum();
            lin + Shape::Diagonal.half_quadratic(&h_true, u)
        };
        let m = 20;
        let u = points(987654321);
        let sw = [1.0; 20];
        let mut r = [0.0; 20];
        for (i, ri) in r.iter_mut().enumerate() {
            *ri = f(&u[i * n..(i + 1) * n]);
        }
        let (mut g, mut h) = ([0.0; 3], [0.0; 3]);
        let noise = fit(
            Shape::Diagonal,
            deviation_share(Shape::Diagonal, n, false),
            n,
            m,
            &u,
            &sw,
            None,
            &mut r,
            Buffers::new().as_mut(Shape::Diagonal, m, n),
            &mut g,
            &mut h,
            Ridge::Determined,
            0,
        );
        assert!(noise.is_some_and(|e| e < 1e-4), "noise {noise:?}");
        for j in 0..n {
            assert!((g[j] - g_true[j]).abs() < 1e-4, "g = {g:?}");
            assert!((h[j] - h_true[j]).abs() < 1e-4, "H = {h:?}");
        }
    }

    /// Where the memory cannot determine a full model (n = 16: 153 coefficients), a fit
    /// to 3n points of a separable quadratic whose curvatures span 10³ puts most of
    /// them on the axes (ω = n): H's diagonal within half of the truth in norm, its
    /// off-diagonal part under 0.15 of it. With the axis features' weight at 0 the
    /// least change spreads the curvature over D instead and misses both bounds.
    #[test]
    fn an_underdetermined_full_fit_learns_axis_curvatures() {
        const N: usize = 16;
        const M: usize = 3 * N;
        assert!(!super::super::memory_determines_model(Shape::Full, N));
        let c: [f64; N] = core::array::from_fn(|j| libm::pow(10.0, 3.0 * j as f64 / 15.0));
        let mut u = [0.0; M * N];
        for (k, chunk) in u.chunks_mut(60).enumerate() {
            chunk.copy_from_slice(&points(77 + k as u64)[..chunk.len()]);
        }
        let sw = [1.0; M];
        let mut r = [0.0; M];
        for (i, ri) in r.iter_mut().enumerate() {
            *ri = Shape::Diagonal.half_quadratic(&c, &u[i * N..(i + 1) * N]);
        }
        let (mut g, mut h) = ([0.0; N], [0.0; N * N]);
        let (mut gram, mut kp, mut norms) = ([0.0; M * M], [0.0; M * (N + 1)], [0.0; M]);
        let (mut schur, mut beta) = ([0.0; (N + 1) * (N + 1)], [0.0; N + 1]);
        let scratch = Scratch {
            gram: &mut gram,
            kp: &mut kp,
            norms: &mut norms,
            schur: &mut schur,
            beta: &mut beta,
            rows: M,
        };
        let fitted = fit(
            Shape::Full,
            deviation_share(Shape::Full, N, false),
            N,
            M,
            &u,
            &sw,
            None,
            &mut r,
            scratch,
            &mut g,
            &mut h,
            Ridge::Prior,
            0,
        );
        assert!(fitted.is_some());
        let norm_c = libm::sqrt(c.iter().map(|x| x * x).sum::<f64>());
        let diagonal = (0..N).map(|j| (h[j * (N + 1)] - c[j]).sq()).sum::<f64>();
        let across = (0..N * N)
            .filter(|k| k % (N + 1) != 0)
            .map(|k| h[k] * h[k])
            .sum::<f64>();
        let (diagonal, across) = (libm::sqrt(diagonal) / norm_c, libm::sqrt(across) / norm_c);
        assert!(diagonal < 0.5, "diagonal error {diagonal}, across {across}");
        assert!(across < 0.15, "diagonal error {diagonal}, across {across}");
    }

    /// Offsets shared within groups of rows (a noisy objective's level per seed) are
    /// absorbed: the quadratic comes back from the differences within the groups.
    #[test]
    fn recovers_a_quadratic_under_group_offsets() {
        let n = 2;
        let g_true = [0.5, -1.0];
        let h_true = [3.0, 0.5, 0.5, 1.0];
        let f = |u: &[f64]| {
            let lin: f64 = u.iter().zip(&g_true).map(|(a, b)| a * b).sum();
            lin + Shape::Full.half_quadratic(&h_true, u)
        };
        // Four groups of five points: the centre and two antithetic pairs, each group
        // shifted by its own large offset.
        let m = 20;
        let mut u = [0.0; 40];
        let mut ids = [0.0; 20];
        let mut r = [0.0; 20];
        let offsets = [7.0, -3.0, 40.0, 0.25];
        for (k, offset) in offsets.iter().enumerate() {
            let a = 0.4 * k as f64;
            let (c, s) = (libm::cos(a), libm::sin(a));
            let rows = [[0.0, 0.0], [c, s], [-c, -s], [-s, c], [s, -c]];
            for (j, x) in rows.iter().enumerate() {
                let i = 5 * k + j;
                u[2 * i..2 * i + 2].copy_from_slice(x);
                ids[i] = k as f64;
                r[i] = f(x) + offset;
            }
        }
        let sw = [1.0; 20];
        let (mut g, mut h) = ([0.0; 2], [0.0; 4]);
        let noise = fit(
            Shape::Full,
            deviation_share(Shape::Full, n, false),
            n,
            m,
            &u,
            &sw,
            Some(&ids),
            &mut r,
            Buffers::new().as_mut(Shape::Full, m, n),
            &mut g,
            &mut h,
            Ridge::Determined,
            0,
        );
        assert!(noise.is_some_and(|e| e < 1e-4), "noise {noise:?}");
        for j in 0..n {
            assert!((g[j] - g_true[j]).abs() < 1e-4, "g = {g:?}");
        }
        for k in 0..n * n {
            assert!((h[k] - h_true[k]).abs() < 1e-4, "H = {h:?}");
        }
    }

    /// With θ, one point along e₀ and its mirror, the prior's curvature across moves
    /// only by the common part of the change: the data's +2 along e₀ splits evenly
    /// between the deviation and the common curvature (equal penalties), so H = diag(2,
    /// 5 + 1) with no cross term.
    #[test]
    fn moves_unsampled_curvature_by_the_common_change_only() {
        let n = 2;
        let u = [1.0, 0.0, -1.0, 0.0, 0.0, 0.0];
        let sw = [1.0, 1.0, 1.0];
        // f = u₀ + u₀² ; prior H = diag(0, 5): the second coordinate is not sampled, and
        // the prior is 0 along the first.
        let (mut g, mut h) = ([0.0; 2], [0.0, 0.0, 0.0, 5.0]);
        let mut r = [2.0, 0.0, 0.0];
        assert!(
            fit(
                Shape::Full,
                deviation_share(Shape::Full, n, false),
                n,
                3,
                &u,
                &sw,
                None,
                &mut r,
                Buffers::new().as_mut(Shape::Full, 3, n),
                &mut g,
                &mut h,
                Ridge::Determined,
                0,
            )
            .is_some()
        );
        assert!((g[0] - 1.0).abs() < 1e-3, "g = {g:?}");
        assert!(
            (h[0] - 2.0).abs() < 1e-5 && (h[3] - 6.0).abs() < 1e-5,
            "H = {h:?}"
        );
        assert!(h[1] == 0.0 && h[2] == 0.0, "H = {h:?}");
    }
}
