//! A suite problem: one definition holding everything a run may know about it, and
//! nothing about any method (docs/design.md §6).

use std::fmt;

use super::random;

/// f: ℝⁿ → ℝ, pure (equal points give equal values) and safe to call from several
/// threads at once.
pub type Function = Box<dyn Fn(&[f64]) -> f64 + Send + Sync>;

/// What a method observes at x, given f(x) there and how many times x was evaluated
/// before in the run: f(x) perturbed by noise drawn from x and that count (a pure
/// function of its arguments, safe to call from several threads at once).
pub type Observe = Box<dyn Fn(&[f64], f64, u64) -> f64 + Send + Sync>;

/// A render: the value at x on noise seed s, a pure function of both (safe to call from
/// several threads at once).
pub type Render = Box<dyn Fn(&[f64], u64) -> f64 + Send + Sync>;

/// How a method sees f.
pub enum Observation {
    /// f itself.
    Exact,
    /// f with noise drawn from x and how many times x was evaluated before: a renderer
    /// whose seed the method cannot pass, so that every call draws fresh noise.
    Unseeded(Observe),
    /// A render on the noise seed the method passes (hodr-core's
    /// [`Objective::evaluate`](hodr_core::Objective::evaluate)), which the problem's
    /// f is the noiseless reference of: values on one seed compare closely, values on
    /// different seeds differ by the render's noise. A method that passes no seed
    /// (CMA-ES, BOBYQA) gets a fresh one at every evaluation.
    Seeded(Render),
}

/// The start distribution: θ₀ as a pure function of a run seed.
pub type StartFn = Box<dyn Fn(u64) -> Vec<f64> + Send + Sync>;

/// The largest n the BBOB and noisy families run at: each instance holds two n×n
/// rotations (16 MB at this n), and a run's budget grows with n.
pub const MAX_DIM: usize = 1000;

/// A family of problems, selected together on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// BBOB noiseless functions (Hansen et al. 2009), [`super::bbob`].
    Bbob,
    /// Discs on a point-sampled image, started off their targets, [`super::plateau`].
    Plateau,
    /// A smooth function of round(x), [`super::plateau::integer`].
    Integer,
    /// A stiff quadratic with one ignored coordinate, [`super::flat`].
    Flat,
    /// Built-in rendering tasks (BOX2), [`super::tasks`].
    Tasks,
    /// The sphere and Rosenbrock's function under BBOB's noise models, [`super::noisy`].
    Noisy,
    /// The disc plateaus rendered by Monte Carlo on the method's noise seed,
    /// [`super::rendered`].
    Rendered,
    /// BBOB functions whose evaluations fail (NaN) at random, [`super::failing`].
    Failing,
}

impl Family {
    /// Every family, in run order.
    pub const ALL: [Family; 8] = [
        Family::Bbob,
        Family::Plateau,
        Family::Integer,
        Family::Flat,
        Family::Tasks,
        Family::Noisy,
        Family::Rendered,
        Family::Failing,
    ];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Family::Bbob => "bbob",
            Family::Plateau => "plateau",
            Family::Integer => "integer",
            Family::Flat => "flat",
            Family::Tasks => "tasks",
            Family::Noisy => "noisy",
            Family::Rendered => "rendered",
            Family::Failing => "failing",
        }
    }

    /// The family called `name` (case-insensitive).
    pub fn from_name(name: &str) -> Option<Family> {
        Family::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Whether the family has problems of dimension n: any n from 2 to [`MAX_DIM`] for
    /// BBOB and its noisy and failing variants, whose functions are defined in every
    /// dimension; the family's own [`Family::dims`] for the others.
    pub fn defined_at(self, n: usize) -> bool {
        match self {
            Family::Bbob | Family::Noisy | Family::Failing => (2..=MAX_DIM).contains(&n),
            _ => self.dims().contains(&n),
        }
    }

    /// The dimensions the family runs at by default.
    pub fn dims(self) -> &'static [usize] {
        match self {
            Family::Bbob => &[2, 5, 10, 20],
            Family::Plateau | Family::Rendered => &[2, 4, 8],
            Family::Integer => &[2, 5, 10],
            Family::Flat => &[super::flat::DIM],
            Family::Tasks => &[2],
            Family::Noisy | Family::Failing => &[2, 5, 10],
        }
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How the distance of a point x to the optimum x* is measured (the parameter error).
#[derive(Clone, Debug, PartialEq)]
pub enum Measure {
    /// ‖x − x*‖.
    Euclidean,
    /// ‖round(x) − x*‖: on a function of round(x) every point of the optimum's unit
    /// cell is optimal, so only the rounded point is judged.
    Rounded,
    /// ‖x − x*‖ over the first `k` coordinates: the others do not affect f.
    Leading(usize),
    /// x lists `n / 2` interchangeable 2-D positions: min over assignments π of
    /// √(Σₖ ‖xₖ − x*_π(k)‖²).
    UnorderedPairs,
}

impl Measure {
    /// The parameter error of `x` against `x_opt`.
    pub fn error(&self, x: &[f64], x_opt: &[f64]) -> f64 {
        let dist = crate::tasks::distance;
        match self {
            Measure::Euclidean => dist(x, x_opt),
            Measure::Rounded => {
                let r: Vec<f64> = x.iter().map(|v| v.round()).collect();
                dist(&r, x_opt)
            }
            Measure::Leading(k) => dist(&x[..*k], &x_opt[..*k]),
            Measure::UnorderedPairs => {
                let k = x.len() / 2;
                random::permutations(k)
                    .iter()
                    .map(|perm| {
                        perm.iter()
                            .enumerate()
                            .map(|(i, &j)| {
                                (x[2 * i] - x_opt[2 * j]).powi(2)
                                    + (x[2 * i + 1] - x_opt[2 * j + 1]).powi(2)
                            })
                            .sum::<f64>()
                    })
                    .fold(f64::INFINITY, f64::min)
                    .sqrt()
            }
        }
    }
}

/// Box bounds lower ≤ x ≤ upper, per coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// Lower bounds.
    pub lower: Vec<f64>,
    /// Upper bounds.
    pub upper: Vec<f64>,
}

impl Bounds {
    /// The same interval [lo, hi] on each of n coordinates.
    pub fn cube(n: usize, lo: f64, hi: f64) -> Bounds {
        Bounds {
            lower: vec![lo; n],
            upper: vec![hi; n],
        }
    }

    /// x clamped into the box, coordinate by coordinate.
    pub fn clamp(&self, x: &mut [f64]) {
        for ((v, lo), hi) in x.iter_mut().zip(&self.lower).zip(&self.upper) {
            *v = v.clamp(*lo, *hi);
        }
    }

    /// x reflected into the box, coordinate by coordinate: across a violated bound, and
    /// again across the other for points more than one box width out — the periodic
    /// mirror y = lo + L − |L − ((x − lo) mod 2L)|, L = hi − lo. The identity inside the
    /// box and on coordinates with an infinite bound. Unlike clamping, it leaves no
    /// region outside the box where f stops depending on x.
    pub fn reflect(&self, x: &mut [f64]) {
        for ((v, &lo), &hi) in x.iter_mut().zip(&self.lower).zip(&self.upper) {
            let width = hi - lo;
            if (lo..=hi).contains(v) || !width.is_finite() || width <= 0.0 {
                continue;
            }
            let t = (*v - lo).rem_euclid(2.0 * width);
            *v = (lo + width - (width - t).abs()).clamp(lo, hi);
        }
    }

    /// The smallest upper − lower over the coordinates.
    pub fn narrowest(&self) -> f64 {
        self.lower
            .iter()
            .zip(&self.upper)
            .map(|(lo, hi)| hi - lo)
            .fold(f64::INFINITY, f64::min)
    }
}

/// One problem of the suite: f, its optimum, how runs start and what they may spend.
pub struct Problem {
    /// Unique name, e.g. `bbob-f08-n05-i2`; seeds derive from it.
    pub name: String,
    /// The family.
    pub family: Family,
    /// Dimension n.
    pub n: usize,
    /// f, noiseless: what runs are judged on.
    pub f: Function,
    /// How a method sees f.
    pub observation: Observation,
    /// f* = min f, the value runs are judged against (f − f*).
    pub f_opt: f64,
    /// A minimiser x*, for the parameter error.
    pub x_opt: Vec<f64>,
    /// How the parameter error is measured.
    pub measure: Measure,
    /// θ₀ from a run seed.
    pub start: StartFn,
    /// σ₀: the distance over which the parameters matter (CMA-ES's initial step size).
    pub sigma0: f64,
    /// Box bounds, if the problem has them.
    pub bounds: Option<Bounds>,
    /// Objective evaluations per run.
    pub budget: usize,
}

impl Problem {
    /// f(x), noiseless.
    pub fn value(&self, x: &[f64]) -> f64 {
        (self.f)(x)
    }

    /// What a method that passes no noise seed sees at x on its `repeat`-th evaluation
    /// there (0 for the first): f(x), f(x) with the problem's noise, or a render of x
    /// on a seed drawn from x and `repeat`.
    pub fn observe(&self, x: &[f64], repeat: u64) -> f64 {
        match &self.observation {
            Observation::Exact => self.value(x),
            Observation::Unseeded(observe) => observe(x, self.value(x), repeat),
            Observation::Seeded(render) => render(
                x,
                random::seed_of("fresh", &[random::point_seed(x), repeat]),
            ),
        }
    }

    /// What a method sees at x on noise seed `seed` on its `repeat`-th evaluation there:
    /// a render on that seed where the problem is [`Observation::Seeded`], otherwise
    /// [`Problem::observe`] (the seed is ignored).
    pub fn observe_on(&self, x: &[f64], seed: u64, repeat: u64) -> f64 {
        match &self.observation {
            Observation::Seeded(render) => render(x, seed),
            _ => self.observe(x, repeat),
        }
    }

    /// Whether the problem is noisy (a method sees other values than f's).
    pub fn is_noisy(&self) -> bool {
        !matches!(self.observation, Observation::Exact)
    }

    /// Whether the problem renders on the method's noise seed ([`Observation::Seeded`]).
    pub fn is_seeded(&self) -> bool {
        matches!(self.observation, Observation::Seeded(_))
    }

    /// The parameter error of x ([`Problem::measure`]).
    pub fn param_error(&self, x: &[f64]) -> f64 {
        self.measure.error(x, &self.x_opt)
    }

    /// The start of run `seed` (already a run seed, see [`run_seed`]).
    pub fn start(&self, seed: u64) -> Vec<f64> {
        (self.start)(seed)
    }
}

impl fmt::Debug for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Problem")
            .field("name", &self.name)
            .field("family", &self.family)
            .field("n", &self.n)
            .field("f_opt", &self.f_opt)
            .field("noisy", &self.is_noisy())
            .field("sigma0", &self.sigma0)
            .field("bounds", &self.bounds)
            .field("budget", &self.budget)
            .finish_non_exhaustive()
    }
}

/// The seed of run `index` on the problem called `name`: a function of these two only,
/// so adding methods, problems or seeds never changes another run.
pub fn run_seed(name: &str, index: usize) -> u64 {
    random::seed_of(name, &[index as u64])
}

/// A start uniform in the open cube (lo, hi)ⁿ drawn from the run seed.
pub fn uniform_start(n: usize, lo: f64, hi: f64) -> StartFn {
    Box::new(move |seed| random::uniform(n, lo, hi, random::seed_of("start", &[seed])))
}
