//! The 3D inverse-rendering tasks (docs/design.md §3): find the scene parameters θ whose
//! path-traced image matches a target rendered from the true parameters θ*.
//!
//! | name | n | what θ is |
//! |---|---|---|
//! | [`SHADOW`](Shadow) | 2 | (x, y) of a sphere behind the camera, seen only through its shadow |
//! | [`MUG`](Mug) | 1 | rotation of a mug about its vertical axis (units of 0.2 rad) |
//! | [`CBOX`](Cbox) | 2 | floor position of the small box in a Cornell box |
//! | [`TEXTURE`](TextureTask) | 1024 | the 32×32 grey texels of a lit plane |
//! | [`CAUSTIC`](Caustic) | 256 | 16×16 control heights of a glass slab whose caustic must match |
//!
//! Every task is fully defined in code (camera, lights, materials, depth, true
//! parameters, start distribution, the paper's hyper-parameters, its scale σ₀, bounds and
//! evaluation budgets; see each type's documentation) and exposes the same [`Task3d`]
//! interface: dimension, θ*, seeded starts, a [`ParametricScene`] that θ updates in
//! place, renders at any resolution, and an [`TaskObjective`] (image MSE against a cached
//! high-spp target) that implements `hodr_core::Objective<f64>`. Nothing elsewhere
//! chooses a setting by a task's name.
//!
//! ```
//! use hodr_host::tasks;
//! let shadow = tasks::by_name("shadow").unwrap();
//! assert_eq!(shadow.dimension(), 2);
//! let film = shadow.render(&shadow.true_params(), 8, 8, 2, 0)?;
//! assert_eq!(film.width(), 8);
//! # Ok::<(), hodr_host::render::RenderError>(())
//! ```

mod caustic;
mod cbox;
mod mug;
mod objective;
mod shadow;
mod texture;

pub use caustic::Caustic;
pub use cbox::Cbox;
pub use mug::Mug;
pub use objective::{TARGET_SEED, TaskObjective};
pub use shadow::Shadow;
pub use texture::TextureTask;

use hodr_core::optim::preset::Hyper;

use crate::render::sampler::mix64;
use crate::render::{Film, RenderError, Scene, render};

/// Resolutions and sample counts a task uses by default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaskSettings {
    /// Objective image (width, height): small, so that one evaluation is cheap.
    pub objective_resolution: (u32, u32),
    /// Samples per pixel of one objective evaluation.
    pub objective_spp: u32,
    /// Samples per pixel of the target image (rendered once per objective).
    pub target_spp: u32,
    /// Resolution of images for viewing and benchmarks (128×128 for every task).
    pub image_resolution: (u32, u32),
}

impl TaskSettings {
    /// What most tasks use: 64×64 objective images at 4 spp, a 256-spp target, 128×128
    /// viewing images.
    pub const STANDARD: TaskSettings = TaskSettings {
        objective_resolution: (64, 64),
        objective_spp: 4,
        target_spp: 256,
        image_resolution: (128, 128),
    };
}

/// A scene whose parameters θ can be set in place.
pub trait ParametricScene: Send + Sync {
    /// The scene, committed for the last θ set.
    fn scene(&self) -> &Scene;

    /// Updates the scene to θ and commits it. Allocation-free.
    ///
    /// # Errors
    /// [`RenderError::DimensionMismatch`], [`RenderError::NonFiniteParameter`], or a
    /// geometry error.
    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError>;
}

/// A 3D inverse-rendering task.
pub trait Task3d: Send + Sync {
    /// Upper-case name, e.g. `"SHADOW"`.
    fn name(&self) -> &'static str;

    /// One-line description (for task listings).
    fn description(&self) -> &'static str;

    /// Number of parameters n.
    fn dimension(&self) -> usize;

    /// The true parameters θ* the target is rendered from.
    fn true_params(&self) -> Vec<f64>;

    /// A start point drawn from the task's start distribution, fixed by `seed`.
    fn start(&self, seed: u64) -> Vec<f64>;

    /// Default resolutions and sample counts.
    fn settings(&self) -> TaskSettings;
    /// Box bounds (lower, upper) on θ where the task has a natural domain. Default: none.
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        None
    }

    /// The paper's hyper-parameters for this task (docs/design.md §3: pairs / σ start → end /
    /// trust radius / line-search steps / recompute; Adam's rate), the same for every
    /// preset.
    fn hyper(&self) -> Hyper<f64>;

    /// σ₀: the distance over which the parameters matter, the scale every method that
    /// takes only a problem statement starts from (Auto, CMA-ES). Default: the paper's
    /// σ start ([`Task3d::hyper`]).
    fn scale(&self) -> f64 {
        self.hyper().sigma_start
    }

    /// Objective evaluations per run of the report; `quick` at the quick report's
    /// objective settings (32×32, 2 spp), where the budgets keep the whole quick report
    /// near a minute.
    fn budget(&self, quick: bool) -> usize;

    /// A fresh scene set to θ*.
    ///
    /// # Errors
    /// Only if the task's own constants were invalid (a bug).
    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError>;

    /// Distance of θ from θ* (Euclidean, [`distance`], unless a task says otherwise).
    fn parameter_error(&self, theta: &[f64]) -> f64 {
        distance(theta, &self.true_params())
    }

    /// Renders θ at `width` × `height` with `spp` samples per pixel and frame seed `seed`
    /// (e.g. for `hodr render` and the report's image strips).
    ///
    /// # Errors
    /// Bad θ, zero spp or a zero resolution.
    fn render(
        &self,
        theta: &[f64],
        width: u32,
        height: u32,
        spp: u32,
        seed: u64,
    ) -> Result<Film, RenderError> {
        let mut scene = self.scene()?;
        scene.set_params(theta)?;
        let mut film = Film::new(width, height)?;
        render(scene.scene(), &mut film, spp, seed)?;
        Ok(film)
    }
}

/// The Euclidean distance ‖a − b‖ over the pairs of coordinates both have: every task's
/// parameter error unless the task defines its own.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Every task, in the order of docs/design.md §3.
pub fn all() -> Vec<Box<dyn Task3d>> {
    vec![
        Box::new(Shadow),
        Box::new(Mug),
        Box::new(Cbox),
        Box::new(TextureTask),
        Box::new(Caustic),
    ]
}

/// The task called `name` (case-insensitive), if any.
pub fn by_name(name: &str) -> Option<Box<dyn Task3d>> {
    all()
        .into_iter()
        .find(|t| t.name().eq_ignore_ascii_case(name))
}

/// Checks θ's length and finiteness.
///
/// # Errors
/// [`RenderError::DimensionMismatch`] or [`RenderError::NonFiniteParameter`].
pub fn check_params(theta: &[f64], n: usize) -> Result<(), RenderError> {
    if theta.len() != n {
        return Err(RenderError::DimensionMismatch {
            expected: n,
            found: theta.len(),
        });
    }
    match theta.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RenderError::NonFiniteParameter { index }),
        None => Ok(()),
    }
}

/// The k-th uniform number in [0, 1) of the start stream `seed` (a counter-based hash,
/// so starts do not depend on any RNG state).
pub fn start_uniform(seed: u64, k: u64) -> f64 {
    (mix64(mix64(seed ^ 0x5354_4152_5453) ^ k) >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_lists_every_task_once() {
        let names: Vec<_> = all().iter().map(|t| t.name()).collect();
        assert_eq!(names, ["SHADOW", "MUG", "CBOX", "TEXTURE", "CAUSTIC"]);
        assert_eq!(by_name("cBoX").unwrap().dimension(), 2);
        assert!(by_name("nope").is_none());
        for task in all() {
            assert_eq!(
                task.true_params().len(),
                task.dimension(),
                "{}",
                task.name()
            );
            assert_eq!(task.start(3).len(), task.dimension(), "{}", task.name());
            assert_eq!(task.start(3), task.start(3));
            assert_ne!(task.start(3), task.start(4));
            assert!(task.parameter_error(&task.true_params()) < 1e-12);
            assert!(!task.description().is_empty());
            assert_eq!(task.hyper().validate(), Ok(()), "{}", task.name());
            assert!(task.scale() > 0.0, "{}", task.name());
            assert!(0 < task.budget(true) && task.budget(true) < task.budget(false));
        }
    }

    #[test]
    fn bad_parameters_are_errors() {
        for task in all() {
            let mut scene = task.scene().unwrap();
            let mut theta = task.true_params();
            theta[0] = f64::NAN;
            assert!(matches!(
                scene.set_params(&theta),
                Err(RenderError::NonFiniteParameter { index: 0 })
            ));
            assert!(matches!(
                scene.set_params(&theta[1..]),
                Err(RenderError::DimensionMismatch { .. })
            ));
            assert!(matches!(
                task.render(&task.true_params(), 4, 4, 0, 0),
                Err(RenderError::ZeroSamples)
            ));
        }
    }
}
