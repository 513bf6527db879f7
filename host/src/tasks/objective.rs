//! A task as an hodr-core objective: f(θ) = image MSE between a render of θ and the
//! target.
//!
//! f(θ) = (1/3P) Σ_pixels Σ_channels (I_θ − T)², P pixels, with I_θ rendered at the
//! objective resolution and spp using the evaluation's noise seed as frame seed (so
//! antithetic halves and common-random-number gradients share renderer noise), and T
//! rendered once, lazily on first use, from θ* with the target spp and a fixed seed
//! ([`TARGET_SEED`]). The scene, the film and the target are owned by the objective and
//! reused: an evaluation allocates nothing.

use hodr_core::{NoiseSeed, Objective};

use super::{ParametricScene, Task3d, TaskSettings};
use crate::render::{Film, RenderError, render};

/// Frame seed of every target render.
pub const TARGET_SEED: u64 = 0x007A_46E7;

/// Image MSE against a cached target; see the module documentation.
pub struct TaskObjective {
    scene: Box<dyn ParametricScene>,
    true_params: Vec<f64>,
    film: Film,
    target: Option<Film>,
    spp: u32,
    target_spp: u32,
    evaluations: u64,
}

impl TaskObjective {
    /// The objective of `task` at its default resolution and sample counts.
    ///
    /// # Errors
    /// As [`TaskObjective::with_settings`].
    pub fn new(task: &dyn Task3d) -> Result<TaskObjective, RenderError> {
        TaskObjective::with_settings(task, task.settings())
    }

    /// The objective of `task` with explicit settings (only the objective resolution and
    /// the two sample counts are used).
    ///
    /// # Errors
    /// [`RenderError::InvalidResolution`], [`RenderError::ZeroSamples`].
    pub fn with_settings(
        task: &dyn Task3d,
        settings: TaskSettings,
    ) -> Result<TaskObjective, RenderError> {
        if settings.objective_spp == 0 || settings.target_spp == 0 {
            return Err(RenderError::ZeroSamples);
        }
        let (w, h) = settings.objective_resolution;
        Ok(TaskObjective {
            scene: task.scene()?,
            true_params: task.true_params(),
            film: Film::new(w, h)?,
            target: None,
            spp: settings.objective_spp,
            target_spp: settings.target_spp,
            evaluations: 0,
        })
    }

    /// Uses `target` (rendered elsewhere at the objective resolution, e.g. shared by
    /// several objectives of one task) instead of rendering one.
    ///
    /// # Errors
    /// [`RenderError::DimensionMismatch`] when `target` is not of the objective's size.
    pub fn with_target(mut self, target: Film) -> Result<TaskObjective, RenderError> {
        if (target.width(), target.height()) != (self.film.width(), self.film.height()) {
            return Err(RenderError::DimensionMismatch {
                expected: self.film.data().len(),
                found: target.data().len(),
            });
        }
        self.target = Some(target);
        Ok(self)
    }

    /// The target image, rendering it on first use.
    ///
    /// # Errors
    /// Only if θ* is invalid for the task (a bug).
    pub fn target(&mut self) -> Result<&Film, RenderError> {
        if self.target.is_none() {
            self.scene.set_params(&self.true_params)?;
            let mut target = Film::new(self.film.width(), self.film.height())?;
            render(
                self.scene.scene(),
                &mut target,
                self.target_spp,
                TARGET_SEED,
            )?;
            self.target = Some(target);
        }
        Ok(self.target.as_ref().expect("target rendered above"))
    }

    /// f(θ) with renderer noise from `seed`.
    ///
    /// # Errors
    /// [`RenderError::DimensionMismatch`], [`RenderError::NonFiniteParameter`], geometry
    /// errors for θ.
    pub fn loss(&mut self, theta: &[f64], seed: NoiseSeed) -> Result<f64, RenderError> {
        self.target()?;
        self.scene.set_params(theta)?;
        render(self.scene.scene(), &mut self.film, self.spp, seed)?;
        self.evaluations += 1;
        let target = self.target.as_ref().expect("target rendered above");
        self.film.mse(target)
    }

    /// The image of the last evaluation.
    pub fn last_image(&self) -> &Film {
        &self.film
    }

    /// Evaluations so far (not counting the target).
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }
}

impl Objective<f64> for TaskObjective {
    /// f(θ); +∞ for a θ the task rejects (wrong length, NaN/∞ entries), which the
    /// estimators report as `hodr_core::Error::NonFiniteObjective`.
    fn evaluate(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        self.loss(theta, seed).unwrap_or(f64::INFINITY)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::Shadow;

    fn small() -> TaskSettings {
        TaskSettings {
            objective_resolution: (16, 16),
            objective_spp: 2,
            target_spp: 16,
            image_resolution: (16, 16),
        }
    }

    #[test]
    fn loss_is_small_at_the_truth_and_larger_elsewhere() {
        let mut f = TaskObjective::with_settings(&Shadow, small()).unwrap();
        let at_truth = f.evaluate(&[-0.55, -0.55], 1);
        let away = f.evaluate(&[0.55, 0.55], 1);
        assert!(at_truth < away, "{at_truth} vs {away}");
        assert_eq!(f.evaluate(&[f64::NAN, 0.0], 1), f64::INFINITY);
        assert_eq!(f.evaluate(&[0.0], 1), f64::INFINITY);
        // Same seed, same value: antithetic halves share noise.
        assert_eq!(f.evaluate(&[0.1, 0.2], 9), f.evaluate(&[0.1, 0.2], 9));
        assert_eq!(f.evaluations(), 4);
    }
}
