//! The suite's files and its stdout table: `suite.csv` (one row per problem × method ×
//! seed × target), `suite.md` (header, per-family aggregates, per-problem tables) and
//! `ecdf.png` ([`super::plot`]).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};

use super::Config;
use super::methods::Method;
use super::problem::{Family, Problem};
use super::summary::{Cell, FamilyRow, Ratio, Row, Run, target_labels};

/// `suite.csv`: problem, family, n, method, seed, target, evaluations and wall time in
/// seconds to reach it (both empty when not reached), then the run's wall time, best
/// f − f* and why it stopped before its budget (empty when it used the budget; commas
/// replaced by semicolons).
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(path: &Path, problems: &[Problem], runs: &[Run]) -> Result<()> {
    let labels = target_labels();
    let mut csv = String::from(
        "problem,family,n,method,seed,target,evaluations,time_to_target_s,time_s,best_f,stopped\n",
    );
    for r in runs {
        let p = &problems[r.problem];
        for (label, e) in labels.iter().zip(r.reached()) {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{:e},{}",
                p.name,
                p.family,
                p.n,
                r.method,
                r.seed,
                label,
                e.map_or(String::new(), |e| e.evaluation.to_string()),
                e.map_or(String::new(), |e| e.time.to_string()),
                r.trace.time,
                r.trace.best(),
                r.trace.stopped.as_deref().unwrap_or("").replace(',', ";"),
            );
        }
    }
    std::fs::write(path, csv).with_context(|| format!("writing {}", path.display()))
}

/// The commit this binary was built from, as its build script recorded it (`build.rs`:
/// `git rev-parse --short HEAD`, with "+ uncommitted changes" when the compiled crates'
/// tracked files differed from it); `None` when it was not built in a git checkout.
pub fn commit() -> Option<String> {
    let stamp = env!("HODR_COMMIT");
    (!stamp.is_empty()).then(|| stamp.to_string())
}

/// Evaluations in a compact form: 1234, 12.3k, 1.23M.
fn evals(x: f64) -> String {
    if x < 1e4 {
        format!("{x:.0}")
    } else if x < 1e6 {
        format!("{:.1}k", x / 1e3)
    } else {
        format!("{:.2}M", x / 1e6)
    }
}

/// Seconds with three significant digits in a fitting unit.
pub fn seconds(t: f64) -> String {
    if !t.is_finite() {
        "—".into()
    } else if t < 1e-3 {
        format!("{:.0} µs", t * 1e6)
    } else if t < 1.0 {
        format!("{:.1} ms", t * 1e3)
    } else {
        format!("{t:.2} s")
    }
}

fn cell(c: &Cell) -> String {
    match c.median {
        Some(m) => format!("{} ({}/{})", evals(m), c.successes, c.runs),
        None => format!("— ({}/{})", c.successes, c.runs),
    }
}

/// A geometric-mean ratio and the problems that entered it, of `problems`.
fn ratio(ratio: Ratio, problems: usize) -> String {
    match ratio.mean {
        Some(x) => format!("{x:.2} ({}/{problems})", ratio.problems),
        None => format!("— (0/{problems})"),
    }
}

/// The table of [`super::summary::pairwise`]: the first method's median evaluations over
/// each other method's, geometric mean over a group's problems, and beside each its
/// median wall time's (Markdown).
pub fn pairwise_table(method: Method, pairs: &[super::summary::PairRow]) -> String {
    let Some(first) = pairs.first() else {
        return String::new();
    };
    let mut s = String::from("| group |");
    for (m, _) in &first.ratios {
        let _ = write!(s, " {method} ÷ {m}: evals (problems) | time |");
    }
    s.push_str("\n|---|");
    for _ in &first.ratios {
        s.push_str("---|---|");
    }
    s.push('\n');
    for row in pairs {
        let _ = write!(s, "| {} |", row.group);
        for ((_, ratio), (_, time)) in row.ratios.iter().zip(&row.time_ratios) {
            match ratio.mean {
                Some(x) => {
                    let _ = write!(s, " {x:.2} ({}) |", ratio.problems);
                }
                None => s.push_str(" — (0) |"),
            }
            match time.mean {
                Some(x) => {
                    let _ = write!(s, " {x:.2} |");
                }
                None => s.push_str(" — |"),
            }
        }
        s.push('\n');
    }
    s
}

/// The per-family table (Markdown), as printed to stdout and at the top of suite.md.
pub fn family_table(families: &[FamilyRow], reference: Method) -> String {
    let mut s = format!(
        "| family | method | problems | runs at 1e-8 | targets reached | evals ÷ {reference} (problems) | time ÷ {reference} | aRT ÷ {reference} (problems) | median time |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in families {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {}/{} | {:.0} % | {} | {} | {} | {} |",
            r.family,
            r.method,
            r.problems,
            r.final_successes,
            r.runs,
            100.0 * r.targets_reached as f64 / r.targets.max(1) as f64,
            ratio(r.ratio, r.problems),
            r.time_ratio
                .mean
                .map_or_else(|| "—".into(), |x| format!("{x:.2}")),
            ratio(r.art_ratio, r.problems),
            seconds(r.median_time),
        );
    }
    s
}

/// `suite.md`.
///
/// # Errors
/// When the file cannot be written.
pub fn write_markdown(
    path: &Path,
    config: &Config,
    problems: &[Problem],
    rows: &[Row],
    families: &[FamilyRow],
    reference: Method,
    interrupted: bool,
) -> Result<()> {
    let mut md = String::from("# hodr generalisation suite\n\n");
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let _ = writeln!(
        md,
        "* seeds per problem: {}; budget: {} evaluations per dimension; instances per function and dimension: {}",
        config.seeds, config.budget_per_dim, config.instances
    );
    let _ = writeln!(
        md,
        "* methods: {}",
        config
            .methods
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        md,
        "* commit: {}",
        commit().unwrap_or_else(|| "unknown".into())
    );
    let _ = writeln!(
        md,
        "* machine: {threads} hardware threads, rayon pool of {}; runs at once: {}",
        rayon::current_num_threads(),
        config.jobs
    );
    if config.quick {
        md.push_str("* `--quick`: small dimensions, 2 seeds, 2 instances, small budgets\n");
    }
    if interrupted {
        md.push_str("* **interrupted**: only the runs finished before Ctrl-C\n");
    }
    md.push_str(
        "\nEvaluations are counted through one wrapper for every method; targets are judged \
         on the best point so far. Medians count a run that never reaches a target as +∞ \
         (\"—\": half or more never did); (s/N) is runs reaching it. The ratio column is the \
         geometric mean over problems of a method's median evaluations over the reference's, \
         each problem at the hardest f-target both reach (so read it with the success counts); \
         (k/m): problems with such a target. The time column is the same mean of median \
         wall-time ratios to the same targets: a method's own work counts there as well as \
         the objective's, and the suite's objectives are cheap. The aRT column is the same mean of aRT ratios \
         (average running time, as COCO reports it: the evaluations of all runs, a failed \
         run's whole run, per run that reached the target), each problem at the hardest \
         f-target both reach in at least one run: it counts the runs that failed. \
         `paramNN`: NN % parameter-error reduction.\n\n",
    );
    md.push_str("## By family\n\n");
    md.push_str(&family_table(families, reference));
    md.push_str("\n![ECDF](ecdf.png)\n");
    if let Some(&first) = config.methods.first() {
        let pairs = super::summary::pairwise(problems, &config.methods, first, rows);
        let _ = write!(
            md,
            "\n## {first} against each method\n\nGeometric mean over a group's problems of \
             {first}'s median evaluations over the other method's, each problem at the hardest \
             f-target both reach (below 1: {first} needs fewer); (k): problems with such a \
             target; beside it, the same mean of median wall times to the same targets (below \
             1: {first} is faster in this run, on these cheap objectives).\n\n{}",
            pairwise_table(first, &pairs)
        );
    }
    let labels = target_labels();
    for family in Family::ALL {
        let mine: Vec<&Row> = rows
            .iter()
            .filter(|r| problems[r.problem].family == family)
            .collect();
        if mine.is_empty() {
            continue;
        }
        let _ = write!(
            md,
            "\n## {family}: median evaluations to f − f* ≤ target (runs reaching it)\n\n| problem | method |"
        );
        for l in &labels {
            let _ = write!(md, " {l} |");
        }
        md.push_str(" median time |\n|---|---|");
        md.push_str(&"---|".repeat(labels.len() + 1));
        md.push('\n');
        for r in mine {
            let _ = write!(md, "| {} | {} |", problems[r.problem].name, r.method);
            for c in &r.cells {
                let _ = write!(md, " {} |", cell(c));
            }
            let _ = writeln!(md, " {} |", seconds(r.median_time));
        }
    }
    std::fs::write(path, md).with_context(|| format!("writing {}", path.display()))
}
