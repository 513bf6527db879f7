//! How long a run probes before each fresh start: longer where its probes have paid.
//!
//! Once a descent has ended, Auto looks for a lower point than the best in two ways:
//! probes, each the best point with one block of coordinates moved (the `probe` module),
//! and a fresh start, a whole new descent about it (`Auto::fresh_start`). Which of the two
//! pays depends on f. Where a local minimum is one object wrong and the rest right (a
//! shape hidden under another, a disc beside its target) a probe finds the way out in a
//! few hundred evaluations and a fresh descent, which moves every object, seldom does.
//! The run counts each way's wins — a probe phase that found a point below the best, a
//! fresh descent that ended below the best point it began from, each by more than √ε of
//! the values ([`clearly_below`]: a descent that polishes the same minimum again finds no
//! new one) — and the evaluations each spent, and lengthens each probe phase beyond its
//! default P·n by how much more often the probes have won per phase than the fresh
//! descents per descent:
//!
//! A = P·n · min(max(g, 1), [`SHARE_RANGE`]),  g = (r_p · P·n) / (r_f · D₁),
//! r_p = (W_p + ½) / (E_p + P·n),  r_f = (W_f + ½) / (E_f + D₁),
//!
//! with W and E each way's wins and evaluations, D₁ the first descent's evaluations (a
//! fresh descent's default cost) and P the probes per coordinate of
//! [`AutoOptions::probes`](super::AutoOptions::probes). Each way starts from half a win in
//! one default attempt, so g = 1 until either has spent something, and g exceeds 1 only
//! where probes have won. A phase never shrinks below P·n: on a rotated multi-modal f,
//! where fresh descents find the lower basins and probes seldom do, phases cut to an
//! eighth lost runs of BBOB's rotated Rastrigin at n = 5 (the 2026-12-04 note on probe
//! phases). A descent that a probe began counts for neither way: it polishes what the
//! probe found.

use crate::real::Real;

/// The most a probe phase may grow beyond its default allotment: 8 times.
pub const SHARE_RANGE: usize = 8;

/// Whether `a` lies below `b` by more than √`grain` of their magnitude (`grain` the
/// relative precision of f's values, `Auto::grain`): a win of the module's header.
/// (Polishing a minimum that an earlier descent found moves its value by far less.)
pub(super) fn clearly_below<T: Real>(a: T, b: T, grain: T) -> bool {
    a < b && b - a > grain.sqrt() * a.abs().max(b.abs())
}

/// Each way's wins and evaluations over a run (see the module's header).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Exploration {
    /// Evaluations of the first descent; 0 until it has ended.
    first: usize,
    /// Probe phases that found a point below the best.
    probe_wins: usize,
    /// Evaluations spent on probes.
    probe_evaluations: usize,
    /// Fresh descents that ended below the best point they began from.
    fresh_wins: usize,
    /// Evaluations of the fresh descents that have ended.
    fresh_evaluations: usize,
    /// Where the current descent began, if a fresh start began it: the run's evaluations
    /// then.
    fresh_began: Option<usize>,
}

impl Exploration {
    /// A descent ends after `evaluations` of the run, the run's best value `before` it
    /// and `after` it (`None`: none finite); a fresh descent won where `after` is
    /// [`clearly_below`] `before` (at f's precision `grain`), or finite where `before`
    /// was not.
    pub(super) fn descent_ended<T: Real>(
        &mut self,
        evaluations: usize,
        before: Option<T>,
        after: Option<T>,
        grain: T,
    ) {
        if self.first == 0 {
            self.first = evaluations.max(1);
        }
        if let Some(began) = self.fresh_began.take() {
            let won = match (before, after) {
                (Some(b), Some(a)) => clearly_below(a, b, grain),
                (None, after) => after.is_some(),
                (Some(_), None) => false,
            };
            self.fresh_wins += usize::from(won);
            self.fresh_evaluations += evaluations.saturating_sub(began);
        }
    }

    /// A fresh start begins a descent after `evaluations` of the run.
    pub(super) fn fresh_started(&mut self, evaluations: usize) {
        self.fresh_began = Some(evaluations);
    }

    /// A batch of `spent` probes has been evaluated; `won`: one of them lies below the
    /// best point (the descent it begins is no fresh one, so it counts for neither way).
    pub(super) fn probed(&mut self, spent: usize, won: bool) {
        self.probe_evaluations += spent;
        self.probe_wins += usize::from(won);
    }

    /// The probes of the next phase in dimension n with `per_coordinate` probes per
    /// coordinate by default: A of the module's header.
    pub(super) fn allotment(&self, n: usize, per_coordinate: usize) -> usize {
        let default = per_coordinate.saturating_mul(n);
        if default == 0 {
            return 0;
        }
        let (phase, descent) = (default as f64, self.first.max(1) as f64);
        let probe_rate = (self.probe_wins as f64 + 0.5) / (self.probe_evaluations as f64 + phase);
        let fresh_rate = (self.fresh_wins as f64 + 0.5) / (self.fresh_evaluations as f64 + descent);
        let range = SHARE_RANGE as f64;
        let gain = (probe_rate * phase / (fresh_rate * descent)).clamp(1.0, range);
        (libm::round(phase * gain) as usize).max(default)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn before_any_evidence_the_default() {
        let mut e = Exploration::default();
        e.descent_ended(1_234, None, Some(1.0), f64::EPSILON);
        assert_eq!(e.allotment(10, 20), 200);
        assert_eq!(e.allotment(1, 20), 20);
    }

    #[test]
    fn probes_that_win_grow_and_probes_that_fail_keep_the_default() {
        let mut wins = Exploration::default();
        wins.descent_ended(1_000, None, Some(1.0), f64::EPSILON);
        for _ in 0..4 {
            wins.probed(50, true);
            wins.descent_ended(2_000, Some(1.0), Some(0.5), f64::EPSILON);
        }
        wins.fresh_started(3_000);
        wins.descent_ended(4_000, Some(0.5), Some(0.5), f64::EPSILON);
        assert_eq!(wins.allotment(10, 20), 200 * SHARE_RANGE);

        let mut fails = Exploration::default();
        fails.descent_ended(1_000, None, Some(1.0), f64::EPSILON);
        for k in 0..8 {
            fails.probed(200, false);
            fails.fresh_started(1_000 * k);
            fails.descent_ended(1_000 * k + 1_000, Some(1.0), Some(0.5), f64::EPSILON);
        }
        assert_eq!(fails.allotment(10, 20), 200);
    }

    #[test]
    fn zero_probes_stay_zero() {
        let mut e = Exploration::default();
        e.descent_ended(10, None, Some(1.0), f64::EPSILON);
        assert_eq!(e.allotment(5, 0), 0);
    }
}
