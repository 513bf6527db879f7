//! One model step (`Auto::model_step`): fit the model around θ, take its trust-region
//! step, evaluate the trial, and judge it — accept or reject by the values, the ratio
//! ρ̂ of actual to predicted decrease, and what that says about σ (shrink, hold, widen,
//! or look wider where f is rough at this scale) and about the metric.

use rand_core::Rng;

use super::memory::{blaming, memory_determines_model, nearby_needed, validating};
use super::model::Shape;
use super::noise::NOISE_RADIUS;
use super::options::AutoStep;
use super::{
    Auto, CONTINUATION_SCALE, Check, DETERMINED_METRIC_WEIGHT, GROWTH_WIDTH, NOISE_MARGIN,
    PAIRS_PAY, PAIRS_SKIPPED, PLATEAU_WIDTH, REACH, ROUGH, SETTLED_FIT, SETTLED_HALVINGS, SHRINK,
    SMOOTH, STRIDE, THETA_DRAWS, lower_median, metric, resolution, tie_width,
};
use crate::error::Error;
use crate::objective::Objective;
use crate::optim::vector::norm;
use crate::real::Real;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Fits the model, evaluates its step and updates σ; returns what happened and the
    /// ratio of actual to predicted decrease.
    pub(super) fn model_step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<(AutoStep, Option<T>), Error> {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let root_n = T::from_usize(n).sqrt();
        let Some(value) = self.st.value else {
            return Ok((AutoStep::Plateau, None));
        };
        if !self.st.noisy && self.st.check == Check::Due {
            self.check_determinism(objective, value, spent)?;
        }
        if self.st.unseeded && !self.st.voting {
            self.st.voting = self.sparse_noise();
        }
        let Some((scale, noise, mut fitted)) = self.fit_about_cliffs(value) else {
            self.st.sigma = sigma * T::HALF;
            return Ok((AutoStep::Rejected, None));
        };
        self.st.unfitted = 0;
        let mut value = value;
        // θ's draw lies below the robust model's value at θ: it may be a lucky one.
        let mut lucky = false;
        // The fit's residuals grow with f (`Auto::residuals_grow`); assumed where unknown.
        let mut noise_grows = true;
        if self.st.unseeded {
            self.st.scatter = noise * scale;
            // One step of iteratively reweighted least squares per iteration, warm
            // started from the points' weights of the last. The noise level η stays the
            // first fit's: the scatter the robust fit sets aside is still the noise a
            // step must clear.
            let cut;
            (cut, noise_grows) = self.reweigh(value, scale);
            let Some((_, refitted)) = self.fit(value, scale, None) else {
                self.st.sigma = sigma * T::HALF;
                return Ok((AutoStep::Rejected, None));
            };
            fitted = refitted;
            lucky = self.mem.beta[0] > T::ZERO;
            // θ's own residual under the robust fit is −c. Where that makes its draw an
            // outlier — a lucky spike that would reject every later step — θ is drawn
            // again, and steps are judged against the new draw. (Only c depends on the
            // value the fit was taken relative to, and c is not used below.)
            if self.mem.beta[0].abs() >= cut && self.remaining() > 0 {
                let again = self.evaluate_theta_again(objective, spent)?;
                let group = self.next_group();
                self.remember(1, group, false);
                if again.is_finite() {
                    value = again;
                    self.st.value = Some(again);
                }
            }
        }
        self.save_prior(scale, sigma);
        // On flat noise the steps stay well inside the points the fit averages over.
        let flat_noise = self.flat_noise(noise * scale);
        let radius = if flat_noise {
            T::from_f64(NOISE_RADIUS) * root_n
        } else {
            root_n
        };
        let ok = self.trust_step(radius);
        // Project the trial point θ + σLs into the box; the step is what remains of s.
        metric::apply(self.shape, self.mem.l, self.mem.s, self.mem.gx);
        for i in 0..n {
            let x = (self.theta[i] + sigma * self.mem.gx[i])
                .max(self.mem.lower[i])
                .min(self.mem.upper[i]);
            self.mem.stage[i] = x;
            self.mem.rs[i] = (x - self.theta[i]) / sigma;
        }
        metric::apply(self.shape, self.mem.li, self.mem.rs, self.mem.s);
        let predicted = if ok {
            self.predicted_decrease()
        } else {
            T::ZERO
        };
        let length = norm(self.mem.s);
        // A model that claims a minimum near θ must have seen θ's surroundings in
        // enough directions before σ shrinks on its word; the pairs it lacks come in
        // one batch (on a declared-noisy objective one pair per iteration, the rule its
        // runs were measured with).
        let validated = self.count_around(T::from_f64(REACH)) > validating(self.shape, n);
        self.judge_basin(
            value,
            scale * predicted.max(T::ZERO),
            ok && noise <= T::from_f64(SMOOTH)
                && (validated || fitted > self.shape.coefficients(n))
                && length < T::from_f64(0.9) * radius,
        );
        // A trial point that moves no coordinate by more than f's arithmetic resolves
        // there ([`resolution`] at |θᵢ|, [`Auto::grain`]) is θ as far as f can tell:
        // the model's minimum lies within θ's rounding.
        let grain = self.grain();
        let unresolved_step = (0..n).all(|i| {
            (self.mem.stage[i] - self.theta[i]).abs() <= resolution(self.theta[i].abs(), grain)
        });
        if predicted <= T::ZERO
            || !predicted.is_finite()
            || length <= T::from_f64(1e-3) * radius
            || unresolved_step
        {
            if validated {
                // σ halves once, or more where the model confirmed at the scale above
                // predicted the points drawn since (SETTLED_HALVINGS). A confirmation on
                // points the last fit saw already says nothing new either way.
                let exact = !self.st.noisy && !self.st.unseeded;
                match self.st.prior_misfit {
                    Some(m) if exact && m <= T::from_f64(SETTLED_FIT) => {
                        self.st.settled = (self.st.settled + 1).min(SETTLED_HALVINGS);
                    }
                    None if exact => {}
                    _ => self.st.settled = 0,
                }
                let mut next = sigma * T::HALF;
                for _ in 1..self.st.settled {
                    next *= T::HALF;
                }
                self.st.sigma = next;
                self.st.confirmed = true;
                self.st.blamed = 0;
            } else {
                self.st.resample = true;
                self.st.validate = !self.st.noisy;
            }
            return Ok((AutoStep::AtModelMinimum, None));
        }
        // The step promises a decrease that T's arithmetic resolves (UNRESOLVED_FITS).
        let resolved = scale * predicted > tie_width(value, T::EPSILON);
        self.st.unresolved = if self.st.noisy || self.st.unseeded || resolved {
            0
        } else {
            self.st.unresolved.saturating_add(1)
        };
        // A noisy objective's trial is compared with f(θ) on common noise: the seed on
        // which this iteration measured f(θ), or a fresh one on which θ is evaluated too.
        // An unseeded objective's θ is drawn again beside the trial after a rejection,
        // where its draw lies below the robust fit, until it has THETA_DRAWS draws.
        let redraw = lucky && self.st.doubted && self.draws_at_theta() < THETA_DRAWS;
        let compare = self.st.noisy && self.st.shared.is_none() || redraw;
        let rows = if compare { 2 } else { 1 };
        if self.remaining() < rows {
            return Ok((AutoStep::OutOfBudget, None));
        }
        if compare {
            self.mem.stage[n..2 * n].copy_from_slice(self.theta);
        }
        let seed = self.rng.next_u64();
        let (seed, group) = match self.st.shared {
            Some(shared) => shared,
            None => (seed, self.next_group()),
        };
        self.evaluate(objective, 0, rows, spent, |_| seed)?;
        let trial = self.mem.stage_f[0];
        let mut reference = if compare { self.mem.stage_f[1] } else { value };
        self.remember(rows, group, false);
        if self.st.unseeded {
            // The trial must beat the median of θ's draws (the larger of two), which one
            // lucky draw — the low tail of the noise — cannot set.
            let draws = self.draws_at_theta();
            if redraw && draws == 2 {
                self.record_theta_spread(self.mem.sw[0], self.mem.sw[1]);
            }
            if draws > 0 {
                reference = lower_median(&self.mem.sw[..draws]);
            }
        }
        if compare && reference.is_finite() {
            self.st.value = Some(reference);
        }
        let ratio = if trial.is_finite() && reference.is_finite() {
            (reference - trial) / (scale * predicted)
        } else {
            -T::MAX
        };
        // A tie is accepted: on a flat piece of f the smoothed model's minimum is the
        // better guess (the middle of a zero-loss region, the continuous optimum of a
        // rounded function). On unseeded noise that every draw carries, a lower draw
        // moves θ only where it delivers a tenth of the decrease the model promised
        // (ρ̂ ≥ 0.1): a smaller one is as likely the noise's, and where the noise grows
        // with f (f·e^(N/2)) accepting such draws walked θ uphill without end.
        let lower = trial.is_finite() && reference.is_finite() && trial <= reference;
        let accepted = lower && !(self.dense_unseeded() && ratio < T::from_f64(0.1));
        let tie = accepted && trial == reference;
        if !accepted
            && trial.is_finite()
            && self.st.cycle > 0
            && sigma > T::from_f64(CONTINUATION_SCALE) * self.st.sigma0
            && length < T::from_f64(0.9) * radius
            && !self.st.noisy
            && (!self.st.unseeded || self.st.voting)
        {
            // Continuation: a restart at a scale above σ₀'s fits the smoothed objective,
            // whose minimum inside the trust region is where the search should go on
            // even where f itself is higher there (a local minimum's wells, a lattice's
            // cells, Rosenbrock's other valley). The centre moves, σ halves on the way
            // down, and the best point is kept (`Auto::restore_best`). A minimum on the
            // region's boundary is the model extrapolating: no move.
            if self.st.best_value.is_none() {
                self.st.best_value = Some(reference);
                self.mem.best.copy_from_slice(self.theta);
            }
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.value = Some(trial);
            self.st.sigma = sigma * T::HALF;
            return Ok((AutoStep::Continued, Some(ratio)));
        }
        // On an unseeded objective, a trial whose draw is higher than f(θ)'s by less than
        // twice the noise's scale, whose step promised no more than that, was judged by
        // the noise; on flat noise whatever it promised, for a fit that averages over
        // noise of θ's own scale promises the noise's excursions too. (A lower draw that
        // fell short of its promise, not accepted on dense noise, is a poor step as it
        // would be on an exact f.) The noise's scale is the spread of repeated draws;
        // where the memory holds too few, on dense noise that does not grow with f, the
        // fit's residual scatter. (Where it grows with f, the scatter of points a radius
        // out overstates the noise at θ, and widening σ on its word cost runs that reach
        // the minimum's precision.)
        let judged_by_noise = self.st.unseeded && !lower && {
            let scatter = (self.st.dense && !noise_grows).then_some(noise * scale);
            let level = T::TWO * self.repeat_spread().or(scatter).unwrap_or(T::ZERO);
            trial - reference <= level && (flat_noise || predicted * scale <= level)
        };
        let widened = self.widened_sigma(PLATEAU_WIDTH);
        let fails_wider = self.st.fail_scale > T::ZERO && widened >= self.st.fail_scale;
        let poor_wider = self.st.poor_scale > T::ZERO && widened >= self.st.poor_scale;
        if judged_by_noise
            || !accepted
                && noise > T::from_f64(ROUGH)
                && trial - reference <= T::TWO * noise * scale
                && !fails_wider
                && !poor_wider
        {
            // f is rough at this scale — the fit leaves scatter comparable to the values'
            // spread, or the step's promise is within the noise — and the trial is no
            // worse than that scatter: look wider, where the smoothed function has a
            // slope to see. Not as wide as a scale whose samples all failed about this θ
            // (`State::fail_scale`): there they fail again, and σ halves back to here.
            // Nor as wide as a scale whose fit was rough too and whose step fell short
            // since f(θ) last fell (`State::poor_scale`): there widening made the fit no
            // smoother — a smooth f seen from far up its flank, a parameter whose scale
            // shrinks with its size near a small optimum — so σ is too wide, not too
            // narrow, and the step is judged as any other that fell short. (Where the
            // wider fit was smooth, as Rastrigin's is once σ spans its wells, widening
            // goes on: a step there that falls short says nothing of roughness.)
            self.st.rough_scale = self.st.rough_scale.max(sigma);
            self.st.sigma = widened;
            return Ok((AutoStep::Plateau, Some(ratio)));
        }
        let boundary = length >= T::from_f64(0.9) * radius;
        let determined = fitted > self.shape.coefficients(n);
        // The step fell short of its prediction (ρ̂ < 0.1) without being a tie.
        let poor = ratio < T::from_f64(0.1) && !tie;
        let least_poor = self.st.poor_scale <= T::ZERO || sigma < self.st.poor_scale;
        if poor && least_poor && noise > T::from_f64(ROUGH) && !self.st.noisy && !self.st.unseeded {
            self.st.poor_scale = sigma;
            // Noise, undeclared, makes fits rough and their steps fall short just so,
            // and a poor scale would stop σ from widening out of it: the next model
            // step checks, and forgets the poor scale where it finds noise.
            if self.st.check == Check::Deferred {
                self.st.check = Check::Due;
            }
        }
        // Whether a shortfall may be blamed on σ: the points near θ determine the model
        // at this scale. Points farther out (z ≤ 2ρ fits them) do not count: they saw f
        // at wider scales, and a kink's smoothed curvature falls with the scale (a
        // cone's as 1/σ), so a model resting on them mispredicts alike at every smaller
        // σ and shrinking on its word only cascades σ down. Where a full model cannot be
        // determined by the memory (n ≥ 15), the points it needs double with each
        // shortfall blamed since the model last proved right (`blaming`): a kink looks
        // alike at every scale, and each smaller σ fails as the last did. The diagonal
        // model may be blamed once validated. A declared-noisy objective keeps the rule it
        // was measured with: a fit determined by its points, or a validated one (holding
        // σ lost SHADOW runs); with the diagonal model (n > FULL_MODEL_MAX_DIM there),
        // already once as many points lie within reach as a model needs to step
        // (`nearby_needed`, half the memory). Validation asks for all but two of the
        // remembered points, which a noisy run, whose accepted steps move θ by about the
        // radius, seldom has within reach: σ stayed at σ₀/4 while steps the noise
        // accepted walked θ uphill (CAUSTIC, n = 256).
        //
        // Before the run's first gain, in its first descent, on a deterministic
        // objective, a trial to the trust region's boundary that f rejects is blamed on
        // σ however few points lie near θ: every point so far was drawn about x₀ at
        // σ₀'s scale, and where σ₀ overstates the scale at which f is a quadratic the
        // fit takes f's higher-order terms there for slope and curvature (Rosenbrock's
        // cubic terms seen from 0 at σ₀ = 0.5), so that each step extrapolates to the
        // boundary and fails while σ waits for a determined model. A kink, whose
        // shortfalls look alike at every scale, meets this only at x₀ itself.
        let overstated = !accepted
            && boundary
            && self.st.descent == 1
            && !self.st.improved
            && !self.st.noisy
            && !self.st.unseeded;
        let blames_scale = poor
            && (overstated
                || if self.st.noisy {
                    determined
                        || validated
                        || self.shape == Shape::Diagonal
                            && self.count_around(T::from_f64(REACH)) > nearby_needed(self.shape, n)
                } else if memory_determines_model(self.shape, n) {
                    self.count_around(T::from_f64(REACH)) > self.shape.coefficients(n)
                } else if self.shape == Shape::Full {
                    self.count_around(T::from_f64(REACH)) > blaming(n, self.st.blamed)
                } else {
                    validated
                });
        // On an unseeded objective whose every draw is noisy, a trial whose draw is
        // higher by less than NOISE_MARGIN times the noise's scale may have been rejected
        // by the noise rather than the model: halving σ on its word shrinks the steps
        // until every comparison is a coin toss. The model needs more points at this
        // scale instead.
        let noise_rejected = poor
            && !lower
            && self.st.unseeded
            && self
                .dense_noise_scale()
                .is_some_and(|s| trial - reference <= T::from_f64(NOISE_MARGIN) * s);
        self.st.sigma = if poor && accepted && boundary && !self.st.noisy {
            // f fell, by far less than predicted, along a step the radius cut short:
            // the model overstates the decrease (a kink or a ridge its fit smooths
            // over, which no smaller σ fits better), not the direction. Shrinking σ
            // would only shorten the next step; let it grow a little instead. (On a
            // noisy objective so small a decrease may be the noise's.)
            (sigma * T::from_f64(STRIDE)).min(self.widened_sigma(GROWTH_WIDTH))
        } else if poor && (noise_rejected || self.st.lattice || !blames_scale) {
            // Too few points near θ to blame the scale, f is piecewise constant at it, or
            // the noise rejected the trial: keep σ. The trial is itself a point the
            // model lacked, within reach where it erred, and the next fit takes it in.
            // Where f is piecewise constant or noisy, or where pairs drawn after failed
            // steps have lowered f(θ) often enough (`PAIRS_PAY`), sample more at this σ
            // too; otherwise the next iteration draws only the pairs the points within
            // reach still lack.
            self.st.resample = noise_rejected
                || self.st.lattice
                || self.st.noisy
                || self.st.pair_rate >= T::from_f64(PAIRS_PAY)
                || self.st.pairs_skipped >= PAIRS_SKIPPED;
            if self.st.resample {
                self.st.pair_pending = true;
                self.st.pairs_skipped = 0;
            } else {
                self.st.pairs_skipped += 1;
            }
            sigma
        } else if poor && self.st.noisy {
            sigma * T::HALF
        } else if poor {
            self.st.blamed = self.st.blamed.saturating_add(1);
            sigma * T::from_f64(SHRINK)
        } else if ratio >= T::from_f64(0.7) && boundary {
            self.widened_sigma(GROWTH_WIDTH)
        } else if length < T::HALF * radius && validated {
            sigma * (T::TWO * length / radius).max(T::HALF)
        } else {
            sigma
        };
        if overstated && self.st.sigma < self.st.lowest_sigma {
            // σ₀ overstated the scale at which f is a quadratic, and σ is still shrinking
            // to it: the patience counts from here (`State::lowest_sigma`).
            self.st.lowest_sigma = self.st.sigma;
            self.st.stale = 0;
        }
        self.st.unconfirmed = self.st.unconfirmed.saturating_add(1);
        if accepted && ratio >= T::from_f64(0.1) {
            // The model predicted the decrease: trust its curvature's shape.
            self.learn_metric(1.0);
            self.st.blamed = 0;
            self.st.unconfirmed = 0;
        } else if !self.st.noisy
            && (!self.st.unseeded || self.st.voting)
            && !self.st.lattice
            && self.st.tie_scale <= T::ZERO
            && !self.on_face()
            && (determined && noise <= T::from_f64(SMOOTH) || self.stalled_on_shape())
        {
            // The points determine the curvature, and fit it closely, though the step
            // did not confirm it: a cone's or a kink's smoothed curvature is what the
            // metric needs even where the quadratic mispredicts f's steps. Or no fit can
            // be determined and a shape the metric has not learnt stalls the run
            // ([`STALLED_ANISOTROPY`]). (Not where samples have tied since f last fell:
            // on a lattice the fitted curvature is the steps', not f's. Nor with θ on a
            // face of the box: samples mirrored there make f look flat across the face,
            // C would stretch along its normal, and steps along that axis are cut off by
            // the bound.)
            self.learn_metric(DETERMINED_METRIC_WEIGHT);
        }
        self.st.doubted = self.st.unseeded && !accepted;
        if accepted {
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.value = Some(trial);
            self.st.gained |= self.clears_noise(trial, reference);
            self.st.improved |= trial < reference;
            Ok((AutoStep::Accepted, Some(ratio)))
        } else {
            Ok((AutoStep::Rejected, Some(ratio)))
        }
    }

    /// Counts towards [`HOPELESS_FITS`](super::HOPELESS_FITS) (or resets the count):
    /// in a descent after the first, on a deterministic objective, after a confirmed
    /// model step, a `trusted` model (a close, determined fit whose minimum lies inside
    /// the trust region) predicts a `decrease` to its minimum of less than half of
    /// `value` − f(record).
    fn judge_basin(&mut self, value: T, decrease: T, trusted: bool) {
        let hopeless = trusted
            && self.st.unconfirmed == 0
            && !self.st.noisy
            && !self.st.unseeded
            && self
                .st
                .record
                .is_some_and(|record| value > record && decrease < T::HALF * (value - record));
        self.st.hopeless = if hopeless {
            self.st.hopeless.saturating_add(1)
        } else {
            0
        };
    }
}
