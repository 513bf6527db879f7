//! The estimator variance study: every estimator at an equal budget of objective
//! evaluations, on a smooth and on a discontinuous problem, in 2 and 10 dimensions.
//!
//! For each (estimator, problem) the study repeats the estimate `repeats` times and
//! reports the total variance Σₑ Var(ĝₑ) (the trace of the estimator's covariance) and,
//! because FR22 and the uniform baseline are biased, the mean squared error
//! E‖ĝ − g‖² against the closed form. Budgets, per estimate:
//!
//! * gradients: 8n evaluations (per-element: P = 4 per element; one-set methods: P = 4n);
//! * Hessians: 2n(n+1) + 1 (per-element: P = 2 per element; one-set methods: P = n(n+1));
//! * HVPs: 8n (central differences: two gradients of 4n; kernel: P = 4n, plus f(θ)).
//!
//! The uniform baseline draws τ uniformly in the box [−4σ, 4σ]ⁿ and weights by
//! Dκ(τ)/p(τ) = Dκ(τ)·(8σ)ⁿ (truncation bias below 1e-4).

use std::fmt::Write as _;

use hodr_core::{Draws, Estimator, GradientMethod, HessianMethod, HvpMethod, Real, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::problems::Problem;

/// Smoothing width of the study.
pub const SIGMA: f64 = 0.5;

/// Half-width of the uniform baseline's box, in σ.
const UNIFORM_HALF_WIDTH: f64 = 4.0;

/// One estimator of the study.
#[derive(Clone, Copy, Debug)]
enum Row {
    Gradient(GradientMethod),
    UniformGradient,
    Hessian(HessianMethod),
    UniformHessian,
    Hvp(HvpMethod),
}

/// The name the rest of hodr gives a gradient estimator (FR22 as the preset, the
/// importance-sampling ones as BENCHMARKS.md does).
fn gradient_name(m: GradientMethod) -> &'static str {
    match m {
        GradientMethod::Fr22 => "FR22",
        GradientMethod::PerElement => "per-element",
        GradientMethod::Aggregate => "aggregate",
        GradientMethod::Gaussian => "Gaussian",
        GradientMethod::Regression => "least squares",
        _ => "other",
    }
}

impl Row {
    fn label(self) -> String {
        match self {
            Row::Gradient(m) => format!("gradient {}", gradient_name(m)),
            Row::UniformGradient => "gradient uniform box".into(),
            Row::Hessian(m) => format!(
                "Hessian {}",
                match m {
                    HessianMethod::PerElement => "per-element",
                    HessianMethod::Aggregate => "aggregate",
                    _ => "Gaussian",
                }
            ),
            Row::UniformHessian => "Hessian uniform box".into(),
            Row::Hvp(HvpMethod::CentralDifference { gradient, draws }) => format!(
                "HVP central difference, {}, {}",
                gradient_name(gradient),
                match draws {
                    Draws::Common => "common draws",
                    _ => "independent draws",
                }
            ),
            Row::Hvp(HvpMethod::ForwardDifference { gradient }) => {
                format!("HVP forward difference, {}", gradient_name(gradient))
            }
            Row::Hvp(_) => "HVP kernel".into(),
        }
    }

    /// Antithetic pairs at this row's budget in dimension n.
    fn pairs(self, n: usize) -> usize {
        match self {
            Row::Gradient(GradientMethod::PerElement) => 4,
            Row::Gradient(_) | Row::UniformGradient => 4 * n,
            Row::Hessian(HessianMethod::PerElement) => 2,
            Row::Hessian(_) | Row::UniformHessian => n * (n + 1),
            Row::Hvp(HvpMethod::CentralDifference {
                gradient: GradientMethod::PerElement,
                ..
            }) => 2,
            Row::Hvp(HvpMethod::CentralDifference { .. }) => 2 * n,
            Row::Hvp(_) => 4 * n,
        }
    }
}

fn rows() -> Vec<Row> {
    let mut rows = vec![
        Row::Gradient(GradientMethod::Fr22),
        Row::Gradient(GradientMethod::PerElement),
        Row::Gradient(GradientMethod::Aggregate),
        Row::Gradient(GradientMethod::Gaussian),
        Row::UniformGradient,
        Row::Hessian(HessianMethod::PerElement),
        Row::Hessian(HessianMethod::Aggregate),
        Row::Hessian(HessianMethod::Gaussian),
        Row::UniformHessian,
    ];
    for gradient in [
        GradientMethod::PerElement,
        GradientMethod::Aggregate,
        GradientMethod::Gaussian,
    ] {
        for draws in [Draws::Independent, Draws::Common] {
            rows.push(Row::Hvp(HvpMethod::CentralDifference { gradient, draws }));
        }
    }
    rows.push(Row::Hvp(HvpMethod::Kernel));
    rows
}

/// Total variance and mean squared error of one row on one problem.
#[derive(Clone, Copy, Debug)]
pub struct Cell {
    /// Σₑ Var(estimate element e).
    pub variance: f64,
    /// E‖estimate − closed form‖².
    pub mse: f64,
    /// Objective evaluations per estimate.
    pub evaluations: usize,
}

fn measure(row: Row, p: &Problem, repeats: usize, seed: u64) -> Cell {
    let n = p.dim();
    let pairs = row.pairs(n);
    let rows_cap = 256;
    let mut buffer = vec![0.0; Workspace::<f64>::buffer_len(n, rows_cap)];
    let mut seeds = vec![0; rows_cap];
    let mut ws = Workspace::new(n, &mut buffer, &mut seeds).expect("workspace sizes are valid");
    let mut est = Estimator::new(SIGMA, pairs, Xoshiro256PlusPlus::seed_from_u64(seed))
        .expect("valid settings");
    let mut f = |x: &[f64]| p.value(x);
    let v = p.direction(7);
    let (truth, len) = match row {
        Row::Gradient(_) | Row::UniformGradient => (p.gradient(p.theta(), SIGMA), n),
        Row::Hessian(_) | Row::UniformHessian => (p.hessian(p.theta(), SIGMA), n * n),
        Row::Hvp(HvpMethod::Kernel) => (p.hvp(p.theta(), &v, SIGMA), n),
        Row::Hvp(_) => (p.hvp_central(p.theta(), &v, SIGMA), n),
    };
    let mut out = vec![0.0; len];
    let (mut sum, mut sum2, mut sq_err) = (vec![0.0; len], vec![0.0; len], 0.0);
    let mut evaluations = 0;
    for _ in 0..repeats {
        evaluations = match row {
            Row::Gradient(m) => est
                .gradient(m, &mut f, p.theta(), &mut ws, &mut out)
                .map(|r| r.evaluations),
            Row::Hessian(m) => est
                .hessian(m, &mut f, p.theta(), &mut ws, &mut out)
                .map(|r| r.evaluations),
            Row::Hvp(m) => est
                .hvp(m, &mut f, p.theta(), &v, &mut ws, &mut out)
                .map(|r| r.evaluations),
            Row::UniformGradient => Ok(uniform(est.rng_mut(), p, pairs, false, &mut out)),
            Row::UniformHessian => Ok(uniform(est.rng_mut(), p, pairs, true, &mut out)),
        }
        .expect("closed-form problems are finite");
        for k in 0..len {
            sum[k] += out[k];
            sum2[k] += out[k] * out[k];
            sq_err += (out[k] - truth[k]).powi(2);
        }
    }
    let m = repeats as f64;
    let variance = (0..len)
        .map(|k| (sum2[k] / m - (sum[k] / m).powi(2)).max(0.0))
        .sum();
    Cell {
        variance,
        mse: sq_err / m,
        evaluations,
    }
}

/// The uniform-box baseline: gradient (or Hessian with the f(θ) control variate) from
/// `pairs` antithetic pairs with τ uniform in [−4σ, 4σ]ⁿ. Returns evaluations used.
fn uniform(
    rng: &mut Xoshiro256PlusPlus,
    p: &Problem,
    pairs: usize,
    hessian: bool,
    out: &mut [f64],
) -> usize {
    let n = p.dim();
    let theta = p.theta();
    let h = UNIFORM_HALF_WIDTH;
    out.fill(0.0);
    let centre = if hessian { p.value(theta) } else { 0.0 };
    let mut t = vec![0.0; n];
    let (mut minus, mut plus) = (vec![0.0; n], vec![0.0; n]);
    for _ in 0..pairs {
        let mut density_ratio = 1.0; // N(t)·(2h)ⁿ in standardised units
        for k in 0..n {
            t[k] = h * (2.0 * f64::uniform_open(rng) - 1.0);
            density_ratio *= hodr_core::sample::normal::pdf(t[k]) * 2.0 * h;
            minus[k] = theta[k] - SIGMA * t[k];
            plus[k] = theta[k] + SIGMA * t[k];
        }
        let (fm, fp) = (p.value(&minus), p.value(&plus));
        if hessian {
            let even = 0.5 * ((fm - centre) + (fp - centre)) * density_ratio;
            for i in 0..n {
                for j in 0..n {
                    let delta = if i == j { 1.0 } else { 0.0 };
                    out[i * n + j] += even * (t[i] * t[j] - delta) / (SIGMA * SIGMA);
                }
            }
        } else {
            let odd = 0.5 * (fm - fp) * density_ratio;
            for k in 0..n {
                out[k] -= odd * t[k] / SIGMA;
            }
        }
    }
    for x in out.iter_mut() {
        *x /= pairs as f64;
    }
    2 * pairs + usize::from(hessian)
}

/// Runs the study and returns it as a Markdown table.
pub fn study(repeats: usize) -> String {
    let problems = [
        ("sin/cos n=2", Problem::sin_cos(2, 1)),
        ("sin/cos n=10", Problem::sin_cos(10, 1)),
        ("step n=2", Problem::step(2, 3, 0.3)),
        ("step n=10", Problem::step(10, 3, 0.3)),
    ];
    let mut md = String::new();
    let _ = writeln!(
        md,
        "σ = {SIGMA}, {repeats} repetitions per cell; each cell: total variance Σₑ Var / mean squared error \
         E‖est − exact‖² (evaluations per estimate)."
    );
    let _ = writeln!(md);
    let _ = write!(md, "| estimator |");
    for (name, _) in &problems {
        let _ = write!(md, " {name} |");
    }
    let _ = writeln!(md);
    let _ = writeln!(md, "|---|{}", "---|".repeat(problems.len()));
    for (r, row) in rows().into_iter().enumerate() {
        let _ = write!(md, "| {} |", row.label());
        for (k, (_, p)) in problems.iter().enumerate() {
            let c = measure(row, p, repeats, 1000 + 37 * r as u64 + k as u64);
            let _ = write!(
                md,
                " {:.3e} / {:.3e} ({}) |",
                c.variance, c.mse, c.evaluations
            );
        }
        let _ = writeln!(md);
    }
    md
}
