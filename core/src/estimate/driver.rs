//! The sampling engine shared by every estimator.
//!
//! An estimator is a [`Scheme`]: a number of *groups*, each one standardised offset t
//! drawn from the scheme's density, and a rule that turns the group's objective values
//! into contributions to its output. The driver places the points of each group,
//! θ_c − σt and θ_c + σt for each centre θ_c (one centre, or two for a common-random-
//! numbers central difference), fills the workspace's batch, evaluates it, checks every
//! value, and hands each group's antithetic combinations to the scheme.
//!
//! Offsets are drawn group by group in order from the caller's RNG, so the estimate is
//! the same whatever the batch capacity. All points of a group share one noise seed
//! (0 for a deterministic objective, which ignores it).

use rand_core::Rng;

use crate::error::Error;
use crate::objective::{Batch, NoiseSeed, Objective};
use crate::real::Real;
use crate::workspace::BatchBuffers;

/// The antithetic combinations of one group's values, signed over the centres
/// (+ for the first, − for the second).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair<T> {
    /// Σ_c ±(f(θ_c − σt) − f(θ_c + σt))/2: what gradient weights multiply.
    pub odd: T,
    /// Σ_c ±((f(θ_c − σt) + f(θ_c + σt))/2 − b): what Hessian weights multiply, b the
    /// control-variate baseline f(θ) (0 when none).
    pub even: T,
}

/// One estimator's sampling rule.
pub(crate) trait Scheme<T: Real> {
    /// Number of groups (each one offset, two evaluations per centre).
    fn groups(&self) -> usize;
    /// Draws the standardised offset of group `group` into `t` (length n). The driver
    /// calls it once per group, for groups 0, 1, … in order.
    fn draw<R: Rng + ?Sized>(&mut self, group: usize, rng: &mut R, t: &mut [T]);
    /// Adds group `group`'s contribution.
    fn accumulate(&mut self, group: usize, t: &[T], pair: Pair<T>);
}

/// Where and how to place a scheme's points.
pub(crate) struct Placement<'c, T> {
    /// One or two centres θ_c.
    pub centres: &'c [&'c [T]],
    /// σ: points are θ_c ∓ σt.
    pub sigma: T,
    /// Control-variate baseline b subtracted in [`Pair::even`] (0 for none).
    pub baseline: T,
    /// Index of the first evaluation, for error reports.
    pub first_sample: usize,
}

/// splitmix64's finaliser: a bijective mix so that nearby group indices give unrelated
/// noise seeds.
#[inline]
pub(crate) fn mix_seed(base: u64, index: u64) -> NoiseSeed {
    let mut z = base.wrapping_add(index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Runs `scheme` to completion and returns the number of evaluations used.
pub(crate) fn run<T, S, O, R>(
    scheme: &mut S,
    objective: &mut O,
    placement: &Placement<'_, T>,
    rng: &mut R,
    buffers: &mut BatchBuffers<'_, T>,
    dim: usize,
) -> Result<usize, Error>
where
    T: Real,
    S: Scheme<T>,
    O: Objective<T> + ?Sized,
    R: Rng + ?Sized,
{
    let rows_per_group = 2 * placement.centres.len();
    let rows = buffers.seeds.len();
    // Groups per batch. The workspace holds offsets for rows/2 groups, enough for one
    // centre; two centres fit half as many. Divisions by constants: a Cortex-M0 has no
    // divide instruction.
    let per_chunk = if placement.centres.len() == 1 {
        rows / 2
    } else {
        rows / 4
    };
    debug_assert!(per_chunk >= 1 && per_chunk * dim <= buffers.offsets.len());
    let base_seed = rng.next_u64();
    let deterministic = objective.deterministic();
    let total = scheme.groups();
    let mut done = 0;
    while done < total {
        let chunk = per_chunk.min(total - done);
        for k in 0..chunk {
            let t = &mut buffers.offsets[k * dim..(k + 1) * dim];
            scheme.draw(done + k, rng, t);
            // A deterministic objective ignores its seeds (`Objective::deterministic`):
            // it gets 0, sparing it three 64-bit multiplies a group, which a
            // microcontroller without a 64-bit multiplier does in a library routine.
            let seed = if deterministic {
                0
            } else {
                mix_seed(base_seed, (done + k) as u64)
            };
            for (c, centre) in placement.centres.iter().enumerate() {
                let row = k * rows_per_group + 2 * c;
                let (minus, plus) = buffers.points[row * dim..(row + 2) * dim].split_at_mut(dim);
                for (((m, p), &x), &tk) in minus
                    .iter_mut()
                    .zip(plus.iter_mut())
                    .zip(centre.iter())
                    .zip(t.iter())
                {
                    let step = placement.sigma * tk;
                    *m = x - step;
                    *p = x + step;
                }
                buffers.seeds[row] = seed;
                buffers.seeds[row + 1] = seed;
            }
        }
        let used = chunk * rows_per_group;
        let batch = Batch::new(&buffers.points[..used * dim], &buffers.seeds[..used], dim)?;
        objective.evaluate_batch(&batch, &mut buffers.values[..used]);
        if objective.cancelled() {
            return Err(Error::Cancelled);
        }
        if let Some(row) = buffers.values[..used].iter().position(|v| !v.is_finite()) {
            buffers.failed = Some(row);
            return Err(Error::NonFiniteObjective {
                sample: placement.first_sample + done * rows_per_group + row,
            });
        }
        #[cfg(feature = "newton-cg")]
        buffers.note_extremes(used, placement.first_sample + done * rows_per_group);
        buffers.value_sum += buffers.values[..used].iter().fold(T::ZERO, |s, &v| s + v);
        buffers.value_count += used;
        for k in 0..chunk {
            let values = &buffers.values[k * rows_per_group..(k + 1) * rows_per_group];
            let mut pair = Pair {
                odd: T::ZERO,
                even: T::ZERO,
            };
            for (c, v) in values.chunks_exact(2).enumerate() {
                let sign = if c == 0 { T::ONE } else { -T::ONE };
                pair.odd += sign * T::HALF * (v[0] - v[1]);
                pair.even +=
                    sign * T::HALF * ((v[0] - placement.baseline) + (v[1] - placement.baseline));
            }
            scheme.accumulate(done + k, &buffers.offsets[k * dim..(k + 1) * dim], pair);
        }
        done += chunk;
    }
    Ok(total * rows_per_group)
}

/// Evaluates the control-variate baseline f(θ) through the batch buffers (so a failure
/// leaves θ retrievable as the failed point).
#[cfg(any(feature = "hessian", all(feature = "hvp", feature = "gaussian")))]
pub(crate) fn evaluate_centre<T, O, R>(
    objective: &mut O,
    theta: &[T],
    rng: &mut R,
    buffers: &mut BatchBuffers<'_, T>,
    sample: usize,
) -> Result<T, Error>
where
    T: Real,
    O: Objective<T> + ?Sized,
    R: Rng + ?Sized,
{
    let seed = rng.next_u64();
    let value = objective.evaluate(theta, seed);
    if !value.is_finite() {
        buffers.points[..theta.len()].copy_from_slice(theta);
        buffers.failed = Some(0);
        return Err(Error::NonFiniteObjective { sample });
    }
    buffers.value_sum += value;
    buffers.value_count += 1;
    Ok(value)
}
