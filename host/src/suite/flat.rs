//! The flat-direction problem: f(x) = Σⱼ κ^(j/4)·(R(x₀..₅ − x*₀..₅))ⱼ², j = 0…4, on
//! x ∈ ℝ⁶ with κ = [`CONDITION`] and R a random 5×5 rotation. The last coordinate x₅
//! does not enter f at all: a method must not be misled by a direction with no
//! information (and no curvature), and its parameter error is measured on x₀…x₄ only.
//! f* = 0; no bounds; starts uniform in [−4, 4]⁶; σ₀ = [`SIGMA0`].

use super::problem::{Family, Measure, Observation, Problem, uniform_start};
use super::random;

/// Dimension n, including the ignored coordinate.
pub const DIM: usize = 6;

/// Condition number κ of the quadratic on the coordinates f sees.
pub const CONDITION: f64 = 1e4;

/// σ₀.
pub const SIGMA0: f64 = 2.0;

/// The flat-direction problem, instance `instance`.
pub fn problem(instance: u64, budget_per_dim: usize) -> Problem {
    let seen = DIM - 1;
    let seed = |salt: &str| random::seed_of(salt, &[instance]);
    let x_opt = random::uniform(DIM, -4.0, 4.0, seed("flat-xopt"));
    let r = random::rotation(seen, seed("flat-r"));
    let weights: Vec<f64> = (0..seen)
        .map(|j| CONDITION.powf(j as f64 / (seen - 1) as f64))
        .collect();
    let centre = x_opt.clone();
    let f = move |x: &[f64]| {
        let d: Vec<f64> = x[..seen].iter().zip(&centre).map(|(a, b)| a - b).collect();
        let mut z = vec![0.0; seen];
        random::mat_vec(&r, &d, &mut z);
        z.iter().zip(&weights).map(|(v, w)| w * v * v).sum()
    };
    Problem {
        name: format!("flat-n{DIM:02}-i{instance}"),
        family: Family::Flat,
        n: DIM,
        f: Box::new(f),
        observation: Observation::Exact,
        f_opt: 0.0,
        x_opt,
        measure: Measure::Leading(seen),
        start: uniform_start(DIM, -4.0, 4.0),
        sigma0: SIGMA0,
        bounds: None,
        budget: budget_per_dim * DIM,
    }
}
