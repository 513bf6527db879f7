//! The estimators as seen by an optimiser: one place that counts evaluations and keeps
//! the latest loss estimate. It also compares candidate points by their objective values
//! (the two-sided negative-curvature step, [`super::NegativeCurvature::TwoSided`], and
//! Newton-CG's [`super::NewtonCg::compare_samples`]).

use rand_core::Rng;

#[cfg(feature = "cg")]
use super::vector::{axpy, distance, norm};
#[cfg(feature = "cg")]
use super::{COMPARISON_MARGIN, Verdict};
use crate::error::Error;
#[cfg(feature = "hessian")]
use crate::estimate::HessianMethod;
#[cfg(feature = "cg")]
use crate::estimate::HvpMethod;
use crate::estimate::{Estimator, GradientMethod, Report};
#[cfg(feature = "cg")]
use crate::objective::Batch;
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
}

impl<T: Real, R: Rng + Clone, O: Objective<T> + ?Sized> Oracle<'_, '_, T, R, O> {
    /// Rewinds the estimator's random stream to the iteration's snapshot, if reusing.
    fn rewind(&mut self) {
        if let Some(s) = &self.snapshot {
            *self.estimator.rng_mut() = s.clone();
        }
    }

    /// Counts an estimate's evaluations and keeps its loss estimate: f(θ) when the
    /// estimate evaluated it, else the mean of its samples.
    fn record(&mut self, r: &Report<T>) {
        self.evaluations += r.evaluations;
        self.loss = r.centre_value.or(r.mean_value).or(self.loss);
    }

    #[cfg(any(feature = "hessian", feature = "cg"))]
    pub fn sigma(&self) -> T {
        self.estimator.sigma()
    }

    pub fn gradient(
        &mut self,
        method: GradientMethod,
        theta: &[T],
        out: &mut [T],
    ) -> Result<(), Error> {
        self.rewind();
        let r = self
            .estimator
            .gradient(method, self.objective, theta, self.ws, out)?;
        self.record(&r);
        Ok(())
    }

    #[cfg(feature = "cg")]
    pub fn hvp(
        &mut self,
        method: HvpMethod,
        theta: &[T],
        v: &[T],
        out: &mut [T],
    ) -> Result<(), Error> {
        self.rewind();
        let r = self
            .estimator
            .hvp(method, self.objective, theta, v, self.ws, out)?;
        self.record(&r);
        Ok(())
    }

    #[cfg(feature = "cg")]
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

    /// Ends an iteration by comparing, on the objective itself, the current θ, the model
    /// step θ + p and the lowest sample this iteration evaluated, and moves θ to the
    /// lowest. θ and θ + p are evaluated with that sample's noise seed (2 evaluations,
    /// counted here), so renderer noise cancels from the comparison as in common random
    /// numbers. Values within [`COMPARISON_MARGIN`] (relative) of each other tie; ties go
    /// to θ + p, then θ. Without a sample (nothing evaluated since the
    /// iteration began) θ takes the model step unevaluated.
    ///
    /// Returns the [`Verdict`] on the model step and the distance θ moved.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (the point stays in the workspace; θ is unchanged).
    #[cfg(feature = "cg")]
    pub fn settle(&mut self, theta: &mut [T], p: &[T]) -> Result<(Verdict, T), Error> {
        let n = self.ws.dim;
        let b = &mut self.ws.batch;
        let Some(sample_value) = b.best.value else {
            axpy(T::ONE, p, theta);
            return Ok((Verdict::Uncompared, norm(p)));
        };
        let (model, current) = b.points[..2 * n].split_at_mut(n);
        for ((m, c), (&x, &pi)) in model
            .iter_mut()
            .zip(current.iter_mut())
            .zip(theta.iter().zip(p))
        {
            *m = x + pi;
            *c = x;
        }
        b.seeds[..2].fill(b.best.seed);
        let batch = Batch::new(&b.points[..2 * n], &b.seeds[..2], n)?;
        self.objective.evaluate_batch(&batch, &mut b.values[..2]);
        self.evaluations += 2;
        if let Some(k) = b.values[..2].iter().position(|v| !v.is_finite()) {
            b.failed = Some(k);
            return Err(Error::NonFiniteObjective { sample: k });
        }
        let (at_model, at_current) = (b.values[0], b.values[1]);
        let margin = T::from_f64(COMPARISON_MARGIN);
        let below = |a: T, b: T| a < b - margin * a.abs().max(b.abs());
        if below(sample_value, at_model.min(at_current)) {
            let moved = distance(theta, b.best.point);
            theta.copy_from_slice(b.best.point);
            Ok((Verdict::Rejected, moved))
        } else if below(at_current, at_model) {
            Ok((Verdict::Rejected, T::ZERO))
        } else {
            axpy(T::ONE, p, theta);
            Ok((Verdict::Kept, norm(p)))
        }
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
        let batch = Batch::new(&b.points[..K * n], &b.seeds[..K], n)?;
        self.objective.evaluate_batch(&batch, &mut b.values[..K]);
        self.evaluations += K;
        let values = &b.values[..K];
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            b.failed = Some(k);
            return Err(Error::NonFiniteObjective { sample: k });
        }
        let mut best = 0;
        for k in 1..K {
            if values[k] < values[best] {
                best = k;
            }
        }
        Ok(best)
    }
}
