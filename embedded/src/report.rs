//! The report: one line per run, written without `core::fmt`, and the comparison of two
//! reports.
//!
//! ```text
//! run QUAD OurHVPA evaluations=3008 iterations=41 end=max-evaluations theta=3a03126f,b9d1b717
//! ```
//!
//! θ is printed as the hexadecimal bit patterns of its `f32`s: exact, and the cheapest
//! form to print. The firmware prints no decimal floats at all: `core::fmt`'s (Grisu with
//! a Dragon fallback) weighs more than the minimal build's whole budget, and even a
//! short writer of its own links software division and conversion that the minimal
//! firmware otherwise does without. `host_reference --check` prints θ in decimal.
//! Lines not starting with `run ` (the firmware's stack report) are not compared.

use core::fmt;

use hodr_core::Error;
use hodr_core::optim::Termination;

use crate::run::{End, MAX_DIM, RunResult};

/// Where report bytes go: semihosting on the firmware, a buffer or stdout on the host.
/// Implemented for every `FnMut(&[u8])`.
pub trait Output {
    /// Writes `bytes`, which are ASCII text. Failures are the sink's to handle; a
    /// report has nowhere to send them.
    fn write(&mut self, bytes: &[u8]);
}

impl<F: FnMut(&[u8]) + ?Sized> Output for F {
    fn write(&mut self, bytes: &[u8]) {
        self(bytes)
    }
}

/// Writes the report line of one run, newline included.
pub fn write_run<O: Output + ?Sized>(
    out: &mut O,
    problem: &str,
    algorithm: &str,
    result: &RunResult,
) {
    out.write(b"run ");
    out.write(problem.as_bytes());
    out.write(b" ");
    out.write(algorithm.as_bytes());
    out.write(b" evaluations=");
    write_decimal(out, result.evaluations);
    out.write(b" iterations=");
    write_decimal(out, result.iterations);
    out.write(b" end=");
    match result.end {
        End::Finished(t) => out.write(termination_name(t).as_bytes()),
        #[cfg(feature = "auto")]
        End::Auto(t) => out.write(match t {
            hodr_core::optim::AutoTermination::Converged => b"converged",
            hodr_core::optim::AutoTermination::Stagnated => b"stagnated",
            hodr_core::optim::AutoTermination::MaxEvaluations => b"max-evaluations",
            hodr_core::optim::AutoTermination::Diverged => b"diverged",
            hodr_core::optim::AutoTermination::EvaluationCap => b"evaluation-cap",
            _ => b"other",
        }),
        End::Failed { iteration, error } => {
            out.write(b"failed-at-");
            write_decimal(out, iteration);
            out.write(b"-");
            out.write(error_name(error).as_bytes());
        }
    }
    out.write(b" theta=");
    for (i, &x) in result.theta().iter().enumerate() {
        if i > 0 {
            out.write(b",");
        }
        write_hex(out, x.to_bits());
    }
    out.write(b"\n");
}

fn termination_name(t: Termination) -> &'static str {
    match t {
        Termination::Converged => "converged",
        Termination::MaxIterations => "max-iterations",
        Termination::MaxEvaluations => "max-evaluations",
        Termination::TimeLimit => "time-limit",
        _ => "other",
    }
}

fn error_name(e: Error) -> &'static str {
    match e {
        Error::InvalidSigma => "invalid-sigma",
        Error::NoSamples => "no-samples",
        Error::DimensionMismatch { .. } => "dimension-mismatch",
        Error::WorkspaceTooSmall { .. } => "workspace-too-small",
        Error::NonFiniteInput { .. } => "non-finite-input",
        Error::NonFiniteObjective { .. } => "non-finite-objective",
        Error::InvalidSetting { .. } => "invalid-setting",
        Error::InvalidEntry { .. } => "invalid-entry",
        Error::NonFiniteEstimate { .. } => "non-finite-estimate",
        Error::Cancelled => "cancelled",
        _ => "error",
    }
}

/// Decimal digits of `usize::MAX`.
const DECIMAL_DIGITS: usize = usize::MAX.ilog10() as usize + 1;

/// 10^(DECIMAL_DIGITS − 1), …, 100, 10, 1.
#[cfg_attr(not(any(target_arch = "arm", test)), allow(dead_code))]
const POWERS_OF_TEN: [usize; DECIMAL_DIGITS] = {
    let mut powers = [1; DECIMAL_DIGITS];
    let mut k = DECIMAL_DIGITS - 1;
    while k > 0 {
        powers[k - 1] = powers[k] * 10;
        k -= 1;
    }
    powers
};

/// Writes `n` in decimal.
pub fn write_decimal<O: Output + ?Sized>(out: &mut O, n: usize) {
    let mut digits = [b'0'; DECIMAL_DIGITS];
    let first = decimal_digits(n, &mut digits);
    out.write(digits.get(first..).unwrap_or_default());
}

/// Puts `n`'s decimal digits at the end of `digits` (which holds `b'0'`s) and returns
/// where the first is.
///
/// Arm repeats subtractions of powers of ten: a Cortex-M0 has no divide instruction, and
/// the software one would be linked for this alone. Elsewhere (RV32IMAC has `divu` and
/// `remu`) a digit is a remainder by ten, in less code.
#[cfg(target_arch = "arm")]
fn decimal_digits(n: usize, digits: &mut [u8; DECIMAL_DIGITS]) -> usize {
    decimal_digits_by_subtraction(n, digits)
}

/// See the Arm form.
#[cfg(not(target_arch = "arm"))]
fn decimal_digits(n: usize, digits: &mut [u8; DECIMAL_DIGITS]) -> usize {
    decimal_digits_by_division(n, digits)
}

/// [`decimal_digits`] by repeated subtraction of powers of ten.
#[cfg_attr(not(any(target_arch = "arm", test)), allow(dead_code))]
fn decimal_digits_by_subtraction(mut n: usize, digits: &mut [u8; DECIMAL_DIGITS]) -> usize {
    for (digit, &power) in digits.iter_mut().zip(&POWERS_OF_TEN) {
        while n >= power {
            n -= power;
            *digit += 1;
        }
    }
    // Leading zeros off, the units digit kept.
    digits
        .iter()
        .position(|&d| d != b'0')
        .unwrap_or(DECIMAL_DIGITS - 1)
}

/// [`decimal_digits`] by division by ten, the units digit first.
#[cfg_attr(all(target_arch = "arm", not(test)), allow(dead_code))]
fn decimal_digits_by_division(mut n: usize, digits: &mut [u8; DECIMAL_DIGITS]) -> usize {
    let mut first = DECIMAL_DIGITS;
    for digit in digits.iter_mut().rev() {
        *digit = b'0' + (n % 10) as u8;
        n /= 10;
        first -= 1;
        if n == 0 {
            break;
        }
    }
    first
}

/// Writes `bits` as eight lower-case hexadecimal digits.
pub fn write_hex<O: Output + ?Sized>(out: &mut O, bits: u32) {
    let mut digits = [0u8; 8];
    for (i, d) in digits.iter_mut().enumerate() {
        let nibble = (bits >> (28 - 4 * i)) & 0xf;
        *d = b"0123456789abcdef"[nibble as usize];
    }
    out.write(&digits);
}

/// One parsed report line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunLine<'a> {
    /// Problem name.
    pub problem: &'a str,
    /// Algorithm name.
    pub algorithm: &'a str,
    /// Objective evaluations used.
    pub evaluations: usize,
    /// Iterations completed.
    pub iterations: usize,
    /// How the run ended, as written.
    pub end: &'a str,
    /// θ; the first `dim` entries are meaningful.
    pub theta: [f32; MAX_DIM],
    /// Number of parameters.
    pub dim: usize,
}

/// Parses a `run` line; `None` if it is not one or is malformed.
pub fn parse_run(line: &str) -> Option<RunLine<'_>> {
    let mut words = line.split_whitespace();
    if words.next()? != "run" {
        return None;
    }
    let problem = words.next()?;
    let algorithm = words.next()?;
    let mut field = |key: &str| words.next()?.strip_prefix(key)?.strip_prefix('=');
    let evaluations = field("evaluations")?.parse().ok()?;
    let iterations = field("iterations")?.parse().ok()?;
    let end = field("end")?;
    let mut theta = [0.0; MAX_DIM];
    let mut dim = 0;
    for hex in field("theta")?.split(',') {
        *theta.get_mut(dim)? = f32::from_bits(u32::from_str_radix(hex, 16).ok()?);
        dim += 1;
    }
    Some(RunLine {
        problem,
        algorithm,
        evaluations,
        iterations,
        end,
        theta,
        dim,
    })
}

/// Largest allowed |a − b| / max(1, |a|, |b|) between corresponding parameters.
///
/// The same code on two IEEE 754 targets gives bit-identical `f32` results unless an
/// operation rounds differently on one of them (a fused multiply-add, a library
/// function's last bit). Such a difference starts at one ulp (6e-8 relative) and may grow
/// over a run; 1e-4 leaves room for that while catching any divergence of the
/// trajectories. The floor of 1 makes the test absolute for parameters near an optimum
/// at 0, whose relative differences mean nothing.
pub const TOLERANCE: f32 = 1e-4;

/// How well two reports agree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Agreement {
    /// Runs compared.
    pub runs: usize,
    /// Largest scaled parameter difference seen (see [`TOLERANCE`]).
    pub max_deviation: f32,
    /// Every parameter equal bit for bit.
    pub bit_identical: bool,
}

/// Why two reports disagree.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Mismatch {
    /// A line starting with `run ` that does not parse, numbered from 1.
    Malformed {
        /// `true` in the candidate, `false` in the reference.
        candidate: bool,
        /// The line's number in its report.
        line: usize,
    },
    /// The reports have different numbers of runs.
    RunCount {
        /// Runs in the reference.
        reference: usize,
        /// Runs in the candidate.
        candidate: usize,
    },
    /// A run's name, counts, ending or dimension differ.
    Field {
        /// The 0-based run.
        run: usize,
        /// The field that differs.
        field: &'static str,
    },
    /// A parameter differs by more than [`TOLERANCE`].
    Parameter {
        /// The 0-based run.
        run: usize,
        /// The 0-based parameter.
        index: usize,
        /// Its value in the reference.
        reference: f32,
        /// Its value in the candidate.
        candidate: f32,
    },
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Mismatch::Malformed { candidate, line } => {
                let which = if candidate { "candidate" } else { "reference" };
                write!(f, "malformed run line {line} in the {which}")
            }
            Mismatch::RunCount {
                reference,
                candidate,
            } => write!(f, "{candidate} runs, the reference has {reference}"),
            Mismatch::Field { run, field } => write!(f, "run {run}: {field} differs"),
            Mismatch::Parameter {
                run,
                index,
                reference,
                candidate,
            } => write!(
                f,
                "run {run}: θ[{index}] = {candidate:e}, the reference has {reference:e}"
            ),
        }
    }
}

impl core::error::Error for Mismatch {}

/// Compares the `run` lines of a candidate report (the firmware's) with a reference
/// report (the host's), in order.
///
/// # Errors
/// The first [`Mismatch`] found.
pub fn compare(reference: &str, candidate: &str) -> Result<Agreement, Mismatch> {
    let (n_ref, n_cand) = (
        runs(reference, false).count(),
        runs(candidate, true).count(),
    );
    if n_ref != n_cand {
        return Err(Mismatch::RunCount {
            reference: n_ref,
            candidate: n_cand,
        });
    }
    let mut agreement = Agreement {
        runs: n_ref,
        max_deviation: 0.0,
        bit_identical: true,
    };
    for (run, (r, c)) in runs(reference, false)
        .zip(runs(candidate, true))
        .enumerate()
    {
        let (r, c) = (r?, c?);
        let field = |field| Err(Mismatch::Field { run, field });
        if r.problem != c.problem {
            return field("problem");
        }
        if r.algorithm != c.algorithm {
            return field("algorithm");
        }
        if r.evaluations != c.evaluations {
            return field("evaluations");
        }
        if r.iterations != c.iterations {
            return field("iterations");
        }
        if r.end != c.end {
            return field("end");
        }
        if r.dim != c.dim {
            return field("dimension");
        }
        for index in 0..r.dim {
            let (a, b) = (r.theta[index], c.theta[index]);
            agreement.bit_identical &= a.to_bits() == b.to_bits();
            let deviation = scaled_difference(a, b);
            if deviation.is_nan() || deviation > TOLERANCE {
                return Err(Mismatch::Parameter {
                    run,
                    index,
                    reference: a,
                    candidate: b,
                });
            }
            agreement.max_deviation = agreement.max_deviation.max(deviation);
        }
    }
    Ok(agreement)
}

/// |a − b| / max(1, |a|, |b|); 0 for equal bits (so equal NaNs agree), NaN if exactly
/// one is NaN.
fn scaled_difference(a: f32, b: f32) -> f32 {
    if a.to_bits() == b.to_bits() {
        return 0.0;
    }
    let scale = 1f32.max(a.abs()).max(b.abs());
    (a - b).abs() / scale
}

/// The `run` lines of `text`, parsed; malformed ones as [`Mismatch::Malformed`].
fn runs(text: &str, candidate: bool) -> impl Iterator<Item = Result<RunLine<'_>, Mismatch>> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| line.starts_with("run "))
        .map(move |(i, line)| {
            parse_run(line).ok_or(Mismatch::Malformed {
                candidate,
                line: i + 1,
            })
        })
}

#[cfg(test)]
mod tests {
    use std::string::String;
    use std::vec::Vec;

    use super::*;

    fn render(f: impl FnOnce(&mut dyn FnMut(&[u8]))) -> String {
        let mut bytes = Vec::new();
        f(&mut |b: &[u8]| bytes.extend_from_slice(b));
        String::from_utf8(bytes).unwrap()
    }

    fn result(theta: [f32; MAX_DIM], dim: usize) -> RunResult {
        RunResult {
            theta,
            dim,
            evaluations: 3008,
            iterations: 41,
            end: End::Finished(Termination::MaxEvaluations),
        }
    }

    #[test]
    fn both_digit_methods_agree() {
        let mut n = 1usize;
        let numbers = core::iter::from_fn(|| {
            n = n.checked_mul(3)?;
            Some(n)
        });
        for n in [0, 1, 9, 10, 11, 99, 100, 101, usize::MAX - 1, usize::MAX]
            .into_iter()
            .chain(numbers)
            .chain((0..100_000).step_by(7))
        {
            let (mut a, mut b) = ([b'0'; DECIMAL_DIGITS], [b'0'; DECIMAL_DIGITS]);
            let (i, j) = (
                decimal_digits_by_subtraction(n, &mut a),
                decimal_digits_by_division(n, &mut b),
            );
            assert_eq!((&a[i..], i), (&b[j..], j), "{n}");
            assert_eq!(std::str::from_utf8(&a[i..]).unwrap(), std::format!("{n}"));
        }
    }

    #[test]
    fn numbers_print_exactly() {
        assert_eq!(render(|o| write_decimal(o, 0)), "0");
        for n in [7, 10, 99, 3008, 1_000_000] {
            assert_eq!(render(|o| write_decimal(o, n)), std::format!("{n}"));
        }
        assert_eq!(
            render(|o| write_decimal(o, usize::MAX)),
            std::format!("{}", usize::MAX)
        );
        assert_eq!(render(|o| write_hex(o, 0x3a03_126f)), "3a03126f");
        assert_eq!(render(|o| write_hex(o, 7)), "00000007");
    }

    #[test]
    fn lines_parse_back() {
        let r = result([5e-4, -4e-4], 2);
        let line = render(|o| write_run(o, "QUAD", "OurHVPA", &r));
        assert_eq!(
            line,
            "run QUAD OurHVPA evaluations=3008 iterations=41 end=max-evaluations \
             theta=3a03126f,b9d1b717\n"
        );
        let parsed = parse_run(&line).unwrap();
        assert_eq!((parsed.problem, parsed.algorithm), ("QUAD", "OurHVPA"));
        assert_eq!((parsed.evaluations, parsed.iterations), (3008, 41));
        assert_eq!((parsed.end, parsed.dim), ("max-evaluations", 2));
        assert_eq!(parsed.theta, r.theta);
        assert_eq!(parse_run("stack peak=512"), None);
        assert_eq!(parse_run("run QUAD OurHVPA evaluations=x"), None);
    }

    #[test]
    fn failures_are_named() {
        let mut r = result([1.0, 0.0], 1);
        r.end = End::Failed {
            iteration: 3,
            error: Error::NonFiniteObjective { sample: 0 },
        };
        let line = render(|o| write_run(o, "P", "A", &r));
        assert_eq!(
            parse_run(&line).unwrap().end,
            "failed-at-3-non-finite-objective"
        );
    }

    #[test]
    fn comparison_tolerates_rounding_and_catches_divergence() {
        let report = |x: f32| {
            render(|o| {
                write_run(o, "QUAD", "FR22", &result([x, 2.0], 2));
                o(b"stack peak=100\n");
            })
        };
        let reference = report(1.0);
        let same = compare(&reference, &report(1.0)).unwrap();
        assert!(same.bit_identical && same.max_deviation == 0.0 && same.runs == 1);
        let close = compare(&reference, &report(1.0 + 1e-6)).unwrap();
        assert!(!close.bit_identical && close.max_deviation > 0.0);
        assert!(matches!(
            compare(&reference, &report(1.001)),
            Err(Mismatch::Parameter {
                run: 0,
                index: 0,
                ..
            })
        ));
        assert!(matches!(
            compare(&reference, &report(f32::NAN)),
            Err(Mismatch::Parameter { .. })
        ));
        assert!(matches!(
            compare(&reference, ""),
            Err(Mismatch::RunCount {
                reference: 1,
                candidate: 0
            })
        ));
        let renamed = reference.replace("FR22", "OurHVPA");
        assert_eq!(
            compare(&reference, &renamed),
            Err(Mismatch::Field {
                run: 0,
                field: "algorithm"
            })
        );
        assert_eq!(
            compare(&reference, "run QUAD\n"),
            Err(Mismatch::Malformed {
                candidate: true,
                line: 1
            })
        );
    }
}
