//! σ between descents and across a run: σ held where samples tie on a plateau
//! (`Auto::hold_sigma`), widened, or set by the restarts' cycle σ₀·2^k; restarts from
//! the best point, fresh starts about it, and the best points a continuation move or an
//! earlier descent left behind.

use rand_core::Rng;

use super::options::AutoStep;
use super::{
    Auto, Check, PLATEAU_WIDTH, RESTART_SCALES, RESTARTS, RESTARTS_BEFORE_FRESH, State,
    UNVARIED_WIDTH, reflect,
};
use crate::real::Real;
use crate::sample::normal;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Keeps σ off the scales where it has already learnt nothing since f(θ) last fell:
    /// an iteration that began at `sigma` and would end below it keeps `sigma` and draws
    /// another pair instead:
    ///
    /// * when the new σ would be at or under [`State::tie_scale`], where the samples tied
    ///   (a plateau): there they would only tie again, and the run would cycle between
    ///   the two scales;
    /// * on a plateau (a tie scale is set), when its model was blind — it saw no
    ///   decrease (`AtModelMinimum`), or f rose by more than the decrease it predicted
    ///   (ρ̂ < −1) — and the new σ would be at or under [`State::rough_scale`], where the
    ///   model was blind before.
    ///
    /// A blind model that is held also widens σ as on a plateau, with `sigma` the new
    /// rough scale: on a plateau the variation the quadratic cannot see is jitter (a
    /// rasteriser's pixel counts), and the samples of a wider σ may reach a slope. Off
    /// plateaus a blind model shrinks σ as before: on a rugged f the lower values lie
    /// at finer scales. A gain or a restart clears both scales.
    pub(super) fn hold_sigma(&mut self, sigma: T, kind: AutoStep, ratio: Option<T>) {
        if self.st.gained {
            self.forget_scales();
            return;
        }
        let next = self.st.sigma;
        if next >= sigma {
            return;
        }
        let blind = kind == AutoStep::AtModelMinimum || ratio.is_some_and(|r| r < -T::ONE);
        let tied = next <= self.st.tie_scale;
        let rough = blind && self.st.tie_scale > T::ZERO && next <= self.st.rough_scale;
        if !tied && !rough {
            return;
        }
        self.st.sigma = sigma;
        self.st.resample = true;
        if blind {
            self.st.rough_scale = sigma;
            self.st.sigma = self.widened_sigma(PLATEAU_WIDTH);
        }
    }

    /// Clears the tie, rough, failure and short-step scales (`Auto::hold_sigma`,
    /// `State::fail_scale`, `State::poor_scale`): f(θ) fell, or the run restarts, so
    /// what they recorded no longer describes θ's surroundings.
    pub(super) fn forget_scales(&mut self) {
        self.st.tie_scale = T::ZERO;
        self.st.rough_scale = T::ZERO;
        self.st.fail_scale = T::ZERO;
        self.st.poor_scale = T::ZERO;
    }

    /// The widest σ: `width`·σ₀, at most [`Auto::max_scale`] and, with bounds, half the
    /// box's widest side. Where f(θ) is finite and no value of the run has differed from
    /// it yet ([`State::varied`]), `width` is [`UNVARIED_WIDTH`] instead: every sample so
    /// far tied with θ, so σ₀ may lie below the scale at which f changes at all
    /// (σ₀ = 10⁻¹² where f's values are near 10⁸, whose spacing is 10⁻⁸), and only a
    /// wider σ can see a slope.
    fn sigma_cap(&self, width: f64) -> T {
        let width = if self.st.varied || self.st.value.is_none() {
            width
        } else {
            width.max(UNVARIED_WIDTH)
        };
        let mut cap = (self.st.sigma0 * T::from_f64(width)).min(Self::max_scale());
        if self.st.bounded {
            // Halves before the difference: a box as wide as T's range has a finite half.
            let half = (0..self.theta.len()).fold(T::ZERO, |w, i| {
                w.max(T::HALF * self.mem.upper[i] - T::HALF * self.mem.lower[i])
            });
            if half > T::ZERO && half.is_finite() {
                cap = cap.min(half);
            }
        }
        cap
    }

    /// 2σ, capped as [`Auto::sigma_cap`] says.
    pub(super) fn widened_sigma(&self, width: f64) -> T {
        (self.st.sigma * T::TWO)
            .min(self.sigma_cap(width))
            .max(self.st.sigma)
    }

    /// σ₀·2^(k mod [`RESTART_SCALES`]) for the k-th restart of the run, at most
    /// [`PLATEAU_WIDTH`]·σ₀ and, with bounds, half the box's widest side.
    pub(super) fn restart_sigma(&self) -> T {
        let doublings = (self.st.cycle % RESTART_SCALES) as i32;
        let sigma = self.st.sigma0 * T::from_f64(libm::pow(2.0, f64::from(doublings)));
        let cap = self.sigma_cap(PLATEAU_WIDTH);
        sigma.min(cap).max(self.st.sigma0.min(cap))
    }

    /// Whether f(θ) is below the best point's value, or θ is the best point. A gain made
    /// by a centre that a continuation move left above the best point resets the
    /// staleness count (the centre is still descending) but earns no further restart:
    /// it is no progress of the run.
    pub(super) fn below_best(&self) -> bool {
        match (self.st.best_value, self.st.value) {
            (Some(b), Some(v)) => v < b,
            (Some(_), None) => false,
            (None, _) => true,
        }
    }

    /// Clears the continuation's record once θ is below the best point again.
    pub(super) fn keep_best(&mut self) {
        if self.st.best_value.is_some() && self.below_best() {
            self.st.best_value = None;
        }
    }

    /// Moves θ back to the best point a continuation move left.
    pub(super) fn restore_best(&mut self) {
        if let Some(b) = self.st.best_value.take() {
            self.theta.copy_from_slice(self.mem.best);
            self.st.value = Some(b);
        }
    }

    /// Moves θ to the best point of the earlier descents where that is at least as good
    /// as the current descent's, or back to x₀ where no value has been finite.
    pub(super) fn restore_record(&mut self) {
        if self.record_leads() || self.nothing_finite() {
            self.theta.copy_from_slice(self.mem.record);
            self.st.value = self.st.record;
        }
    }

    /// Restarts in a row without a gain, after the first such one, before the descent
    /// ends ([`AutoOptions::restarts`](super::AutoOptions::restarts), or its default for this run).
    pub(super) fn restarts(&self) -> usize {
        self.options.restarts.unwrap_or(if self.may_start_fresh() {
            RESTARTS_BEFORE_FRESH
        } else {
            RESTARTS
        })
    }

    /// Whether a descent that ended (converged, or stagnated after its restarts) is
    /// followed by a fresh one ([`AutoOptions::fresh_starts`](super::AutoOptions::fresh_starts)): the run has a budget
    /// and the objective is deterministic (values on different seeds, or draws of
    /// unseeded noise, would make one descent's best point incomparable with
    /// another's).
    pub(super) fn may_start_fresh(&self) -> bool {
        self.options.fresh_starts
            && self.options.max_evaluations.is_some()
            && !self.st.noisy
            && !self.st.unseeded
    }

    /// Begins a new descent from a fresh start about the run's best point, as basin
    /// hopping does: each coordinate moved by its start scale times 2^(k mod
    /// [`RESTART_SCALES`]) times a standard normal draw for the k-th fresh start (the
    /// cycle's widest by at least the coordinate's side of the box), and mirrored into
    /// the box. The best point so far is kept as the record; the jump is
    /// from where its descent left it ([`Memory::origin`](super::memory::Memory::origin),
    /// before `Auto::centre` moved it). The memory,
    /// the model and the metric start over as in [`Auto::new`]; σ starts at the k-th
    /// restart's scale σ₀·2^(k mod [`RESTART_SCALES`]) ([`Auto::restart_sigma`]'s cap),
    /// where continuation applies: the wider the jump, the wider the first look, at
    /// a smoothed objective whose minimum lies past the wells a descent at σ₀ ends
    /// in (Griewank's, a rotated Rastrigin's). Once a probe of the run has found a
    /// point below the record (the `probe` module), or two wide descents in a row have
    /// ended on the same value (|v − w| ≤ √ε·max(|v|, |w|)), σ starts at σ₀ instead:
    /// the run's minima are one block of θ wrong, which the probes fix, or the
    /// smoothed objective leads every wide descent to one point (Gallagher's peaks,
    /// Schwefel's function), and σ₀ descents from scattered jumps sample the basins
    /// that a wide one averages away. Where no evaluation
    /// has been finite yet (a start where the objective fails, NaN all around), the jump
    /// is from the run's start, not from the last jump's end: the search spreads about
    /// x₀ instead of wandering off in a random walk (and such a descent ends once σ has
    /// widened to its cap, `Auto::step`).
    pub(super) fn fresh_start(&mut self) {
        self.keep_record();
        if self.st.fresh_wide {
            if let (Some(v), Some(w)) = (self.st.value, self.st.wide_end)
                && (v - w).abs() <= self.grain().sqrt() * v.abs().max(w.abs())
            {
                self.st.fresh_narrow = true;
            }
            self.st.wide_end = self.st.value;
        }
        self.theta.copy_from_slice(self.mem.origin);
        let n = self.theta.len();
        let k = self.st.fresh % RESTART_SCALES;
        let widen = T::from_f64(libm::pow(2.0, f64::from(k)));
        self.st.fresh = self.st.fresh.wrapping_add(1);
        let least = self.least_start_scale();
        // The widest jump of the cycle reaches across the box: where a caller's σ₀ is
        // far narrower than the bounds they gave, the search still looks beyond the
        // basins about its start.
        let widest = k + 1 == RESTART_SCALES;
        for i in 0..n {
            let x = self.theta[i];
            let spread = self.start_scale(i).max(least) * widen;
            let side = self.mem.upper[i] - self.mem.lower[i];
            let spread = if widest && self.boxed(i) && side.is_finite() {
                spread.max(side)
            } else {
                spread
            };
            self.theta[i] = self.jumped_by(i, x, spread);
        }
        self.new_descent();
        self.st.explore.fresh_started(self.st.evaluations);
        self.st.fresh_wide = k > 0 && !self.st.fresh_narrow;
        if self.st.fresh_wide {
            self.st.cycle = k;
            self.st.sigma = self.restart_sigma();
        }
    }

    /// Coordinate i moved from `from` by its start scale (at least `least`) times `widen`
    /// times a standard normal draw, mirrored into the box: a fresh start's jump and a
    /// probe's move.
    pub(super) fn jumped(&mut self, i: usize, from: T, widen: T, least: T) -> T {
        let spread = self.start_scale(i).max(least) * widen;
        self.jumped_by(i, from, spread)
    }

    /// Coordinate i moved from `from` by `spread` times a standard normal draw, mirrored
    /// into the box.
    fn jumped_by(&mut self, i: usize, from: T, spread: T) -> T {
        let x = from + spread * normal::quantile(T::uniform_open(&mut self.rng));
        reflect(x, self.mem.lower[i], self.mem.upper[i])
    }

    /// Keeps the descent's best point as the run's record where it beats the record
    /// ([`Memory::record`](super::memory::Memory::record)), and where the descent left it
    /// as the fresh start's origin ([`Memory::origin`](super::memory::Memory::origin)).
    pub(super) fn keep_record(&mut self) {
        self.restore_best();
        if !self.record_leads()
            && let Some(v) = self.st.value
        {
            self.mem.record.copy_from_slice(self.theta);
            self.st.record = Some(v);
            if !self.st.centred {
                self.mem.origin.copy_from_slice(self.theta);
            }
        }
    }

    /// Begins a new descent from θ as it stands: the memory, the model, the metric and σ
    /// start over as in [`Auto::new`], what the run as a whole has learnt (the
    /// record, the noise's kind, the fresh starts' count) is kept, and the descents'
    /// count ([`Auto::descents`]) goes up by one.
    pub(super) fn new_descent(&mut self) {
        let n = self.theta.len();
        let run = self.st;
        self.st = State {
            iteration: run.iteration,
            evaluations: run.evaluations,
            bounded: run.bounded,
            noisy: run.noisy,
            check: Check::after_restart(run.unseeded),
            unseeded: run.unseeded,
            dense: run.dense,
            voting: run.voting,
            failures: run.failures,
            groups: run.groups,
            metric_changes: run.metric_changes.wrapping_add(1),
            record: run.record,
            fresh: run.fresh,
            descent: run.descent.saturating_add(1),
            fresh_narrow: run.fresh_narrow,
            fresh_wide: run.fresh_wide,
            wide_end: run.wide_end,
            varied: run.varied,
            explore: run.explore,
            // What the line checks found of f holds for every descent.
            quadratic: run.quadratic,
            checked_sigma: run.checked_sigma,
            ..State::start(run.sigma0, n)
        };
        self.shape_scales();
        self.mem.path.fill(T::ZERO);
    }

    /// Starts over from the best point at `sigma` with the memory of points and the
    /// sampling metric. The metric is kept: it is a shape, not a scale, and the shape that
    /// a narrow valley or ridge taught is what the next descent along it needs. The last
    /// model is kept too, as the survey's first prior, where the descent showed f neither
    /// tied nor rough ([`State::tie_scale`](super::State::tie_scale),
    /// [`State::rough_scale`](super::State::rough_scale)): a survey of n pairs measures n
    /// of the curvature's n(n + 1)/2 coefficients, and on a smooth minimum the rest are
    /// what the descent learnt, which the points it left near θ hold every later fit of
    /// the restart to. Where f is rugged, the restart is a search at a wider scale, and a
    /// local minimum's curvature would hold its fits back.
    pub(super) fn restart(&mut self, sigma: T) {
        self.restore_best();
        let smooth = self.st.rough_scale <= T::ZERO && self.st.tie_scale <= T::ZERO;
        self.forget_scales();
        self.st.may_restart = false;
        self.st.stale = 0;
        self.st.hopeless = 0;
        self.st.unresolved = 0;
        self.st.settled = 0;
        self.st.blamed = 0;
        self.st.travelled = T::ZERO;
        self.st.fallen = T::ZERO;
        self.st.sigma = sigma;
        self.st.creep.restart();
        self.st.survey = true;
        self.st.has_prior &= smooth;
        self.st.check = Check::after_restart(self.st.unseeded);
    }
}
