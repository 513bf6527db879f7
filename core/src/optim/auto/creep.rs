//! Creeping descents: f(θ) still falls, so the patience never runs out, but by amounts
//! that neither shrink nor matter, and σ does not converge.
//!
//! A kinked minimum in many dimensions (a renderer's anti-aliased edges, each crossing a
//! pixel boundary) can hold a descent so: its samples keep finding points lower by a
//! millionth of the descent's fall or less, each gain resets [`AutoOptions::patience`](super::AutoOptions::patience),
//! and σ wanders within a few decades above the tolerance for tens of thousands of
//! evaluations. Such a descent is counted as stagnated (restart from the best point, or
//! the next descent) once a window of [`CREEP_WINDOWS`]·patience iterations, not the
//! first of its chain, shows all of:
//!
//! * no model step confirmed its model (ρ̂ ≥ 0.1) in the window: a confirmed step is the
//!   model working, whatever the gain;
//! * σ stayed above [`CREEP_SHRINK`] of its lowest value since the window chain began: a
//!   descent whose σ converges reaches the tolerance on its own;
//! * f(θ) fell, by at most [`CREEP_GAIN`] times the descent's fall since its first
//!   finite value, and by more than half the window before's fall: gains that shrink
//!   geometrically are a convergence (an attractive sector's or a ridge's), not a creep.
//!
//! Where either of the first two fails, a new chain of windows begins.

use crate::real::Real;

/// Creep windows are this many times [`AutoOptions::patience`](super::AutoOptions::patience)
/// iterations long.
pub const CREEP_WINDOWS: usize = 4;

/// A creeping window's fall of f(θ) is at most this fraction of the descent's fall.
pub const CREEP_GAIN: f64 = 1e-6;

/// σ at or below this fraction of its lowest value in the chain of windows counts as
/// converging (two halvings), and starts the chain again.
pub const CREEP_SHRINK: f64 = 0.25;

/// What the current chain of creep windows has seen (see the module's header).
#[derive(Clone, Copy, Debug)]
pub(super) struct Creep<T> {
    /// The descent's first finite f(θ).
    first: Option<T>,
    /// The lowest σ since the chain began.
    sigma: T,
    /// The iteration at which the current window began.
    iteration: usize,
    /// f(θ) when the current window began; `None` before the chain begins.
    value: Option<T>,
    /// The last window's fall of f(θ); `None` in the chain's first window.
    gain: Option<T>,
}

impl<T: Real> Creep<T> {
    /// A descent's start: nothing seen.
    pub const fn new() -> Self {
        Creep {
            first: None,
            sigma: T::ZERO,
            iteration: 0,
            value: None,
            gain: None,
        }
    }

    /// Starts the chain again at the next observation (a restart: σ is set anew).
    pub fn restart(&mut self) {
        self.value = None;
    }

    /// Observes the end of `iteration`, with f(θ) `value`, σ `sigma`, whether the last
    /// model step confirmed its model (`confirmed`) and windows of `window` iterations;
    /// returns whether the descent creeps (and then starts the chain again).
    pub fn observe(
        &mut self,
        value: T,
        sigma: T,
        iteration: usize,
        confirmed: bool,
        window: usize,
    ) -> bool {
        let first = *self.first.get_or_insert(value);
        let Some(start) = self.value else {
            self.begin(value, sigma, iteration);
            return false;
        };
        if confirmed || sigma <= T::from_f64(CREEP_SHRINK) * self.sigma {
            self.begin(value, self.sigma.min(sigma), iteration);
            return false;
        }
        if iteration.saturating_sub(self.iteration) < window {
            return false;
        }
        let gain = start - value;
        let steady = self.gain.is_some_and(|last| gain > T::HALF * last);
        if gain > T::ZERO && steady && gain <= T::from_f64(CREEP_GAIN) * (first - value) {
            self.value = None;
            return true;
        }
        self.iteration = iteration;
        self.value = Some(value);
        self.gain = Some(gain);
        false
    }

    /// Begins a chain of windows at this observation.
    fn begin(&mut self, value: T, sigma: T, iteration: usize) {
        self.sigma = sigma;
        self.iteration = iteration;
        self.value = Some(value);
        self.gain = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Observes 1 000 iterations in windows of 100: f(θ) falls by 0.9 at iteration 0
    /// and then by `gain(k)` at iteration k, σ is `sigma(k)` and the model confirmed
    /// where `confirmed(k)`; returns the first iteration at which the descent creeps.
    fn first_creep(
        gain: impl Fn(usize) -> f64,
        sigma: impl Fn(usize) -> f64,
        confirmed: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        let mut creep = Creep::<f64>::new();
        let mut value = 1.0;
        for k in 0..1_000 {
            if creep.observe(value, sigma(k), k, confirmed(k), 100) {
                return Some(k);
            }
            value -= if k == 0 { 0.9 } else { gain(k) };
        }
        None
    }

    /// Falls of 1e-9 per iteration after the first: the first window holds the large
    /// fall, the second's tiny one is no steady gain yet, the third's is, at its end.
    #[test]
    fn steady_tiny_gains_creep() {
        assert_eq!(first_creep(|_| 1e-9, |_| 1e-3, |_| false), Some(300));
    }

    /// Gains that halve every 30 iterations (a linear convergence), or that matter
    /// (1e-4 of the descent's fall per iteration), are no creep.
    #[test]
    fn converging_or_large_gains_do_not_creep() {
        let halving = |k: usize| 1e-6 * 0.5f64.powf(k as f64 / 30.0);
        assert_eq!(first_creep(halving, |_| 1e-3, |_| false), None);
        assert_eq!(first_creep(|_| 1e-4, |_| 1e-3, |_| false), None);
    }

    /// The steady tiny gains of `steady_tiny_gains_creep` with a confirmed model step
    /// every 150 iterations, or σ falling to a quarter as often, are no creep: each
    /// starts the chain of windows again.
    #[test]
    fn confirmation_or_a_converging_sigma_restart_the_chain() {
        let every = |k: usize| k % 150 == 149;
        assert_eq!(first_creep(|_| 1e-9, |_| 1e-3, every), None);
        let quartering = |k: usize| 0.25f64.powi((k / 150) as i32);
        assert_eq!(first_creep(|_| 1e-9, quartering, |_| false), None);
    }
}
