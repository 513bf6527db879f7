//! Error-against-time metrics: when does a run first reduce its error by 90, 99 and
//! 99.9 % from the start, and the medians of those times over seeds.

/// Error reductions reported: 90 %, 99 %, 99.9 %.
pub const REDUCTIONS: [f64; 3] = [0.9, 0.99, 0.999];

/// One recorded point of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Wall time since the start of the run, seconds.
    pub time: f64,
    /// Objective evaluations used.
    pub evaluations: usize,
    /// The error (e.g. parameter distance to the optimum).
    pub error: f64,
}

/// When a run first reached an error reduction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reached {
    /// Seconds.
    pub time: f64,
    /// Evaluations.
    pub evaluations: usize,
}

/// The first sample whose error is at most (1 − `reduction`) × the first sample's
/// error, or `None` if the run never gets there. A run that starts at zero error has
/// reached every reduction at its start. Non-finite errors never count as reached.
pub fn first_reaching(samples: &[Sample], reduction: f64) -> Option<Reached> {
    let start = samples.first()?.error;
    let goal = (1.0 - reduction) * start;
    samples
        .iter()
        .find(|s| s.error.is_finite() && s.error <= goal)
        .map(|s| Reached {
            time: s.time,
            evaluations: s.evaluations,
        })
}

/// The median of per-seed values where `None` means "never": never counts as +∞, so the
/// median is `None` ("—") when half or more of the runs never got there. For an even
/// count the upper median is used, so the statement "at least half the runs reached it
/// by then" holds.
pub fn median(values: &[Option<f64>]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let mut v: Vec<f64> = values.iter().map(|x| x.unwrap_or(f64::INFINITY)).collect();
    v.sort_by(f64::total_cmp);
    let m = v[v.len() / 2];
    m.is_finite().then_some(m)
}

/// Formats an optional median: seconds with 3 significant digits in a fitting unit,
/// "—" when never reached.
pub fn format_seconds(t: Option<f64>) -> String {
    match t {
        None => "—".into(),
        Some(t) if t < 1e-3 => format!("{:.3} ms", t * 1e3),
        Some(t) if t < 1.0 => format!("{:.1} ms", t * 1e3),
        Some(t) => format!("{t:.2} s"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(errors: &[f64]) -> Vec<Sample> {
        errors
            .iter()
            .enumerate()
            .map(|(k, &e)| Sample {
                time: k as f64 * 0.5,
                evaluations: 10 * k,
                error: e,
            })
            .collect()
    }

    #[test]
    fn thresholds_on_hand_made_traces() {
        let t = trace(&[10.0, 5.0, 0.9, 2.0, 0.05, 0.001]);
        assert_eq!(
            first_reaching(&t, 0.9),
            Some(Reached {
                time: 1.0,
                evaluations: 20
            })
        );
        assert_eq!(
            first_reaching(&t, 0.99),
            Some(Reached {
                time: 2.0,
                evaluations: 40
            })
        );
        assert_eq!(
            first_reaching(&t, 0.999),
            Some(Reached {
                time: 2.5,
                evaluations: 50
            })
        );
        let never = trace(&[1.0, 0.5, f64::NAN, 0.2]);
        assert_eq!(first_reaching(&never, 0.9), None);
        assert_eq!(first_reaching(&[], 0.9), None);
        let zero = trace(&[0.0, 1.0]);
        assert_eq!(first_reaching(&zero, 0.999).map(|r| r.evaluations), Some(0));
    }

    #[test]
    fn medians_count_never_as_infinite() {
        assert_eq!(median(&[Some(3.0), Some(1.0), Some(2.0)]), Some(2.0));
        assert_eq!(median(&[Some(3.0), None, Some(1.0)]), Some(3.0));
        assert_eq!(median(&[None, None, Some(1.0)]), None);
        assert_eq!(
            median(&[Some(1.0), Some(2.0), Some(3.0), Some(4.0)]),
            Some(3.0)
        );
        assert_eq!(median(&[]), None);
        assert_eq!(format_seconds(None), "—");
    }
}
