//! Rendered plateaus: the discs of [`plateau::discs`] rendered by Monte Carlo on the noise
//! seed the method passes — a stochastic renderer in miniature, on the plateau where
//! hodr's smoothing matters. Values on one seed compare closely; values on different
//! seeds differ by the render's noise, and below the pixels' scale the differences on one
//! seed are the samples' grain.
//!
//! Pixel p's coverage by θ's discs (a point counts when strictly inside a disc) is
//! estimated from points p + u in the pixel: the reference c_p(θ) from a stratified
//! [`REFERENCE`]×[`REFERENCE`] grid, u = ((i + ½)/G, (j + ½)/G); a render on seed s,
//! ĉ_p(θ; s), from [`SPP`] points u uniform in the pixel, drawn from (s, p, k) alone. The
//! target t_p is the reference coverage of the target discs, and
//!
//! f(θ) = (1/SIDE²)·Σ_p (c_p(θ) − t_p)²,
//!
//! the reference render's mean squared error, is what runs are judged on (f* = 0 at the
//! targets); a method sees the same sum over ĉ_p(θ; s). Names (`rendered-nNN-iI`),
//! instances, starts, bounds, σ₀, budgets and the parameter error are those of
//! [`plateau::discs`].

use super::plateau::{self, RADIUS, SIDE, inside, pixel_range};
use super::problem::{Family, Observation, Problem};
use super::random;

/// Samples per pixel of a render on a noise seed.
pub const SPP: usize = 4;

/// The reference render's stratified grid per pixel side (REFERENCE² points per pixel).
pub const REFERENCE: usize = 8;

/// The rendered disc problem with n/2 discs (n even, 2 ≤ n ≤ 16), instance `instance`.
///
/// # Panics
/// As [`plateau::discs`].
pub fn discs(n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    let plain = plateau::discs(n, instance, budget_per_dim);
    let target: Vec<f64> = (0..SIDE * SIDE)
        .map(|p| coverage(&plain.x_opt, p, REFERENCE * REFERENCE, reference_point))
        .collect();
    let scene = std::sync::Arc::new(Scene {
        base: target.iter().map(|t| t * t).sum(),
        target,
    });
    let reference = scene.clone();
    Problem {
        name: format!("rendered-n{n:02}-i{instance}"),
        family: Family::Rendered,
        f: Box::new(move |x| reference.loss(x, REFERENCE * REFERENCE, reference_point)),
        observation: Observation::Seeded(Box::new(move |x, seed| {
            scene.loss(x, SPP, |p, k| {
                let h = random::mix(seed ^ random::mix((p * SPP + k) as u64));
                let unit = |bits: u64| (bits as f64 + 0.5) / 4_294_967_296.0;
                (unit(h >> 32), unit(h & 0xFFFF_FFFF))
            })
        })),
        ..plain
    }
}

/// The target's coverage and Σ_p t_p², the loss of an empty image.
struct Scene {
    target: Vec<f64>,
    base: f64,
}

impl Scene {
    /// (1/SIDE²)·Σ_p (c_p − t_p)², c_p from `count` points per pixel ([`coverage`]): only
    /// pixels in the discs' bounding boxes can be covered, so the sum starts from the
    /// empty image's and corrects those pixels, each once — in the first disc's box that
    /// holds it. Allocates nothing.
    fn loss(
        &self,
        theta: &[f64],
        count: usize,
        sample: impl Fn(usize, usize) -> (f64, f64) + Copy,
    ) -> f64 {
        let bounding = |c: &[f64]| {
            let (x0, x1) = (pixel_range(c[0] - RADIUS), pixel_range(c[0] + RADIUS));
            let (y0, y1) = (pixel_range(c[1] - RADIUS), pixel_range(c[1] + RADIUS));
            (x0..=x1, y0..=y1)
        };
        let mut sum = self.base;
        for (k, c) in theta.chunks_exact(2).enumerate() {
            let (cols, rows) = bounding(c);
            for row in rows {
                for col in cols.clone() {
                    let counted = theta[..2 * k].chunks_exact(2).any(|e| {
                        let (cols, rows) = bounding(e);
                        cols.contains(&col) && rows.contains(&row)
                    });
                    if counted {
                        continue;
                    }
                    let p = row * SIDE + col;
                    let t = self.target[p];
                    let c = coverage(theta, p, count, sample);
                    sum += (c - t) * (c - t) - t * t;
                }
            }
        }
        sum / (SIDE * SIDE) as f64
    }
}

/// The k-th point of the reference grid in a pixel, as an offset in [0, 1)².
fn reference_point(_pixel: usize, k: usize) -> (f64, f64) {
    let g = REFERENCE as f64;
    (
        ((k % REFERENCE) as f64 + 0.5) / g,
        ((k / REFERENCE) as f64 + 0.5) / g,
    )
}

/// The fraction of pixel p's points p + `sample(p, k)`, k < `count`, that lie inside some
/// disc centred at `centres` (x₁, y₁, x₂, y₂, …).
fn coverage(
    centres: &[f64],
    p: usize,
    count: usize,
    sample: impl Fn(usize, usize) -> (f64, f64),
) -> f64 {
    let (col, row) = ((p % SIDE) as f64, (p / SIDE) as f64);
    let covered = (0..count)
        .filter(|&k| {
            let (u, v) = sample(p, k);
            centres
                .chunks_exact(2)
                .any(|c| inside(c[0], c[1], col + u, row + v))
        })
        .count();
    covered as f64 / count as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference is 0 at the targets and nearly flat while the discs are off them
    /// (only the edge pixels' partial coverage moves); a render repeats itself on one
    /// seed, differs between seeds, and its mean over seeds is the mean squared error of
    /// an image whose pixels are SPP-point estimates: Σ_p [(a_p − t_p)² + a_p(1 − a_p)/SPP]
    /// / SIDE², a_p the pixel's covered area (the reference's, here).
    #[test]
    fn renders_repeat_on_a_seed_and_average_to_the_estimate_s_error() {
        let p = discs(2, 1, 100);
        assert!(p.is_seeded());
        assert_eq!(p.value(&p.x_opt), 0.0);
        let start = p.start(7);
        let shifted = [start[0] + 0.37, start[1] - 0.61];
        let (f0, f1) = (p.value(&start), p.value(&shifted));
        assert!((f0 - f1).abs() < 0.01 * f0, "{f0} vs {f1}");
        let render = |x: &[f64], s: u64| p.observe_on(x, s, 0);
        assert_eq!(render(&start, 3), render(&start, 3));
        assert_ne!(render(&start, 3), render(&start, 4));
        let x = [p.x_opt[0] + 2.3, p.x_opt[1] - 1.1];
        let grid = REFERENCE * REFERENCE;
        let expected = (0..SIDE * SIDE)
            .map(|q| {
                let a = coverage(&x, q, grid, reference_point);
                let t = coverage(&p.x_opt, q, grid, reference_point);
                (a - t).powi(2) + a * (1.0 - a) / SPP as f64
            })
            .sum::<f64>()
            / (SIDE * SIDE) as f64;
        let seeds = 2000;
        let draws: Vec<f64> = (0..seeds).map(|s| render(&x, s)).collect();
        let mean = draws.iter().sum::<f64>() / seeds as f64;
        let var = draws.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (seeds - 1) as f64;
        let error = (var / seeds as f64).sqrt();
        assert!(
            (mean - expected).abs() < 5.0 * error,
            "mean {mean}, expected {expected}, standard error {error}"
        );
    }
}
