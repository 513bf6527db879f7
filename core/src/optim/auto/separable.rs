//! Whether f is separable, f(x) = Σᵢ gᵢ(xᵢ): the test by which the default model
//! ([`AutoModel::ByDimension`]) takes the diagonal shape from n = 15, where the full
//! model's memory no longer determines it.
//!
//! A separable f has no mixed differences: for disjoint sets of coordinates A and B and
//! offsets d_A, d_B along them,
//!
//! D = f(θ + d_A + d_B) − f(θ + d_A) − f(θ + d_B) + f(θ) = 0,
//!
//! and a pair of coordinates that interact, one in A and one in B, makes D ≠ 0 (for a
//! quadratic D = Σ_{i∈A, j∈B} H_ij d_i d_j). Splitting the coordinates by each bit of their
//! index, A_b = {i : bit b of i is 1} and B_b its complement for b < ⌈log₂ n⌉, puts every
//! pair on opposite sides in at least one split, and every split shares the point
//! θ + d. Two more points, θ + d/2 and θ + d/4, check whether f is a quadratic along the
//! line θ + t·d to rounding (`on_quadratic`); a full model then takes no axis prior
//! (`model::deviation_share`). One line near x₀ cannot see a kink further on (an L1
//! norm's at the minimum, past a start that lies beyond it in every coordinate), so
//! such a run checks again, along the same kind of line from θ at the current scale,
//! each time σ has fallen tenfold ([`RECHECK`]; three evaluations, θ's value known),
//! and takes the prior back for good where f is no quadratic there. The test costs
//! 4 + 2⌈log₂ n⌉ evaluations (14 at n = 20),
//! once, before the first survey, which takes the test's f(θ) rather than evaluating θ
//! again. Only a D within
//! rounding of zero in every split — |D| ≤ 4nε(|f(θ + d)| + |f(θ + d_A)| + |f(θ + d_B)| +
//! |f(θ)|) — passes, so a function whose coordinates
//! interact anywhere in the test's reach keeps the full model; values all equal to f(θ)
//! (a plateau) tell nothing, and non-finite ones fail.
//!
//! Why it pays: above n = 14 the full model's (n + 1)(n + 2)/2 coefficients outnumber its
//! memory, each fit leans on the last, and on kinks (the L1 norm) it mispredicts most
//! steps; the diagonal model's 2n + 1 coefficients are determined by its memory, and it
//! holds a separable f's curvature exactly. On a rotated f the diagonal model fails, and
//! there the test keeps the full one.

use rand_core::Rng;

use super::memory::memory_determines_model;
use super::model::Shape;
use super::options::{AutoModel, AutoStep};
use super::{Auto, Memory};
use crate::error::Error;
use crate::objective::Objective;
use crate::real::Real;

/// Splits of the coordinates the test makes in dimension n: ⌈log₂ n⌉, one per bit of an
/// index below n.
const fn splits(n: usize) -> usize {
    (usize::BITS - (n - 1).leading_zeros()) as usize
}

/// Points the test evaluates in dimension n: θ, θ + d, two per split, and θ + d/2 and
/// θ + d/4 for the line check.
const fn test_rows(n: usize) -> usize {
    4 + 2 * splits(n)
}

/// σ's fall, as a factor of σ at the last line check, at which a run that found f a
/// quadratic checks again ([`Auto::recheck_quadratic`]).
const RECHECK: f64 = 0.1;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Whether this run tests f's separability before its first survey: the default
    /// model in a dimension where the full model's memory does not determine it
    /// (15 ≤ n ≤ [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM)), a deterministic
    /// objective, nothing evaluated yet.
    pub(super) fn tests_separability(&self, noisy: bool) -> bool {
        let n = self.theta.len();
        self.model == AutoModel::ByDimension
            && self.shape == Shape::Full
            && !memory_determines_model(Shape::Full, n)
            && !noisy
            && self.st.evaluations == 0
    }

    /// Evaluates the test's points (module header) and, where f is separable, takes the
    /// diagonal model. The points but θ are not remembered (the first survey's geometry
    /// is what a first fit needs; θ's value is the survey's centre); the lowest is the
    /// run's record where it lies below f(x₀).
    /// Offsets are each coordinate's starting scale σL_ii, turned back where that would
    /// leave the box. Returns [`AutoStep::OutOfBudget`] where the budget ends
    /// within the test (the points evaluated so far count).
    ///
    /// Kept out of line: its frame (the memory's regions while they are cut) then adds
    /// nothing to the stack of a step that does not test.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] under [`NonFinite::Error`](super::NonFinite::Error).
    #[inline(never)]
    pub(super) fn test_separability<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<Option<AutoStep>, Error> {
        let n = self.theta.len();
        let rows = test_rows(n);
        self.line_offsets();
        self.st.checked_sigma = self.st.sigma;
        for row in 0..rows {
            let stage = &mut self.mem.stage[row * n..(row + 1) * n];
            for (i, x) in stage.iter_mut().enumerate() {
                // Row 0 is θ, row 1 θ + d, rows 2 + 2b and 3 + 2b θ + d_A and θ + d_B
                // for split b, the last two θ + d/2 and θ + d/4 (inside the box, which
                // holds θ and θ + d).
                let part = match row {
                    0 => T::ZERO,
                    1 => T::ONE,
                    _ if row == rows - 2 => T::HALF,
                    _ if row == rows - 1 => T::HALF * T::HALF,
                    _ if (i >> ((row - 2) / 2)) & 1 == (row % 2 == 0) as usize => T::ONE,
                    _ => T::ZERO,
                };
                *x = self.theta[i] + part * self.mem.rs[i];
            }
        }
        let allowed = rows.min(self.remaining());
        self.evaluate(objective, 0, allowed, spent, |_| 0)?;
        let f = &self.mem.stage_f[..allowed];
        self.st.tested_centre = f.first().copied();
        // A point below f(x₀) is the run's record until a descent beats it, as an
        // earlier descent's best would be (θ stays: the survey looks around x₀).
        let centre = f.first().copied().filter(|v| v.is_finite());
        self.record_lowest(allowed, centre);
        if allowed < rows {
            return Ok(Some(AutoStep::OutOfBudget));
        }
        let f = &self.mem.stage_f[..allowed];
        let (splits, line) = f.split_at(rows - 2);
        if separable(splits, n) {
            self.take_diagonal_model();
        } else {
            self.st.quadratic = on_quadratic([f[0], line[1], line[0], f[1]], n) == Some(true);
        }
        Ok(None)
    }

    /// Whether this step checks again that f is a quadratic ([`Auto::recheck_quadratic`]):
    /// the test or the last check found it one, f is deterministic, f(θ) is known, and σ
    /// has fallen to [`RECHECK`] times its value at that check.
    pub(super) fn rechecks_quadratic(&self, noisy: bool) -> bool {
        self.st.quadratic
            && !noisy
            && self.st.value.is_some()
            && self.st.sigma <= T::from_f64(RECHECK) * self.st.checked_sigma
    }

    /// Evaluates θ + d, θ + d/2 and θ + d/4, d as the test's from the current σ and
    /// metric, and clears [`State::quadratic`](super::State::quadratic) for the rest of
    /// the run where these and f(θ) lie on no quadratic in t to rounding (a kink between
    /// them, a non-finite value). A line too short to show curvature above rounding does
    /// not clear it. The points are not remembered; the lowest is the run's record where
    /// it lies below the best value so far. Returns [`AutoStep::OutOfBudget`] where the
    /// budget ends within the check.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] under [`NonFinite::Error`](super::NonFinite::Error).
    pub(super) fn recheck_quadratic<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<Option<AutoStep>, Error> {
        let n = self.theta.len();
        self.line_offsets();
        self.st.checked_sigma = self.st.sigma;
        // Rows: θ + d, θ + d/2, θ + d/4.
        for (row, part) in [T::ONE, T::HALF, T::HALF * T::HALF].into_iter().enumerate() {
            let stage = &mut self.mem.stage[row * n..(row + 1) * n];
            for ((x, &t), &d) in stage
                .iter_mut()
                .zip(self.theta.iter())
                .zip(self.mem.rs.iter())
            {
                *x = t + part * d;
            }
        }
        let allowed = 3.min(self.remaining());
        self.evaluate(objective, 0, allowed, spent, |_| 0)?;
        let best = self.value();
        self.record_lowest(allowed, best);
        if allowed < 3 {
            return Ok(Some(AutoStep::OutOfBudget));
        }
        let f = &self.mem.stage_f[..3];
        if self
            .st
            .value
            .is_some_and(|centre| on_quadratic([centre, f[2], f[1], f[0]], n).is_none())
        {
            self.st.quadratic = false;
        }
        Ok(None)
    }

    /// Writes the line's offset d to `rs`: each coordinate's scale σL_ii, towards the
    /// side of the box with room (or the whole room where neither side has that much).
    fn line_offsets(&mut self) {
        let n = self.theta.len();
        for i in 0..n {
            let h = self.st.sigma * self.mem.l[i * n + i];
            let (x, low, high) = (self.theta[i], self.mem.lower[i], self.mem.upper[i]);
            self.mem.rs[i] = if x + h <= high {
                h
            } else if x - h >= low {
                -h
            } else if high - x >= x - low {
                high - x
            } else {
                low - x
            };
        }
    }

    /// Makes the lowest finite value among the first `rows` staged points the run's
    /// record, where it lies below `than` (any finite value does where `than` is `None`).
    fn record_lowest(&mut self, rows: usize, than: Option<T>) {
        let n = self.theta.len();
        if let Some((k, &low)) = self.mem.stage_f[..rows]
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_finite())
            .min_by(|a, b| a.1.partial_cmp(b.1).unwrap_or(core::cmp::Ordering::Equal))
            && than.is_none_or(|v| low < v)
        {
            self.mem
                .record
                .copy_from_slice(&self.mem.stage[k * n..(k + 1) * n]);
            self.st.record = Some(low);
        }
    }

    /// Changes the run's model to the diagonal one before anything is remembered: the
    /// memory cut to the diagonal model's regions and the metric set up afresh from the
    /// coordinates' starting scales.
    fn take_diagonal_model(&mut self) {
        let n = self.theta.len();
        let memory = core::mem::replace(&mut self.mem, Memory::empty());
        self.mem = memory.reshaped(Shape::Diagonal, n);
        self.shape = Shape::Diagonal;
        self.st.factored = 0;
        self.shape_scales();
        // `shape_scales` worked in `tmp`, which holds θ at the iteration's start: x₀.
        self.mem.tmp.copy_from_slice(self.mem.origin);
    }
}

/// Whether the test's values (`f`: θ, θ + d, then θ + d_A and θ + d_B per split) show no
/// mixed difference beyond rounding, and not only ties with f(θ).
fn separable<T: Real>(f: &[T], n: usize) -> bool {
    let (centre, all) = (f[0], f[1]);
    if f.iter().any(|v| !v.is_finite()) || f.iter().all(|&v| v == centre) {
        return false;
    }
    let rounding = T::from_f64(4.0) * T::from_usize(n) * T::EPSILON;
    f[2..].chunks_exact(2).all(|pair| {
        let (a, b) = (pair[0], pair[1]);
        let mixed = all - a - b + centre;
        mixed.abs() <= rounding * (all.abs() + a.abs() + b.abs() + centre.abs())
    })
}

/// Whether f(θ + t·d) at t = 0, ¼, ½ and 1 (`f`, in that order) lies on a quadratic in t
/// to rounding: the quadratic through t = 0, ½ and 1 predicts f at ¼ as
/// (3f₀ + 6f_½ − f₁)/8, within 4nε of the four values' magnitudes. `None` where it does
/// not or a value is non-finite; otherwise whether its t² coefficient 2(f₀ − 2f_½ + f₁)
/// exceeds that bound (a piecewise-linear f, an L1 norm between its kinks, is straight
/// along a line that crosses none).
fn on_quadratic<T: Real>(f: [T; 4], n: usize) -> Option<bool> {
    let [at0, quarter, half, at1] = f;
    if f.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let rounding = T::from_f64(4.0) * T::from_usize(n) * T::EPSILON;
    let bound = rounding * f.iter().fold(T::ZERO, |s, v| s + v.abs());
    let predicted = (T::from_f64(3.0) * at0 + T::from_f64(6.0) * half - at1) / T::from_f64(8.0);
    let curvature = T::TWO * (at0 - T::TWO * half + at1);
    ((quarter - predicted).abs() <= bound).then_some(curvature.abs() > bound)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_cover_every_pair_of_coordinates() {
        for n in [15usize, 16, 17, 20, 32, 33, 63, 64, 127] {
            let bits = splits(n);
            assert!(1 << bits >= n && 1 << (bits - 1) < n, "n = {n}");
            for i in 0..n {
                for j in 0..i {
                    assert!((0..bits).any(|b| (i >> b) & 1 != (j >> b) & 1));
                }
            }
        }
        assert_eq!(test_rows(20), 14);
    }

    /// A coupled quadratic in 16 dimensions with its minimum at 0.3, plus `kinks` times
    /// the L1 norm about that minimum, run by Auto from x₀ = 3 with σ₀ = 1 (the test's
    /// line, x₀ + t, crosses no kink) until σ has fallen below 10⁻³. Returns
    /// `State::quadratic` after the first step and at the end.
    fn line_checks(kinks: f64, seed: u64) -> (bool, bool) {
        use rand_xoshiro::rand_core::SeedableRng;
        const N: usize = 16;
        let mut f = |x: &[f64]| {
            (0..N).fold(0.0, |s, i| {
                let (a, b) = (x[i] - 0.3, x[(i + 1) % N] - 0.3);
                s + a * a + 0.5 * a * b + kinks * a.abs()
            })
        };
        let mut theta = [3.0; N];
        let mut buffer = [0.0; super::super::buffer_len(N)];
        let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng).unwrap();
        auto.step(&mut f).unwrap();
        let first = auto.st.quadratic;
        while auto.st.sigma >= 1e-3 && matches!(auto.step(&mut f), Ok(Some(_))) {}
        assert!(
            auto.st.sigma < 1e-3,
            "the run ended at σ = {}",
            auto.st.sigma
        );
        (first, auto.st.quadratic)
    }

    /// The test finds both functions quadratics along its line; a recheck as σ falls
    /// finds the kinks and clears the finding, and leaves the quadratic's standing.
    #[test]
    fn a_recheck_finds_kinks_the_first_line_missed() {
        for seed in 1..=2 {
            assert_eq!(line_checks(0.0, seed), (true, true));
            assert_eq!(line_checks(1.0, seed), (true, false));
        }
    }

    #[test]
    fn the_line_check_takes_quadratics_only() {
        let along = |g: &dyn Fn(f64) -> f64| [0.0, 0.25, 0.5, 1.0].map(g);
        assert_eq!(
            on_quadratic(along(&|t| 3.0 - 2.0 * t + 0.7 * t * t), 20),
            Some(true)
        );
        assert_eq!(
            on_quadratic(along(&|t| 1e8 + (t - 0.3) * (t - 0.3)), 20),
            Some(true)
        );
        // A straight piece lies on a quadratic without curvature; a plateau too.
        assert_eq!(on_quadratic(along(&|t| 5.0 - 3.0 * t), 20), Some(false));
        assert_eq!(on_quadratic(along(&|_| 2.0), 20), Some(false));
        // A quartic, a kink and a NaN lie on none.
        assert_eq!(
            on_quadratic(along(&|t| 1.0 + t * t + 0.01 * t.powi(4)), 20),
            None
        );
        assert_eq!(on_quadratic(along(&|t| (t - 0.6).abs()), 20), None);
        assert_eq!(on_quadratic([0.0, f64::NAN, 1.0, 4.0], 20), None);
    }
}
