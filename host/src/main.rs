//! The `hodr` command line. Every subcommand reports bad arguments or files as one line
//! on stderr and exits with a non-zero code.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};
use hodr_core::optim::preset::Preset;
use hodr_host::report::{self, Config, Method, Overrides, Settings, task};
use signal_hook::consts::{SIGINT, SIGTERM};

/// Set once a write to stdout has failed because its reader has gone (`hodr optimize … |
/// head`): the work then stops as an interrupt stops it, what it finished is written, and
/// the exit is quiet and successful.
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// `println!` that records a closed stdout ([`STDOUT_CLOSED`]) instead of panicking.
macro_rules! say {
    ($($arg:tt)*) => {
        say(format_args!($($arg)*), true)
    };
}

/// `print!` that records a closed stdout ([`STDOUT_CLOSED`]) instead of panicking.
macro_rules! say_raw {
    ($($arg:tt)*) => {
        say(format_args!($($arg)*), false)
    };
}

/// Writes `args` (and a newline where `newline`) to stdout; a failed write sets
/// [`STDOUT_CLOSED`].
fn say(args: std::fmt::Arguments<'_>, newline: bool) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let written = out.write_fmt(args).and_then(|()| {
        if newline {
            out.write_all(b"\n")
        } else {
            Ok(())
        }
    });
    if written.is_err() {
        STDOUT_CLOSED.store(true, Ordering::SeqCst);
    }
}

/// hodr: second-order optimisation of discontinuous, black-box renderers.
#[derive(Parser, Debug)]
#[command(
    name = "hodr",
    version,
    about = "hodr: second-order optimisation of discontinuous, black-box renderers",
    after_help = "Without a command, hodr runs the quick report (every method on every built-in \
                  task, then the quick generalisation suite; about a minute on 2 cores) and \
                  writes it to ./report/ (report.md, plots, CSV, JSON; about 15 MB)."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

// Every subcommand takes a negative number as an option's value (`allow_negative_numbers`),
// so that `--budget -1` is refused by that option's parser, which names it, rather than
// read as an unknown flag.
#[derive(Subcommand, Debug)]
enum Command {
    /// Error against run time for every method on every task (report.md, plots, CSV, JSON).
    #[command(allow_negative_numbers = true)]
    Report {
        /// Tasks to run (comma-separated; default all, see `hodr tasks`).
        #[arg(long, value_delimiter = ',')]
        tasks: Vec<String>,
        /// Methods to run (comma-separated; default all presets and CMA-ES).
        #[arg(long, value_delimiter = ',')]
        methods: Vec<String>,
        /// Seeds per task × method (default 20, or 5 with --quick).
        #[arg(long)]
        seeds: Option<u64>,
        /// 5 seeds and smaller budgets: about a minute on 2 cores.
        #[arg(long)]
        quick: bool,
        /// Objective evaluations per run for every task, ≥ 1 (default: each task's
        /// budget).
        #[arg(long, value_parser = at_least_one)]
        budget: Option<usize>,
        /// Hyper-parameter override for every task, key=value (repeatable): pairs,
        /// sigma_start, sigma_end, trust_radius, ls_iters, recompute, lr, crn,
        /// negative_curvature (fallback | two-sided), sigma_shrink, inner_steps,
        /// line_curvature (true | false).
        #[arg(long = "set")]
        set: Vec<String>,
        /// Output directory.
        #[arg(long, default_value = "report")]
        out: PathBuf,
        /// The generalisation suite run after the tasks, into OUT/suite: off, quick
        /// (seconds) or full (tens of minutes; the same as `hodr suite`).
        #[arg(long, value_enum, ignore_case = true, default_value_t = report::SuiteScope::Quick)]
        suite: report::SuiteScope,
    },
    /// Every task with its dimension and a one-line description.
    Tasks,
    /// Render a task at given parameters (default: its true parameters) to a PNG.
    #[command(allow_negative_numbers = true)]
    Render {
        /// The task.
        #[arg(long)]
        task: String,
        /// Parameters, comma-separated, or @FILE to read them from a file (separated by
        /// commas, spaces or newlines; TEXTURE has 1024). Default: the task's θ*.
        #[arg(long, allow_hyphen_values = true)]
        params: Option<String>,
        /// Samples per pixel, ≥ 1 (path-traced tasks only; default 64). The image is the
        /// task's viewing image (128×128 for the path-traced tasks), not the smaller
        /// one its objective renders (see `hodr tasks`).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        spp: Option<u32>,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
    },
    /// Optimise one task with one method, printing per-iteration progress.
    #[command(allow_negative_numbers = true)]
    Optimize {
        /// The task.
        #[arg(long)]
        task: String,
        /// The method: Auto (hodr's default), a preset name, or CMA-ES.
        #[arg(long, default_value = "Auto")]
        method: String,
        /// Seed (start and sampling).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Objective evaluations, ≥ 1 (default: the task's budget).
        #[arg(long, value_parser = at_least_one)]
        budget: Option<usize>,
        /// Hyper-parameter override, key=value (repeatable), as for `report`.
        #[arg(long = "set")]
        set: Vec<String>,
        /// Where to write the result image (tasks with images; none is written without
        /// it).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print every N-th iteration's line (and the last), ≥ 1.
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        every: u64,
        /// No per-iteration lines: the header and the result only.
        #[arg(long)]
        quiet: bool,
    },
    /// Approximate an image with N shapes; writes PNG (and SVG).
    #[command(allow_negative_numbers = true)]
    Fit2d {
        /// The target image (PNG or JPEG).
        #[arg(long)]
        target: PathBuf,
        /// Number of shapes.
        #[arg(long, default_value_t = 16)]
        shapes: usize,
        /// Shape kind: triangle, rect, ellipse or circle.
        #[arg(long, default_value = "triangle")]
        kind: String,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        /// Also write an SVG.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Seed of every random choice (same seed, same shapes).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Scale the target so that its longer side is this many pixels first (as
        /// primitive's -r; the shapes are fitted and written at that size).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
        resize: Option<u32>,
        /// Stop placing shapes after this many seconds; the shapes placed so far are
        /// written.
        #[arg(long)]
        time: Option<f64>,
    },
    /// Variance of every estimator at equal evaluation budgets (Markdown on stdout).
    #[command(allow_negative_numbers = true)]
    Variance {
        /// Repetitions per table cell.
        #[arg(long, default_value_t = 2000, value_parser = clap::value_parser!(u64).range(2..))]
        repeats: u64,
    },
    /// Generalisation suite: Auto, CMA-ES, BOBYQA and FR22 on BBOB functions, plateaus,
    /// integer plateaus, a flat direction, BOX2, noisy functions, discs rendered on a
    /// noise seed and functions that fail at random (suite.md, suite.csv, ecdf.png).
    #[command(allow_negative_numbers = true)]
    Suite {
        /// Families (comma-separated; default all): bbob, plateau, integer, flat, tasks,
        /// noisy, rendered, failing.
        #[arg(long, value_delimiter = ',')]
        families: Vec<String>,
        /// Dimensions to run (comma-separated; default every family's own: BBOB 2, 5, 10, 20, plateau 2, 4, 8, integer 2, 5, 10, flat 6, tasks 2, noisy 2, 5, 10, rendered 2, 4, 8, failing 2, 5, 10). BBOB, noisy and failing run at any n from 2 to 1000, e.g. 40,100; the other families only at their own.
        #[arg(long, value_delimiter = ',')]
        dims: Vec<usize>,
        /// Functions of the bbob, noisy and failing families (comma-separated numbers; default all): bbob 1, 2, 6, 7, 8, 10, 11, 12, 13, 14, 15; noisy 101–112; failing 1, 2, 8, 10, 15. A selected bbob, noisy or failing family none of whose functions is listed runs none.
        #[arg(long, value_delimiter = ',')]
        functions: Vec<u32>,
        /// Methods (comma-separated; default all): Auto, CMA-ES, BOBYQA, FR22.
        #[arg(long, value_delimiter = ',')]
        methods: Vec<String>,
        /// Seeds per problem (default 5, or 2 with --quick).
        #[arg(long)]
        seeds: Option<usize>,
        /// Evaluations per dimension (default 1000, or 200 with --quick).
        #[arg(long)]
        budget_per_dim: Option<usize>,
        /// n ≤ 5 (and the 6-D flat problem), 2 seeds, 2 instances, small budgets.
        #[arg(long)]
        quick: bool,
        /// Output directory.
        #[arg(long, default_value = "suite")]
        out: PathBuf,
        /// Runs at once (default 1, so that times are measured on an idle machine;
        /// results and evaluation counts do not depend on it).
        #[arg(long, default_value_t = 1)]
        jobs: usize,
    },
    /// Error against run time of every preset on QUAD, BOX2-REF and stiff quadratics.
    #[command(allow_negative_numbers = true)]
    Runtime {
        /// Seeds per task and preset.
        #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u64).range(1..))]
        seeds: u64,
        /// Draw the paper presets' central-difference gradients with common random numbers.
        #[arg(long)]
        crn: bool,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help, --version: print as clap formats them.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("hodr: {} (see --help)", clap_message(&e.to_string()));
            return ExitCode::from(2);
        }
    };
    // SIGINT (Ctrl-C) and SIGTERM alike: the work stops at its next iteration or run,
    // what is finished is written, and the exit code says which signal came.
    let interrupt = Arc::new(AtomicBool::new(false));
    let terminated = Arc::new(AtomicBool::new(false));
    for (signal, flag) in [
        (SIGINT, &interrupt),
        (SIGTERM, &interrupt),
        (SIGTERM, &terminated),
    ] {
        if let Err(e) = signal_hook::flag::register(signal, Arc::clone(flag)) {
            eprintln!("hodr: cannot watch for signal {signal}: {e}");
            return ExitCode::from(2);
        }
    }
    let result = run(cli, &interrupt);
    if let Err(e) = &result {
        eprintln!("hodr: {}", causes(e));
    }
    if STDOUT_CLOSED.load(Ordering::SeqCst) && result.is_ok() {
        ExitCode::SUCCESS
    } else if interrupt.load(Ordering::SeqCst) {
        ExitCode::from(if terminated.load(Ordering::SeqCst) {
            EXIT_SIGTERM
        } else {
            EXIT_SIGINT
        })
    } else if result.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    }
}

/// A count of at least 1, for clap.
fn at_least_one(text: &str) -> Result<usize, String> {
    match text.trim().parse::<i128>() {
        Ok(n) if n >= 1 => usize::try_from(n).map_err(|_| format!("{n} is too large")),
        Ok(n) => Err(format!("{n} is below 1")),
        Err(_) => Err(format!("`{text}` is not a whole number")),
    }
}

/// Exit code after SIGINT: 128 + 2, as shells report a process the signal ended.
const EXIT_SIGINT: u8 = 130;
/// Exit code after SIGTERM: 128 + 15.
const EXIT_SIGTERM: u8 = 143;

/// Clap's error on one line: its first line, and when that ends in a colon (a list
/// follows, e.g. the missing required arguments) the listed items.
fn clap_message(text: &str) -> String {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines
        .next()
        .unwrap_or("invalid arguments")
        .trim_start_matches("error: ");
    match first.strip_suffix(':') {
        Some(head) => {
            let items: Vec<&str> = lines
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more"))
                .collect();
            format!("{head}: {}", items.join(", "))
        }
        None => first.to_string(),
    }
}

/// An error and its causes joined by ": ", each said once: a cause whose text its
/// context already ends with (an I/O error wrapped by the image crate) is left out.
fn causes(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if parts.last().is_none_or(|last| !last.ends_with(&text)) {
            parts.push(text);
        }
    }
    parts.join(": ")
}

/// Makes sure `path` can be written before any work is done: creates its parent
/// folders (as `report` does for its directory) and opens it for writing, leaving an
/// existing file as it was and removing a file it had to create.
///
/// # Errors
/// A one-line message naming the path and the cause.
fn check_writable(path: &std::path::Path) -> Result<()> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("cannot create the folder {}", parent.display()))?;
    }
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    if !existed {
        let _ = std::fs::remove_file(path);
    }
    Ok(())
}

/// Makes sure an image can be written to `path` (given by the option `flag`) in the
/// format its extension names, before any work is done ([`check_writable`]).
///
/// # Errors
/// An extension that names no image format this build writes (PNG, JPEG), or as
/// [`check_writable`].
fn check_image_path(path: &std::path::Path, flag: &str) -> Result<()> {
    match image::ImageFormat::from_path(path) {
        Ok(format) if format.writing_enabled() => check_writable(path),
        _ => bail!(
            "{flag} {}: name the image .png or .jpg (its extension sets the format)",
            path.display()
        ),
    }
}

/// Most bytes `--params @FILE` reads: TEXTURE's 1 024 values take about 20 KB.
const MAX_PARAMS_BYTES: u64 = 1 << 20;

/// The numbers of `--params`: the text itself, or with a leading `@` the contents of
/// that file (at most [`MAX_PARAMS_BYTES`]); separated by commas and/or whitespace.
///
/// # Errors
/// An unreadable or oversized file, or a value that is not a finite number (named,
/// with its position).
fn parse_params(list: &str) -> Result<Vec<f64>> {
    let text = match list.strip_prefix('@') {
        Some(path) => {
            use std::io::Read;
            let context = || format!("reading the parameters of --params @{path}");
            let mut text = String::new();
            std::fs::File::open(path)
                .with_context(context)?
                .take(MAX_PARAMS_BYTES + 1)
                .read_to_string(&mut text)
                .with_context(context)?;
            if text.len() as u64 > MAX_PARAMS_BYTES {
                bail!(
                    "--params @{path}: the file is larger than {MAX_PARAMS_BYTES} bytes, far more than any task's parameters"
                );
            }
            text
        }
        None => list.to_string(),
    };
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|v| !v.is_empty())
        .enumerate()
        .map(|(k, v)| match v.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => bail!("--params: value {} is `{v}`, not a finite number", k + 1),
        })
        .collect()
}

/// θ for one line: every value up to 16, else the first 8 and the count.
fn brief(theta: &[f64]) -> String {
    if theta.len() <= 16 {
        format!("{theta:?}")
    } else {
        format!("{:?} … ({} parameters)", &theta[..8], theta.len())
    }
}

/// Whether `path`'s extension is `ext` (any case).
fn has_extension(path: &std::path::Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case(ext))
}

/// The shape kinds `fit2d` places (hodr-raster's fit encodes no polygon or cubic path).
const FIT_KINDS: [&str; 4] = ["triangle", "rect", "ellipse", "circle"];

/// The hyper-parameter overrides of `--set key=value` arguments.
fn overrides(set: &[String]) -> Result<Overrides> {
    let mut overrides = Overrides::default();
    for s in set {
        overrides.set(s)?;
    }
    Ok(overrides)
}

fn run(cli: Cli, interrupt: &AtomicBool) -> Result<()> {
    if cli.command.is_none() {
        eprintln!(
            "hodr: no command given, so running the quick report into {}/ (about a minute; \
             `hodr --help` lists the commands)",
            report::default_out().display()
        );
    }
    let command = cli.command.unwrap_or(Command::Report {
        tasks: Vec::new(),
        methods: Vec::new(),
        seeds: None,
        quick: true,
        budget: None,
        set: Vec::new(),
        out: report::default_out().to_path_buf(),
        suite: report::SuiteScope::Quick,
    });
    match command {
        Command::Report {
            tasks,
            methods,
            seeds,
            quick,
            budget,
            set,
            out,
            suite,
        } => {
            let config = Config {
                tasks,
                methods,
                seeds: seeds.unwrap_or(if quick { 5 } else { 20 }),
                settings: Settings {
                    quick,
                    budget,
                    overrides: overrides(&set)?,
                },
                out,
                suite,
            };
            let path = report::report(&config, interrupt, true)?;
            if interrupt.load(Ordering::Relaxed) {
                eprintln!("interrupted: wrote the finished runs");
            }
            say!("report written to {}", path.display());
        }
        Command::Tasks => {
            for t in task::all(false)? {
                say!("{:<10} n = {:<5} {}", t.name(), t.dim(), t.description());
            }
        }
        Command::Render {
            task: name,
            params,
            spp,
            out,
        } => {
            let t = task::select(std::slice::from_ref(&name), false)?.remove(0);
            let theta = match params {
                None => t.optimum(),
                Some(list) => parse_params(&list)?,
            };
            if theta.len() != t.dim() {
                bail!(
                    "{} takes {} parameters, got {}",
                    t.name(),
                    t.dim(),
                    theta.len()
                );
            }
            check_image_path(&out, "--out")?;
            let spp = match (spp, t.image_spp()) {
                (Some(_), None) => bail!(
                    "--spp applies to the path-traced tasks only; {} renders without sampling noise",
                    t.name()
                ),
                (asked, default) => asked.or(default),
            };
            let img = match spp {
                Some(spp) => t.image_with_spp(&theta, spp)?,
                None => t.image(&theta)?,
            }
            .with_context(|| format!("{} has no image", t.name()))?;
            img.save(&out)
                .with_context(|| format!("writing {}", out.display()))?;
            let at = spp.map_or(String::new(), |s| format!(" at {s} spp"));
            say!(
                "wrote {} ({}×{}{at})",
                out.display(),
                img.width(),
                img.height()
            );
        }
        Command::Optimize {
            task: name,
            method,
            seed,
            budget,
            set,
            out,
            every,
            quiet,
        } => {
            let t = task::select(std::slice::from_ref(&name), false)?.remove(0);
            let m = Method::parse(&method)?;
            if let Some(path) = &out {
                if t.image(&t.optimum())?.is_none() {
                    bail!(
                        "{} has no image to write to {} (--out applies to tasks with images)",
                        t.name(),
                        path.display()
                    );
                }
                check_image_path(path, "--out")?;
            }
            let settings = Settings {
                quick: false,
                budget,
                overrides: overrides(&set)?,
            };
            settings.check_for(&[m])?;
            say!(
                "optimize {} (n = {}) with {}, seed {seed}, budget {} evaluations",
                t.name(),
                t.dim(),
                m.name(),
                settings.budget.unwrap_or_else(|| t.budget(false))
            );
            say!("start θ₀ = {}", brief(&t.start(seed)));
            say!("truth θ* = {}", brief(&t.optimum()));
            let line = |k: usize, p: &report::Point| {
                let sigma = p.sigma.map_or(String::new(), |s| format!("  σ = {s:.3e}"));
                let step = p.step.map_or(String::new(), |(kind, descent)| {
                    format!("  {kind:?}, descent {descent}")
                });
                format!(
                    "iter {k:>4}  t = {:>9.4} s  evals = {:>7}  param error = {:.4e}  image error = {:.4e}{sigma}{step}",
                    p.time, p.evaluations, p.param_error, p.image_error
                )
            };
            let mut k = 0usize;
            let mut shown = None;
            let r = report::run_observed(t.as_ref(), m, seed, &settings, interrupt, &mut |p| {
                if !quiet && (k as u64).is_multiple_of(every) {
                    say!("{}", line(k, p));
                    shown = Some(k);
                    if STDOUT_CLOSED.load(Ordering::SeqCst) {
                        // Nobody reads the lines: stop as an interrupt would.
                        interrupt.store(true, Ordering::SeqCst);
                    }
                }
                k += 1;
            })?;
            if r.skipped() {
                bail!(
                    "{} on {}: {} (fewer pairs or a larger --budget)",
                    m.name(),
                    t.name(),
                    r.stopped.as_deref().unwrap_or_default()
                );
            }
            let last = r.points.len() - 1;
            if !quiet && shown != Some(last) {
                say!("{}", line(last, &r.points[last]));
            }
            // An interrupt has its own exit code; any other early stop is a failure,
            // reported (and the exit code set) once what was found is written.
            let failure = r.stopped.as_deref().filter(|&why| why != "interrupted");
            if failure.is_none() && r.stopped.is_some() && !STDOUT_CLOSED.load(Ordering::SeqCst) {
                eprintln!("stopped early: interrupted");
            }
            let b = &r.points[r.best];
            say!(
                "best: iteration {} of {last}, {} evaluations, param error {:.4e}, image error {:.4e}",
                r.best,
                b.evaluations,
                b.param_error,
                b.image_error
            );
            say!("θ = {}", brief(&r.best_theta));
            if let Some(path) = &out
                && let Some(img) = t.image(&r.best_theta)?
            {
                img.save(path)
                    .with_context(|| format!("writing {}", path.display()))?;
                say!("result image written to {}", path.display());
            }
            if let Some(why) = failure {
                bail!("{} on {} stopped early: {why}", m.name(), t.name());
            }
        }
        Command::Fit2d {
            target,
            shapes,
            kind,
            out,
            svg,
            seed,
            resize,
            time,
        } => {
            if let Some(t) = time
                && !(t.is_finite() && t > 0.0)
            {
                bail!("--time must be a positive number of seconds, got {t}");
            }
            if !FIT_KINDS.contains(&kind.as_str()) {
                bail!("--kind `{kind}`: fit2d places {}", FIT_KINDS.join(", "));
            }
            let kind_name = kind.as_str();
            let kind: hodr_raster::ShapeKind =
                kind_name.parse().map_err(|e| anyhow::anyhow!("{e}"))?;
            if !has_extension(&out, "png") {
                bail!("--out {}: fit2d writes a PNG; name it .png", out.display());
            }
            check_writable(&out)?;
            if let Some(svg) = &svg {
                if !has_extension(svg, "svg") {
                    bail!("--svg {}: name the SVG .svg", svg.display());
                }
                check_writable(svg)?;
            }
            let target_image = hodr_raster::Target::open(&target)?;
            let target_image = match resize {
                None => target_image,
                Some(side) => {
                    let img = image::RgbImage::from_raw(
                        target_image.width(),
                        target_image.height(),
                        target_image.rgb().to_vec(),
                    )
                    .context("the decoded target has an inconsistent size")?;
                    let scale = f64::from(side) / f64::from(img.width().max(img.height()));
                    let (w, h) = (
                        ((f64::from(img.width()) * scale).round() as u32).max(1),
                        ((f64::from(img.height()) * scale).round() as u32).max(1),
                    );
                    let small =
                        image::imageops::resize(&img, w, h, image::imageops::FilterType::Triangle);
                    hodr_raster::Target::from_rgb8(w, h, small.into_raw())?
                }
            };
            let mut options = hodr_raster::fit::FitOptions::new(shapes, kind);
            options.seed = seed;
            say!(
                "fit2d: {shapes} {kind_name} shapes to {} ({}×{}), seed {seed}{}",
                target.display(),
                target_image.width(),
                target_image.height(),
                time.map_or(String::new(), |t| if (1e-3..1e6).contains(&t) {
                    format!(", at most {t} s")
                } else {
                    format!(", at most {t:.3e} s")
                })
            );
            let clock = std::time::Instant::now();
            // Stop before the next shape on a signal or when the time is up.
            let stop = AtomicBool::new(false);
            let fit = std::thread::scope(|scope| {
                let watcher = scope.spawn(|| {
                    let done = || {
                        interrupt.load(Ordering::Relaxed)
                            || time.is_some_and(|t| clock.elapsed().as_secs_f64() >= t)
                    };
                    while !stop.load(Ordering::Relaxed) {
                        if done() {
                            stop.store(true, Ordering::Relaxed);
                            break;
                        }
                        std::thread::sleep(std::time::Duration::from_millis(20));
                    }
                });
                let bar = indicatif::ProgressBar::new(shapes as u64);
                bar.set_style(
                    indicatif::ProgressStyle::with_template(
                        "{elapsed_precise} [{bar:40}] {pos}/{len} shapes  {msg}  ETA {eta}",
                    )
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
                );
                let fit = hodr_raster::fit::fit_observed(
                    &target_image,
                    &options,
                    &stop,
                    &mut |k, rmse| {
                        bar.set_position(k as u64);
                        bar.set_message(format!("RMSE {rmse:.5}"));
                    },
                );
                bar.finish_and_clear();
                stop.store(true, Ordering::Relaxed);
                let _ = watcher.join();
                fit
            })?;
            fit.save_png(&out)?;
            if let Some(svg) = &svg {
                fit.save_svg(svg)?;
            }
            let placed = fit.scene().shapes().len();
            if interrupt.load(Ordering::Relaxed) {
                eprintln!("interrupted: wrote the {placed} shapes placed so far");
            } else if placed < shapes {
                let why = if time.is_some_and(|t| clock.elapsed().as_secs_f64() >= t) {
                    "time is up"
                } else {
                    "no further shape lowers the error"
                };
                say!("{why} after {placed} of {shapes} shapes");
            }
            say!(
                "{placed} shapes, RMSE {:.5}, {:.1} s; wrote {}",
                fit.rmse(),
                clock.elapsed().as_secs_f64(),
                out.display()
            );
        }
        Command::Variance { repeats } => {
            say_raw!("{}", hodr_host::variance::study(repeats as usize));
        }
        Command::Suite {
            families,
            dims,
            functions,
            methods,
            seeds,
            budget_per_dim,
            quick,
            out,
            jobs,
        } => {
            use hodr_host::suite;
            let config = suite::Config::from_args(
                &families,
                &dims,
                &methods,
                seeds,
                budget_per_dim,
                quick,
                out,
            )?
            .with_jobs(jobs)?
            .with_functions(&functions)?;
            let outcome = suite::run(&config, interrupt, true)?;
            if outcome.interrupted {
                eprintln!("interrupted: wrote the finished runs");
            }
            say_raw!("{}", outcome.table());
            say!("suite written to {}", config.out.join("suite.md").display());
        }
        Command::Runtime { seeds, crn } => {
            use hodr_host::runtime::{table, tasks};
            say_raw!("{}", table(&tasks(), &Preset::ALL, seeds, crn)?);
        }
    }
    Ok(())
}
