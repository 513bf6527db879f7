//! The estimators as seen by an optimiser: one place that counts evaluations and keeps
//! the latest loss estimate. It also compares candidate points by their objective values
//! (the two-sided negative-curvature step, [`super::NegativeCurvature::TwoSided`], and
//! Newton-CG's [`super::NewtonCg::compare_samples`]).

use rand_core::Rng;

#[cfg(feature = "newton-cg")]
use super::vector::{axpy, distance, norm};
#[cfg(feature = "newton-cg")]
use super::{COMPARISON_MARGIN, PLATEAU_MARGIN, Verdict};
use crate::error::Error;
#[cfg(feature = "hessian")]
use crate::estimate::HessianMethod;
#[cfg(feature = "cg")]
use crate::estimate::HvpMethod;
#[cfg(feature = "newton-cg")]
use crate::estimate::Lowest;
use crate::estimate::{Estimator, GradientMethod, Report};
#[cfg(feature = "cg")]
use crate::objective::Batch;
#[cfg(feature = "newton-cg")]
use crate::objective::NoiseSeed;
use crate::objective::Objective;
use crate::real::Real;
#[cfg(feature = "cg")]
use crate::workspace::MIN_ROWS;
use crate::workspace::Workspace;

pub(crate) struct Oracle<'a, 'w, T, R, O: ?Sized> {
    pub estimator: &'a mut Estimator<T, R>,
    pub objective: &'a mut O,
    pub ws: &'a mut Workspace<'w, T>,
    /// Evaluations used by this iteration so far.
    pub evaluations: usize,
    /// The latest mean objective value seen (an estimate of the loss near θ).
    pub loss: Option<T>,
    /// With sample reuse: the RNG state at the start of the iteration, restored before
    /// every estimate so that all of them draw the same offsets and noise seeds.
    pub snapshot: Option<R>,
    /// f(θ) at the current θ if known (a deterministic objective evaluated there).
    pub value_at_theta: Option<T>,
    /// f(θ) at the current θ evaluated with this noise seed this iteration
    /// ([`Oracle::pair_curvature`], [`Oracle::line_curvature`]).
    #[cfg(feature = "newton-cg")]
    pub centre_sample: Option<(T, NoiseSeed)>,
    /// [`Oracle::settle`] moved θ this iteration and set `value_at_theta` for it.
    pub settled: bool,
    /// The lowest sample of this iteration's estimates (the earliest among equals), from
    /// their reports.
    #[cfg(feature = "newton-cg")]
    pub lowest: Option<Lowest<T>>,
    /// Its point, kept for [`Oracle::settle`]: n floats of the optimiser's memory, or
    /// empty when the method never settles (then no point is kept).
    #[cfg(feature = "newton-cg")]
    pub lowest_point: &'a mut [T],
    /// The highest value among this iteration's samples, from the estimates' reports.
    #[cfg(feature = "newton-cg")]
    pub highest: Option<T>,
}

impl<T: Real, R: Rng + Clone, O: Objective<T> + ?Sized> Oracle<'_, '_, T, R, O> {
    /// Rewinds the estimator's random stream to the iteration's snapshot, if reusing.
    fn rewind(&mut self) {
        if let Some(s) = &self.snapshot {
            *self.estimator.rng_mut() = s.clone();
        }
    }

    /// Counts an estimate's evaluations and keeps its loss estimate: f(θ) when the
    /// estimate evaluated it, else the mean of its samples. With `newton-cg`, also keeps the
    /// iteration's lowest sample (its point copied while the workspace still holds it)
    /// and highest value.
    fn record(&mut self, r: &Report<T>) {
        self.evaluations += r.evaluations;
        self.loss = r.centre_value.or(r.mean_value).or(self.loss);
        #[cfg(feature = "newton-cg")]
        {
            if let Some(low) = r.lowest {
                if self.lowest.is_none_or(|kept| low.value < kept.value) {
                    self.lowest = Some(low);
                    if !self.lowest_point.is_empty() {
                        self.lowest_point.copy_from_slice(self.ws.lowest_point());
                    }
                }
            }
            if let Some(high) = r.highest {
                if self.highest.is_none_or(|h| high > h) {
                    self.highest = Some(high);
                }
            }
        }
    }

    #[cfg(any(feature = "hessian", feature = "cg"))]
    pub fn sigma(&self) -> T {
        self.estimator.sigma()
    }

    /// ĝ at θ into `out`, and the estimate's report.
    pub fn gradient(
        &mut self,
        method: GradientMethod,
        theta: &[T],
        out: &mut [T],
    ) -> Result<Report<T>, Error> {
        self.rewind();
        let r = self
            .estimator
            .gradient(method, self.objective, theta, self.ws, out)?;
        self.record(&r);
        Ok(r)
    }

    /// Ĥv at θ. `gradient` is this iteration's gradient estimate at θ and the estimator
    /// that made it: with sample reuse it came from the draws the rewound stream repeats,
    /// so a forward difference of that same estimator uses it instead of re-estimating
    /// g(θ). Otherwise it is ignored.
    #[cfg(feature = "cg")]
    pub fn hvp(
        &mut self,
        method: HvpMethod,
        theta: &[T],
        gradient: (GradientMethod, &[T]),
        v: &[T],
        out: &mut [T],
    ) -> Result<(), Error> {
        self.rewind();
        let (made_by, estimate) = gradient;
        let base =
            (self.snapshot.is_some() && method.differenced() == Some(made_by)).then_some(estimate);
        let r = self.estimator.hvp_given_gradient(
            method,
            self.objective,
            theta,
            base,
            v,
            self.ws,
            out,
        )?;
        self.record(&r);
        Ok(())
    }

    #[cfg(all(feature = "cg", feature = "gaussian"))]
    pub fn gradient_and_hvp(
        &mut self,
        theta: &[T],
        v: &[T],
        grad: &mut [T],
        hv: &mut [T],
    ) -> Result<(), Error> {
        self.rewind();
        let r = self
            .estimator
            .gradient_and_hvp(self.objective, theta, v, self.ws, grad, hv)?;
        self.record(&r);
        Ok(())
    }

    #[cfg(feature = "hessian")]
    pub fn hessian(
        &mut self,
        method: HessianMethod,
        theta: &[T],
        out: &mut [T],
    ) -> Result<(), Error> {
        self.rewind();
        let r = self
            .estimator
            .hessian(method, self.objective, theta, self.ws, out)?;
        self.record(&r);
        Ok(())
    }

    /// The curvature along the offset of the gradient estimate `g` just made by
    /// `gradient` (its report `estimate`, no estimate since), when it came from one
    /// antithetic pair θ ± σt ([`Report::pair`]) and lies along t, in two or more
    /// dimensions ([`super::NewtonCg::pair_curvature`]): the second difference
    /// c = (f(θ + σt) + f(θ − σt) − 2f(θ))/(σ‖t‖)², in the estimator's scale. An
    /// estimator's one-pair estimate is ĝ = m·D·t̂ with D = (f(θ + σt) − f(θ − σt))/(2σ‖t‖)
    /// the pair's directional derivative and m > 0 its weight (1 for none; the aggregate
    /// weight n·Z·‖t‖²/‖t‖₁), as its difference HVP is m·(t̂ᵀ∇²f̄t̂)·t̂; the result is m·c,
    /// so that the model step ‖ĝ‖/(m·c) = |D|/c is the minimum of the parabola through
    /// the three values. Where the pair's values are equal (ĝ = 0) it is c.
    ///
    /// f(θ) is the remembered value of a deterministic objective, or evaluated here with
    /// the pair's noise seed (1 evaluation, kept for [`Oracle::settle`]). `None` when
    /// the estimate was not such a pair.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] for a non-finite f(θ) (θ stays in the workspace).
    #[cfg(feature = "newton-cg")]
    pub fn pair_curvature(
        &mut self,
        gradient: GradientMethod,
        estimate: &Report<T>,
        theta: &[T],
        g: &[T],
    ) -> Result<Option<T>, Error> {
        let n = self.ws.dim;
        let Some(pair) = estimate.pair.filter(|_| n >= 2 && gradient.along_offset()) else {
            return Ok(None);
        };
        let seed = pair.seed;
        let known = self.known_value(Some(seed));
        let b = &mut self.ws.batch;
        let centre = match known {
            Some(v) => v,
            None => {
                let v = self.objective.evaluate(theta, seed);
                self.evaluations += 1;
                if !v.is_finite() {
                    b.points[..n].copy_from_slice(theta);
                    b.failed = Some(0);
                    return Err(Error::NonFiniteObjective { sample: 0 });
                }
                self.remember_centre(v, seed);
                v
            }
        };
        let t = self.ws.pair_offset();
        let sigma = self.estimator.sigma();
        let tt = t.iter().fold(T::ZERO, |s, &x| s + x.sq());
        let (minus, plus) = (pair.minus, pair.plus);
        let c = (plus + minus - T::TWO * centre) / (sigma.sq() * tt);
        let rise = plus - minus;
        if rise == T::ZERO {
            return Ok(c.is_finite().then_some(c));
        }
        let gt = g.iter().zip(t).fold(T::ZERO, |s, (&gi, &ti)| s + gi * ti);
        let m = weight(sigma * gt, rise);
        let scaled = m * c;
        Ok((m > T::ZERO && scaled.is_finite()).then_some(scaled))
    }

    /// The curvature along the gradient estimate `g` (≠ 0) from f on the line through θ
    /// along û = ĝ/‖ĝ‖ ([`super::NewtonCg::line_curvature`]): the second difference
    /// c = (f(θ + hû) + f(θ − hû) − 2f(θ))/h² at h = σ√n, in the estimator's scale m·c
    /// with m = ‖ĝ‖/D, D = (f(θ + hû) − f(θ − hû))/(2h) the line's slope, so that the
    /// model step ‖ĝ‖/(m·c) = D/c is the minimum of the parabola through the three
    /// values (exact on quadratics). Where the line does not fall along −ĝ (D ≤ 0) the
    /// result is 0: no model minimum, and Newton-CG takes its fallback step.
    ///
    /// The three points share one noise seed, the iteration's lowest sample's (a fresh
    /// one from the stream before any), so renderer noise cancels from the differences;
    /// f(θ) is the remembered value of a deterministic objective, else evaluated (kept
    /// for [`Oracle::settle`]). Costs 2 or 3 evaluations, counted here.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (the point stays in the workspace).
    #[cfg(feature = "newton-cg")]
    pub fn line_curvature(&mut self, theta: &[T], g: &[T]) -> Result<T, Error> {
        let n = self.ws.dim;
        let seed = match self.lowest {
            Some(low) => low.seed,
            None => self.estimator.rng_mut().next_u64(),
        };
        let known = self.known_value(Some(seed));
        let count = if known.is_some() { 2 } else { 3 };
        let h = self.estimator.sigma() * T::from_usize(n).sqrt();
        let gradient_norm = norm(g);
        let scale = h / gradient_norm;
        let b = &mut self.ws.batch;
        for (k, side) in [T::ONE, -T::ONE, T::ZERO]
            .into_iter()
            .take(count)
            .enumerate()
        {
            for ((x, &t), &gi) in b.points[k * n..(k + 1) * n].iter_mut().zip(theta).zip(g) {
                *x = t + side * scale * gi;
            }
        }
        b.seeds[..count].fill(seed);
        self.evaluate_rows(count)?;
        let values = &self.ws.batch.values;
        let (plus, minus) = (values[0], values[1]);
        let centre = match known {
            Some(v) => v,
            None => {
                let v = values[2];
                self.remember_centre(v, seed);
                v
            }
        };
        let rise = plus - minus;
        if rise <= T::ZERO {
            return Ok(T::ZERO);
        }
        let c = (plus + minus - T::TWO * centre) / h.sq();
        // ĝ·(hû) = h‖ĝ‖.
        let scaled = weight(h * gradient_norm, rise) * c;
        Ok(if scaled.is_finite() { scaled } else { T::ZERO })
    }

    /// Keeps f(θ) = `value`, evaluated this iteration with noise seed `seed`: for this
    /// iteration's comparison, and for later iterations while θ stays if the objective
    /// is deterministic.
    #[cfg(feature = "newton-cg")]
    fn remember_centre(&mut self, value: T, seed: NoiseSeed) {
        if self.objective.deterministic() {
            self.value_at_theta = Some(value);
        }
        self.centre_sample = Some((value, seed));
    }

    /// f(θ) where it is known without evaluating it: a deterministic objective's
    /// remembered value, else the value [`Oracle::pair_curvature`] or
    /// [`Oracle::line_curvature`] evaluated this
    /// iteration with noise seed `seed` (with any seed for `None`).
    #[cfg(feature = "newton-cg")]
    fn known_value(&self, seed: Option<NoiseSeed>) -> Option<T> {
        self.value_at_theta
            .filter(|_| self.objective.deterministic())
            .or_else(|| {
                self.centre_sample
                    .filter(|&(_, s)| seed.is_none_or(|want| want == s))
                    .map(|(v, _)| v)
            })
    }

    /// True when this iteration has evaluated samples and they, with f(θ) where it is
    /// known (remembered, or evaluated this iteration), all lie within
    /// [`PLATEAU_MARGIN`] (relative) of the lowest: nothing near θ tells one point from
    /// another — a plateau at this σ.
    #[cfg(feature = "newton-cg")]
    pub fn flat(&self) -> bool {
        let centre = self.known_value(None);
        match (self.lowest, self.highest) {
            (Some(Lowest { value: low, .. }), Some(high)) => {
                let (low, high) = centre.map_or((low, high), |c| (low.min(c), high.max(c)));
                !below(low, high, PLATEAU_MARGIN)
            }
            _ => false,
        }
    }

    /// Ends an iteration by comparing, on the objective itself, the current θ, the model
    /// step θ + p and the lowest sample this iteration evaluated, and moves θ to the
    /// lowest. θ and θ + p are evaluated with that sample's noise seed (2 evaluations,
    /// counted here), so renderer noise cancels from the comparison as in common random
    /// numbers; a [deterministic](Objective::deterministic) objective's f(θ) is not
    /// evaluated again once known (1 evaluation). Values within [`COMPARISON_MARGIN`]
    /// (relative) of each other tie; ties go to θ + p, then θ. Without a sample (nothing
    /// evaluated since the iteration began, or no memory for its point) θ takes the
    /// model step unevaluated.
    ///
    /// Returns the [`Verdict`] on the model step and the distance θ moved.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (the point stays in the workspace; θ is unchanged).
    #[cfg(feature = "newton-cg")]
    pub fn settle(&mut self, theta: &mut [T], p: &[T]) -> Result<(Verdict, T), Error> {
        let n = self.ws.dim;
        let deterministic = self.objective.deterministic();
        let Some(low) = self.lowest.filter(|_| self.lowest_point.len() == n) else {
            axpy(T::ONE, p, theta);
            return Ok((Verdict::Uncompared, norm(p)));
        };
        let sample_value = low.value;
        let known = self.known_value(Some(low.seed));
        let b = &mut self.ws.batch;
        let count = if known.is_some() { 1 } else { 2 };
        let (model, current) = b.points[..2 * n].split_at_mut(n);
        for ((m, c), (&x, &pi)) in model
            .iter_mut()
            .zip(current.iter_mut())
            .zip(theta.iter().zip(p))
        {
            *m = x + pi;
            *c = x;
        }
        b.seeds[..2].fill(low.seed);
        self.evaluate_rows(count)?;
        let b = &self.ws.batch;
        let at_model = b.values[0];
        let at_current = known.unwrap_or(b.values[1]);
        let (verdict, moved, value) =
            if below(sample_value, at_model.min(at_current), COMPARISON_MARGIN) {
                let moved = distance(theta, self.lowest_point);
                theta.copy_from_slice(self.lowest_point);
                (Verdict::Rejected, moved, sample_value)
            } else if below(at_current, at_model, COMPARISON_MARGIN) {
                (Verdict::Rejected, T::ZERO, at_current)
            } else {
                axpy(T::ONE, p, theta);
                (Verdict::Kept, norm(p), at_model)
            };
        self.value_at_theta = deterministic.then_some(value);
        self.settled = true;
        Ok((verdict, moved))
    }

    /// Evaluates the workspace batch's first `count` points at their noise seeds into
    /// its values, counting the evaluations.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (the point stays in the workspace).
    #[cfg(feature = "cg")]
    fn evaluate_rows(&mut self, count: usize) -> Result<(), Error> {
        let n = self.ws.dim;
        let b = &mut self.ws.batch;
        let batch = Batch::new(&b.points[..count * n], &b.seeds[..count], n)?;
        self.objective
            .evaluate_batch(&batch, &mut b.values[..count]);
        self.evaluations += count;
        if self.objective.cancelled() {
            return Err(Error::Cancelled);
        }
        if let Some(k) = b.values[..count].iter().position(|v| !v.is_finite()) {
            b.failed = Some(k);
            return Err(Error::NonFiniteObjective { sample: k });
        }
        Ok(())
    }

    /// The index of the lowest of `K` candidate points by objective value, all evaluated
    /// with one fresh noise seed (common random numbers: the renderer noise the
    /// candidates share cancels from their differences, and no offsets are drawn, so
    /// what is compared is f itself, not f̄). `place(k, x)` writes candidate k into x
    /// (length n). Ties go to the earlier candidate. Costs K evaluations, counted here.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (the point stays in the workspace).
    #[cfg(feature = "cg")]
    pub fn lowest<const K: usize>(
        &mut self,
        mut place: impl FnMut(usize, &mut [T]),
    ) -> Result<usize, Error> {
        const { assert!(K >= 1 && K <= MIN_ROWS) };
        let n = self.ws.dim;
        let seed = self.estimator.rng_mut().next_u64();
        let b = &mut self.ws.batch;
        for k in 0..K {
            place(k, &mut b.points[k * n..(k + 1) * n]);
            b.seeds[k] = seed;
        }
        self.evaluate_rows(K)?;
        let values = &self.ws.batch.values[..K];
        let mut best = 0;
        for k in 1..K {
            if values[k] < values[best] {
                best = k;
            }
        }
        Ok(best)
    }
}

/// The estimator's scale m along an offset s from θ: m = (ĝ·s)/(‖s‖·D) with
/// D = (f(θ + s) − f(θ − s))/(2‖s‖) the slope f shows along s, i.e.
/// m = 2(ĝ·s)/(f(θ + s) − f(θ − s)) for `gs` = ĝ·s and `rise` = f(θ + s) − f(θ − s).
#[cfg(feature = "newton-cg")]
fn weight<T: Real>(gs: T, rise: T) -> T {
    T::TWO * gs / rise
}

/// a < b by more than `margin` × the larger magnitude (else they tie).
#[cfg(feature = "newton-cg")]
fn below<T: Real>(a: T, b: T, margin: f64) -> bool {
    a < b - T::from_f64(margin) * a.abs().max(b.abs())
}
