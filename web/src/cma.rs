//! CMA-ES, (μ/μ_w, λ) with rank-one and rank-μ updates and cumulative step-size
//! adaptation (Hansen, *The CMA Evolution Strategy: A Tutorial*, 2016, Table 1 and its
//! default parameters), as an ask/tell step machine.
//!
//! Why not the `cmaes` crate the host uses: `CMAESOptions::build` calls
//! `std::time::Instant::now()`, which panics on wasm32-unknown-unknown, so the crate
//! cannot run in the page. This one has no clock and no threads; the covariance is
//! decomposed by cyclic Jacobi rotations, ample for the demo's n ≤ 18. Logarithms,
//! exponentials and powers come from `libm`, as in hodr-core, so the wasm build and the
//! native one compute the same numbers bit for bit (the platform's `f64::exp` need not
//! round like Rust's wasm fallback; square roots are exact everywhere).

use hodr_core::sample::normal;
use libm::{exp, log, pow};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::Rng;

/// Jacobi sweeps at most per decomposition (each sweep rotates every off-diagonal pair).
const JACOBI_SWEEPS: usize = 32;

/// A CMA-ES run: ask for a population, tell its values, repeat.
#[derive(Clone, Debug)]
pub struct CmaEs {
    n: usize,
    lambda: usize,
    weights: Vec<f64>,
    mu_eff: f64,
    c_sigma: f64,
    d_sigma: f64,
    c_c: f64,
    c_1: f64,
    c_mu: f64,
    chi_n: f64,
    mean: Vec<f64>,
    sigma: f64,
    /// Covariance, row-major n × n.
    cov: Vec<f64>,
    /// Eigenvectors of the covariance (columns), row-major.
    basis: Vec<f64>,
    /// Square roots of the covariance's eigenvalues.
    scales: Vec<f64>,
    p_sigma: Vec<f64>,
    p_c: Vec<f64>,
    generation: usize,
    /// The last population's steps y = B·D·z, rows of n.
    steps: Vec<f64>,
    /// The last population's points m + σy, rows of n.
    population: Vec<f64>,
}

impl CmaEs {
    /// A run from mean `x0` with step size `sigma0`, the default population
    /// λ = 4 + ⌊3 ln n⌋ and μ = ⌊λ/2⌋ log-weighted parents.
    pub fn new(x0: &[f64], sigma0: f64) -> Self {
        let n = x0.len();
        let nf = n as f64;
        let lambda = 4 + (3.0 * log(nf)).floor() as usize;
        let mu = lambda / 2;
        let raw: Vec<f64> = (1..=mu)
            .map(|i| log(mu as f64 + 0.5) - log(i as f64))
            .collect();
        let total: f64 = raw.iter().sum();
        let weights: Vec<f64> = raw.iter().map(|w| w / total).collect();
        let mu_eff = 1.0 / weights.iter().map(|w| w * w).sum::<f64>();
        let c_sigma = (mu_eff + 2.0) / (nf + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (nf + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let c_1 = 2.0 / ((nf + 1.3) * (nf + 1.3) + mu_eff);
        let c_mu = (1.0 - c_1)
            .min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0) * (nf + 2.0) + mu_eff));
        let chi_n = nf.sqrt() * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
        let mut identity = vec![0.0; n * n];
        for i in 0..n {
            identity[i * n + i] = 1.0;
        }
        CmaEs {
            n,
            lambda,
            weights,
            mu_eff,
            c_sigma,
            d_sigma,
            c_c,
            c_1,
            c_mu,
            chi_n,
            mean: x0.to_vec(),
            sigma: sigma0,
            cov: identity.clone(),
            basis: identity,
            scales: vec![1.0; n],
            p_sigma: vec![0.0; n],
            p_c: vec![0.0; n],
            generation: 0,
            steps: vec![0.0; lambda * n],
            population: vec![0.0; lambda * n],
        }
    }

    /// λ, the population size.
    pub fn lambda(&self) -> usize {
        self.lambda
    }

    /// The distribution's mean.
    pub fn mean(&self) -> &[f64] {
        &self.mean
    }

    /// The step size σ.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Draws the next population, λ rows of n (valid until the next call).
    pub fn ask(&mut self, rng: &mut Xoshiro256PlusPlus) -> &[f64] {
        let n = self.n;
        let mut z = vec![0.0; n];
        for k in 0..self.lambda {
            for v in &mut z {
                // A uniform in (0, 1) from the top 53 bits, then the normal quantile.
                let u = ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
                *v = normal::quantile(u);
            }
            for i in 0..n {
                let y: f64 = (0..n)
                    .map(|j| self.basis[i * n + j] * self.scales[j] * z[j])
                    .sum();
                self.steps[k * n + i] = y;
                self.population[k * n + i] = self.mean[i] + self.sigma * y;
            }
        }
        &self.population
    }

    /// Updates the distribution from the values of the population [`CmaEs::ask`] drew
    /// (ties ranked by index, so the update is deterministic).
    pub fn tell(&mut self, values: &[f64]) {
        let n = self.n;
        let mut order: Vec<usize> = (0..self.lambda).collect();
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
        let mut y_w = vec![0.0; n];
        for (w, &k) in self.weights.iter().zip(&order) {
            for (acc, y) in y_w.iter_mut().zip(&self.steps[k * n..(k + 1) * n]) {
                *acc += w * y;
            }
        }
        for (m, y) in self.mean.iter_mut().zip(&y_w) {
            *m += self.sigma * y;
        }
        // C^{-1/2}·y_w = B·D⁻¹·Bᵀ·y_w.
        let coords: Vec<f64> = (0..n)
            .map(|j| (0..n).map(|i| self.basis[i * n + j] * y_w[i]).sum::<f64>() / self.scales[j])
            .collect();
        let a_sigma = (self.c_sigma * (2.0 - self.c_sigma) * self.mu_eff).sqrt();
        for i in 0..n {
            let whitened: f64 = (0..n).map(|j| self.basis[i * n + j] * coords[j]).sum();
            self.p_sigma[i] = (1.0 - self.c_sigma) * self.p_sigma[i] + a_sigma * whitened;
        }
        self.generation += 1;
        let norm = self.p_sigma.iter().map(|v| v * v).sum::<f64>().sqrt();
        let decay = 1.0 - pow(1.0 - self.c_sigma, 2.0 * self.generation as f64);
        let h_sigma = norm / decay.sqrt() < (1.4 + 2.0 / (n as f64 + 1.0)) * self.chi_n;
        let a_c = (self.c_c * (2.0 - self.c_c) * self.mu_eff).sqrt();
        for (p, y) in self.p_c.iter_mut().zip(&y_w) {
            *p = (1.0 - self.c_c) * *p + if h_sigma { a_c * y } else { 0.0 };
        }
        let lost = if h_sigma {
            0.0
        } else {
            self.c_1 * self.c_c * (2.0 - self.c_c)
        };
        for i in 0..n {
            for j in 0..n {
                let rank_mu: f64 = self
                    .weights
                    .iter()
                    .zip(&order)
                    .map(|(w, &k)| w * self.steps[k * n + i] * self.steps[k * n + j])
                    .sum();
                let c = &mut self.cov[i * n + j];
                *c = (1.0 - self.c_1 - self.c_mu + lost) * *c
                    + self.c_1 * self.p_c[i] * self.p_c[j]
                    + self.c_mu * rank_mu;
            }
        }
        self.sigma *= exp((self.c_sigma / self.d_sigma) * (norm / self.chi_n - 1.0));
        self.decompose();
    }

    /// B and D from C by cyclic Jacobi rotations.
    fn decompose(&mut self) {
        let n = self.n;
        let mut a = self.cov.clone();
        let mut v = vec![0.0; n * n];
        for i in 0..n {
            v[i * n + i] = 1.0;
        }
        for _ in 0..JACOBI_SWEEPS {
            let off: f64 = (0..n)
                .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
                .map(|(i, j)| a[i * n + j] * a[i * n + j])
                .sum();
            let diagonal: f64 = (0..n).map(|i| a[i * n + i] * a[i * n + i]).sum();
            if off <= 1e-30 * diagonal {
                break;
            }
            for p in 0..n {
                for q in p + 1..n {
                    let apq = a[p * n + q];
                    if apq == 0.0 {
                        continue;
                    }
                    let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                    let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                    let c = 1.0 / (t * t + 1.0).sqrt();
                    let s = t * c;
                    for k in 0..n {
                        let (akp, akq) = (a[k * n + p], a[k * n + q]);
                        a[k * n + p] = c * akp - s * akq;
                        a[k * n + q] = s * akp + c * akq;
                    }
                    for k in 0..n {
                        let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                        a[p * n + k] = c * apk - s * aqk;
                        a[q * n + k] = s * apk + c * aqk;
                    }
                    for k in 0..n {
                        let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                        v[k * n + p] = c * vkp - s * vkq;
                        v[k * n + q] = s * vkp + c * vkq;
                    }
                }
            }
        }
        self.basis = v;
        for i in 0..n {
            self.scales[i] = a[i * n + i].max(1e-300).sqrt();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::rand_core::SeedableRng;

    /// On an ill-conditioned quadratic (condition 10⁴) the default CMA-ES reaches 1e-10
    /// within 600 generations: the covariance learnt the scaling.
    #[test]
    fn solves_an_ellipsoid() {
        let f = |x: &[f64]| {
            x.iter()
                .enumerate()
                .map(|(i, v)| pow(100.0, i as f64) * v * v)
                .sum::<f64>()
        };
        let mut cma = CmaEs::new(&[1.0, -1.0, 0.5], 0.5);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        for _ in 0..600 {
            let values: Vec<f64> = cma.ask(&mut rng).chunks_exact(3).map(f).collect();
            cma.tell(&values);
        }
        assert!(f(cma.mean()) < 1e-10, "f = {}", f(cma.mean()));
    }
}
