//! Sparse probes about the best point before a fresh start.
//!
//! A descent's end is often a minimum where one part of θ is wrong and the rest right: a
//! shape hidden under another or stranded off its target while the others sit on theirs,
//! one coordinate of a lattice in the wrong cell, one term of a separable sum in the
//! wrong well. A fresh start moves every coordinate and loses what was right; a probe
//! moves one block of coordinates and keeps the rest, and its value alone says whether
//! the block found a better place (a hidden shape moved onto its own target lowers f at
//! once, however far it had to go). The parameters of one object usually sit side by
//! side in θ (a position's x and y, a colour's channels), so a probe's block is
//! contiguous: its length L = 2^j with j uniform over 0 … max(⌊log₂ n⌋ − 1, 0) (so L ≤ n/2
//! from n = 2 on: moving everything is the fresh start's part), its start uniform over the
//! multiples of L. Each
//! coordinate i of the block that is boxed on both sides is drawn uniformly over its box
//! within 32·sᵢ of the record's (sᵢ its start scale, 32 the widest fresh start's two
//! spreads), or over the whole box at k = 4 (below): a hidden object may belong anywhere
//! in the box, and a draw centred on where it is hidden reaches a target some spreads
//! away too rarely. Any other coordinate moves by sᵢ·2^k·ξᵢ, k uniform over 0 … 4 (as a
//! restart's and a fresh start's scales cycle) and ξᵢ ~ N(0, 1), mirrored into a bound
//! it has.
//!
//! Once a descent has ended, `Auto::begin_probes` keeps the best point as the record
//! and allots the probes: [`AutoOptions::probes`](super::AutoOptions::probes) per
//! coordinate, more where the run's probes have paid (the `explore` module);
//! `Auto::probe_step` evaluates them n at a time (one iteration each, at least two
//! probes), and the first batch with a value below the record's moves θ to its lowest
//! point and starts the next descent there, without a jump (its first iteration
//! evaluates θ again beside its survey, as every descent's first iteration does, so that
//! the new memory holds it). When the allotment is spent without one, the fresh start
//! follows as before. Probes cost no buffer: they are staged in the rows a survey uses.

use rand_core::Rng;

use super::explore::clearly_below;
use super::options::{AutoStep, AutoTermination};
use super::{Auto, AutoReport, RESTART_SCALES};
use crate::error::Error;
use crate::objective::Objective;
use crate::optim::vector::distance;
use crate::real::Real;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Ends a descent before a fresh start: keeps its best point as the record and
    /// allots the probes, or starts fresh at once where [`AutoOptions::probes`](super::AutoOptions::probes) is 0.
    pub(super) fn begin_probes(&mut self) {
        let before = self.st.record;
        self.keep_record();
        let evaluations = self.st.evaluations;
        let grain = self.grain();
        self.st
            .explore
            .descent_ended(evaluations, before, self.st.record, grain);
        let allotted = self
            .st
            .explore
            .allotment(self.theta.len(), self.options.probes);
        if allotted == 0 || self.st.record.is_none() {
            self.fresh_start();
        } else {
            self.st.probes = allotted;
        }
    }

    /// One batch of probes about the record (see the module's header).
    ///
    /// # Errors
    /// As [`Auto::step`]: a non-finite value under [`NonFinite::Error`](super::NonFinite::Error), a cancelled
    /// objective.
    pub(super) fn probe_step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
    ) -> Result<AutoReport<T>, Error> {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let rows = n
            .max(2)
            .min(self.st.probes)
            .min(self.mem.stage_f.len())
            .min(self.remaining());
        for row in 0..rows {
            self.stage_probe(row);
        }
        let mut spent = 0;
        self.evaluate(objective, 0, rows, &mut spent, |_| 0)?;
        self.st.iteration += 1;
        self.st.probes -= rows;
        let record = self.st.record.unwrap_or(T::MAX);
        let mut lowest: Option<(usize, T)> = None;
        for (row, &f) in self.mem.stage_f[..rows].iter().enumerate() {
            if f.is_finite() && f < record && lowest.is_none_or(|(_, l)| f < l) {
                lowest = Some((row, f));
            }
        }
        let grain = self.grain();
        let won = lowest.is_some_and(|(_, f)| clearly_below(f, record, grain));
        self.st.explore.probed(spent, won);
        let mut step_length = T::ZERO;
        if let Some((row, _)) = lowest {
            self.st.probes = 0;
            self.theta
                .copy_from_slice(&self.mem.stage[row * n..(row + 1) * n]);
            step_length = distance(self.mem.record, self.theta);
            self.new_descent();
            self.st.fresh_narrow = true;
            self.st.fresh_wide = false;
        } else if self.st.probes == 0 && self.remaining() > 0 {
            self.fresh_start();
        }
        let termination = (self.remaining() == 0).then_some(AutoTermination::MaxEvaluations);
        Ok(self.end_iteration(sigma, step_length, None, AutoStep::Probed, termination))
    }

    /// Writes stage row `row`: the record with one block of its coordinates moved.
    fn stage_probe(&mut self, row: usize) {
        let n = self.theta.len();
        // Block lengths 1, 2, …, 2^(levels − 1) ≤ n/2 (1 alone for n ≤ 3).
        let levels = (usize::BITS - (n / 2).max(1).leading_zeros()) as usize;
        let length = 1 << self.uniform_below(levels);
        let start = length * self.uniform_below(n.div_ceil(length));
        let doublings = self.uniform_below(RESTART_SCALES as usize);
        let widen = T::from_f64(libm::pow(2.0, doublings as f64));
        let least = self.least_start_scale();
        self.mem.stage[row * n..(row + 1) * n].copy_from_slice(self.mem.record);
        for i in start..(start + length).min(n) {
            self.mem.stage[row * n + i] = self.probed(i, widen, least);
        }
    }

    /// Coordinate i of a probe. Boxed on both sides: uniform over the box within
    /// 2^[`RESTART_SCALES`] start scales (at least `least`) of the record's coordinate,
    /// or over the whole box where `widen` is the widest, 2^([`RESTART_SCALES`] − 1).
    /// Otherwise: the record's coordinate [`jumped`](Auto::jumped) by `widen` start
    /// scales.
    fn probed(&mut self, i: usize, widen: T, least: T) -> T {
        let (lower, upper) = (self.mem.lower[i], self.mem.upper[i]);
        let from = self.mem.record[i];
        if !self.boxed(i) {
            return self.jumped(i, from, widen, least);
        }
        let reach = self.start_scale(i).max(least) * T::from_f64(f64::from(1u32 << RESTART_SCALES));
        // The widest probes draw over the whole box (as the widest fresh start jumps
        // across it): a σ₀ far narrower than the bounds still lets them look there.
        let widest = widen >= T::from_f64(f64::from(1u32 << (RESTART_SCALES - 1)));
        let (lo, hi) = if widest {
            (lower, upper)
        } else {
            (lower.max(from - reach), upper.min(from + reach))
        };
        let u = T::uniform_open(&mut self.rng);
        let width = hi - lo;
        let x = if width.is_finite() {
            lo + width * u
        } else {
            // A box as wide as T's range: its width overflows, its weighted ends do not.
            lo * (T::ONE - u) + hi * u
        };
        x.max(lo).min(hi)
    }

    /// A uniform draw from 0 … k − 1 (k ≥ 1).
    fn uniform_below(&mut self, k: usize) -> usize {
        (self.rng.next_u64() % k as u64) as usize
    }
}
