//! The functions the page calls (wasm32 only). Each returns `Result<_, JsError>` whose
//! message is the one-line [`crate::Error`] text, so the page shows it and carries on.

use std::fmt::Display;
use std::future::Future;

use js_sys::{Float64Array, Function, Object, Promise, Reflect, Uint8Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

use crate::fit;
use crate::run::{self, Method, Outcome, Pace, Progress, RenderLoop, RunSettings};

fn js_error(e: impl Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A plain object built key by key.
struct Record(Object);

impl Record {
    fn new() -> Self {
        Record(Object::new())
    }

    fn set(self, key: &str, value: impl Into<JsValue>) -> Self {
        // Setting a property on a fresh plain object cannot fail.
        let _ = Reflect::set(&self.0, &JsValue::from_str(key), &value.into());
        self
    }

    fn floats(self, key: &str, values: &[f64]) -> Self {
        self.set(key, Float64Array::from(values))
    }
}

/// What the page needs to know of task `name`: `{name, dim, size, thetaTrue, start,
/// lower, upper, sigma0, pairs, budget}` (start drawn with `seed`).
#[wasm_bindgen(js_name = taskInfo)]
pub fn task_info(name: &str, seed: u32) -> Result<JsValue, JsError> {
    let task = run::task(name).map_err(js_error)?;
    let (lower, upper) = task.map().bounds();
    let settings = task.settings();
    Ok(Record::new()
        .set("name", task.name())
        .set("dim", task.dim() as u32)
        .set("size", task.size())
        .floats("thetaTrue", task.theta_true())
        .floats("start", &task.start(u64::from(seed)))
        .floats("lower", &lower)
        .floats("upper", &upper)
        .set("sigma0", settings.sigma_start)
        .set("pairs", settings.pairs as u32)
        .set("budget", run::default_budget(task.dim()) as u32)
        .0
        .into())
}

/// The task's scene at θ as RGBA bytes (size × size × 4).
#[wasm_bindgen]
pub fn render(name: &str, theta: &[f64]) -> Result<Vec<u8>, JsError> {
    let task = run::task(name).map_err(js_error)?;
    let scene = task.map().apply_to(task.truth(), theta).map_err(js_error)?;
    Ok(scene.render().data().to_vec())
}

/// The task's loss at each θ of `points` (rows of n).
#[wasm_bindgen]
pub fn losses(name: &str, points: &[f64]) -> Result<Vec<f64>, JsError> {
    run::losses(name, points).map_err(js_error)
}

/// The run's pace in the page: `on_progress(progress)` after every iteration; a
/// returned promise is awaited, and a falsy result (or a throw) stops the run.
struct JsPace {
    on_progress: Function,
}

impl Pace for JsPace {
    fn after(&mut self, p: &Progress<'_>) -> impl Future<Output = bool> {
        let record = Record::new()
            .set("method", p.method.name())
            .set("iteration", p.iteration as u32)
            .set("evaluations", p.evaluations as u32)
            .floats("theta", p.theta)
            .set("error", p.error)
            .set("sigma", p.sigma)
            .floats("samples", p.samples)
            .floats("values", p.values);
        let answer = self.on_progress.call1(&JsValue::NULL, &record.0);
        async move {
            match answer {
                Ok(v) if v.is_instance_of::<Promise>() => JsFuture::from(Promise::from(v))
                    .await
                    .is_ok_and(|v| v.is_truthy()),
                Ok(v) => v.is_truthy(),
                Err(_) => false,
            }
        }
    }
}

fn outcome(out: &Outcome) -> JsValue {
    Record::new()
        .set("method", out.method.name())
        .set("evaluations", out.evaluations as u32)
        .set("iterations", out.iterations as u32)
        .floats("theta", &out.theta)
        .set("initialError", out.initial_error)
        .set("error", out.error)
        .set(
            "evaluationsToTarget",
            out.evaluations_to_target
                .map_or(JsValue::NULL, |e| JsValue::from(e as u32)),
        )
        .set("stopped", out.stopped)
        .0
        .into()
}

/// Runs `method` on `task` (the native `reference` binary's `run`), calling
/// `on_progress` after every iteration; resolves to the outcome
/// `{method, evaluations, iterations, theta, initialError, error, evaluationsToTarget,
/// stopped}`. `sigma0`, `pairs`, `start` and `budget` default to the task's.
#[wasm_bindgen(js_name = runMethod)]
#[allow(clippy::too_many_arguments)]
pub async fn run_method(
    task: String,
    method: String,
    seed: u32,
    sigma0: Option<f64>,
    pairs: Option<u32>,
    start: Option<Vec<f64>>,
    budget: Option<u32>,
    on_progress: Function,
) -> Result<JsValue, JsError> {
    let method = Method::from_name(&method).map_err(js_error)?;
    let mut settings = RunSettings::new(&task, method, u64::from(seed));
    settings.sigma0 = sigma0;
    settings.pairs = pairs.map(|p| p as usize);
    settings.start = start;
    settings.budget = budget.map(|b| b as usize);
    let out = run::run(&settings, &mut JsPace { on_progress })
        .await
        .map_err(js_error)?;
    Ok(outcome(&out))
}

/// BENCHMARKS.md's render loop: BOX2's objective, built once; time [`RenderBench::run`].
#[wasm_bindgen]
pub struct RenderBench(RenderLoop);

#[wasm_bindgen]
impl RenderBench {
    /// BOX2's cached objective.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Result<RenderBench, JsError> {
        RenderLoop::box2().map(RenderBench).map_err(js_error)
    }

    /// Evaluates `renders` points; returns the checksum (sum of the losses).
    pub fn run(&mut self, renders: u32) -> f64 {
        self.0.run(renders as usize)
    }
}

fn rgba_of_rgb(rgb: &[u8]) -> Uint8Array {
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    Uint8Array::from(rgba.as_slice())
}

/// Image to shapes: decodes `bytes` (PNG or JPEG; the shipped landscape when absent),
/// calls `on_target(rgba, width, height)`, then fits `shapes` shapes of `kind`, calling
/// `on_shape(rgba, [count, rmse, evaluations])` after each; returns
/// `{svg, count, rmse, evaluations}`.
/// Blocking: the page calls it in a worker.
#[wasm_bindgen(js_name = fitImage)]
pub fn fit_image(
    bytes: Option<Vec<u8>>,
    kind: &str,
    shapes: u32,
    seed: u32,
    on_target: &Function,
    on_shape: &Function,
) -> Result<JsValue, JsError> {
    let options = fit::options(kind, shapes as usize, u64::from(seed)).map_err(js_error)?;
    let target = match bytes {
        Some(bytes) => fit::load(&bytes),
        None => fit::landscape(),
    }
    .map_err(js_error)?;
    let (width, height) = (target.width(), target.height());
    on_target
        .call3(
            &JsValue::NULL,
            &rgba_of_rgb(target.rgb()),
            &width.into(),
            &height.into(),
        )
        .map_err(|_| JsError::new("the page's target callback failed"))?;
    let result = fit::shapes(&target, &options, &mut |scene, rmse, evaluations| {
        let pixels = Uint8Array::from(scene.render().data());
        let numbers =
            Float64Array::from([scene.shapes().len() as f64, rmse, evaluations as f64].as_slice());
        // A failing observer only loses a frame of the animation.
        let _ = on_shape.call2(&JsValue::NULL, &pixels, &numbers);
    })
    .map_err(js_error)?;
    Ok(Record::new()
        .set("svg", result.scene().to_svg())
        .set("count", result.scene().shapes().len() as u32)
        .set("rmse", result.rmse())
        .set("evaluations", result.evaluations() as f64)
        .0
        .into())
}
