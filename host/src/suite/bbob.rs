//! Eleven BBOB noiseless functions, written from their published definitions: N. Hansen,
//! S. Finck, R. Ros, A. Auger, "Real-Parameter Black-Box Optimization Benchmarking 2009:
//! Noiseless Functions Definitions", INRIA research report RR-6829.
//!
//! Notation as in the report, D = n, i = 1…D, f_opt = 0 here (the suite reports f − f*):
//!
//! * T_osz: xᵢ ↦ sign(xᵢ)·exp(x̂ᵢ + 0.049(sin(c₁x̂ᵢ) + sin(c₂x̂ᵢ))), x̂ᵢ = ln|xᵢ| (0 for
//!   xᵢ = 0), c₁ = 10 and c₂ = 7.9 for xᵢ > 0, else 5.5 and 3.1;
//! * T_asy^β: xᵢ ↦ xᵢ^(1 + β·(i−1)/(D−1)·√xᵢ) for xᵢ > 0, else xᵢ;
//! * Λ^α: diagonal, λᵢᵢ = α^(½·(i−1)/(D−1));
//! * f_pen(x) = Σ max(0, |xᵢ| − 5)²;
//! * R, Q: random rotations ([`super::random::rotation`]), fixed by the instance;
//! * x_opt uniform in [−4, 4]ᴰ, fixed by the instance (f8: scaled by ¾, into [−3, 3]ᴰ,
//!   as the report's code does).
//!
//! | id | name | f |
//! |---|---|---|
//! | f1 | sphere | ‖z‖², z = x − x_opt |
//! | f2 | separable ellipsoid | Σ 10^(6(i−1)/(D−1)) zᵢ², z = T_osz(x − x_opt) |
//! | f6 | attractive sector | T_osz(Σ (sᵢzᵢ)²)^0.9, z = QΛ¹⁰R(x − x_opt), sᵢ = 100 if zᵢ·x_opt,ᵢ > 0 else 1 |
//! | f7 | step ellipsoid | 0.1·max(\|ẑ₁\|/10⁴, Σ 10^(2(i−1)/(D−1)) zᵢ²) + f_pen(x), ẑ = Λ¹⁰R(x − x_opt), z̃ᵢ = ⌊0.5 + ẑᵢ⌋ if \|ẑᵢ\| > 0.5 else ⌊0.5 + 10ẑᵢ⌋/10, z = Qz̃ |
//! | f8 | Rosenbrock, original | Σ_{i<D} 100(zᵢ² − zᵢ₊₁)² + (zᵢ − 1)², z = max(1, √D/8)(x − x_opt) + 1 |
//! | f10 | rotated ellipsoid | Σ 10^(6(i−1)/(D−1)) zᵢ², z = T_osz(R(x − x_opt)) |
//! | f11 | discus | 10⁶z₁² + Σ_{i≥2} zᵢ², z = T_osz(R(x − x_opt)) |
//! | f12 | bent cigar | z₁² + 10⁶Σ_{i≥2} zᵢ², z = R·T_asy^0.5(R(x − x_opt)) |
//! | f13 | sharp ridge | z₁² + 100·√(Σ_{i≥2} zᵢ²), z = QΛ¹⁰R(x − x_opt) |
//! | f14 | different powers | √(Σ \|zᵢ\|^(2 + 4(i−1)/(D−1))), z = R(x − x_opt) |
//! | f15 | rotated Rastrigin | 10(D − Σ cos 2πzᵢ) + ‖z‖², z = RΛ¹⁰Q·T_asy^0.2(T_osz(R(x − x_opt))) |
//!
//! Each is zero at x_opt and positive elsewhere (f7: almost everywhere — it is zero on
//! the set where ẑ₁ = 0 and every |ẑᵢ| < 0.05, a subset of a hyperplane through x_opt).
//! Our instances use our own seeds, so they are not COCO's instances 1–5; the functions
//! are the same.

use std::f64::consts::PI;

use super::problem::{Bounds, Family, Measure, Observation, Problem, uniform_start};
use super::random;

/// The functions of the suite, by BBOB number.
pub const IDS: [u32; 11] = [1, 2, 6, 7, 8, 10, 11, 12, 13, 14, 15];

/// σ₀ of every BBOB problem: a common CMA-ES choice on the domain [−5, 5]ⁿ.
pub const SIGMA0: f64 = 2.0;

/// The domain [−LIMIT, LIMIT]ⁿ, used as the problems' bounds.
pub const LIMIT: f64 = 5.0;

/// Short name of function `id`.
pub fn function_name(id: u32) -> &'static str {
    match id {
        1 => "sphere",
        2 => "ellipsoid",
        6 => "attractive-sector",
        7 => "step-ellipsoid",
        8 => "rosenbrock",
        10 => "rotated-ellipsoid",
        11 => "discus",
        12 => "bent-cigar",
        13 => "sharp-ridge",
        14 => "different-powers",
        15 => "rastrigin",
        _ => "unknown",
    }
}

/// One BBOB function instance: the function id, D, and the instance's data.
#[derive(Clone, Debug)]
pub struct Bbob {
    id: u32,
    n: usize,
    x_opt: Vec<f64>,
    r: Vec<f64>,
    q: Vec<f64>,
}

impl Bbob {
    /// Function `id` (one of [`IDS`]) in `n` ≥ 2 dimensions, instance `instance`: x_opt,
    /// R and Q are drawn from seeds of (id, n, instance).
    ///
    /// # Panics
    /// If `id` is not in [`IDS`] or n < 2 (programming errors: the suite lists its
    /// problems itself).
    pub fn new(id: u32, n: usize, instance: u64) -> Bbob {
        assert!(IDS.contains(&id), "BBOB f{id} is not in the suite");
        assert!(n >= 2, "BBOB functions need n ≥ 2");
        let seed = |salt: &str| random::seed_of(salt, &[u64::from(id), n as u64, instance]);
        let mut x_opt = random::uniform(n, -4.0, 4.0, seed("bbob-xopt"));
        if id == 8 {
            x_opt.iter_mut().for_each(|v| *v *= 0.75);
        }
        Bbob {
            id,
            n,
            x_opt,
            r: random::rotation(n, seed("bbob-r")),
            q: random::rotation(n, seed("bbob-q")),
        }
    }

    /// The function's BBOB number.
    pub fn id(&self) -> u32 {
        self.id
    }

    /// x_opt, where f = 0.
    pub fn x_opt(&self) -> &[f64] {
        &self.x_opt
    }

    /// The rotation R, row-major n×n.
    pub fn r(&self) -> &[f64] {
        &self.r
    }

    /// The rotation Q, row-major n×n.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// f(x) (f_opt = 0).
    pub fn value(&self, x: &[f64]) -> f64 {
        let n = self.n;
        let d: Vec<f64> = x.iter().zip(&self.x_opt).map(|(a, b)| a - b).collect();
        let mut z = vec![0.0; n];
        match self.id {
            1 => d.iter().map(|v| v * v).sum(),
            2 => {
                let z = t_osz(&d);
                (0..n).map(|i| ill(1e6, i, n) * z[i] * z[i]).sum()
            }
            6 => {
                self.q_lambda_r(&d, &mut z);
                let s: f64 = z
                    .iter()
                    .zip(&self.x_opt)
                    .map(|(zi, xo)| {
                        let si = if zi * xo > 0.0 { 100.0 } else { 1.0 };
                        (si * zi).powi(2)
                    })
                    .sum();
                t_osz1(s).powf(0.9)
            }
            7 => {
                let mut zhat = vec![0.0; n];
                random::mat_vec(&self.r, &d, &mut zhat);
                for (i, v) in zhat.iter_mut().enumerate() {
                    *v *= lambda(10.0, i, n);
                }
                let ztilde: Vec<f64> = zhat
                    .iter()
                    .map(|&v| {
                        if v.abs() > 0.5 {
                            (0.5 + v).floor()
                        } else {
                            (0.5 + 10.0 * v).floor() / 10.0
                        }
                    })
                    .collect();
                random::mat_vec(&self.q, &ztilde, &mut z);
                let sum: f64 = (0..n).map(|i| ill(1e2, i, n) * z[i] * z[i]).sum();
                0.1 * (zhat[0].abs() / 1e4).max(sum) + f_pen(x)
            }
            8 => {
                let scale = 1f64.max((n as f64).sqrt() / 8.0);
                let z: Vec<f64> = d.iter().map(|v| scale * v + 1.0).collect();
                z.windows(2)
                    .map(|w| 100.0 * (w[0] * w[0] - w[1]).powi(2) + (w[0] - 1.0).powi(2))
                    .sum()
            }
            10 => {
                random::mat_vec(&self.r, &d, &mut z);
                let z = t_osz(&z);
                (0..n).map(|i| ill(1e6, i, n) * z[i] * z[i]).sum()
            }
            11 => {
                random::mat_vec(&self.r, &d, &mut z);
                let z = t_osz(&z);
                1e6 * z[0] * z[0] + z[1..].iter().map(|v| v * v).sum::<f64>()
            }
            12 => {
                let mut y = vec![0.0; n];
                random::mat_vec(&self.r, &d, &mut y);
                random::mat_vec(&self.r, &t_asy(&y, 0.5), &mut z);
                z[0] * z[0] + 1e6 * z[1..].iter().map(|v| v * v).sum::<f64>()
            }
            13 => {
                self.q_lambda_r(&d, &mut z);
                z[0] * z[0] + 100.0 * z[1..].iter().map(|v| v * v).sum::<f64>().sqrt()
            }
            14 => {
                random::mat_vec(&self.r, &d, &mut z);
                z.iter()
                    .enumerate()
                    .map(|(i, v)| v.abs().powf(2.0 + 4.0 * i as f64 / (n - 1) as f64))
                    .sum::<f64>()
                    .sqrt()
            }
            15 => {
                let mut y = vec![0.0; n];
                random::mat_vec(&self.r, &d, &mut y);
                let y = t_asy(&t_osz(&y), 0.2);
                random::mat_vec(&self.q, &y, &mut z);
                for (i, v) in z.iter_mut().enumerate() {
                    *v *= lambda(10.0, i, n);
                }
                let mut w = vec![0.0; n];
                random::mat_vec(&self.r, &z, &mut w);
                10.0 * (n as f64 - w.iter().map(|v| (2.0 * PI * v).cos()).sum::<f64>())
                    + w.iter().map(|v| v * v).sum::<f64>()
            }
            _ => unreachable!("checked in Bbob::new"),
        }
    }

    /// z = QΛ¹⁰R·d.
    fn q_lambda_r(&self, d: &[f64], z: &mut [f64]) {
        let n = self.n;
        let mut y = vec![0.0; n];
        random::mat_vec(&self.r, d, &mut y);
        for (i, v) in y.iter_mut().enumerate() {
            *v *= lambda(10.0, i, n);
        }
        random::mat_vec(&self.q, &y, z);
    }
}

/// λᵢᵢ of Λ^α for 0-based i: α^(½·i/(D−1)).
fn lambda(alpha: f64, i: usize, n: usize) -> f64 {
    alpha.powf(0.5 * i as f64 / (n - 1) as f64)
}

/// The ill-conditioning weight c^(i/(D−1)) for 0-based i (c = 10⁶ for f2/f10, 10² for f7).
fn ill(c: f64, i: usize, n: usize) -> f64 {
    c.powf(i as f64 / (n - 1) as f64)
}

/// T_osz of one coordinate.
pub fn t_osz1(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let xhat = x.abs().ln();
    let (c1, c2) = if x > 0.0 { (10.0, 7.9) } else { (5.5, 3.1) };
    x.signum() * (xhat + 0.049 * ((c1 * xhat).sin() + (c2 * xhat).sin())).exp()
}

/// T_osz, coordinate-wise.
pub fn t_osz(x: &[f64]) -> Vec<f64> {
    x.iter().map(|&v| t_osz1(v)).collect()
}

/// T_asy^β.
pub fn t_asy(x: &[f64], beta: f64) -> Vec<f64> {
    let n = x.len();
    x.iter()
        .enumerate()
        .map(|(i, &v)| {
            if v > 0.0 {
                v.powf(1.0 + beta * i as f64 / (n - 1) as f64 * v.sqrt())
            } else {
                v
            }
        })
        .collect()
}

/// f_pen(x) = Σ max(0, |xᵢ| − 5)².
pub fn f_pen(x: &[f64]) -> f64 {
    x.iter().map(|v| (v.abs() - LIMIT).max(0.0).powi(2)).sum()
}

/// The suite problem for function `id`, dimension `n`, instance `instance`: bounds
/// [−5, 5]ⁿ, starts uniform in [−4, 4]ⁿ, σ₀ = [`SIGMA0`], f* = 0, the Euclidean
/// parameter error, `budget_per_dim`·n evaluations.
pub fn problem(id: u32, n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    let b = Bbob::new(id, n, instance);
    let x_opt = b.x_opt().to_vec();
    Problem {
        name: format!("bbob-f{id:02}-n{n:02}-i{instance}"),
        family: Family::Bbob,
        n,
        f: Box::new(move |x| b.value(x)),
        observation: Observation::Exact,
        f_opt: 0.0,
        x_opt,
        measure: Measure::Euclidean,
        start: uniform_start(n, -4.0, 4.0),
        sigma0: SIGMA0,
        bounds: Some(Bounds::cube(n, -LIMIT, LIMIT)),
        budget: budget_per_dim * n,
    }
}
