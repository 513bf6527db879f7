//! The counting wrapper every method evaluates through, and the trace it records, so
//! that every method is measured identically.
//!
//! Each evaluation is numbered 1, 2, … in the order the method asks for it. The point
//! is first clamped into the problem's bounds (a no-op for methods that stay inside);
//! f and the parameter error are those of the clamped point. The method sees the value
//! [`Problem::observe`] gives (f itself unless the problem is noisy); the trace judges
//! the noiseless f, at the points where the method saw a value: an evaluation that
//! failed (NaN or ±∞ seen where f is finite) finds nothing. Whenever f − f* falls below the best so far, the trace records
//! (evaluation number, wall time since the run began, f − f*, parameter error).
//! Evaluations after the budget still return f (so a method can finish its iteration)
//! but are not recorded or counted.
//!
//! A batch (or a CMA-ES generation) is spread over threads only when its expected work,
//! rows × the last measured time of one evaluation, is at least [`PARALLEL_WORK`]; below
//! that, handing it to rayon's pool costs more than it saves, and how much more depends
//! on whether the run itself is on a pool thread (`--jobs` above 1) or not. Values and
//! counts never depend on the choice, only the times do.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use hodr_core::{Batch, NoiseSeed, Objective};
use rayon::prelude::*;
use serde::Serialize;

use super::problem::Problem;

/// The least expected work of a batch, seconds, for it to be evaluated in parallel: a
/// few times what it takes to wake rayon's pool from outside it and collect the results.
pub const PARALLEL_WORK: f64 = 2e-4;

/// A new best point of a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Event {
    /// 1-based number of the evaluation that found it.
    pub evaluation: usize,
    /// Wall time from the run's start to that evaluation's count, seconds (a batch's
    /// rows are counted once the whole batch has returned).
    pub time: f64,
    /// f − f* there.
    pub f: f64,
    /// Its parameter error.
    pub param_error: f64,
}

/// The record of one run.
#[derive(Clone, Debug, Serialize)]
pub struct Trace {
    /// Each new best, in order.
    pub events: Vec<Event>,
    /// Evaluations counted (at most the budget).
    pub evaluations: usize,
    /// The parameter error of the start θ₀ (clamped into the bounds).
    pub initial_error: f64,
    /// Wall time of the run, seconds.
    pub time: f64,
    /// Why the run ended before its budget, if it did and said why (e.g. the method's own
    /// convergence test, or an error).
    pub stopped: Option<String>,
}

impl Trace {
    /// The first new best with f − f* ≤ `target`, if any.
    pub fn reaching_f(&self, target: f64) -> Option<Event> {
        self.events.iter().find(|e| e.f <= target).copied()
    }

    /// The first new best with parameter error at most (1 − `reduction`) × the start's
    /// (e.g. 0.99: a 99 % reduction), if any.
    pub fn reaching_param(&self, reduction: f64) -> Option<Event> {
        let goal = (1.0 - reduction) * self.initial_error;
        self.events.iter().find(|e| e.param_error <= goal).copied()
    }

    /// The best f − f* of the run (+∞ when nothing was evaluated).
    pub fn best(&self) -> f64 {
        self.events.last().map_or(f64::INFINITY, |e| e.f)
    }
}

/// Evaluations so far per point (by its bits) of a run on a noisy problem, shared by
/// the threads that evaluate it.
type Repeats = Arc<Mutex<HashMap<Vec<u64>, u64>>>;

/// A problem's f at points clamped into its bounds, shareable between threads; on a
/// noisy problem it counts each point's evaluations, so that a repeat draws fresh noise.
/// [`Counter`]'s batches number their repeats in the batch's order before evaluating
/// in parallel; CMA-ES's parallel generations, whose points never coincide, count them
/// as they come.
#[derive(Clone, Debug)]
pub struct Clamped<'p> {
    problem: &'p Problem,
    repeats: Option<Repeats>,
}

impl Clamped<'_> {
    /// x clamped into the problem's bounds.
    pub fn point(&self, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        if let Some(b) = &self.problem.bounds {
            b.clamp(&mut y);
        }
        y
    }

    /// What the method sees at x clamped into the bounds ([`Problem::observe`]).
    pub fn value(&self, x: &[f64]) -> f64 {
        let y = self.point(x);
        let repeat = self.next_repeat(&y);
        self.problem.observe(&y, repeat)
    }

    /// What the method sees at x clamped into the bounds on noise seed `seed`
    /// ([`Problem::observe_on`]).
    pub fn value_on(&self, x: &[f64], seed: NoiseSeed) -> f64 {
        let y = self.point(x);
        let repeat = self.next_repeat(&y);
        self.problem.observe_on(&y, seed, repeat)
    }

    /// How many times the run evaluated the clamped point y before, counting this
    /// evaluation (0 on a problem without noise, which does not count).
    fn next_repeat(&self, y: &[f64]) -> u64 {
        self.repeats.as_ref().map_or(0, |r| {
            let key = y.iter().map(|v| v.to_bits()).collect();
            let mut seen = r.lock().unwrap_or_else(PoisonError::into_inner);
            let count = seen.entry(key).or_insert(0);
            *count += 1;
            *count - 1
        })
    }
}

/// The counting wrapper around a problem's f for one run.
pub struct Counter<'p> {
    problem: &'p Problem,
    repeats: Option<Repeats>,
    budget: usize,
    count: usize,
    best: f64,
    events: Vec<Event>,
    start: Instant,
    /// The wall time of one evaluation, seconds, as last measured on one thread (None
    /// before the first).
    cost: Option<f64>,
}

impl<'p> Counter<'p> {
    /// A fresh counter for a run of `budget` evaluations; the run's clock starts here.
    pub fn new(problem: &'p Problem, budget: usize) -> Self {
        Counter {
            problem,
            repeats: problem.is_noisy().then(Repeats::default),
            budget,
            count: 0,
            best: f64::INFINITY,
            events: Vec::new(),
            start: Instant::now(),
            cost: None,
        }
    }

    /// Whether a batch of `rows` evaluations is worth spreading over threads: its
    /// expected work, `rows` × the last measured cost of one evaluation, is at least
    /// [`PARALLEL_WORK`]. False until a cost has been measured, so the first batch runs
    /// on the caller's thread and measures it.
    pub fn parallel_pays(&self, rows: usize) -> bool {
        rows >= 2 && self.cost.is_some_and(|c| c * rows as f64 >= PARALLEL_WORK)
    }

    /// Notes `total`, the time `rows` evaluations took summed over the threads that ran
    /// them, as the cost of one evaluation (the mean); nothing when `rows` is 0.
    pub fn note_cost(&mut self, total: Duration, rows: usize) {
        if rows > 0 {
            self.cost = Some(total.as_secs_f64() / rows as f64);
        }
    }

    /// f without counting, for evaluation on any thread; pair each value with
    /// [`Counter::record`] in the method's order.
    pub fn clamped(&self) -> Clamped<'p> {
        Clamped {
            problem: self.problem,
            repeats: self.repeats.clone(),
        }
    }

    /// Counts one evaluation of x (unclamped, as the method asked) that the method saw
    /// as `seen` ([`Clamped::value`]); a noisy problem's run is judged on f there, unless
    /// `seen` is not finite (a failed evaluation finds nothing).
    pub fn record(&mut self, x: &[f64], seen: f64) {
        if self.count >= self.budget {
            return;
        }
        self.count += 1;
        let y = self.clamped().point(x);
        let f = if self.problem.is_noisy() && seen.is_finite() {
            self.problem.value(&y)
        } else {
            seen
        };
        let gap = f - self.problem.f_opt;
        if gap < self.best {
            self.best = gap;
            self.events.push(Event {
                evaluation: self.count,
                time: self.elapsed(),
                f: gap,
                param_error: self.problem.param_error(&y),
            });
        }
    }

    /// Evaluates and counts x.
    pub fn evaluate(&mut self, x: &[f64]) -> f64 {
        let clock = Instant::now();
        let f = self.clamped().value(x);
        self.note_cost(clock.elapsed(), 1);
        self.record(x, f);
        f
    }

    /// Evaluates and counts x on noise seed `seed` ([`Clamped::value_on`]).
    pub fn evaluate_on(&mut self, x: &[f64], seed: NoiseSeed) -> f64 {
        let clock = Instant::now();
        let f = self.clamped().value_on(x, seed);
        self.note_cost(clock.elapsed(), 1);
        self.record(x, f);
        f
    }

    /// Evaluations counted so far.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Wall time since the counter was made (the run's start), seconds.
    pub fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    /// True once the budget is used.
    pub fn exhausted(&self) -> bool {
        self.count >= self.budget
    }

    /// The trace of the run so far, its wall time the counter's clock, with the start's
    /// parameter error and stopping reason supplied by the runner.
    pub fn into_trace(self, initial_error: f64, stopped: Option<String>) -> Trace {
        Trace {
            time: self.elapsed(),
            events: self.events,
            evaluations: self.count,
            initial_error,
            stopped,
        }
    }
}

/// hodr-core's objective interface: single points and batches, a batch evaluated in
/// parallel (rayon) when that pays ([`Counter::parallel_pays`]) and counted in batch
/// order either way. A rendered problem
/// ([`Observation::Seeded`](super::problem::Observation::Seeded)) renders each point on
/// the seed it comes with and says it is not deterministic; every other problem is a
/// function of θ alone (an unseeded noisy one draws its noise from θ and the repeat).
impl Objective<f64> for Counter<'_> {
    fn evaluate(&mut self, theta: &[f64], seed: NoiseSeed) -> f64 {
        Counter::evaluate_on(self, theta, seed)
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) {
        // Repeats are numbered in the batch's order, so that two rows at one point draw
        // the same noise whichever thread comes first.
        let f = self.clamped();
        let points: Vec<(Vec<f64>, u64, NoiseSeed)> = (0..out.len())
            .map(|k| {
                let y = f.point(batch.point(k));
                let repeat = f.next_repeat(&y);
                (y, repeat, batch.seed(k))
            })
            .collect();
        let problem = self.problem;
        let evaluate = |(v, (y, repeat, seed)): (&mut f64, &(Vec<f64>, u64, NoiseSeed))| {
            *v = problem.observe_on(y, *seed, *repeat);
        };
        let work = if self.parallel_pays(out.len()) {
            // Each row timed on its thread: the sum is the work, not the wall time.
            out.par_iter_mut()
                .zip(&points)
                .map(|row| {
                    let clock = Instant::now();
                    evaluate(row);
                    clock.elapsed()
                })
                .sum()
        } else {
            let clock = Instant::now();
            out.iter_mut().zip(&points).for_each(evaluate);
            clock.elapsed()
        };
        self.note_cost(work, out.len());
        for (k, &v) in out.iter().enumerate() {
            self.record(batch.point(k), v);
        }
    }

    fn deterministic(&self) -> bool {
        !self.problem.is_seeded()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::suite::noisy;

    /// A batch is spread over threads only once a measured cost says its work pays
    /// for it, and the cost follows the latest measurement.
    #[test]
    fn a_batch_runs_in_parallel_only_when_its_measured_work_pays() {
        let problem = noisy::problem(101, 2, 1, 10);
        let mut counter = Counter::new(&problem, 100);
        assert!(!counter.parallel_pays(1000), "no cost measured yet");
        let per_row = PARALLEL_WORK / 10.0;
        counter.note_cost(std::time::Duration::from_secs_f64(3.0 * per_row), 3);
        assert!(!counter.parallel_pays(9));
        assert!(counter.parallel_pays(11));
        assert!(!counter.parallel_pays(1), "one row never pays");
        counter.note_cost(std::time::Duration::ZERO, 0);
        assert!(counter.parallel_pays(11), "no rows: the cost stands");
        counter.evaluate(&[0.5, -0.5]);
        assert!(
            !counter.parallel_pays(11),
            "a microsecond function: sequential"
        );
    }

    /// A batch that evaluates one point of a noisy problem many times draws the same
    /// noise for each row on one thread or two: its repeats are numbered in its order.
    #[test]
    fn a_batch_numbers_its_repeats_in_its_order_whatever_the_threads() {
        let problem = noisy::problem(101, 2, 1, 10);
        let x = [0.5, -0.5];
        let rows = 32;
        let points: Vec<f64> = x.iter().copied().cycle().take(2 * rows).collect();
        let seeds = vec![0; rows];
        let batch = Batch::new(&points, &seeds, 2).unwrap();
        let run = |threads: usize| {
            let mut counter = Counter::new(&problem, 100);
            // A measured cost that makes the batch worth spreading over the threads.
            counter.note_cost(std::time::Duration::from_secs(1), 1);
            assert!(counter.parallel_pays(rows));
            let mut out = vec![0.0; rows];
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| counter.evaluate_batch(&batch, &mut out));
            out
        };
        let in_order: Vec<f64> = (0..rows as u64).map(|r| problem.observe(&x, r)).collect();
        assert_eq!(run(1), in_order);
        assert_eq!(run(2), in_order);
    }
}
