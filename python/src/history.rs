//! A run's record per iteration, which the Python half groups into
//! `OptimizeResult.history`.

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Per iteration: the evaluations so far, f at the best point, σ, and the descent the
/// run is in once the iteration has ended (from 1: `AutoReport::descent`).
#[derive(Default)]
pub(crate) struct History {
    nfev: Vec<u64>,
    fun: Vec<f64>,
    sigma: Vec<f64>,
    descent: Vec<u64>,
}

impl History {
    /// Records an iteration.
    pub(crate) fn push(&mut self, evaluations: usize, fun: f64, sigma: f64, descent: usize) {
        self.nfev.push(evaluations as u64);
        self.fun.push(fun);
        self.sigma.push(sigma);
        self.descent.push(descent as u64);
    }

    /// Iterations recorded.
    pub(crate) fn iterations(&self) -> usize {
        self.nfev.len()
    }

    /// Descents the run has begun: the last iteration's, or 1 before any
    /// (`Auto::descents`).
    pub(crate) fn descents(&self) -> usize {
        self.descent.last().map_or(1, |&d| d as usize)
    }

    /// Writes the `history_nfev`, `history_fun`, `history_sigma` and `history_descent`
    /// fields of `result`.
    pub(crate) fn write(&self, result: &Bound<'_, PyDict>) -> PyResult<()> {
        let py = result.py();
        result.set_item("history_nfev", self.nfev.clone().into_pyarray(py))?;
        result.set_item("history_fun", self.fun.clone().into_pyarray(py))?;
        result.set_item("history_sigma", self.sigma.clone().into_pyarray(py))?;
        result.set_item("history_descent", self.descent.clone().into_pyarray(py))?;
        Ok(())
    }
}
