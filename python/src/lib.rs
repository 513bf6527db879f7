//! `hodr._hodr`: the Rust half of the `hodr` Python package. The Python half
//! (`python/hodr/__init__.py`) holds the public functions, their docstrings and the result
//! type; this module checks arguments, drives hodr-core and calls back into Python.
//!
//! A Python callable becomes a hodr-core [`Objective`] ([`PyObjective`]): each point (or,
//! with `batch`, each batch of points as one (k, n) array) is handed to it as a float64
//! numpy array, and it must return a real number (one per row). With `noisy` it also
//! receives the noise seed (with `batch`, a uint64 array of one seed per row): equal
//! seeds must give equal noise, so that the halves of an antithetic pair share it. An exception raised by
//! the callable, or a pending KeyboardInterrupt, is kept, ends the work at the next batch
//! ([`Objective::cancelled`]) and is raised again unchanged to the caller; a value that is
//! not a real number is a `TypeError` naming `fun` ([`values`]).
//!
//! numpy's C API is loaded when the module is imported ([`load_numpy`]): loaded on first
//! use, its import would fail on a pending KeyboardInterrupt, and rust-numpy panics then.

use hodr_core::log_scale::{LogScaled, bounds_to_log, from_log, to_log};
use hodr_core::optim::auto::FULL_MODEL_MAX_DIM;
use hodr_core::optim::{Auto, AutoModel, AutoOptions, AutoTermination, NonFinite};
use hodr_core::{
    Batch, Error, Estimator, GradientMethod, HessianMethod, HvpMethod, NoiseSeed, Objective,
    Workspace,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

use history::History;
use values::{Seen, fmt_float};

mod ask_tell;
mod history;
mod values;

/// Points per batch handed to the objective (with `batch`, rows per call): the
/// estimators' batches, and the most Auto hands over at once.
const ROWS: usize = 64;

/// A Python callable as a hodr-core objective. It holds no GIL: every call attaches to
/// the interpreter for its duration, so the optimiser's own work runs detached (other
/// Python threads go on meanwhile).
struct PyObjective {
    fun: Py<PyAny>,
    batch: bool,
    /// A stochastic callable, called with the noise seed.
    noisy: bool,
    /// The first exception the callable raised (or a KeyboardInterrupt); once set, no
    /// more calls are made.
    error: Option<PyErr>,
    /// Points handed to the callable (a batch's rows all count, even where it raised).
    calls: usize,
    /// The values it returned.
    seen: Seen,
}

impl PyObjective {
    fn new(fun: Bound<'_, PyAny>, batch: bool, noisy: bool) -> PyResult<Self> {
        if !fun.is_callable() {
            return Err(PyTypeError::new_err("fun must be callable"));
        }
        Ok(PyObjective {
            fun: fun.unbind(),
            batch,
            noisy,
            error: None,
            calls: 0,
            seen: Seen::default(),
        })
    }

    /// `fun(x)` (noisy: `fun(x, seed)`) as a float, or NaN with the error kept.
    fn call_one(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        if self.error.is_some() {
            return f64::NAN;
        }
        self.calls += 1;
        let value = Python::attach(|py| {
            let x = PyArray1::from_slice(py, theta);
            let fun = self.fun.bind(py);
            let value = if self.noisy {
                fun.call1((x, seed))
            } else {
                fun.call1((x,))
            };
            values::one_value(&value?)
        });
        match value {
            Ok(v) => {
                self.seen.record(theta, v);
                v
            }
            Err(e) => {
                self.error = Some(e);
                f64::NAN
            }
        }
    }

    /// `fun(X)` (noisy: `fun(X, seeds)`) for a (k, n) array, as k floats.
    fn call_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) -> PyResult<()> {
        let rows = Array2::from_shape_vec((batch.len(), batch.dim()), batch.points().to_vec())
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        self.calls += batch.len();
        let values: Vec<f64> = Python::attach(|py| {
            let rows = rows.into_pyarray(py);
            let fun = self.fun.bind(py);
            let values = if self.noisy {
                let seeds = PyArray1::from_slice(py, batch.seeds());
                fun.call1((rows, seeds))?
            } else {
                fun.call1((rows,))?
            };
            values::batch_values(&values, out.len())
        })?;
        out.copy_from_slice(&values);
        for (k, &value) in values.iter().enumerate() {
            self.seen.record(batch.point(k), value);
        }
        Ok(())
    }

    /// The kept exception, or `fallback` converted.
    fn error_or(&mut self, fallback: Error) -> PyErr {
        self.error.take().unwrap_or_else(|| core_error(fallback))
    }
}

impl Objective<f64> for PyObjective {
    fn evaluate(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        self.call_one(theta, seed)
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) {
        if !self.batch {
            for (k, value) in out.iter_mut().enumerate() {
                *value = self.call_one(batch.point(k), batch.seed(k));
            }
            return;
        }
        if self.error.is_some() {
            out.fill(f64::NAN);
            return;
        }
        if let Err(e) = self.call_batch(batch, out) {
            self.error = Some(e);
            out.fill(f64::NAN);
        }
    }

    fn deterministic(&self) -> bool {
        !self.noisy
    }

    fn cancelled(&mut self) -> bool {
        if self.error.is_none()
            && let Err(e) = Python::attach(|py| py.check_signals())
        {
            self.error = Some(e);
        }
        self.error.is_some()
    }
}

/// A hodr-core error as a Python exception: bad settings are `ValueError`s.
pub(crate) fn core_error(error: Error) -> PyErr {
    match error {
        Error::InvalidSigma
        | Error::NoSamples
        | Error::DimensionMismatch { .. }
        | Error::NonFiniteInput { .. }
        | Error::InvalidSetting { .. }
        | Error::InvalidEntry { .. }
        | Error::NonFiniteObjective { .. } => PyValueError::new_err(error.to_string()),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

/// `values` as a vector of finite floats, or a `ValueError` naming `name`.
pub(crate) fn finite_vector(name: &str, values: Vec<f64>) -> PyResult<Vec<f64>> {
    if values.is_empty() {
        return Err(PyValueError::new_err(format!(
            "{name} must have at least one element"
        )));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name}[{i}] is not finite ({})",
            fmt_float(values[i])
        )));
    }
    Ok(values)
}

/// σ as a finite positive float, or a `ValueError` naming `name`.
pub(crate) fn positive(name: &str, sigma: f64) -> PyResult<f64> {
    if sigma.is_finite() && sigma > 0.0 {
        Ok(sigma)
    } else {
        Err(PyValueError::new_err(format!(
            "{name} must be finite and > 0, got {}",
            fmt_float(sigma)
        )))
    }
}

/// Auto's options from Python's `options` dict, its keys checked by the Python half:
/// (tolerance, patience, restarts, fresh_starts, centre, probes, non_finite, model), each
/// `None` for the default.
pub(crate) type Settings = (
    Option<f64>,
    Option<usize>,
    Option<usize>,
    Option<bool>,
    Option<bool>,
    Option<usize>,
    Option<String>,
    Option<String>,
);

/// The options `settings` asks for, or a `ValueError` naming the one out of range.
fn apply_settings(settings: Settings, mut options: AutoOptions<f64>) -> PyResult<AutoOptions<f64>> {
    let (tolerance, patience, restarts, fresh_starts, centre, probes, non_finite, _) = settings;
    if let Some(t) = tolerance {
        options = options.with_tolerance(t).map_err(|_| {
            PyValueError::new_err(format!(
                "options['tolerance'] must be > 0 and < 1, got {}",
                fmt_float(t)
            ))
        })?;
    }
    if let Some(p) = patience {
        options = options
            .with_patience(p)
            .map_err(|_| PyValueError::new_err("options['patience'] must be at least 1"))?;
    }
    if let Some(r) = restarts {
        options = options.with_restarts(r);
    }
    if let Some(f) = fresh_starts {
        options = options.with_fresh_starts(f);
    }
    if let Some(c) = centre {
        options = options.with_centre(c);
    }
    if let Some(p) = probes {
        options = options.with_probes(p);
    }
    match non_finite.as_deref() {
        None | Some("worst") => {}
        Some("error") => options = options.with_non_finite(NonFinite::Error),
        Some(other) => {
            return Err(PyValueError::new_err(format!(
                "options['non_finite'] must be 'worst' or 'error', got {other:?}"
            )));
        }
    }
    Ok(options)
}

/// A problem statement for Auto, checked: x₀, σ₀ (one scale per coordinate), bounds,
/// the coordinates searched in log₁₀, budget and seed. Auto runs in its own
/// coordinates u (log₁₀ xᵢ where `log_scale[i]`, xᵢ elsewhere:
/// [`hodr_core::log_scale`]); the objective, the callback and the result see x.
pub(crate) struct Problem {
    /// x₀ as the caller gave it.
    start: Vec<f64>,
    /// x₀ in Auto's coordinates.
    x0: Vec<f64>,
    sigma0: Vec<f64>,
    /// The box in Auto's coordinates.
    bounds: Option<(Vec<f64>, Vec<f64>)>,
    /// One flag per coordinate: searched in log₁₀.
    log_scale: Vec<bool>,
    options: AutoOptions<f64>,
    model: AutoModel,
    seed: u64,
}

/// The model `options['model']` names (`None`: Auto's default), or a `ValueError` naming
/// it; the full model holds at most [`FULL_MODEL_MAX_DIM`] parameters.
fn model_named(name: Option<&str>, n: usize) -> PyResult<AutoModel> {
    match name {
        None => Ok(AutoModel::ByDimension),
        Some("diagonal") => Ok(AutoModel::Diagonal),
        Some("full") if n <= FULL_MODEL_MAX_DIM => Ok(AutoModel::Full),
        Some("full") => Err(PyValueError::new_err(format!(
            "options['model'] = 'full' holds at most {FULL_MODEL_MAX_DIM} parameters, got {n}"
        ))),
        Some(other) => Err(PyValueError::new_err(format!(
            "options['model'] must be 'full' or 'diagonal', got {other:?}"
        ))),
    }
}

impl Problem {
    /// Checks the arguments, naming the culprit in a `ValueError`.
    pub(crate) fn new(
        x0: Vec<f64>,
        sigma0: Vec<f64>,
        mut bounds: Option<(Vec<f64>, Vec<f64>)>,
        log_scale: Option<Vec<bool>>,
        budget: Option<usize>,
        seed: u64,
        settings: Settings,
    ) -> PyResult<Problem> {
        let x0 = finite_vector("x0", x0)?;
        let n = x0.len();
        if sigma0.len() != n {
            return Err(PyValueError::new_err(format!(
                "sigma0 must be one scale or {n} (one per coordinate), got {}",
                sigma0.len()
            )));
        }
        for (i, &s) in sigma0.iter().enumerate() {
            positive(&format!("sigma0[{i}]"), s)?;
        }
        let model = model_named(settings.7.as_deref(), n)?;
        let mut options = apply_settings(settings, AutoOptions::default())?;
        if let Some(budget) = budget {
            options = options
                .with_max_evaluations(budget)
                .map_err(|_| PyValueError::new_err("budget must be at least 1"))?;
        }
        if let Some((lower, upper)) = &bounds {
            if lower.len() != n || upper.len() != n {
                return Err(PyValueError::new_err(format!(
                    "bounds must give {n} lower and {n} upper limits, got {} and {}",
                    lower.len(),
                    upper.len()
                )));
            }
            let bad = |i: usize| lower[i].is_nan() || upper[i].is_nan() || lower[i] > upper[i];
            if let Some(i) = (0..n).find(|&i| bad(i)) {
                return Err(PyValueError::new_err(format!(
                    "bounds[{i}]: lower {} must not exceed upper {}",
                    fmt_float(lower[i]),
                    fmt_float(upper[i])
                )));
            }
            // A box with no finite point in it: a lower limit of +inf or an upper of -inf.
            let empty = |i: usize| lower[i] == f64::INFINITY || upper[i] == f64::NEG_INFINITY;
            if let Some(i) = (0..n).find(|&i| empty(i)) {
                return Err(PyValueError::new_err(format!(
                    "bounds[{i}] = ({}, {}) holds no finite point (lower must be < inf, upper > -inf)",
                    fmt_float(lower[i]),
                    fmt_float(upper[i])
                )));
            }
        }
        let log_scale = log_scale.unwrap_or_else(|| vec![false; n]);
        if log_scale.len() != n {
            return Err(PyValueError::new_err(format!(
                "log_scale must be a bool or {n} bools (one per coordinate), got {}",
                log_scale.len()
            )));
        }
        // Both transforms leave their input as it was on error: the messages quote it.
        let start = x0.clone();
        let mut x0 = x0;
        to_log(&log_scale, &mut x0).map_err(|error| match error {
            Error::InvalidEntry { index: i, .. } => PyValueError::new_err(format!(
                "x0[{i}] = {} must be > 0: log_scale[{i}] is True",
                fmt_float(x0[i])
            )),
            other => core_error(other),
        })?;
        if let Some((lower, upper)) = &mut bounds {
            bounds_to_log(&log_scale, lower, upper).map_err(|error| match error {
                Error::InvalidEntry { index: i, .. } => PyValueError::new_err(format!(
                    "bounds[{i}] = ({}, {}) holds no x > 0, which log_scale[{i}] needs",
                    fmt_float(lower[i]),
                    fmt_float(upper[i])
                )),
                other => core_error(other),
            })?;
        }
        let problem = Problem {
            start,
            x0,
            sigma0,
            bounds,
            log_scale,
            options,
            model,
            seed,
        };
        // Whatever else Auto refuses, refuse it here, before any evaluation.
        let (mut theta, mut buffer) = problem.memory();
        problem.auto(&mut theta, &mut buffer).map_err(core_error)?;
        Ok(problem)
    }

    /// The dimension n.
    pub(crate) fn dim(&self) -> usize {
        self.x0.len()
    }

    /// The model a run starts with: the one named, or by the dimension the full model up
    /// to [`FULL_MODEL_MAX_DIM`] and the diagonal one above (from n = 15 the default may
    /// take the diagonal model after its first step: [`Auto::model`]).
    pub(crate) fn starting_model(&self) -> AutoModel {
        match self.model {
            AutoModel::ByDimension if self.dim() > FULL_MODEL_MAX_DIM => AutoModel::Diagonal,
            AutoModel::ByDimension => AutoModel::Full,
            named => named,
        }
    }

    /// x₀ as the caller gave it.
    pub(crate) fn start(&self) -> &[f64] {
        &self.start
    }

    /// The caller's point for Auto's point `u`, in place (10^uᵢ on the log coordinates).
    pub(crate) fn to_caller(&self, u: &mut [f64]) {
        from_log(&self.log_scale, u);
    }

    /// `inner`, an objective over the caller's x, as one over Auto's coordinates, with
    /// `points` (resized here) the scratch that holds a batch's points in x.
    pub(crate) fn objective<'a, O: Objective<f64>>(
        &'a self,
        inner: O,
        points: &'a mut Vec<f64>,
    ) -> Result<LogScaled<'a, f64, O>, Error> {
        points.resize(ROWS * self.dim(), 0.0);
        LogScaled::new(inner, &self.log_scale, points)
    }

    /// θ (x₀ in Auto's coordinates) and Auto's buffer.
    pub(crate) fn memory(&self) -> (Vec<f64>, Vec<f64>) {
        let n = self.dim();
        (self.x0.clone(), vec![0.0; self.model.buffer_len(n)])
    }

    /// Auto on this problem, in `theta` and `buffer` from [`Problem::memory`].
    pub(crate) fn auto<'b>(
        &self,
        theta: &'b mut [f64],
        buffer: &'b mut [f64],
    ) -> Result<Auto<'b, f64, Xoshiro256PlusPlus>, Error> {
        let rng = Xoshiro256PlusPlus::seed_from_u64(self.seed);
        let auto = Auto::with_model(theta, self.sigma0[0], buffer, rng, self.model)?
            .with_options(self.options)
            .with_scales(&self.sigma0)?;
        match &self.bounds {
            Some((lower, upper)) => auto.with_bounds(lower, upper),
            None => Ok(auto),
        }
    }
}

/// Minimises `fun` with Auto; returns the result's fields as a dict (the Python half
/// makes it an `OptimizeResult`).
#[pyfunction]
#[pyo3(signature = (fun, x0, sigma0, bounds, log_scale, budget, seed, batch, noisy, callback, settings))]
#[allow(clippy::too_many_arguments)]
fn minimize_auto<'py>(
    py: Python<'py>,
    fun: Bound<'py, PyAny>,
    x0: Vec<f64>,
    sigma0: Vec<f64>,
    bounds: Option<(Vec<f64>, Vec<f64>)>,
    log_scale: Option<Vec<bool>>,
    budget: Option<usize>,
    seed: u64,
    batch: bool,
    noisy: bool,
    callback: Option<Bound<'py, PyAny>>,
    settings: Settings,
) -> PyResult<Bound<'py, PyDict>> {
    let problem = Problem::new(x0, sigma0, bounds, log_scale, budget, seed, settings)?;
    let mut points = Vec::new();
    let mut objective = problem
        .objective(PyObjective::new(fun, batch, noisy)?, &mut points)
        .map_err(core_error)?;
    let (mut theta, mut buffer) = problem.memory();
    let mut auto = problem.auto(&mut theta, &mut buffer).map_err(core_error)?;
    let callback = callback.map(Bound::unbind);
    let mut history = History::default();
    let mut failure = None;
    // θ in the caller's coordinates.
    let mut theta_x = problem.start().to_vec();
    // The run holds no GIL; the objective and the callback attach for their calls.
    let end = py.detach(|| -> PyResult<End> {
        loop {
            match auto.step(&mut objective) {
                Ok(Some(report)) => {
                    let seen = &mut objective.inner_mut().seen;
                    seen.settle();
                    theta_x.copy_from_slice(auto.theta());
                    problem.to_caller(&mut theta_x);
                    let (x, value) = seen.best(report.value, &theta_x);
                    history.push(report.evaluations, value, report.sigma, report.descent);
                    if let Some(cb) = &callback {
                        let stop = Python::attach(|py| {
                            let x = PyArray1::from_slice(py, x);
                            cb.bind(py).call1((x, value))?.is_truthy()
                        })?;
                        if stop {
                            return Ok(End::Callback);
                        }
                    }
                }
                Ok(None) => return Ok(End::Auto(auto.termination())),
                Err(error) => {
                    // The callable's own exception (its NaN is what Auto refused) goes
                    // back as it was raised.
                    if let Some(raised) = objective.inner_mut().error.take() {
                        return Err(raised);
                    }
                    if matches!(error, Error::NonFiniteObjective { .. }) {
                        failure = Some(error);
                    }
                    return Err(core_error(error));
                }
            }
        }
    });
    theta_x.copy_from_slice(auto.theta());
    problem.to_caller(&mut theta_x);
    let objective = objective.inner();
    let (x, value) = objective.seen.best(auto.value(), &theta_x);
    let outcome = match (&end, failure) {
        (Ok(end), _) => *end,
        (Err(_), Some(error)) => End::Failed(error),
        (Err(_), None) => End::Interrupted,
    };
    let result = result_dict(
        py,
        outcome,
        x,
        value,
        objective.calls,
        auto.iteration(),
        history.descents(),
        objective.seen.any_finite(),
        auto.model(),
    )?;
    history.write(&result)?;
    match end {
        Ok(_) => Ok(result),
        Err(error) => {
            // A Ctrl-C, or a non-finite value under options['non_finite'] = 'error',
            // carries the run so far, for the Python half to hand back.
            if error.is_instance_of::<PyKeyboardInterrupt>(py) || failure.is_some() {
                error.value(py).setattr("result", result)?;
            }
            Err(error)
        }
    }
}

/// How a run ended.
#[derive(Clone, Copy)]
pub(crate) enum End {
    /// Auto ended it (`None`: it had not ended, the budget's end is reported).
    Auto(Option<AutoTermination>),
    /// The caller's callback stopped it.
    Callback,
    /// Ctrl-C (KeyboardInterrupt) stopped it.
    Interrupted,
    /// Auto refused to go on: a non-finite value under `options['non_finite'] = 'error'`.
    Failed(Error),
}

/// The `OptimizeResult` fields of a run, history aside: `x` and `fun` the best point and
/// its value, `nfev` the evaluations, `nit` the iterations, `ndescents` the descents
/// ([`Auto::descents`]), `model` the model the run uses (`"full"` or `"diagonal"`,
/// [`Auto::model`]). A run in which `fun` never returned a finite value (`finite` false)
/// has not succeeded, whatever ended it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn result_dict<'py>(
    py: Python<'py>,
    end: End,
    x: &[f64],
    fun: f64,
    nfev: usize,
    nit: usize,
    ndescents: usize,
    finite: bool,
    model: AutoModel,
) -> PyResult<Bound<'py, PyDict>> {
    let (success, status, mut message) = match end {
        End::Callback => (false, 3, "stopped by the callback".to_string()),
        End::Interrupted => (false, 4, "interrupted (KeyboardInterrupt)".to_string()),
        End::Failed(error @ Error::NonFiniteObjective { .. }) => (
            false,
            5,
            format!("{error} (options['non_finite'] = 'error')"),
        ),
        End::Failed(error) => (false, 5, error.to_string()),
        End::Auto(Some(AutoTermination::MaxEvaluations)) | End::Auto(None) => {
            (false, 1, AutoTermination::MaxEvaluations.to_string())
        }
        End::Auto(Some(t @ AutoTermination::Converged)) => (true, 0, t.to_string()),
        End::Auto(Some(t @ AutoTermination::Diverged)) => (false, 6, t.to_string()),
        End::Auto(Some(t @ AutoTermination::EvaluationCap)) => (false, 7, t.to_string()),
        End::Auto(Some(t)) => (true, 2, t.to_string()),
    };
    if !finite && nfev > 0 {
        message.push_str("; fun returned no finite value");
    }
    let result = PyDict::new(py);
    result.set_item("x", PyArray1::from_slice(py, x))?;
    result.set_item("fun", fun)?;
    result.set_item("nfev", nfev)?;
    result.set_item("nit", nit)?;
    result.set_item("ndescents", ndescents)?;
    result.set_item("success", success && finite)?;
    result.set_item("status", status)?;
    result.set_item("message", message)?;
    let model = match model {
        AutoModel::Diagonal => "diagonal",
        _ => "full",
    };
    result.set_item("model", model)?;
    Ok(result)
}

/// The estimator for these settings.
fn estimator(sigma: f64, pairs: usize, seed: u64) -> PyResult<Estimator<f64, Xoshiro256PlusPlus>> {
    let sigma = positive("sigma", sigma)?;
    if pairs == 0 {
        return Err(PyValueError::new_err("pairs must be at least 1"));
    }
    Estimator::new(sigma, pairs, Xoshiro256PlusPlus::seed_from_u64(seed)).map_err(core_error)
}

/// Runs `estimate` without the GIL, with a workspace for dimension n (with a moment
/// region for least squares), turning a cancellation into the callable's own exception.
fn with_workspace<R: Send>(
    py: Python<'_>,
    objective: &mut PyObjective,
    n: usize,
    estimate: impl FnOnce(&mut PyObjective, &mut Workspace<'_, f64>) -> Result<R, Error> + Send,
) -> PyResult<R> {
    let mut buffer =
        vec![0.0; Workspace::<f64>::buffer_len(n, ROWS) + Workspace::<f64>::moments_len(n)];
    let mut seeds = vec![0; ROWS];
    let mut ws = Workspace::new(n, &mut buffer, &mut seeds).map_err(core_error)?;
    // Without the GIL: the objective attaches for its calls.
    py.detach(|| estimate(objective, &mut ws))
        .map_err(|e| match e {
            // σ itself was checked by `estimator`: what remains is σ against x.
            Error::InvalidSigma => PyValueError::new_err(
                "sigma is at or below what x's floats resolve (8*eps*max|x_i|: every sample \
             would round to x), or x +- 16*sigma overflows",
            ),
            other => objective.error_or(other),
        })
}

/// The gradient estimator called `name`.
fn gradient_method(name: &str) -> PyResult<GradientMethod> {
    Ok(match name.to_ascii_lowercase().as_str() {
        "aggregate" => GradientMethod::Aggregate,
        "per-element" | "per_element" => GradientMethod::PerElement,
        "gaussian" => GradientMethod::Gaussian,
        "fr22" => GradientMethod::Fr22,
        "ls" | "regression" => GradientMethod::Regression,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown gradient method {name:?} (methods: aggregate, per-element, gaussian, fr22, ls)"
            )));
        }
    })
}

/// ∇f_σ(x) and the evaluations it took.
#[pyfunction]
#[pyo3(signature = (fun, x, sigma, pairs, method, seed, batch, noisy))]
#[allow(clippy::too_many_arguments)]
fn gradient<'py>(
    py: Python<'py>,
    fun: Bound<'py, PyAny>,
    x: Vec<f64>,
    sigma: f64,
    pairs: usize,
    method: &str,
    seed: u64,
    batch: bool,
    noisy: bool,
) -> PyResult<(Bound<'py, PyArray1<f64>>, usize)> {
    let x = finite_vector("x", x)?;
    let method = gradient_method(method)?;
    let mut est = estimator(sigma, pairs, seed)?;
    let mut objective = PyObjective::new(fun, batch, noisy)?;
    let mut g = vec![0.0; x.len()];
    let report = with_workspace(py, &mut objective, x.len(), |o, ws| {
        est.gradient(method, o, &x, ws, &mut g)
    })?;
    Ok((g.into_pyarray(py), report.evaluations))
}

/// ∇²f_σ(x) (n×n) and the evaluations it took.
#[pyfunction]
#[pyo3(signature = (fun, x, sigma, pairs, method, seed, batch, noisy))]
#[allow(clippy::too_many_arguments)]
fn hessian<'py>(
    py: Python<'py>,
    fun: Bound<'py, PyAny>,
    x: Vec<f64>,
    sigma: f64,
    pairs: usize,
    method: &str,
    seed: u64,
    batch: bool,
    noisy: bool,
) -> PyResult<(Bound<'py, PyArray2<f64>>, usize)> {
    let x = finite_vector("x", x)?;
    let method = match method.to_ascii_lowercase().as_str() {
        "aggregate" => HessianMethod::Aggregate,
        "per-element" | "per_element" => HessianMethod::PerElement,
        "gaussian" => HessianMethod::Gaussian,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown Hessian method {method:?} (methods: aggregate, per-element, gaussian)"
            )));
        }
    };
    let mut est = estimator(sigma, pairs, seed)?;
    let mut objective = PyObjective::new(fun, batch, noisy)?;
    let n = x.len();
    let mut h = vec![0.0; n * n];
    let report = with_workspace(py, &mut objective, n, |o, ws| {
        est.hessian(method, o, &x, ws, &mut h)
    })?;
    let h =
        Array2::from_shape_vec((n, n), h).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((h.into_pyarray(py), report.evaluations))
}

/// ∇²f_σ(x)·v and the evaluations it took.
#[pyfunction]
#[pyo3(signature = (fun, x, v, sigma, pairs, method, seed, batch, noisy))]
#[allow(clippy::too_many_arguments)]
fn hvp<'py>(
    py: Python<'py>,
    fun: Bound<'py, PyAny>,
    x: Vec<f64>,
    v: Vec<f64>,
    sigma: f64,
    pairs: usize,
    method: &str,
    seed: u64,
    batch: bool,
    noisy: bool,
) -> PyResult<(Bound<'py, PyArray1<f64>>, usize)> {
    let x = finite_vector("x", x)?;
    let v = finite_vector("v", v)?;
    if v.len() != x.len() {
        return Err(PyValueError::new_err(format!(
            "v has {} elements, x has {}",
            v.len(),
            x.len()
        )));
    }
    let method = match method.to_ascii_lowercase().as_str() {
        "kernel" => HvpMethod::Kernel,
        "central" => HvpMethod::CentralDifference {
            gradient: GradientMethod::Aggregate,
            draws: hodr_core::Draws::Common,
        },
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown HVP method {method:?} (methods: kernel, central)"
            )));
        }
    };
    let mut est = estimator(sigma, pairs, seed)?;
    let mut objective = PyObjective::new(fun, batch, noisy)?;
    let mut hv = vec![0.0; x.len()];
    let report = with_workspace(py, &mut objective, x.len(), |o, ws| {
        est.hvp(method, o, &x, &v, ws, &mut hv)
    })?;
    Ok((hv.into_pyarray(py), report.evaluations))
}

/// Loads numpy's C API and everything else of rust-numpy's that loads on first use (the
/// borrow checker's shared state, the type that owns a vector handed to numpy). Loaded
/// later, the import of `numpy._core.multiarray` behind them could meet a pending
/// KeyboardInterrupt, which rust-numpy turns into a panic; at import it is an
/// ordinary exception.
fn load_numpy(py: Python<'_>) -> PyResult<()> {
    numpy::get_array_module(py)?;
    PyArray1::from_slice(py, &[0 as NoiseSeed]);
    vec![0u64].into_pyarray(py);
    Array2::<f64>::zeros((1, 1)).into_pyarray(py).readonly();
    Ok(())
}

/// The extension module.
#[pymodule]
fn _hodr(m: &Bound<'_, PyModule>) -> PyResult<()> {
    load_numpy(m.py())?;
    m.add_function(wrap_pyfunction!(minimize_auto, m)?)?;
    m.add_function(wrap_pyfunction!(gradient, m)?)?;
    m.add_function(wrap_pyfunction!(hessian, m)?)?;
    m.add_function(wrap_pyfunction!(hvp, m)?)?;
    m.add_class::<ask_tell::AskTell>()?;
    Ok(())
}
