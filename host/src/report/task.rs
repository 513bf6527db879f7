//! The tasks of the report behind one interface: analytic (QUAD, BOX2-REF), 2D raster
//! (hodr-raster) and, as they land, 3D path-traced ones.

use anyhow::{Context, Result};
use hodr_core::optim::preset::{Hyper, Preset};
use hodr_core::{Objective, Real};
use image::{GrayImage, RgbImage};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use crate::box2ref::{self, Box2Ref};

/// Noise seed of the image-error probe: every probe sees the same renderer noise.
pub const PROBE_SEED: u64 = 0x1A6E_E550_4BE5;

/// A task the report can run.
pub trait Task: Send + Sync {
    /// Name as on the command line, e.g. "BOX2-REF".
    fn name(&self) -> &str;
    /// One line for `hodr tasks`.
    fn description(&self) -> String;
    /// Number of parameters n.
    fn dim(&self) -> usize;
    /// θ*.
    fn optimum(&self) -> Vec<f64>;
    /// The parameter error of θ, the distance the report's reductions are measured in.
    /// Default: ‖θ − θ*‖; a task whose θ* is one of several equivalent points (MUG's
    /// periodic angle, SHAPES's orderings of its circles) measures to the nearest.
    fn param_error(&self, theta: &[f64]) -> f64 {
        crate::tasks::distance(theta, &self.optimum())
    }
    /// A start from the task's start distribution, fixed by `seed`.
    fn start(&self, seed: u64) -> Vec<f64>;
    /// Per-task hyper-parameters of `preset` (docs/design.md §3; data, overridable).
    fn hyper(&self, preset: Preset) -> Hyper<f64>;
    /// The hyper-parameters `preset` runs with: the paper's settings for this task
    /// ([`Task::hyper`]) for the paper's presets and NCG-kernel; for a Newton-CG
    /// [`Recipe`](hodr_core::optim::recipe::Recipe), which the paper does not tune,
    /// only what the task states ([`recipe_hyper`] of [`Task::scale`]).
    fn run_hyper(&self, preset: Preset) -> Hyper<f64> {
        match preset {
            Preset::NewtonCg(_) => recipe_hyper(self.scale(), self.dim()),
            _ => self.hyper(preset),
        }
    }
    /// σ₀: the distance over which the parameters matter, the scale every method that
    /// takes only a problem statement starts from (Auto, CMA-ES). Default: the paper's
    /// σ_start for the task (docs/design.md §3).
    fn scale(&self) -> f64 {
        self.hyper(Preset::OurHvpa).sigma_start
    }
    /// Box bounds (lower, upper) on θ, if the task has any. Default: none.
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        None
    }
    /// Objective evaluations per run (`quick`: the smaller budget of `--quick`).
    fn budget(&self, quick: bool) -> usize;
    /// A fresh objective (the loss being optimised).
    ///
    /// # Errors
    /// When the task's own setup fails (e.g. a target image cannot be built).
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>>;
    /// The image error at θ: the loss at a fixed noise seed ([`PROBE_SEED`]).
    fn image_error(&self, objective: &mut dyn Objective<f64>, theta: &[f64]) -> f64 {
        objective.evaluate(theta, PROBE_SEED)
    }
    /// A picture of θ for the init / result / target strips, if the task has one.
    ///
    /// # Errors
    /// When rendering fails.
    fn image(&self, theta: &[f64]) -> Result<Option<RgbImage>>;
    /// Samples per pixel of [`Task::image`] where the task is path-traced; `None` for
    /// the others, whose images have no sampling noise.
    fn image_spp(&self) -> Option<u32> {
        None
    }
    /// [`Task::image`] with `spp` samples per pixel (path-traced tasks; the others
    /// ignore it, see [`Task::image_spp`]).
    ///
    /// # Errors
    /// When rendering fails.
    fn image_with_spp(&self, theta: &[f64], spp: u32) -> Result<Option<RgbImage>> {
        let _ = spp;
        self.image(theta)
    }
}

/// What a Newton-CG [`Recipe`](hodr_core::optim::recipe::Recipe) runs with on a task
/// of n parameters and scale σ₀: [`Hyper::default`] with σ from σ₀ down to
/// σ₀·[`RECIPE_SIGMA_END`], and one antithetic pair per estimate where n ≤ 2 (an
/// iteration reuses its samples for every estimate, so in one or two dimensions cheap
/// iterations win).
pub fn recipe_hyper(scale: f64, n: usize) -> Hyper<f64> {
    Hyper {
        sigma_start: scale,
        sigma_end: scale * RECIPE_SIGMA_END,
        pairs: if n <= 2 {
            1
        } else {
            Hyper::<f64>::default().pairs
        },
        ..Hyper::default()
    }
}

/// σ_end / σ₀ of [`recipe_hyper`]: [`Hyper::default`]'s ratio.
pub const RECIPE_SIGMA_END: f64 = 0.01;

/// The paper's QUAD hyper-parameters (docs/design.md §3): 4 pairs, σ 1 → 0.05, Δ = 50,
/// 5 line-search steps, recompute 5; Adam η = 0.5; independent HVP draws.
pub fn quad_hyper() -> Hyper<f64> {
    Hyper {
        pairs: 4,
        sigma_start: 1.0,
        sigma_end: 0.05,
        trust_radius: 50.0,
        line_search_iterations: 5,
        recompute: 5,
        learning_rate: 0.5,
        ..Hyper::default()
    }
}

/// The paper's BOX2 hyper-parameters for BOX2-REF (docs/design.md §3): 6 pairs, σ 100 → 0.01 px
/// (FR22: → 0.1), Δ = 2, 2 line-search steps, tolerance 1e-3, recompute 10; Adam
/// η = 0.5 (FR22: 0.3).
pub fn box2ref_hyper(preset: Preset) -> Hyper<f64> {
    let fr22 = preset == Preset::Fr22;
    Hyper {
        pairs: 6,
        sigma_start: 100.0,
        sigma_end: if fr22 { 0.1 } else { 0.01 },
        trust_radius: 2.0,
        line_search_iterations: 2,
        line_search_tolerance: 1e-3,
        recompute: 10,
        learning_rate: if fr22 { 0.3 } else { 0.5 },
        ..Hyper::default()
    }
}

/// QUAD, f = 5x₀² + 5x₁² + 7.5x₀x₁, with either start distribution.
pub struct Quad {
    far: bool,
}

impl Quad {
    /// Starts uniform in [−3, 3]² (`far = false`) or the paper's [800, 1000]².
    pub fn new(far: bool) -> Self {
        Quad { far }
    }
}

fn uniform(seed: u64, salt: u64) -> impl FnMut() -> f64 {
    let mut rng =
        Xoshiro256PlusPlus::seed_from_u64(seed.wrapping_mul(0x9E37_79B9).wrapping_add(salt));
    move || f64::uniform_open(&mut rng)
}

/// The QUAD objective.
pub fn quad(x: &[f64]) -> f64 {
    5.0 * x[0] * x[0] + 5.0 * x[1] * x[1] + 7.5 * x[0] * x[1]
}

impl Task for Quad {
    fn name(&self) -> &str {
        if self.far { "QUAD-far" } else { "QUAD" }
    }
    fn description(&self) -> String {
        let range = if self.far {
            "[800, 1000]²"
        } else {
            "[−3, 3]²"
        };
        format!("5x₀² + 5x₁² + 7.5x₀x₁, starts uniform in {range}")
    }
    fn dim(&self) -> usize {
        2
    }
    fn optimum(&self) -> Vec<f64> {
        vec![0.0, 0.0]
    }
    fn start(&self, seed: u64) -> Vec<f64> {
        let mut u = uniform(seed, 1);
        if self.far {
            vec![800.0 + 200.0 * u(), 800.0 + 200.0 * u()]
        } else {
            vec![6.0 * u() - 3.0, 6.0 * u() - 3.0]
        }
    }
    fn hyper(&self, _preset: Preset) -> Hyper<f64> {
        quad_hyper()
    }
    fn budget(&self, quick: bool) -> usize {
        match (self.far, quick) {
            (false, true) => 1500,
            (false, false) => 3000,
            (true, true) => 3000,
            (true, false) => 6000,
        }
    }
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>> {
        Ok(Box::new(quad as fn(&[f64]) -> f64))
    }
    fn image(&self, _theta: &[f64]) -> Result<Option<RgbImage>> {
        Ok(None)
    }
}

/// The paper's BOX2 renderer ([`crate::box2ref`]).
pub struct Box2RefTask;

impl Task for Box2RefTask {
    fn name(&self) -> &str {
        "BOX2-REF"
    }
    fn description(&self) -> String {
        "the paper's BOX2: a 500×500 superellipse square to (150, 150), starts in [210, 360)²"
            .into()
    }
    fn dim(&self) -> usize {
        2
    }
    fn optimum(&self) -> Vec<f64> {
        box2ref::TARGET.to_vec()
    }
    fn start(&self, seed: u64) -> Vec<f64> {
        let mut u = uniform(seed, 2);
        vec![210.0 + 150.0 * u(), 210.0 + 150.0 * u()]
    }
    fn hyper(&self, preset: Preset) -> Hyper<f64> {
        box2ref_hyper(preset)
    }
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        let [lo, hi] = box2ref::BOUNDS;
        Some((vec![lo; 2], vec![hi; 2]))
    }
    fn budget(&self, quick: bool) -> usize {
        if quick { 1500 } else { 4000 }
    }
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>> {
        Ok(Box::new(Box2Ref::new()))
    }
    fn image(&self, theta: &[f64]) -> Result<Option<RgbImage>> {
        let img = Box2Ref::new().render(theta);
        let side = box2ref::SIZE as u32;
        let gray = GrayImage::from_fn(side, side, |x, y| {
            image::Luma([(img[(y * side + x) as usize].clamp(0.0, 1.0) * 255.0).round() as u8])
        });
        Ok(Some(image::DynamicImage::ImageLuma8(gray).to_rgb8()))
    }
}

/// A hodr-raster task (TRI1D, BOX2, BOX10, SHAPES) at 64×64.
pub struct RasterTask {
    task: hodr_raster::tasks::Task,
    name: String,
}

impl RasterTask {
    /// The raster task called `name`.
    ///
    /// # Errors
    /// Unknown name.
    pub fn new(name: &str) -> Result<Self> {
        let task =
            hodr_raster::tasks::by_name(name).with_context(|| format!("raster task {name}"))?;
        Ok(RasterTask {
            name: task.name().to_ascii_uppercase(),
            task,
        })
    }
}

impl Task for RasterTask {
    fn name(&self) -> &str {
        &self.name
    }
    fn description(&self) -> String {
        let s = self.task.size();
        format!(
            "2D raster ({s}×{s}, tiny-skia): {} parameter{}, image MSE, plateau starts",
            self.task.dim(),
            if self.task.dim() == 1 { "" } else { "s" }
        )
    }
    fn dim(&self) -> usize {
        self.task.dim()
    }
    fn optimum(&self) -> Vec<f64> {
        self.task.theta_true().to_vec()
    }
    fn param_error(&self, theta: &[f64]) -> f64 {
        self.task.parameter_distance(theta)
    }
    fn start(&self, seed: u64) -> Vec<f64> {
        self.task.start(seed)
    }
    fn hyper(&self, preset: Preset) -> Hyper<f64> {
        let mut h = self.task.settings().hyper();
        if preset.is_first_order() {
            // Adam's step is η per iteration; the paper's first-order rates are in the
            // same σ units as its second-order trust radii.
            h.learning_rate = h.learning_rate.max(0.05);
        }
        h
    }
    /// Where each binding's clamp, or a colour's [0, 1], ends (the parameter map's
    /// bounds): beyond them θ changes nothing.
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        Some(self.task.map().bounds())
    }
    fn budget(&self, quick: bool) -> usize {
        let base = 600 * self.task.dim().max(2);
        if quick { base / 2 } else { base * 2 }
    }
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>> {
        Ok(Box::new(self.task.objective()?))
    }
    fn image(&self, theta: &[f64]) -> Result<Option<RgbImage>> {
        let objective = self.task.objective()?;
        let pixmap = objective.render(theta)?;
        let target = hodr_raster::Target::from_pixmap(&pixmap);
        Ok(RgbImage::from_raw(
            target.width(),
            target.height(),
            target.rgb().to_vec(),
        ))
    }
}

/// A path-traced task (SHADOW, MUG, CBOX, TEXTURE, CAUSTIC).
///
/// The full report uses each task's own objective settings; `--quick` renders the
/// objective at 32×32 with 2 spp (target 64 spp) so that a run takes a fraction of a
/// second. The target is rendered once per task and shared by every run's objectives.
pub struct PathTask {
    task: Box<dyn crate::tasks::Task3d>,
    quick: bool,
    target: std::sync::OnceLock<crate::render::Film>,
}

impl PathTask {
    /// Wraps `task`; `quick` selects the small objective settings.
    pub fn new(task: Box<dyn crate::tasks::Task3d>, quick: bool) -> Self {
        PathTask {
            task,
            quick,
            target: std::sync::OnceLock::new(),
        }
    }

    fn settings(&self) -> crate::tasks::TaskSettings {
        let mut s = self.task.settings();
        if self.quick {
            s.objective_resolution = (32, 32);
            s.objective_spp = 2;
            s.target_spp = 64;
        }
        s
    }
}

impl Task for PathTask {
    fn name(&self) -> &str {
        self.task.name()
    }
    fn description(&self) -> String {
        let s = self.settings();
        format!(
            "3D path tracer: {} ({}×{}, {} spp per evaluation)",
            self.task.description(),
            s.objective_resolution.0,
            s.objective_resolution.1,
            s.objective_spp
        )
    }
    fn dim(&self) -> usize {
        self.task.dimension()
    }
    fn optimum(&self) -> Vec<f64> {
        self.task.true_params()
    }
    fn param_error(&self, theta: &[f64]) -> f64 {
        self.task.parameter_error(theta)
    }
    fn start(&self, seed: u64) -> Vec<f64> {
        self.task.start(seed)
    }
    /// The task's own ([`crate::tasks::Task3d::hyper`]), the same for every preset.
    fn hyper(&self, _preset: Preset) -> Hyper<f64> {
        self.task.hyper()
    }
    fn scale(&self) -> f64 {
        self.task.scale()
    }
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        self.task.bounds()
    }
    fn budget(&self, quick: bool) -> usize {
        self.task.budget(quick)
    }
    fn objective(&self) -> Result<Box<dyn Objective<f64> + Send>> {
        let settings = self.settings();
        let mut objective =
            crate::tasks::TaskObjective::with_settings(self.task.as_ref(), settings)?;
        let target = match self.target.get() {
            Some(t) => t.clone(),
            None => {
                let t = objective.target()?.clone();
                let _ = self.target.set(t.clone());
                t
            }
        };
        Ok(Box::new(objective.with_target(target)?))
    }
    fn image(&self, theta: &[f64]) -> Result<Option<RgbImage>> {
        self.image_with_spp(theta, PATH_IMAGE_SPP[usize::from(self.quick)])
    }
    fn image_spp(&self) -> Option<u32> {
        Some(PATH_IMAGE_SPP[usize::from(self.quick)])
    }
    /// The task's viewing resolution (`TaskSettings::image_resolution`), not the
    /// objective's.
    fn image_with_spp(&self, theta: &[f64], spp: u32) -> Result<Option<RgbImage>> {
        let (w, h) = self.task.settings().image_resolution;
        let film = self
            .task
            .render(theta, w, h, spp, crate::tasks::TARGET_SEED)?;
        Ok(RgbImage::from_raw(w, h, film.to_srgb8()))
    }
}

/// Samples per pixel of a path-traced task's viewing image: [full, quick].
const PATH_IMAGE_SPP: [u32; 2] = [64, 16];

/// The image of θ*, for the strip's target panel.
pub fn target_image(task: &dyn Task) -> Result<Option<RgbImage>> {
    task.image(&task.optimum())
}

/// Every built-in task, in report order (`quick`: the path-traced tasks at their small
/// objective settings).
///
/// # Errors
/// When a task cannot be constructed (a bug in its constants).
pub fn all(quick: bool) -> Result<Vec<Box<dyn Task>>> {
    let mut tasks: Vec<Box<dyn Task>> = vec![
        Box::new(Quad::new(false)),
        Box::new(Quad::new(true)),
        Box::new(Box2RefTask),
    ];
    for name in hodr_raster::tasks::NAMES {
        tasks.push(Box::new(RasterTask::new(name)?));
    }
    for task in crate::tasks::all() {
        tasks.push(Box::new(PathTask::new(task, quick)));
    }
    Ok(tasks)
}

/// The tasks named in `names` (case-insensitive), or an error naming the unknown one.
///
/// # Errors
/// An unknown task name.
pub fn select(names: &[String], quick: bool) -> Result<Vec<Box<dyn Task>>> {
    let mut all = all(quick)?;
    if names.is_empty() {
        return Ok(all);
    }
    let mut chosen: Vec<Box<dyn Task>> = Vec::new();
    for name in names {
        if chosen.iter().any(|t| t.name().eq_ignore_ascii_case(name)) {
            anyhow::bail!("task `{name}` listed twice");
        }
        let k = all
            .iter()
            .position(|t| t.name().eq_ignore_ascii_case(name))
            .with_context(|| format!("unknown task `{name}` (see `hodr tasks`)"))?;
        chosen.push(all.remove(k));
    }
    Ok(chosen)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The report measures each task's parameter error as the task defines it: to the
    /// nearest ordering of SHAPES's circles, to the nearest turn of MUG's angle.
    #[test]
    fn the_parameter_error_is_the_tasks_own() {
        let shapes = RasterTask::new("shapes").unwrap();
        let truth = shapes.optimum();
        let mut reordered = truth[6..].to_vec();
        reordered.extend_from_slice(&truth[..6]);
        assert_eq!(shapes.param_error(&reordered), 0.0);
        assert!(shapes.param_error(&truth.iter().map(|t| t + 0.1).collect::<Vec<_>>()) > 0.4);

        let mug = PathTask::new(crate::tasks::by_name("mug").unwrap(), true);
        let turn = std::f64::consts::TAU / crate::tasks::Mug::RADIANS_PER_UNIT;
        let mut theta = mug.optimum();
        theta[0] += turn;
        assert!(mug.param_error(&theta) < 1e-9);
        theta[0] += 0.5;
        assert!((mug.param_error(&theta) - 0.5).abs() < 1e-9);
    }
}
