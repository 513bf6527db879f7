//! The generalisation suite: problem definitions against hand-computed values, the
//! counting wrapper, and `hodr suite` end to end with a tiny configuration.

use std::path::PathBuf;
use std::process::Command;

use hodr_host::suite::bbob::{self, Bbob};
use hodr_host::suite::plateau::{self, Discs};
use hodr_host::suite::{self, Config, Method, flat, random};

/// Tolerances, each with its reason.
mod tol {
    /// f at x_opt: every function is exactly 0 there in exact arithmetic, and x − x_opt
    /// is exactly 0 in floating point, so only rounding inside f remains.
    pub const AT_OPTIMUM: f64 = 1e-9;
    /// ‖RRᵀ − I‖_max after two passes of modified Gram–Schmidt on Gaussian rows.
    pub const ORTHOGONAL: f64 = 1e-12;
    /// (x_opt + d) − x_opt differs from d by an ulp of x_opt (|x_opt| ≤ 4); squared and
    /// multiplied by at most 100·9 in the hand-computed values.
    pub const HAND: f64 = 1e-9;
}

#[test]
fn bbob_functions_vanish_at_their_optimum_and_are_positive_elsewhere() {
    for id in bbob::IDS {
        for n in [2, 5, 10, 20] {
            for instance in 1..=3 {
                let f = Bbob::new(id, n, instance);
                let at = f.value(f.x_opt());
                assert!(at.abs() <= tol::AT_OPTIMUM, "f{id} n={n}: f(x_opt) = {at}");
                for k in 0..20 {
                    let x = random::uniform(n, -5.0, 5.0, random::seed_of("t", &[k]));
                    let v = f.value(&x);
                    assert!(v > 0.0, "f{id} n={n} i={instance}: f = {v} at {x:?}");
                }
                // Near x_opt too, where f7's rounding and f6's sector switch act.
                let mut x = f.x_opt().to_vec();
                x[0] += 1e-3;
                assert!(f.value(&x) > 0.0, "f{id} n={n}: zero next to x_opt");
            }
        }
    }
}

#[test]
fn bbob_optima_lie_where_the_definition_puts_them() {
    for id in bbob::IDS {
        let f = Bbob::new(id, 10, 1);
        let limit = if id == 8 { 3.0 } else { 4.0 };
        assert!(f.x_opt().iter().all(|v| v.abs() <= limit), "f{id}");
    }
}

#[test]
fn rotations_are_orthogonal() {
    for n in [1, 2, 5, 10, 20, 40] {
        for seed in 0..3 {
            let r = random::rotation(n, seed);
            for i in 0..n {
                for j in 0..n {
                    let d: f64 = (0..n).map(|k| r[i * n + k] * r[j * n + k]).sum();
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((d - want).abs() <= tol::ORTHOGONAL, "n={n} ({i},{j}): {d}");
                }
            }
        }
    }
    let f = Bbob::new(15, 7, 2);
    assert_ne!(f.r(), f.q(), "R and Q come from different seeds");
}

#[test]
fn sphere_and_rosenbrock_match_hand_computed_values() {
    // f1 at x_opt + (1, 2): 1² + 2² = 5.
    let f1 = Bbob::new(1, 2, 1);
    let x: Vec<f64> = f1
        .x_opt()
        .iter()
        .zip([1.0, 2.0])
        .map(|(a, b)| a + b)
        .collect();
    assert!((f1.value(&x) - 5.0).abs() <= tol::HAND);

    // f8, n = 2 (scale max(1, √2/8) = 1), x = x_opt + (1, 0): z = (2, 1),
    // 100·(2² − 1)² + (2 − 1)² = 901.
    let f8 = Bbob::new(8, 2, 1);
    let x: Vec<f64> = f8
        .x_opt()
        .iter()
        .zip([1.0, 0.0])
        .map(|(a, b)| a + b)
        .collect();
    assert!((f8.value(&x) - 901.0).abs() <= tol::HAND);

    // f8, n = 256 (scale √256/8 = 2), x = x_opt + ½e₁: z = (2, 1, 1, …): again 901.
    let f8 = Bbob::new(8, 256, 1);
    let mut x = f8.x_opt().to_vec();
    x[0] += 0.5;
    assert!((f8.value(&x) - 901.0).abs() <= tol::HAND);
}

/// x_opt + t·(row k of R): R(x − x_opt) = t·eₖ up to rounding.
fn along_row(f: &Bbob, k: usize, t: f64) -> Vec<f64> {
    let n = f.x_opt().len();
    (0..n)
        .map(|j| f.x_opt()[j] + t * f.r()[k * n + j])
        .collect()
}

#[test]
fn discus_bent_cigar_and_different_powers_match_hand_computed_values() {
    let n = 6;
    // f11 along R's first row, t = 1: z = T_osz(e₁) = e₁ (T_osz(1) = 1), f = 10⁶.
    let f11 = Bbob::new(11, n, 2);
    let v = f11.value(&along_row(&f11, 0, 1.0));
    assert!((v - 1e6).abs() <= 1e6 * 1e-12, "f11: {v}");
    // … and along the second, t = 2: z = T_osz(2e₂), f = T_osz(2)².
    let v = f11.value(&along_row(&f11, 1, 2.0));
    assert!((v - bbob::t_osz1(2.0).powi(2)).abs() <= 1e-12, "f11: {v}");
    // f12 along R's first row, t = 1: T_asy leaves e₁ (its first coordinate's exponent
    // is 1), z = R·e₁, R's first column c: f = c₁² + 10⁶(1 − c₁²).
    let f12 = Bbob::new(12, n, 2);
    let c1 = f12.r()[0];
    let want = c1 * c1 + 1e6 * (1.0 - c1 * c1);
    let v = f12.value(&along_row(&f12, 0, 1.0));
    assert!((v - want).abs() <= want * 1e-12, "f12: {v} against {want}");
    // f14: z = t·eₖ gives √(|t|^(2 + 4k/(n − 1))): |t| for k = 0, |t|³ for k = n − 1.
    let f14 = Bbob::new(14, n, 2);
    let v = f14.value(&along_row(&f14, 0, -0.5));
    assert!((v - 0.5).abs() <= 1e-12, "f14: {v}");
    let v = f14.value(&along_row(&f14, n - 1, 0.5));
    assert!((v - 0.125).abs() <= 1e-12, "f14: {v}");
}

#[test]
fn oscillation_and_asymmetry_transforms_follow_the_definition() {
    // T_osz(1) = exp(0 + 0.049·(sin 0 + sin 0)) = 1; odd-like sign handling.
    assert_eq!(bbob::t_osz1(0.0), 0.0);
    assert!((bbob::t_osz1(1.0) - 1.0).abs() < 1e-15);
    let x = 2.5f64;
    let xh = x.ln();
    let want = (xh + 0.049 * ((10.0 * xh).sin() + (7.9 * xh).sin())).exp();
    assert!((bbob::t_osz1(x) - want).abs() < 1e-12);
    let want = -(xh + 0.049 * ((5.5 * xh).sin() + (3.1 * xh).sin())).exp();
    assert!((bbob::t_osz1(-x) - want).abs() < 1e-12);
    // T_asy^β leaves x₁ and negative entries alone; x_D > 0 gets exponent 1 + β√x_D.
    let y = bbob::t_asy(&[4.0, -3.0, 4.0], 0.2);
    assert_eq!(y[0], 4.0);
    assert_eq!(y[1], -3.0);
    assert!((y[2] - 4f64.powf(1.0 + 0.2 * 2.0)).abs() < 1e-12);
}

#[test]
fn disc_plateau_is_zero_at_the_truth_and_flat_at_the_start() {
    for n in [2, 4, 8] {
        let p = plateau::discs(n, 1, 100);
        assert_eq!(p.value(&p.x_opt), 0.0, "n={n}");
        assert_eq!(p.param_error(&p.x_opt), 0.0);
        for s in 0..5 {
            let start = p.start(suite::problem::run_seed(&p.name, s));
            let f0 = p.value(&start);
            assert!(f0 > 0.0);
            // The mismatch is symmetric: scoring the target against the start's discs
            // (full-image construction) gives the same count as the bounding-box sum.
            assert_eq!(Discs::new(&start).value(&p.x_opt), f0, "n={n} seed={s}");
            // A plateau: moving every disc by a whole pixel (still clear of every
            // target, as starts are ≥ 13 px from targets, and inside the image) changes
            // nothing.
            for (dx, dy) in [(1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)] {
                let moved: Vec<f64> = start
                    .chunks_exact(2)
                    .flat_map(|c| [c[0] + dx, c[1] + dy])
                    .collect();
                assert_eq!(p.value(&moved), f0, "n={n} seed={s} moved by ({dx}, {dy})");
            }
        }
    }
}

#[test]
fn disc_parameter_error_ignores_the_order_of_discs() {
    let p = plateau::discs(4, 2, 100);
    let swapped = [p.x_opt[2], p.x_opt[3], p.x_opt[0], p.x_opt[1]];
    assert_eq!(p.value(&swapped), 0.0);
    assert_eq!(p.param_error(&swapped), 0.0);
}

#[test]
fn integer_plateau_is_constant_on_the_optimum_cell() {
    let p = plateau::integer(5, 1, 100);
    assert!(p.x_opt.iter().all(|v| v.fract() == 0.0));
    assert_eq!(p.value(&p.x_opt), 0.0);
    let near: Vec<f64> = p.x_opt.iter().map(|v| v + 0.3).collect();
    assert_eq!(p.value(&near), 0.0);
    assert_eq!(p.param_error(&near), 0.0);
    let off: Vec<f64> = p.x_opt.iter().map(|v| v + 0.7).collect();
    assert!(p.value(&off) > 0.0);
}

#[test]
fn flat_problem_ignores_its_last_coordinate() {
    let p = flat::problem(1, 100);
    let mut x = p.x_opt.clone();
    assert_eq!(p.value(&x), 0.0);
    x[flat::DIM - 1] += 1e3;
    assert_eq!(p.value(&x), 0.0);
    assert_eq!(p.param_error(&x), 0.0);
    x[0] += 1.0;
    assert!(p.value(&x) > 0.0);
}

#[test]
fn runs_are_deterministic_and_truncated_at_the_budget() {
    let p = bbob::problem(10, 5, 1, 60);
    let seed = suite::problem::run_seed(&p.name, 0);
    let x0 = p.start(seed);
    for m in [Method::CmaEs, Method::Bobyqa, Method::Fr22] {
        let a = m.run(&p, &x0, seed);
        let b = m.run(&p, &x0, seed);
        // Everything but the wall times.
        let results = |t: &suite::trace::Trace| {
            t.events
                .iter()
                .map(|e| (e.evaluation, e.f, e.param_error))
                .collect::<Vec<_>>()
        };
        assert_eq!(results(&a), results(&b), "{m}");
        assert!(a.evaluations <= p.budget, "{m}");
        assert!(a.events.iter().all(|e| e.evaluation <= p.budget));
        assert!(a.events.windows(2).all(|w| w[1].f < w[0].f));
        // Each new best's time is after the last one's, within the run's.
        assert!(a.events.windows(2).all(|w| w[1].time >= w[0].time));
        assert!(a.events.iter().all(|e| e.time >= 0.0 && e.time <= a.time));
    }
}

/// A noisy problem's methods see noisy values, and its runs are judged on f.
#[test]
fn noisy_runs_are_judged_on_the_noiseless_function() {
    let p = suite::noisy::problem(103, 4, 1, 50);
    let x0 = p.start(suite::problem::run_seed(&p.name, 0));
    assert!(p.is_noisy());
    let mut counter = suite::trace::Counter::new(&p, p.budget);
    let seen = counter.evaluate(&x0);
    // f103's Cauchy noise adds α·1 000 = 10 to all but a few values.
    assert_eq!(seen, p.observe(&x0, 0));
    assert_eq!(counter.evaluate(&x0), p.observe(&x0, 1));
    assert!((seen - p.value(&x0)).abs() > 1.0);
    let trace = counter.into_trace(0.0, None);
    assert_eq!(trace.events[0].f, p.value(&x0) - p.f_opt);
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hodr-suite-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn hodr(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_hodr"))
        .args(args)
        .output()
        .expect("hodr runs")
}

#[test]
fn quick_suite_writes_its_files() {
    let dir = scratch("quick");
    let out = hodr(&[
        "suite",
        "--quick",
        "--methods",
        "CMA-ES,BOBYQA",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("| bbob | CMA-ES |"), "{stdout}");
    let md = std::fs::read_to_string(dir.join("suite.md")).unwrap();
    assert!(md.contains("## plateau") && md.contains("BOBYQA"));
    let csv = std::fs::read_to_string(dir.join("suite.csv")).unwrap();
    let config = Config::from_args(&[], &[], &[], None, None, true, dir.clone()).unwrap();
    let problems = suite::catalogue(&config).unwrap().len();
    let targets = suite::summary::target_labels().len();
    assert_eq!(csv.lines().count(), 1 + problems * 2 * 2 * targets);
    let fields = csv.lines().next().unwrap().split(',').count();
    assert!(csv.lines().all(|l| l.split(',').count() == fields));
    let png = std::fs::read(dir.join("ecdf.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs at once change only the times: every evaluation count of the CSV is the same.
#[test]
fn parallel_runs_give_the_same_results() {
    let evaluations = |jobs: &str| {
        let dir = scratch(&format!("jobs{jobs}"));
        let out = hodr(&[
            "suite",
            "--quick",
            "--families",
            "integer,flat,noisy",
            "--methods",
            "Auto,CMA-ES",
            "--jobs",
            jobs,
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let csv = std::fs::read_to_string(dir.join("suite.csv")).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        // Every column but the times.
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let times: Vec<usize> = ["time_to_target_s", "time_s"]
            .iter()
            .map(|name| header.iter().position(|h| h == name).unwrap())
            .collect();
        csv.lines()
            .map(|l| {
                let fields: Vec<&str> = l
                    .split(',')
                    .enumerate()
                    .filter(|(k, _)| !times.contains(k))
                    .map(|(_, f)| f)
                    .collect();
                fields.join(",")
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(evaluations("1"), evaluations("2"));
}

/// BBOB and its noisy and failing variants run at any chosen dimension ≥ 2, the other
/// families only at their own.
#[test]
fn chosen_dimensions_select_bbob_anywhere_and_the_rest_at_their_own() {
    let dims = [40, 2];
    let config = Config::from_args(&[], &dims, &[], None, None, true, "unused".into()).unwrap();
    let problems = suite::catalogue(&config).unwrap();
    let bbob_40 = problems
        .iter()
        .filter(|p| p.family == suite::problem::Family::Bbob && p.n == 40)
        .count();
    assert_eq!(bbob_40, suite::bbob::IDS.len() * config.instances);
    assert!(problems.iter().all(|p| p.n == 40 || p.n == 2));
    assert!(problems.iter().filter(|p| p.n == 40).all(|p| matches!(
        p.family,
        suite::problem::Family::Bbob
            | suite::problem::Family::Noisy
            | suite::problem::Family::Failing
    )));
}

/// `--functions` keeps the chosen BBOB, noisy and failing functions, in the suite's
/// order, and the other families whole; a BBOB, noisy or failing family none of whose
/// functions is listed runs none.
#[test]
fn chosen_functions_select_bbob_noisy_and_failing_problems() {
    use suite::problem::Family;
    let all = Config::from_args(&[], &[], &[], None, None, true, "unused".into()).unwrap();
    let names = |config: &Config, family: Family| -> Vec<String> {
        suite::catalogue(config)
            .unwrap()
            .iter()
            .filter(|p| p.family == family)
            .map(|p| p.name.split("-n").next().unwrap().to_string())
            .collect()
    };
    let bbob_only = all.clone().with_functions(&[10, 2]).unwrap();
    let bbob = names(&bbob_only, Family::Bbob);
    assert!(!bbob.is_empty());
    let first_f10 = bbob.iter().position(|n| n == "bbob-f10").unwrap();
    assert!(bbob[..first_f10].iter().all(|n| n == "bbob-f02"));
    assert!(bbob[first_f10..].iter().all(|n| n == "bbob-f10"));
    assert!(!names(&bbob_only, Family::Plateau).is_empty());
    assert!(names(&bbob_only, Family::Noisy).is_empty());

    // The failing family's functions are BBOB's numbers, selected with them.
    assert!(
        names(&bbob_only, Family::Failing)
            .iter()
            .all(|n| n.ends_with("-f02") || n.ends_with("-f10"))
    );
    let failing_only = Config::from_args(
        &["failing".into()],
        &[],
        &[],
        None,
        None,
        true,
        "unused".into(),
    )
    .unwrap()
    .with_functions(&[8])
    .unwrap();
    let failing = names(&failing_only, Family::Failing);
    assert!(!failing.is_empty());
    assert!(failing.iter().all(|n| n.ends_with("-f08")));

    let mixed = all.with_functions(&[109, 13, 104]).unwrap();
    assert!(names(&mixed, Family::Bbob).iter().all(|n| n == "bbob-f13"));
    assert!(
        names(&mixed, Family::Failing).is_empty(),
        "f13 is not a failing function"
    );
    let noisy = names(&mixed, Family::Noisy);
    let first_f109 = noisy.iter().position(|n| n == "noisy-f109").unwrap();
    assert!(first_f109 > 0);
    assert!(noisy[..first_f109].iter().all(|n| n == "noisy-f104"));
    assert!(noisy[first_f109..].iter().all(|n| n == "noisy-f109"));
}

#[test]
fn bad_suite_arguments_fail_with_one_line() {
    for (args, culprit) in [
        (&["suite", "--methods", "Nelder"][..], "Nelder"),
        (&["suite", "--families", "bbob,cec"][..], "cec"),
        (&["suite", "--families", "plateau", "--dims", "3"][..], "3"),
        (&["suite", "--dims", "1"][..], "dimension 1"),
        (&["suite", "--methods", "FR22,fr22"][..], "fr22"),
        (&["suite", "--seeds", "0"][..], "seeds"),
        (&["suite", "--seeds", "many"][..], "many"),
        (&["suite", "--jobs", "0"][..], "jobs"),
        (&["suite", "--functions", "3"][..], "function 3"),
        (&["suite", "--functions", "113"][..], "function 113"),
        (
            &["suite", "--functions", "2,2"][..],
            "function 2 listed twice",
        ),
        (
            &["suite", "--families", "plateau", "--functions", "2"][..],
            "bbob",
        ),
        (
            &["suite", "--families", "bbob", "--functions", "2,104"][..],
            "function 104 belongs to the noisy family",
        ),
        (
            &["suite", "--families", "failing", "--functions", "6"][..],
            "function 6 belongs to the bbob family",
        ),
        (
            &["suite", "--families", "noisy", "--functions", "8"][..],
            "function 8 belongs to the bbob or failing family",
        ),
    ] {
        let out = hodr(args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(culprit), "{args:?}: {err}");
    }
}

#[test]
fn reflection_maps_into_the_box_and_keeps_the_inside() {
    let b = suite::problem::Bounds::cube(1, -5.0, 5.0);
    for (x, want) in [
        (0.0, 0.0),
        (5.0, 5.0),
        (6.0, 4.0),
        (-7.5, -2.5),
        (16.0, -4.0),
        (25.0, 5.0),
        (-25.0, -5.0),
    ] {
        let mut v = [x];
        b.reflect(&mut v);
        assert!((v[0] - want).abs() < 1e-12, "{x} → {} not {want}", v[0]);
    }
    let open = suite::problem::Bounds::cube(1, f64::NEG_INFINITY, f64::INFINITY);
    let mut v = [1e300];
    open.reflect(&mut v);
    assert_eq!(v[0], 1e300);
}
