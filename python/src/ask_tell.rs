//! Ask/tell: Auto runs on a thread of its own, and its objective hands each batch of
//! points to the caller and waits for their values. The caller evaluates a batch however
//! it likes (a process pool, a GPU, a cluster) and tells the values back; the run is the
//! same as `minimize(..., batch=True)` with the same seed, point for point.
//!
//! Dropping the object (or a value count that does not match) ends the thread: its
//! objective then reports [`Objective::cancelled`], and Auto stops at once.
//!
//! A run that fails (a non-finite value under `options['non_finite'] = 'error'`) says so
//! from the `tell` that handed over the value, and again from every later `ask`, `tell`
//! and `stop`, each error carrying the run so far in its `result` attribute.

use std::sync::Mutex;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::thread::JoinHandle;
use std::time::Duration;

use hodr_core::optim::{AutoModel, AutoTermination};
use hodr_core::{Batch, Error, NoiseSeed, Objective};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::history::History;
use crate::values::Seen;
use crate::{End, Problem, Settings, core_error, result_dict};

/// How long `ask` and `stop` wait for the optimiser between looks for a Ctrl-C.
const SIGNAL_CHECK: Duration = Duration::from_millis(50);

/// What the Auto thread says.
enum FromAuto {
    /// Points to evaluate, row-major, and their noise seeds.
    Batch(Vec<f64>, Vec<NoiseSeed>),
    /// An iteration ended: evaluations so far, f at the best point (where Auto has seen
    /// a finite one), σ, the descent the run is in, the best point (in the caller's
    /// coordinates), the model the run uses.
    Iteration {
        evaluations: usize,
        value: Option<f64>,
        sigma: f64,
        descent: usize,
        theta: Vec<f64>,
        model: AutoModel,
    },
    /// The run ended.
    Done {
        termination: Option<AutoTermination>,
        evaluations: usize,
        iterations: usize,
        /// Why the run failed, if it did.
        error: Option<Error>,
    },
}

/// Why an ask/tell run failed.
enum Failure {
    /// Auto returned an error (a non-finite value under `options['non_finite'] =
    /// 'error'`, or arguments it refused).
    Core(Error),
    /// The optimiser's thread ended without saying why.
    Lost,
}

/// The Auto thread's objective: batches out, values back.
struct Channel {
    to_caller: Sender<FromAuto>,
    values: Receiver<Vec<f64>>,
    noisy: bool,
    closed: bool,
}

impl Objective<f64> for Channel {
    fn evaluate(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        let mut out = [f64::NAN];
        self.exchange(theta, &[seed], &mut out);
        out[0]
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) {
        self.exchange(batch.points(), batch.seeds(), out);
    }

    fn deterministic(&self) -> bool {
        !self.noisy
    }

    fn cancelled(&mut self) -> bool {
        self.closed
    }
}

impl Channel {
    fn exchange(&mut self, points: &[f64], seeds: &[NoiseSeed], out: &mut [f64]) {
        out.fill(f64::NAN);
        if self.closed
            || self
                .to_caller
                .send(FromAuto::Batch(points.to_vec(), seeds.to_vec()))
                .is_err()
        {
            self.closed = true;
            return;
        }
        match self.values.recv() {
            Ok(values) if values.len() == out.len() => out.copy_from_slice(&values),
            _ => self.closed = true,
        }
    }
}

/// Auto driven by ask and tell (the Python class `hodr.Optimizer` wraps it).
#[pyclass(module = "hodr._hodr")]
pub struct AskTell {
    n: usize,
    /// In a mutex only so that the class is `Sync`, as Python classes must be.
    from_auto: Option<Mutex<Receiver<FromAuto>>>,
    values: Option<Sender<Vec<f64>>>,
    thread: Option<JoinHandle<()>>,
    /// The batch asked and not yet told.
    asked: Option<Vec<f64>>,
    /// A batch received and not yet asked for, with its seeds.
    pending: Option<(Vec<f64>, Vec<NoiseSeed>)>,
    /// The noise seeds of the batch last asked.
    seeds: Vec<NoiseSeed>,
    /// Auto's best point (in the caller's coordinates) and its value at its last
    /// iteration.
    best: (Vec<f64>, Option<f64>),
    /// The values told.
    seen: Seen,
    /// Values told.
    told: usize,
    /// `options['non_finite'] = 'error'`: a non-finite value ends the run.
    non_finite_error: bool,
    history: History,
    /// The model the run uses, as of its last iteration ([`Problem::starting_model`]
    /// before the first).
    model: AutoModel,
    done: Option<(Option<AutoTermination>, usize, usize)>,
    error: Option<Failure>,
}

impl AskTell {
    /// Reads what the thread says until it asks for a batch or ends; a Ctrl-C meanwhile
    /// is a KeyboardInterrupt, and the next call goes on waiting.
    fn advance(&mut self, py: Python<'_>) -> PyResult<()> {
        while self.pending.is_none() && self.done.is_none() {
            let Some(rx) = self.from_auto.take() else {
                return Ok(());
            };
            let (message, rx) = py.detach(move || {
                let message = rx.lock().map_or(Err(RecvTimeoutError::Disconnected), |r| {
                    r.recv_timeout(SIGNAL_CHECK)
                });
                (message, rx)
            });
            self.from_auto = Some(rx);
            match message {
                Err(RecvTimeoutError::Timeout) => py.check_signals()?,
                Ok(FromAuto::Batch(points, seeds)) => self.pending = Some((points, seeds)),
                Ok(FromAuto::Iteration {
                    evaluations,
                    value,
                    sigma,
                    descent,
                    theta,
                    model,
                }) => {
                    self.model = model;
                    self.seen.settle();
                    let fun = self.seen.best(value, &theta).1;
                    self.history.push(evaluations, fun, sigma, descent);
                    self.best = (theta, value);
                }
                Ok(FromAuto::Done {
                    termination,
                    evaluations,
                    iterations,
                    error,
                }) => {
                    self.done = Some((termination, evaluations, iterations));
                    self.error = error.map(Failure::Core);
                    if let Some(thread) = self.thread.take() {
                        let _ = thread.join();
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    self.done = Some((None, 0, 0));
                    self.error = Some(Failure::Lost);
                }
            }
        }
        Ok(())
    }

    /// The run's failure as an exception carrying the run so far (`result`), if it failed.
    fn failure(&self, py: Python<'_>) -> PyResult<Option<PyErr>> {
        let error = match &self.error {
            None => return Ok(None),
            Some(Failure::Core(e)) => core_error(*e),
            Some(Failure::Lost) => {
                PyRuntimeError::new_err("the optimiser's thread ended unexpectedly")
            }
        };
        error.value(py).setattr("result", self.result(py)?)?;
        Ok(Some(error))
    }
}

#[pymethods]
impl AskTell {
    #[new]
    #[pyo3(signature = (x0, sigma0, bounds, log_scale, budget, seed, noisy, settings))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        x0: Vec<f64>,
        sigma0: Vec<f64>,
        bounds: Option<(Vec<f64>, Vec<f64>)>,
        log_scale: Option<Vec<bool>>,
        budget: Option<usize>,
        seed: u64,
        noisy: bool,
        settings: Settings,
    ) -> PyResult<Self> {
        let non_finite_error = settings.6.as_deref() == Some("error");
        let problem = Problem::new(x0, sigma0, bounds, log_scale, budget, seed, settings)?;
        let n = problem.dim();
        let best = (problem.start().to_vec(), None);
        let model = problem.starting_model();
        let (to_caller, from_auto) = channel();
        let (values, from_caller) = channel();
        let thread = std::thread::spawn(move || {
            let channel = Channel {
                to_caller: to_caller.clone(),
                values: from_caller,
                noisy,
                closed: false,
            };
            let mut points = Vec::new();
            let (mut theta, mut buffer) = problem.memory();
            let mut error = None;
            let run = problem
                .objective(channel, &mut points)
                .and_then(|objective| Ok((objective, problem.auto(&mut theta, &mut buffer)?)));
            let (termination, evaluations, iterations) = match run {
                Ok((mut objective, mut auto)) => {
                    loop {
                        match auto.step(&mut objective) {
                            Ok(Some(report)) => {
                                let mut theta = auto.theta().to_vec();
                                problem.to_caller(&mut theta);
                                let iteration = FromAuto::Iteration {
                                    evaluations: report.evaluations,
                                    value: report.value,
                                    sigma: report.sigma,
                                    descent: report.descent,
                                    theta,
                                    model: auto.model(),
                                };
                                if to_caller.send(iteration).is_err() {
                                    break;
                                }
                            }
                            Ok(None) => break,
                            Err(e) => {
                                if !objective.inner().closed {
                                    error = Some(e);
                                }
                                break;
                            }
                        }
                    }
                    (auto.termination(), auto.evaluations(), auto.iteration())
                }
                Err(e) => {
                    error = Some(e);
                    (None, 0, 0)
                }
            };
            let _ = to_caller.send(FromAuto::Done {
                termination,
                evaluations,
                iterations,
                error,
            });
        });
        Ok(AskTell {
            n,
            from_auto: Some(Mutex::new(from_auto)),
            values: Some(values),
            thread: Some(thread),
            asked: None,
            pending: None,
            seeds: Vec::new(),
            best,
            seen: Seen::default(),
            told: 0,
            non_finite_error,
            history: History::default(),
            model,
            done: None,
            error: None,
        })
    }

    /// The next batch as a (k, n) array, or the batch asked and not yet told, again;
    /// (0, n) once the run has ended.
    fn ask<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        // A batch asked and not yet told is asked again, unchanged: a Ctrl-C that lands
        // after it left the extension, before the caller held it, does not lose it.
        let points = match &self.asked {
            Some(points) => points.clone(),
            None => {
                self.advance(py)?;
                if let Some(error) = self.failure(py)? {
                    return Err(error);
                }
                let (points, seeds) = self.pending.take().unwrap_or_default();
                self.seeds = seeds;
                if !points.is_empty() {
                    self.asked = Some(points.clone());
                }
                points
            }
        };
        let rows = points.len() / self.n;
        let array = Array2::from_shape_vec((rows, self.n), points)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(array.into_pyarray(py))
    }

    /// The values of the batch last asked, one per row, in order. Once the run has
    /// ended, the empty batch asked takes no values.
    fn tell(&mut self, py: Python<'_>, values: PyReadonlyArrayDyn<'_, f64>) -> PyResult<()> {
        let Some(points) = self.asked.take() else {
            if let Some(error) = self.failure(py)? {
                return Err(error);
            }
            if self.done.is_none() {
                return Err(PyRuntimeError::new_err(
                    "tell() without ask(): nothing was asked",
                ));
            }
            if values.len() != 0 {
                return Err(PyValueError::new_err(format!(
                    "values has {} elements, the batch asked has 0 points (the run has ended)",
                    values.len()
                )));
            }
            return Ok(());
        };
        let rows = points.len() / self.n;
        if values.len() != rows {
            self.asked = Some(points);
            return Err(PyValueError::new_err(format!(
                "values has {} elements, the batch asked has {rows} points",
                values.len()
            )));
        }
        let values = values
            .as_slice()
            .map(<[f64]>::to_vec)
            .unwrap_or_else(|_| values.as_array().iter().copied().collect());
        for (x, &value) in points.chunks_exact(self.n).zip(&values) {
            self.seen.record(x, value);
        }
        self.told += rows;
        let fails = self.non_finite_error && values.iter().any(|v| !v.is_finite());
        if let Some(tx) = &self.values {
            let _ = tx.send(values);
        }
        if fails {
            // Auto refuses the value: say so now, with the run so far.
            self.advance(py)?;
            if let Some(error) = self.failure(py)? {
                return Err(error);
            }
        }
        Ok(())
    }

    /// The noise seeds of the batch last asked, one per row (equal seeds: equal noise).
    #[getter]
    fn seeds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<NoiseSeed>> {
        PyArray1::from_slice(py, &self.seeds)
    }

    /// True once the run has ended (waits for the optimiser to say what it wants next).
    fn stop(&mut self, py: Python<'_>) -> PyResult<bool> {
        if self.asked.is_some() {
            return Ok(false);
        }
        self.advance(py)?;
        match self.failure(py)? {
            Some(error) => Err(error),
            None => Ok(self.done.is_some()),
        }
    }

    /// The result so far (the best point and its value) as `OptimizeResult` fields.
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (termination, iterations) = match self.done {
            Some((termination, _, iterations)) => (termination, iterations),
            None => (None, self.history.iterations()),
        };
        let end = match &self.error {
            Some(Failure::Core(e)) => End::Failed(*e),
            _ => End::Auto(termination),
        };
        let (x, fun) = self.seen.best(self.best.1, &self.best.0);
        let result = result_dict(
            py,
            end,
            x,
            fun,
            self.told,
            iterations,
            self.history.descents(),
            self.seen.any_finite(),
            self.model,
        )?;
        if self.done.is_none() {
            result.set_item("success", false)?;
            result.set_item("message", "running")?;
        }
        self.history.write(&result)?;
        Ok(result)
    }
}

impl Drop for AskTell {
    fn drop(&mut self) {
        // Closing both channels makes the thread's objective report cancellation.
        self.values = None;
        self.from_auto = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
