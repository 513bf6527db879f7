//! Image-to-shapes fitting: approximate a target with N shapes, one at a time.
//!
//! For each new shape:
//!
//! 1. **Where**: `candidates` random shapes are drawn with centres sampled in
//!    proportion to the current squared residual ‖C − T‖² per pixel and log-uniform
//!    sizes; all are evaluated in one parallel batch.
//! 2. **Refine**: the best `restarts` candidates are optimised with hodr-core's
//!    Newton optimiser on the smoothed loss (aggregate gradient + aggregate Hessian
//!    estimators, shifted Cholesky, trust radius Δ·σ, σ annealed linearly). The objective
//!    (`coverage`) gives each geometry its best colour in closed form, so θ is
//!    geometry only and the colour is exact for it.
//! 3. **Keep**: the lowest loss seen by any evaluation (candidates, estimator samples
//!    and iterates) is the new shape. It is composited onto the canvas with tiny-skia,
//!    and kept only if the rendered RMSE drops; otherwise up to [`MAX_ATTEMPTS`] fresh
//!    attempts are made, and the fit stops early if none helps.
//!
//! The result renders to PNG and writes SVG. Everything is a deterministic function of
//! the target and the options (parallel batches are split and reduced in index order).

mod coverage;
mod encode;
mod newton;

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng, SeedableRng};

use crate::color::Rgba;
use crate::error::Error;
use crate::scene::{Scene, new_pixmap};
use crate::shape::{PathScratch, Shape, ShapeKind};
use crate::target::Target;
use coverage::{Best, Scratch, ShapeObjective};

/// Fresh attempts at a shape whose best candidate did not lower the rendered RMSE.
pub const MAX_ATTEMPTS: usize = 3;

/// The most shapes a fit places.
pub const MAX_SHAPES: usize = 100_000;

/// What to fit and how hard to try. Construct with [`FitOptions::new`] and adjust
/// fields; [`fit`] checks them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// N, the number of shapes, 1..=[`MAX_SHAPES`].
    pub shapes: usize,
    /// Triangle, rect (axis-aligned), ellipse (rotated) or circle.
    pub kind: ShapeKind,
    /// Opacity of every shape, (0, 1]. Default: 0.5 (as `primitive`'s 128).
    pub alpha: f32,
    /// Seed of all random choices. Default: 0.
    pub seed: u64,
    /// Random candidates per shape, ≥ 1. Default: 256.
    pub candidates: usize,
    /// Best candidates refined per shape, 1..=candidates. Default: 2.
    pub restarts: usize,
    /// Newton iterations per refinement (0 = candidates only). Default: 64.
    pub iterations: usize,
    /// Antithetic pairs per estimate, ≥ 1. Default: 3.
    pub pairs: usize,
    /// σ at the first iteration, in units of an eighth of the longer image side.
    /// Default: 0.2.
    pub sigma_start: f64,
    /// σ at the last iteration, same units, (0, sigma_start]. Default: 0.02.
    pub sigma_end: f64,
    /// Trust radius in units of σ. Default: 2.
    pub trust: f64,
}

impl FitOptions {
    /// `shapes` shapes of `kind` with the defaults above.
    pub fn new(shapes: usize, kind: ShapeKind) -> Self {
        FitOptions {
            shapes,
            kind,
            alpha: 0.5,
            seed: 0,
            candidates: 256,
            restarts: 2,
            iterations: 64,
            pairs: 3,
            sigma_start: 0.2,
            sigma_end: 0.02,
            trust: 2.0,
        }
    }

    fn check(&self) -> Result<usize, Error> {
        let bad = |name, reason| Err(Error::InvalidOption { name, reason });
        if !(1..=MAX_SHAPES).contains(&self.shapes) {
            return bad("shapes", "between 1 and 100000");
        }
        if !(self.alpha > 0.0 && self.alpha <= 1.0) {
            return bad("alpha", "in (0, 1]");
        }
        if self.candidates == 0 || !(1..=self.candidates).contains(&self.restarts) {
            return bad("candidates/restarts", "1 ≤ restarts ≤ candidates");
        }
        if self.pairs == 0 {
            return bad("pairs", "at least 1");
        }
        if !(self.sigma_end > 0.0
            && self.sigma_end <= self.sigma_start
            && self.sigma_start.is_finite())
        {
            return bad("sigma", "0 < sigma_end ≤ sigma_start, finite");
        }
        if !(self.trust > 0.0 && self.trust.is_finite()) {
            return bad("trust", "finite and > 0");
        }
        encode::dim(self.kind)
    }
}

/// A finished fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    scene: Scene,
    rmse: Vec<f64>,
    evaluations: u64,
}

impl Fit {
    /// The fitted scene: the target's mean colour as background, then the shapes.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// RMSE (RGB in [0, 1]) of the rendered fit after 0, 1, …, N shapes; strictly
    /// decreasing. Shorter than N + 1 if the fit stopped early.
    pub fn rmse_history(&self) -> &[f64] {
        &self.rmse
    }

    /// RMSE of the final rendering.
    pub fn rmse(&self) -> f64 {
        self.rmse.last().copied().unwrap_or(f64::NAN)
    }

    /// Objective evaluations used.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Renders the fit and writes it as PNG.
    ///
    /// # Errors
    /// [`Error::Encode`].
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        self.scene.save_png(path)
    }

    /// Writes the fit as SVG.
    ///
    /// # Errors
    /// [`Error::Write`].
    pub fn save_svg(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        self.scene.save_svg(path)
    }
}

/// Fits `options.shapes` shapes to `target`.
///
/// # Errors
/// [`Error::InvalidOption`] for options out of range; estimator errors (not expected:
/// the objective is finite everywhere).
pub fn fit(target: &Target, options: &FitOptions) -> Result<Fit, Error> {
    fit_until(target, options, &AtomicBool::new(false))
}

/// [`fit`], stopping before the next shape once `stop` is set (e.g. by Ctrl-C): the
/// result then holds the shapes placed so far.
///
/// # Errors
/// As [`fit`].
pub fn fit_until(target: &Target, options: &FitOptions, stop: &AtomicBool) -> Result<Fit, Error> {
    fit_observed(target, options, stop, &mut |_, _| {})
}

/// [`fit_until`], calling `placed(k, rmse)` after the k-th shape is placed (for
/// progress reports).
///
/// # Errors
/// As [`fit`].
pub fn fit_observed(
    target: &Target,
    options: &FitOptions,
    stop: &AtomicBool,
    placed: &mut dyn FnMut(usize, f64),
) -> Result<Fit, Error> {
    fit_watched(target, options, stop, &mut |scene, rmse, _| {
        placed(scene.shapes().len(), rmse)
    })
}

/// [`fit_until`], calling `placed(scene, rmse, evaluations)` with the scene so far and
/// the objective evaluations used after each shape is placed (to draw the fit as it
/// grows, as the web demo does).
///
/// # Errors
/// As [`fit`].
pub fn fit_watched(
    target: &Target,
    options: &FitOptions,
    stop: &AtomicBool,
    placed: &mut dyn FnMut(&Scene, f64, u64),
) -> Result<Fit, Error> {
    let dim = options.check()?;
    let (width, height) = (target.width(), target.height());
    let unit = f64::from(width.max(height)) / 8.0;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(options.seed);
    let mut scene = Scene::new(width, height, mean_colour(target))?;
    let mut canvas = new_pixmap(width, height);
    scene.paint(&mut canvas, &mut PathScratch::default());
    let mut next = canvas.clone();
    let mut rmse = vec![Target::from_pixmap(&canvas).rmse(target)?];
    let mut scratch: Vec<Scratch> = (0..rayon::current_num_threads().max(1))
        .map(|_| Scratch::new(width, height))
        .collect();
    let mut evaluations = 0;
    let mut candidates = vec![0.0; options.candidates * dim];
    let mut values = vec![0.0; options.candidates];
    let mut residual = Vec::with_capacity(width as usize * height as usize);
    let schedule = newton::Schedule {
        iterations: options.iterations,
        pairs: options.pairs,
        sigma_start: options.sigma_start,
        sigma_end: options.sigma_end,
        trust: options.trust,
    };

    'shapes: while scene.shapes().len() < options.shapes && !stop.load(Ordering::Relaxed) {
        for _ in 0..MAX_ATTEMPTS {
            let base = residual_cdf(canvas.data(), target.rgb(), &mut residual);
            let mut objective = ShapeObjective {
                target,
                canvas: canvas.data(),
                kind: options.kind,
                unit,
                alpha: options.alpha,
                base,
                scratch: &mut scratch,
                best: Best {
                    value: f64::INFINITY,
                    theta: vec![0.0; dim],
                },
                evaluations: 0,
            };
            // 1. Random candidates where the residual is.
            let mut u = || unit_f64(&mut rng);
            let max_r = f64::from(width.max(height)) / 2.0;
            for theta in candidates.chunks_exact_mut(dim) {
                let at = u() * residual.last().copied().unwrap_or(0.0);
                let p = residual
                    .partition_point(|&c| c <= at)
                    .min(residual.len() - 1);
                let (px, py) = (p % width as usize, p / width as usize);
                let centre = (px as f64 + u(), py as f64 + u());
                let r = (2.0f64.ln() + u() * (max_r / 2.0).ln()).exp();
                encode::random(options.kind, unit, centre, r, &mut u, theta);
            }
            let seeds = vec![0; options.candidates];
            let batch = hodr_core::Batch::new(&candidates, &seeds, dim)?;
            hodr_core::Objective::evaluate_batch(&mut objective, &batch, &mut values);

            // 2. Refine the best few.
            let mut order: Vec<usize> = (0..options.candidates).collect();
            order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
            for &c in order.iter().take(options.restarts) {
                let mut theta = candidates[c * dim..(c + 1) * dim].to_vec();
                let seed = rng.next_u64();
                newton::optimise(&mut objective, &mut theta, &schedule, seed)?;
                hodr_core::Objective::<f64>::evaluate(&mut objective, &theta, 0);
            }

            // 3. Keep the best point seen if the rendering improves.
            evaluations += objective.evaluations;
            let best = objective.best.theta.clone();
            let (_, fill) = objective.evaluate_at(|k| best[k]);
            let shape = Shape::new(encode::geometry(options.kind, unit, |k| best[k]), fill);
            next.data_mut().copy_from_slice(canvas.data());
            shape.draw(&mut next.as_mut(), &mut PathScratch::default());
            let error = Target::from_pixmap(&next).rmse(target)?;
            if error < rmse[rmse.len() - 1] && shape.validate(scene.shapes().len()).is_ok() {
                scene.push(shape)?;
                std::mem::swap(&mut canvas, &mut next);
                rmse.push(error);
                placed(&scene, error, evaluations);
                continue 'shapes;
            }
        }
        break;
    }
    Ok(Fit {
        scene,
        rmse,
        evaluations,
    })
}

/// Loads `target_path`, fits, writes the PNG (and the SVG if asked): what `hodr fit2d`
/// does.
///
/// # Errors
/// [`Error::ImageRead`], the errors of [`fit`], [`Error::Encode`], [`Error::Write`].
pub fn fit_file(
    target_path: impl AsRef<Path>,
    options: &FitOptions,
    png: impl AsRef<Path>,
    svg: Option<&Path>,
) -> Result<Fit, Error> {
    let target = Target::open(target_path)?;
    let result = fit(&target, options)?;
    result.save_png(png)?;
    if let Some(svg) = svg {
        result.save_svg(svg)?;
    }
    Ok(result)
}

/// The mean colour of the target.
fn mean_colour(target: &Target) -> Rgba {
    let mut sum = [0u64; 3];
    for p in target.rgb().chunks_exact(3) {
        for (s, &v) in sum.iter_mut().zip(p) {
            *s += u64::from(v);
        }
    }
    let n = (target.rgb().len() / 3).max(1) as f64;
    let c = sum.map(|s| (s as f64 / n / 255.0) as f32);
    Rgba::rgb(c[0], c[1], c[2])
}

/// Fills `cdf` with the cumulative squared residual per pixel (8-bit units) and returns
/// the total.
fn residual_cdf(canvas: &[u8], target: &[u8], cdf: &mut Vec<f64>) -> f64 {
    cdf.clear();
    let mut sum = 0.0;
    for (c, t) in canvas.chunks_exact(4).zip(target.chunks_exact(3)) {
        let e: i32 = (0..3)
            .map(|k| (i32::from(c[k]) - i32::from(t[k])).pow(2))
            .sum();
        sum += f64::from(e);
        cdf.push(sum);
    }
    sum
}

/// A uniform number in [0, 1).
fn unit_f64(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}
