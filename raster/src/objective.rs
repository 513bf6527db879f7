//! A (scene, parameter map, target) triple as a hodr-core [`Objective`].

use hodr_core::{Batch, NoiseSeed, Objective, Real};
use rayon::prelude::*;
use tiny_skia::Pixmap;

use crate::cache::{Cache, Renderer};
use crate::error::Error;
use crate::loss::Loss;
use crate::params::{ParamMap, check_theta};
use crate::scene::Scene;
use crate::target::Target;

/// Whether evaluations re-render only the region θ can change.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Caching {
    /// Cached static layer and dirty-region re-render and re-score (see the `cache`
    /// module docs). Default. Gives bit-identical losses to [`Caching::Off`].
    #[default]
    On,
    /// Render every shape and score every pixel on each evaluation (the baseline).
    Off,
}

/// What to render, what θ moves, and what to match.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    scene: Scene,
    map: ParamMap,
    target: Target,
    loss: Loss,
    caching: Caching,
}

impl Problem {
    /// A problem with the MSE loss and caching on. θ's attributes are set on top of
    /// `scene`'s shapes; attributes θ does not drive keep the scene's values.
    ///
    /// # Errors
    /// [`Error::TargetSize`] if the target's size is not the scene's; the errors of
    /// [`ParamMap::new`] if `map` does not fit `scene`.
    pub fn new(scene: Scene, map: ParamMap, target: Target) -> Result<Self, Error> {
        if (target.width(), target.height()) != (scene.width(), scene.height()) {
            return Err(Error::TargetSize {
                width: scene.width(),
                height: scene.height(),
                found_width: target.width(),
                found_height: target.height(),
            });
        }
        let map = ParamMap::new(map.bindings().to_vec(), &scene)?;
        Ok(Problem {
            scene,
            map,
            target,
            loss: Loss::Mse,
            caching: Caching::On,
        })
    }

    /// The same problem with `loss`. Default: [`Loss::Mse`].
    pub fn with_loss(mut self, loss: Loss) -> Self {
        self.loss = loss;
        self
    }

    /// The same problem with `caching`. Default: [`Caching::On`].
    pub fn with_caching(mut self, caching: Caching) -> Self {
        self.caching = caching;
        self
    }

    /// The scene (θ's attributes as given: the values at θ = [`ParamMap::read`]).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The parameter map.
    pub fn map(&self) -> &ParamMap {
        &self.map
    }

    /// The target image.
    pub fn target(&self) -> &Target {
        &self.target
    }

    /// The loss.
    pub fn loss(&self) -> Loss {
        self.loss
    }

    /// The caching mode.
    pub fn caching(&self) -> Caching {
        self.caching
    }
}

/// The loss of a [`Problem`] as a function of θ, with one reusable renderer per thread.
///
/// [`Objective::evaluate_batch`] splits a batch into contiguous chunks, one per
/// renderer, on rayon's pool, when the batch holds at least 100 µs (`PARALLEL_WORK`) of
/// work at the evaluation cost measured on earlier batches; smaller batches (and the
/// first one) run on the calling thread, since waking the pool costs more than a few
/// small renders. Every evaluation is a pure function of θ (the seed is ignored:
/// rendering is deterministic), so results do not depend on the thread count, the
/// split or scheduling. A non-finite θ or wrong dimension evaluates to NaN through the trait
/// (the estimators then report it); [`RasterObjective::loss`] returns the typed error.
#[derive(Debug)]
pub struct RasterObjective {
    problem: Problem,
    cache: Cache,
    renderers: Vec<Renderer>,
    normaliser: f64,
    evaluations: u64,
    /// Running mean wall time of one evaluation, seconds (`None` before the first batch).
    cost: Option<f64>,
}

/// Sequential work, in seconds, above which a batch is split across rayon's pool.
const PARALLEL_WORK: f64 = 100e-6;

impl RasterObjective {
    /// Builds the caches and one renderer per thread of rayon's current pool.
    ///
    /// # Errors
    /// None today; `Result` leaves room for cache limits.
    pub fn new(problem: Problem) -> Result<Self, Error> {
        Self::with_threads(problem, rayon::current_num_threads())
    }

    /// As [`RasterObjective::new`] with `threads` renderers (batches are split into at
    /// most that many chunks).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] if `threads` is 0 or above 1024.
    pub fn with_threads(problem: Problem, threads: usize) -> Result<Self, Error> {
        if !(1..=1024).contains(&threads) {
            return Err(Error::InvalidOption {
                name: "threads",
                reason: "between 1 and 1024",
            });
        }
        let cache = Cache::new(&problem);
        let renderers = (0..threads)
            .map(|_| Renderer::new(&problem, &cache))
            .collect();
        let scene = problem.scene();
        let normaliser = problem
            .loss()
            .normaliser(u64::from(scene.width()) * u64::from(scene.height()));
        Ok(RasterObjective {
            problem,
            cache,
            renderers,
            normaliser,
            evaluations: 0,
            cost: None,
        })
    }

    /// The problem.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// n, the dimension of θ.
    pub fn dim(&self) -> usize {
        self.problem.map().dim()
    }

    /// Evaluations so far (through every entry point).
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// The loss at θ.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] or [`Error::NonFiniteParameter`].
    pub fn loss(&mut self, theta: &[f64]) -> Result<f64, Error> {
        check_theta(self.dim(), theta.iter().copied())?;
        self.evaluations += 1;
        let sum = self.renderers[0].error_sum(&self.problem, &self.cache, |k| theta[k]);
        Ok(sum as f64 / self.normaliser)
    }

    /// The scene at θ.
    ///
    /// # Errors
    /// As [`ParamMap::apply_to`].
    pub fn scene_at(&self, theta: &[f64]) -> Result<Scene, Error> {
        self.problem.map().apply_to(self.problem.scene(), theta)
    }

    /// A full render of the scene at θ into a new pixmap (for output, not for loops).
    ///
    /// # Errors
    /// As [`RasterObjective::scene_at`].
    pub fn render(&self, theta: &[f64]) -> Result<Pixmap, Error> {
        Ok(self.scene_at(theta)?.render())
    }

    fn value<T: Real>(&self, renderer: &mut Renderer, theta: &[T]) -> T {
        if check_theta(self.dim(), theta.iter().map(|t| t.to_f64())).is_err() {
            return T::from_f64(f64::NAN);
        }
        let sum = renderer.error_sum(&self.problem, &self.cache, |k| theta[k].to_f64());
        T::from_f64(sum as f64 / self.normaliser)
    }
}

impl<T: Real> Objective<T> for RasterObjective {
    fn evaluate(&mut self, theta: &[T], _seed: NoiseSeed) -> T {
        self.evaluations += 1;
        let mut renderer = std::mem::take(&mut self.renderers);
        let value = self.value(&mut renderer[0], theta);
        self.renderers = renderer;
        value
    }

    /// tiny-skia rasterises without randomness: the seed is ignored.
    fn deterministic(&self) -> bool {
        true
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, T>, out: &mut [T]) {
        self.evaluations += out.len() as u64;
        let mut renderers = std::mem::take(&mut self.renderers);
        let this = &*self;
        let chunk = out.len().div_ceil(renderers.len()).max(1);
        let parallel = renderers.len() > 1
            && out.len() >= 2
            && self
                .cost
                .is_some_and(|c| c * out.len() as f64 >= PARALLEL_WORK);
        let clock = Clock::start();
        if parallel {
            out.par_chunks_mut(chunk)
                .zip(renderers.par_iter_mut())
                .enumerate()
                .for_each(|(c, (values, renderer))| {
                    for (j, v) in values.iter_mut().enumerate() {
                        *v = this.value(renderer, batch.point(c * chunk + j));
                    }
                });
        } else {
            for (k, v) in out.iter_mut().enumerate() {
                *v = this.value(&mut renderers[0], batch.point(k));
            }
        }
        // Per-evaluation cost: each of the chunks ran one after another on its thread.
        let sequential = if parallel { chunk } else { out.len() };
        if let Some(elapsed) = clock.seconds() {
            let measured = elapsed / sequential.max(1) as f64;
            self.cost = Some(self.cost.map_or(measured, |c| 0.5 * (c + measured)));
        }
        self.renderers = renderers;
    }
}

/// The wall clock behind [`RasterObjective`]'s cost estimate. On wasm32-unknown-unknown
/// `Instant::now` panics and rayon runs on the calling thread alone (one renderer, so
/// batches never split): there the clock reads nothing and the cost stays unknown.
struct Clock(#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))] std::time::Instant);

impl Clock {
    fn start() -> Self {
        Clock(
            #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
            std::time::Instant::now(),
        )
    }

    /// Seconds since [`Clock::start`], where the platform has a clock.
    #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
    fn seconds(&self) -> Option<f64> {
        Some(self.0.elapsed().as_secs_f64())
    }

    #[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
    fn seconds(&self) -> Option<f64> {
        None
    }
}
