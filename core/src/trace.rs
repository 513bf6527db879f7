//! A fixed-memory convergence trace.
//!
//! Keeps the first point and the most recent `N` points (a ring buffer from heapless), so
//! error reduction from the start can always be computed and memory never grows. A host
//! that wants every point records them itself from [`crate::optim::StepReport`]s.

use heapless::HistoryBuf;

use crate::optim::StepReport;
use crate::optim::vector::distance;
use crate::real::Real;

/// One point of a trace.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracePoint<T> {
    /// Iterations completed.
    pub iteration: usize,
    /// Objective evaluations used.
    pub evaluations: usize,
    /// The caller's clock.
    pub time: T,
    /// The loss estimate of the iteration, if any.
    pub loss: Option<T>,
    /// ‖θ − θ*‖ when the caller knows θ*.
    pub distance: Option<T>,
}

impl<T: Real> TracePoint<T> {
    /// The point describing `report` at caller time `time`, with θ's distance to
    /// `optimum` when given (lengths must match; otherwise no distance).
    pub fn from_report(
        report: &StepReport<T>,
        time: T,
        theta: &[T],
        optimum: Option<&[T]>,
    ) -> Self {
        TracePoint {
            iteration: report.iteration,
            evaluations: report.evaluations,
            time,
            loss: report.loss,
            distance: optimum
                .filter(|o| o.len() == theta.len())
                .map(|o| distance(theta, o)),
        }
    }

    /// The starting point (iteration 0) of a run at θ₀.
    pub fn start(time: T, theta: &[T], optimum: Option<&[T]>) -> Self {
        TracePoint {
            iteration: 0,
            evaluations: 0,
            time,
            loss: None,
            distance: optimum
                .filter(|o| o.len() == theta.len())
                .map(|o| distance(theta, o)),
        }
    }
}

/// The first and the latest `N` trace points.
#[derive(Clone, Debug)]
pub struct Trace<T, const N: usize> {
    first: Option<TracePoint<T>>,
    recent: HistoryBuf<TracePoint<T>, N>,
    recorded: usize,
}

impl<T: Real, const N: usize> Default for Trace<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const N: usize> Trace<T, N> {
    /// An empty trace.
    pub const fn new() -> Self {
        Trace {
            first: None,
            recent: HistoryBuf::new(),
            recorded: 0,
        }
    }

    /// Appends a point; the oldest retained one drops out when `N` are held.
    pub fn record(&mut self, point: TracePoint<T>) {
        if self.first.is_none() {
            self.first = Some(point);
        }
        self.recent.write(point);
        self.recorded += 1;
    }

    /// The first point ever recorded.
    pub fn first(&self) -> Option<&TracePoint<T>> {
        self.first.as_ref()
    }

    /// The latest point.
    pub fn latest(&self) -> Option<&TracePoint<T>> {
        self.recent.recent()
    }

    /// The retained points, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = &TracePoint<T>> {
        self.recent.oldest_ordered()
    }

    /// Points recorded in total (retained or not).
    pub fn recorded(&self) -> usize {
        self.recorded
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_first_and_latest() {
        let mut t = Trace::<f64, 3>::new();
        for k in 0..10 {
            t.record(TracePoint {
                iteration: k,
                evaluations: 2 * k,
                time: k as f64,
                loss: None,
                distance: None,
            });
        }
        assert_eq!(t.first().unwrap().iteration, 0);
        assert_eq!(t.latest().unwrap().iteration, 9);
        let mut kept = [0usize; 3];
        for (slot, p) in kept.iter_mut().zip(t.iter()) {
            *slot = p.iteration;
        }
        assert_eq!(kept, [7, 8, 9]);
        assert_eq!(t.iter().count(), 3);
        assert_eq!(t.recorded(), 10);
    }
}
