//! `Auto`: hodr's default optimiser. It needs a start x₀ and a scale σ₀ — the distance
//! over which the parameters matter, as CMA-ES asks for; one per coordinate
//! ([`Auto::with_scales`]) where they come in different units — and optionally box
//! bounds; nothing else.
//!
//! Auto is a trust-region method on a smoothed quadratic model that remembers its
//! evaluations:
//!
//! * **Memory.** Every evaluation is kept (up to [`Auto::history_len`] points, about twice
//!   the model's coefficients; when full, the point farthest from θ gives way, and
//!   a survey's rows only to points older than the survey, not θ's own). Each
//!   iteration fits the model m(θ + σu) = c + gᵀu + ½uᵀHu to the remembered points
//!   within reach, weighted by w = exp(−½(z/ρ)²), z = ‖L⁻¹(x − θ)‖/(σ√n),
//!   ρ = [`REACH`], by ridge regression towards the previous iteration's model (the
//!   `model` module): an overdetermined fit averages the points over a Gaussian of width
//!   ~σ, as hodr's estimators average samples, so the model is that of the *smoothed*
//!   objective; an underdetermined one changes the curvature least, as Powell's NEWUOA
//!   does, so curvature learnt earlier is kept.
//!   A full Hessian is modelled for n ≤ [`FULL_MODEL_MAX_DIM`], a diagonal one above;
//!   the memory holds at most [`MAX_MEMORY`] points, so that an iteration's cost is
//!   bounded for a full model and linear in n for a diagonal one (the `model` module says
//!   how a fit with fewer points than coefficients learns).
//! * **Samples.** Where fewer than n + 1 remembered points (or half the memory, if
//!   smaller) lie within z ≤ ρ, the iteration evaluates antithetic pairs θ ± σ√n·b along
//!   Lb, b the columns of a random orthonormal frame (n pairs, or half the memory's
//!   worth, and θ on the first iteration). A model that puts its minimum at θ shrinks
//!   σ only once more than 2q − 2 remembered points lie within reach, q the count
//!   above; short of that, the next iteration draws the pairs it lacks in one batch
//!   (one pair per iteration on a declared-noisy objective): one fit instead of one per
//!   pair, and a batch the caller can evaluate in parallel. A restart's survey of a
//!   full model runs along the parameter axes instead, each scaled to unit length in
//!   whitened coordinates, wherever the metric keeps them nearly orthogonal there
//!   ([`AXIS_COHERENCE`]) — except a noisy objective's from θ on a face of the box,
//!   where pairs along the axes normal to it fold onto one point. A half that would
//!   leave the box stops at the face on its line (so the pair still fixes the slope and
//!   curvature along it, and a survey of a quadratic gives the exact model) unless that
//!   keeps less than an eighth of its length. Such a half, the pairs drawn to explore
//!   (below), and every pair from n = 15 (where the memory is smaller than the full
//!   model, and for the diagonal model) are mirrored into the box at the faces they
//!   cross instead, keeping their reach. The two halves of a pair share a noise seed,
//!   so where mirroring folds them onto one point (from a corner every pair folds) that
//!   point is evaluated once, unless the objective draws unseeded noise.
//! * **Metric.** Samples, reach and the trust region live in whitened coordinates
//!   u = L⁻¹(x − θ)/σ, C = LLᵀ a shape (det C = 1) that moves towards |H|⁻¹ after each
//!   step the model predicted (the `metric` module), as CMA-ES's covariance follows its
//!   population: ill-conditioned valleys look round. On a deterministic objective a
//!   model its points determine (more of them than coefficients, fitted within
//!   [`SMOOTH`], off a lattice, θ off the box's faces) moves C too, at
//!   [`DETERMINED_METRIC_WEIGHT`] of the rate, whatever its step did: on a sharp ridge
//!   (a cone, as an L1 image loss makes) no quadratic predicts f's steps, yet the
//!   smoothed curvature across the ridge is what stretches C along it. Where no fit
//!   can be determined (n = 15–20), a model whose whitened curvature is still far from
//!   round after n unconfirmed steps moves C at that weight too
//!   ([`STALLED_ANISOTROPY`]): a stiff direction the metric has not squashed otherwise
//!   stalls the run for good. A survey along the axes that finds some coordinates flat
//!   (both halves of their pairs tie with f(θ)) and f moving both ways along others
//!   stretches C along the flat ones ([`FLAT_STRETCH`]): one object of a scene still on
//!   its plateau while the others are fitted needs wider samples than they can bear.
//!   A full C also stretches along the evolution path of θ's accepted steps, CMA-ES's
//!   rank-one update (`Auto::follow_path`), off lattices, rough f and noise: a ridge's
//!   direction, which its cone's fitted curvature never gives precisely enough.
//!   C has the model's shape: full for n ≤ [`FULL_MODEL_MAX_DIM`], diagonal above (per-coordinate
//!   scales).
//! * **Noise.** A stochastic objective ([`Objective::deterministic`] false) — a Monte
//!   Carlo render — is evaluated on common random numbers: an iteration's samples, θ
//!   beside them and its trial point share one seed (where it draws no samples, θ and
//!   the trial point share a fresh one). The points of one seed form a *noise group*:
//!   the model gives each group a free offset, because a render's level moves from
//!   seed to seed by far more than the differences between nearby θ on one seed, so
//!   only differences within a group inform g and H, and values are compared (θ's
//!   replacement, ties, the values' spread) only within a group.
//! * **Unseeded noise.** An objective declared deterministic is checked: at the first
//!   model step after each restart (until noise is found) θ is evaluated once more,
//!   unremembered. Where the two values differ, the objective draws fresh noise at
//!   every call — a renderer whose seed is not passed on — and a lucky draw of f(θ)
//!   rejects every later step, which is how such a descent ends; a third draw then
//!   tells noise that every draw carries (all three differ) from sparse outliers on
//!   exact values, and only the former's rejections within the noise keep σ (below).
//!   From then on the fit gives each point a robustness weight, Tukey's biweight of its
//!   residual (one step of iteratively reweighted least squares per iteration), so
//!   that an outlier — a Cauchy noise spike — loses its pull; where θ's own draw is
//!   such an outlier, θ is drawn again; and after a rejected trial, where θ's draw lies
//!   below the robust fit, θ is drawn again beside the next one (until
//!   [`THETA_DRAWS`] draws), trials being compared with the median of θ's draws, so
//!   that a draw from the noise's low tail cannot hold θ by itself. Sparse outliers
//!   (the check's draws did not all differ, or two remembered draws at one point
//!   agree) are voted out instead: from then on every point is drawn until two of its
//!   draws agree exactly (at most [`VOTES`] draws, else their median), which costs
//!   about 2/(1 − p) evaluations per point for an outlier rate p; the voted values are
//!   exact, so the rules kept for deterministic objectives (continuation, the metric
//!   from determined fits) apply to them too. Without the vote a model fitted to fewer
//!   points than it has coefficients interpolates the outliers, which no residual then
//!   exposes, and predicts steps from them.
//! * **Step.** The model's minimiser within ‖s‖ ≤ σ√n (the `trust` module: exact for
//!   indefinite H, so a non-PSD model steps along its negative curvature) is evaluated;
//!   where it would leave the box, the coordinates it carries out are held on the
//!   bounds they cross and the model is minimised again over the rest of the region. It
//!   replaces θ when f is no higher there on common noise (a tie moves to the smoothed
//!   model's minimum of a flat piece of f). A sample lower than f(θ) on its seed
//!   replaces θ too.
//! * **σ is the trust radius** and follows the ratio ρ̂ of actual to predicted decrease:
//!   ρ̂ ≥ 0.7 with a step to the boundary doubles σ; on a deterministic objective, a step
//!   to the boundary that lowered f with ρ̂ < 0.1 grows σ by 2^¼ (the model overstated
//!   the decrease — a kink or a ridge that its fit smooths over, which a smaller σ fits
//!   no better — but not the direction); a step shorter than half the radius
//!   shrinks σ towards twice its length (at most halving it); ρ̂ < 0.1 shrinks σ by
//!   [`SHRINK`] (halves it on a declared-noisy objective) — unless
//!   the points within reach do not determine the model (no more of them than it has
//!   coefficients, for n ≤ 14; at most 2n, or all but two of a full memory, above), so
//!   that it rests on its prior or on points from wider scales, where a kink's
//!   smoothed curvature is flatter (a cone's falls as 1/σ) and the model would
//!   mispredict alike at every smaller σ (on a declared-noisy objective: at most 2n
//!   within reach and no more points fitted than coefficients) — or, on an unseeded
//!   objective whose draws never agree exactly, the trial fell short by less than
//!   [`NOISE_MARGIN`] times the noise's scale (below): then a pair is drawn at the same
//!   σ first), or the fit finds f rough at this scale (residual scatter above
//!   [`ROUGH`] of the values' spread) and the trial lies within twice that scatter, or
//!   the objective is unseeded and both the trial's shortfall and the step's promise
//!   lie within twice the noise's scale (the median |f − f′| over pairs of repeated
//!   draws at one point): then σ doubles, as on a plateau.
//! * **Plateaus.** Where most of an iteration's samples tie with f(θ) (or, where it
//!   drew none, every remembered value within reach does), σ doubles (up to
//!   [`PLATEAU_WIDTH`]·σ₀) and an exploring pair is drawn at a Gaussian distance σ‖t‖,
//!   t ~ N(0, I): where a model-based method sees zero slope, the wider kernel reaches
//!   the slope. A smooth f never ties, so where some samples tie (a lattice, a
//!   staircase) f is piecewise constant at σ: a failed step there draws another pair at
//!   the same σ instead of shrinking it below the steps' width (as it does after the
//!   samples moved θ to a lower point, where they still make progress at this σ).
//!   Until f(θ) falls, σ does not shrink back to a scale where the samples tied, nor,
//!   once some have, after a step whose model was blind (it saw no decrease, or f rose
//!   by more than it predicted) to one where the model was blind before: the iteration
//!   draws another pair instead, and a blind one widens σ, so that a plateau seen
//!   through a rasteriser's pixel jitter is searched ever wider rather than between two
//!   scales.
//! * **Anytime.** Nothing depends on a budget's size: the first k evaluations of a run
//!   are the same whatever its [`AutoOptions::max_evaluations`], which only stops it
//!   (never exceeded, even inside an iteration) — and, by being set, lets it start
//!   fresh descents (below). When every coordinate's spread σ√Cᵢᵢ falls
//!   below [`AutoOptions::tolerance`] of its start (σ below it times σ₀ on a noisy
//!   objective; or σ below what T resolves at θ), or after
//!   [`AutoOptions::patience`] iterations without a lower f(θ), the run restarts from
//!   the best point with a survey of pairs, as the first iteration's, at the next scale of the cycle σ₀, 2σ₀,
//!   …, [`PLATEAU_WIDTH`]·σ₀, σ₀, … (wider scales average over more of the basin that
//!   held it; a gain does not send the next restart back to σ₀, since on a lattice of
//!   small steps some gain is always found there); after [`AutoOptions::restarts`]
//!   restarts in a row without a gain its descent ends, converged or stagnated.
//! * **Fresh starts.** A run with a budget on a deterministic objective then starts a
//!   new descent about its best point, as basin hopping does
//!   ([`AutoOptions::fresh_starts`]): each coordinate moves by its start scale times
//!   2^(k mod 5) times a normal draw at the k-th fresh start, mirrored into the box,
//!   and the memory, model, metric and σ start over. A descent's end is as likely a
//!   local minimum (a disc hidden under another, a lattice cell beside the optimum's)
//!   as the global one, and nothing in the values tells which; the budget says how
//!   much more the caller will spend to find out. [`Auto::theta`] is the best point of
//!   all descents. Without a budget, or on a noisy objective, the run ends with its
//!   first descent.
//! * **Continuation.** At such a restart, while σ > [`CONTINUATION_SCALE`]·σ₀, a
//!   rejected trial whose step ends inside the trust region still moves θ, now the
//!   search centre, and halves σ ([`AutoStep::Continued`]): the model fitted at a wide
//!   σ is that of the smoothed objective, whose minimum lies past a local minimum's
//!   wells, a lattice's cells or a second valley, and θ follows it down as σ shrinks,
//!   as the paper's annealed σ does. A minimum on the region's boundary is the model
//!   extrapolating (a cone's), so no move. The best point is kept: [`Auto::theta`]
//!   returns it, and the next restart and the run's end put it back into θ. The centre's
//!   descent from above the best point keeps the run from stagnating but is not a gain
//!   of the run: only a value below the best point's lets the restarts go on.
//!   Deterministic objectives only, and voted ones (a noisy trial is judged on common
//!   noise).
//!
//! Memory: one caller buffer of [`Auto::buffer_len`] floats, O(n² + m²) for m =
//! [`Auto::history_len`] remembered points. Cost per iteration: O(m²n + m³) for the fit
//! (twice with unseeded noise, and O(m²n) more for the noise's scale after a
//! rejection), O(mn² + n³) for the full model's linear part and eigen-decomposition;
//! O(n³) per n pairs for the diagonal model's sampling frames.

mod eigen;
mod fixed;
mod metric;
mod model;
mod trust;

pub use fixed::FixedAuto;

use core::fmt;

use rand_core::Rng;

use crate::error::Error;
use crate::objective::{Batch, NoiseSeed, Objective};
use crate::optim::vector::{
    axpy, distance, dot, mat_vec_by_columns, norm, orthogonalise, transpose,
};
use crate::real::Real;
use crate::sample::normal;
use model::{Ridge, Shape};

/// Largest n for which the model has a full Hessian and C a full shape; above it, both
/// are diagonal (2n + 1 coefficients instead of (n+1)(n+2)/2). Only a full model and
/// metric represent a valley that runs along no parameter axis (a rotated one, the
/// common case); a diagonal one learns per-coordinate scales from far fewer points, but
/// no rotation. The full model costs O(n³) per iteration (its trust step's and the
/// metric's eigen-decompositions) and n² floats per Hessian and shape, which bounds it.
pub const FULL_MODEL_MAX_DIM: usize = 40;

/// Most points Auto remembers (it reaches this for n ≥ 10 with a full model — n ≥ 14 on a
/// declared-noisy objective — and always with a diagonal one). A fit costs O(m²n + m³)
/// per iteration for m remembered points, so the bound keeps the cost affordable for a
/// full model and linear in n for a diagonal one; with fewer points than the model's
/// coefficients the fit corrects the model carried from earlier iterations along the
/// directions of the recent points.
pub const MAX_MEMORY: usize = 128;

/// σ/σ₀ above which a restart follows the smoothed model past a rejected trial
/// ([`AutoStep::Continued`]).
pub const CONTINUATION_SCALE: f64 = 1.5;

/// ρ: the kernel's reach in units of σ√n (the distance of a fresh sample). Points with
/// z ≤ ρ count as nearby; points with z ≤ 2ρ are fitted, with weight exp(−½(z/ρ)²) ≥ e⁻².
pub const REACH: f64 = 2.0;

/// A fit whose residual scatter η exceeds this fraction of the spread F of the values
/// it fits finds f rough at σ: a failed step that lands within 2η of f(θ) then widens σ
/// instead of shrinking it. A smooth f's residuals (its Taylor remainder) are a
/// fraction of F that falls with σ, so a smooth f never reaches it for long.
pub const ROUGH: f64 = 0.25;

/// A fit whose residual scatter η is within this fraction of the spread F of the values
/// it fits describes f closely enough that its curvature may shape the sampling metric
/// without a step to confirm it ([`DETERMINED_METRIC_WEIGHT`]).
pub const SMOOTH: f64 = 0.1;

/// c of Tukey's biweight in units of the residuals' robust spread (1.4826 × their
/// median absolute value): the usual 4.685, 95 % efficient for Gaussian residuals.
const TUKEY: f64 = 4.685;

/// σ/σ₀ beyond which a plateau no longer widens σ: the run keeps drawing pairs at
/// Gaussian distances within that reach instead, since samples scattered ever wider
/// meet a distant basin ever more rarely. σ₀ states where the parameters matter.
pub const PLATEAU_WIDTH: f64 = 16.0;

/// Every coordinate's spread relative to its start, σ√Cᵢᵢ/sᵢ, at which a run on a
/// deterministic objective converges by default.
pub const TOLERANCE: f64 = 1e-9;

/// σ/σ₀ at which a run on a noisy objective converges by default. Far below its scale a
/// Monte Carlo render's differences on one seed are its own grain — the noise that a
/// common seed does not cancel, a mesh's facets — which a model at that width descends
/// step by step, each a spurious gain that keeps the run from restarting wider: the
/// evaluations spent there are lost to the restarts that look farther afield. The test
/// is on σ itself, not on every coordinate's spread as [`TOLERANCE`]'s: the narrowest
/// axes reach the grain first, and holding a run until its stretched axes shrink too
/// cost the path-traced SHADOW task 2 of 40 seeds.
pub const NOISY_TOLERANCE: f64 = 1e-3;

/// σ's factor after a step whose decrease fell short of a tenth of the model's prediction
/// (ρ̂ < 0.1), on an objective not declared noisy. A fit uses the remembered points
/// within 2ρ of θ at the scale of σ: halving σ doubles their whitened distances, so that
/// every point beyond ρ leaves the next fit, and where shortfalls come often without the
/// scale being wrong — a kink, a ridge, an orthant where the curvature changes (BBOB's
/// attractive sector) — σ fell far below the distance to the optimum while the model
/// refitted from ever fewer points. At 0.7 the points within 1.4ρ stay. A declared-noisy
/// objective (a render on the caller's seed) still halves σ: the gentler factor was
/// measured to lose runs there (docs/notes/2026-11-27-shrink.md).
pub const SHRINK: f64 = 0.7;

/// σ's growth after a step to the trust region's boundary that lowered f by less than a
/// tenth of the decrease its model predicted: 2^¼, so that four such steps double σ as
/// one well-predicted step does.
const STRIDE: f64 = 1.189_207_115_002_721;

/// Scales in the restarts' cycle σ₀, 2σ₀, …, [`PLATEAU_WIDTH`]·σ₀.
const RESTART_SCALES: u32 = 5;

/// Restarts in a row without a gain after the first such one before a run's only
/// descent ends (no budget, or a noisy objective; [`AutoOptions::restarts`]): the cycle
/// σ₀ … [`PLATEAU_WIDTH`]·σ₀ and more, since restarts are then the run's only way out of
/// a basin.
pub const RESTARTS: usize = 8;

/// Restarts in a row without a gain after the first such one before a descent that a
/// fresh start follows ends ([`AutoOptions::fresh_starts`], [`AutoOptions::restarts`]):
/// none. The descent restarts from its best point while its restarts gain, and ends
/// with the first restart that gains nothing; the wider search is left to the new
/// descent, which starts from a point about the best one with a memory and a model
/// that no longer hold the basin that held the last.
pub const RESTARTS_BEFORE_FRESH: usize = 0;

/// σ/σ₀ beyond which a confirmed step to the trust boundary no longer widens σ.
const GROWTH_WIDTH: f64 = 1_048_576.0;

/// The fraction of the metric's rate at which a model moves it when its points
/// determine it (more fitted points than coefficients, residual scatter within
/// [`SMOOTH`], no samples tied since f(θ) last fell, θ on no face of the box) but its
/// step did not confirm it (ρ̂ < 0.1 or rejected), on a deterministic objective. A
/// confirmed step moves it at the full rate. Models that stall a run where no fit is
/// determined move it at the same weight ([`STALLED_ANISOTROPY`]).
pub const DETERMINED_METRIC_WEIGHT: f64 = 0.3;

/// Where no fit can be determined (a full model from n = 15, whose [`MAX_MEMORY`] points
/// are fewer than its coefficients), confirmed steps are the metric's only teacher, and
/// a stiff direction the metric has not yet squashed can keep every step from being
/// confirmed: sampled at the soft directions' scale, it dominates the values, and the
/// model's slope along the soft directions drowns in the misfit of its curvature
/// (BBOB's discus f11 at n = 20: ρ̂ ≈ 0.005 for 20 000 evaluations). So once n model steps
/// in a row have gone unconfirmed, a model whose curvature in whitened coordinates is
/// this anisotropic — its largest |eigenvalue| at least this multiple of the median one
/// — moves the metric at [`DETERMINED_METRIC_WEIGHT`] (on a deterministic objective, off
/// a lattice and off the box's faces, as for determined fits). A rounder model is left
/// alone: at the kinks of BBOB's attractive sector f06 stalled fits read 3–6, and
/// learning from them there lost the runs that succeed.
pub const STALLED_ANISOTROPY: f64 = 10.0;

/// Largest |cosine| between two parameter axes in whitened coordinates, between L⁻¹eₐ
/// and L⁻¹e_b, (C⁻¹)_ab/√((C⁻¹)_aa·(C⁻¹)_bb), at which a restart's survey of a full
/// model is drawn along the parameter axes rather than a random frame
/// ([`FLAT_STRETCH`]). Where the metric has learnt a rotated shape (a ridge's stretch
/// of 10³ along a diagonal) the axes crowd into its stiff directions in whitened
/// coordinates, and a survey along them would leave the soft ones unsampled.
pub const AXIS_COHERENCE: f64 = 0.5;

/// The metric's stretch along a coordinate that a survey finds flat: where both halves
/// of a restart survey's pair along a parameter axis tie with f(θ) while neither half of
/// some other pair does, f does not depend on that coordinate at this σ but does on
/// others — an object that does not yet touch its target while others are fitted — and
/// C's scale along it
/// grows by this factor (C ← SCS, then det C = 1 again), so that the samples reach
/// across the plateau there without throwing the fitted coordinates off. A plateau in
/// every direction widens σ instead.
pub const FLAT_STRETCH: f64 = 2.0;

/// Draws of f(θ) an unseeded objective's trials are compared with, at most: after a
/// rejected trial, where θ's draw lies below the robust fit's value at θ, θ is drawn
/// again beside the next trial until the memory holds this many, and trials must beat
/// their median (the larger of two).
pub const THETA_DRAWS: usize = 2;

/// On an unseeded objective whose every draw is noisy, a rejected trial halves σ only
/// where it is worse than f(θ) by more than this many times the noise's scale (the
/// median |f − f′| over repeated draws at one point); a smaller shortfall may be the
/// noise's, and the iteration draws another pair at the same σ instead.
pub const NOISE_MARGIN: f64 = 10.0;

/// Draws of one point at most on sparse unseeded noise (`Auto::vote`): it is drawn
/// until two draws agree exactly, and keeps the median of its draws when none do.
pub const VOTES: usize = 5;

/// Dimension from which a fit with a full model forms its offsets and prior values from
/// the transposes of L⁻¹ and H ([`Auto::fit`]).
const BY_COLUMNS_MIN_DIM: usize = 10;

/// Points evaluated per noise-seed chunk of one batch (a stack array of seeds).
const CHUNK: usize = 64;

/// What to do with an objective value that is NaN or ±∞.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum NonFinite {
    /// The point counts as worse than any finite value: it is not fitted, a trial point
    /// there is rejected. Default.
    #[default]
    Worst,
    /// [`Auto::step`] returns [`Error::NonFiniteObjective`]; θ is unchanged.
    Error,
}

/// Auto's options. Every one has a default; none is required.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct AutoOptions<T> {
    /// The run converges (and restarts, see [`AutoOptions::restarts`]) once every
    /// coordinate's spread σ√Cᵢᵢ is below `tolerance` times its spread at the start (a
    /// deterministic objective), or once σ < `tolerance`·σ₀ (a noisy one). Default:
    /// `None`, meaning [`TOLERANCE`] for a deterministic objective and
    /// [`NOISY_TOLERANCE`] for a noisy one.
    pub tolerance: Option<T>,
    /// Iterations without a lower f(θ) after which the run restarts from the best point
    /// (see [`AutoOptions::restarts`]) or ends stagnated. Default: `None`, meaning
    /// 20 + 10n.
    pub patience: Option<usize>,
    /// A descent restarts from its best point whenever it converges or stagnates with a
    /// lower f(θ) since its last restart (or its start); once a restart has found none,
    /// `restarts` more in a row without a lower f(θ) are made before the descent ends.
    /// The k-th restart of a run is at σ₀·2^(k mod 5): σ₀, 2σ₀, …, [`PLATEAU_WIDTH`]·σ₀
    /// (and, with bounds, at most half the box's widest side), then σ₀ again. Each
    /// looks around its scale with n antithetic pairs (at most half the memory's
    /// worth). Default: `None`, meaning [`RESTARTS_BEFORE_FRESH`] where a fresh start
    /// follows the descent (see [`AutoOptions::fresh_starts`]) and [`RESTARTS`] where
    /// the descent is the run.
    pub restarts: Option<usize>,
    /// Objective evaluations after which the run stops; never exceeded. Default: none.
    pub max_evaluations: Option<usize>,
    /// Whether a run with a budget ([`AutoOptions::max_evaluations`]) on a
    /// deterministic objective spends what its descent leaves: once a descent ends
    /// (converged, or stagnated after its [`AutoOptions::restarts`]), another starts
    /// from a point about the best one, as basin hopping does (each coordinate moved
    /// by its start scale times 2^(k mod 5) times a standard normal draw at the k-th
    /// fresh start, mirrored into the box), with its memory, model, metric and σ
    /// started over; the best point of all descents is kept, and the run ends with its
    /// budget. A run without a budget, or on a noisy objective (values of different
    /// descents would not compare), ends with its first descent. Default: `true`.
    pub fresh_starts: bool,
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
    /// what T resolves at θ.
    Converged,
    /// [`AutoOptions::patience`] iterations passed without a lower f(θ).
    Stagnated,
    /// [`AutoOptions::max_evaluations`] were used.
    MaxEvaluations,
}

impl fmt::Display for AutoTermination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AutoTermination::Converged => "converged (spread below tolerance)",
            AutoTermination::Stagnated => "stagnated (no lower value within the patience)",
            AutoTermination::MaxEvaluations => "evaluation budget used",
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
    /// f(θ) after the iteration, when known and finite.
    pub value: Option<T>,
    /// Distance θ moved (including a move to a lower sample).
    pub step_length: T,
    /// Actual over predicted decrease of the trial step, when one was evaluated.
    pub ratio: Option<T>,
    /// What the iteration did.
    pub kind: AutoStep,
    /// Set when this iteration ended the run.
    pub termination: Option<AutoTermination>,
}

/// Regions of the caller's buffer.
struct Memory<'b, T> {
    lower: &'b mut [T],
    upper: &'b mut [T],
    /// Remembered points (rows of n) and their values.
    xs: &'b mut [T],
    fs: &'b mut [T],
    /// The noise group of each remembered point (see [`State::groups`]).
    gs: &'b mut [T],
    /// z of each remembered point, for θ = `zt` and the σ and metric of
    /// [`State::reach_key`] (see `Auto::refresh_reach`).
    zs: &'b mut [T],
    zt: &'b mut [T],
    /// The fit's rows u, √w, noise groups, residuals, and its m×m system.
    u: &'b mut [T],
    sw: &'b mut [T],
    gid: &'b mut [T],
    r: &'b mut [T],
    gram: &'b mut [T],
    kp: &'b mut [T],
    schur: &'b mut [T],
    beta: &'b mut [T],
    /// The model (standardised units) and the prior (parameter units, at `c0`).
    g: &'b mut [T],
    h: &'b mut [T],
    g0: &'b mut [T],
    h0: &'b mut [T],
    c0: &'b mut [T],
    /// Trust-region scratch.
    a: &'b mut [T],
    v: &'b mut [T],
    gamma: &'b mut [T],
    lambda: &'b mut [T],
    s: &'b mut [T],
    /// θ at the start of the iteration (the report's step length).
    tmp: &'b mut [T],
    /// Orthonormal sampling frame (columns as rows of n).
    frame: &'b mut [T],
    /// Points of the current batch and their values. While the trust step is solved,
    /// its first two rows hold the held coordinates' moves and flags (`trust_step`).
    stage: &'b mut [T],
    stage_f: &'b mut [T],
    /// The trust step with coordinates held on bounds (`held_step`): the reduced
    /// problem's slope (first R's solution y), curvature (first R) and step w.
    rg: &'b mut [T],
    rh: &'b mut [T],
    rs: &'b mut [T],
    /// `gx` holds the trial step Ls (parameter directions, over σ) and other n-vectors
    /// of the iteration; `hx` the held step's orthonormal basis (Q's rows, then Z's).
    gx: &'b mut [T],
    hx: &'b mut [T],
    /// The sampling metric C = LLᵀ, L and L⁻¹, of the model's shape (see `metric`).
    c: &'b mut [T],
    l: &'b mut [T],
    li: &'b mut [T],
    /// Each remembered point's robustness weight in the fit, in [0, 1]: 1 unless the
    /// objective draws unseeded noise ([`State::unseeded`]), where points the model
    /// cannot explain (a Cauchy outlier) lose it (`Auto::reweigh`).
    credit: &'b mut [T],
    /// The scale each coordinate was given ([`Auto::new`]'s σ₀ or
    /// [`Auto::with_scales`]), from which `Auto::shape_scales` sets σ₀ and C.
    scale: &'b mut [T],
    /// The best point while a continuation move has left θ, the search centre, above it
    /// ([`State::best_value`]).
    best: &'b mut [T],
    /// The evolution path of θ's accepted model steps in units of σ ([`Auto::follow_path`]).
    path: &'b mut [T],
    /// The best point of the run's earlier descents ([`State::record`]).
    record: &'b mut [T],
}

/// Region lengths for dimension n, in [`Memory`]'s order.
const fn regions(n: usize) -> [usize; 42] {
    let shape = Shape::for_dim(n);
    let m = history_len(n);
    let hl = shape.hessian_len(n);
    let full = if matches!(shape, Shape::Full) {
        n * n
    } else {
        0
    };
    let rows = stage_rows(n);
    let [gram, kp, schur, beta] = model::scratch_lens(shape, m, n);
    [
        n,
        n,
        m * n,
        m,
        m,
        m,
        n,
        m * n,
        m,
        m,
        m,
        gram,
        kp,
        schur,
        beta,
        n,
        hl,
        n,
        hl,
        n,
        full,
        full,
        n,
        n,
        n,
        n,
        n * n,
        rows * n,
        rows,
        n,
        hl,
        n,
        n,
        hl,
        hl,
        hl,
        hl,
        m,
        n,
        n,
        n,
        n,
    ]
}

/// Floats of buffer an [`Auto`] run needs in dimension n, for m = [`Auto::history_len`]
/// points remembered:
/// m(2n + 7) + m² + mp + p² + p + 17n + 7h + r(n + 1) + n² + 2f,
/// with, for the full model (n ≤ [`FULL_MODEL_MAX_DIM`]), h = f = n² and p = n + 1, and
/// for the diagonal one h = n, f = 0 and p = 1; r = 2·min(n, ⌊m/2⌋) + 2 staged points.
/// A `const fn`, so that storage can be sized at compile time ([`FixedAuto`]).
pub const fn buffer_len(n: usize) -> usize {
    let lens = regions(n);
    let mut sum = 0;
    let mut k = 0;
    while k < lens.len() {
        sum += lens[k];
        k += 1;
    }
    sum
}

const fn history_len(n: usize) -> usize {
    memory_of(n, 2)
}

/// Points a run on a declared-noisy objective remembers ([`Auto::history_len`]).
const fn noisy_history_len(n: usize) -> usize {
    memory_of(n, 1)
}

/// `copies` times the model's coefficients plus n + 1, at most [`MAX_MEMORY`].
const fn memory_of(n: usize, copies: usize) -> usize {
    let m = copies * Shape::for_dim(n).coefficients(n) + n + 1;
    if m > MAX_MEMORY { MAX_MEMORY } else { m }
}

/// Whether a fit can determine the model from the data alone: the model is full (its
/// linear part unpenalised) and the memory holds as many points as it has coefficients,
/// which is n ≤ 14. Above, every fit after the first leans on its prior (and the
/// diagonal model's penalised gradient is never exact); only a full model's first fit
/// after a survey is made exact there ([`Auto::ridge`]).
const fn memory_determines_model(n: usize) -> bool {
    let shape = Shape::for_dim(n);
    matches!(shape, Shape::Full) && shape.coefficients(n) <= history_len(n)
}

/// Remembered points within reach that a model needs before it steps without sampling:
/// n + 1, or half the memory where that holds fewer than 2n + 2 points.
const fn nearby_needed(n: usize) -> usize {
    let half = history_len(n) / 2;
    if n + 1 < half { n + 1 } else { half }
}

/// Points within reach above which a model that puts its minimum at θ is validated, so
/// that σ may shrink on its word: 2q − 2 for q = [`nearby_needed`] — pairs in about as
/// many directions as the model has linear coefficients.
const fn validating(n: usize) -> usize {
    2 * nearby_needed(n) - 2
}

/// Pairs a survey (the first iteration, a restart) draws: n, or as many as half the
/// memory holds.
const fn survey_pairs(n: usize) -> usize {
    let half = history_len(n) / 2;
    if n < half { n } else { half }
}

/// Points one batch can hold: a survey's samples and θ, or a trial point and θ.
const fn stage_rows(n: usize) -> usize {
    2 * survey_pairs(n) + 2
}

fn carve<'b, T>(buffer: &'b mut [T], n: usize) -> Memory<'b, T> {
    let lens = regions(n);
    let mut lens = lens.iter();
    let mut rest = buffer;
    // Regions in `regions`' order: struct fields are initialised in source order.
    let mut take = || {
        let len = lens.next().copied().unwrap_or(0);
        let (head, tail) = core::mem::take(&mut rest).split_at_mut(len);
        rest = tail;
        head
    };
    Memory {
        lower: take(),
        upper: take(),
        xs: take(),
        fs: take(),
        gs: take(),
        zs: take(),
        zt: take(),
        u: take(),
        sw: take(),
        gid: take(),
        r: take(),
        gram: take(),
        kp: take(),
        schur: take(),
        beta: take(),
        g: take(),
        h: take(),
        g0: take(),
        h0: take(),
        c0: take(),
        a: take(),
        v: take(),
        gamma: take(),
        lambda: take(),
        s: take(),
        tmp: take(),
        frame: take(),
        stage: take(),
        stage_f: take(),
        rg: take(),
        rh: take(),
        rs: take(),
        gx: take(),
        hx: take(),
        c: take(),
        l: take(),
        li: take(),
        credit: take(),
        scale: take(),
        best: take(),
        path: take(),
        record: take(),
    }
}

/// Auto's state between iterations.
#[derive(Clone, Copy, Debug)]
struct State<T> {
    sigma: T,
    sigma0: T,
    iteration: usize,
    evaluations: usize,
    /// f(θ) when known and finite.
    value: Option<T>,
    /// θ has been evaluated (its value may be non-finite).
    centre_known: bool,
    /// Remembered points.
    count: usize,
    has_prior: bool,
    /// Next unused column of the sampling frame (n: draw a new frame).
    frame_next: usize,
    /// Draw a pair this iteration whatever the count of nearby points: σ widened on a
    /// plateau, or a step failed on a model the nearby points did not determine.
    resample: bool,
    /// The model claimed its minimum at θ before enough points around θ validated it:
    /// the next iteration draws the pairs the validation lacks at once (with `resample`).
    validate: bool,
    /// Iterations since f(θ) last fell.
    stale: usize,
    /// f(θ) fell since the last restart (or the run began): a stagnation restarts
    /// instead of ending the run.
    may_restart: bool,
    bounded: bool,
    /// Draw a survey's pairs this iteration, as the first does: a restart
    /// looks around at its new scale before the model decides anything.
    survey: bool,
    /// Restarts in a row since the last gain.
    widenings: u32,
    /// Restarts so far: the k-th is at σ₀·2^(k mod [`RESTART_SCALES`]).
    cycle: u32,
    /// Some of the last exploration's samples tie with f(θ) — counting the one θ moved
    /// to, if it moved — but not all: f is piecewise constant at this scale, or the
    /// samples found a lower point at it, so a failed step is no reason to shrink σ.
    lattice: bool,
    /// The largest σ at which an iteration's samples tied with f(θ) (a plateau) while
    /// the values around θ differed from it by more than √ε·|f(θ)|, since f(θ) last fell
    /// or the run last restarted; zero when none did (`Auto::hold_sigma`).
    tie_scale: T,
    /// The largest σ at which the model was blind since f(θ) last fell or the run last
    /// restarted — f rough there, or a held step's model blind (`Auto::hold_sigma`);
    /// zero when none was.
    rough_scale: T,
    /// The objective is noisy ([`Objective::deterministic`] is false): values are
    /// compared, and fitted, only within a noise group — the points evaluated on one
    /// seed.
    noisy: bool,
    /// θ was evaluated a second time since the run last restarted, to check that an
    /// objective declared deterministic is (`Auto::check_determinism`); true until the
    /// first restart.
    checked: bool,
    /// The check found otherwise: the objective draws fresh noise at every evaluation
    /// though it claims to be deterministic (a renderer whose seed the caller does not
    /// pass on). The fit then down-weighs the points it cannot explain, and θ is drawn
    /// again where its own draw is one of them.
    unseeded: bool,
    /// The check's draws of f(θ) — three, once the second differed from the first — all
    /// differ: the noise touches every draw (a Monte Carlo estimate), not a few of them
    /// (sparse outliers on exact values, where two of three draws mostly agree).
    dense: bool,
    /// The last trial, on an unseeded objective, was rejected: where the robust fit
    /// also puts f(θ)'s draw below the model, that draw may be a lucky one, and the
    /// next trial's comparison draws θ again (up to [`THETA_DRAWS`] draws).
    doubted: bool,
    /// The unseeded noise is sparse (`Auto::sparse_noise`): every point is drawn until
    /// two draws agree (`Auto::vote`). Once set, it stays set.
    voting: bool,
    /// Noise groups handed out so far; a point's group is stored as this count modulo
    /// 2²⁰ (exact in `f32`; the memory never holds points that far apart in time).
    groups: u32,
    /// This iteration's seed and noise group when f(θ) (`value`) was measured on it
    /// (noisy objectives), so that the samples and the trial step compare with it.
    shared: Option<(NoiseSeed, T)>,
    /// θ moved this iteration to a point of lower value on a common seed.
    gained: bool,
    finished: Option<AutoTermination>,
    /// Changes of the sampling metric so far.
    metric_changes: u32,
    /// Model steps since the last one that confirmed its model (ρ̂ ≥ 0.1).
    unconfirmed: usize,
    /// f at [`Memory::best`], the best point, while a continuation move
    /// ([`AutoStep::Continued`]) has left θ above it; `None` otherwise (θ is the best
    /// point).
    best_value: Option<T>,
    /// (σ, `metric_changes`) for which [`Memory::zs`] holds the remembered points' z
    /// (with θ = [`Memory::zt`]); `None` before it is first filled.
    reach_key: Option<(T, u32)>,
    /// f at [`Memory::record`], the best point of the descents before the current one
    /// (`Auto::fresh_start`); `None` before the first fresh start.
    record: Option<T>,
    /// Fresh starts so far.
    fresh: u32,
}

impl<T: Real> State<T> {
    /// The state of a run's first descent at scale σ₀ in dimension n, before its first
    /// iteration ([`Auto::new`]); a fresh start (`Auto::fresh_start`) begins from it too,
    /// keeping what the run as a whole has learnt.
    fn start(sigma0: T, n: usize) -> State<T> {
        State {
            sigma: sigma0,
            sigma0,
            iteration: 0,
            evaluations: 0,
            value: None,
            centre_known: false,
            count: 0,
            has_prior: false,
            frame_next: n,
            resample: false,
            validate: false,
            stale: 0,
            may_restart: false,
            bounded: false,
            survey: false,
            widenings: 0,
            cycle: 0,
            lattice: false,
            tie_scale: T::ZERO,
            rough_scale: T::ZERO,
            noisy: false,
            checked: true,
            unseeded: false,
            dense: false,
            doubted: false,
            voting: false,
            groups: 0,
            shared: None,
            gained: false,
            finished: None,
            metric_changes: 0,
            unconfirmed: 0,
            best_value: None,
            reach_key: None,
            record: None,
            fresh: 0,
        }
    }
}

/// Auto: a resumable run over θ (borrowed, updated in place to the best point found).
///
/// ```
/// use hodr_core::optim::{Auto, AutoOptions};
/// use rand_xoshiro::{Xoshiro256PlusPlus, rand_core::SeedableRng};
///
/// // A staircase on a quadratic bowl: flat steps, no useful derivative anywhere.
/// let mut f = |x: &[f64]| {
///     let q = (x[0] - 1.0).powi(2) + 10.0 * (x[1] + 2.0).powi(2);
///     (q * 20.0).floor() / 20.0
/// };
/// let mut theta = [4.0, 3.0];
/// let mut buffer = vec![0.0; Auto::<f64, Xoshiro256PlusPlus>::buffer_len(2)];
/// let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, Xoshiro256PlusPlus::seed_from_u64(1))?
///     .with_bounds(&[-5.0, -5.0], &[5.0, 5.0])?
///     .with_options(AutoOptions::default().with_max_evaluations(500)?);
/// let end = auto.run(&mut f, |_report, _theta| {})?;
/// assert_eq!(auto.value(), Some(0.0));
/// println!("{end} after {} evaluations at {:?}", auto.evaluations(), auto.theta());
/// # Ok::<(), hodr_core::Error>(())
/// ```
pub struct Auto<'b, T, R> {
    theta: &'b mut [T],
    mem: Memory<'b, T>,
    rng: R,
    options: AutoOptions<T>,
    shape: Shape,
    st: State<T>,
}

impl<T: Real, R> fmt::Debug for Auto<'_, T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Auto")
            .field("theta", &self.theta)
            .field("sigma", &self.st.sigma)
            .field("value", &self.st.value)
            .field("iteration", &self.st.iteration)
            .field("evaluations", &self.st.evaluations)
            .finish_non_exhaustive()
    }
}

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Floats of buffer [`Auto::new`] needs in dimension n ([`buffer_len`]).
    pub const fn buffer_len(n: usize) -> usize {
        buffer_len(n)
    }

    /// Points remembered in dimension n: twice the model's coefficient count p
    /// ((n+1)(n+2)/2 for a full Hessian, 2n + 1 for a diagonal one) plus n + 1, at most
    /// [`MAX_MEMORY`]: 2p + n + 1 (15 at n = 2, 48 at n = 5, 128 from n = 10). Twice p
    /// lets a fit average over the kernel rather than interpolate, and leaves room, once
    /// a converged descent has crowded θ's surroundings, for the wider points of a
    /// restart or a widening σ (each new point replaces the one farthest from θ; a
    /// survey's, the farthest of those older than the survey other than θ's).
    ///
    /// A run on a declared-noisy objective ([`Objective::deterministic`] false) uses
    /// only p + n + 1 of them (at most [`MAX_MEMORY`]): the rules that end its descents
    /// (the fit's scatter, the counts of points that determine the model) are set for
    /// that memory (docs/notes/2026-11-27-memory-twice-the-coefficients.md).
    pub const fn history_len(n: usize) -> usize {
        history_len(n)
    }

    /// A run from `theta` (x₀; updated in place to the best point found) with scale
    /// `sigma0` > 0 and default options, drawing its samples from `rng`.
    ///
    /// # Errors
    /// [`Error::InvalidSigma`] for σ₀ not finite and positive, [`Error::NonFiniteInput`]
    /// for a non-finite x₀, [`Error::DimensionMismatch`] for an empty x₀,
    /// [`Error::WorkspaceTooSmall`] for a buffer shorter than [`Auto::buffer_len`].
    pub fn new(theta: &'b mut [T], sigma0: T, buffer: &'b mut [T], rng: R) -> Result<Self, Error> {
        let n = theta.len();
        if n == 0 {
            return Err(Error::DimensionMismatch {
                expected: 1,
                found: 0,
            });
        }
        if !(sigma0.is_finite() && sigma0 > T::ZERO) {
            return Err(Error::InvalidSigma);
        }
        if let Some(index) = theta.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFiniteInput { index });
        }
        let needed = Self::buffer_len(n);
        if buffer.len() < needed {
            return Err(Error::WorkspaceTooSmall {
                needed,
                available: buffer.len(),
            });
        }
        let buffer = &mut buffer[..needed];
        buffer.fill(T::ZERO);
        let mem = carve(buffer, n);
        mem.lower.fill(-T::MAX);
        mem.upper.fill(T::MAX);
        mem.scale.fill(sigma0);
        mem.tmp.fill(T::ONE);
        metric::axes(Shape::for_dim(n), mem.tmp, mem.c, mem.l, mem.li);
        Ok(Auto {
            theta,
            mem,
            rng,
            options: AutoOptions::default(),
            shape: Shape::for_dim(n),
            st: State::start(sigma0, n),
        })
    }

    /// Keeps every evaluated point within lower ≤ x ≤ upper (x₀ is projected into the
    /// box). A coordinate's scale (σ₀, or its own from [`Auto::with_scales`]) is cut to
    /// a quarter of its side of the box where that is narrower: wider samples would only
    /// fold back into the box (`Auto::shape_scales`). Call before the first
    /// [`Auto::step`].
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for bounds of the wrong length,
    /// [`Error::NonFiniteInput`] for a NaN bound, [`Error::InvalidSetting`] (`bounds`)
    /// where lower > upper.
    pub fn with_bounds(self, lower: &[T], upper: &[T]) -> Result<Self, Error> {
        let n = self.theta.len();
        for b in [lower, upper] {
            if b.len() != n {
                return Err(Error::DimensionMismatch {
                    expected: n,
                    found: b.len(),
                });
            }
        }
        for (i, (&l, &u)) in lower.iter().zip(upper).enumerate() {
            if l.partial_cmp(&u).is_none() {
                return Err(Error::NonFiniteInput { index: i });
            }
            if l > u {
                return Err(Error::InvalidSetting { name: "bounds" });
            }
        }
        let mut this = self;
        for i in 0..n {
            this.mem.lower[i] = lower[i].max(-T::MAX);
            this.mem.upper[i] = upper[i].min(T::MAX);
            this.theta[i] = this.theta[i].max(this.mem.lower[i]).min(this.mem.upper[i]);
        }
        this.st.bounded = true;
        this.shape_scales();
        Ok(this)
    }

    /// Gives each coordinate its own scale σ₀ᵢ > 0, the distance over which it matters,
    /// in place of [`Auto::new`]'s common σ₀: for parameters in different units (a
    /// position in pixels beside a colour in [0, 1]), as pycma's `CMA_stds` does. The
    /// run starts with σ₀ the scales' geometric mean and its metric stretched by
    /// σ₀ᵢ/σ₀ along coordinate i, a shape the metric then learns from as it learns from
    /// any other (`Auto::shape_scales`). Call before the first [`Auto::step`], in either
    /// order with [`Auto::with_bounds`].
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for scales of the wrong length,
    /// [`Error::InvalidSetting`] (`scales`) for a scale not finite and positive.
    pub fn with_scales(mut self, scales: &[T]) -> Result<Self, Error> {
        let n = self.theta.len();
        if scales.len() != n {
            return Err(Error::DimensionMismatch {
                expected: n,
                found: scales.len(),
            });
        }
        if !scales.iter().all(|&s| s.is_finite() && s > T::ZERO) {
            return Err(Error::InvalidSetting { name: "scales" });
        }
        self.mem.scale.copy_from_slice(scales);
        self.shape_scales();
        Ok(self)
    }

    /// Sets σ₀ (and σ) and the initial metric from the coordinates' scales: sᵢ is
    /// [`Auto::start_scale`] held to at least [`Auto::least_start_scale`]; σ₀ is the sᵢ's
    /// geometric mean and C = diag((sᵢ/σ₀)²). Equal sᵢ give σ₀ = sᵢ exactly and C = I.
    fn shape_scales(&mut self) {
        let n = self.theta.len();
        let least = self.least_start_scale();
        for i in 0..n {
            self.mem.tmp[i] = self.start_scale(i).max(least);
        }
        let m = &mut self.mem;
        let first = m.tmp[0];
        let sigma0 = if m.tmp.iter().all(|&s| s == first) {
            m.tmp.fill(T::ONE);
            first
        } else {
            let mean_log = m.tmp.iter().fold(T::ZERO, |a, &s| a + s.ln()) / T::from_usize(n);
            let sigma0 = mean_log.exp();
            for s in m.tmp.iter_mut() {
                *s /= sigma0;
            }
            sigma0
        };
        metric::axes(self.shape, m.tmp, m.c, m.l, m.li);
        self.st.sigma = sigma0;
        self.st.sigma0 = sigma0;
    }

    /// Replaces the options (see [`AutoOptions`]).
    pub fn with_options(mut self, options: AutoOptions<T>) -> Self {
        self.options = options;
        self
    }

    /// The best point found so far (x₀ before the first step).
    pub fn theta(&self) -> &[T] {
        if self.record_leads() {
            self.mem.record
        } else if self.st.best_value.is_some() {
            self.mem.best
        } else {
            self.theta
        }
    }

    /// f at [`Auto::theta`], once evaluated and finite.
    pub fn value(&self) -> Option<T> {
        if self.record_leads() {
            self.st.record
        } else {
            self.st.best_value.or(self.st.value)
        }
    }

    /// An earlier descent's best point is at least as good as the current descent's.
    fn record_leads(&self) -> bool {
        match (self.st.record, self.st.best_value.or(self.st.value)) {
            (Some(r), Some(v)) => r <= v,
            (Some(_), None) => true,
            (None, _) => false,
        }
    }

    /// σ for the next iteration.
    pub fn sigma(&self) -> T {
        self.st.sigma
    }

    /// Objective evaluations used.
    pub fn evaluations(&self) -> usize {
        self.st.evaluations
    }

    /// Iterations completed.
    pub fn iteration(&self) -> usize {
        self.st.iteration
    }

    /// Why the run ended, once it has.
    pub fn termination(&self) -> Option<AutoTermination> {
        self.st.finished
    }

    /// Steps until the run ends, calling `observe` after every iteration.
    ///
    /// # Errors
    /// As [`Auto::step`].
    pub fn run<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        mut observe: impl FnMut(&AutoReport<T>, &[T]),
    ) -> Result<AutoTermination, Error> {
        while let Some(report) = self.step(objective)? {
            observe(&report, self.theta);
        }
        Ok(self.st.finished.unwrap_or(AutoTermination::MaxEvaluations))
    }

    /// One iteration; `Ok(None)` without evaluating anything once the run has ended.
    ///
    /// # Errors
    /// [`Error::NonFiniteObjective`] (with [`NonFinite::Error`]) naming the evaluation
    /// of this iteration that was not finite; [`Error::Cancelled`] when the objective
    /// asks to stop. θ keeps its value and the run may go on.
    pub fn step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
    ) -> Result<Option<AutoReport<T>>, Error> {
        if self.st.finished.is_some() {
            return Ok(None);
        }
        if self.remaining() == 0 {
            self.st.finished = Some(AutoTermination::MaxEvaluations);
            self.restore_best();
            self.restore_record();
            return Ok(None);
        }
        let n = self.theta.len();
        let sigma = self.st.sigma;
        self.st.noisy = !objective.deterministic();
        self.st.shared = None;
        self.st.gained = false;
        self.mem.tmp.copy_from_slice(self.theta);
        let mut spent = 0;
        let mut kind = self.sample(objective, &mut spent)?;
        self.st.resample = false;
        self.st.validate = false;
        let mut ratio = None;
        if kind.is_none() {
            let (k, r) = self.model_step(objective, &mut spent)?;
            kind = Some(k);
            ratio = r;
        }
        let kind = kind.unwrap_or(AutoStep::OutOfBudget);
        self.st.iteration += 1;
        self.st.resample |= kind == AutoStep::Plateau;
        self.hold_sigma(sigma, kind, ratio);
        if self.st.gained {
            self.st.stale = 0;
            self.st.may_restart |= self.below_best();
        } else {
            self.st.stale += 1;
        }
        let step_length = distance(self.mem.tmp, self.theta);
        if kind == AutoStep::Accepted && step_length > T::ZERO && self.follows_path() {
            self.follow_path(sigma);
        }
        let patience = self.options.patience.unwrap_or(20 + 10 * n);
        let scale = self.theta.iter().fold(T::ZERO, |m, x| m.max(x.abs()));
        let resolvable = T::from_f64(8.0) * T::EPSILON * scale;
        let converged = self.sigma_converged() || self.st.sigma <= resolvable;
        let stagnated = self.st.stale >= patience;
        // Before a restart or the end moves θ back to the best point: a centre that
        // continuation left above it may have just stepped below it.
        self.keep_best();
        let termination = if kind == AutoStep::OutOfBudget || self.remaining() == 0 {
            Some(AutoTermination::MaxEvaluations)
        } else if (converged || stagnated)
            && (self.st.may_restart || (self.st.widenings as usize) < self.restarts())
        {
            // A kink or a lattice can hold σ far from the optimum: look again from the
            // best point, at the next scale of the cycle σ₀, 2σ₀, …, where the smoothed
            // objective averages over ever more of the basin that held the run.
            if self.st.may_restart {
                self.st.widenings = 0;
            } else {
                self.st.widenings += 1;
            }
            self.restart(self.restart_sigma());
            self.st.cycle += 1;
            None
        } else if (converged || stagnated) && self.may_start_fresh() {
            self.fresh_start();
            None
        } else if converged {
            Some(AutoTermination::Converged)
        } else if stagnated {
            Some(AutoTermination::Stagnated)
        } else {
            None
        };
        if termination.is_some() {
            self.restore_best();
            self.restore_record();
        }
        self.st.finished = termination;
        Ok(Some(AutoReport {
            iteration: self.st.iteration,
            evaluations: self.st.evaluations,
            sigma,
            next_sigma: self.st.sigma,
            value: self.value(),
            step_length,
            ratio,
            kind,
            termination,
        }))
    }

    /// Whether σ has converged: on a deterministic objective every coordinate's spread
    /// σ√Cᵢᵢ (a sample's standard deviation along it) is below `tolerance` times its
    /// spread at the start ([`Auto::start_scale`]), as CMA-ES's TolX asks of its
    /// coordinates; on a noisy one σ < `tolerance`·σ₀ (see [`NOISY_TOLERANCE`]).
    fn sigma_converged(&self) -> bool {
        let n = self.theta.len();
        let limit = self.tolerance();
        if self.st.noisy {
            return self.st.sigma < limit * self.st.sigma0;
        }
        let least = self.least_start_scale();
        (0..n).all(|i| {
            let c = match self.shape {
                Shape::Full => self.mem.c[i * n + i],
                Shape::Diagonal => self.mem.c[i],
            };
            self.st.sigma * c.sqrt() < limit * self.start_scale(i).max(least)
        })
    }

    /// Coordinate i's scale at the start before [`Auto::least_start_scale`]: the scale
    /// it was given, cut to a quarter of its side of the box where that is narrower
    /// (pycma's advice for σ₀: about a quarter of the search interval).
    fn start_scale(&self, i: usize) -> T {
        let m = &self.mem;
        let width = m.upper[i] - m.lower[i];
        if width > T::ZERO && width.is_finite() {
            m.scale[i].min(T::HALF * T::HALF * width)
        } else {
            m.scale[i]
        }
    }

    /// The least scale a coordinate starts with: √[`metric::floor`] of the largest
    /// [`Auto::start_scale`], which keeps C within what T whitens.
    fn least_start_scale(&self) -> T {
        let largest = (0..self.theta.len()).fold(T::ZERO, |a, i| a.max(self.start_scale(i)));
        largest * metric::floor::<T>().sqrt()
    }

    /// The tolerance of [`Auto::sigma_converged`] ([`AutoOptions::tolerance`]).
    fn tolerance(&self) -> T {
        let default = if self.st.noisy {
            NOISY_TOLERANCE
        } else {
            TOLERANCE
        };
        self.options.tolerance.unwrap_or(T::from_f64(default))
    }

    /// Evaluations left in the budget (`usize::MAX` without one).
    fn remaining(&self) -> usize {
        self.options
            .max_evaluations
            .map_or(usize::MAX, |m| m.saturating_sub(self.st.evaluations))
    }

    /// The centre's value and the samples the model needs; `Some(kind)` when the
    /// iteration ends here (a plateau, or the budget).
    fn sample<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<Option<AutoStep>, Error> {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let first = !self.st.centre_known;
        let near = self.count_within(T::from_f64(REACH));
        let survey = first || self.st.survey;
        self.st.survey = false;
        let pairs = if survey {
            survey_pairs(n)
        } else if self.st.validate {
            (validating(n) + 1)
                .saturating_sub(self.count_around(T::from_f64(REACH)))
                .div_ceil(2)
                .clamp(1, survey_pairs(n))
        } else if self.st.resample {
            1
        } else {
            nearby_needed(n).saturating_sub(near).div_ceil(2)
        };
        // θ is evaluated first, and again beside the samples of a noisy objective: they
        // share its seed, so that they compare with f(θ) on common noise.
        let centre = first || (self.st.noisy && pairs > 0);
        let mut rows = 0;
        if centre {
            self.mem.stage[..n].copy_from_slice(self.theta);
            rows = 1;
        }
        let root_n = T::from_usize(n).sqrt();
        let exploring = !survey && self.st.resample;
        // Halves that would leave the box stay on their lines (below) only where that can
        // make the model exact: geometry pairs of an exact fit.
        let keep_on_line = !exploring && self.ridge() != Ridge::Prior;
        // A restart's survey of a full model is drawn along the parameter axes where the
        // metric keeps them nearly orthogonal, so that it can tell which coordinates f
        // ignores at this σ (FLAT_STRETCH); pair p then runs along axis (first_axis + p)
        // mod n. The first survey keeps the random frame: from a plateau start every
        // pair ties whatever its direction, and pairs along the axes miss a target that
        // lies diagonally off more often than pairs along random directions do. Nor on a
        // noisy objective from θ on a face of the box: a pair along an axis normal to
        // the face folds onto one point inside (from a corner, every pair does), which
        // a deterministic objective's ties still read as flat or not, but a noisy one's
        // values never tie, so the fold only loses a direction.
        let axes = survey && !first && !(self.st.noisy && self.on_face()) && self.axes_orthogonal();
        let first_axis = if self.st.frame_next >= n {
            0
        } else {
            self.st.frame_next
        };
        for _ in 0..pairs {
            let k = self.next_direction();
            // Geometry pairs lie at the samples' typical distance σ√n; a pair drawn to
            // explore (a plateau, a failed step) at a Gaussian sample's distance σ‖t‖,
            // t ~ N(0, I), so that every scale below σ is searched too.
            let radius = if exploring {
                sigma * self.gaussian_length(n)
            } else {
                sigma * root_n
            };
            // The direction Lb, or the axis eₖ scaled to unit whitened length, in the
            // batch's next row for now.
            if axes {
                let length = (0..n).fold(T::ZERO, |s, i| s + self.mem.li[i * n + k].sq());
                self.mem.rs.fill(T::ZERO);
                self.mem.rs[k] = T::ONE / length.sqrt();
            } else {
                metric::apply(
                    self.shape,
                    self.mem.l,
                    &self.mem.frame[k * n..(k + 1) * n],
                    self.mem.rs,
                );
            }
            for sign in [T::ONE, -T::ONE] {
                // A half that would leave the box stops where its line does, so that the
                // pair stays on one line through θ: three points on a line fix the
                // model's slope and curvature along it, as a survey of such lines fixes
                // a quadratic. Where that leaves less than an eighth of its length, for a
                // pair drawn to explore (whose reach is its purpose), and where no fit
                // can be exact, it is mirrored at the faces instead.
                let mut length = radius;
                if keep_on_line {
                    let (lower, upper) = (&*self.mem.lower, &*self.mem.upper);
                    let room = room_along(self.theta, self.mem.rs, sign, lower, upper);
                    if room < radius && room >= T::from_f64(0.125) * radius {
                        length = room;
                    }
                }
                for i in 0..n {
                    let x = self.theta[i] + sign * length * self.mem.rs[i];
                    self.mem.stage[rows * n + i] = reflect(x, self.mem.lower[i], self.mem.upper[i]);
                }
                rows += 1;
            }
        }
        let allowed = rows.min(self.remaining());
        if rows > 0 && allowed == 0 {
            return Ok(Some(AutoStep::OutOfBudget));
        }
        let group = self.next_group();
        if allowed > 0 {
            // Both halves of a pair share a seed; θ has its own. A noisy objective's
            // points all share one.
            let seed_base = self.rng.next_u64();
            let centre_rows = usize::from(centre);
            let noisy = self.st.noisy;
            self.evaluate(objective, allowed, spent, |row| {
                if row < centre_rows || noisy {
                    seed_base
                } else {
                    seed_base.wrapping_add(1 + ((row - centre_rows) / 2) as u64)
                }
            })?;
            if centre {
                self.st.centre_known = true;
                let f = self.mem.stage_f[0];
                self.st.value = f.is_finite().then_some(f);
                self.st.gained |= first && f.is_finite();
                if self.st.noisy && f.is_finite() {
                    self.st.shared = Some((seed_base, group));
                }
            }
        }
        if axes && allowed == rows {
            self.stretch_flat_axes(first_axis, pairs, usize::from(centre));
        }
        // Remember the points and move θ to the lowest when it beats f(θ).
        self.remember(allowed, group, survey);
        let mut lowest: Option<(usize, T)> = None;
        for row in 0..allowed {
            let f = self.mem.stage_f[row];
            if f.is_finite() && lowest.is_none_or(|(_, b)| f < b) {
                lowest = Some((row, f));
            }
        }
        let trust_samples = !self.st.noisy || self.st.shared.is_some() || self.st.value.is_none();
        if let Some((row, f)) = lowest {
            if trust_samples && self.st.value.is_none_or(|v| f < v) {
                let (theta, stage) = (&mut *self.theta, &self.mem.stage);
                theta.copy_from_slice(&stage[row * n..(row + 1) * n]);
                self.st.value = Some(f);
                self.st.gained = true;
            }
        }
        if allowed < rows {
            return Ok(Some(AutoStep::OutOfBudget));
        }
        // A plateau: most of this iteration's samples tie with f(θ) or, where it drew
        // none, every value within reach does. A smooth f never ties, so even one tie
        // says that f is piecewise constant at this scale. Where θ has just moved to a
        // sample, that sample counts among them and ties with itself: a move to a lower
        // sample marks a lattice unless every other sample ties too, so that the next
        // failed step draws another pair at this σ, where the samples still find lower
        // points, instead of halving it. (Counting only the other samples, and keeping
        // the resampling after a move as a rule of its own, measured the same runs at
        // 1e-8 and 1–12 % more evaluations on BBOB; the 2026-11-26 note on the tie
        // count.)
        let fresh = usize::from(centre)..allowed;
        let (near, ties) = if fresh.is_empty() && self.st.noisy {
            // Values on other seeds do not compare: nothing new to read.
            (2, usize::from(self.st.lattice))
        } else if fresh.is_empty() {
            self.ties_within(T::from_f64(REACH))
        } else {
            let v = self.st.value.unwrap_or(T::MAX);
            self.mem.stage_f[fresh]
                .iter()
                .filter(|f| f.is_finite())
                .fold((0, 0), |(near, ties), &f| {
                    (near + 1, ties + usize::from(ties_with(f, v)))
                })
        };
        self.st.lattice = ties > 0 && ties < near;
        if self.st.value.is_none() || 2 * ties > near || ties == near {
            // Ties say that f is flat here only where the values around θ differ by far
            // more than the 16 ulps within which they tie: at a smooth minimum they tie
            // once σ is small enough that the arithmetic no longer resolves f.
            if let Some(v) = self.st.value {
                if self.spread(T::from_f64(2.0 * REACH)) > T::EPSILON.sqrt() * v.abs() {
                    self.st.tie_scale = self.st.tie_scale.max(sigma);
                }
            }
            self.st.sigma = self.widened_sigma(PLATEAU_WIDTH);
            return Ok(Some(AutoStep::Plateau));
        }
        Ok(None)
    }

    /// Fits the model, evaluates its step and updates σ; returns what happened and the
    /// ratio of actual to predicted decrease.
    fn model_step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<(AutoStep, Option<T>), Error> {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let root_n = T::from_usize(n).sqrt();
        let Some(value) = self.st.value else {
            return Ok((AutoStep::Plateau, None));
        };
        if !self.st.noisy && !self.st.checked {
            self.check_determinism(objective, value, spent)?;
        }
        if self.st.unseeded && !self.st.voting {
            self.st.voting = self.sparse_noise();
        }
        let scale = self.spread(T::from_f64(2.0 * REACH));
        let Some((noise, mut fitted)) = self.fit(value, scale) else {
            self.st.sigma = sigma * T::HALF;
            return Ok((AutoStep::Rejected, None));
        };
        let mut value = value;
        // θ's draw lies below the robust model's value at θ: it may be a lucky one.
        let mut lucky = false;
        if self.st.unseeded {
            // One step of iteratively reweighted least squares per iteration, warm
            // started from the points' weights of the last. The noise level η stays the
            // first fit's: the scatter the robust fit sets aside is still the noise a
            // step must clear.
            let cut = self.reweigh(value, scale);
            let Some((_, refitted)) = self.fit(value, scale) else {
                self.st.sigma = sigma * T::HALF;
                return Ok((AutoStep::Rejected, None));
            };
            fitted = refitted;
            lucky = self.mem.beta[0] > T::ZERO;
            // θ's own residual under the robust fit is −c. Where that makes its draw an
            // outlier — a lucky spike that would reject every later step — θ is drawn
            // again, and steps are judged against the new draw. (Only c depends on the
            // value the fit was taken relative to, and c is not used below.)
            if self.mem.beta[0].abs() >= cut && self.remaining() > 0 {
                let again = self.evaluate_theta_again(objective, spent)?;
                let group = self.next_group();
                self.remember(1, group, false);
                if again.is_finite() {
                    value = again;
                    self.st.value = Some(again);
                }
            }
        }
        self.save_prior(scale, sigma);
        let radius = root_n;
        let ok = self.trust_step(radius);
        // Project the trial point θ + σLs into the box; the step is what remains of s.
        metric::apply(self.shape, self.mem.l, self.mem.s, self.mem.gx);
        for i in 0..n {
            let x = (self.theta[i] + sigma * self.mem.gx[i])
                .max(self.mem.lower[i])
                .min(self.mem.upper[i]);
            self.mem.stage[i] = x;
            self.mem.rs[i] = (x - self.theta[i]) / sigma;
        }
        metric::apply(self.shape, self.mem.li, self.mem.rs, self.mem.s);
        let predicted = if ok {
            self.predicted_decrease()
        } else {
            T::ZERO
        };
        let length = norm(self.mem.s);
        // A model that claims a minimum near θ must have seen θ's surroundings in
        // enough directions before σ shrinks on its word; the pairs it lacks come in
        // one batch (on a declared-noisy objective one pair per iteration, the rule its
        // runs were measured with).
        let validated = self.count_around(T::from_f64(REACH)) > validating(n);
        if predicted <= T::ZERO || !predicted.is_finite() || length <= T::from_f64(1e-3) * radius {
            if validated {
                self.st.sigma = sigma * T::HALF;
            } else {
                self.st.resample = true;
                self.st.validate = !self.st.noisy;
            }
            return Ok((AutoStep::AtModelMinimum, None));
        }
        // A noisy objective's trial is compared with f(θ) on common noise: the seed on
        // which this iteration measured f(θ), or a fresh one on which θ is evaluated too.
        // An unseeded objective's θ is drawn again beside the trial after a rejection,
        // where its draw lies below the robust fit, until it has THETA_DRAWS draws.
        let redraw = lucky && self.st.doubted && self.draws_at_theta() < THETA_DRAWS;
        let compare = self.st.noisy && self.st.shared.is_none() || redraw;
        let rows = if compare { 2 } else { 1 };
        if self.remaining() < rows {
            return Ok((AutoStep::OutOfBudget, None));
        }
        if compare {
            self.mem.stage[n..2 * n].copy_from_slice(self.theta);
        }
        let seed = self.rng.next_u64();
        let (seed, group) = match self.st.shared {
            Some(shared) => shared,
            None => (seed, self.next_group()),
        };
        self.evaluate(objective, rows, spent, |_| seed)?;
        let trial = self.mem.stage_f[0];
        let mut reference = if compare { self.mem.stage_f[1] } else { value };
        self.remember(rows, group, false);
        if self.st.unseeded {
            // The trial must beat the median of θ's draws (the larger of two), which one
            // lucky draw — the low tail of the noise — cannot set.
            let draws = self.draws_at_theta();
            if draws > 0 {
                reference = lower_median(&self.mem.sw[..draws]);
            }
        }
        if compare && reference.is_finite() {
            self.st.value = Some(reference);
        }
        let ratio = if trial.is_finite() && reference.is_finite() {
            (reference - trial) / (scale * predicted)
        } else {
            -T::MAX
        };
        // A tie is accepted: on a flat piece of f the smoothed model's minimum is the
        // better guess (the middle of a zero-loss region, the continuous optimum of a
        // rounded function).
        let accepted = trial.is_finite() && reference.is_finite() && trial <= reference;
        let tie = accepted && trial == reference;
        if !accepted
            && trial.is_finite()
            && self.st.cycle > 0
            && sigma > T::from_f64(CONTINUATION_SCALE) * self.st.sigma0
            && length < T::from_f64(0.9) * radius
            && !self.st.noisy
            && (!self.st.unseeded || self.st.voting)
        {
            // Continuation: a restart at a scale above σ₀'s fits the smoothed objective,
            // whose minimum inside the trust region is where the search should go on
            // even where f itself is higher there (a local minimum's wells, a lattice's
            // cells, Rosenbrock's other valley). The centre moves, σ halves on the way
            // down, and the best point is kept (`Auto::restore_best`). A minimum on the
            // region's boundary is the model extrapolating: no move.
            if self.st.best_value.is_none() {
                self.st.best_value = Some(reference);
                self.mem.best.copy_from_slice(self.theta);
            }
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.value = Some(trial);
            self.st.sigma = sigma * T::HALF;
            return Ok((AutoStep::Continued, Some(ratio)));
        }
        // On an unseeded objective, a trial rejected by less than twice the noise's
        // scale, whose step promised no more than that, was judged by the noise.
        let judged_by_noise = self.st.unseeded && !accepted && {
            let level = T::TWO * self.repeat_spread().unwrap_or(T::ZERO);
            trial - reference <= level && predicted * scale <= level
        };
        if judged_by_noise
            || !accepted
                && noise > T::from_f64(ROUGH)
                && trial - reference <= T::TWO * noise * scale
        {
            // f is rough at this scale — the fit leaves scatter comparable to the values'
            // spread, or the step's promise is within the noise — and the trial is no
            // worse than that scatter: look wider, where the smoothed function has a
            // slope to see.
            self.st.rough_scale = self.st.rough_scale.max(sigma);
            self.st.sigma = self.widened_sigma(PLATEAU_WIDTH);
            return Ok((AutoStep::Plateau, Some(ratio)));
        }
        let boundary = length >= T::from_f64(0.9) * radius;
        let determined = fitted > self.shape.coefficients(n);
        // The step fell short of its prediction (ρ̂ < 0.1) without being a tie.
        let poor = ratio < T::from_f64(0.1) && !tie;
        // Whether a shortfall may be blamed on σ: the points near θ determine the model
        // at this scale. Points farther out (z ≤ 2ρ fits them) do not count: they saw f
        // at wider scales, and a kink's smoothed curvature falls with the scale (a
        // cone's as 1/σ), so a model resting on them mispredicts alike at every smaller
        // σ and shrinking on its word only cascades σ down. Where the memory cannot
        // determine the model (n ≥ 15, the diagonal model), a validated one may be
        // blamed. A declared-noisy objective keeps the rule it was measured with: a fit
        // determined by its points, or a validated one (holding σ lost SHADOW runs).
        let blames_scale = poor
            && if self.st.noisy {
                determined || validated
            } else if memory_determines_model(n) {
                self.count_around(T::from_f64(REACH)) > self.shape.coefficients(n)
            } else {
                validated
            };
        // On an unseeded objective whose every draw is noisy, a trial rejected by less
        // than NOISE_MARGIN times the noise's scale may have been rejected by the noise
        // rather than the model: halving σ on its word shrinks the steps until every
        // comparison is a coin toss. The model needs more points at this scale instead.
        let noise_rejected = poor
            && !accepted
            && self.st.unseeded
            && self
                .dense_noise_scale()
                .is_some_and(|s| trial - reference <= T::from_f64(NOISE_MARGIN) * s);
        self.st.sigma = if poor && accepted && boundary && !self.st.noisy {
            // f fell, by far less than predicted, along a step the radius cut short:
            // the model overstates the decrease (a kink or a ridge its fit smooths
            // over, which no smaller σ fits better), not the direction. Shrinking σ
            // would only shorten the next step; let it grow a little instead. (On a
            // noisy objective so small a decrease may be the noise's.)
            (sigma * T::from_f64(STRIDE)).min(self.widened_sigma(GROWTH_WIDTH))
        } else if poor && (noise_rejected || self.st.lattice || !blames_scale) {
            // Too few points near θ to blame the scale, f is piecewise constant at it, or
            // the noise rejected the trial: sample more at this σ first.
            self.st.resample = true;
            sigma
        } else if poor && self.st.noisy {
            sigma * T::HALF
        } else if poor {
            sigma * T::from_f64(SHRINK)
        } else if ratio >= T::from_f64(0.7) && boundary {
            self.widened_sigma(GROWTH_WIDTH)
        } else if length < T::HALF * radius && validated {
            sigma * (T::TWO * length / radius).max(T::HALF)
        } else {
            sigma
        };
        self.st.unconfirmed = self.st.unconfirmed.saturating_add(1);
        if accepted && ratio >= T::from_f64(0.1) {
            // The model predicted the decrease: trust its curvature's shape.
            self.learn_metric(1.0);
            self.st.unconfirmed = 0;
        } else if !self.st.noisy
            && (!self.st.unseeded || self.st.voting)
            && !self.st.lattice
            && self.st.tie_scale <= T::ZERO
            && !self.on_face()
            && (determined && noise <= T::from_f64(SMOOTH) || self.stalled_on_shape())
        {
            // The points determine the curvature, and fit it closely, though the step
            // did not confirm it: a cone's or a kink's smoothed curvature is what the
            // metric needs even where the quadratic mispredicts f's steps. Or no fit can
            // be determined and a shape the metric has not learnt stalls the run
            // ([`STALLED_ANISOTROPY`]). (Not where samples have tied since f last fell:
            // on a lattice the fitted curvature is the steps', not f's. Nor with θ on a
            // face of the box: samples mirrored there make f look flat across the face,
            // C would stretch along its normal, and steps along that axis are cut off by
            // the bound.)
            self.learn_metric(DETERMINED_METRIC_WEIGHT);
        }
        self.st.doubted = self.st.unseeded && !accepted;
        if accepted {
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.value = Some(trial);
            self.st.gained |= trial < reference;
            Ok((AutoStep::Accepted, Some(ratio)))
        } else {
            Ok((AutoStep::Rejected, Some(ratio)))
        }
    }

    /// Evaluates θ once more, unremembered, on an objective declared deterministic, at
    /// the first model step after each restart until noise is found, and sets
    /// [`State::unseeded`] when the value differs from f(θ)'s; then a third time, to
    /// tell dense noise from sparse outliers ([`State::dense`]). One evaluation on a
    /// deterministic objective, on seed 0 (which it ignores), so the run's random
    /// stream, and a deterministic run's points, are unchanged.
    fn check_determinism<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        value: T,
        spent: &mut usize,
    ) -> Result<(), Error> {
        if self.remaining() == 0 {
            return Ok(());
        }
        self.st.checked = true;
        let again = self.evaluate_theta_again(objective, spent)?;
        self.st.unseeded = again.is_finite() && again != value;
        if self.st.unseeded && self.remaining() > 0 {
            let third = self.evaluate_theta_again(objective, spent)?;
            self.st.dense = third != value && third != again;
        }
        Ok(())
    }

    /// f(θ) evaluated once more, staged in row 0 (so that [`Auto::remember`] can keep
    /// it), on seed 0: only objectives declared deterministic are evaluated again this
    /// way, and they ignore the seed.
    fn evaluate_theta_again<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<T, Error> {
        let n = self.theta.len();
        self.mem.stage[..n].copy_from_slice(self.theta);
        self.evaluate(objective, 1, spent, |_| 0)?;
        Ok(self.mem.stage_f[0])
    }

    /// Sets the robustness weights ([`Memory::credit`]) of the points the fit used from
    /// their residuals rᵢ under the model just fitted: Tukey's biweight
    /// (1 − (rᵢ/(cs))²)², zero beyond |rᵢ| = cs, with c = [`TUKEY`] and s = 1.4826 ×
    /// the median |rᵢ| (floored at √ε of the values' spread, so that a model that
    /// interpolates most points exactly keeps them). Points beyond the fit's reach keep
    /// their weights. Returns the cut cs, in the fit's units (values over `scale`;
    /// `T::MAX` when no point was within reach).
    fn reweigh(&mut self, value: T, scale: T) -> T {
        let shape = self.shape;
        let limit = T::from_f64(2.0 * REACH);
        let c = self.mem.beta[0];
        // |rᵢ| in `sw`, free until the next fit fills it again.
        let mut used = 0;
        for k in 0..self.st.count {
            if self.offset_of(k) > limit {
                continue;
            }
            let u = &*self.mem.gx;
            let model = c + dot(self.mem.g, u) + shape.half_quadratic(self.mem.h, u);
            let r = (self.mem.fs[k] - value) / scale - model;
            // Kept in the reach cache `zs` (invalidated below) until the scale is known.
            self.mem.zs[k] = r;
            self.mem.sw[used] = r.abs();
            used += 1;
        }
        if used == 0 {
            return T::MAX;
        }
        let spread = T::from_f64(1.4826) * lower_median(&self.mem.sw[..used]);
        let cut = T::from_f64(TUKEY) * spread.max(T::EPSILON.sqrt());
        for k in 0..self.st.count {
            if self.offset_of(k) > limit {
                continue;
            }
            let t = self.mem.zs[k] / cut;
            self.mem.credit[k] = if t.abs() < T::ONE {
                (T::ONE - t.sq()).sq()
            } else {
                T::ZERO
            };
        }
        // `zs` held residuals: the reach cache is stale.
        self.st.reach_key = None;
        cut
    }

    /// Writes remembered point k's standardised offset u = L⁻¹(x − θ)/σ to `gx` (as the
    /// fit computes it) and returns its reach ‖u‖/√n.
    fn offset_of(&mut self, k: usize) -> T {
        let n = self.theta.len();
        let x = &self.mem.xs[k * n..(k + 1) * n];
        for ((ri, &xi), &ti) in self.mem.rs.iter_mut().zip(x).zip(self.theta.iter()) {
            *ri = (xi - ti) / self.st.sigma;
        }
        metric::apply(self.shape, self.mem.li, self.mem.rs, self.mem.gx);
        norm(self.mem.gx) / T::from_usize(n).sqrt()
    }

    /// Writes to `s` the model's minimiser within ‖s‖ ≤ `radius` over the steps that
    /// stay in the box along the coordinates whose bounds they would cross: the
    /// unconstrained minimiser first; while it would carry a coordinate out of the box,
    /// that coordinate is held on the bound it crosses and the model is minimised again
    /// over the steps that keep every held coordinate there ([`Auto::held_step`]; at
    /// most n rounds). Without that, the projection into the box cuts such a step off
    /// where it is no longer the model's minimiser — often a step uphill — and where θ
    /// lies close to a face σ shrinks while θ creeps towards it. The held coordinates'
    /// moves are kept in the first two rows of `stage` (the trial point overwrites them).
    /// False when the model is not finite.
    fn trust_step(&mut self, radius: T) -> bool {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let m = &mut self.mem;
        if !trust::solve(
            self.shape,
            m.g,
            m.h,
            radius,
            trust::Scratch {
                a: m.a,
                v: m.v,
                gamma: m.gamma,
                lambda: m.lambda,
            },
            m.s,
        ) {
            return false;
        }
        // stage[n + i] is 1 where coordinate i is held, stage[i] its move over σ.
        m.stage[n..2 * n].fill(T::ZERO);
        for _ in 0..n {
            let m = &mut self.mem;
            metric::apply(self.shape, m.l, m.s, m.gx);
            let (moves, held) = m.stage[..2 * n].split_at_mut(n);
            let mut crossed = false;
            for i in 0..n {
                let x = self.theta[i] + sigma * m.gx[i];
                let bound = if x < m.lower[i] {
                    m.lower[i]
                } else if x > m.upper[i] {
                    m.upper[i]
                } else {
                    continue;
                };
                if held[i] == T::ZERO {
                    held[i] = T::ONE;
                    moves[i] = (bound - self.theta[i]) / sigma;
                    crossed = true;
                }
            }
            if !crossed {
                break;
            }
            if !self.held_step(radius) {
                return false;
            }
        }
        true
    }

    /// Writes to `s` the model's minimiser within ‖s‖ ≤ `radius` over the steps that
    /// move each held coordinate i (`stage[n + i]` = 1) by σ·`stage[i]`: with k held, the
    /// constraint Au = b for the k rows of L that belong to them. With Q an orthonormal
    /// basis of A's rows (A = RQ, R lower triangular, by Gram–Schmidt) and Z one of the
    /// directions orthogonal to them, u = u₀ + Zᵀw with u₀ = Qᵀy, Ry = b, the smallest
    /// step that meets the constraint; since u₀ ⊥ Z, ‖u‖² = ‖u₀‖² + ‖w‖², and w solves
    /// the trust-region problem for the slope Z(g + Hu₀) and curvature ZHZᵀ within
    /// √(radius² − ‖u₀‖²) (u₀ scaled back to the radius where it alone leaves the
    /// region). A diagonal metric maps coordinates to coordinates, so there Q and Z are
    /// unit vectors. Uses `hx` for the basis (Q's k rows, then Z's n − k) and `rh` for R,
    /// then for ZHZᵀ. False when the model is not finite.
    fn held_step(&mut self, radius: T) -> bool {
        let n = self.theta.len();
        let shape = self.shape;
        let m = &mut self.mem;
        let (moves, held) = m.stage[..2 * n].split_at(n);
        let is_held = |i: usize| held[i] != T::ZERO;
        let k = (0..n).filter(|&i| is_held(i)).count();
        let free = n - k;
        let (basis, l, u0) = (&mut *m.hx, &*m.l, &mut *m.s);
        match shape {
            Shape::Full => {
                for (row, i) in (0..n).filter(|&i| is_held(i)).enumerate() {
                    basis[row * n..(row + 1) * n].copy_from_slice(&l[i * n..(i + 1) * n]);
                    m.rh[row * k..(row + 1) * k].fill(T::ZERO);
                    let r_row = Some(&mut m.rh[row * k..row * k + row]);
                    let length = orthogonalise(basis, row, n, 2, r_row);
                    if length <= T::ZERO || !length.is_finite() {
                        return false;
                    }
                    for x in basis[row * n..(row + 1) * n].iter_mut() {
                        *x /= length;
                    }
                    m.rh[row * k + row] = length;
                    // Ry = b by forward substitution, y in `rg`.
                    let sum = (0..row).fold(T::ZERO, |s, p| s + m.rh[row * k + p] * m.rg[p]);
                    m.rg[row] = (moves[i] - sum) / length;
                }
                // Complete the basis with the unit vectors least covered by it so far.
                for row in k..n {
                    let mut best = (0, -T::ONE);
                    for j in 0..n {
                        let covered = (0..row).fold(T::ZERO, |s, p| s + basis[p * n + j].sq());
                        if T::ONE - covered > best.1 {
                            best = (j, T::ONE - covered);
                        }
                    }
                    let q = &mut basis[row * n..(row + 1) * n];
                    q.fill(T::ZERO);
                    q[best.0] = T::ONE;
                    let length = orthogonalise(basis, row, n, 2, None);
                    for x in basis[row * n..(row + 1) * n].iter_mut() {
                        *x /= length;
                    }
                }
                u0.fill(T::ZERO);
                for row in 0..k {
                    axpy(m.rg[row], &basis[row * n..(row + 1) * n], u0);
                }
            }
            Shape::Diagonal => {
                for i in 0..n {
                    u0[i] = if is_held(i) { moves[i] / l[i] } else { T::ZERO };
                }
            }
        }
        let reach = norm(u0);
        if reach >= radius {
            // The held moves alone leave the region: go as far towards them as it allows.
            for x in u0.iter_mut() {
                *x = *x * radius / reach;
            }
            return true;
        }
        let inner = (radius.sq() - reach.sq()).sqrt();
        // The reduced model over w: slope Z(g + Hu₀), curvature ZHZᵀ.
        shape.apply(m.h, u0, m.gamma);
        for (gi, &x) in m.gamma.iter_mut().zip(m.g.iter()) {
            *gi += x;
        }
        match shape {
            Shape::Full => {
                // ZH into `a` (rows of n), then ZHZᵀ into `rh`.
                for a in 0..free {
                    let z = &basis[(k + a) * n..(k + a + 1) * n];
                    m.rg[a] = dot(z, m.gamma);
                    shape.apply(m.h, z, &mut m.a[a * n..(a + 1) * n]);
                }
                for a in 0..free {
                    for b in 0..free {
                        m.rh[a * free + b] = dot(
                            &m.a[a * n..(a + 1) * n],
                            &basis[(k + b) * n..(k + b + 1) * n],
                        );
                    }
                }
            }
            Shape::Diagonal => {
                for (a, i) in (0..n).filter(|&i| !is_held(i)).enumerate() {
                    m.rg[a] = m.gamma[i];
                    m.rh[a] = m.h[i];
                }
            }
        }
        let ok = free == 0
            || trust::solve(
                shape,
                &m.rg[..free],
                &m.rh[..shape.hessian_len(free)],
                inner,
                trust::Scratch {
                    a: m.a,
                    v: m.v,
                    gamma: m.gamma,
                    lambda: m.lambda,
                },
                &mut m.rs[..free],
            );
        if ok {
            match shape {
                Shape::Full => {
                    for a in 0..free {
                        axpy(m.rs[a], &basis[(k + a) * n..(k + a + 1) * n], u0);
                    }
                }
                Shape::Diagonal => {
                    for (a, i) in (0..n).filter(|&i| !is_held(i)).enumerate() {
                        u0[i] = m.rs[a];
                    }
                }
            }
        }
        ok
    }

    /// Keeps σ off the scales where it has already learnt nothing since f(θ) last fell:
    /// an iteration that began at `sigma` and would end below it keeps `sigma` and draws
    /// another pair instead:
    ///
    /// * when the new σ would be at or under [`State::tie_scale`], where the samples tied
    ///   (a plateau): there they would only tie again, and the run would cycle between
    ///   the two scales;
    /// * on a plateau (a tie scale is set), when its model was blind — it saw no
    ///   decrease (`AtModelMinimum`), or f rose by more than the decrease it predicted
    ///   (ρ̂ < −1) — and the new σ would be at or under [`State::rough_scale`], where the
    ///   model was blind before.
    ///
    /// A blind model that is held also widens σ as on a plateau, with `sigma` the new
    /// rough scale: on a plateau the variation the quadratic cannot see is jitter (a
    /// rasteriser's pixel counts), and the samples of a wider σ may reach a slope. Off
    /// plateaus a blind model shrinks σ as before: on a rugged f the lower values lie
    /// at finer scales. A gain or a restart clears both scales.
    fn hold_sigma(&mut self, sigma: T, kind: AutoStep, ratio: Option<T>) {
        if self.st.gained {
            self.forget_scales();
            return;
        }
        let next = self.st.sigma;
        if next >= sigma {
            return;
        }
        let blind = kind == AutoStep::AtModelMinimum || ratio.is_some_and(|r| r < -T::ONE);
        let tied = next <= self.st.tie_scale;
        let rough = blind && self.st.tie_scale > T::ZERO && next <= self.st.rough_scale;
        if !tied && !rough {
            return;
        }
        self.st.sigma = sigma;
        self.st.resample = true;
        if blind {
            self.st.rough_scale = sigma;
            self.st.sigma = self.widened_sigma(PLATEAU_WIDTH);
        }
    }

    /// Clears the tie and rough scales (`Auto::hold_sigma`): f(θ) fell, or the run
    /// restarts, so what they recorded no longer describes θ's surroundings.
    fn forget_scales(&mut self) {
        self.st.tie_scale = T::ZERO;
        self.st.rough_scale = T::ZERO;
    }

    /// 2σ, capped at `width`·σ₀ and, with bounds, at half the box's widest side.
    fn widened_sigma(&self, width: f64) -> T {
        let mut cap = self.st.sigma0 * T::from_f64(width);
        if self.st.bounded {
            let width = (0..self.theta.len())
                .fold(T::ZERO, |w, i| w.max(self.mem.upper[i] - self.mem.lower[i]));
            if width > T::ZERO && width.is_finite() {
                cap = cap.min(T::HALF * width);
            }
        }
        (self.st.sigma * T::TWO).min(cap).max(self.st.sigma)
    }

    /// σ₀·2^(k mod [`RESTART_SCALES`]) for the k-th restart of the run, at most
    /// [`PLATEAU_WIDTH`]·σ₀ and, with bounds, half the box's widest side.
    fn restart_sigma(&self) -> T {
        let doublings = (self.st.cycle % RESTART_SCALES) as i32;
        let sigma = self.st.sigma0 * T::from_f64(libm::pow(2.0, f64::from(doublings)));
        let mut cap = self.st.sigma0 * T::from_f64(PLATEAU_WIDTH);
        if self.st.bounded {
            let width = (0..self.theta.len())
                .fold(T::ZERO, |w, i| w.max(self.mem.upper[i] - self.mem.lower[i]));
            if width > T::ZERO && width.is_finite() {
                cap = cap.min(T::HALF * width);
            }
        }
        sigma.min(cap).max(self.st.sigma0.min(cap))
    }

    /// ‖t‖ for t ~ N(0, I) in n dimensions (a χ_n draw).
    fn gaussian_length(&mut self, n: usize) -> T {
        (0..n)
            .fold(T::ZERO, |s, _| {
                s + normal::quantile(T::uniform_open(&mut self.rng)).sq()
            })
            .sqrt()
    }

    /// The next column of the sampling frame, drawing a new random orthonormal frame
    /// (Gram–Schmidt on Gaussian vectors) when the last is used up.
    fn next_direction(&mut self) -> usize {
        let n = self.theta.len();
        if self.st.frame_next >= n {
            for k in 0..n {
                loop {
                    for i in 0..n {
                        self.mem.frame[k * n + i] =
                            normal::quantile(T::uniform_open(&mut self.rng));
                    }
                    let len = orthogonalise(self.mem.frame, k, n, 1, None);
                    if len > T::from_f64(1e-3) {
                        for x in self.mem.frame[k * n..(k + 1) * n].iter_mut() {
                            *x /= len;
                        }
                        break;
                    }
                }
            }
            self.st.frame_next = 0;
        }
        self.st.frame_next += 1;
        self.st.frame_next - 1
    }

    /// Evaluates the first `rows` staged points with the given seeds, in chunks; with
    /// [`NonFinite::Error`] the first chunk that leaves a point non-finite ends the batch
    /// with [`Error::NonFiniteObjective`], naming that point's first draw.
    ///
    /// A row equal to an earlier row of its chunk with the same seed (up to rounding) is
    /// not evaluated again but takes that row's value ([`Objective`]: equal seeds give
    /// equal noise), unless the objective draws unseeded noise, where a second draw is
    /// information: a pair whose halves the box folds onto one point (from a corner, or
    /// along an axis normal to a face) costs one evaluation.
    fn evaluate<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        rows: usize,
        spent: &mut usize,
        seed: impl Fn(usize) -> NoiseSeed,
    ) -> Result<(), Error> {
        let n = self.theta.len();
        let mut seeds = [0 as NoiseSeed; CHUNK];
        let mut start = 0;
        while start < rows {
            let len = (rows - start).min(CHUNK);
            for (k, s) in seeds[..len].iter_mut().enumerate() {
                *s = seed(start + k);
            }
            // Row k's first draw is evaluation first + k, or, where a vote draws the first
            // `doubled` rows twice at once, first + 2k below them and first + doubled + k
            // from them on; where rows repeat, first + the number of distinct rows before
            // the one it repeats.
            let first = *spent;
            let mut draws = [0u8; CHUNK];
            let doubled = if self.st.voting {
                self.vote(objective, start, len, spent)?
            } else {
                let distinct = self.distinct_rows(start, len, &mut seeds, &mut draws);
                draw(
                    objective,
                    &self.mem.stage[start * n..(start + distinct) * n],
                    &seeds[..distinct],
                    &mut self.mem.stage_f[start..start + distinct],
                    &mut self.st.evaluations,
                    spent,
                )?;
                if distinct < len {
                    self.spread_distinct(start, len, &draws);
                }
                0
            };
            if self.options.non_finite == NonFinite::Error {
                let values = &self.mem.stage_f[start..start + len];
                if let Some(k) = values.iter().position(|f| !f.is_finite()) {
                    let sample = if self.st.voting {
                        first + k + k.min(doubled)
                    } else {
                        first + usize::from(draws[k])
                    };
                    return Err(Error::NonFiniteObjective { sample });
                }
            }
            start += len;
        }
        Ok(())
    }

    /// Moves the distinct rows of the staged chunk `start … start + len − 1` (at most
    /// [`CHUNK`]) and their seeds to its front, in order, by swaps, and returns their
    /// number; `draws[k]` is where row k's value will be. A row repeats an earlier one,
    /// and shares its draw, where their seeds are equal, their coordinates equal up to
    /// rounding ([`same_point`]) and the objective draws no unseeded noise. With no row
    /// repeated nothing moves.
    fn distinct_rows(
        &mut self,
        start: usize,
        len: usize,
        seeds: &mut [NoiseSeed; CHUNK],
        draws: &mut [u8; CHUNK],
    ) -> usize {
        let n = self.theta.len();
        let stage = &mut self.mem.stage[start * n..(start + len) * n];
        let row = |k: usize| k * n..(k + 1) * n;
        let mut distinct = 0;
        for k in 0..len {
            let repeats = if self.st.unseeded {
                None
            } else {
                (0..k).find(|&j| seeds[j] == seeds[k] && same_point(&stage[row(j)], &stage[row(k)]))
            };
            // CHUNK ≤ 256: indices fit in a byte.
            draws[k] = match repeats {
                Some(j) => draws[j],
                None => {
                    distinct += 1;
                    (distinct - 1) as u8
                }
            };
        }
        if distinct < len {
            for k in 0..len {
                let d = usize::from(draws[k]);
                if first_draw(draws, k) && d != k {
                    swap_rows(stage, n, d, k);
                    seeds.swap(d, k);
                }
            }
        }
        distinct
    }

    /// Undoes [`Auto::distinct_rows`] once its distinct rows were evaluated: every row of
    /// the chunk back in its place, a repeated one with the value of the row it repeats.
    fn spread_distinct(&mut self, start: usize, len: usize, draws: &[u8; CHUNK]) {
        let n = self.theta.len();
        let stage = &mut self.mem.stage[start * n..(start + len) * n];
        let values = &mut self.mem.stage_f[start..start + len];
        // The moves to the front were swaps, made in ascending order: undone in reverse.
        for k in (0..len).rev() {
            let d = usize::from(draws[k]);
            if first_draw(draws, k) && d != k {
                swap_rows(stage, n, d, k);
                values.swap(d, k);
            }
        }
        for k in 0..len {
            if !first_draw(draws, k) {
                let j = draws.iter().position(|&d| d == draws[k]).unwrap_or(k);
                values[k] = values[j];
            }
        }
    }

    /// On sparse unseeded noise ([`State::voting`]), evaluates the staged rows
    /// `start … start + len − 1` (at most [`CHUNK`] rows; the objective ignores their
    /// seeds) until two draws of each agree exactly, and keeps that value, which an
    /// outlier on exact values cannot set (two non-finite draws agree); after [`VOTES`]
    /// draws that all differ it keeps the median of the finite ones. The draws go out in
    /// rounds ([`Auto::draw_rows`]): first every row twice (its two draws side by side),
    /// then the rows still undecided once each, so that a batch renderer sees few calls
    /// however many rows disagree. Within the budget: every row is drawn once; the first
    /// rows twice, as far as the budget goes (their number is returned); a round the
    /// budget cuts short leaves its last rows with the median of the draws they have.
    fn vote<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        start: usize,
        len: usize,
        spent: &mut usize,
    ) -> Result<usize, Error> {
        // Row k's draws are gram[k·VOTES …], `counts[k]` of them; `open[k]` while they
        // disagree and more may be drawn, `agreed[k]` once two agree.
        let mut counts = [0usize; CHUNK];
        let mut open = [true; CHUNK];
        let mut agreed = [false; CHUNK];
        debug_assert!(len * VOTES <= self.mem.gram.len());
        let doubled = len.min(self.remaining().saturating_sub(len));
        let mut round = [0usize; 2 * CHUNK];
        let mut size = 0;
        for k in 0..len {
            for _ in 0..1 + usize::from(k < doubled) {
                round[size] = k;
                size += 1;
            }
        }
        while size > 0 {
            self.draw_rows(objective, start, &round[..size], &mut counts, spent)?;
            // Settle the rows whose newest draw agrees with an earlier one; a row with a
            // single draw (the budget) or VOTES of them is done.
            for k in 0..len {
                if !open[k] {
                    continue;
                }
                let draws = &self.mem.gram[k * VOTES..k * VOTES + counts[k]];
                let last = draws[counts[k] - 1];
                let same = |d: &T| *d == last || !d.is_finite() && !last.is_finite();
                agreed[k] = draws[..counts[k] - 1].iter().any(same);
                open[k] = !agreed[k] && (2..VOTES).contains(&counts[k]);
            }
            // The next round: every open row once more, within the budget.
            size = 0;
            let mut left = self.remaining();
            for (k, open) in open[..len].iter_mut().enumerate() {
                if !*open {
                    continue;
                }
                if left == 0 {
                    *open = false;
                } else {
                    round[size] = k;
                    size += 1;
                    left -= 1;
                }
            }
        }
        // A row keeps the value two of its draws agree on, or the median of its finite
        // draws.
        for k in 0..len {
            let draws = &self.mem.gram[k * VOTES..k * VOTES + counts[k]];
            self.mem.stage_f[start + k] = if agreed[k] {
                draws[counts[k] - 1]
            } else {
                let mut finite = [T::ZERO; VOTES];
                let mut m = 0;
                for &d in draws.iter().filter(|d| d.is_finite()) {
                    finite[m] = d;
                    m += 1;
                }
                if m > 0 {
                    lower_median(&finite[..m])
                } else {
                    draws[0]
                }
            };
        }
        Ok(doubled)
    }

    /// Draws the staged rows `start + k` for each k of `rows` in order (a row listed
    /// twice is drawn twice), in batches of min(m, [`CHUNK`]) rows, m =
    /// [`Auto::history_len`], gathered in the fit's row scratch; row k's draw is appended
    /// to its draws in the fit's Gram scratch (`gram[k·VOTES + counts[k]]`). Both scratch
    /// regions are free outside a fit; the objective ignores the seeds (unseeded noise).
    fn draw_rows<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        start: usize,
        rows: &[usize],
        counts: &mut [usize],
        spent: &mut usize,
    ) -> Result<(), Error> {
        let n = self.theta.len();
        let group = history_len(n).min(CHUNK);
        debug_assert!(group * n <= self.mem.u.len());
        let seeds = [0 as NoiseSeed; CHUNK];
        let mut fresh = [T::ZERO; CHUNK];
        for batch in rows.chunks(group) {
            for (r, &k) in batch.iter().enumerate() {
                let row = &self.mem.stage[(start + k) * n..(start + k + 1) * n];
                self.mem.u[r * n..(r + 1) * n].copy_from_slice(row);
            }
            let m = batch.len();
            let evaluations = &mut self.st.evaluations;
            draw(
                objective,
                &self.mem.u[..m * n],
                &seeds[..m],
                &mut fresh[..m],
                evaluations,
                spent,
            )?;
            for (&k, &f) in batch.iter().zip(&fresh[..m]) {
                self.mem.gram[k * VOTES + counts[k]] = f;
                counts[k] += 1;
            }
        }
        Ok(())
    }

    /// A fresh noise group's id.
    fn next_group(&mut self) -> T {
        self.st.groups = self.st.groups.wrapping_add(1);
        T::from_usize((self.st.groups % (1 << 20)) as usize)
    }

    /// Remembers the staged rows 0 … `rows` − 1 with finite values, in noise group
    /// `group`. When the memory is full, each replaces the point farthest from θ (by z).
    /// With `keep_batch` it replaces the farthest of the points that are neither this
    /// batch's nor θ's own draws, while there is one. A survey asks for that: it is the
    /// geometry a model is fitted from, n lines through θ, and a restart's, drawn at a σ
    /// far above the one the memory was filled at, lies farther out than every older
    /// point, so that each of its rows would evict the last (the first fit would see one
    /// of them), and where it fills the memory, θ's value, which alone tells the model's
    /// constant from its curvature on points all at one distance.
    fn remember(&mut self, rows: usize, group: T, keep_batch: bool) {
        let n = self.theta.len();
        let cap = if self.st.noisy {
            noisy_history_len(n)
        } else {
            history_len(n)
        };
        // A kept point's z is stored as −1 − z until the batch is in (and then
        // computed again: the round trip through −1 − z is not exact).
        let kept = |z: T| -T::ONE - z;
        if self.st.count + rows > cap {
            self.refresh_reach();
            if keep_batch {
                for z in self.mem.zs[..self.st.count].iter_mut() {
                    if *z == T::ZERO {
                        *z = kept(*z);
                    }
                }
            }
        }
        for row in 0..rows {
            let f = self.mem.stage_f[row];
            if !f.is_finite() {
                continue;
            }
            let slot = if self.st.count < cap {
                self.st.count += 1;
                self.st.count - 1
            } else {
                // The farthest point not kept, else the farthest kept one.
                let (mut free, mut held) = ((None, -T::ONE), (0, -T::ONE));
                for (k, &z) in self.mem.zs[..cap].iter().enumerate() {
                    if z >= T::ZERO {
                        if z > free.1 {
                            free = (Some(k), z);
                        }
                    } else if kept(z) > held.1 {
                        held = (k, kept(z));
                    }
                }
                free.0.unwrap_or(held.0)
            };
            self.mem.xs[slot * n..(slot + 1) * n]
                .copy_from_slice(&self.mem.stage[row * n..(row + 1) * n]);
            self.mem.fs[slot] = f;
            self.mem.gs[slot] = group;
            self.mem.credit[slot] = T::ONE;
            if self.reach_is_current() {
                let z = self.reach_of(slot);
                self.mem.zs[slot] = if keep_batch { kept(z) } else { z };
            }
        }
        if keep_batch && self.reach_is_current() {
            for k in 0..self.st.count {
                if self.mem.zs[k] < T::ZERO {
                    self.mem.zs[k] = self.reach_of(k);
                }
            }
        }
    }

    /// Whether [`Memory::zs`] holds the remembered points' z for the current θ, σ and
    /// metric.
    fn reach_is_current(&self) -> bool {
        self.st.reach_key == Some((self.st.sigma, self.st.metric_changes))
            && *self.mem.zt == *self.theta
    }

    /// Brings [`Memory::zs`] (z of remembered point k at index k) up to date, computing
    /// it afresh only when θ, σ or the metric changed since it was filled: most
    /// iterations ask several times (ties, spread, counts, the memory's replacements),
    /// each O(mn²) for a full metric.
    fn refresh_reach(&mut self) {
        if !self.reach_is_current() {
            for k in 0..self.st.count {
                self.mem.zs[k] = self.reach_of(k);
            }
            self.mem.zt.copy_from_slice(self.theta);
            self.st.reach_key = Some((self.st.sigma, self.st.metric_changes));
        }
    }

    /// z = ‖L⁻¹(x − θ)‖/(σ√n) of remembered point k.
    fn reach_of(&self, k: usize) -> T {
        let n = self.theta.len();
        let x = &self.mem.xs[k * n..(k + 1) * n];
        metric::whitened_distance(self.shape, self.mem.li, x, self.theta)
            / (self.st.sigma * T::from_usize(n).sqrt())
    }

    /// Remembered points within z.
    fn count_within(&mut self, z: T) -> usize {
        self.refresh_reach();
        self.mem.zs[..self.st.count]
            .iter()
            .filter(|&&r| r <= z)
            .count()
    }

    /// Remembered points within z that show the model θ's surroundings: on a noisy
    /// objective θ itself counts once, since it is drawn again beside every iteration's
    /// samples and those draws, each on a seed of its own, lie at θ. (Counted, they let
    /// σ shrink on a model that has seen no other point: on a local minimum in the box's
    /// corner, a run ended after a few evaluations.)
    fn count_around(&mut self, z: T) -> usize {
        let within = self.count_within(z);
        if !self.st.noisy {
            return within;
        }
        let at_theta = self.mem.zs[..self.st.count]
            .iter()
            .filter(|&&r| r == T::ZERO)
            .count();
        within - at_theta.saturating_sub(1)
    }

    /// Remembered points within z other than θ, and how many of them tie with f(θ);
    /// (0, 0) when f(θ) is unknown. Deterministic objectives only: a noisy one's values
    /// compare only within their noise group.
    fn ties_within(&mut self, z: T) -> (usize, usize) {
        let Some(v) = self.st.value else {
            return (0, 0);
        };
        self.refresh_reach();
        (0..self.st.count)
            .filter(|&k| {
                let reach = self.mem.zs[k];
                reach > T::ZERO && reach <= z
            })
            .fold((0, 0), |(near, ties), k| {
                (near + 1, ties + usize::from(ties_with(self.mem.fs[k], v)))
            })
    }

    /// max |f − f(θ)| over remembered points within z (0 when f(θ) is unknown); for a
    /// noisy objective the largest difference within a noise group, where values
    /// compare (max |f − f(θ)| where no group holds two such points).
    fn spread(&mut self, z: T) -> T {
        let Some(v) = self.st.value else {
            return T::ZERO;
        };
        self.refresh_reach();
        let near = |k: &usize| self.mem.zs[*k] <= z;
        if self.st.noisy {
            let within = (0..self.st.count).filter(near).fold(T::ZERO, |s, k| {
                (0..k)
                    .filter(|&j| self.mem.gs[j] == self.mem.gs[k])
                    .filter(near)
                    .fold(s, |s, j| s.max((self.mem.fs[k] - self.mem.fs[j]).abs()))
            });
            if within > T::ZERO {
                return within;
            }
        }
        (0..self.st.count)
            .filter(near)
            .fold(T::ZERO, |s, k| s.max((self.mem.fs[k] - v).abs()))
    }

    /// Fits the model around θ to the remembered points within 2ρ, values scaled by
    /// `scale`, from the prior moved to θ and σ. Returns the fit's noise level and the
    /// number of points fitted; `None` when the fit failed.
    fn fit(&mut self, value: T, scale: T) -> Option<(T, usize)> {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let shape = self.shape;
        let hl = shape.hessian_len(n);
        // The prior in standardised units: g = σLᵀ(g₀ + H₀(θ − c₀))/F, H = σ²LᵀH₀L/F.
        if self.st.has_prior {
            for i in 0..n {
                self.mem.s[i] = self.theta[i] - self.mem.c0[i];
            }
            shape.apply(self.mem.h0, self.mem.s, self.mem.rs);
            for i in 0..n {
                self.mem.rs[i] += self.mem.g0[i];
            }
            metric::apply_transposed(shape, self.mem.l, self.mem.rs, self.mem.g);
            for gi in self.mem.g.iter_mut() {
                *gi = sigma * *gi / scale;
            }
            metric::congruence(shape, self.mem.l, self.mem.h0, n, self.mem.a, self.mem.h);
            for k in 0..hl {
                self.mem.h[k] = sigma * sigma * self.mem.h[k] / scale;
            }
        } else {
            self.mem.g.fill(T::ZERO);
            self.mem.h.fill(T::ZERO);
        }
        let limit = T::from_f64(2.0 * REACH);
        let reach = T::from_f64(REACH);
        let mut m = 0;
        let root_n = T::from_usize(n).sqrt();
        // From BY_COLUMNS_MIN_DIM coordinates on, L⁻¹ and H by columns for the products
        // below (the same sums as by rows, in contiguous passes that vectorise); below
        // it the transposes cost more than they save.
        let by_columns = shape == Shape::Full && n >= BY_COLUMNS_MIN_DIM;
        if by_columns {
            transpose(self.mem.li, n, self.mem.a);
            transpose(self.mem.h, n, self.mem.v);
        }
        for k in 0..self.st.count {
            // Row m of u = L⁻¹(x − θ)/σ, kept if z = ‖u‖/√n is within the limit.
            let x = &self.mem.xs[k * n..(k + 1) * n];
            for ((ri, &xi), &ti) in self.mem.rs.iter_mut().zip(x).zip(self.theta.iter()) {
                *ri = (xi - ti) / sigma;
            }
            let row = &mut self.mem.u[m * n..(m + 1) * n];
            if by_columns {
                mat_vec_by_columns(self.mem.a, self.mem.rs, row);
            } else {
                metric::apply(shape, self.mem.li, self.mem.rs, row);
            }
            let z = norm(row) / root_n;
            if z > limit {
                continue;
            }
            let credit = self.mem.credit[k];
            if credit <= T::ZERO {
                continue;
            }
            let sw = (-(z / reach).sq() / T::from_f64(4.0)).exp() * credit.sqrt();
            let quadratic = if by_columns {
                Shape::half_quadratic_by_columns(self.mem.v, row, self.mem.lambda)
            } else {
                shape.half_quadratic(self.mem.h, row)
            };
            let prior = dot(self.mem.g, row) + quadratic;
            self.mem.sw[m] = sw;
            self.mem.gid[m] = self.mem.gs[k];
            self.mem.r[m] = sw * ((self.mem.fs[k] - value) / scale - prior);
            m += 1;
        }
        let ridge = self.ridge();
        model::fit(
            shape,
            n,
            m,
            self.mem.u,
            self.mem.sw,
            self.st.noisy.then_some(&self.mem.gid[..m]),
            self.mem.r,
            model::Scratch {
                gram: self.mem.gram,
                kp: self.mem.kp,
                schur: self.mem.schur,
                beta: self.mem.beta,
            },
            self.mem.g,
            self.mem.h,
            ridge,
        )
        .map(|noise| (noise, m))
    }

    /// The ridge of the next fit ([`Ridge`]); all but [`Ridge::Prior`] make the fit
    /// reproduce a quadratic where its points determine it, and a survey's pairs stay on
    /// their lines to let them. A full model's fits where the memory determines the model
    /// (n ≤ 14), and above that its first fit after a survey, which has no prior: the
    /// survey's pairs fix the model along their lines and the least change from zero
    /// fixes the rest, so that a round bowl's first model is exact at every n. Later fits
    /// of a full model above n = 14, and every fit of a diagonal one, lean on the prior
    /// they carry and keep its weakly determined part.
    fn ridge(&self) -> Ridge {
        if memory_determines_model(self.theta.len()) {
            Ridge::Determined
        } else if self.shape == Shape::Full && !self.st.has_prior {
            Ridge::Survey
        } else {
            Ridge::Prior
        }
    }

    /// −(gᵀs + ½sᵀHs) of the model for the step in `s` (standardised units).
    fn predicted_decrease(&self) -> T {
        -(dot(self.mem.g, self.mem.s) + self.shape.half_quadratic(self.mem.h, self.mem.s))
    }

    /// Keeps this iteration's model, in parameter units at θ, as the next prior.
    fn save_prior(&mut self, scale: T, sigma: T) {
        let n = self.theta.len();
        self.mem.c0.copy_from_slice(self.theta);
        // g₀ = F L⁻ᵀg/σ, H₀ = F L⁻ᵀHL⁻¹/σ².
        metric::apply_transposed(self.shape, self.mem.li, self.mem.g, self.mem.g0);
        for g0 in self.mem.g0.iter_mut() {
            *g0 = scale * *g0 / sigma;
        }
        metric::congruence(
            self.shape,
            self.mem.li,
            self.mem.h,
            n,
            self.mem.a,
            self.mem.h0,
        );
        for k in 0..self.shape.hessian_len(n) {
            self.mem.h0[k] = scale * self.mem.h0[k] / (sigma * sigma);
        }
        self.st.has_prior = true;
    }

    /// Whether f(θ) is below the best point's value, or θ is the best point. A gain made
    /// by a centre that a continuation move left above the best point resets the
    /// staleness count (the centre is still descending) but earns no further restart:
    /// it is no progress of the run.
    fn below_best(&self) -> bool {
        match (self.st.best_value, self.st.value) {
            (Some(b), Some(v)) => v < b,
            (Some(_), None) => false,
            (None, _) => true,
        }
    }

    /// Clears the continuation's record once θ is below the best point again.
    fn keep_best(&mut self) {
        if self.st.best_value.is_some() && self.below_best() {
            self.st.best_value = None;
        }
    }

    /// Moves θ back to the best point a continuation move left.
    fn restore_best(&mut self) {
        if let Some(b) = self.st.best_value.take() {
            self.theta.copy_from_slice(self.mem.best);
            self.st.value = Some(b);
        }
    }

    /// Moves θ to the best point of the earlier descents where that is at least as good
    /// as the current descent's.
    fn restore_record(&mut self) {
        if self.record_leads() {
            self.theta.copy_from_slice(self.mem.record);
            self.st.value = self.st.record;
        }
    }

    /// Restarts in a row without a gain, after the first such one, before the descent
    /// ends ([`AutoOptions::restarts`], or its default for this run).
    fn restarts(&self) -> usize {
        self.options.restarts.unwrap_or(if self.may_start_fresh() {
            RESTARTS_BEFORE_FRESH
        } else {
            RESTARTS
        })
    }

    /// Whether a descent that ended (converged, or stagnated after its restarts) is
    /// followed by a fresh one ([`AutoOptions::fresh_starts`]): the run has a budget
    /// and the objective is deterministic (values on different seeds, or draws of
    /// unseeded noise, would make one descent's best point incomparable with
    /// another's).
    fn may_start_fresh(&self) -> bool {
        self.options.fresh_starts
            && self.options.max_evaluations.is_some()
            && !self.st.noisy
            && !self.st.unseeded
    }

    /// Begins a new descent from a fresh start about the run's best point, as basin
    /// hopping does: each coordinate moved by its start scale times 2^(k mod
    /// [`RESTART_SCALES`]) times a standard normal draw for the k-th fresh start, and
    /// mirrored into the box. The best point so far is kept as the record; the memory,
    /// the model, the metric and σ start over as in [`Auto::new`].
    fn fresh_start(&mut self) {
        self.restore_best();
        self.restore_record();
        if let Some(v) = self.st.value {
            self.mem.record.copy_from_slice(self.theta);
            self.st.record = Some(v);
        }
        let n = self.theta.len();
        let widen = T::from_f64(libm::pow(2.0, f64::from(self.st.fresh % RESTART_SCALES)));
        self.st.fresh = self.st.fresh.wrapping_add(1);
        let least = self.least_start_scale();
        for i in 0..n {
            let spread = self.start_scale(i).max(least) * widen;
            let x = self.theta[i] + spread * normal::quantile(T::uniform_open(&mut self.rng));
            self.theta[i] = reflect(x, self.mem.lower[i], self.mem.upper[i]);
        }
        let run = self.st;
        self.st = State {
            iteration: run.iteration,
            evaluations: run.evaluations,
            bounded: run.bounded,
            noisy: run.noisy,
            // A descent may end held by noise: check again, as a restart does.
            checked: run.unseeded,
            unseeded: run.unseeded,
            dense: run.dense,
            voting: run.voting,
            groups: run.groups,
            metric_changes: run.metric_changes.wrapping_add(1),
            record: run.record,
            fresh: run.fresh,
            ..State::start(run.sigma0, n)
        };
        self.shape_scales();
        self.mem.path.fill(T::ZERO);
    }

    /// Starts over from the best point at `sigma` with the memory of points and the
    /// sampling metric, but without the model learnt at the scale the run had shrunk to.
    /// The metric is kept: it is a shape, not a scale, and the shape that a narrow valley
    /// or ridge taught is what the next descent along it needs.
    fn restart(&mut self, sigma: T) {
        self.restore_best();
        self.forget_scales();
        self.st.may_restart = false;
        self.st.stale = 0;
        self.st.sigma = sigma;
        self.st.survey = true;
        self.st.has_prior = false;
        // A run that ends its descent may have been held by noise: a lucky draw of
        // f(θ) that no later step can beat. Check, until noise is found.
        self.st.checked = self.st.unseeded;
    }

    /// The unseeded noise's scale: the median |f − f′| over pairs of remembered draws at
    /// one point (θ's, and earlier θ's), about its standard deviation for Gaussian
    /// noise and zero where most draws are exact (sparse outliers), with `sw` as scratch;
    /// `None` when the memory holds fewer than three such pairs (the median of two is
    /// their larger, which one outlier sets). O(m²n) for m remembered points.
    fn repeat_spread(&mut self) -> Option<T> {
        let pairs = self.repeat_differences();
        (pairs >= 3).then(|| lower_median(&self.mem.sw[..pairs]))
    }

    /// The scale of unseeded noise that every draw carries: [`Auto::repeat_spread`]
    /// where the check found the noise dense and no two remembered draws at one point
    /// agree exactly, `None` otherwise. Sparse outliers (most draws exact) have no such
    /// scale: their pairs' median is zero, or an outlier's where θ was drawn again
    /// because its draw was one, and a trial's shortfall measured against it says
    /// nothing of the step. O(m²n).
    fn dense_noise_scale(&mut self) -> Option<T> {
        if !self.st.dense {
            return None;
        }
        let pairs = self.repeat_differences();
        let exact = self.mem.sw[..pairs].contains(&T::ZERO);
        (pairs >= 3 && !exact).then(|| lower_median(&self.mem.sw[..pairs]))
    }

    /// The unseeded noise is sparse: outliers on values that are mostly exact — the
    /// check's three draws did not all differ, or two remembered draws at one point
    /// agree exactly. O(m²n) for m remembered points.
    fn sparse_noise(&mut self) -> bool {
        self.st.unseeded
            && (!self.st.dense || {
                let pairs = self.repeat_differences();
                self.mem.sw[..pairs].contains(&T::ZERO)
            })
    }

    /// Writes |f − f′| for every pair of remembered draws at one point to `sw` (as many
    /// as it holds) and returns how many it wrote.
    fn repeat_differences(&mut self) -> usize {
        let n = self.theta.len();
        let mut pairs = 0;
        for a in 0..self.st.count {
            let xa = &self.mem.xs[a * n..(a + 1) * n];
            for b in 0..a {
                if pairs < self.mem.sw.len() && *xa == self.mem.xs[b * n..(b + 1) * n] {
                    self.mem.sw[pairs] = (self.mem.fs[a] - self.mem.fs[b]).abs();
                    pairs += 1;
                }
            }
        }
        pairs
    }

    /// Copies the draws of f at θ the memory holds (its points equal to θ) to `sw`, the
    /// fit's scratch, and returns how many there are.
    fn draws_at_theta(&mut self) -> usize {
        let n = self.theta.len();
        let mut draws = 0;
        for k in 0..self.st.count {
            if self.mem.xs[k * n..(k + 1) * n] == *self.theta {
                self.mem.sw[draws] = self.mem.fs[k];
                draws += 1;
            }
        }
        draws
    }

    /// θ lies on a face of the box: some coordinate at its lower or upper bound.
    fn on_face(&self) -> bool {
        self.theta
            .iter()
            .zip(self.mem.lower.iter().zip(self.mem.upper.iter()))
            .any(|(&t, (&lo, &hi))| t <= lo || t >= hi)
    }

    /// Whether the run has stalled on a shape the metric has not learnt: no fit can be
    /// determined (a full model from n = 15), the last n model steps went unconfirmed,
    /// and the model's curvature in whitened coordinates is anisotropic — its largest
    /// |eigenvalue| at least [`STALLED_ANISOTROPY`] times the median one. O(n³), with
    /// the trust region's scratch (`a`, `v`, `lambda`).
    fn stalled_on_shape(&mut self) -> bool {
        let n = self.theta.len();
        if self.shape != Shape::Full || memory_determines_model(n) || self.st.unconfirmed < n {
            return false;
        }
        self.mem.a[..n * n].copy_from_slice(&self.mem.h[..n * n]);
        eigen::symmetric(self.mem.a, self.mem.v, n);
        for (m, &e) in self.mem.lambda[..n].iter_mut().zip(self.mem.a[..n].iter()) {
            *m = e.abs();
        }
        let top = self.mem.lambda[..n].iter().fold(T::ZERO, |t, &e| t.max(e));
        top > T::ZERO
            && top >= T::from_f64(STALLED_ANISOTROPY) * lower_median(&self.mem.lambda[..n])
    }

    /// Whether a survey may run along the parameter axes: the model is full and no two
    /// axes have a |cosine| above [`AXIS_COHERENCE`] in whitened coordinates, where
    /// (L⁻¹eₐ)·(L⁻¹e_b) = (C⁻¹)_ab. O(n³).
    fn axes_orthogonal(&self) -> bool {
        let n = self.theta.len();
        if self.shape != Shape::Full {
            return false;
        }
        let li = &*self.mem.li;
        let inverse =
            |a: usize, b: usize| (0..n).fold(T::ZERO, |s, i| s + li[i * n + a] * li[i * n + b]);
        let bound = T::from_f64(AXIS_COHERENCE * AXIS_COHERENCE);
        (0..n).all(|a| {
            let caa = inverse(a, a);
            (0..a).all(|b| inverse(a, b).sq() <= bound * caa * inverse(b, b))
        })
    }

    /// After a survey along the parameter axes (pair p along axis (`first_axis` + p)
    /// mod n, its halves in the staged rows after the `centre` rows): stretches the
    /// metric by [`FLAT_STRETCH`] along every axis both of whose halves tie with f(θ),
    /// where some other pair has neither half tie (f depends on that coordinate both
    /// ways: a fitted object, not a plateau whose target one half happens to reach).
    fn stretch_flat_axes(&mut self, first_axis: usize, pairs: usize, centre: usize) {
        let n = self.theta.len();
        let Some(v) = self.st.value else {
            return;
        };
        let factors = &mut self.mem.gx[..n];
        factors.fill(T::ONE);
        let (mut flat, mut moving) = (0, 0);
        for p in 0..pairs {
            let halves = &self.mem.stage_f[centre + 2 * p..centre + 2 * p + 2];
            if halves.iter().all(|&f| ties_with(f, v)) {
                factors[(first_axis + p) % n] = T::from_f64(FLAT_STRETCH);
                flat += 1;
            } else if !halves.iter().any(|&f| ties_with(f, v)) {
                moving += 1;
            }
        }
        if flat == 0 || moving == 0 {
            return;
        }
        self.st.metric_changes = self.st.metric_changes.wrapping_add(1);
        metric::stretch(
            self.mem.c,
            self.mem.l,
            self.mem.li,
            factors,
            self.mem.a,
            self.mem.v,
        );
    }

    /// Whether an accepted step teaches the metric its direction ([`Auto::follow_path`]):
    /// a full model on a deterministic objective that has shown neither ties nor
    /// roughness since the last restart. (On a lattice, or where f is rough at some
    /// scale, steps go where the cells or wells let them, not along a valley: on the
    /// step ellipsoid and on Rastrigin the path cost runs.)
    fn follows_path(&self) -> bool {
        self.shape == Shape::Full
            && !self.st.noisy
            && !self.st.unseeded
            && !self.st.lattice
            && self.st.tie_scale <= T::ZERO
            && self.st.rough_scale <= T::ZERO
    }

    /// CMA-ES's rank-one update from the evolution path of θ's accepted steps, made
    /// before this iteration at σ = `sigma` (θ moved from `tmp`): with y = (θ − θ_old)/σ,
    ///
    /// p ← (1 − c_c)p + √(c_c(2 − c_c))·y,  C ← (1 − c₁)C + c₁ppᵀ (then det C = 1),
    ///
    /// c_c = 4/(n + 4), c₁ = 2/((n + 1.3)² + 1), CMA-ES's defaults for a single parent.
    /// Steps that zig-zag across a valley cancel in p while their progress along it adds
    /// up, so C stretches along the valley's floor however precisely that direction must
    /// be known — more precisely than a fitted curvature's eigenvectors tell it on a
    /// sharp ridge, whose cone is no quadratic.
    fn follow_path(&mut self, sigma: T) {
        let n = self.theta.len();
        let dims = n as f64;
        let cc = 4.0 / (dims + 4.0);
        let c1 = 2.0 / ((dims + 1.3) * (dims + 1.3) + 1.0);
        let keep = T::from_f64(1.0 - cc);
        let push = T::from_f64((cc * (2.0 - cc)).sqrt());
        for i in 0..n {
            let y = (self.theta[i] - self.mem.tmp[i]) / sigma;
            self.mem.path[i] = keep * self.mem.path[i] + push * y;
        }
        self.st.metric_changes = self.st.metric_changes.wrapping_add(1);
        metric::rank_one(
            self.mem.c,
            self.mem.l,
            self.mem.li,
            self.mem.path,
            c1,
            self.mem.a,
            self.mem.v,
        );
    }

    /// Moves the sampling metric towards the shape of the prior's curvature H₀ by
    /// `weight` of the metric's rate.
    fn learn_metric(&mut self, weight: f64) {
        let n = self.theta.len();
        self.st.metric_changes = self.st.metric_changes.wrapping_add(1);
        metric::update(
            self.shape,
            self.mem.c,
            self.mem.l,
            self.mem.li,
            self.mem.h0,
            n,
            weight,
            metric::Scratch {
                a: self.mem.a,
                v: self.mem.v,
                w: self.mem.lambda,
            },
        );
    }
}

/// Evaluates `points` (rows of `points.len() / seeds.len()` floats), one per seed, into
/// `out`, and counts them in `evaluations` and `spent`; [`Error::Cancelled`] when the
/// objective asks to stop after the batch.
fn draw<T: Real, O: Objective<T> + ?Sized>(
    objective: &mut O,
    points: &[T],
    seeds: &[NoiseSeed],
    out: &mut [T],
    evaluations: &mut usize,
    spent: &mut usize,
) -> Result<(), Error> {
    let n = points.len() / seeds.len().max(1);
    objective.evaluate_batch(&Batch::new(points, seeds, n)?, out);
    *evaluations += seeds.len();
    *spent += seeds.len();
    if objective.cancelled() {
        return Err(Error::Cancelled);
    }
    Ok(())
}

/// The element of rank ⌊len/2⌋ (from 0) of `xs` in ascending order, by counting: O(len²)
/// comparisons, where the standard library's selection would cost kilobytes of code on a
/// microcontroller and saves nothing next to the fit's O(m³). `T::MAX` when no element
/// has that rank (NaN among them).
fn lower_median<T: Real>(xs: &[T]) -> T {
    let middle = xs.len() / 2;
    for &x in xs {
        let below = xs.iter().filter(|&&y| y < x).count();
        let at_most = xs.iter().filter(|&&y| y <= x).count();
        if below <= middle && middle < at_most {
            return x;
        }
    }
    T::MAX
}

/// Whether row k is the first of its chunk with its draw (`Auto::distinct_rows`): not a
/// repeat.
fn first_draw(draws: &[u8; CHUNK], k: usize) -> bool {
    !draws[..k].contains(&draws[k])
}

/// Swaps rows a < b (n floats each) of `rows`.
fn swap_rows<T>(rows: &mut [T], n: usize, a: usize, b: usize) {
    let (head, tail) = rows.split_at_mut(b * n);
    head[a * n..(a + 1) * n].swap_with_slice(&mut tail[..n]);
}

/// a and b are one point up to rounding: every coordinate equal to within 8 ulps (a
/// pair's halves folded by the box onto one point differ by the rounding of their
/// mirroring).
fn same_point<T: Real>(a: &[T], b: &[T]) -> bool {
    a.iter()
        .zip(b)
        .all(|(&x, &y)| (x - y).abs() <= T::from_f64(8.0) * T::EPSILON * x.abs().max(y.abs()))
}

/// f ties with v: equal to within 16 ulps of v (a smooth f almost never does).
fn ties_with<T: Real>(f: T, v: T) -> bool {
    (f - v).abs() <= T::from_f64(16.0) * T::EPSILON * v.abs()
}

/// The largest t ≥ 0 with θ + t·sign·d inside [lower, upper] (`T::MAX` where d never
/// leaves it), for θ inside the box.
fn room_along<T: Real>(theta: &[T], d: &[T], sign: T, lower: &[T], upper: &[T]) -> T {
    let mut room = T::MAX;
    for i in 0..theta.len() {
        let step = sign * d[i];
        let limit = if step > T::ZERO {
            (upper[i] - theta[i]) / step
        } else if step < T::ZERO {
            (lower[i] - theta[i]) / step
        } else {
            continue;
        };
        room = room.min(limit.max(T::ZERO));
    }
    room
}

/// x mirrored into [lower, upper] at the bounds it crosses (clamped after a few
/// reflections, for a point many box widths out). A sample is reflected rather than
/// clamped: clamping piles samples on the box's faces, where f is constant along every
/// clamped coordinate, so a wide survey of a bounded problem would learn nothing there.
fn reflect<T: Real>(mut x: T, lower: T, upper: T) -> T {
    for _ in 0..4 {
        if x > upper {
            x = upper - (x - upper);
        } else if x < lower {
            x = lower + (lower - x);
        } else {
            return x;
        }
    }
    x.max(lower).min(upper)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lower median is the order statistic that a full sort puts at ⌊len/2⌋, ties and
    /// all; a NaN among the values leaves it undefined (T::MAX).
    #[test]
    fn lower_median_is_the_middle_order_statistic() {
        assert_eq!(lower_median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(lower_median(&[4.0, 1.0, 3.0, 2.0]), 3.0);
        assert_eq!(lower_median(&[5.0, 5.0, 1.0, 5.0]), 5.0);
        assert_eq!(lower_median(&[7.0]), 7.0);
        let mut xs = [0.0f64; 101];
        for (k, x) in xs.iter_mut().enumerate() {
            *x = ((k * 37) % 101) as f64;
        }
        assert_eq!(lower_median(&xs), 50.0);
        assert_eq!(lower_median(&[f64::NAN, 1.0]), f64::MAX);
    }

    /// The room along a line is set by the first face it meets, on either side of θ.
    #[test]
    fn room_along_a_line_ends_at_the_first_face() {
        let (lower, upper) = ([0.0, -1.0], [4.0, 1.0]);
        let theta = [1.0, 0.0];
        let d = [0.6, 0.8];
        // +d meets y = 1 at t = 1.25 before x = 4 at t = 5; −d meets y = −1 at t = 1.25
        // and x = 0 at t = 1/0.6.
        assert_eq!(room_along(&theta, &d, 1.0, &lower, &upper), 1.25);
        assert_eq!(room_along(&theta, &d, -1.0, &lower, &upper), 1.25);
        let along_x = [1.0, 0.0];
        assert_eq!(room_along(&theta, &along_x, 1.0, &lower, &upper), 3.0);
        assert_eq!(room_along(&theta, &along_x, -1.0, &lower, &upper), 1.0);
    }

    /// On a face, the room towards it is 0; without bounds (±T::MAX), it is T::MAX.
    #[test]
    fn room_on_a_face_and_without_bounds() {
        let (lower, upper) = ([0.0, 0.0], [1.0, 1.0]);
        assert_eq!(
            room_along(&[0.0, 0.5], &[1.0, 0.0], -1.0, &lower, &upper),
            0.0
        );
        let (lower, upper) = ([-f64::MAX; 2], [f64::MAX; 2]);
        assert_eq!(
            room_along(&[3.0, -2.0], &[0.6, -0.8], 1.0, &lower, &upper),
            f64::MAX
        );
    }
}
