//! What `fun` returns: its conversion to floats, with errors that name `fun` and say what
//! it returned, and the binding's own record of the values ([`Seen`]).
//!
//! Auto's account of the run leaves out two things a Python caller needs. It knows no
//! value that is not finite (NaN and ±∞ count as worse than any value), so a run that
//! never saw a finite one has no best value in it; and a batch that a Ctrl-C or an error
//! cut short is not in it, though the values computed before the cut are real. [`Seen`]
//! keeps both.

use numpy::{PyArray1, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{
    PyBytes, PyComplex, PyFloat, PyInt, PyList, PySequence, PyString, PyTuple, PyType,
};

/// `value` as Python would write it (`repr`): `1e+300` rather than Rust's 301 digits,
/// `nan` and `inf` as Python spells them.
pub(crate) fn fmt_float(value: f64) -> String {
    if value.is_nan() {
        return "nan".into();
    }
    if value.is_infinite() {
        return if value > 0.0 { "inf" } else { "-inf" }.into();
    }
    // Debug, like repr, is the shortest string that reads back exactly, with an exponent
    // below 1e-4 and from 1e16 on; Python writes the exponent's sign and two digits.
    let debug = format!("{value:?}");
    match debug.split_once('e') {
        Some((mantissa, exponent)) => {
            let (sign, digits) = match exponent.strip_prefix('-') {
                Some(digits) => ('-', digits),
                None => ('+', exponent),
            };
            format!("{mantissa}e{sign}{digits:0>2}")
        }
        None => debug,
    }
}

/// A shape as Python writes it: `(5,)`, `(5, 1)`.
fn fmt_shape(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => {
            let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
            format!("({})", dims.join(", "))
        }
    }
}

/// What `value` is, for a message: its type, and an array's shape and dtype.
fn describe(value: &Bound<'_, PyAny>) -> String {
    let name = value
        .get_type()
        .name()
        .map_or_else(|_| "object".to_string(), |n| n.to_string());
    match value.cast::<PyUntypedArray>() {
        Ok(array) => format!(
            "{name} of shape {} and dtype {}",
            fmt_shape(array.shape()),
            array.dtype()
        ),
        Err(_) => name,
    }
}

/// `numbers.Complex` and `numbers.Real`: a complex number that is not a real one (numpy's
/// complex64) would otherwise become its real part, with a warning at most.
fn number_types(py: Python<'_>) -> PyResult<&(Py<PyType>, Py<PyType>)> {
    static TYPES: PyOnceLock<(Py<PyType>, Py<PyType>)> = PyOnceLock::new();
    TYPES.get_or_try_init(py, || {
        let numbers = py.import("numbers")?;
        let get = |name: &str| -> PyResult<Py<PyType>> {
            Ok(numbers.getattr(name)?.cast_into::<PyType>()?.unbind())
        };
        Ok((get("Complex")?, get("Real")?))
    })
}

/// `value` as a float, where it is a real number: a Python or numpy float, int or bool, a
/// 0-d real array, or any other object with `__float__` that is not complex. Otherwise a
/// `TypeError` (an int too large for a float: a `ValueError`) whose message is
/// `message(what value is)`, caused by the conversion's own error where there was one.
pub(crate) fn real(value: &Bound<'_, PyAny>, message: &dyn Fn(&str) -> String) -> PyResult<f64> {
    if let Ok(float) = value.cast::<PyFloat>() {
        return Ok(float.value());
    }
    let py = value.py();
    let not_real = |cause: Option<PyErr>| {
        let error = PyTypeError::new_err(message(&describe(value)));
        error.set_cause(py, cause);
        error
    };
    if !value.is_instance_of::<PyInt>() {
        let textual = value.is_instance_of::<PyString>() || value.is_instance_of::<PyBytes>();
        if textual || value.is_instance_of::<PyComplex>() {
            return Err(not_real(None));
        }
        if let Ok(array) = value.cast::<PyUntypedArray>() {
            if array.ndim() != 0 || !matches!(array.dtype().kind(), b'b' | b'i' | b'u' | b'f') {
                return Err(not_real(None));
            }
        } else {
            let (complex, real) = number_types(py)?;
            if value.is_instance(complex.bind(py))? && !value.is_instance(real.bind(py))? {
                return Err(not_real(None));
            }
        }
    }
    value.extract::<f64>().map_err(|e| {
        if e.is_instance_of::<PyOverflowError>(py) {
            let error = PyValueError::new_err(message(&format!(
                "{} too large for a float",
                describe(value)
            )));
            error.set_cause(py, Some(e));
            error
        } else {
            not_real(Some(e))
        }
    })
}

/// What `fun` returned for one point, as a float.
pub(crate) fn one_value(value: &Bound<'_, PyAny>) -> PyResult<f64> {
    real(value, &|got| {
        format!("fun must return a real number (a float), got {got}")
    })
}

/// What `fun` returned for a batch of `k` points (`batch=True`): k real numbers, as a
/// list, a tuple, a 1-D array or another sequence of them.
pub(crate) fn batch_values(values: &Bound<'_, PyAny>, k: usize) -> PyResult<Vec<f64>> {
    let py = values.py();
    let wrong = |got: &str| {
        PyTypeError::new_err(format!(
            "with batch=True, fun must return k = {k} values (a sequence or 1-D array of real numbers, one per row of X), got {got}"
        ))
    };
    let mut values = values.clone();
    if !values.is_instance_of::<PyUntypedArray>() && values.hasattr("__array__")? {
        // A tensor or a pandas Series: numpy's view of it.
        values = py.import("numpy")?.call_method1("asarray", (values,))?;
    }
    let floats = if let Ok(array) = values.cast::<PyUntypedArray>() {
        if array.ndim() != 1 {
            return Err(wrong(&describe(&values)));
        }
        match array.dtype().kind() {
            b'b' | b'i' | b'u' | b'f' => {
                let array = array
                    .call_method1("astype", ("float64",))?
                    .cast_into::<PyArray1<f64>>()?;
                array.readonly().as_array().to_vec()
            }
            b'O' => elements(&values, k)?,
            _ => return Err(wrong(&describe(&values))),
        }
    } else if values.is_instance_of::<PyList>()
        || values.is_instance_of::<PyTuple>()
        || (values.cast::<PySequence>().is_ok()
            && !values.is_instance_of::<PyString>()
            && !values.is_instance_of::<PyBytes>())
    {
        elements(&values, k)?
    } else {
        return Err(wrong(&describe(&values)));
    };
    if floats.len() != k {
        return Err(PyValueError::new_err(format!(
            "fun returned {} values for a batch of {k} points (with batch=True it must return one per row)",
            floats.len()
        )));
    }
    Ok(floats)
}

/// The elements of a sequence `fun` returned for a batch of `k` points, each a real number.
fn elements(values: &Bound<'_, PyAny>, k: usize) -> PyResult<Vec<f64>> {
    values
        .try_iter()?
        .enumerate()
        .map(|(i, v)| {
            real(&v?, &|got| {
                format!(
                    "with batch=True, fun must return k = {k} real numbers (floats), got {got} at row {i}"
                )
            })
        })
        .collect()
}

/// The values `fun` returned, as the binding saw them.
#[derive(Default)]
pub(crate) struct Seen {
    /// The lowest finite value of the run, and its point.
    lowest: Option<(f64, Vec<f64>)>,
    /// The lowest finite value since Auto's last completed iteration ([`Seen::settle`]),
    /// and its point: values Auto has not yet taken into its account.
    recent: Option<(f64, Vec<f64>)>,
    /// The first value that was not finite, and its point; the first infinite one
    /// replaces a NaN.
    non_finite: Option<(f64, Vec<f64>)>,
}

impl Seen {
    /// f(`x`) = `value`.
    pub(crate) fn record(&mut self, x: &[f64], value: f64) {
        if value.is_finite() {
            for slot in [&mut self.lowest, &mut self.recent] {
                if slot.as_ref().is_none_or(|(lowest, _)| value < *lowest) {
                    *slot = Some((value, x.to_vec()));
                }
            }
        } else if self
            .non_finite
            .as_ref()
            .is_none_or(|(first, _)| first.is_nan() && !value.is_nan())
        {
            self.non_finite = Some((value, x.to_vec()));
        }
    }

    /// Auto has completed an iteration: the values so far are in its account.
    pub(crate) fn settle(&mut self) {
        self.recent = None;
    }

    /// Whether `fun` has returned a finite value.
    pub(crate) fn any_finite(&self) -> bool {
        self.lowest.is_some()
    }

    /// The best point and its value: Auto's (`value` at `theta`) where it has one, unless
    /// a value Auto has not yet taken in is lower; where Auto has none, the lowest finite
    /// value seen, else the first infinite one, else the first NaN (`theta` and NaN
    /// before any evaluation).
    pub(crate) fn best<'a>(&'a self, value: Option<f64>, theta: &'a [f64]) -> (&'a [f64], f64) {
        match (value, &self.recent) {
            (Some(v), Some((r, x))) if *r < v => (x, *r),
            (Some(v), _) => (theta, v),
            (None, _) => match (&self.lowest, &self.non_finite) {
                (Some((v, x)), _) | (None, Some((v, x))) => (x, *v),
                (None, None) => (theta, f64::NAN),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_read_as_python_writes_them() {
        let cases = [
            (1e300, "1e+300"),
            (1e-5, "1e-05"),
            (1.5e-7, "1.5e-07"),
            (1e16, "1e+16"),
            (0.0001, "0.0001"),
            (2.5, "2.5"),
            (1.0, "1.0"),
            (-3e100, "-3e+100"),
            (f64::NAN, "nan"),
            (f64::NEG_INFINITY, "-inf"),
        ];
        for (value, text) in cases {
            assert_eq!(fmt_float(value), text);
        }
    }

    #[test]
    fn the_best_value_prefers_finite_then_infinite_then_nan() {
        let mut seen = Seen::default();
        assert!(seen.best(None, &[0.0]).1.is_nan());
        seen.record(&[1.0], f64::NAN);
        assert_eq!(seen.best(None, &[0.0]).0, &[1.0]);
        seen.record(&[2.0], f64::INFINITY);
        seen.record(&[3.0], f64::NEG_INFINITY);
        assert_eq!(seen.best(None, &[0.0]), (&[2.0][..], f64::INFINITY));
        seen.record(&[4.0], 5.0);
        seen.record(&[5.0], 7.0);
        assert_eq!(seen.best(None, &[0.0]), (&[4.0][..], 5.0));
        // Auto's own value stands unless a value it has not yet taken in is lower.
        assert_eq!(seen.best(Some(6.0), &[9.0]), (&[4.0][..], 5.0));
        seen.settle();
        assert_eq!(seen.best(Some(6.0), &[9.0]), (&[9.0][..], 6.0));
        assert!(seen.any_finite());
    }
}
