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
//!   within 2ρ (ρ = [`REACH`]), weighted by w = exp(−½(z/b)²), z = ‖L⁻¹(x − θ)‖/(σ√n),
//!   b = 1 where the memory determines the model and b = ρ above ([`FIT_WIDTH`]), by ridge
//!   regression towards the previous iteration's model (the
//!   `model` module; from zero instead where that model misses the points by far more
//!   than their own spread, as one fitted to a wall that σ has since shrunk past does):
//!   an overdetermined fit averages the points over a Gaussian of width
//!   ~σ, as hodr's estimators average samples, so the model is that of the *smoothed*
//!   objective; an underdetermined one changes the curvature least, as Powell's NEWUOA
//!   does, so curvature learnt earlier is kept.
//!   A full Hessian is modelled for n ≤ [`FULL_MODEL_MAX_DIM`], a diagonal one above
//!   and, from n = 15, where the first step finds f separable ([`AutoModel`]);
//!   the memory holds at most [`MAX_MEMORY`] points, or [`FULL_MEMORY_PER_DIM`]·n for a
//!   full model where that is more, so that an iteration's cost is bounded for a full
//!   model and linear in n for a diagonal one (the `model` module says how a fit with
//!   fewer points than coefficients learns).
//! * **Samples.** Where fewer than n + 1 remembered points (or half the memory, if
//!   smaller) lie within z ≤ ρ, the iteration evaluates antithetic pairs θ ± σ√n·b along
//!   Lb, b the columns of a random orthonormal frame (n pairs, or half the memory's
//!   worth, and θ on the first iteration). A model that puts its minimum at θ halves
//!   σ (k times at its k-th such confirmation in a row, up to [`SETTLED_HALVINGS`],
//!   where the model of the scale above predicted the points drawn since to
//!   [`SETTLED_FIT`]) only once more than 2q − 2 remembered points lie within reach, q
//!   the count above; short of that, the next iteration draws the pairs it lacks in one batch
//!   (one pair per iteration on a declared-noisy objective): one fit instead of one per
//!   pair, and a batch the caller can evaluate in parallel. A fit whose prior (the
//!   last model, moved to θ and σ) already predicts every point to rounding
//!   ([`EXACT`]) keeps it and solves no system: on a quadratic, the confirmations of
//!   its minimum at each smaller σ are such fits. A restart's survey of a
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
//!   model step after each restart (until noise is found), and in the first descent at
//!   the model step after the first step on a rough fit that falls short, θ is
//!   evaluated once more, unremembered. Where the two values differ, the objective
//!   draws fresh noise at every call — a renderer whose seed is not passed on — and a lucky draw of f(θ)
//!   rejects every later step, which is how such a descent ends; a third draw then
//!   tells noise that every draw carries (all three differ) from sparse outliers on
//!   exact values, and only the former's rejections within the noise keep σ (below).
//!   From then on the fit gives each point a robustness weight, Tukey's biweight of its
//!   residual (one step of iteratively reweighted least squares per iteration), so
//!   that an outlier — a Cauchy noise spike — loses its pull; where θ's own draw is
//!   such an outlier, θ is drawn again; and after a rejected trial, where θ's draw lies
//!   below the robust fit, θ is drawn again beside the next one (until
//!   [`THETA_DRAWS`] draws), trials being compared with the median of θ's draws, so
//!   that a draw from the noise's low tail cannot hold θ by itself; nor can it move θ:
//!   where every draw is noisy, a sample takes θ's place only when lower by more than
//!   the noise's scale. Nor does a lucky draw count as a lower f(θ) for the patience
//!   of a run without a budget: where every draw is noisy, a gain must lie below both
//!   f(θ)'s draw and the lowest draw that counted before by more than the last fit's
//!   residual scatter
//!   (`Auto::clears_noise`), so that a descent whose θ wanders within the noise about
//!   the minimum stagnates. Where the noise is flat, of one scale wherever θ lies (θ's
//!   pairs of draws differ by as much as the fit's points scatter, and by no more at
//!   the descent's higher values: `Auto::flat_noise`), model steps stay within
//!   0.3·σ√n, well inside the points the fit averages over, and a trial the noise could
//!   have rejected widens σ whatever it promised. Sparse outliers
//!   (the check's draws did not all differ, or two remembered draws at one point
//!   agree) are voted out instead: from then on every point is drawn until two of its
//!   draws agree exactly (at most [`VOTES`] draws, else their median), which costs
//!   about 2/(1 − p) evaluations per point for an outlier rate p; the voted values are
//!   exact, so the rules kept for deterministic objectives (continuation, the metric
//!   from determined fits) apply to them too. Without the vote a model fitted to fewer
//!   points than it has coefficients interpolates the outliers, which no residual then
//!   exposes, and predicts steps from them.
//! * **Step.** The model's minimiser within ‖s‖ ≤ σ√n (0.3·σ√n on flat noise; the
//!   `trust` module: exact for indefinite H, so a non-PSD model steps along its
//!   negative curvature) is evaluated;
//!   where it would leave the box, the coordinates it carries out are held on the
//!   bounds they cross and the model is minimised again over the rest of the region. It
//!   replaces θ when f is no higher there on common noise (a tie moves to the smoothed
//!   model's minimum of a flat piece of f); on unseeded noise that every draw carries,
//!   only when it is lower by a tenth of the decrease the model predicted (ρ̂ ≥ 0.1). A
//!   sample lower than f(θ) on its seed replaces θ too.
//! * **σ is the trust radius** and follows the ratio ρ̂ of actual to predicted decrease:
//!   ρ̂ ≥ 0.7 with a step to the boundary doubles σ; on a deterministic objective, a step
//!   to the boundary that lowered f with ρ̂ < 0.1 grows σ by 2^¼ (the model overstated
//!   the decrease — a kink or a ridge that its fit smooths over, which a smaller σ fits
//!   no better — but not the direction); a step shorter than half the radius
//!   shrinks σ towards twice its length (at most halving it); ρ̂ < 0.1 shrinks σ by
//!   [`SHRINK`] (halves it on a declared-noisy objective) — unless
//!   the points within reach do not determine the model (no more of them than it has
//!   coefficients, for n ≤ 14; above, at most 2n, or all but two of a full memory, for
//!   the diagonal model, and for the full one 2n doubled for each shortfall blamed on
//!   σ since the model last proved right, up to all but n + 1 of its memory), so
//!   that it rests on its prior or on points from wider scales, where a kink's
//!   smoothed curvature is flatter (a cone's falls as 1/σ) and the model would
//!   mispredict alike at every smaller σ (on a declared-noisy objective: at most 2n
//!   within reach and no more points fitted than coefficients; but in the first descent
//!   before the run's first gain, on a deterministic objective, a rejected step to the
//!   boundary shrinks σ however few points lie within reach: every point so far saw f
//!   at σ₀'s scale, and where σ₀ overstates the scale at which f is a quadratic each
//!   step extrapolates to the boundary and fails) — or, on an unseeded
//!   objective whose draws never agree exactly, the trial fell short by less than
//!   [`NOISE_MARGIN`] times the noise's scale (below): then σ stays, and the next fit
//!   takes in the trial, which lies where the model erred, as Powell's methods take in
//!   each trial; a pair is drawn at the same σ too on a lattice, a noisy objective, or
//!   where such pairs have lowered f(θ) often enough ([`PAIRS_PAY`])), or the fit
//!   finds f rough at this scale (residual scatter above [`ROUGH`] of the values'
//!   spread) and the trial lies within twice that scatter, or
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
//!   objective; or σ below what f's arithmetic resolves at θ, or the model's promised
//!   decrease below what it resolves of f(θ), [`UNRESOLVED_FITS`], or samples that tie
//!   with f(θ) by rounding alone at a minimum the model confirmed, or values that
//!   settle: a window of [`CREEP_WINDOWS`]·patience iterations that lowers f(θ) by at
//!   most ε of the descent's fall, as along an asymptote to an infimum at infinity; ε
//!   is T's, or f32's where f's values show single precision, `Auto::grain`), or after
//!   [`AutoOptions::patience`] iterations without a lower f(θ) (in the first descent
//!   before its first gain, on a deterministic objective, without a rejected step to the
//!   trust region's boundary that took σ to a new low either: there σ₀ overstates the
//!   scale, and σ is still shrinking to it), or once it creeps (a window of
//!   [`CREEP_WINDOWS`]·patience iterations that follows another, both without
//!   a confirmed model step or σ converging, and lowers f(θ) by at most [`CREEP_GAIN`]
//!   of the descent's fall and by more than half the window before), the run restarts from
//!   the best point with a survey of pairs, as the first iteration's, at the next scale of the cycle σ₀, 2σ₀,
//!   …, [`PLATEAU_WIDTH`]·σ₀, σ₀, … (wider scales average over more of the basin that
//!   held it; a gain does not send the next restart back to σ₀, since on a lattice of
//!   small steps some gain is always found there); after [`AutoOptions::restarts`]
//!   restarts in a row without a gain its descent ends, converged or stagnated. Where
//!   no fresh start follows (below), a restart's gains count only once they have moved
//!   the best point, summed over the gains, by the tolerance in some coordinate (in
//!   units of its start scale) and lowered it by more than ε of the descent's fall: a
//!   restart that lowers f by moving θ less than the caller asked to resolve has found
//!   the descent's own minimum again, and one that lowers it by less than the values
//!   register has only gone farther along an asymptote.
//! * **Fresh starts.** A run with a budget on a deterministic objective then starts a
//!   new descent about its best point (about x₀ while no value has been finite), as
//!   basin hopping does ([`AutoOptions::fresh_starts`]): each coordinate moves by its
//!   start scale times 2^(k mod 5) times a normal draw at the k-th fresh start (at
//!   the widest, k mod 5 = 4, by at least its side of the box, so that a σ₀ stated
//!   far narrower than the bounds still lets the run look beyond the start's basins),
//!   mirrored into the box; the memory, model and metric start over, and σ starts at
//!   that restart's scale σ₀·2^(k mod 5), continuation allowed, so that successive
//!   descents look at ever wider smoothings, as IPOP-CMA-ES's growing populations
//!   average over ever more of a multi-modal surface — until the run shows that a wide
//!   look adds nothing: a probe (below) has found a point below the best (the run's
//!   local minima are one object wrong, which the probes fix), or two wide descents in
//!   a row ended on the same value to √ε (the smoothed objective leads to one point,
//!   which is then known). Its later fresh descents begin at σ₀. A
//!   descent's end is as likely a local minimum (a disc hidden under another, a
//!   lattice cell beside the optimum's) as the global one, and nothing in the values
//!   tells which; the budget says how
//!   much more the caller will spend to find out. A later descent whose close, confirmed
//!   model puts its basin's bottom above the best point of the earlier ones ends there,
//!   unpolished ([`HOPELESS_FITS`]). [`Auto::theta`] is the best point of all descents.
//!   Without a budget, or on a noisy objective, the run ends with its first descent.
//!   Without a budget it also ends once it has used [`unbudgeted_cap`]`(n)`
//!   evaluations ([`AutoTermination::EvaluationCap`]), as pycma's default `maxiter`
//!   ends its runs: an infimum approached ever more slowly at infinity
//!   (1/(1 + |x₀|) + …) would otherwise hold a call forever.
//! * **Probes.** Before each fresh start, up to [`AutoOptions::probes`] points per
//!   coordinate ([`AutoStep::Probed`], n per iteration), each the best point with one
//!   contiguous block of 1, 2, 4, … ≤ n/2 coordinates moved: uniformly over the box
//!   (within 32 start scales, or at k = 4 anywhere in it) where a coordinate has one,
//!   else by its start scale times 2^k·N(0, 1), k uniform over 0 … 4 (the `probe`
//!   module). The first batch with a
//!   point below the best starts the next descent there. A descent that ends with one
//!   object wrong and the rest right — a shape hidden under another or stranded off its
//!   target, one coordinate in the wrong cell of a lattice — is left by moving that
//!   object's parameters alone, and its value says so at once; a fresh start moves them
//!   all and loses what was right. Where the run's probes have found lower points more
//!   often than its fresh descents, each later phase is longer, up to [`SHARE_RANGE`]
//!   times the default (the `explore` module).
//! * **Centre.** A descent that ends on a flat piece of f (a remembered point other than
//!   θ has exactly f(θ)'s value, f(θ) below every earlier descent's) spends one
//!   more iteration ([`AutoStep::Centred`]) moving θ to the piece's centre along the
//!   parameter axes (the `centre` module; [`AutoOptions::centre`]): a rasteriser
//!   without anti-aliasing, or rounded coordinates, leaves θ anywhere within a pixel's
//!   or a cell's width of the truth, and the centre is where the smoothed objective's
//!   minimum tends as σ → 0. The centre is the run's answer; fresh starts still jump
//!   about where the descent left θ. A probe below f(θ) instead moves θ there and
//!   restarts the descent.
//! * **Continuation.** At such a restart, or in a fresh start's descent, while σ >
//!   [`CONTINUATION_SCALE`]·σ₀, a
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
//! O(kn) for the k-th pair of a sampling frame (O(n³) per n pairs).
//!
//! This module holds the run itself (an iteration: [`Auto::step`], and when it ends);
//! its parts: `memory` (the buffer's regions and the remembered points), `sampling` (an
//! iteration's points and their evaluation), `model_step` (fit, step, trial and the
//! ratio test that judges it), `fitting` (which points a fit uses, its prior and
//! ridge), `model` (the quadratic fit's regression), `step` and `trust` (the
//! trust-region step inside the box), `metric`, `eigen` and
//! `adapt_metric` (the sampling metric and how it learns), `restart` (σ's control,
//! restarts and fresh starts), `probe` (the probes before a fresh start), `centre` (a
//! flat minimum's centre), `noise` (undeclared noise), `separable` (the test that picks
//! the diagonal model for a separable f), `options` (the public types) and `fixed`
//! ([`FixedAuto`]).

mod adapt_metric;
mod centre;
mod creep;
mod eigen;
mod explore;
mod failures;
mod fitting;
mod fixed;
mod memory;
mod metric;
mod model;
mod model_step;
mod noise;
mod options;
mod probe;
mod restart;
mod sampling;
mod separable;
mod step;
mod trust;

use centre::Centring;
use creep::Creep;
pub use creep::{CREEP_GAIN, CREEP_SHRINK, CREEP_WINDOWS};
use explore::Exploration;
pub use explore::SHARE_RANGE;
use failures::Failures;
pub use fixed::FixedAuto;
pub use memory::buffer_len;
use memory::{Memory, buffer_len_of, carve, history_len, memory_determines_model};
pub use options::{AutoModel, AutoOptions, AutoReport, AutoStep, AutoTermination, NonFinite};

use core::fmt;

use rand_core::Rng;

use crate::error::Error;
use crate::objective::{NoiseSeed, Objective};
use crate::optim::vector::distance;
use crate::real::Real;
use model::Shape;

/// Largest n for which the model has a full Hessian and C a full shape; above it, both
/// are diagonal (2n + 1 coefficients instead of (n+1)(n+2)/2). Only a full model and
/// metric represent a valley that runs along no parameter axis (a rotated one, the
/// common case); a diagonal one learns per-coordinate scales from far fewer points, but
/// no rotation: on a smooth f whose parameters are coupled (neighbours through a
/// smoothness term, or all of them through a rotation) a diagonal model converges only
/// as a Jacobi iteration on f's Hessian does. The bound is the full model's cost, per
/// iteration O(m²n + m³) for its fit to m = [`FULL_MEMORY_PER_DIM`]·n remembered points
/// and O(mn² + n³) for their whitening and the trust step's and the metric's
/// eigen-decompositions, O(n³) in all; its buffer ([`buffer_len`]), dominated by the
/// fit's m×m system, grows as n² (1 789 307 floats, about 14 MB of f64, at n = 127),
/// where the diagonal model's memory is bounded by [`MAX_MEMORY`].
pub const FULL_MODEL_MAX_DIM: usize = 127;

/// Most points Auto remembers with a diagonal model, and with a full one up to n = 16
/// (where [`FULL_MEMORY_PER_DIM`]·n is less): it reaches this for n ≥ 10 with a full
/// model — n ≥ 14 on a declared-noisy objective — and always with a diagonal one. A fit
/// costs O(m²n + m³) per iteration for m remembered points, so the bound keeps a diagonal
/// model's cost linear in n; with fewer points than the model's coefficients the fit
/// corrects the model carried from earlier iterations along the directions of the recent
/// points.
pub const MAX_MEMORY: usize = 128;

/// Points per coordinate a full model remembers at least, where [`MAX_MEMORY`] is fewer
/// (n ≥ 17; still fewer than its (n+1)(n+2)/2 coefficients, so no fit is determined
/// from n = 15 on). Each fit corrects the curvature carried from earlier fits along the
/// directions its points span; with a memory that does not grow with n those are ever
/// fewer of the n directions, and a descent along a curved valley outruns what the
/// model has learnt.
pub const FULL_MEMORY_PER_DIM: usize = 8;

/// Default of [`AutoOptions::probes`]: probes per coordinate before each fresh start.
pub const PROBES: usize = 20;

/// σ/σ₀ above which a restart follows the smoothed model past a rejected trial
/// ([`AutoStep::Continued`]).
pub const CONTINUATION_SCALE: f64 = 1.5;

/// ρ: the kernel's reach in units of σ√n (the distance of a fresh sample). Points with
/// z ≤ ρ count as nearby; points with z ≤ 2ρ are fitted ([`FIT_WIDTH`]).
pub const REACH: f64 = 2.0;

/// The width of the fit's weights in units of σ√n where the memory determines the model
/// (a full model, n ≤ 14): a point at z enters the fit with weight
/// w = exp(−½(z/FIT_WIDTH)²), from 1 at θ through e^(−½) at a fresh sample's distance to
/// e⁻⁸ at the fit's limit 2ρ. Points left by wider scales (z of 2–4 after σ has shrunk)
/// show f's shape there, which a quadratic at σ need not share, and the nearer points
/// determine the model without them. Where the memory cannot determine it, each fit
/// leans on its prior for what its points leave open, and the width is ρ (w ≥ e⁻² within
/// 2ρ): a far point the fit gives up is a constraint the older prior fills instead.
pub const FIT_WIDTH: f64 = 1.0;

/// How often an exploring pair drawn after a failed model step must lower f(θ) for the
/// next such failure to draw one. Below it, a failure draws none (up to
/// [`PAIRS_SKIPPED`] in a row): the next fit takes in the failed trial, the point where
/// the model erred, as Powell's methods take in each trial, so that a failure costs one
/// evaluation instead of three. Where the steps fail because no quadratic follows f at
/// this scale (the kinks of an attractive sector), the pairs often lower θ: they search
/// as CMA-ES's samples do. Where the model merely lacks points (a smooth f in many
/// dimensions, fitted with fewer points than coefficients), they seldom do.
pub const PAIRS_PAY: f64 = 0.1;

/// The weight of each exploring pair's outcome in the rate of [`PAIRS_PAY`] is
/// 1/`PAIR_MEMORY`.
pub const PAIR_MEMORY: f64 = 8.0;

/// The rate of [`PAIRS_PAY`] at a descent's start: twice the bar, so that a descent
/// draws pairs after its failed steps until about six have failed to lower f(θ).
pub const PAIR_RATE_START: f64 = 2.0 * PAIRS_PAY;

/// Failed model steps in a row that draw no exploring pair at most ([`PAIRS_PAY`]): the
/// next draws one, whose outcome keeps the rate current.
pub const PAIRS_SKIPPED: usize = 3;

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

/// σ/σ₀ up to which a plateau widens σ while no value of the run has differed from f(θ)
/// (in place of [`PLATEAU_WIDTH`]): 2⁴⁰ ≈ 10¹², so that σ₀ may understate the scale at
/// which f's values change at all by as much as the σ range the stability suite covers.
pub const UNVARIED_WIDTH: f64 = 1_099_511_627_776.0;

/// A coordinate's spread relative to its start, σ√Cᵢᵢ/sᵢ, past which the run ends
/// [`AutoTermination::Diverged`]: 2⁶⁴ ≈ 1.8·10¹⁹ (pycma's `tolupsigma` is 10²⁰). A trust
/// region grows that far only while every step gains: an objective without a minimum
/// (f = x) or a σ₀ that understates the problem's scale by as much.
pub const DIVERGENCE_WIDTH: f64 = 18_446_744_073_709_551_616.0;

/// Evaluations per (n + 3)² after which a run without a budget ends
/// ([`unbudgeted_cap`]).
pub const UNBUDGETED_EVALUATIONS: usize = 1000;

/// Evaluations after which a run in dimension n without a budget
/// ([`AutoOptions::max_evaluations`] `None`) ends, [`AutoTermination::EvaluationCap`]:
/// [`UNBUDGETED_EVALUATIONS`]·(n + 3)² (25 000 at n = 2, 529 000 at n = 20), at the end
/// of the iteration that reaches it. pycma's default `maxiter`, 100 + 150(n + 3)²/√λ
/// iterations of λ evaluations, grows with n alike. A run that should go on longer
/// states a budget, with [`AutoOptions::fresh_starts`] off for one descent.
pub const fn unbudgeted_cap(n: usize) -> usize {
    UNBUDGETED_EVALUATIONS.saturating_mul((n + 3).saturating_mul(n + 3))
}

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

/// The most halvings of σ one validated model minimum makes. Where a model validated by
/// its points puts its minimum at θ on a deterministic objective for the k-th time in a
/// row, each time having predicted the points drawn since the fit before to
/// [`SETTLED_FIT`], σ halves min(k, `SETTLED_HALVINGS`) times (a confirmation that drew
/// no new points neither counts nor breaks the row; one whose prior mispredicted them
/// ends it). A quadratic confirmed at one scale is confirmed at every smaller one, and
/// halving once per validating survey spends a survey per factor 2 on the way to the
/// tolerance. A model wrong below the scale it was confirmed at shows it at the next
/// one, whose step, tie or misfit ends the row.
pub const SETTLED_HALVINGS: u32 = 4;

/// The largest misfit of a confirmed model on the points of the next scale, as a
/// fraction of their spread about f(θ), for a confirmation there to count towards
/// [`SETTLED_HALVINGS`]: the model of the scale above predicted the points at this one.
/// A smooth f's misfit about its quadratic falls with σ; a piecewise-constant one's does
/// not fall below its steps'.
pub const SETTLED_FIT: f64 = 1e-3;

/// How closely a fit's prior (the last model, moved to θ and σ) must predict the points
/// for the fit to keep it as it is: a weighted RMS misfit of at most this fraction of
/// theirs about f(θ) (the flat model's). That is rounding's level for f64, on a
/// deterministic objective that is a quadratic over the points' span (f32's rounding
/// never reaches it): a regression could change such a prior by no more, and its
/// O(m²n + m³) system is not solved. It is what a confirmation of a quadratic's minimum
/// at each smaller σ finds. A looser bound (10⁻⁶) changed the runs: a model within 10⁻⁶
/// of the spread of values that span 10⁴ is not exact enough to step to 10⁻⁸.
pub const EXACT: f64 = 1e-10;

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

/// σ/σ₀ beyond which a confirmed step to the trust boundary no longer widens σ: none.
/// A run of confirmed steps to the boundary is evidence that σ₀ understated the distance
/// to go (σ₀ = 10⁻¹² for a minimum a unit away), so σ grows as CMA-ES's step size
/// does on a slope, bounded only by the box and [`Auto::max_scale`].
const GROWTH_WIDTH: f64 = f64::INFINITY;

/// The fraction of the metric's rate at which a model moves it when its points
/// determine it (more fitted points than coefficients, residual scatter within
/// [`SMOOTH`], no samples tied since f(θ) last fell, θ on no face of the box) but its
/// step did not confirm it (ρ̂ < 0.1 or rejected), on a deterministic objective. A
/// confirmed step moves it at the full rate. Models that stall a run where no fit is
/// determined move it at the same weight ([`STALLED_ANISOTROPY`]).
pub const DETERMINED_METRIC_WEIGHT: f64 = 0.3;

/// Where no fit can be determined (a full model from n = 15, whose remembered points are
/// fewer than its coefficients), confirmed steps are the metric's only teacher, and
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

/// Model steps in a row after which a later descent counts as converged because its
/// basin is worse than the best point of the earlier ones: each step's fit close
/// (noise ≤ [`SMOOTH`]) and determined or validated, the model step before it confirmed
/// (accepted with ρ̂ ≥ 0.1: along a ridge, whose rejected steps predict little and still
/// progress, the quadratic does not say where the basin's bottom lies), its minimum
/// inside the trust region (the step interior), and its predicted decrease to that
/// minimum under half of f(θ) − f(record). Polishing such a basin cannot beat the
/// record; the budget goes to the next fresh start instead. Three, so that one misfit
/// does not end a descent.
pub const HOPELESS_FITS: u32 = 3;

/// Model steps in a row after which a descent counts as converged because f's
/// arithmetic no longer resolves what its model promises: each step's predicted
/// decrease at most the width within which values tie in T (16 ulps of f(θ),
/// `tie_width`; T's, not f's: at 16 of f32's ulps a descent that still gained ended
/// short of the 10⁻⁶ a user asks of a single-precision loss near 1, where the plateau
/// and resolution rules of `Auto::grain` end it without this count).
/// Below that the ratio test compares rounding errors: σ would shrink on a rejection
/// and widen again where the model turns blind, at a minimum whose value is far from
/// zero, until [`AutoOptions::patience`] ran out (20 + 10n iterations). Steps that end
/// at the model's minimum or tie on a plateau neither count nor reset the count. Three,
/// as [`HOPELESS_FITS`]. Deterministic objectives, once the run has found a value below
/// f(x₀), as the tolerance.
pub const UNRESOLVED_FITS: u32 = 3;

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

/// The noise group of the points remembered in place of failed evaluations
/// (`Auto::stand_in`); the groups of drawn values are never negative.
const WALL_GROUP: f64 = -1.0;

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

/// Failed evaluations that fail again when repeated (`Auto::evaluate`), after which an
/// objective's failures are taken to belong to its points — a wall, a region where it
/// is undefined — and are repeated only at each doubling of the failures from the 16th
/// after the checks: a run beside a wall pays this many evaluations for the check, and
/// one for each doubling.
pub const FAILURE_CHECKS: usize = 4;

/// Draws of one point at most on sparse unseeded noise (`Auto::vote`): it is drawn
/// until two draws agree exactly, and keeps the median of its draws when none do.
pub const VOTES: usize = 5;

/// Dimension from which a fit with a full model forms its offsets and prior values from
/// the transposes of L⁻¹ and H ([`Auto::fit`]).
const BY_COLUMNS_MIN_DIM: usize = 10;

/// Points evaluated per noise-seed chunk of one batch (a stack array of seeds).
const CHUNK: usize = 64;

/// Auto's state between iterations.
/// The σ, the value scale F and the `metric_changes` of the fit whose model
/// `Auto::save_prior` kept: [`Memory::gp`] and [`Memory::hp`] hold it in their
/// standardised units.
#[derive(Clone, Copy, Debug)]
struct SavedPrior<T> {
    sigma: T,
    scale: T,
    metric: u32,
}

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
    /// f(θ) as the separability test measured it (possibly non-finite): the first
    /// survey takes it rather than evaluating θ again.
    tested_centre: Option<T>,
    /// The separability test found f a quadratic along its line, to rounding: the full
    /// model takes no axis prior ([`model::deviation_share`]) while θ is inside the box.
    /// Checked again as σ falls (`Auto::recheck_quadratic`).
    quadratic: bool,
    /// σ at the last line check (the separability test's or a recheck's).
    checked_sigma: T,
    /// The rows [`State::factored`] counts were built with no axis prior: `quadratic`
    /// with θ inside the box at the last fit.
    factored_axis_free: bool,
    /// Remembered points.
    count: usize,
    has_prior: bool,
    /// Where the prior was saved (`Auto::save_prior`).
    saved: SavedPrior<T>,
    /// [`Memory::g0`] and [`Memory::h0`] hold the saved prior in parameter units
    /// (`Auto::prior_to_parameters`).
    in_parameters: bool,
    /// Next unused column of the sampling frame (n: draw a new frame).
    frame_next: usize,
    /// Draw a pair this iteration whatever the count of nearby points: σ widened on a
    /// plateau, or a step failed on a model the nearby points did not determine (on a
    /// lattice, a noisy objective, or where such pairs pay: [`PAIRS_PAY`]).
    resample: bool,
    /// The model claimed its minimum at θ before enough points around θ validated it:
    /// the next iteration draws the pairs the validation lacks at once (with `resample`).
    validate: bool,
    /// Iterations since f(θ) last fell or, before the run's first gain, since a rejected
    /// step to the trust region's boundary took σ below its lowest
    /// ([`State::lowest_sigma`]).
    stale: usize,
    /// The lowest σ a rejected step to the trust region's boundary has left in the run's
    /// first descent before its first gain ([`State::improved`]), on a deterministic
    /// objective. Where σ₀ overstates the scale at which f is a quadratic (Rosenbrock's
    /// valley seen from σ₀ = 500), the model extrapolates to the region's boundary and
    /// its steps fail until σ shrinks to that scale: each shrink below the lowest is that
    /// search going on, not a stagnant descent, and a restart would send σ back to
    /// σ₀·2^k to search again. Nothing else counts: at a minimum x₀ already holds (on a
    /// face of the box too) the model's steps end inside the region, or fail to fit,
    /// and σ would shrink without end.
    lowest_sigma: T,
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
    /// The least σ at which every sample of an iteration failed (NaN or ±∞) about θ
    /// since f(θ) last fell or the run last restarted; zero when none did. The rough rule
    /// (`Auto::model_step`) widens σ only below it: θ lies near where f stops being
    /// defined, and the samples of the wider σ fail again.
    fail_scale: T,
    /// The least σ at which a model step on a rough fit (η > `ROUGH`) fell short
    /// (ρ̂ < 0.1, no tie) and σ was not widened for it, since f(θ) last fell or the run
    /// last restarted, on a deterministic objective; zero when none did, or when the
    /// check that followed found noise. The rough rule (`Auto::model_step`) widens σ
    /// only below it.
    poor_scale: T,
    /// The objective is noisy ([`Objective::deterministic`] is false): values are
    /// compared, and fitted, only within a noise group — the points evaluated on one
    /// seed.
    noisy: bool,
    /// Where the check that an objective declared deterministic is
    /// (`Auto::check_determinism`) stands in this descent.
    check: Check,
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
    /// How the run's failed evaluations (NaN or ±∞) fared when evaluated again at the
    /// same point and seed (`Auto::evaluate`): whether the objective fails at random,
    /// and how often a repeat then returns a value.
    failures: Failures,
    /// Noise groups handed out so far; a point's group is stored as this count modulo
    /// 2²⁰ (exact in `f32`; the memory never holds points that far apart in time).
    groups: u32,
    /// This iteration's seed and noise group when f(θ) (`value`) was measured on it
    /// (noisy objectives), so that the samples and the trial step compare with it.
    shared: Option<(NoiseSeed, T)>,
    /// θ moved this iteration to a point of lower value on a common seed.
    gained: bool,
    /// On dense unseeded noise, the last model step's fit residual scatter in value
    /// units (ηF, its weighted RMS residual): in a run without a budget, a draw below
    /// f(θ)'s by less may be the noise's low tail, and moves θ without counting as a
    /// gain for the patience (`Auto::clears_noise`). Zero until such a fit.
    scatter: T,
    /// On dense unseeded noise in a run without a budget, the lowest draw that counted
    /// as a gain in the run (`Auto::clears_noise`; such a run has one descent); `None`
    /// before one.
    floor: Option<T>,
    /// On unseeded noise, pairs (the lower draw, |f − f′|) of two draws of f at θ, the
    /// last [`THETA_SPREADS`](noise::THETA_SPREADS) of the descent in a ring
    /// (`Auto::record_theta_spread`, `Auto::flat_noise`): the check's first two draws,
    /// and θ's two draws each time it was drawn again beside a trial.
    theta_spreads: [(T, T); noise::THETA_SPREADS],
    /// How many spreads [`State::theta_spreads`] has taken in the descent (the ring's
    /// next slot is this modulo its length).
    theta_spreads_taken: usize,
    /// How often an exploring pair drawn after a failed model step has lowered f(θ):
    /// an average over such pairs, each weighing 1/[`PAIR_MEMORY`] (see [`PAIRS_PAY`]).
    pair_rate: T,
    /// This iteration's exploring pair follows a failed model step, and its outcome
    /// updates `pair_rate`.
    pair_pending: bool,
    /// Failed model steps in a row since one drew an exploring pair.
    pairs_skipped: usize,
    /// θ has moved to a value below f(x₀) at some point of the run.
    improved: bool,
    /// Some finite value of the run differed from f(θ) as it then stood (beyond
    /// [`ties_with`]): f has been seen to vary. Until then a plateau widens σ past
    /// [`PLATEAU_WIDTH`]·σ₀ ([`Auto::widened_sigma`]).
    varied: bool,
    /// The staged row whose value stopped this step under [`NonFinite::Error`]
    /// ([`Auto::failed_point`]).
    failed: Option<usize>,
    finished: Option<AutoTermination>,
    /// Changes of the sampling metric so far.
    metric_changes: u32,
    /// Leading rows of the fit's system that are still the last successful fit's, bit
    /// for bit ([`Memory::u`]), which the next fit keeps (`model::fit`'s `reuse`).
    factored: usize,
    /// Model steps since the last one that confirmed its model (ρ̂ ≥ 0.1).
    unconfirmed: usize,
    /// f at [`Memory::best`], the best point, while a continuation move
    /// ([`AutoStep::Continued`]) has left θ above it; `None` otherwise (θ is the best
    /// point).
    best_value: Option<T>,
    /// (σ, `metric_changes`) for which [`Memory::zs`] holds the remembered points' z
    /// (with θ = [`Memory::zt`]); `None` before it is first filled.
    reach_key: Option<(T, u32)>,
    /// `metric_changes` for which [`Memory::ys`] holds the remembered points' whitened
    /// positions; `None` before they are first computed.
    positions: Option<u32>,
    /// f at [`Memory::record`], the best point of the descents before the current one
    /// (`Auto::fresh_start`); `None` before the first fresh start.
    record: Option<T>,
    /// Fresh starts so far.
    fresh: u32,
    /// The descent the run is in, from 1 ([`Auto::descents`]).
    descent: usize,
    /// Model steps in a row, in a descent after the first, whose close, confirmed fit
    /// puts its minimum within reach and above [`State::record`] by more than half θ's
    /// gap to it ([`HOPELESS_FITS`]).
    hopeless: u32,
    /// Model steps in a row whose predicted decrease f's arithmetic does not resolve
    /// ([`UNRESOLVED_FITS`]).
    unresolved: u32,
    /// The most significant bits of any finite value f has returned
    /// ([`significant_bits`]; 0 before the first), which tells the precision of f's
    /// arithmetic ([`Auto::grain`]). Kept for the whole run.
    value_bits: u32,
    /// The last iteration's model, its points validating it, put its minimum at θ and
    /// σ halved (`Auto::model_step`). Cleared once this iteration's samples are read.
    confirmed: bool,
    /// Validated model minima in a row whose prior predicted the points drawn since the
    /// fit before ([`SETTLED_HALVINGS`], `Auto::model_step`); 0 after an iteration of
    /// another kind, a gain or a restart.
    settled: u32,
    /// Poor steps blamed on σ since the model last confirmed a step (ρ̂ ≥ 0.1) or its
    /// minimum, or since the descent's last restart (`memory::blaming`).
    blamed: u32,
    /// Σ over the gains since the descent's last restart (or its start) of how far each
    /// moved the best point: maxᵢ |Δxᵢ| / sᵢ, sᵢ coordinate i's start scale (as
    /// [`AutoOptions::tolerance`] measures it); at least how far the restart has taken
    /// the best point in those units.
    travelled: T,
    /// Σ over the same gains of how far each lowered f at the best point: at least how
    /// far the restart has lowered it.
    fallen: T,
    /// Points remembered since the last model fit.
    unfitted: usize,
    /// The last fit's prior (the model before it, moved to θ and σ): its weighted RMS
    /// misfit on the points remembered since the fit before, as a fraction of theirs
    /// about f(θ); `None` without a prior, with fewer than n such points, or where they
    /// all tie with f(θ).
    prior_misfit: Option<T>,
    /// This iteration's samples tied with f(θ) by rounding alone right after a model
    /// confirmed θ as its minimum ([`Auto::ties_are_rounding`]): σ is below the scale at
    /// which T resolves f about that minimum, and the descent has converged.
    rounded: bool,
    /// Fresh descents start at σ₀ rather than at their jump's scale from now on
    /// (`Auto::fresh_start`): a probe of this run has found a point below the record,
    /// or two wide descents in a row ended on the same value.
    fresh_narrow: bool,
    /// The current descent is a fresh start's that began wider than σ₀.
    fresh_wide: bool,
    /// The best value of the last descent that began wider than σ₀; `None` before
    /// one has ended.
    wide_end: Option<T>,
    /// The descent has ended on a flat piece of f: the next iteration centres θ on it
    /// (`Auto::centre`), then goes on as this says.
    centre_then: Option<AfterCentre>,
    /// `Auto::centre` moved θ, this descent's best point, to its flat piece's centre;
    /// [`Memory::origin`] holds where the descent left it.
    centred: bool,
    /// Probes left before the next fresh start (the `probe` module).
    probes: usize,
    /// The run's wins and evaluations of probes and fresh starts, which size each probe
    /// phase (the `explore` module).
    explore: Exploration,
    /// What the descent's gains and σ have done in its latest windows (the `creep`
    /// module).
    creep: Creep<T>,
}

/// Where the check that an objective declared deterministic is, evaluating θ a second
/// time (`Auto::check_determinism`), stands in a descent.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Check {
    /// The run's first descent waits for a step on a rough fit that falls short, where
    /// the run would record a poor scale (`State::poor_scale`), a rule for exact values
    /// that noise undoes: the check is due then. A descent that never meets one pays
    /// nothing for the check until it restarts.
    Deferred,
    /// The next model step evaluates θ again.
    Due,
    /// θ was evaluated again since the run last restarted, or noise was found.
    Done,
}

impl Check {
    /// The check at a restart or a new descent: due, unless noise was found already — a
    /// descent may end held by a lucky draw of f(θ) that no later step can beat.
    fn after_restart(unseeded: bool) -> Check {
        if unseeded { Check::Done } else { Check::Due }
    }
}

/// How a run goes on after a descent that ended on a flat piece of f is centred.
#[derive(Clone, Copy, Debug, PartialEq)]
enum AfterCentre {
    /// A fresh start ([`AutoOptions::fresh_starts`]).
    FreshStart,
    /// The run ends.
    End(AutoTermination),
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
            tested_centre: None,
            quadratic: false,
            checked_sigma: T::ZERO,
            factored_axis_free: false,
            count: 0,
            has_prior: false,
            saved: SavedPrior {
                sigma: T::ONE,
                scale: T::ONE,
                metric: 0,
            },
            in_parameters: false,
            frame_next: n,
            resample: false,
            validate: false,
            stale: 0,
            lowest_sigma: sigma0,
            may_restart: false,
            bounded: false,
            survey: false,
            widenings: 0,
            cycle: 0,
            lattice: false,
            tie_scale: T::ZERO,
            rough_scale: T::ZERO,
            fail_scale: T::ZERO,
            poor_scale: T::ZERO,
            scatter: T::ZERO,
            floor: None,
            theta_spreads: [(T::ZERO, T::ZERO); noise::THETA_SPREADS],
            theta_spreads_taken: 0,
            noisy: false,
            check: Check::Deferred,
            unseeded: false,
            dense: false,
            doubted: false,
            voting: false,
            failures: Failures::default(),
            groups: 0,
            shared: None,
            gained: false,
            pair_rate: T::from_f64(PAIR_RATE_START),
            pair_pending: false,
            pairs_skipped: 0,
            improved: false,
            varied: false,
            failed: None,
            finished: None,
            metric_changes: 0,
            factored: 0,
            unconfirmed: 0,
            best_value: None,
            reach_key: None,
            positions: None,
            record: None,
            hopeless: 0,
            unresolved: 0,
            value_bits: 0,
            confirmed: false,
            settled: 0,
            blamed: 0,
            travelled: T::ZERO,
            fallen: T::ZERO,
            unfitted: 0,
            prior_misfit: None,
            rounded: false,
            fresh: 0,
            descent: 1,
            fresh_narrow: false,
            fresh_wide: false,
            wide_end: None,
            centre_then: None,
            centred: false,
            probes: 0,
            creep: Creep::new(),
            explore: Exploration::default(),
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
    /// The model asked for; [`AutoModel::ByDimension`] lets a separability test change
    /// `shape` (the `separable` module).
    model: AutoModel,
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
    /// The largest σ₀ (or coordinate scale) [`Auto::new`] accepts in precision T: 2⁻⁶⁴
    /// of T's largest value (9.7e288 in f64, 1.8e19 in f32). σ widens to 16σ₀ on a
    /// plateau and samples reach several σ along a metric axis stretched by up to 7·10⁶:
    /// a σ₀ near T's range would put infinite or NaN points into the objective.
    pub fn max_scale() -> T {
        T::MAX * T::from_f64(libm::pow(2.0, -64.0))
    }

    /// Floats of buffer [`Auto::new`] needs in dimension n ([`buffer_len`]).
    pub const fn buffer_len(n: usize) -> usize {
        buffer_len(n)
    }

    /// Points remembered in dimension n: twice the model's coefficient count p
    /// ((n+1)(n+2)/2 for a full Hessian, 2n + 1 for a diagonal one) plus n + 1, at most
    /// [`MAX_MEMORY`] or, for a full model, [`FULL_MEMORY_PER_DIM`]·n where that is more:
    /// 2p + n + 1 (15 at n = 2, 48 at n = 5), 128 for n = 10–16 and n ≥ 128, 8n for
    /// n = 17–127. Twice p lets a fit average over the kernel rather than interpolate, and
    /// leaves room, once a converged descent has crowded θ's surroundings, for the wider
    /// points of a restart or a widening σ (each new point replaces the one farthest from
    /// θ; a survey's, the farthest of those older than the survey other than θ's).
    ///
    /// A run on a declared-noisy objective ([`Objective::deterministic`] false) uses
    /// only p + n + 1 of them (at most the same bound): the rules that end its descents
    /// (the fit's scatter, the counts of points that determine the model) are set for
    /// that memory (docs/notes/2026-11-27-memory-twice-the-coefficients.md).
    pub const fn history_len(n: usize) -> usize {
        history_len(Shape::for_dim(n), n)
    }

    /// A run from `theta` (x₀; updated in place to the best point found) with scale
    /// `sigma0` > 0 and default options, drawing its samples from `rng`. A σ₀ below twice
    /// x₀'s resolution 8ε·maxᵢ|x₀ᵢ| is raised to it: a smaller one samples x₀ itself.
    ///
    /// # Errors
    /// [`Error::InvalidSigma`] for σ₀ not in (0, [`Auto::max_scale`]],
    /// [`Error::NonFiniteInput`] for a non-finite x₀, [`Error::DimensionMismatch`] for an
    /// empty x₀, [`Error::WorkspaceTooSmall`] for a buffer shorter than
    /// [`Auto::buffer_len`].
    pub fn new(theta: &'b mut [T], sigma0: T, buffer: &'b mut [T], rng: R) -> Result<Self, Error> {
        Self::with_model(theta, sigma0, buffer, rng, AutoModel::ByDimension)
    }

    /// A run as [`Auto::new`] makes it, with the model and metric of shape `model`
    /// ([`AutoModel`]); a buffer of [`Auto::buffer_len`] floats holds any shape, and
    /// [`AutoModel::buffer_len`]'s suffice for `model`.
    ///
    /// # Errors
    /// Those of [`Auto::new`], with [`Error::WorkspaceTooSmall`] for a buffer shorter
    /// than [`AutoModel::buffer_len`], and [`Error::InvalidSetting`] (`model`) for
    /// [`AutoModel::Full`] above n = [`FULL_MODEL_MAX_DIM`].
    pub fn with_model(
        theta: &'b mut [T],
        sigma0: T,
        buffer: &'b mut [T],
        rng: R,
        model: AutoModel,
    ) -> Result<Self, Error> {
        let n = theta.len();
        if n == 0 {
            return Err(Error::DimensionMismatch {
                expected: 1,
                found: 0,
            });
        }
        if !(sigma0 > T::ZERO && sigma0 <= Self::max_scale()) {
            return Err(Error::InvalidSigma);
        }
        if let Some(index) = theta.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFiniteInput { index });
        }
        // A scale below what x₀'s floats resolve samples x₀ itself: every value ties.
        let largest = theta.iter().fold(T::ZERO, |m, x| m.max(x.abs()));
        let sigma0 = sigma0.max(T::TWO * resolution(largest, T::EPSILON));
        let shape = match model {
            AutoModel::ByDimension => Shape::for_dim(n),
            AutoModel::Full if n > FULL_MODEL_MAX_DIM => {
                return Err(Error::InvalidSetting { name: "model" });
            }
            AutoModel::Full => Shape::Full,
            AutoModel::Diagonal => Shape::Diagonal,
        };
        let needed = buffer_len_of(shape, n);
        if buffer.len() < needed {
            return Err(Error::WorkspaceTooSmall {
                needed,
                available: buffer.len(),
            });
        }
        let buffer = &mut buffer[..needed];
        buffer.fill(T::ZERO);
        let mem = carve(buffer, shape, n);
        mem.lower.fill(-T::MAX);
        mem.upper.fill(T::MAX);
        mem.scale.fill(sigma0);
        mem.tmp.fill(T::ONE);
        metric::axes(shape, mem.tmp, mem.c, mem.l, mem.li);
        Ok(Auto {
            theta,
            mem,
            rng,
            options: AutoOptions::default(),
            model,
            shape,
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
    /// [`Error::NonFiniteInput`] for a NaN bound, [`Error::InvalidEntry`] (`bounds`,
    /// naming the coordinate) where lower > upper, lower = +∞ or upper = −∞ (no finite
    /// point lies there; other infinite bounds mean no bound on that side).
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
            if l > u || l > T::MAX || u < -T::MAX {
                return Err(Error::InvalidEntry {
                    name: "bounds",
                    index: i,
                });
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
    /// [`Error::InvalidEntry`] (`scales`, naming the coordinate) for a scale not in
    /// (0, [`Auto::max_scale`]].
    pub fn with_scales(mut self, scales: &[T]) -> Result<Self, Error> {
        let n = self.theta.len();
        if scales.len() != n {
            return Err(Error::DimensionMismatch {
                expected: n,
                found: scales.len(),
            });
        }
        if let Some(index) = scales
            .iter()
            .position(|&s| !(s > T::ZERO && s <= Self::max_scale()))
        {
            return Err(Error::InvalidEntry {
                name: "scales",
                index,
            });
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
        self.change_metric();
        let m = &mut self.mem;
        metric::axes(self.shape, m.tmp, m.c, m.l, m.li);
        self.st.sigma = sigma0;
        self.st.sigma0 = sigma0;
        self.st.lowest_sigma = sigma0;
    }

    /// Replaces the options (see [`AutoOptions`]).
    pub fn with_options(mut self, options: AutoOptions<T>) -> Self {
        self.options = options;
        self
    }

    /// The best point found so far: x₀ until a finite value has been found.
    pub fn theta(&self) -> &[T] {
        if self.record_leads() || self.nothing_finite() {
            self.mem.record
        } else if self.st.best_value.is_some() {
            self.mem.best
        } else {
            self.theta
        }
    }

    /// Whether the run has evaluated f and found no finite value: [`Memory::record`]
    /// then holds x₀ (see its doc).
    fn nothing_finite(&self) -> bool {
        self.st.evaluations > 0
            && self.st.record.is_none()
            && self.st.best_value.is_none()
            && self.st.value.is_none()
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

    /// The point whose non-finite value stopped the last [`Auto::step`] with
    /// [`Error::NonFiniteObjective`] (under [`NonFinite::Error`]); `None` once another
    /// step has begun, or where no step failed so.
    pub fn failed_point(&self) -> Option<&[T]> {
        let n = self.theta.len();
        self.st
            .failed
            .map(|row| &self.mem.stage[row * n..(row + 1) * n])
    }

    /// The model the run uses: [`AutoModel::Full`] or [`AutoModel::Diagonal`]. Under
    /// [`AutoModel::ByDimension`] that is the one n picks, or, from n = 15 up to
    /// [`FULL_MODEL_MAX_DIM`], the diagonal one once the first step has found f
    /// separable (the test in the `separable` module, on a deterministic objective).
    pub fn model(&self) -> AutoModel {
        match self.shape {
            Shape::Full => AutoModel::Full,
            Shape::Diagonal => AutoModel::Diagonal,
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

    /// Descents begun: 1 for the run's first, and one more for each fresh start and
    /// each probe that found a point below the record, which begin the next (with a
    /// budget, on a deterministic objective: [`AutoOptions::fresh_starts`],
    /// [`AutoOptions::probes`]). Restarts within a descent (σ widened again about its
    /// best point) do not count.
    pub fn descents(&self) -> usize {
        self.st.descent
    }

    /// Why the run ended, once it has.
    pub fn termination(&self) -> Option<AutoTermination> {
        self.st.finished
    }

    /// Steps until the run ends, calling `observe` after every iteration with its report
    /// and the best point so far ([`Auto::theta`], whose value is the report's).
    ///
    /// # Errors
    /// As [`Auto::step`].
    pub fn run<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        mut observe: impl FnMut(&AutoReport<T>, &[T]),
    ) -> Result<AutoTermination, Error> {
        while let Some(report) = self.step(objective)? {
            observe(&report, self.theta());
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
        self.st.failed = None;
        if self.remaining() == 0 {
            self.st.finished = Some(AutoTermination::MaxEvaluations);
            self.restore_best();
            self.restore_record();
            return Ok(None);
        }
        if let Some(then) = self.st.centre_then.take() {
            return self.centre_step(objective, then).map(Some);
        }
        if self.st.probes > 0 {
            return self.probe_step(objective).map(Some);
        }
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let noisy = !objective.deterministic();
        if noisy != self.st.noisy {
            // The fit's rows gain or lose their noise groups.
            self.st.factored = 0;
        }
        self.st.noisy = noisy;
        self.st.shared = None;
        self.st.gained = false;
        self.st.rounded = false;
        // f at the best point as the iteration begins (θ's, unless a continuation move
        // left θ above it).
        let best_before = self.st.best_value.or(self.st.value);
        self.mem.tmp.copy_from_slice(self.theta);
        if self.st.evaluations == 0 {
            // x₀ is the run's record and origin until a descent ends (`Auto::keep_record`).
            self.mem.record.copy_from_slice(self.theta);
            self.mem.origin.copy_from_slice(self.theta);
        }
        let mut spent = 0;
        let mut kind = if self.tests_separability(noisy) {
            self.test_separability(objective, &mut spent)?
        } else if self.rechecks_quadratic(noisy) {
            self.recheck_quadratic(objective, &mut spent)?
        } else {
            None
        };
        if kind.is_none() {
            kind = self.sample(objective, &mut spent)?;
        }
        self.st.confirmed = false;
        if self.st.pair_pending {
            let gain = if self.st.gained { T::ONE } else { T::ZERO };
            self.st.pair_rate += (gain - self.st.pair_rate) / T::from_f64(PAIR_MEMORY);
            self.st.pair_pending = false;
        }
        self.st.resample = false;
        self.st.validate = false;
        let mut ratio = None;
        if kind.is_none() {
            let (k, r) = self.model_step(objective, &mut spent)?;
            kind = Some(k);
            ratio = r;
        }
        let kind = kind.unwrap_or(AutoStep::OutOfBudget);
        if kind != AutoStep::AtModelMinimum || self.st.gained {
            self.st.settled = 0;
        }
        self.st.iteration += 1;
        self.st.resample |= kind == AutoStep::Plateau;
        self.hold_sigma(sigma, kind, ratio);
        if self.st.gained {
            self.st.stale = 0;
            // Without a fresh start to follow, a restart whose gains have moved the best
            // point by less than the tolerance, or lowered it negligibly (the `creep`
            // module's settled values: an asymptote's restarts move it far for nothing),
            // has found only what the descent before it had: it earns no further
            // restart. (With one, any gain does: the restarts' cycle through the wider
            // scales is what finds a multi-modal f's better basins, and the budget
            // bounds it.)
            if self.below_best() {
                self.st.travelled += self.best_moved();
                if let (Some(before), Some(value)) = (best_before, self.st.value) {
                    self.st.fallen += before - value;
                }
                let fallen = self.st.value.is_some_and(|value| {
                    !self
                        .st
                        .creep
                        .negligible(self.st.fallen, value, self.grain())
                });
                self.st.may_restart |=
                    self.may_start_fresh() || (self.st.travelled >= self.tolerance() && fallen);
            }
        } else {
            self.st.stale += 1;
        }
        let step_length = distance(self.mem.tmp, self.theta);
        if kind == AutoStep::Accepted && step_length > T::ZERO && self.follows_path() {
            self.follow_path(sigma);
        }
        let patience = self.options.patience.unwrap_or(20 + 10 * n);
        let scale = self.theta.iter().fold(T::ZERO, |m, x| m.max(x.abs()));
        // Before the run has found any value below f(x₀) the tolerance relative to σ₀
        // does not apply (on a deterministic objective): σ₀ may overstate the scale at
        // which f varies (σ₀ = 10¹² for a minimum a unit away), and σ shrinks until it
        // finds that scale or θ's resolution.
        let tolerated = self.st.improved || self.st.noisy;
        let creeping = self.creeping(patience);
        let settled = self.values_settled(patience);
        let converged = tolerated
            && (self.sigma_converged()
                || self.st.unresolved >= UNRESOLVED_FITS
                || self.st.rounded
                || settled)
            || self.st.sigma <= resolution(scale, self.grain())
            || self.st.hopeless >= HOPELESS_FITS;
        // A descent that has found no finite value has nothing to wait for once σ has
        // widened to its cap: a fresh start about x₀ looks at the finer scales again.
        let lost = self.st.value.is_none()
            && self.st.record.is_none()
            && self.widened_sigma(PLATEAU_WIDTH) <= self.st.sigma;
        let stagnated = self.st.stale >= patience || lost || creeping;
        // Before a restart or the end moves θ back to the best point: a centre that
        // continuation left above it may have just stepped below it.
        self.keep_best();
        // A box of zero width in every coordinate leaves one point: it has been evaluated.
        let pinned = (0..n).all(|i| self.mem.lower[i] == self.mem.upper[i]);
        let termination = if kind == AutoStep::OutOfBudget || self.remaining() == 0 {
            Some(AutoTermination::MaxEvaluations)
        } else if pinned {
            Some(AutoTermination::Converged)
        } else if self.diverged() {
            Some(AutoTermination::Diverged)
        } else if self.options.max_evaluations.is_none() && self.st.evaluations >= unbudgeted_cap(n)
        {
            Some(AutoTermination::EvaluationCap)
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
        } else if converged || stagnated {
            let then = if self.may_start_fresh() {
                AfterCentre::FreshStart
            } else if converged {
                AfterCentre::End(AutoTermination::Converged)
            } else {
                AfterCentre::End(AutoTermination::Stagnated)
            };
            if self.rests_on_flat_piece() {
                self.st.centre_then = Some(then);
                None
            } else {
                self.go_on(then)
            }
        } else {
            None
        };
        Ok(Some(self.end_iteration(
            sigma,
            step_length,
            ratio,
            kind,
            termination,
        )))
    }

    /// Ends an iteration that began at `sigma`: where it ends the run, puts the best point
    /// back into θ; returns its report.
    fn end_iteration(
        &mut self,
        sigma: T,
        step_length: T,
        ratio: Option<T>,
        kind: AutoStep,
        termination: Option<AutoTermination>,
    ) -> AutoReport<T> {
        if termination.is_some() {
            self.restore_best();
            self.restore_record();
        }
        self.st.finished = termination;
        AutoReport {
            iteration: self.st.iteration,
            evaluations: self.st.evaluations,
            sigma,
            next_sigma: self.st.sigma,
            value: self.value(),
            descent: self.st.descent,
            step_length,
            ratio,
            kind,
            termination,
        }
    }

    /// The iteration that centres θ on the flat piece its descent ended on
    /// (`Auto::centre`) and then goes on as `then` says — unless a probe found a lower
    /// value, which moves θ there and restarts the descent, as a gain does.
    fn centre_step<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        then: AfterCentre,
    ) -> Result<AutoReport<T>, Error> {
        let sigma = self.st.sigma;
        let mut spent = 0;
        self.mem.tmp.copy_from_slice(self.theta);
        let outcome = self.centre(objective, &mut spent)?;
        self.st.iteration += 1;
        let step_length = distance(self.mem.tmp, self.theta);
        let (kind, termination) = match outcome {
            Centring::Lower => {
                self.st.widenings = 0;
                self.restart(self.restart_sigma());
                self.st.cycle += 1;
                (AutoStep::Accepted, None)
            }
            Centring::OutOfBudget => (AutoStep::OutOfBudget, Some(AutoTermination::MaxEvaluations)),
            Centring::Done => (AutoStep::Centred, self.go_on(then)),
        };
        Ok(self.end_iteration(sigma, step_length, None, kind, termination))
    }

    /// Goes on after a descent's end: probes and a fresh start, or the run's end.
    fn go_on(&mut self, then: AfterCentre) -> Option<AutoTermination> {
        match then {
            AfterCentre::FreshStart => {
                self.begin_probes();
                None
            }
            AfterCentre::End(termination) => Some(termination),
        }
    }

    /// Whether the descent creeps (the `creep` module): observed once per iteration,
    /// while θ is the descent's best point and f(θ) is finite.
    fn creeping(&mut self, patience: usize) -> bool {
        match self.st.value {
            Some(value) if self.st.best_value.is_none() => self.st.creep.observe(
                value,
                self.st.sigma,
                self.st.iteration,
                self.st.unconfirmed == 0,
                CREEP_WINDOWS * patience,
            ),
            Some(_) => false,
            None => {
                self.st.creep.restart();
                false
            }
        }
    }

    /// Whether the descent's values have settled (the `creep` module): observed after
    /// [`Auto::creeping`], on a deterministic objective while θ is the descent's best
    /// point and f(θ) is finite.
    fn values_settled(&mut self, patience: usize) -> bool {
        let exact = !self.st.noisy && !self.st.unseeded;
        let grain = self.grain();
        match self.st.value {
            Some(value) if exact && self.st.best_value.is_none() => {
                self.st
                    .creep
                    .settled(value, self.st.iteration, CREEP_WINDOWS * patience, grain)
            }
            _ => false,
        }
    }

    /// Coordinate i's spread σ√Cᵢᵢ: a sample's standard deviation along it.
    fn axis_spread(&self, i: usize) -> T {
        let n = self.theta.len();
        let c = match self.shape {
            Shape::Full => self.mem.c[i * n + i],
            Shape::Diagonal => self.mem.c[i],
        };
        self.st.sigma * c.sqrt()
    }

    /// Whether some coordinate's spread ([`Auto::axis_spread`]) is above [`DIVERGENCE_WIDTH`]
    /// times its start scale ([`Auto::start_scale`]), or f(θ) is below
    /// −[`Auto::max_scale`] (2⁻⁶⁴ of T's largest value: an objective whose values run to
    /// −∞ faster than θ moves).
    fn diverged(&self) -> bool {
        if self.st.value.is_some_and(|v| v < -Self::max_scale()) {
            return true;
        }
        let limit = T::from_f64(DIVERGENCE_WIDTH);
        (0..self.theta.len()).any(|i| self.axis_spread(i) > limit * self.start_scale(i))
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
        (0..n).all(|i| self.axis_spread(i) < limit * self.start_scale(i).max(least))
    }

    /// How far θ, below the best point, lies from it, in units of each coordinate's
    /// start scale: maxᵢ |θᵢ − bᵢ| / max(sᵢ, [`Auto::least_start_scale`]), b the point a
    /// continuation move left ([`Memory::best`]) or else θ where this iteration began
    /// ([`Memory::tmp`]).
    fn best_moved(&self) -> T {
        let least = self.least_start_scale();
        let from: &[T] = if self.st.best_value.is_some() {
            self.mem.best
        } else {
            self.mem.tmp
        };
        (0..self.theta.len()).fold(T::ZERO, |m, i| {
            m.max((self.theta[i] - from[i]).abs() / self.start_scale(i).max(least))
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

    /// Whether coordinate i has a bound on both sides (`Auto::new` leaves ±T::MAX
    /// where it has none).
    fn boxed(&self, i: usize) -> bool {
        self.mem.lower[i] > -T::MAX && self.mem.upper[i] < T::MAX
    }

    /// The least scale a coordinate starts with: √[`metric::floor`] of the largest
    /// [`Auto::start_scale`], which keeps C within what T whitens.
    fn least_start_scale(&self) -> T {
        let largest = (0..self.theta.len()).fold(T::ZERO, |a, i| a.max(self.start_scale(i)));
        largest * metric::floor::<T>().sqrt()
    }

    /// The relative precision of f's values: f32's ε (2⁻²³) once some finite value has had
    /// 24 significant bits and none more ([`State::value_bits`]) — an objective computed
    /// in single precision, as a GPU renderer's or a float32 loss's is, whose parameters
    /// are rounded to f32 on their way in too — else T's ε. Values tie within 16 of its
    /// ulps ([`tie_width`]), σ converges at 8 ([`resolution`]), a trial point that moves
    /// no coordinate by more is θ's own (`Auto::model_step`) and a descent's values
    /// settle at a fall of one ([`Creep::negligible`]): below these the run would
    /// compare f's rounding, not f.
    fn grain(&self) -> T {
        if self.st.value_bits == f32::MANTISSA_DIGITS {
            T::from_f64(f64::from(f32::EPSILON)).max(T::EPSILON)
        } else {
            T::EPSILON
        }
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

    /// θ lies on a face of the box: some coordinate at its lower or upper bound.
    fn on_face(&self) -> bool {
        self.theta
            .iter()
            .zip(self.mem.lower.iter().zip(self.mem.upper.iter()))
            .any(|(&t, (&lo, &hi))| t <= lo || t >= hi)
    }
}

/// The smallest σ that moves a parameter of magnitude `scale` in arithmetic of relative
/// precision `grain` (ε of T, or [`Auto::grain`]): 8·grain·scale. A σ at or below it
/// has converged, and σ₀ starts at twice it at least for T's ε ([`Auto::new`]).
fn resolution<T: Real>(scale: T, grain: T) -> T {
    T::from_f64(8.0) * grain * scale
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

/// f ties with v: equal to within `tie_width(v, grain)` of it, `grain` the precision
/// of f's values ([`Auto::grain`]) (a smooth f almost never does).
fn ties_with<T: Real>(f: T, v: T, grain: T) -> bool {
    (f - v).abs() <= tie_width(v, grain)
}

/// 16·grain·|v|: values closer than this to v tie with it ([`ties_with`]), 16 ulps of v
/// at f's precision `grain` ([`Auto::grain`]).
fn tie_width<T: Real>(v: T, grain: T) -> T {
    T::from_f64(16.0) * grain * v.abs()
}

/// The significant bits of v's value as an f64: 53 less the trailing zeros of its
/// significand (an f32 value has at most 24, an integer below 2¹⁶ at most 16); 0 for
/// zero and for subnormal or non-finite values, which say nothing of f's precision.
fn significant_bits<T: Real>(v: T) -> u32 {
    let v = v.to_f64();
    if !v.is_normal() {
        return 0;
    }
    let significand = (v.to_bits() & ((1 << 52) - 1)) | (1 << 52);
    53 - significand.trailing_zeros()
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

    /// An f32 value has at most 24 significant bits, a value of f64 arithmetic nearly
    /// always more (0.1 has 52); zero, subnormal and non-finite values count none.
    #[test]
    fn significant_bits_tell_single_precision() {
        assert_eq!(significant_bits(1.0f64), 1);
        assert_eq!(significant_bits(9.0f64), 4);
        assert_eq!(significant_bits(f64::from(0.1f32)), 24);
        assert_eq!(significant_bits(f64::from(f32::MAX)), 24);
        assert_eq!(significant_bits(0.1f64), 52);
        assert_eq!(significant_bits(1.0f64 / 3.0), 53);
        assert_eq!(significant_bits(0.1f32), 24);
        for v in [0.0f64, -0.0, 1e-310, f64::NAN, f64::INFINITY] {
            assert_eq!(significant_bits(v), 0);
        }
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

    /// A rotated ellipsoid of condition 10⁴ in 6 dimensions with its minimum near 10³, and
    /// a run of Auto on it from 1 with σ₀ = 1, 150 iterations long; `check` is called after
    /// each iteration.
    fn on_ellipsoid(mut check: impl FnMut(&mut Auto<'_, f64, rand_xoshiro::Xoshiro256PlusPlus>)) {
        use rand_xoshiro::rand_core::SeedableRng;
        const N: usize = 6;
        let mut f = |x: &[f64]| {
            (0..N).fold(0.0, |s, i| {
                let along = (x[i] - 1000.0) + 0.5 * (x[(i + 1) % N] - 1000.0);
                s + libm::pow(10.0, 4.0 * i as f64 / 5.0) * along * along
            })
        };
        let mut theta = [1.0; N];
        let mut buffer = [0.0; buffer_len(N)];
        let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
        let mut auto = Auto::new(&mut theta, 1.0, &mut buffer, rng).unwrap();
        for _ in 0..150 {
            if !matches!(auto.step(&mut f), Ok(Some(_))) {
                break;
            }
            check(&mut auto);
        }
    }

    /// The remembered points' offsets from their whitened positions
    /// (`Auto::offset_of`, `Auto::reach_of`) are L⁻¹(x − θ)/σ computed directly, up to
    /// rounding, whichever anchor the positions were last computed about.
    #[test]
    fn whitened_positions_give_the_direct_offsets() {
        let mut direct = [0.0; 6];
        let mut checked = 0;
        on_ellipsoid(|auto| {
            let n = auto.theta.len();
            for k in 0..auto.st.count {
                for i in 0..n {
                    auto.mem.s[i] = (auto.mem.xs[k * n + i] - auto.theta[i]) / auto.st.sigma;
                }
                metric::apply(auto.shape, auto.mem.li, auto.mem.s, &mut direct);
                let reach = auto.offset_of(k);
                let size = libm::sqrt(direct.iter().map(|u| u * u).sum::<f64>());
                for (u, d) in auto.mem.gx.iter().zip(direct.iter()) {
                    assert!((u - d).abs() <= 1e-9 * (1.0 + size), "{u} against {d}");
                }
                assert!((reach - size / libm::sqrt(n as f64)).abs() <= 1e-9 * (1.0 + size));
                assert!((auto.reach_of(k) - reach).abs() <= 1e-9 * (1.0 + reach));
                checked += 1;
            }
        });
        assert!(checked > 1000, "{checked} offsets checked");
    }

    /// A fit with no point within 2ρ (their spread F = 0) fails: the prior moved to F = 0
    /// would be infinite, and saved, it would fail every later fit of the descent. And a
    /// model that is not finite is never kept as a prior.
    #[test]
    fn a_fit_without_points_fails_and_no_prior_is_infinite() {
        let mut checked = 0;
        on_ellipsoid(|auto| {
            let Some(value) = auto.st.value else {
                return;
            };
            if !auto.st.has_prior {
                return;
            }
            let count = auto.st.count;
            auto.st.count = 0;
            let scale = auto.spread(2.0 * REACH, None);
            let fitted = auto.fit(value, scale, None);
            auto.st.count = count;
            assert_eq!(scale, 0.0);
            assert!(fitted.is_none());
            let n = auto.theta.len();
            assert!(
                auto.mem.gp[..n]
                    .iter()
                    .chain(&auto.mem.hp[..n * n])
                    .all(|c| c.is_finite())
            );
            let sigma = auto.st.sigma;
            let kept = auto.mem.g[0];
            auto.mem.g[0] = f64::INFINITY;
            auto.save_prior(1.0, sigma);
            auto.mem.g[0] = kept;
            assert!(!auto.st.has_prior);
            checked += 1;
        });
        assert!(checked > 10, "{checked} fits checked");
    }

    /// A prior moved to θ and σ within the metric it was saved under (O(n²)) is the one
    /// moved through parameter units (O(n³)), up to rounding.
    #[test]
    fn a_prior_moves_alike_with_and_without_parameter_units() {
        let mut moved = 0;
        on_ellipsoid(|auto| {
            if !auto.st.has_prior || auto.st.saved.metric != auto.st.metric_changes {
                return;
            }
            let n = auto.theta.len();
            auto.move_prior(1.7);
            let (g, h): ([f64; 6], [f64; 36]) = (
                auto.mem.g[..n].try_into().unwrap(),
                auto.mem.h[..n * n].try_into().unwrap(),
            );
            auto.prior_to_parameters();
            let saved = auto.st.saved;
            auto.st.saved.metric = saved.metric.wrapping_add(1);
            auto.move_prior(1.7);
            auto.st.saved = saved;
            let top = h.iter().chain(g.iter()).fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in g
                .iter()
                .chain(h.iter())
                .zip(auto.mem.g.iter().chain(auto.mem.h.iter()))
            {
                assert!((a - b).abs() <= 1e-8 * top, "{a} against {b}");
            }
            moved += 1;
        });
        assert!(moved > 10, "{moved} priors compared");
    }
}
