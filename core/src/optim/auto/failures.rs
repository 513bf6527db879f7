//! Failed evaluations (NaN or ±∞) and whether to evaluate one again: [`Failures`], the
//! run's record of how its repeats ended.
//!
//! A failure may belong to its point (a wall: the objective is undefined there) or be
//! random (a renderer that sometimes crashes). A repeat at the same point and seed tells
//! them apart: until one returns a value the run checks, once per failure, and after
//! [`FAILURE_CHECKS`] failed checks it takes its failures as its points' own. Once one
//! has returned a value the objective fails at random, and a failure is repeated while
//! the next repeat is likely enough to return a value.
//!
//! That chance, after k failed repeats of one point, follows from two rates the run
//! estimates from its own repeats: p, the chance that an evaluation fails at random, from
//! the failed repeats of the points that returned a value at last; and w, the share of
//! failed points that belong to a wall, from the first repeats, which every failure gets
//! and which fail with probability w + (1 − w)p. A point that has failed k repeats fails
//! at random with probability (1 − w)pᵏ / ((1 − w)pᵏ + w), and the next repeat returns a
//! value with that probability times 1 − p. Where failures are random only (w = 0) a
//! failure is repeated until p^(1 + k) is negligible; beside a wall as well, a point that
//! keeps failing is given up after a repeat or two, where a fixed number of repeats
//! spent that many evaluations on every point beyond the wall.

use super::FAILURE_CHECKS;

/// The least chance that one more repeat of a failed evaluation returns a value for it
/// to be made.
const WORTH: f64 = 0.05;

/// The chance at most that a point failing at random is still failing when its
/// repeats end: a failure is repeated no more once p^(1 + repeats) ≤ this.
const LOST: f64 = 1e-4;

/// Repeats of one failed evaluation at most.
const MOST_REPEATS: usize = 16;

/// Once [`FAILURE_CHECKS`] checks have failed, the failed evaluations numbered 16, 32,
/// 64, … from there are checked again: an objective that fails at random with
/// probability p fails every first check with probability p^FAILURE_CHECKS (1 in 16 at p
/// = ½), and a run that took its failures for a wall then has a chance 1 − p at each
/// recheck to learn otherwise, while a wall's run pays one evaluation per doubling of
/// its failures.
const RECHECK_FROM: u32 = 16;

/// How the run's failed evaluations fared when repeated (module header). Kept across
/// descents.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Failures {
    /// Checks that failed too, while none has returned a value.
    checked: u8,
    /// Failed evaluations since [`FAILURE_CHECKS`] checks had failed, while none has
    /// returned a value: each whose number is a power of two from [`RECHECK_FROM`] is
    /// checked again.
    since_checks: u32,
    /// A repeat has returned a value: the objective fails at random.
    random: bool,
    /// Failed evaluations repeated since `random`.
    repeated: u32,
    /// Those whose first repeat failed too.
    first_failed: u32,
    /// Failed evaluations that a repeat turned into a value, since `random`.
    recovered: u32,
    /// Repeats of those that failed before the one that returned a value.
    misses: u32,
}

impl Failures {
    /// Whether the objective has been seen to fail at random.
    pub(super) fn random(&self) -> bool {
        self.random
    }

    /// Whether a failed evaluation whose `repeats` repeats have failed too is evaluated
    /// again: once while the run checks (fewer than [`FAILURE_CHECKS`] failed checks, then
    /// at each doubling of the failures since from [`RECHECK_FROM`]);
    /// once failures are known random, always once, and then while the next repeat
    /// returns a value with probability at least [`WORTH`] and p^(1 + repeats) > [`LOST`],
    /// at most [`MOST_REPEATS`] times.
    pub(super) fn repeat(&self, repeats: usize) -> bool {
        if !self.random {
            let next = self.since_checks.saturating_add(1);
            let recheck = next >= RECHECK_FROM && next.is_power_of_two();
            return repeats == 0 && (usize::from(self.checked) < FAILURE_CHECKS || recheck);
        }
        if repeats == 0 {
            return true;
        }
        if repeats >= MOST_REPEATS {
            return false;
        }
        let count = |c: u32| f64::from(c);
        // p from the recovered points' repeats, with half a count of prior on either
        // side; the share of first repeats that fail is w + (1 − w)p, with one count of
        // prior at p (no wall).
        let p = (count(self.misses) + 0.5) / (count(self.misses) + count(self.recovered) + 1.0);
        let first = (count(self.first_failed) + p) / (count(self.repeated) + 1.0);
        let wall = ((first - p) / (1.0 - p)).clamp(0.0, 1.0);
        let mut still = 1.0;
        for _ in 0..repeats {
            still *= p;
        }
        let random = (1.0 - wall) * still;
        still * p > LOST && random * (1.0 - p) >= WORTH * (random + wall)
    }

    /// Notes how a failed evaluation's repeats ended: `repeats` made, the first of them
    /// failing when `first_failed`, the last returning a value when `recovered`. Not for
    /// repeats the budget cut short.
    pub(super) fn note(&mut self, repeats: usize, first_failed: bool, recovered: bool) {
        if !self.random && !recovered && usize::from(self.checked) >= FAILURE_CHECKS {
            self.since_checks = self.since_checks.saturating_add(1);
            return;
        }
        if repeats == 0 {
            return;
        }
        let repeats = u32::try_from(repeats).unwrap_or(u32::MAX);
        if recovered && !self.random {
            self.random = true;
        } else if !self.random {
            self.checked = self.checked.saturating_add(1);
            return;
        }
        self.repeated = self.repeated.saturating_add(1);
        self.first_failed = self.first_failed.saturating_add(u32::from(first_failed));
        if recovered {
            self.recovered = self.recovered.saturating_add(1);
            self.misses = self.misses.saturating_add(repeats - 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Failures at a wall are checked [`FAILURE_CHECKS`] times, once each, and then once
    /// at each doubling of the failures since from [`RECHECK_FROM`]: 16, 32 and 64 of 100.
    #[test]
    fn a_wall_is_checked_failure_checks_times_and_at_doublings() {
        let mut f = Failures::default();
        let mut repeats = 0;
        for _ in 0..FAILURE_CHECKS + 100 {
            let mut k = 0;
            while f.repeat(k) {
                k += 1;
            }
            f.note(k, k > 0, false);
            repeats += k;
        }
        assert_eq!(repeats, FAILURE_CHECKS + 3);
        assert!(!f.random());
    }

    /// The repeats a failure gets follow the estimated rates: more where random failures
    /// are frequent, fewer where most points whose first repeat fails are a wall's, and
    /// always at least one.
    #[test]
    fn repeats_follow_the_estimated_rates() {
        let allowed = |f: &Failures| (0..).find(|&k| !f.repeat(k)).unwrap();
        let record = |repeated, first_failed, recovered, misses| Failures {
            checked: 0,
            since_checks: 0,
            random: true,
            repeated,
            first_failed,
            recovered,
            misses,
        };
        // p ≈ 0.1 and 0.5, no wall.
        let rare = allowed(&record(200, 20, 200, 22));
        let frequent = allowed(&record(200, 100, 200, 200));
        // p ≈ 0.1, and half the failed points a wall's: first repeats fail 55 % of the
        // time.
        let walled = allowed(&record(200, 110, 100, 11));
        assert!(frequent > rare, "{frequent} against {rare}");
        assert!(walled < rare, "{walled} against {rare}");
        assert!(walled >= 1);
        assert!(frequent <= MOST_REPEATS);
        // Without any record yet, a failure is repeated more than once.
        assert!(allowed(&record(0, 0, 0, 0)) > 1);
    }

    /// The first repeat that returns a value makes the failures random; from then on
    /// each repeated failure is counted.
    #[test]
    fn a_value_makes_failures_random() {
        let mut f = Failures::default();
        f.note(1, true, false);
        assert!(!f.random());
        assert_eq!(f.checked, 1);
        f.note(1, false, true);
        assert!(f.random());
        assert_eq!(
            (f.repeated, f.first_failed, f.recovered, f.misses),
            (1, 0, 1, 0)
        );
        f.note(3, true, true);
        f.note(2, true, false);
        assert_eq!(
            (f.repeated, f.first_failed, f.recovered, f.misses),
            (3, 2, 2, 2)
        );
        f.note(0, false, true);
        assert_eq!(f.repeated, 3, "no repeat, nothing to note");
    }
}
