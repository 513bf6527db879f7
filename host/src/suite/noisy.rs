//! Noisy problems: the sphere and Rosenbrock's function observed through the noise
//! models of the BBOB noisy testbed — N. Hansen, S. Finck, R. Ros, A. Auger,
//! "Real-Parameter Black-Box Optimization Benchmarking 2009: Noisy Functions
//! Definitions", INRIA research report RR-6869 — functions f101–f112.
//!
//! A Monte Carlo renderer whose seed the caller does not control is such a function:
//! every evaluation, even of the same θ twice, draws fresh noise. The methods are not
//! told: they see f̃(x) as an ordinary, deterministic-looking function (what a user
//! who passes a noisy closure gets). Runs are judged on the noiseless f of the points
//! they evaluated, as COCO judges its noisy suite: the trace's f − f* is that of the
//! evaluation with the lowest noiseless value so far.
//!
//! Noise models, with U, U′ uniform on (0, 1) and N, N′ standard normal, all
//! independent:
//!
//! * Gaussian: f_GN(f, β) = f·exp(βN);
//! * uniform: f_UN(f, α, β) = f·U^β·max(1, (10⁹/(f + 10⁻⁹⁹))^(αU′));
//! * Cauchy: f_CN(f, α, p) = f + α·max(0, 1000 + 𝟙{U < p}·N/(|N′| + 10⁻¹⁹⁹)),
//!
//! applied only where f ≥ 10⁻⁸, which then becomes f_XN(f) + 1.01·10⁻⁸ (so values
//! below 10⁻⁸ are seen exactly and the optimum stays the optimum).
//!
//! | id | f | noise | strength |
//! |---|---|---|---|
//! | f101, f107 | sphere (BBOB f1) | Gaussian | β = 0.01, 1 |
//! | f102, f108 | sphere | uniform | α = 0.01·(0.49 + 1/D), β = 0.01; α = 0.49 + 1/D, β = 1 |
//! | f103, f109 | sphere | Cauchy | α = 0.01, p = 0.05; α = 1, p = 0.2 |
//! | f104–f106, f110–f112 | Rosenbrock (BBOB f8) | as f101–f103, f107–f109 | |
//!
//! f101–f106 are the report's *moderate* noise, f107–f112 its *severe* noise. The
//! noiseless functions, instances, bounds, starts and σ₀ are those of [`super::bbob`].
//! The noise of an evaluation is drawn from a hash of the problem's name, the bits of
//! x and how many times the run evaluated x before ([`super::trace::Clamped`] counts),
//! so runs are reproducible whatever the thread count, and a point evaluated again
//! draws fresh noise, as a renderer without a seed does.

use super::bbob;
use super::problem::{Family, Observation, Problem};
use super::random;

/// The functions of the family, by BBOB number.
pub const IDS: [u32; 12] = [101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112];

/// Values below this are observed without noise.
const NOISE_FLOOR: f64 = 1e-8;

/// The noise models of the BBOB noisy testbed, with their parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Noise {
    /// f·exp(βN).
    Gaussian {
        /// β.
        beta: f64,
    },
    /// f·U^β·max(1, (10⁹/(f + 10⁻⁹⁹))^(αU′)).
    Uniform {
        /// α.
        alpha: f64,
        /// β.
        beta: f64,
    },
    /// f + α·max(0, 1000 + 𝟙{U < p}·N/(|N′| + 10⁻¹⁹⁹)).
    Cauchy {
        /// α.
        alpha: f64,
        /// p, the probability of an outlier.
        p: f64,
    },
}

impl Noise {
    /// The model of function `id` (101–112) in `n` dimensions.
    ///
    /// # Panics
    /// If `id` is not in [`IDS`] (the suite lists its problems itself).
    pub fn of(id: u32, n: usize) -> Noise {
        assert!(IDS.contains(&id), "f{id} is not in the noisy family");
        let severe = id >= 107;
        let spread = 0.49 + 1.0 / n as f64;
        match ((id - 101) % 3, severe) {
            (0, false) => Noise::Gaussian { beta: 0.01 },
            (0, true) => Noise::Gaussian { beta: 1.0 },
            (1, false) => Noise::Uniform {
                alpha: 0.01 * spread,
                beta: 0.01,
            },
            (1, true) => Noise::Uniform {
                alpha: spread,
                beta: 1.0,
            },
            (_, false) => Noise::Cauchy {
                alpha: 0.01,
                p: 0.05,
            },
            (_, true) => Noise::Cauchy { alpha: 1.0, p: 0.2 },
        }
    }

    /// f observed with this noise, the noise drawn from `seed`.
    pub fn apply(self, f: f64, seed: u64) -> f64 {
        if f.is_nan() || f < NOISE_FLOOR {
            return f;
        }
        let normal = random::gaussian(2, seed);
        let uniform = random::uniform(2, 0.0, 1.0, random::mix(seed));
        let noisy = match self {
            Noise::Gaussian { beta } => f * (beta * normal[0]).exp(),
            Noise::Uniform { alpha, beta } => {
                let boost = (1e9 / (f + 1e-99)).powf(alpha * uniform[1]).max(1.0);
                f * uniform[0].powf(beta) * boost
            }
            Noise::Cauchy { alpha, p } => {
                let outlier = if uniform[0] < p {
                    normal[0] / (normal[1].abs() + 1e-199)
                } else {
                    0.0
                };
                f + alpha * (1000.0 + outlier).max(0.0)
            }
        };
        noisy + 1.01 * NOISE_FLOOR
    }
}

/// The noisy problem for function `id` (one of [`IDS`]), dimension `n`, instance
/// `instance`: BBOB's sphere (f1) or Rosenbrock (f8) problem of that dimension and
/// instance, observed through [`Noise::of`]`(id, n)`.
pub fn problem(id: u32, n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    let base = if (id - 101) % 6 < 3 { 1 } else { 8 };
    let name = format!("noisy-f{id}-n{n:02}-i{instance}");
    let salt = random::seed_of(&name, &[]);
    let noise = Noise::of(id, n);
    let observe = move |x: &[f64], value: f64, repeat: u64| {
        let point = random::point_seed(x);
        noise.apply(value, random::seed_of("noise", &[salt, point, repeat]))
    };
    Problem {
        name,
        family: Family::Noisy,
        observation: Observation::Unseeded(Box::new(observe)),
        ..bbob::problem(base, n, instance, budget_per_dim)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_pure_and_spares_the_optimum() {
        for &id in &IDS {
            let noise = Noise::of(id, 5);
            assert_eq!(noise.apply(3.0, 7), noise.apply(3.0, 7), "f{id}");
            assert_eq!(noise.apply(0.0, 7), 0.0, "f{id}");
            assert_eq!(noise.apply(5e-9, 7), 5e-9, "f{id}");
            assert!(noise.apply(3.0, 7).is_finite(), "f{id}");
        }
    }

    #[test]
    fn gaussian_noise_has_the_stated_spread() {
        // ln(f̃/f) = βN: over 4 000 draws its standard deviation is β within 5 %.
        let noise = Noise::of(107, 5);
        let logs: Vec<f64> = (0..4000)
            .map(|s| (noise.apply(1.0, random::mix(s)) - 1.01e-8).ln())
            .collect();
        let mean = logs.iter().sum::<f64>() / logs.len() as f64;
        let var = logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / logs.len() as f64;
        assert!((var.sqrt() - 1.0).abs() < 0.05, "sd {}", var.sqrt());
        assert!(mean.abs() < 0.05, "mean {mean}");
    }

    #[test]
    fn problems_are_judged_on_the_noiseless_function() {
        let p = problem(107, 4, 1, 10);
        let base = bbob::problem(1, 4, 1, 10);
        let x = [0.5, -1.0, 2.0, 0.25];
        assert_eq!(p.value(&x), base.value(&x));
        assert_ne!(p.observe(&x, 0), p.value(&x));
        assert_ne!(p.observe(&x, 0), p.observe(&x, 1));
        assert_eq!(p.observe(&x, 1), p.observe(&x, 1));
        assert_eq!(p.x_opt, base.x_opt);
        assert_eq!(p.family, Family::Noisy);
    }
}
