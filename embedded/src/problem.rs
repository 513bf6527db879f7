//! The built-in problems and their settings.
//!
//! | problem | n | f | start | optimum of f̄_σ | budget |
//! |---|---|---|---|---|---|
//! | QUAD | 2 | 5x₀² + 5x₁² + 7.5x₀x₁ | (2.5, 1.5) | (0, 0) | 3000 evaluations |
//! | PLATEAU | 1 | 0 on (2.5, 3.5), 1 elsewhere | 0 | 3 | 2000 evaluations |
//!
//! PLATEAU has a zero gradient wherever it is defined: only smoothing reveals the well.
//! Its smoothed loss f̄_σ(x) = 1 − Φ((3.5 − x)/σ) + Φ((2.5 − x)/σ) is symmetric about 3
//! and decreasing towards it for every σ, so the minimiser stays put while σ anneals —
//! a well-defined target for both a first- and a second-order method, as long as σ stays
//! comparable to the well's width.

use rand_xoshiro::Xoshiro128PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// Hyper-parameters of one problem: the fields of hodr-core's `optim::preset::Hyper`
/// (which only exists with every hodr-core feature, so the minimal firmware cannot use
/// it) and the evaluation budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Antithetic pairs per estimate.
    pub pairs: usize,
    /// σ at the start of the run.
    pub sigma_start: f32,
    /// σ at the end of the budget (linear annealing in the evaluations used).
    pub sigma_end: f32,
    /// Δ, the step cap of NCG and Newton, in units of σ.
    pub trust_radius: f32,
    /// NCG line-search steps.
    pub line_search_iterations: usize,
    /// NCG line-search tolerance on α²·dᵀd.
    pub line_search_tolerance: f32,
    /// NCG restart period.
    pub recompute: usize,
    /// Adam's learning rate η.
    pub learning_rate: f32,
    /// Objective evaluations per run.
    pub evaluations: usize,
}

#[cfg(feature = "hessian")]
impl Settings {
    /// The same values as hodr-core's preset hyper-parameters, its defaults for the rest
    /// (the paper's draws: independent central-difference gradients).
    pub fn hyper(&self) -> hodr_core::optim::preset::Hyper<f32> {
        hodr_core::optim::preset::Hyper {
            pairs: self.pairs,
            sigma_start: self.sigma_start,
            sigma_end: self.sigma_end,
            trust_radius: self.trust_radius,
            line_search_iterations: self.line_search_iterations,
            line_search_tolerance: self.line_search_tolerance,
            recompute: self.recompute,
            learning_rate: self.learning_rate,
            ..hodr_core::optim::preset::Hyper::default()
        }
    }
}

/// A deterministic black-box objective to minimise, with where to start.
#[derive(Clone, Copy, Debug)]
pub struct Problem {
    /// Name in the report (no spaces).
    pub name: &'static str,
    /// f(θ); `θ.len()` is the problem's dimension.
    pub objective: fn(&[f32]) -> f32,
    /// θ₀; its length is the dimension n (at most [`crate::MAX_DIM`]).
    pub start: &'static [f32],
    /// The minimiser of the smoothed objective (for tests and readers).
    pub optimum: &'static [f32],
    /// Hyper-parameters and budget.
    pub settings: Settings,
    /// Seed of the estimator's random stream: the 128-bit seed of xoshiro128++
    /// (`Xoshiro128PlusPlus::from_seed`). Each problem's is the one `seed_from_u64`
    /// expands its small seed to (a test checks), written out so that the firmware does
    /// not link the expansion, SplitMix64's 64-bit multiplications.
    pub seed: Seed,
}

/// A 128-bit seed of xoshiro128++ as its four state words. Kept as words rather than
/// the 16 bytes `from_seed` takes: the optimiser then sees the bytes built from words and
/// reads the words back, where a stored byte array (alignment 1) is read byte by byte,
/// sixteen loads and the shifts that join them on RISC-V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seed(pub [u32; 4]);

impl Seed {
    /// The random stream whose xoshiro128++ state words are these (little-endian bytes,
    /// as `from_seed` reads them).
    pub fn rng(self) -> Xoshiro128PlusPlus {
        let mut bytes = [0; 16];
        for (chunk, word) in bytes.chunks_exact_mut(4).zip(self.0) {
            chunk.copy_from_slice(&word.to_le_bytes());
        }
        Xoshiro128PlusPlus::from_seed(bytes)
    }
}

/// f = 5x₀² + 5x₁² + 7.5x₀x₁ (= ½xᵀAx, A = [[10, 7.5], [7.5, 10]], condition number 7),
/// with the paper's QUAD settings (docs/design.md §3): 4 pairs, σ 1 → 0.05, Δ 50, 5 line-search
/// steps, restart every 5, η 0.5.
pub const QUAD: Problem = Problem {
    name: "QUAD",
    objective: quad,
    start: &[2.5, 1.5],
    optimum: &[0.0, 0.0],
    settings: Settings {
        pairs: 4,
        sigma_start: 1.0,
        sigma_end: 0.05,
        trust_radius: 50.0,
        line_search_iterations: 5,
        line_search_tolerance: 1e-3,
        recompute: 5,
        learning_rate: 0.5,
        evaluations: 3000,
    },
    seed: Seed([0x5932_0dd7, 0x63cb_e1e4, 0xf43c_661c, 0x044c_3cd7]),
};

/// f(x) = 0 for 2.5 < x < 3.5 and 1 elsewhere, from x₀ = 0. σ anneals from 2 (the well's
/// centre 1.5σ away, so the start sees it) to 0.5, the well's half-width: much smaller σ
/// flattens f̄ across the whole well, and any point in it would do. 8 pairs, Δ 2, 3
/// line-search steps, restart every 5, η 0.05 (Adam crosses the 3 units in 60 of its
/// 125 steps).
pub const PLATEAU: Problem = Problem {
    name: "PLATEAU",
    objective: plateau,
    start: &[0.0],
    optimum: &[3.0],
    settings: Settings {
        pairs: 8,
        sigma_start: 2.0,
        sigma_end: 0.5,
        trust_radius: 2.0,
        line_search_iterations: 3,
        line_search_tolerance: 1e-3,
        recompute: 5,
        learning_rate: 0.05,
        evaluations: 2000,
    },
    seed: Seed([0x2380_309d, 0x50f5_647d, 0x7a6b_13a1, 0x432a_5cd2]),
};

/// Every problem, in report order.
pub const PROBLEMS: [Problem; 2] = [QUAD, PLATEAU];

fn quad(x: &[f32]) -> f32 {
    5.0 * x[0] * x[0] + 5.0 * x[1] * x[1] + 7.5 * x[0] * x[1]
}

fn plateau(x: &[f32]) -> f32 {
    if x[0] > 2.5 && x[0] < 3.5 { 0.0 } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objectives_match_their_definitions() {
        assert_eq!((QUAD.objective)(&[1.0, -1.0]), 2.5);
        assert_eq!((QUAD.objective)(QUAD.optimum), 0.0);
        assert_eq!((PLATEAU.objective)(&[3.4]), 0.0);
        assert_eq!((PLATEAU.objective)(&[3.5]), 1.0);
        assert_eq!((PLATEAU.objective)(PLATEAU.start), 1.0);
    }

    /// QUAD's stream is `seed_from_u64(7)`'s, PLATEAU's `seed_from_u64(11)`'s.
    #[test]
    fn seeds_are_the_expansions_of_small_seeds() {
        for (p, small) in [(QUAD, 7), (PLATEAU, 11)] {
            assert_eq!(
                p.seed.rng(),
                Xoshiro128PlusPlus::seed_from_u64(small),
                "{}",
                p.name
            );
        }
    }

    #[test]
    fn dimensions_fit_the_storage() {
        for p in PROBLEMS {
            assert!(!p.start.is_empty() && p.start.len() <= crate::MAX_DIM);
            assert_eq!(p.start.len(), p.optimum.len());
        }
    }
}
