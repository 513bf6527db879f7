//! Error against run time for every preset on QUAD, BOX2-REF and stiff quadratics.
//!
//! For each problem × preset × seed the optimiser runs on one thread, stepping under a
//! wall clock; after every iteration the parameter error ‖θ − θ*‖ is recorded with the
//! elapsed time and evaluation count ([`crate::metrics`]). The table gives, per preset,
//! the median over seeds of the time and evaluations to 90 / 99 / 99.9 % parameter-error
//! reduction ("—" when half or more of the seeds never get there).
//!
//! Problems and settings (DESIGN §3, the paper's hyper-parameters where it gives them):
//!
//! | problem | start | pairs | σ | Δ | LS | recompute | Adam η | budget |
//! |---|---|---|---|---|---|---|---|---|
//! | QUAD-near | U\[−3,3\]² | 4 | 1 → 0.05 | 50 | 5 | 5 | 0.5 | 3000 evaluations |
//! | QUAD-far | U\[800,1000\]² | 4 | 1 → 0.05 | 50 | 5 | 5 | 0.5 | 6000 evaluations |
//! | BOX2-REF | U\[210,360)² | 6 | 100 → 0.01 (FR22 → 0.1) | 2 | 2 | 10 | 0.5 (FR22 0.3) | 4000 evaluations |
//! | STIFF-κ | θ* + 1·(unit vector) | 4 | 0.5 → 0.05 | 10 | 3 | 5 | 0.05 | 3000 evaluations |
//!
//! STIFF-κ is ½(x − θ*)ᵀA(x − θ*) in 2-D with eigenvalues 1 and κ on axes rotated by 30°.
//! With `crn`, the paper's central-difference presets draw their two gradients with
//! common random numbers.

use std::fmt::Write as _;
use std::time::Instant;

use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::optim::{Budget, NegativeCurvature, Optimiser};
use hodr_core::{Estimator, Objective, Real, Workspace};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::box2ref::{self, Box2Ref};
use crate::metrics::{REDUCTIONS, Sample, first_reaching, format_seconds, median};
use crate::report::task::{box2ref_hyper, quad_hyper};

/// A benchmark problem with a known optimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Problem {
    /// f = 5x₀² + 5x₁² + 7.5x₀x₁, starts uniform in [−3, 3]².
    QuadNear,
    /// The same, starts uniform in [800, 1000]² (the paper's).
    QuadFar,
    /// The paper's BOX2 renderer.
    Box2Ref,
    /// A 2-D quadratic with condition number κ.
    Stiff(f64),
}

impl Problem {
    /// Every problem of the default table.
    pub fn all() -> Vec<Problem> {
        vec![
            Problem::QuadNear,
            Problem::QuadFar,
            Problem::Box2Ref,
            Problem::Stiff(1e2),
            Problem::Stiff(1e4),
            Problem::Stiff(1e6),
            Problem::Stiff(1e8),
        ]
    }

    /// Display name.
    pub fn name(&self) -> String {
        match self {
            Problem::QuadNear => "QUAD-near".into(),
            Problem::QuadFar => "QUAD-far".into(),
            Problem::Box2Ref => "BOX2-REF".into(),
            Problem::Stiff(k) => format!("STIFF-{k:.0e}"),
        }
    }

    fn optimum(&self) -> [f64; 2] {
        match self {
            Problem::Box2Ref => box2ref::TARGET,
            Problem::Stiff(_) => [0.3, -0.2],
            _ => [0.0, 0.0],
        }
    }

    fn start(&self, seed: u64) -> [f64; 2] {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ 0x5EED_0F57_A127);
        let mut u = || f64::uniform_open(&mut rng);
        match self {
            Problem::QuadNear => [6.0 * u() - 3.0, 6.0 * u() - 3.0],
            Problem::QuadFar => [800.0 + 200.0 * u(), 800.0 + 200.0 * u()],
            Problem::Box2Ref => [210.0 + 150.0 * u(), 210.0 + 150.0 * u()],
            Problem::Stiff(_) => {
                let a = std::f64::consts::TAU * u();
                let o = self.optimum();
                [o[0] + a.cos(), o[1] + a.sin()]
            }
        }
    }

    fn hyper(&self, preset: Preset, crn: bool) -> Hyper<f64> {
        match self {
            Problem::QuadNear | Problem::QuadFar => Hyper {
                common_random_numbers: crn,
                ..quad_hyper()
            },
            Problem::Box2Ref => Hyper {
                common_random_numbers: crn,
                ..box2ref_hyper(preset)
            },
            Problem::Stiff(_) => Hyper {
                pairs: 4,
                sigma_start: 0.5,
                sigma_end: 0.05,
                trust_radius: 10.0,
                line_search_iterations: 3,
                line_search_tolerance: 1e-12,
                recompute: 5,
                learning_rate: 0.05,
                common_random_numbers: crn,
                negative_curvature: NegativeCurvature::Fallback,
                sigma_shrink: hodr_core::optim::preset::SIGMA_SHRINK,
                inner_steps: hodr_core::optim::preset::NEWTON_CG_INNER_STEPS,
                line_curvature: false,
            },
        }
    }

    fn budget(&self) -> usize {
        match self {
            Problem::QuadNear => 3000,
            Problem::QuadFar => 6000,
            Problem::Box2Ref => 4000,
            Problem::Stiff(_) => 3000,
        }
    }
}

/// QUAD and the stiff quadratics as objectives.
struct Quadratic {
    /// Row-major 2×2 matrix.
    a: [f64; 4],
    optimum: [f64; 2],
}

impl Quadratic {
    fn quad() -> Self {
        // 5x₀² + 5x₁² + 7.5x₀x₁ = ½xᵀAx with A = [[10, 7.5], [7.5, 10]].
        Quadratic {
            a: [10.0, 7.5, 7.5, 10.0],
            optimum: [0.0, 0.0],
        }
    }

    fn stiff(kappa: f64, optimum: [f64; 2]) -> Self {
        let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        // A = R diag(1, κ) Rᵀ.
        let a = [
            c * c + kappa * s * s,
            (1.0 - kappa) * c * s,
            (1.0 - kappa) * c * s,
            s * s + kappa * c * c,
        ];
        Quadratic { a, optimum }
    }
}

impl Objective<f64> for Quadratic {
    fn evaluate(&mut self, x: &[f64], _seed: u64) -> f64 {
        let d = [x[0] - self.optimum[0], x[1] - self.optimum[1]];
        0.5 * (d[0] * (self.a[0] * d[0] + self.a[1] * d[1])
            + d[1] * (self.a[2] * d[0] + self.a[3] * d[1]))
    }

    fn deterministic(&self) -> bool {
        true
    }
}

/// One run: the samples (time, evaluations, parameter error) after every iteration.
pub fn run(problem: Problem, preset: Preset, seed: u64, crn: bool) -> Vec<Sample> {
    let h = problem.hyper(preset, crn);
    let method = preset.method(&h);
    let optimum = problem.optimum();
    let mut theta = problem.start(seed);
    let mut buffer = vec![0.0; method.buffer_len(2)];
    let est = Estimator::new(
        h.sigma_start,
        h.pairs,
        Xoshiro256PlusPlus::seed_from_u64(seed),
    )
    .expect("valid settings");
    let budget = Budget::evaluations(problem.budget());
    let mut opt = Optimiser::new(
        method,
        preset.schedule(&h),
        budget,
        est,
        &mut theta,
        &mut buffer,
    )
    .expect("valid settings");
    let (mut wb, mut seeds) = (vec![0.0; method.workspace_len(2, 64)], vec![0; 64]);
    let mut ws = Workspace::new(2, &mut wb, &mut seeds).expect("valid sizes");
    let mut objective: Box<dyn Objective<f64>> = match problem {
        Problem::QuadNear | Problem::QuadFar => Box::new(Quadratic::quad()),
        Problem::Stiff(k) => Box::new(Quadratic::stiff(k, optimum)),
        Problem::Box2Ref => Box::new(Box2Ref::new()),
    };
    let error = |t: &[f64]| ((t[0] - optimum[0]).powi(2) + (t[1] - optimum[1]).powi(2)).sqrt();
    let mut samples = vec![Sample {
        time: 0.0,
        evaluations: 0,
        error: error(opt.theta()),
    }];
    let clock = Instant::now();
    // A failed iteration ends the run; its samples so far stand.
    while let Ok(Some(report)) = opt.step(objective.as_mut(), &mut ws, 0.0) {
        samples.push(Sample {
            time: clock.elapsed().as_secs_f64(),
            evaluations: report.evaluations,
            error: error(opt.theta()),
        });
    }
    samples
}

/// The Markdown tables for `problems` × `presets` over `seeds` seeds.
pub fn table(problems: &[Problem], presets: &[Preset], seeds: u64, crn: bool) -> String {
    let mut md = String::new();
    for problem in problems {
        let _ = writeln!(md, "### {}\n", problem.name());
        let _ = writeln!(
            md,
            "| method | 90 %: time / evals | 99 %: time / evals | 99.9 %: time / evals | median final error |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|");
        for &preset in presets {
            let runs: Vec<Vec<Sample>> =
                (0..seeds).map(|s| run(*problem, preset, s, crn)).collect();
            let _ = write!(md, "| {} |", preset.name());
            for reduction in REDUCTIONS {
                let reached: Vec<_> = runs.iter().map(|r| first_reaching(r, reduction)).collect();
                let t = median(
                    &reached
                        .iter()
                        .map(|r| r.map(|x| x.time))
                        .collect::<Vec<_>>(),
                );
                let e = median(
                    &reached
                        .iter()
                        .map(|r| r.map(|x| x.evaluations as f64))
                        .collect::<Vec<_>>(),
                );
                let evals = e.map_or("—".to_string(), |e| format!("{e:.0}"));
                let _ = write!(md, " {} / {} |", format_seconds(t), evals);
            }
            let finals: Vec<Option<f64>> = runs.iter().map(|r| r.last().map(|s| s.error)).collect();
            let _ = writeln!(md, " {:.2e} |", median(&finals).unwrap_or(f64::NAN));
        }
        let _ = writeln!(md);
    }
    md
}
