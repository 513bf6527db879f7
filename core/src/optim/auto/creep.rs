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
//!
//! Settled values: a descent along an asymptote — f bounded below with its infimum at
//! infinity in some direction (1 − tanh x, e⁻ˣ beside a quadratic in the other
//! coordinates) — confirms its model at every step and gains at every step, by amounts
//! that shrink too slowly for the chain above, while the metric stretches along the
//! flat direction so that no coordinate's spread converges. Its values have settled
//! once a window of [`CREEP_WINDOWS`]·patience iterations (counted from the descent's
//! start or its last restart, whatever its model or σ did) lowers f(θ) by at most
//! ε·(f₀ − f(θ)), ε the precision of f's values (T's machine epsilon, or f32's where
//! f computes in single precision, `Auto::grain`) and f₀ the descent's first finite
//! f(θ): a fall below what f's arithmetic resolves of the values the descent began from
//! ([`Creep::negligible`]). The descent then counts as converged.

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
    /// The iteration and f(θ) at which the current settling window began (see the
    /// module's header); `None` until the first observation after a restart.
    settling: Option<(usize, T)>,
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
            settling: None,
        }
    }

    /// Starts the chain and the settling window again at the next observation (a
    /// restart: σ is set anew).
    pub fn restart(&mut self) {
        self.value = None;
        self.settling = None;
    }

    /// Whether a fall of f(θ) by `gain` is negligible for a descent now at `value`: at
    /// most `grain`·(f₀ − `value`), f₀ its first finite f(θ) and `grain` the relative
    /// precision of f's values (see the module's header); false before anything has
    /// been observed.
    pub fn negligible(&self, gain: T, value: T, grain: T) -> bool {
        self.first
            .is_some_and(|first| gain <= grain * (first - value))
    }

    /// Observes the end of `iteration`, with f(θ) `value`, for the settling test (the
    /// module's header), in windows of `window` iterations; returns whether the window
    /// that ends here lowered f(θ) negligibly at f's precision `grain`
    /// ([`Creep::negligible`]), and then begins the next one. Called after
    /// [`Creep::observe`], which records the descent's first value.
    pub fn settled(&mut self, value: T, iteration: usize, window: usize, grain: T) -> bool {
        let Some((begun, start)) = self.settling else {
            self.settling = Some((iteration, value));
            return false;
        };
        if iteration.saturating_sub(begun) < window {
            return false;
        }
        self.settling = Some((iteration, value));
        self.negligible(start - value, value, grain)
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

    /// f(θ) falls from 1 to 10⁻¹⁰ at the first iteration and then by 10⁻²⁰ per
    /// iteration, with a confirmed model step at every iteration and σ falling to a
    /// quarter every 150 (an asymptote's descent, which the chain of creep windows never
    /// holds): the first window holds the large fall, the second's (10⁻¹⁸) is below ε
    /// (2.2·10⁻¹⁶) of the descent's fall, and the values settle at its end. Falls of
    /// 10⁻¹⁷ per iteration (a window's 10⁻¹⁵, above that) never do.
    #[test]
    fn negligible_falls_settle_whatever_the_model_and_sigma() {
        let settles = |fall: f64| {
            let mut creep = Creep::<f64>::new();
            for k in 0..1_000 {
                let value = if k == 0 { 1.0 } else { 1e-10 - fall * k as f64 };
                let sigma = 0.25f64.powi((k / 150) as i32);
                creep.observe(value, sigma, k, true, 100);
                if creep.settled(value, k, 100, f64::EPSILON) {
                    return Some(k);
                }
            }
            None
        };
        assert_eq!(settles(1e-20), Some(200));
        assert_eq!(settles(1e-17), None);
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
