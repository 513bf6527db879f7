//! BOX2-REF: the paper's own BOX2 renderer, reproduced exactly (docs/design.md §3).
//!
//! A 500×500 single-channel image, pixel (row r, column c). θ = (pₓ, p_y) in pixels, each
//! clamped to [50, 450]. Before a vertical flip the square is
//! J(r, c) = clamp(1 − 2·(|(p_y − r)/50|¹⁰ + |(c − pₓ)/50|¹⁰), 0, 1), and the image is
//! I(r, c) = J(499 − r, c). Loss = mean over all 250 000 pixels of (I_θ − I_θ*)², with
//! θ* = (150, 150); on the plateau (no overlap) it is 0.0520089.
//!
//! The flip permutes rows, so the loss equals the mean of (J_θ − J_θ*)². Only pixels in
//! the support of either square can differ from zero: J > 0 needs both
//! |p_y − r| < 50·2^{−1/10} and |c − pₓ| < 50·2^{−1/10} (≈ 46.65 px). An evaluation visits
//! the two squares' bounding boxes (≤ 94×94 pixels each), not 250 000 pixels; with no
//! overlap the target's part is a precomputed sum.

use hodr_core::{NoiseSeed, Objective};

/// Image side in pixels.
pub const SIZE: usize = 500;
/// The target θ* = (pₓ, p_y).
pub const TARGET: [f64; 2] = [150.0, 150.0];
/// The square's half-size parameter, pixels.
const HALF: f64 = 50.0;
/// Parameters are clamped to [CLAMP_LO, CLAMP_HI] before drawing.
const CLAMP_LO: f64 = 50.0;
const CLAMP_HI: f64 = 450.0;

/// The box [50, 450]² beyond which θ changes nothing (the paper's clamp).
pub const BOUNDS: [f64; 2] = [CLAMP_LO, CLAMP_HI];

/// The most pixels a square's support spans along one axis (2·46.65 rounded up, plus
/// slack).
const SPAN: usize = 96;

/// The 1-D factors |d/50|¹⁰ of one square along one axis, over its support's pixels.
#[derive(Clone, Debug)]
struct Profile {
    /// First pixel of the support.
    lo: usize,
    /// Last pixel of the support (inclusive).
    hi: usize,
    /// `tenth` at each pixel lo..=hi (`SPAN` entries, the first hi − lo + 1 used).
    tenth: [f64; SPAN],
}

impl Profile {
    /// Along rows (`row = true`: d = centre − r) or columns (d = c − centre).
    fn new(centre: f64, row: bool) -> Self {
        let (lo, hi) = range(centre);
        let mut tenth_at = [0.0; SPAN];
        for (k, t) in tenth_at[..=hi - lo].iter_mut().enumerate() {
            let pixel = (lo + k) as f64;
            *t = tenth(if row { centre - pixel } else { pixel - centre });
        }
        Profile {
            lo,
            hi,
            tenth: tenth_at,
        }
    }

    /// The factors over the support, pixel lo first.
    fn factors(&self) -> &[f64] {
        &self.tenth[..=self.hi - self.lo]
    }
}

/// J from the two 1-D factors: clamp(1 − 2·(row + column), 0, 1), exactly as
/// [`value`] computes it.
#[inline]
fn combine(row: f64, column: f64) -> f64 {
    (1.0 - 2.0 * (row + column)).clamp(0.0, 1.0)
}

/// Independent partial sums of the pixel loops: the additions of different lanes do
/// not wait on one another, so the loops vectorise.
const LANES: usize = 8;

/// Σ over `columns` of J² for the row factor `row`.
fn squares(row: f64, columns: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let chunks = columns.chunks_exact(LANES);
    let tail: f64 = chunks
        .remainder()
        .iter()
        .map(|&c| combine(row, c).powi(2))
        .sum();
    for chunk in chunks {
        for (a, &c) in acc.iter_mut().zip(chunk) {
            *a += combine(row, c).powi(2);
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Σ over `columns` of (J − J*)² for the row factor `row` and J* along the same pixels.
fn differences(row: f64, columns: &[f64], target: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let chunks = columns.chunks_exact(LANES);
    let target_chunks = target.chunks_exact(LANES);
    let tail: f64 = chunks
        .remainder()
        .iter()
        .zip(target_chunks.remainder())
        .map(|(&c, &t)| (combine(row, c) - t).powi(2))
        .sum();
    for (chunk, target) in chunks.zip(target_chunks) {
        for ((a, &c), &t) in acc.iter_mut().zip(chunk).zip(target) {
            *a += (combine(row, c) - t).powi(2);
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Σ x² over `values`.
fn energy(values: &[f64]) -> f64 {
    values.iter().map(|x| x * x).sum()
}

/// The BOX2-REF objective.
#[derive(Clone, Debug)]
pub struct Box2Ref {
    /// The target's factors along rows and columns.
    target_rows: Profile,
    target_columns: Profile,
    /// J* over its support, row-major, one row per target row of width
    /// `target_columns.factors().len()`.
    target: Vec<f64>,
    /// Σ J*² along each target row.
    target_row_energy: Vec<f64>,
    /// Σ J*² over the image.
    target_energy: f64,
}

impl Default for Box2Ref {
    fn default() -> Self {
        Self::new()
    }
}

/// The 1-D factor |d/50|¹⁰ of the square's profile.
#[inline]
fn tenth(d: f64) -> f64 {
    let x = (d / HALF).powi(2);
    let x4 = x * x;
    x4 * x4 * x
}

/// Half-width of the support: 50·2^{−1/10}.
fn support() -> f64 {
    HALF * 2f64.powf(-0.1)
}

/// Inclusive pixel range [lo, hi] within 0..SIZE whose distance to `centre` is below
/// the support half-width.
fn range(centre: f64) -> (usize, usize) {
    let s = support();
    let lo = (centre - s).ceil().max(0.0) as usize;
    let hi = ((centre + s).floor().max(0.0) as usize).min(SIZE - 1);
    (lo, hi)
}

impl Box2Ref {
    /// The task with θ* = (150, 150).
    pub fn new() -> Self {
        let target_rows = Profile::new(TARGET[1], true);
        let target_columns = Profile::new(TARGET[0], false);
        let target: Vec<f64> = target_rows
            .factors()
            .iter()
            .flat_map(|&a| target_columns.factors().iter().map(move |&b| combine(a, b)))
            .collect();
        let target_row_energy: Vec<f64> = target
            .chunks_exact(target_columns.factors().len())
            .map(energy)
            .collect();
        let target_energy = target_row_energy.iter().sum();
        Box2Ref {
            target_rows,
            target_columns,
            target,
            target_row_energy,
            target_energy,
        }
    }

    /// The loss at θ (any finite θ; coordinates are clamped as in the paper).
    ///
    /// Σ (J_θ − J*)² = Σ_{box θ} (J_θ − J*)² + Σ_{box* ∖ box θ} J*², summed exactly (no
    /// cancellation against the precomputed energies, so the loss is 0 at θ*). J is
    /// separable before the clamp, so each pixel of θ's box combines two precomputed
    /// 1-D factors; J* is precomputed over its support and 0 outside it. Along each row
    /// the columns split into runs outside and inside the target's columns, each summed
    /// in `LANES` partial sums.
    pub fn loss(&self, theta: &[f64]) -> f64 {
        let p = [
            theta[0].clamp(CLAMP_LO, CLAMP_HI),
            theta[1].clamp(CLAMP_LO, CLAMP_HI),
        ];
        let rows = Profile::new(p[1], true);
        let columns = Profile::new(p[0], false);
        let (tr, tc) = (&self.target_rows, &self.target_columns);
        let width = tc.factors().len();
        let factors = columns.factors();
        // The shared columns, if any: [lo, hi] in image coordinates.
        let (lo, hi) = (columns.lo.max(tc.lo), columns.hi.min(tc.hi));
        let rows_meet = rows.lo <= tr.hi && tr.lo <= rows.hi;
        let mut sum = 0.0;
        for (r, &row) in (rows.lo..=rows.hi).zip(rows.factors()) {
            if lo > hi || !(tr.lo..=tr.hi).contains(&r) {
                sum += squares(row, factors);
                continue;
            }
            let target = &self.target[(r - tr.lo) * width..][..width];
            let (before, rest) = factors.split_at(lo - columns.lo);
            let (shared, after) = rest.split_at(hi - lo + 1);
            let (target_before, rest) = target.split_at(lo - tc.lo);
            let (target_shared, target_after) = rest.split_at(hi - lo + 1);
            sum += squares(row, before)
                + differences(row, shared, target_shared)
                + squares(row, after)
                + energy(target_before)
                + energy(target_after);
        }
        if lo > hi || !rows_meet {
            sum += self.target_energy;
        } else {
            for (r, &e) in (tr.lo..=tr.hi).zip(&self.target_row_energy) {
                if !(rows.lo..=rows.hi).contains(&r) {
                    sum += e;
                }
            }
        }
        sum / (SIZE * SIZE) as f64
    }

    /// The full 500×500 image I_θ (with the flip), row-major, for display.
    pub fn render(&self, theta: &[f64]) -> Vec<f64> {
        let p = [
            theta[0].clamp(CLAMP_LO, CLAMP_HI),
            theta[1].clamp(CLAMP_LO, CLAMP_HI),
        ];
        let mut img = vec![0.0; SIZE * SIZE];
        for r in 0..SIZE {
            for c in 0..SIZE {
                img[r * SIZE + c] = value(p, SIZE - 1 - r, c);
            }
        }
        img
    }
}

/// J(r, c) for the square at p = (pₓ, p_y).
#[inline]
fn value(p: [f64; 2], r: usize, c: usize) -> f64 {
    (1.0 - 2.0 * (tenth(p[1] - r as f64) + tenth(c as f64 - p[0]))).clamp(0.0, 1.0)
}

impl Objective<f64> for Box2Ref {
    fn evaluate(&mut self, theta: &[f64], _seed: NoiseSeed) -> f64 {
        if theta.len() != 2 || theta.iter().any(|x| !x.is_finite()) {
            return f64::NAN;
        }
        self.loss(theta)
    }

    fn deterministic(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The brute-force loss over all 250 000 pixels of the flipped images.
    fn brute(theta: [f64; 2]) -> f64 {
        let t = Box2Ref::new();
        let (a, b) = (t.render(&theta), t.render(&TARGET));
        a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / (SIZE * SIZE) as f64
    }

    #[test]
    fn plateau_value_matches_the_paper() {
        let t = Box2Ref::new();
        let plateau = t.loss(&[300.0, 320.0]);
        assert!((plateau - 0.0520089).abs() < 5e-8, "{plateau}");
        assert_eq!(t.loss(&[300.0, 320.0]), t.loss(&[260.0, 355.0]));
        assert_eq!(t.loss(&TARGET), 0.0);
    }

    #[test]
    fn support_restricted_loss_equals_brute_force() {
        let t = Box2Ref::new();
        for theta in [
            [150.0, 150.0],
            [171.3, 140.2],
            [199.0, 120.5],
            [40.0, 460.0],
            [240.0, 260.0],
        ] {
            let fast = t.loss(&theta);
            let slow = brute(theta);
            assert!((fast - slow).abs() < 1e-12, "{theta:?}: {fast} vs {slow}");
        }
    }

    /// The loss pixel by pixel with `value` over both bounding boxes (the target's
    /// precomputed energy where they are disjoint).
    fn per_pixel(t: &Box2Ref, theta: [f64; 2]) -> f64 {
        let p = theta.map(|x| x.clamp(CLAMP_LO, CLAMP_HI));
        let ((r0, r1), (c0, c1)) = (range(p[1]), range(p[0]));
        let ((t0, t1), (u0, u1)) = (range(TARGET[1]), range(TARGET[0]));
        let mut sum = 0.0;
        for r in r0..=r1 {
            for c in c0..=c1 {
                sum += (value(p, r, c) - value(TARGET, r, c)).powi(2);
            }
        }
        if r1 < t0 || r0 > t1 || c1 < u0 || c0 > u1 {
            return (sum + t.target_energy) / (SIZE * SIZE) as f64;
        }
        for r in t0..=t1 {
            for c in u0..=u1 {
                if !(r0..=r1).contains(&r) || !(c0..=c1).contains(&c) {
                    sum += value(TARGET, r, c).powi(2);
                }
            }
        }
        sum / (SIZE * SIZE) as f64
    }

    /// The separable, run-split evaluation agrees with the pixel-by-pixel sum to
    /// rounding, and is exactly 0 at θ*.
    #[test]
    fn separable_loss_matches_per_pixel() {
        let t = Box2Ref::new();
        let mut x = 0.123_f64;
        for _ in 0..400 {
            x = (x * 7.31 + 0.417).fract();
            let y = (x * 3.77 + 0.291).fract();
            let theta = [60.0 + 260.0 * x, 60.0 + 260.0 * y];
            let (fast, slow) = (t.loss(&theta), per_pixel(&t, theta));
            assert!(
                (fast - slow).abs() <= 1e-13 * slow,
                "{theta:?}: {fast} vs {slow}"
            );
        }
        assert_eq!(t.loss(&TARGET), 0.0);
        assert_eq!(per_pixel(&t, TARGET), 0.0);
    }

    #[test]
    fn non_finite_parameters_give_nan_for_the_estimators_to_report() {
        let mut t = Box2Ref::new();
        assert!(t.evaluate(&[f64::NAN, 1.0], 0).is_nan());
    }
}
