//! Test problems whose Gaussian-smoothed derivatives are known in closed form.
//!
//! With Φ/φ the standard normal CDF/density, σ the smoothing width and
//! e_a = exp(−σ²|a|²/2) (the smoothing of a plane wave along a):
//!
//! * [`Problem::sin_cos`]: f = sin(a·x) + 0.3 cos(b·x);
//!   ∇f̄ = e_a cos(a·θ) a − 0.3 e_b sin(b·θ) b, ∇²f̄ = −e_a sin(a·θ) aaᵀ − 0.3 e_b cos(b·θ) bbᵀ;
//! * [`Problem::separable`]: f = Σₖ sin(aₖxₖ) + 0.3 cos(bₖxₖ), each term smoothed on its own
//!   axis (so the FR22 estimator, which blurs other axes with a different density, is
//!   exact on it);
//! * [`Problem::quadratic`]: f = ½xᵀAx + cᵀx; ∇f̄ = Aθ + c, ∇²f̄ = A (smoothing adds a
//!   constant σ²tr(A)/2);
//! * [`Problem::step`]: f = 1[u·x > s] for a unit u; with z = (u·θ − s)/σ, f̄ = Φ(z),
//!   ∇f̄ = φ(z)/σ·u, ∇²f̄ = −zφ(z)/σ²·uuᵀ.
//!
//! Problem data are deterministic functions of (n, seed).

use hodr_core::Real;
use hodr_core::sample::normal;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// A closed-form test problem in n dimensions, with a reference point θ.
#[derive(Clone, Debug)]
pub struct Problem {
    n: usize,
    theta: Vec<f64>,
    kind: Kind,
}

#[derive(Clone, Debug)]
enum Kind {
    SinCos { a: Vec<f64>, b: Vec<f64> },
    Separable { a: Vec<f64>, b: Vec<f64> },
    Quadratic { a: Vec<f64>, c: Vec<f64> },
    Step { u: Vec<f64>, s: f64 },
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// n numbers uniform in (−scale, scale), fixed by (seed, salt).
fn data(n: usize, seed: u64, salt: u64, scale: f64) -> Vec<f64> {
    let mut rng =
        Xoshiro256PlusPlus::seed_from_u64(seed.wrapping_mul(1_000_003).wrapping_add(salt));
    (0..n)
        .map(|_| scale * (2.0 * f64::uniform_open(&mut rng) - 1.0))
        .collect()
}

impl Problem {
    /// sin(a·x) + 0.3 cos(b·x) with |aᵢ| < 1.2, |bᵢ| < 0.9 and θ in (−1, 1)ⁿ.
    pub fn sin_cos(n: usize, seed: u64) -> Self {
        Problem {
            n,
            theta: data(n, seed, 1, 1.0),
            kind: Kind::SinCos {
                a: data(n, seed, 2, 1.2),
                b: data(n, seed, 3, 0.9),
            },
        }
    }

    /// Σₖ sin(aₖxₖ) + 0.3 cos(bₖxₖ) with |aₖ| < 1.5, |bₖ| < 1.
    pub fn separable(n: usize, seed: u64) -> Self {
        Problem {
            n,
            theta: data(n, seed, 4, 1.0),
            kind: Kind::Separable {
                a: data(n, seed, 5, 1.5),
                b: data(n, seed, 6, 1.0),
            },
        }
    }

    /// ½xᵀAx + cᵀx with A = MᵀM/n + I symmetric positive definite.
    pub fn quadratic(n: usize, seed: u64) -> Self {
        let m = data(n * n, seed, 7, 1.0);
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let mtm: f64 = (0..n).map(|k| m[k * n + i] * m[k * n + j]).sum();
                a[i * n + j] = mtm / n as f64 + if i == j { 1.0 } else { 0.0 };
            }
        }
        Problem {
            n,
            theta: data(n, seed, 8, 1.0),
            kind: Kind::Quadratic {
                a,
                c: data(n, seed, 9, 1.0),
            },
        }
    }

    /// 1[u·x > s] with u a random unit vector and s such that u·θ − s = `offset`.
    pub fn step(n: usize, seed: u64, offset: f64) -> Self {
        let raw = data(n, seed, 10, 1.0);
        let norm = dot(&raw, &raw).sqrt();
        let u: Vec<f64> = raw.iter().map(|x| x / norm).collect();
        let theta = data(n, seed, 11, 1.0);
        let s = dot(&u, &theta) - offset;
        Problem {
            n,
            theta,
            kind: Kind::Step { u, s },
        }
    }

    /// 1[x_{n−1} > s], a step along the last axis, with θ_{n−1} − s = `offset`.
    pub fn axis_step(n: usize, seed: u64, offset: f64) -> Self {
        let mut u = vec![0.0; n];
        u[n - 1] = 1.0;
        let theta = data(n, seed, 12, 1.0);
        let s = theta[n - 1] - offset;
        Problem {
            n,
            theta,
            kind: Kind::Step { u, s },
        }
    }

    /// The dimension n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The reference point θ.
    pub fn theta(&self) -> &[f64] {
        &self.theta
    }

    /// f(x).
    pub fn value(&self, x: &[f64]) -> f64 {
        match &self.kind {
            Kind::SinCos { a, b } => dot(a, x).sin() + 0.3 * dot(b, x).cos(),
            Kind::Separable { a, b } => (0..self.n)
                .map(|k| (a[k] * x[k]).sin() + 0.3 * (b[k] * x[k]).cos())
                .sum(),
            Kind::Quadratic { a, c } => {
                let n = self.n;
                let quad: f64 = (0..n).map(|i| x[i] * dot(&a[i * n..(i + 1) * n], x)).sum();
                0.5 * quad + dot(c, x)
            }
            Kind::Step { u, s } => {
                if dot(u, x) > *s {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// ∇f̄(θ) at smoothing σ.
    pub fn gradient(&self, theta: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        match &self.kind {
            Kind::SinCos { a, b } => {
                let (ea, eb) = (damping(a, sigma), damping(b, sigma));
                let (ca, sb) = (dot(a, theta).cos(), dot(b, theta).sin());
                (0..n)
                    .map(|i| ea * ca * a[i] - 0.3 * eb * sb * b[i])
                    .collect()
            }
            Kind::Separable { a, b } => (0..n)
                .map(|k| {
                    let (ea, eb) = (damping(&a[k..=k], sigma), damping(&b[k..=k], sigma));
                    ea * a[k] * (a[k] * theta[k]).cos() - 0.3 * eb * b[k] * (b[k] * theta[k]).sin()
                })
                .collect(),
            Kind::Quadratic { a, c } => (0..n)
                .map(|i| dot(&a[i * n..(i + 1) * n], theta) + c[i])
                .collect(),
            Kind::Step { u, s } => {
                let z = (dot(u, theta) - s) / sigma;
                u.iter().map(|ui| normal::pdf(z) / sigma * ui).collect()
            }
        }
    }

    /// ∇²f̄(θ) at smoothing σ, n×n row-major.
    pub fn hessian(&self, theta: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        let mut h = vec![0.0; n * n];
        match &self.kind {
            Kind::SinCos { a, b } => {
                let (ea, eb) = (damping(a, sigma), damping(b, sigma));
                let (sa, cb) = (dot(a, theta).sin(), dot(b, theta).cos());
                for i in 0..n {
                    for j in 0..n {
                        h[i * n + j] = -ea * sa * a[i] * a[j] - 0.3 * eb * cb * b[i] * b[j];
                    }
                }
            }
            Kind::Separable { a, b } => {
                for k in 0..n {
                    let (ea, eb) = (damping(&a[k..=k], sigma), damping(&b[k..=k], sigma));
                    h[k * n + k] = -ea * a[k] * a[k] * (a[k] * theta[k]).sin()
                        - 0.3 * eb * b[k] * b[k] * (b[k] * theta[k]).cos();
                }
            }
            Kind::Quadratic { a, .. } => h.copy_from_slice(a),
            Kind::Step { u, s } => {
                let z = (dot(u, theta) - s) / sigma;
                let curvature = -z * normal::pdf(z) / (sigma * sigma);
                for i in 0..n {
                    for j in 0..n {
                        h[i * n + j] = curvature * u[i] * u[j];
                    }
                }
            }
        }
        h
    }

    /// ∇²f̄(θ)·v at smoothing σ.
    pub fn hvp(&self, theta: &[f64], v: &[f64], sigma: f64) -> Vec<f64> {
        let n = self.n;
        let h = self.hessian(theta, sigma);
        (0..n).map(|i| dot(&h[i * n..(i + 1) * n], v)).collect()
    }

    /// What the central-difference HVP estimates: (∇f̄(θ + εu) − ∇f̄(θ − εu))/(2ε)·‖v‖
    /// with u = v/‖v‖ and ε = σ/3.
    pub fn hvp_central(&self, theta: &[f64], v: &[f64], sigma: f64) -> Vec<f64> {
        self.hvp_difference(theta, v, sigma, -1.0)
    }

    /// What the forward-difference HVP estimates: (∇f̄(θ + εu) − ∇f̄(θ))/ε·‖v‖ with
    /// u = v/‖v‖ and ε = σ/3.
    pub fn hvp_forward(&self, theta: &[f64], v: &[f64], sigma: f64) -> Vec<f64> {
        self.hvp_difference(theta, v, sigma, 0.0)
    }

    /// (∇f̄(θ + εu) − ∇f̄(θ + bεu))/((1 − b)ε)·‖v‖, ε = σ/3.
    fn hvp_difference(&self, theta: &[f64], v: &[f64], sigma: f64, b: f64) -> Vec<f64> {
        let norm = dot(v, v).sqrt();
        let eps = sigma * hodr_core::estimate::HVP_STEP_RATIO;
        let shift = |s: f64| -> Vec<f64> {
            theta
                .iter()
                .zip(v)
                .map(|(t, d)| t + s * eps * d / norm)
                .collect()
        };
        let (gp, gb) = (
            self.gradient(&shift(1.0), sigma),
            self.gradient(&shift(b), sigma),
        );
        gp.iter()
            .zip(&gb)
            .map(|(p, q)| (p - q) / ((1.0 - b) * eps) * norm)
            .collect()
    }

    /// A deterministic direction for HVP tests, entries in (−2, 2).
    pub fn direction(&self, seed: u64) -> Vec<f64> {
        data(self.n, seed, 40, 2.0)
    }
}

/// exp(−σ²|a|²/2).
fn damping(a: &[f64], sigma: f64) -> f64 {
    (-0.5 * sigma * sigma * dot(a, a)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed forms against finite differences of the smoothed value for the step
    /// (f̄ = Φ(z)) and of the raw function for the quadratic.
    #[test]
    fn closed_forms_are_consistent() {
        let sigma = 0.5;
        let p = Problem::step(3, 1, 0.3);
        let (u, s) = match &p.kind {
            Kind::Step { u, s } => (u.clone(), *s),
            _ => unreachable!(),
        };
        let smoothed = |x: &[f64]| normal::cdf((dot(&u, x) - s) / sigma);
        let h = 1e-5;
        let g = p.gradient(p.theta(), sigma);
        for i in 0..3 {
            let mut a = p.theta().to_vec();
            let mut b = a.clone();
            a[i] += h;
            b[i] -= h;
            assert!(((smoothed(&a) - smoothed(&b)) / (2.0 * h) - g[i]).abs() < 1e-8);
        }
        let q = Problem::quadratic(3, 2);
        let g = q.gradient(q.theta(), sigma);
        for i in 0..3 {
            let mut a = q.theta().to_vec();
            let mut b = a.clone();
            a[i] += h;
            b[i] -= h;
            assert!(((q.value(&a) - q.value(&b)) / (2.0 * h) - g[i]).abs() < 1e-6);
        }
    }
}
