//! Metrics over seeds: evaluations to targets, success rates, wall time, and the
//! per-family aggregate against a reference method.
//!
//! * Targets: f − f* ≤ 10ᵏ for k = 1, 0, −1, …, −8 ([`F_TARGETS`]), and a 99 % reduction
//!   of the parameter error from the start's ([`PARAM_REDUCTION`]), all judged on the
//!   best point so far ([`super::trace`]).
//! * Per problem, method and target: the median over seeds of the evaluations to reach
//!   it, a run that never does counting as +∞ — so the median exists only when at least
//!   half the runs got there (upper median for an even count: "at least half the runs
//!   reached it by then") — the median wall time to reach it by the same rule, and the
//!   number of runs that did.
//! * Per family and method: the geometric mean over problems of (median evaluations /
//!   the reference method's), each problem taken at the hardest f-target both medians
//!   reach (problems where they share none are left out and counted separately); the
//!   runs reaching the final target 10⁻⁸; the fraction of (problem, seed, f-target)
//!   triples reached; the median wall time of a run. Beside the median ratio, the same
//!   geometric mean of median wall-time ratios at the same targets (a method's time to a
//!   target counts its own work as well as the objective's, which the suite's functions
//!   make cheap: a renderer's evaluations would move it towards the evaluations'), and the
//!   geometric mean of aRT ratios, each problem at the hardest f-target both methods
//!   reach in at least one run: a median says nothing about a problem where one method
//!   succeeds in 2 runs of 5 and the other in 4, and its hardest common target may be one
//!   the start already meets; aRT counts the failures.
//! * aRT (average running time, as the COCO platform reports it): the evaluations all
//!   runs spent — a successful run's evaluations to the target, a failed run's whole
//!   run — divided by the successful runs: the expected cost of reaching the target by
//!   restarting the method from fresh seeds until it does.

use super::methods::Method;
use super::problem::{Family, Problem};
use super::trace::{Event, Trace};
use crate::metrics::median;

/// The exponents k of the f-targets 10ᵏ, easiest first.
pub const F_TARGETS: [i32; 10] = [1, 0, -1, -2, -3, -4, -5, -6, -7, -8];

/// The parameter-error reduction reported beside the f-targets.
pub const PARAM_REDUCTION: f64 = 0.99;

/// Labels of the targets, f-targets then the parameter target, as in tables and CSV.
pub fn target_labels() -> Vec<String> {
    F_TARGETS
        .iter()
        .map(|k| format!("1e{k}"))
        .chain([format!("param{}", (PARAM_REDUCTION * 100.0).round())])
        .collect()
}

/// One finished run.
#[derive(Clone, Debug)]
pub struct Run {
    /// Index of the problem in the suite's list.
    pub problem: usize,
    /// The method.
    pub method: Method,
    /// Seed index (0-based; the run seed derives from it and the problem's name).
    pub seed: usize,
    /// What the run recorded.
    pub trace: Trace,
}

impl Run {
    /// The new best that first reached each target, in [`target_labels`] order.
    pub fn reached(&self) -> Vec<Option<Event>> {
        F_TARGETS
            .iter()
            .map(|&k| self.trace.reaching_f(10f64.powi(k)))
            .chain([self.trace.reaching_param(PARAM_REDUCTION)])
            .collect()
    }
}

/// One target's result over seeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Median evaluations (a miss counts as +∞); `None` when half or more missed.
    pub median: Option<f64>,
    /// Median wall time to the target, seconds, by the same rule.
    pub time: Option<f64>,
    /// Runs that reached the target.
    pub successes: usize,
    /// aRT: evaluations of all runs (to the target, or all of a failed run's) per
    /// success; `None` without a success.
    pub art: Option<f64>,
    /// Runs.
    pub runs: usize,
}

/// One problem × method over its seeds.
#[derive(Clone, Debug)]
pub struct Row {
    /// Index of the problem.
    pub problem: usize,
    /// The method.
    pub method: Method,
    /// One cell per target, in [`target_labels`] order.
    pub cells: Vec<Cell>,
    /// Median wall time of a run, seconds.
    pub median_time: f64,
}

/// The rows of every problem × method that has runs, in problem then `methods` order.
pub fn rows(problems: &[Problem], methods: &[Method], runs: &[Run]) -> Vec<Row> {
    let mut out = Vec::new();
    for p in 0..problems.len() {
        for &m in methods {
            let mine: Vec<&Run> = runs
                .iter()
                .filter(|r| r.problem == p && r.method == m)
                .collect();
            if mine.is_empty() {
                continue;
            }
            let reached: Vec<Vec<Option<Event>>> = mine.iter().map(|r| r.reached()).collect();
            let cells = (0..=F_TARGETS.len())
                .map(|t| {
                    let v: Vec<Option<f64>> = reached
                        .iter()
                        .map(|r| r[t].map(|e| e.evaluation as f64))
                        .collect();
                    let times: Vec<Option<f64>> =
                        reached.iter().map(|r| r[t].map(|e| e.time)).collect();
                    let successes = v.iter().filter(|x| x.is_some()).count();
                    let spent: f64 = v
                        .iter()
                        .zip(&mine)
                        .map(|(x, r)| x.unwrap_or(r.trace.evaluations as f64))
                        .sum();
                    Cell {
                        median: median(&v),
                        time: median(&times),
                        successes,
                        runs: v.len(),
                        art: (successes > 0).then(|| spent / successes as f64),
                    }
                })
                .collect();
            let times: Vec<Option<f64>> = mine.iter().map(|r| Some(r.trace.time)).collect();
            out.push(Row {
                problem: p,
                method: m,
                cells,
                median_time: median(&times).unwrap_or(f64::NAN),
            });
        }
    }
    out
}

/// One family × method aggregate.
#[derive(Clone, Debug)]
pub struct FamilyRow {
    /// The family.
    pub family: Family,
    /// The method.
    pub method: Method,
    /// Problems with runs of this method.
    pub problems: usize,
    /// Median evaluations over the reference's, at the hardest target both medians reach.
    pub ratio: Ratio,
    /// aRT over the reference's, at the hardest target both reach in some run.
    pub art_ratio: Ratio,
    /// Median wall time to the target over the reference's, at the targets of `ratio`.
    pub time_ratio: Ratio,
    /// Runs reaching the final target 10⁻⁸.
    pub final_successes: usize,
    /// Runs.
    pub runs: usize,
    /// (problem, seed, f-target) triples reached.
    pub targets_reached: usize,
    /// (problem, seed, f-target) triples.
    pub targets: usize,
    /// Median wall time of a run, seconds.
    pub median_time: f64,
}

/// A geometric mean over problems of per-problem ratios, and how many problems had a
/// target to compare at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ratio {
    /// exp(mean of the ln ratios); `None` when no problem entered.
    pub mean: Option<f64>,
    /// Problems that entered the mean.
    pub problems: usize,
}

impl Ratio {
    fn of(logs: &[f64]) -> Ratio {
        Ratio {
            mean: (!logs.is_empty()).then(|| (logs.iter().sum::<f64>() / logs.len() as f64).exp()),
            problems: logs.len(),
        }
    }
}

/// What a ratio compares: median evaluations, median wall time or aRT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Statistic {
    /// [`Cell::median`].
    Median,
    /// [`Cell::time`]: it exists exactly where [`Cell::median`] does (both count the
    /// same runs as misses), so its ratios are taken at the same targets.
    Time,
    /// [`Cell::art`].
    Art,
}

impl Statistic {
    fn of(self, cell: &Cell) -> Option<f64> {
        match self {
            Statistic::Median => cell.median,
            Statistic::Time => cell.time,
            Statistic::Art => cell.art,
        }
    }
}

/// ln(`statistic` of each row ÷ that of `reference` on the same problem), each at the
/// hardest f-target where both have it; problems without such a target are left out.
fn log_ratios(mine: &[&Row], rows: &[Row], reference: Method, statistic: Statistic) -> Vec<f64> {
    let mut logs = Vec::new();
    for r in mine {
        let Some(base) = rows
            .iter()
            .find(|b| b.problem == r.problem && b.method == reference)
        else {
            continue;
        };
        let common = (0..F_TARGETS.len())
            .rev()
            .find_map(|t| Some((statistic.of(&r.cells[t])?, statistic.of(&base.cells[t])?)));
        // A time below the clock's resolution has no ratio.
        if let Some((a, b)) = common.filter(|&(a, b)| a > 0.0 && b > 0.0) {
            logs.push((a / b).ln());
        }
    }
    logs
}

/// One group of problems (a family, one BBOB or noisy function across its dimensions
/// and instances, or one failure rate of the failing family) and the geometric-mean ratios of `method`'s median evaluations and median
/// wall time to each other method's, with the number of problems that entered each.
#[derive(Clone, Debug)]
pub struct PairRow {
    /// The group's name: a family, `bbob-fNN`, `noisy-fNNN` or `failing-pNN`.
    pub group: String,
    /// Each other method and the geometric-mean ratio of evaluations against it.
    pub ratios: Vec<(Method, Ratio)>,
    /// Each other method and the geometric-mean ratio of wall time against it.
    pub time_ratios: Vec<(Method, Ratio)>,
}

/// `method` against every other method of `methods`, per family and per BBOB function.
pub fn pairwise(
    problems: &[Problem],
    methods: &[Method],
    method: Method,
    rows: &[Row],
) -> Vec<PairRow> {
    let group_of = |p: &Problem| match p.family {
        Family::Bbob | Family::Noisy | Family::Failing => {
            p.name.split('-').take(2).collect::<Vec<_>>().join("-")
        }
        f => f.to_string(),
    };
    let mut groups: Vec<String> = Family::ALL.iter().map(|f| f.to_string()).collect();
    for p in problems {
        let g = group_of(p);
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    let mut out = Vec::new();
    for g in groups {
        let in_group = |r: &&Row| {
            let p = &problems[r.problem];
            r.method == method && (group_of(p) == g || p.family.to_string() == g)
        };
        let mine: Vec<&Row> = rows.iter().filter(in_group).collect();
        if mine.is_empty() {
            continue;
        }
        let against = |statistic| {
            methods
                .iter()
                .filter(|&&m| m != method)
                .map(|&m| (m, Ratio::of(&log_ratios(&mine, rows, m, statistic))))
                .collect()
        };
        out.push(PairRow {
            group: g,
            ratios: against(Statistic::Median),
            time_ratios: against(Statistic::Time),
        });
    }
    out
}

/// The per-family aggregates of `methods` against `reference`, in family then method
/// order.
pub fn families(
    problems: &[Problem],
    methods: &[Method],
    reference: Method,
    rows: &[Row],
    runs: &[Run],
) -> Vec<FamilyRow> {
    let last = F_TARGETS.len() - 1;
    let mut out = Vec::new();
    for family in Family::ALL {
        for &m in methods {
            let mine: Vec<&Row> = rows
                .iter()
                .filter(|r| r.method == m && problems[r.problem].family == family)
                .collect();
            if mine.is_empty() {
                continue;
            }
            let ratio = Ratio::of(&log_ratios(&mine, rows, reference, Statistic::Median));
            let art_ratio = Ratio::of(&log_ratios(&mine, rows, reference, Statistic::Art));
            let time_ratio = Ratio::of(&log_ratios(&mine, rows, reference, Statistic::Time));
            let my_runs: Vec<&Run> = runs
                .iter()
                .filter(|r| r.method == m && problems[r.problem].family == family)
                .collect();
            let reached: Vec<Vec<Option<Event>>> = my_runs.iter().map(|r| r.reached()).collect();
            let times: Vec<Option<f64>> = my_runs.iter().map(|r| Some(r.trace.time)).collect();
            out.push(FamilyRow {
                family,
                method: m,
                problems: mine.len(),
                ratio,
                art_ratio,
                time_ratio,
                final_successes: reached.iter().filter(|r| r[last].is_some()).count(),
                runs: my_runs.len(),
                targets_reached: reached
                    .iter()
                    .map(|r| r[..F_TARGETS.len()].iter().filter(|x| x.is_some()).count())
                    .sum(),
                targets: my_runs.len() * F_TARGETS.len(),
                median_time: median(&times).unwrap_or(f64::NAN),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::bbob;
    use super::super::trace::{Event, Trace};
    use super::*;

    fn run(seed: usize, evaluations: usize, best: &[(usize, f64)]) -> Run {
        Run {
            problem: 0,
            method: Method::Auto,
            seed,
            trace: Trace {
                events: best
                    .iter()
                    .map(|&(evaluation, f)| Event {
                        evaluation,
                        time: evaluation as f64 * 1e-3,
                        f,
                        param_error: 1.0,
                    })
                    .collect(),
                evaluations,
                initial_error: 1.0,
                time: 0.0,
                stopped: None,
            },
        }
    }

    /// The time ratio compares the median times to the target the evaluations' ratio
    /// is taken at, whatever each method's time per evaluation.
    #[test]
    fn time_ratios_are_taken_at_the_evaluations_targets() {
        let problems = [bbob::problem(1, 2, 1, 10)];
        // Auto reaches 10¹ at evaluation 4 and 10⁰ at 6 in every run, at 10 ms per
        // evaluation; CMA-ES reaches 10¹ at evaluation 8 only, at 1 ms per evaluation.
        let with = |method: Method, per_evaluation: f64, best: &[(usize, f64)]| {
            let mut r = run(0, 10, best);
            r.method = method;
            for e in &mut r.trace.events {
                e.time = e.evaluation as f64 * per_evaluation;
            }
            r
        };
        let runs = [
            with(Method::Auto, 1e-2, &[(4, 5.0), (6, 0.5)]),
            with(Method::CmaEs, 1e-3, &[(8, 5.0)]),
        ];
        let methods = [Method::Auto, Method::CmaEs];
        let rows = rows(&problems, &methods, &runs);
        let families = families(&problems, &methods, Method::CmaEs, &rows, &runs);
        let auto = &families[0];
        assert_eq!(auto.method, Method::Auto);
        let close = |r: Ratio, x: f64| r.mean.is_some_and(|m| (m - x).abs() < 1e-12);
        // At 10¹, the hardest target both reach: 4/8 evaluations, 40 ms/8 ms.
        assert!(close(auto.ratio, 0.5), "{:?}", auto.ratio);
        assert!(close(auto.time_ratio, 5.0), "{:?}", auto.time_ratio);
        let pairs = pairwise(&problems, &methods, Method::Auto, &rows);
        assert!(close(pairs[0].ratios[0].1, 0.5));
        assert!(close(pairs[0].time_ratios[0].1, 5.0));
    }

    /// aRT counts a failed run's whole run; the median counts it as +∞.
    #[test]
    fn art_counts_failed_runs() {
        let problems = [bbob::problem(1, 2, 1, 10)];
        let runs = [
            run(0, 10, &[(1, 50.0), (5, 5.0)]),
            run(1, 12, &[(1, 50.0)]),
            run(2, 8, &[(1, 50.0), (7, 0.5)]),
        ];
        let rows = rows(&problems, &[Method::Auto], &runs);
        // Target 10¹: runs 0 and 2 at evaluations 5 and 7, run 1 never.
        let cell = rows[0].cells[0];
        assert_eq!((cell.successes, cell.runs), (2, 3));
        assert_eq!(cell.median, Some(7.0));
        // The median time to it by the same rule: run 2's (its events carry 1 ms per
        // evaluation here).
        assert_eq!(cell.time, Some(7e-3));
        assert_eq!(cell.art, Some((5.0 + 12.0 + 7.0) / 2.0));
        // Target 10⁰: run 2 alone; the median does not exist, aRT does.
        let cell = rows[0].cells[1];
        assert_eq!(cell.median, None);
        assert_eq!(cell.time, None);
        assert_eq!(cell.art, Some(10.0 + 12.0 + 7.0));
        // Target 10⁻¹: no run; neither exists.
        assert_eq!(rows[0].cells[2].art, None);
    }
}
