//! Smoke tests of the `hodr` command line with tiny budgets.

use std::ops::Deref;
use std::path::{Path, PathBuf};
use std::process::Command;

fn hodr(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_hodr"))
        .args(args)
        .output()
        .expect("hodr runs")
}

/// A test's own empty directory under the system's temporary one, removed when the test
/// passes and kept, for a look at what the run wrote, when it fails.
struct Scratch(PathBuf);

impl Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("hodr-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

#[test]
fn help_everywhere() {
    for sub in [
        &[][..],
        &["report"],
        &["tasks"],
        &["render"],
        &["optimize"],
        &["fit2d"],
        &["variance"],
        &["runtime"],
        &["suite"],
    ] {
        let mut args = sub.to_vec();
        args.push("--help");
        let out = hodr(&args);
        assert!(out.status.success(), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("Usage"));
    }
}

#[test]
fn tasks_lists_every_task() {
    let out = hodr(&["tasks"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for name in [
        "QUAD", "BOX2-REF", "TRI1D", "BOX2", "BOX10", "SHAPES", "SHADOW", "MUG", "CBOX", "TEXTURE",
        "CAUSTIC",
    ] {
        assert!(text.contains(name), "{name} missing from {text}");
    }
}

#[test]
fn report_writes_parseable_files() {
    let dir = scratch("report");
    let out = hodr(&[
        "report",
        "--tasks",
        "quad,box2",
        "--methods",
        "OurHVPA,FR22,CMA-ES",
        "--seeds",
        "2",
        "--budget",
        "200",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 3 * 2);
    let header_fields = csv.lines().next().unwrap().split(',').count();
    assert!(csv.lines().all(|l| l.split(',').count() == header_fields));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    assert_eq!(json["runs"].as_array().unwrap().len(), 12);
    assert_eq!(json["interrupted"], serde_json::Value::Bool(false));
    // Per-iteration points live in traces.csv, one row each, not in the JSON.
    assert!(json["runs"][0].get("points").is_none());
    let traces = std::fs::read_to_string(dir.join("traces.csv")).unwrap();
    let mut rows = traces.lines();
    let header = rows.next().unwrap();
    assert_eq!(
        header,
        "task,method,seed,iteration,time_s,evaluations,param_error,image_error,sigma"
    );
    let rows: Vec<&str> = rows.collect();
    assert!(rows.len() > 12);
    assert!(rows.iter().all(|r| r.split(',').count() == 9));
    assert_eq!(
        rows.iter()
            .filter(|r| r.split(',').nth(3) == Some("0"))
            .count(),
        12
    );
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(md.contains("## QUAD") && md.contains("## BOX2") && md.contains("OurHVPA"));
    assert!(dir.join("plot_quad_param.png").exists());
    assert!(dir.join("strip_box2.png").exists());
    // The quick generalisation suite by default: its family table in report.md, its
    // files under suite/.
    assert!(md.contains("## Generalisation suite") && md.contains("| bbob | Auto |"));
    assert!(md.contains("](suite/suite.md)") && md.contains("](suite/ecdf.png)"));
    for file in ["suite.md", "suite.csv", "ecdf.png"] {
        assert!(dir.join("suite").join(file).exists(), "{file}");
    }
}

/// A method whose first estimate alone exceeds the budget is shown as skipped, with no
/// figures, not as a run that ended where it started.
#[test]
fn skipped_methods_read_as_skipped() {
    let dir = scratch("skipped");
    let out = hodr(&[
        "report",
        "--tasks",
        "box2",
        "--methods",
        "OurH,Auto",
        "--seeds",
        "1",
        "--budget",
        "20",
        "--suite",
        "off",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let row = md.lines().find(|l| l.starts_with("| OurH |")).unwrap();
    assert!(
        row.matches("skipped").count() == 8 && !row.contains("e0"),
        "{row}"
    );
    assert!(md.contains(
        "Skipped (one estimate, iteration or generation exceeds the run's budget): OurH"
    ));
}

/// A setting whose first estimate cannot fit the budget is refused at once, not run to
/// 10 000 times the budget.
#[test]
fn an_estimate_larger_than_the_budget_is_refused() {
    use std::time::{Duration, Instant};
    let clock = Instant::now();
    let out = hodr(&[
        "optimize",
        "--task",
        "BOX2",
        "--method",
        "OurHVPA",
        "--budget",
        "200",
        "--set",
        "pairs=1000000000",
    ]);
    assert!(clock.elapsed() < Duration::from_secs(20));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("2000000000 evaluations") && err.contains("200"),
        "{err}"
    );
}

/// `render --params @FILE` reads θ from a file (TEXTURE's 1024 values), as the same
/// values given inline would; bad values are named with their position.
#[test]
fn render_reads_params_from_a_file() {
    let dir = scratch("params");
    let values: Vec<String> = (0..1024)
        .map(|k| format!("{:.3}", (k % 7) as f64 / 7.0))
        .collect();
    let file = dir.join("theta.txt");
    std::fs::write(
        &file,
        values
            .chunks(32)
            .map(|c| c.join(", "))
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .unwrap();
    let from_file = dir.join("file.png");
    let arg = format!("@{}", file.display());
    let out = hodr(&[
        "render",
        "--task",
        "texture",
        "--spp",
        "1",
        "--params",
        &arg,
        "--out",
        from_file.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let inline = dir.join("inline.png");
    let out = hodr(&[
        "render",
        "--task",
        "texture",
        "--spp",
        "1",
        "--params",
        &values.join(","),
        "--out",
        inline.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(from_file).unwrap(),
        std::fs::read(inline).unwrap()
    );
    let out = hodr(&[
        "render",
        "--task",
        "box2",
        "--params",
        "1,x,3",
        "--out",
        "/tmp/never.png",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("value 2 is `x`"),
        "{err}"
    );
    let out = hodr(&[
        "render",
        "--task",
        "box2",
        "--params",
        "@/no/such/file",
        "--out",
        "/tmp/never.png",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("/no/such/file"),
        "{err}"
    );
}

/// fit2d: a seed fixes the shapes (same seed, same PNG; another seed, another),
/// --resize sets the working size, and --time stops placing shapes when it is up.
#[test]
fn fit2d_takes_seed_resize_and_time() {
    let dir = scratch("fit2d");
    let target = dir.join("mug.png");
    let out = hodr(&[
        "render",
        "--task",
        "mug",
        "--spp",
        "4",
        "--out",
        target.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The shapes themselves, in the SVG (two fits may paint the same pixels).
    let fit = |seed: &str, name: &str| {
        let file = dir.join(name);
        let svg = file.with_extension("svg");
        let args = [
            "fit2d",
            "--target",
            target.to_str().unwrap(),
            "--shapes",
            "3",
            "--kind",
            "rect",
            "--resize",
            "32",
            "--seed",
            seed,
            "--out",
            file.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
        ];
        let out = hodr(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let size = image::open(&file).unwrap();
        assert_eq!((size.width(), size.height()), (32, 32));
        (
            String::from_utf8_lossy(&out.stdout).into_owned(),
            std::fs::read_to_string(svg).unwrap(),
        )
    };
    let (text, a) = fit("1", "a.png");
    assert!(text.contains("(32×32), seed 1"), "{text}");
    let (_, b) = fit("1", "b.png");
    let (_, c) = fit("2", "c.png");
    assert_eq!(a, b);
    assert_ne!(a, c);
    let out = hodr(&[
        "fit2d",
        "--target",
        target.to_str().unwrap(),
        "--shapes",
        "4000",
        "--time",
        "0.3",
        "--out",
        dir.join("d.png").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("time is up after"), "{text}");
}

#[test]
fn report_without_the_suite() {
    let dir = scratch("report-no-suite");
    let out = hodr(&[
        "report",
        "--tasks",
        "quad",
        "--methods",
        "Auto",
        "--seeds",
        "1",
        "--budget",
        "50",
        "--suite",
        "off",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(!md.contains("Generalisation suite"));
    assert!(!dir.join("suite").exists());
    let out = hodr(&["report", "--suite", "most"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("most"));
}

/// `render --spp` sets the path tracer's samples per pixel (different images at 1 and
/// 8 spp) and is refused, naming it, where a task has no sampling.
#[test]
fn render_honours_spp() {
    let dir = scratch("spp");
    let render = |spp: &str| {
        let file = dir.join(format!("mug{spp}.png"));
        let out = hodr(&[
            "render",
            "--task",
            "mug",
            "--spp",
            spp,
            "--out",
            file.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stdout).contains(&format!("at {spp} spp")));
        std::fs::read(file).unwrap()
    };
    assert_ne!(render("1"), render("8"));
    let out = hodr(&[
        "render",
        "--task",
        "box2",
        "--spp",
        "4",
        "--out",
        dir.join("box2.png").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--spp") && err.contains("BOX2"), "{err}");
    assert!(!dir.join("box2.png").exists());
}

/// The program names itself `hodr`, and counts in the singular where there is one.
#[test]
fn names_and_counts_read_right() {
    let out = hodr(&["--version"]);
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("hodr "));
    let out = hodr(&["tasks"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("1 parameters"), "{text}");
    assert!(text.contains("1 parameter,"), "{text}");
    // Estimators read as elsewhere: FR22, not Rust's Fr22 or PerElement.
    let out = hodr(&["variance", "--repeats", "2"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("| gradient FR22 |"), "{text}");
    assert!(
        !text.contains("Fr22") && !text.contains("PerElement"),
        "{text}"
    );
}

#[test]
fn render_optimize_and_fit2d_write_images() {
    let dir = scratch("images");
    let shadow = dir.join("shadow.png");
    let out = hodr(&[
        "render",
        "--task",
        "shadow",
        "--spp",
        "2",
        "--out",
        shadow.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(shadow.exists());
    let png = dir.join("box2.png");
    let out = hodr(&["render", "--task", "BOX2", "--out", png.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(png.exists());
    let res = dir.join("opt.png");
    let out = hodr(&[
        "optimize",
        "--task",
        "box2",
        "--method",
        "OurHVPA",
        "--budget",
        "300",
        "--set",
        "negative_curvature=two-sided",
        "--out",
        res.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("iter"));
    assert!(res.exists());
    let fit = dir.join("fit.png");
    let svg = dir.join("fit.svg");
    let out = hodr(&[
        "fit2d",
        "--target",
        png.to_str().unwrap(),
        "--shapes",
        "2",
        "--kind",
        "rect",
        "--out",
        fit.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(fit.exists() && svg.exists());
}

/// Output files: written only when asked, into folders created as needed, and a path
/// that cannot be written fails before any work, naming it, its cause said once.
#[test]
fn outputs_are_asked_for_and_checked_first() {
    let dir = scratch("outputs");
    let run_in = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_hodr"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("hodr runs")
    };
    // No --out: no image appears in the working folder.
    let out = run_in(&["optimize", "--task", "BOX2", "--budget", "60"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    // --out for a task without an image is an error, not a silent no-op.
    let out = run_in(&[
        "optimize", "--task", "QUAD", "--budget", "60", "--out", "q.png",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("QUAD") && err.contains("q.png"), "{err}");
    assert!(!dir.join("q.png").exists());
    // Missing folders are created, for render as for report.
    let nested = dir.join("a/b/box2.png");
    let out = hodr(&[
        "render",
        "--task",
        "BOX2",
        "--out",
        nested.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(nested.exists());
    // A path under a file cannot be written: one line naming it, before the fit runs.
    let blocked = dir.join("a/b/box2.png/fit.png");
    let out = hodr(&[
        "fit2d",
        "--target",
        nested.to_str().unwrap(),
        "--shapes",
        "500",
        "--out",
        blocked.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("box2.png"), "{err}");
    // A missing input: its cause once.
    let out = hodr(&[
        "fit2d",
        "--target",
        dir.join("none.png").to_str().unwrap(),
        "--out",
        dir.join("x.png").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("none.png"), "{err}");
    assert_eq!(err.matches("os error").count(), 1, "{err}");
}

/// Clap's errors name what is missing, and fit2d lists only the kinds it places.
#[test]
fn argument_errors_name_what_is_wrong() {
    let out = hodr(&["render", "--task", "BOX2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--out"), "{err}");
    let out = hodr(&[
        "fit2d", "--target", "x.png", "--kind", "hexagon", "--out", "y.png",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("hexagon") && err.contains("circle"), "{err}");
    assert!(!err.contains("polygon") && !err.contains("cubic"), "{err}");
}

#[test]
fn bad_input_gives_one_line_and_nonzero_exit() {
    for args in [
        &["report", "--tasks", "nope", "--out", "/tmp/hodr-never"][..],
        &["optimize", "--task", "QUAD", "--method", "nope"],
        &[
            "render",
            "--task",
            "BOX2",
            "--params",
            "1,2,3",
            "--out",
            "/tmp/x.png",
        ],
        &[
            "fit2d",
            "--target",
            "/does/not/exist.png",
            "--out",
            "/tmp/x.png",
        ],
        &["report", "--set", "pairs=many"],
        &[
            "optimize",
            "--task",
            "quad",
            "--set",
            "negative_curvature=sideways",
        ],
        &[
            "render",
            "--task",
            "shadow",
            "--spp",
            "0",
            "--out",
            "/tmp/x.png",
        ],
        &["report", "--no-such-flag"],
        &["no-such-command"],
    ] {
        let out = hodr(args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("hodr: "), "{err}");
    }
}

/// Selections name what is wrong: an unknown method with the list of methods, a task
/// or method listed twice as such (not as unknown).
#[test]
fn selection_errors_name_the_culprit() {
    for (args, says) in [
        (
            &["optimize", "--task", "QUAD", "--method", "Nelder"][..],
            &["`Nelder`", "Auto", "FR22", "CMA-ES"][..],
        ),
        (
            &["report", "--methods", "nope", "--out", "/tmp/hodr-never"],
            &["`nope`", "OurHVPA"],
        ),
        (
            &["report", "--tasks", "QUAD,quad", "--out", "/tmp/hodr-never"],
            &["`quad` listed twice"],
        ),
        (
            &[
                "report",
                "--methods",
                "FR22,fr22",
                "--out",
                "/tmp/hodr-never",
            ],
            &["`fr22` listed twice"],
        ),
    ] {
        let out = hodr(args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        for s in says {
            assert!(err.contains(s), "{args:?}: {err} lacks {s}");
        }
    }
}

/// optimize says what it runs, prints every N-th iteration (and the last) or none, and
/// ends with the best point seen, not merely the last.
#[test]
fn optimize_reports_header_progress_and_best() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "optimize", "--task", "BOX2", "--method", "FR22", "--budget", "300",
        ];
        args.extend_from_slice(extra);
        let out = hodr(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let quiet = run(&["--quiet"]);
    assert!(!quiet.contains("iter "), "{quiet}");
    for s in [
        "optimize BOX2 (n = 2) with FR22",
        "budget 300",
        "start θ₀",
        "truth θ*",
        "best: iteration",
    ] {
        assert!(quiet.contains(s), "{s} missing: {quiet}");
    }
    let every = run(&["--every", "5"]);
    let iterations: Vec<usize> = every
        .lines()
        .filter_map(|l| l.strip_prefix("iter "))
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    let (last, shown) = iterations.split_last().unwrap();
    assert!(shown.iter().all(|k| k % 5 == 0), "{iterations:?}");
    let all = run(&[]);
    let errors: Vec<f64> = all
        .lines()
        .filter_map(|l| l.split("image error = ").nth(1))
        .map(|v| v.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(errors.len(), last + 1);
    let best: f64 = all
        .lines()
        .find_map(|l| l.strip_prefix("best: "))
        .and_then(|l| l.split("image error ").nth(1))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    let lowest = errors.iter().fold(f64::INFINITY, |m, &e| m.min(e));
    assert!(
        (best - lowest).abs() <= 1e-4 * lowest.abs().max(1e-12),
        "{best} vs {lowest}"
    );
}

/// SIGTERM and SIGINT stop the work alike: what finished is written, marked as
/// interrupted, and the exit code names the signal (143, 130).
#[test]
fn signals_write_what_finished_and_exit_non_zero() {
    use std::time::{Duration, Instant};
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        let dir = scratch(&format!("signal{code}"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_hodr"))
            .args([
                "report",
                "--tasks",
                "box2,box10",
                "--methods",
                "FR22,Auto",
                "--seeds",
                "1000",
                "--suite",
                "off",
                "--out",
                dir.to_str().unwrap(),
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(1500));
        let kill = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        assert!(kill.success());
        let clock = Instant::now();
        let status = child.wait().unwrap();
        assert!(clock.elapsed() < Duration::from_secs(60));
        assert_eq!(status.code(), Some(code), "{signal}");
        let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
        assert!(
            md.contains("**Interrupted**") && md.contains("up to 1000"),
            "{md}"
        );
        assert!(md.contains("seeds finished by every method"), "{md}");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap())
                .unwrap();
        assert_eq!(json["interrupted"], serde_json::Value::Bool(true));
        assert!(!json["runs"].as_array().unwrap().is_empty());
        assert!(dir.join("results.csv").exists());
    }
}

/// `optimize` without `--method` runs Auto, which solves QUAD to machine precision; each
/// iteration's line says what the iteration did and which descent it belongs to.
#[test]
fn optimize_defaults_to_auto() {
    let out = hodr(&["optimize", "--task", "QUAD", "--budget", "200"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let last = text
        .lines()
        .rfind(|l| l.starts_with("iter"))
        .expect("per-iteration lines");
    let error: f64 = last
        .split("param error = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .expect("a parameter error");
    assert!(error < 1e-8, "{last}");
    let kinds = [
        "Plateau",
        "AtModelMinimum",
        "Accepted",
        "Rejected",
        "Continued",
        "OutOfBudget",
        "Centred",
        "Probed",
    ];
    // Each Auto iteration ends with what it did and its descent: 1 first, then rising
    // by at most one per iteration.
    let mut descent = 1;
    for line in text
        .lines()
        .filter(|l| l.starts_with("iter") && !l.starts_with("iter    0"))
    {
        let (head, number) = line.rsplit_once(", descent ").expect(line);
        assert!(kinds.iter().any(|k| head.ends_with(k)), "{line}");
        let d: usize = number.parse().expect(line);
        assert!(d == descent || d == descent + 1, "{line}");
        descent = d;
    }
}

/// Ctrl-C during an iteration of millions of evaluations stops it within a batch, not
/// at the iteration's end: `optimize` exits 130 at once and says why it stopped.
#[test]
fn an_interrupt_stops_a_long_iteration_between_batches() {
    use std::time::{Duration, Instant};
    let mut child = Command::new(env!("CARGO_BIN_EXE_hodr"))
        .args([
            "optimize",
            "--task",
            "BOX2",
            "--method",
            "FR22",
            "--budget",
            "1000000000",
            "--set",
            "pairs=100000000",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let clock = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if clock.elapsed() > Duration::from_secs(5) {
            child.kill().unwrap();
            panic!("still running 5 s after the signal");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("stopped early: interrupted"), "{stderr}");
}

/// Newton-CG is named by its options: a recipe runs under its text form, and a bad
/// option is an error that teaches the syntax.
#[test]
fn newton_cg_recipes_are_named_by_their_options() {
    let out = hodr(&[
        "optimize",
        "--task",
        "QUAD",
        "--method",
        "newtoncg/FR22/compare",
        "--budget",
        "300",
        "--quiet",
    ]);
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("with NewtonCG/fr22/compare"), "{stdout}");
    let out = hodr(&["optimize", "--task", "QUAD", "--method", "NewtonCG/fast"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("unknown method `NewtonCG/fast`") && stderr.contains("/compare"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

/// No method spends more than its budget: a preset's iteration that would overrun it
/// (a Newton step costs several estimates) is abandoned, CMA-ES stops before a
/// generation that would, and a run that cannot complete one iteration is skipped.
#[test]
fn runs_keep_within_their_budget() {
    let dir = scratch("budget");
    let out = hodr(&[
        "report",
        "--tasks",
        "box2,quad",
        "--methods",
        "OurHVP,OurHVPA,NCG-kernel,CMA-ES",
        "--seeds",
        "2",
        "--budget",
        "300",
        "--suite",
        "off",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("traces.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|&h| h == "evaluations").unwrap();
    let mut rows = 0;
    for line in lines {
        let evaluations: usize = line.split(',').nth(column).unwrap().parse().unwrap();
        assert!(evaluations <= 300, "{line}");
        rows += 1;
    }
    assert!(rows > 16, "{csv}");
    let out = hodr(&[
        "optimize", "--task", "BOX2", "--method", "OurHVP", "--budget", "30",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("skipped") && err.contains("30"), "{err}");
}

/// Values that clap would otherwise misread or that a method would fail on name the
/// option or key as the user typed it; a failed run exits non-zero after its output.
#[test]
fn options_and_settings_are_checked_by_name() {
    for (args, says) in [
        (
            &["optimize", "--task", "BOX2", "--budget", "-1"][..],
            &["--budget", "-1"][..],
        ),
        (
            &["optimize", "--task", "BOX2", "--budget", "0"],
            &["--budget", "below 1"],
        ),
        (
            &[
                "optimize",
                "--task",
                "BOX2",
                "--method",
                "NewtonCG",
                "--set",
                "sigma_shrink=2",
            ],
            &["sigma_shrink=2", "between 0 and 1"],
        ),
        (
            &[
                "optimize", "--task", "BOX2", "--method", "FR22", "--set", "lr=nan",
            ],
            &["lr=nan", "above 0"],
        ),
        (
            &["optimize", "--task", "BOX2", "--set", "pairs=4"],
            &["--set", "Auto takes no hyper-parameters"],
        ),
        (
            &["suite", "--families", "bbob", "--dims", "1001"],
            &["1001", "2–1000"],
        ),
        (
            &[
                "optimize",
                "--task",
                "BOX2",
                "--budget",
                "1000000000",
                "--out",
                "no-extension",
            ],
            &["--out", "no-extension", ".png"],
        ),
        (
            &["fit2d", "--target", "t.png", "--out", "o.bmp"],
            &["--out", "o.bmp", ".png"],
        ),
    ] {
        let out = hodr(args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        for s in says {
            assert!(err.contains(s), "{args:?}: {err} lacks {s}");
        }
    }
    let out = hodr(&[
        "report",
        "--suite",
        "OFF",
        "--tasks",
        "quad",
        "--methods",
        "Auto",
        "--seeds",
        "1",
        "--out",
        scratch("suite-case").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The report names a run that failed rather than showing it as a row of dashes.
    let dir = scratch("failed");
    let out = hodr(&[
        "report",
        "--tasks",
        "quad",
        "--methods",
        "FR22,Auto",
        "--seeds",
        "1",
        "--suite",
        "off",
        "--set",
        "sigma_start=1e308",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(md.contains("Failed: FR22 seed 0: "), "{md}");
    assert!(!md.contains("Failed: Auto"), "{md}");
    // A run that fails at once still prints its header and best point, then exits 2.
    let out = hodr(&[
        "optimize",
        "--task",
        "BOX2",
        "--method",
        "NewtonCG",
        "--set",
        "sigma_start=1e308",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stdout).contains("best:"));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("NewtonCG on BOX2 stopped early"), "{err}");
}

/// `--params @FILE` reads at most a megabyte: /dev/zero is refused, not read forever.
#[test]
fn a_params_file_is_read_up_to_a_cap() {
    let out = hodr(&[
        "render",
        "--task",
        "BOX2",
        "--params",
        "@/dev/zero",
        "--out",
        "/tmp/x.png",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("@/dev/zero") && err.contains("larger than"),
        "{err}"
    );
}

#[test]
fn a_closed_stdout_ends_the_run_quietly() {
    // `hodr optimize … | head -n 3`: the reader goes after three lines. The run must stop
    // without a panic or an error message, and exit successfully.
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_hodr"))
        .args(["optimize", "--task", "quad", "--budget", "100000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("hodr runs");
    let mut stdout = BufReader::new(child.stdout.take().expect("piped"));
    let mut line = String::new();
    for _ in 0..3 {
        line.clear();
        stdout.read_line(&mut line).expect("a line");
        assert!(!line.is_empty());
    }
    drop(stdout);
    let out = child.wait_with_output().expect("hodr ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{:?}: {stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}
