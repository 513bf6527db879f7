//! Auto's public vocabulary: its options ([`AutoOptions`], [`NonFinite`]), what each
//! iteration reports ([`AutoReport`], [`AutoStep`]) and how a run ends
//! ([`AutoTermination`]).

use core::fmt;

use crate::error::Error;
use crate::real::Real;

/// What to do with an objective value that is NaN or ±∞.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum NonFinite {
    /// The point counts as worse than any finite value: a trial point there is rejected,
    /// and on an objective not declared noisy the model is fitted to it at just above the
    /// largest finite value remembered near it, so that the steps follow a wall of such
    /// points (a constraint the objective enforces by failing) instead of running into
    /// it. A failed evaluation is first repeated at its point and seed, until
    /// [`FAILURE_CHECKS`](super::FAILURE_CHECKS) repeats have failed too, then at each
    /// doubling of the failures; once a repeat returns a finite value, the objective
    /// fails at random and each failure is repeated while the next repeat is likely
    /// enough to return a value, by the rate of random failures and the share of failed
    /// points that are a wall's, as the run has seen them. Default.
    #[default]
    Worst,
    /// [`Auto::step`](super::Auto::step) returns [`Error::NonFiniteObjective`]; θ is unchanged.
    Error,
}

/// The shape of Auto's local model of f and of its sampling metric, chosen when the run
/// is made ([`Auto::with_model`](super::Auto::with_model)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum AutoModel {
    /// [`AutoModel::Full`] up to n = 14, where its memory determines it;
    /// [`AutoModel::Diagonal`] above [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM);
    /// in between the full model, unless the first step finds a deterministic f
    /// separable, f(x) = Σᵢ gᵢ(xᵢ), to rounding — a test of 4 + 2⌈log₂ n⌉ evaluations
    /// (14 at n = 20), f(x₀) among them, which the run does not evaluate again — and
    /// takes the diagonal one, which holds such an f's curvature exactly
    /// ([`Auto::model`](super::Auto::model) says which). Default.
    #[default]
    ByDimension,
    /// A full Hessian, (n + 1)(n + 2)/2 coefficients, and a full metric C: learns
    /// curvature along any directions, a rotated ellipsoid's or a curved valley's. From
    /// n = 15 its memory holds fewer points than it has coefficients, and each fit leans
    /// on the last. At most n = [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM).
    Full,
    /// A diagonal Hessian, 2n + 1 coefficients, and a diagonal metric (one scale per
    /// coordinate): a memory of 2(2n + 1) + n + 1 points, at most
    /// [`MAX_MEMORY`](super::MAX_MEMORY), more than its coefficients up to n = 63; O(n)
    /// per point; blind to curvature across coordinates, so that a rotated
    /// ill-conditioned f stalls it. Above n = 14, where the full model's fits lean on
    /// their priors, it suits an f whose parameters interact little: a sum of terms in
    /// one or a few of them, kinks about an isotropic minimum (BENCHMARKS.md, "A seventh
    /// set").
    Diagonal,
}

impl AutoModel {
    /// Floats of buffer a run with this model needs in dimension n
    /// ([`Auto::with_model`](super::Auto::with_model)). [`AutoModel::ByDimension`]'s is
    /// [`buffer_len`](super::buffer_len)`(n)`, which holds either shape, since from
    /// n = 15 the run may take the diagonal model after its first step;
    /// [`AutoModel::Full`]'s is the same up to n =
    /// [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM) (above, `with_model` refuses
    /// the full model whatever the buffer); [`AutoModel::Diagonal`]'s, whose memory holds
    /// at most [`MAX_MEMORY`](super::MAX_MEMORY) points where the full model's holds
    /// [`FULL_MEMORY_PER_DIM`](super::FULL_MEMORY_PER_DIM)·n,
    /// is a thirteenth of it at n = 100: a run without a heap at such n sizes its
    /// storage by it.
    ///
    /// ```
    /// use hodr_core::optim::auto::{AutoModel, buffer_len};
    ///
    /// const FLOATS: usize = AutoModel::Diagonal.buffer_len(100);
    /// assert!(FLOATS * 10 < buffer_len(100));
    /// assert_eq!(AutoModel::ByDimension.buffer_len(100), buffer_len(100));
    /// ```
    pub const fn buffer_len(self, n: usize) -> usize {
        match self {
            AutoModel::ByDimension => super::buffer_len(n),
            AutoModel::Full => super::memory::buffer_len_of(super::model::Shape::Full, n),
            AutoModel::Diagonal => super::memory::buffer_len_of(super::model::Shape::Diagonal, n),
        }
    }
}

/// Auto's options. Every one has a default; none is required.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct AutoOptions<T> {
    /// The run converges (and restarts, see [`AutoOptions::restarts`]) once every
    /// coordinate's spread σ√Cᵢᵢ is below `tolerance` times its spread at the start (a
    /// deterministic objective, once the run has found a value below f(x₀); before, σ
    /// may shrink to θ's resolution 8ε·maxᵢ|θᵢ|), or once σ < `tolerance`·σ₀ (a noisy
    /// one). Default:
    /// `None`, meaning [`TOLERANCE`](super::TOLERANCE) for a deterministic objective and
    /// [`NOISY_TOLERANCE`](super::NOISY_TOLERANCE) for a noisy one.
    pub tolerance: Option<T>,
    /// Iterations without a lower f(θ) after which the run restarts from the best point
    /// (see [`AutoOptions::restarts`]) or ends stagnated. In the first descent before its
    /// first gain, on a deterministic objective, the count also starts again whenever a
    /// rejected step to the trust region's boundary takes σ below its lowest so far: σ₀
    /// overstates the scale at which f is a quadratic, and σ is still shrinking to it.
    /// Default: `None`, meaning 20 + 10n.
    pub patience: Option<usize>,
    /// A descent restarts from its best point whenever it converges or stagnates with a
    /// lower f(θ) since its last restart (or its start); once a restart has found none,
    /// `restarts` more in a row without a lower f(θ) are made before the descent ends.
    /// (Where no fresh start follows, a restart's gains count once they have moved the
    /// best point by `tolerance` times its start scale in some coordinate, summed over
    /// the gains.)
    /// The k-th restart of a run is at σ₀·2^(k mod 5): σ₀, 2σ₀, …, [`PLATEAU_WIDTH`](super::PLATEAU_WIDTH)·σ₀
    /// (and, with bounds, at most half the box's widest side), then σ₀ again. Each
    /// looks around its scale with n antithetic pairs (at most half the memory's
    /// worth). Default: `None`, meaning [`RESTARTS_BEFORE_FRESH`](super::RESTARTS_BEFORE_FRESH) where a fresh start
    /// follows the descent (see [`AutoOptions::fresh_starts`]) and [`RESTARTS`](super::RESTARTS) where
    /// the descent is the run.
    pub restarts: Option<usize>,
    /// Objective evaluations after which the run stops; never exceeded. Default: none
    /// (the run still ends after [`unbudgeted_cap`](super::unbudgeted_cap)`(n)`
    /// evaluations, [`AutoTermination::EvaluationCap`]).
    pub max_evaluations: Option<usize>,
    /// Whether a run with a budget ([`AutoOptions::max_evaluations`]) on a
    /// deterministic objective spends what its descent leaves: once a descent ends
    /// (converged, or stagnated after its [`AutoOptions::restarts`]), another starts
    /// from a point about the best one, as basin hopping does (each coordinate moved
    /// by its start scale times 2^(k mod 5) times a standard normal draw at the k-th
    /// fresh start, at the widest (k mod 5 = 4) by at least its side of the box, and
    /// mirrored into the box), with its memory, model and metric started over and σ at the same σ₀·2^(k mod 5) (at most 16σ₀ or half the box's widest
    /// side), where continuation applies as after a restart: the wider the jump, the
    /// wider its descent's first look at the smoothed objective, whose minimum lies
    /// past the wells of a bowl's multi-modal surface. Once a probe
    /// ([`AutoOptions::probes`]) has found a point below the best, or two wide
    /// descents in a row have ended on the same value, later fresh descents start at
    /// σ₀: the run's minima are one object wrong, which the probes fix, or the
    /// smoothed objective leads to one point, which is then known. A later descent
    /// ends early where its model shows its basin worse than the best point's
    /// ([`HOPELESS_FITS`](super::HOPELESS_FITS)). The best point of all descents is
    /// kept, and the run ends with its budget. A run without a budget,
    /// or on a noisy objective (values of different descents would not compare), ends
    /// with its first descent. Default: `true`.
    pub fresh_starts: bool,
    /// Whether a descent that ends on a flat piece of f — some remembered point other
    /// than θ has exactly f(θ)'s value, farther from θ than f's rounding explains (a
    /// smooth f's values round to f(θ) within √(w/q) of its minimum, w the width within
    /// which values tie (16 ulps of f(θ) at f's precision, T's or f32's), q the least
    /// rise per squared distance of the untied points near θ),
    /// on an objective whose values are exact, and f(θ) is below every earlier descent's —
    /// moves θ to the piece's centre before the run goes on:
    /// along each parameter axis, the midpoint of the piece's two edges, each found by
    /// probes that start as far out as a tied point lies, grow ×4 and then bisect to
    /// 1/16 of the edge's distance (one batch of at most 2n probes per round), where
    /// that point keeps f(θ). An axis along which f stays flat up to 16 times its start
    /// scale (and no face of the box bounds it) keeps θ's value.
    /// A rasteriser without anti-aliasing, or coordinates rounded before f, leaves θ
    /// anywhere within a pixel's or a cell's width of the truth; the centre is where
    /// the smoothed objective's minimum tends as σ → 0. The search is one iteration
    /// ([`AutoStep::Centred`]); a probe below f(θ) moves θ there and the descent goes
    /// on. Default: `true`.
    pub centre: bool,
    /// Probes per coordinate before each fresh start ([`AutoOptions::fresh_starts`]):
    /// up to `probes`·n points, n per iteration ([`AutoStep::Probed`]), and more in a
    /// later phase where the run's probes have found lower points more often than its
    /// fresh descents (at most [`SHARE_RANGE`](super::SHARE_RANGE) times as many). Each
    /// probe is the best
    /// point so far with one contiguous block of 1, 2, 4, … ≤ n/2 of its coordinates
    /// (its length and then its place, aligned to the length, drawn uniformly) moved: a
    /// coordinate boxed on both sides drawn uniformly over its box within 32 start
    /// scales of the best point's (anywhere in it at k = 4), any other moved by its
    /// start scale times 2^k (k uniform over 0 … 4) times a standard normal draw,
    /// mirrored into a bound it has.
    /// The first batch with a point below the best one moves θ
    /// there and starts the next descent from it; where none is, the fresh start
    /// follows. A descent that ends with one object wrong and the rest right (a shape
    /// hidden under another, one coordinate in the wrong cell of a lattice) is left by
    /// moving that object's parameters alone, which a fresh start, moving all of them,
    /// rarely does; the parameters of one object usually sit side by side in θ. 0: no
    /// probes. Default: [`PROBES`](super::PROBES).
    pub probes: usize,
    /// Policy for NaN/±∞ objective values. Default: [`NonFinite::Worst`].
    pub non_finite: NonFinite,
}

impl<T: Real> Default for AutoOptions<T> {
    fn default() -> Self {
        AutoOptions {
            tolerance: None,
            patience: None,
            restarts: None,
            max_evaluations: None,
            fresh_starts: true,
            centre: true,
            probes: super::PROBES,
            non_finite: NonFinite::Worst,
        }
    }
}

impl<T: Real> AutoOptions<T> {
    /// Sets [`AutoOptions::tolerance`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] unless 0 < `tolerance` < 1.
    pub fn with_tolerance(mut self, tolerance: T) -> Result<Self, Error> {
        if !(tolerance > T::ZERO && tolerance < T::ONE) {
            return Err(Error::InvalidSetting { name: "tolerance" });
        }
        self.tolerance = Some(tolerance);
        Ok(self)
    }

    /// Sets [`AutoOptions::patience`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_patience(mut self, patience: usize) -> Result<Self, Error> {
        if patience == 0 {
            return Err(Error::InvalidSetting { name: "patience" });
        }
        self.patience = Some(patience);
        Ok(self)
    }

    /// Sets [`AutoOptions::restarts`] (0: the descent ends once a restart has found no
    /// lower f(θ)).
    pub fn with_restarts(mut self, restarts: usize) -> Self {
        self.restarts = Some(restarts);
        self
    }

    /// Sets [`AutoOptions::max_evaluations`].
    ///
    /// # Errors
    /// [`Error::InvalidSetting`] for 0.
    pub fn with_max_evaluations(mut self, max: usize) -> Result<Self, Error> {
        if max == 0 {
            return Err(Error::InvalidSetting {
                name: "max_evaluations",
            });
        }
        self.max_evaluations = Some(max);
        Ok(self)
    }

    /// Sets [`AutoOptions::fresh_starts`] (false: the run ends with its first descent,
    /// budget or not).
    pub fn with_fresh_starts(mut self, fresh_starts: bool) -> Self {
        self.fresh_starts = fresh_starts;
        self
    }

    /// Sets [`AutoOptions::centre`] (false: a descent that ends on a flat piece of f
    /// leaves θ where it entered the piece).
    pub fn with_centre(mut self, centre: bool) -> Self {
        self.centre = centre;
        self
    }

    /// Sets [`AutoOptions::probes`] (0: a fresh start follows a descent at once).
    pub fn with_probes(mut self, probes: usize) -> Self {
        self.probes = probes;
        self
    }

    /// Sets [`AutoOptions::non_finite`].
    pub fn with_non_finite(mut self, policy: NonFinite) -> Self {
        self.non_finite = policy;
        self
    }
}

/// Why an Auto run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum AutoTermination {
    /// The samples' spread fell below [`AutoOptions::tolerance`] of its start, or σ below
    /// what T resolves at θ, or the model's promise below what T resolves of f(θ)
    /// ([`UNRESOLVED_FITS`](super::UNRESOLVED_FITS)), or the samples tie with f(θ) by
    /// f's rounding alone right after the model confirmed θ as its minimum, or the
    /// descent's values settled (a window of iterations lowered f(θ) by at most ε of
    /// the descent's fall: an infimum approached along an asymptote), or the box leaves
    /// a single point (every lower bound equal to its upper bound), which has been
    /// evaluated.
    Converged,
    /// [`AutoOptions::patience`] iterations passed without a lower f(θ).
    Stagnated,
    /// [`AutoOptions::max_evaluations`] were used.
    MaxEvaluations,
    /// Some coordinate's spread grew past [`DIVERGENCE_WIDTH`](super::DIVERGENCE_WIDTH)
    /// times its start scale, or f(θ) fell below −[`Auto::max_scale`](super::Auto::max_scale)
    /// (−9.7e288 in f64, −1.8e19 in f32): the objective looks unbounded below (or σ₀
    /// understates the problem's scale about as much). The run ends, whatever its
    /// budget, at the best point found.
    Diverged,
    /// A run without a budget used [`unbudgeted_cap`](super::unbudgeted_cap)`(n)`
    /// evaluations without converging: f may approach its infimum only at infinity, or
    /// its noise hide what is left to gain. θ is the best point found.
    EvaluationCap,
}

impl fmt::Display for AutoTermination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AutoTermination::Converged => "converged (spread below tolerance, or f settled)",
            AutoTermination::Stagnated => "stagnated (no lower value within the patience)",
            AutoTermination::MaxEvaluations => "evaluation budget used",
            AutoTermination::EvaluationCap => {
                "evaluation cap of a run without a budget reached (f may approach its infimum only at infinity, or be too noisy to converge; give a budget to run longer)"
            }
            AutoTermination::Diverged => {
                "diverged (spread grew 2^64-fold or f fell below -2^-64 of the largest float: f may be unbounded below, or sigma0 far too small)"
            }
        })
    }
}

/// What an iteration did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AutoStep {
    /// The values within reach tied: σ widened, no step.
    Plateau,
    /// The model's minimum is at θ (no predicted decrease): σ shrank, nothing evaluated.
    AtModelMinimum,
    /// The trial point had a lower value and replaced θ.
    Accepted,
    /// The trial point was no better; θ stayed.
    Rejected,
    /// The trial point was no better, but the run's search centre moved there: after a
    /// restart, at a scale above σ₀'s, where the model's minimum lies inside the trust
    /// region (continuation on the smoothed objective). The best point is kept.
    Continued,
    /// The budget ran out before the iteration could compare a step.
    OutOfBudget,
    /// The descent had ended on a flat piece of f, and θ moved to the piece's centre
    /// (or stayed, where the piece had no centre or its centre was higher); see
    /// [`AutoOptions::centre`].
    Centred,
    /// Probes about the best point before a fresh start ([`AutoOptions::probes`]): none
    /// was below it (more follow, or the fresh start), or θ moved to the lowest, where
    /// the next descent starts.
    Probed,
}

/// One iteration's plain-data report.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoReport<T> {
    /// 1-based iteration number.
    pub iteration: usize,
    /// Objective evaluations so far (all iterations).
    pub evaluations: usize,
    /// σ this iteration used (its trust radius is σ√n).
    pub sigma: T,
    /// σ for the next iteration.
    pub next_sigma: T,
    /// f at the best point so far ([`Auto::theta`](super::Auto::theta)) after the
    /// iteration, when known and finite (the search centre may lie above it: after a
    /// continuation move, during probes, in a later descent).
    pub value: Option<T>,
    /// The descent the run is in once the iteration has ended, from 1
    /// ([`Auto::descents`](super::Auto::descents)): the iteration that begins a descent
    /// reports it.
    pub descent: usize,
    /// Distance θ moved (including a move to a lower sample).
    pub step_length: T,
    /// Actual over predicted decrease of the trial step, when one was evaluated.
    pub ratio: Option<T>,
    /// What the iteration did.
    pub kind: AutoStep,
    /// Set when this iteration ended the run.
    pub termination: Option<AutoTermination>,
}
