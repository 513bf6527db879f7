//! Auto's memory: the caller's buffer carved into its regions ([`buffer_len`], `carve`),
//! the sizes that depend on n (points remembered, pairs of a survey, points a model
//! needs within reach), which evaluated points are kept (`Auto::remember`: the farthest
//! from θ goes), and their whitened distances to θ, counted within the kernel's reach.

use core::cmp::Ordering;

use rand_core::Rng;

use super::model::{self, Shape};
use super::{
    Auto, FULL_MEMORY_PER_DIM, MAX_MEMORY, REACH, WALL_GROUP, metric, significant_bits, tie_width,
    ties_with,
};
use crate::optim::vector::{distance, norm};
use crate::real::Real;

/// How far θ may move from the whitened positions' anchor, in units of σ√n (whitened),
/// before they are computed again about θ ([`Auto::whiten_positions`]): the offsets
/// (ys_k − yt)/σ then lose at most about this many times rounding's share of |u| to the
/// subtraction, where L⁻¹(x_k − θ)/σ loses rounding's.
const ANCHOR_REACH: f64 = 32.0;

/// How far a gap in f's values about θ must exceed the spreads of the values on either
/// side of it, together, to be a cliff ([`Auto::cliff`]): more than 9 times, the gap
/// spanning more than 90 % of their range.
const CLIFF: f64 = 9.0;

/// How far a gap must exceed the spreads on either side of it, together, to be a cliff
/// where the fit it makes is smooth ([`Auto::cliff`]): more than once, the gap spanning
/// more than half of their range.
const SMOOTHED_CLIFF: f64 = 1.0;

/// Regions of the caller's buffer.
pub(super) struct Memory<'b, T> {
    pub(super) lower: &'b mut [T],
    pub(super) upper: &'b mut [T],
    /// Remembered points (rows of n) and their values, in slots: a new point takes the
    /// next free slot, or that of the point it replaces.
    pub(super) xs: &'b mut [T],
    pub(super) fs: &'b mut [T],
    /// The noise group of each remembered point (see [`State::groups`](super::State::groups)).
    pub(super) gs: &'b mut [T],
    /// z of each remembered point, for θ = `zt` and the σ and metric of
    /// [`State::reach_key`](super::State::reach_key) (see `Auto::refresh_reach`).
    pub(super) zs: &'b mut [T],
    pub(super) zt: &'b mut [T],
    /// Whitened positions of the remembered points (rows of n), ys_k = L⁻¹(x_k − a)
    /// about the anchor a = `ya`, for the metric of
    /// [`State::positions`](super::State::positions); and `yt` = L⁻¹(θ − a) for
    /// θ = `ytheta` (see `Auto::whiten_positions`).
    pub(super) ys: &'b mut [T],
    pub(super) ya: &'b mut [T],
    pub(super) yt: &'b mut [T],
    pub(super) ytheta: &'b mut [T],
    /// The fit's rows u, √w, noise groups, residuals, and its m×m system. The first
    /// [`State::factored`](super::State::factored) rows of `u`, `sw` and `gid`, with
    /// `gram`'s and `kp`'s, are the last fit's, which the next one extends
    /// (`Auto::fit`); other code that borrows them as scratch sets that count to 0.
    pub(super) u: &'b mut [T],
    pub(super) sw: &'b mut [T],
    pub(super) gid: &'b mut [T],
    pub(super) r: &'b mut [T],
    pub(super) gram: &'b mut [T],
    pub(super) kp: &'b mut [T],
    pub(super) norms: &'b mut [T],
    pub(super) schur: &'b mut [T],
    pub(super) beta: &'b mut [T],
    /// The model (standardised units) and the prior (parameter units, at `c0`; see
    /// `Auto::prior_to_parameters`).
    pub(super) g: &'b mut [T],
    pub(super) h: &'b mut [T],
    pub(super) g0: &'b mut [T],
    pub(super) h0: &'b mut [T],
    pub(super) c0: &'b mut [T],
    /// The prior as it was saved, in the standardised units of its σ, scale and metric
    /// ([`SavedPrior`](super::SavedPrior)).
    pub(super) gp: &'b mut [T],
    pub(super) hp: &'b mut [T],
    /// Trust-region scratch.
    pub(super) a: &'b mut [T],
    pub(super) v: &'b mut [T],
    pub(super) gamma: &'b mut [T],
    pub(super) lambda: &'b mut [T],
    pub(super) s: &'b mut [T],
    /// θ at the start of the iteration (the report's step length).
    pub(super) tmp: &'b mut [T],
    /// Orthonormal sampling frame (columns as rows of n).
    pub(super) frame: &'b mut [T],
    /// Points of the current batch and their values. While the trust step is solved,
    /// its first two rows hold the held coordinates' moves and flags (`trust_step`).
    pub(super) stage: &'b mut [T],
    pub(super) stage_f: &'b mut [T],
    /// The trust step with coordinates held on bounds (`held_step`): the reduced
    /// problem's slope (first R's solution y), curvature (first R) and step w.
    pub(super) rg: &'b mut [T],
    pub(super) rh: &'b mut [T],
    pub(super) rs: &'b mut [T],
    /// `gx` holds the trial step Ls (parameter directions, over σ) and other n-vectors
    /// of the iteration; `hx` the held step's orthonormal basis (Q's rows, then Z's).
    pub(super) gx: &'b mut [T],
    pub(super) hx: &'b mut [T],
    /// The sampling metric C = LLᵀ, L and L⁻¹, of the model's shape (see `metric`).
    pub(super) c: &'b mut [T],
    pub(super) l: &'b mut [T],
    pub(super) li: &'b mut [T],
    /// Each remembered point's robustness weight in the fit, in [0, 1]: 1 unless the
    /// objective draws unseeded noise ([`State::unseeded`](super::State::unseeded)), where points the model
    /// cannot explain (a Cauchy outlier) lose it (`Auto::reweigh`).
    pub(super) credit: &'b mut [T],
    /// The slots of the remembered points in the order they came in, the newest last
    /// (slot indices as floats, exact below 2²⁴; `Auto::slot`).
    pub(super) order: &'b mut [T],
    /// The scale each coordinate was given ([`Auto::new`]'s σ₀ or
    /// [`Auto::with_scales`]), from which `Auto::shape_scales` sets σ₀ and C.
    pub(super) scale: &'b mut [T],
    /// The best point while a continuation move has left θ, the search centre, above it
    /// ([`State::best_value`](super::State::best_value)).
    pub(super) best: &'b mut [T],
    /// The evolution path of θ's accepted model steps in units of σ ([`Auto::follow_path`]).
    pub(super) path: &'b mut [T],
    /// The best point of the run's earlier descents ([`State::record`](super::State::record));
    /// until a finite value is found, the run's start, about which fresh starts then
    /// jump (`Auto::fresh_start`).
    pub(super) record: &'b mut [T],
    /// Where fresh starts jump about: the record as its descent left it, before
    /// `Auto::centre` moved it to its flat piece's centre (the record itself
    /// otherwise). The centre is the run's answer, not a step of its search: a shape
    /// hidden under another is no nearer to its target at the middle of its cover.
    pub(super) origin: &'b mut [T],
    /// The search for a flat minimum's centre (`Auto::centre`): per side k = 2i + s of
    /// coordinate i (s = 0 below θ, 1 above), five runs of 2n — the inner bound, the
    /// outer bound, the first probe's distance, the room to the box's face, the probe
    /// in flight.
    pub(super) bracket: &'b mut [T],
}

/// Region lengths for dimension n, in [`Memory`]'s order.
pub(super) const fn regions(shape: Shape, n: usize) -> [usize; 52] {
    let m = history_len(shape, n);
    let hl = shape.hessian_len(n);
    let full = if matches!(shape, Shape::Full) {
        n * n
    } else {
        0
    };
    let rows = stage_rows(shape, n);
    let [gram, kp, norms, schur, beta] = model::scratch_lens(shape, m, n);
    [
        n,
        n,
        m * n,
        m,
        m,
        m,
        n,
        m * n,
        n,
        n,
        n,
        m * n,
        m,
        m,
        m,
        gram,
        kp,
        norms,
        schur,
        beta,
        n,
        hl,
        n,
        hl,
        n,
        n,
        hl,
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
        m,
        n,
        n,
        n,
        n,
        n,
        10 * n,
    ]
}

/// Floats of buffer an [`Auto`] run needs in dimension n, for m = [`Auto::history_len`]
/// points remembered:
/// m(3n + 9) + m² + mp + p² + p + 32n + 8h + r(n + 1) + n² + 2f,
/// with, for the full model (n ≤ [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM)), h = f = n² and p = n + 1, and
/// for the diagonal one h = n, f = 0 and p = 1; r = 2·min(n, ⌊m/2⌋) + 2 staged points.
/// A `const fn`, so that storage can be sized at compile time ([`FixedAuto`](super::FixedAuto)).
/// It is that of the model [`AutoModel::ByDimension`](super::AutoModel::ByDimension)
/// picks, whose buffer holds either shape's.
pub const fn buffer_len(n: usize) -> usize {
    buffer_len_of(Shape::for_dim(n), n)
}

/// Floats of buffer a run with the model `shape` needs in dimension n.
pub(super) const fn buffer_len_of(shape: Shape, n: usize) -> usize {
    let lens = regions(shape, n);
    let mut sum = 0;
    let mut k = 0;
    while k < lens.len() {
        sum += lens[k];
        k += 1;
    }
    sum
}

pub(super) const fn history_len(shape: Shape, n: usize) -> usize {
    memory_of(shape, n, 2)
}

/// Points a run on a declared-noisy objective remembers ([`Auto::history_len`]).
pub(super) const fn noisy_history_len(shape: Shape, n: usize) -> usize {
    memory_of(shape, n, 1)
}

/// `copies` times the model's coefficients plus n + 1, at most [`memory_cap`].
pub(super) const fn memory_of(shape: Shape, n: usize, copies: usize) -> usize {
    let m = copies * shape.coefficients(n) + n + 1;
    let cap = memory_cap(shape, n);
    if m > cap { cap } else { m }
}

/// Most points remembered in dimension n: [`MAX_MEMORY`], or for a full model
/// [`FULL_MEMORY_PER_DIM`]·n where that is more (from n = 17; 1 016 at n = 127).
pub(super) const fn memory_cap(shape: Shape, n: usize) -> usize {
    let grown = FULL_MEMORY_PER_DIM * n;
    if matches!(shape, Shape::Full) && grown > MAX_MEMORY {
        grown
    } else {
        MAX_MEMORY
    }
}

// Where the full model is the default (n ≤ FULL_MODEL_MAX_DIM), its buffer holds the
// diagonal model's ([`Auto::with_model`](super::Auto::with_model)).
const _: () = {
    let mut n = 1;
    while n <= super::FULL_MODEL_MAX_DIM {
        assert!(buffer_len_of(Shape::Diagonal, n) <= buffer_len_of(Shape::Full, n));
        n += 1;
    }
};

// A run that starts with the full model and finds f separable takes the diagonal one
// (`Auto::take_diagonal_model`): each of its regions fits in the full model's.
const _: () = {
    let mut n = 1;
    while n <= super::FULL_MODEL_MAX_DIM {
        let (full, diagonal) = (regions(Shape::Full, n), regions(Shape::Diagonal, n));
        let mut k = 0;
        while k < full.len() {
            assert!(diagonal[k] <= full[k]);
            k += 1;
        }
        n += 1;
    }
};

// A full model's memory never holds as many points as it has coefficients from n = 15
// on, grown or not: which fits are determined does not depend on the memory's growth.
const _: () = {
    let mut n = 15;
    while n <= super::FULL_MODEL_MAX_DIM {
        assert!(memory_cap(Shape::Full, n) < Shape::Full.coefficients(n));
        n += 1;
    }
};

/// Whether a fit can determine the model from the data alone: the model is full (its
/// linear part unpenalised) and the memory holds as many points as it has coefficients,
/// which is n ≤ 14. Above, every fit after the first leans on its prior (and the
/// diagonal model's penalised gradient is never exact); only a full model's first fit
/// after a survey is made exact there ([`Auto::ridge`]).
pub(super) const fn memory_determines_model(shape: Shape, n: usize) -> bool {
    matches!(shape, Shape::Full) && shape.coefficients(n) <= history_len(shape, n)
}

/// Remembered points within reach that a model needs before it steps without sampling:
/// n + 1, or half the memory where that holds fewer than 2n + 2 points.
pub(super) const fn nearby_needed(shape: Shape, n: usize) -> usize {
    let half = history_len(shape, n) / 2;
    if n + 1 < half { n + 1 } else { half }
}

/// Points within reach above which a model that puts its minimum at θ is validated, so
/// that σ may shrink on its word: 2q − 2 for q = [`nearby_needed`] — pairs in about as
/// many directions as the model has linear coefficients.
pub(super) const fn validating(shape: Shape, n: usize) -> usize {
    2 * nearby_needed(shape, n) - 2
}

/// Points within reach above which a full model's poor step (ρ̂ < 0.1) is blamed on σ
/// where the memory cannot determine the model (n ≥ 15), after `blamed` such steps since
/// the model last proved right (a confirmed step or minimum): [`validating`]'s count,
/// doubled for each, up to every remembered point but n + 1. A smooth f's model fails at
/// too wide a σ and holds at a narrower one; a kink's fails alike at every σ (its
/// smoothed curvature grows as σ shrinks), and σ shrinking at each shortfall falls far
/// below the distance still to go.
pub(super) const fn blaming(n: usize, blamed: u32) -> usize {
    let most = history_len(Shape::Full, n) - n - 1;
    let doublings = if blamed < 8 { blamed } else { 8 };
    let need = validating(Shape::Full, n) << doublings;
    if need < most { need } else { most }
}

/// Pairs a survey (the first iteration, a restart) draws: n, or as many as half the
/// memory holds.
pub(super) const fn survey_pairs(shape: Shape, n: usize) -> usize {
    let half = history_len(shape, n) / 2;
    if n < half { n } else { half }
}

/// Points one batch can hold: a survey's samples and θ, or a trial point and θ.
pub(super) const fn stage_rows(shape: Shape, n: usize) -> usize {
    2 * survey_pairs(shape, n) + 2
}

pub(super) fn carve<'b, T>(buffer: &'b mut [T], shape: Shape, n: usize) -> Memory<'b, T> {
    let mut rest = buffer;
    Memory::from_regions(regions(shape, n).map(|len| {
        let (head, tail) = core::mem::take(&mut rest).split_at_mut(len);
        rest = tail;
        head
    }))
}

impl<'b, T> Memory<'b, T> {
    /// A memory of empty regions, which holds nothing: what stands in a run's place while
    /// its memory is being reshaped.
    pub(super) fn empty() -> Self {
        Self::from_regions(core::array::from_fn(|_| <&mut [T]>::default()))
    }

    /// The memory of a run that takes the model `shape` before anything is remembered
    /// (`Auto::take_diagonal_model`): each region cut to `shape`'s length, which is at
    /// most its length now (a constant assertion above), its first floats kept.
    pub(super) fn reshaped(self, shape: Shape, n: usize) -> Self {
        let mut cut = self.into_regions();
        for (region, len) in cut.iter_mut().zip(regions(shape, n)) {
            *region = core::mem::take(region).split_at_mut(len).0;
        }
        Self::from_regions(cut)
    }
}

/// [`Memory::from_regions`] and [`Memory::into_regions`], from one list of its fields in
/// [`regions`]' order.
macro_rules! region_order {
    ($($field:ident),* $(,)?) => {
        impl<'b, T> Memory<'b, T> {
            /// The memory from its regions, in [`regions`]' order.
            fn from_regions(regions: [&'b mut [T]; 52]) -> Self {
                let [$($field),*] = regions;
                Memory { $($field),* }
            }

            /// The memory's regions, in [`regions`]' order.
            fn into_regions(self) -> [&'b mut [T]; 52] {
                let Memory { $($field),* } = self;
                [$($field),*]
            }
        }
    };
}

region_order!(
    lower, upper, xs, fs, gs, zs, zt, ys, ya, yt, ytheta, u, sw, gid, r, gram, kp, norms, schur,
    beta, g, h, g0, h0, c0, gp, hp, a, v, gamma, lambda, s, tmp, frame, stage, stage_f, rg, rh, rs,
    gx, hx, c, l, li, credit, order, scale, best, path, record, origin, bracket,
);

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// A fresh noise group's id.
    pub(super) fn next_group(&mut self) -> T {
        self.st.groups = self.st.groups.wrapping_add(1);
        T::from_usize((self.st.groups % (1 << 20)) as usize)
    }

    /// Remembers the staged rows 0 … `rows` − 1 with finite values, in noise group
    /// `group`, and then its failed rows (NaN or ±∞) with their stand-in values
    /// ([`Auto::stand_in`]) in group [`WALL_GROUP`], after the points remembered before
    /// them. When the memory is full, each
    /// replaces the point farthest from θ (by z) —
    /// on unseeded noise that every draw carries, the point whose z lies farthest from
    /// σ's scale (the largest max(z, 1/z)), θ's own draws kept: a point at z ≪ 1 is one
    /// more draw of f at θ, whose differences the noise swamps, and a point at z ≫ 1 lies
    /// beyond the fit's reach, while the model at σ needs points at σ's distance.
    /// With `keep_batch` it replaces the farthest of the points that are neither this
    /// batch's nor θ's own draws, while there is one. A survey asks for that: it is the
    /// geometry a model is fitted from, n lines through θ, and a restart's, drawn at a σ
    /// far above the one the memory was filled at, lies farther out than every older
    /// point, so that each of its rows would evict the last (the first fit would see one
    /// of them), and where it fills the memory, θ's value, which alone tells the model's
    /// constant from its curvature on points all at one distance.
    pub(super) fn remember(&mut self, rows: usize, group: T, keep_batch: bool) {
        let n = self.theta.len();
        let cap = if self.st.noisy {
            noisy_history_len(self.shape, n)
        } else {
            history_len(self.shape, n)
        };
        // A kept point's z is stored as −1 − z until the batch is in (and then
        // computed again: the round trip through −1 − z is not exact).
        let kept = |z: T| -T::ONE - z;
        let noisy_draws = self.dense_unseeded();
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
        // The finite rows in a first pass, the failed ones in a second, so that a
        // failed row's stand-in sees its batch's values.
        for pass in 0..2 * rows {
            let row = pass % rows;
            let f = self.mem.stage_f[row];
            if f.is_finite() != (pass < rows) {
                continue;
            }
            let (f, group) = if f.is_finite() {
                (f, group)
            } else {
                match self.stand_in(row) {
                    Some(f) => (f, T::from_f64(WALL_GROUP)),
                    None => continue,
                }
            };
            // A value f returned, not a stand-in for a failed one.
            if group != T::from_f64(WALL_GROUP) {
                self.st.value_bits = self.st.value_bits.max(significant_bits(f));
                let grain = self.grain();
                if self.st.value.is_some_and(|v| !ties_with(f, v, grain)) {
                    self.st.varied = true;
                }
            }
            let count = self.st.count;
            let slot = if count >= cap {
                // The farthest point not kept, else the farthest kept one, leaves (the
                // first in the order they came in, of equals); the new point takes its
                // slot and the last place in `order`, the points after it there moving
                // up one, so that a fit at an unchanged θ and σ finds its last system's
                // rows first (`Auto::fit`).
                let (mut free, mut held) = ((None, -T::ONE), (0, -T::ONE));
                for j in 0..count {
                    let z = self.mem.zs[self.slot(j)];
                    if z >= T::ZERO {
                        let far = if !noisy_draws || z == T::ZERO {
                            z
                        } else {
                            z.max(T::ONE / z)
                        };
                        if far > free.1 {
                            free = (Some(j), far);
                        }
                    } else if kept(z) > held.1 {
                        held = (j, kept(z));
                    }
                }
                let gone = free.0.unwrap_or(held.0);
                let slot = self.slot(gone);
                self.mem.order.copy_within(gone + 1..count, gone);
                self.mem.order[count - 1] = T::from_usize(slot);
                slot
            } else {
                self.mem.order[count] = T::from_usize(count);
                self.st.count += 1;
                count
            };
            self.mem.xs[slot * n..(slot + 1) * n]
                .copy_from_slice(&self.mem.stage[row * n..(row + 1) * n]);
            self.mem.fs[slot] = f;
            self.mem.gs[slot] = group;
            self.st.unfitted += 1;
            self.mem.credit[slot] = T::ONE;
            if self.st.positions == Some(self.st.metric_changes) {
                self.whiten_position(slot);
            }
            if self.reach_is_current() {
                self.whiten_positions();
                let z = self.reach_of(slot);
                self.mem.zs[slot] = if keep_batch { kept(z) } else { z };
            }
        }
        if keep_batch && self.reach_is_current() {
            self.whiten_positions();
            for k in 0..self.st.count {
                if self.mem.zs[k] < T::ZERO {
                    self.mem.zs[k] = self.reach_of(k);
                }
            }
        }
    }

    /// The value a failed evaluation (NaN or ±∞) at staged row `row` is remembered
    /// with, on an objective not declared noisy: just above (by twice the tie width) the
    /// value of the finite point remembered nearest to it, where one lies within the
    /// fit's reach of it (‖L⁻¹(x − x_f)‖ ≤ 2ρσ√n; else `None`, and the row is not
    /// remembered). The fit reads it as a floor ([`Auto::fit`]): where the model would put
    /// f lower there, the point holds it up to that value; elsewhere it pulls on nothing.
    /// The model then sees where f fails as no better than the nearest point where it
    /// does not. Fitted to the finite values alone, it carried on past a wall (a
    /// constraint the objective enforces by failing) and, where the minimum of f lies on
    /// the wall, put its own minimum beyond it: every trial failed, σ shrank and θ stalled
    /// short of the minimum. Not on a declared-noisy objective, whose values on different
    /// seeds do not compare.
    fn stand_in(&mut self, row: usize) -> Option<T> {
        if self.st.noisy {
            return None;
        }
        let n = self.theta.len();
        self.whiten_positions();
        let x = &self.mem.stage[row * n..(row + 1) * n];
        metric::whiten(self.shape, self.mem.li, x, self.mem.ya, self.mem.gx);
        let limit = T::from_f64(2.0 * REACH) * self.st.sigma * T::from_usize(n).sqrt();
        let points = Points {
            ys: self.mem.ys,
            fs: self.mem.fs,
            gs: self.mem.gs,
            count: self.st.count,
            reach: None,
            grain: self.grain(),
        };
        points.floor_beside(self.mem.gx, T::ZERO, limit, T::MAX)
    }

    /// The level above which f's values about θ stand on a cliff, where they do:
    /// sorted, the values of the remembered points within the fit's reach (z ≤ 2ρ,
    /// stand-ins left out) split at a gap above f(θ) more than [`CLIFF`] times the
    /// spreads of the values below and above it together, with more than n values on
    /// either side of it, those below not all equal. That is f jumping between two
    /// levels about θ — a constant penalty where a constraint is broken, a step — which
    /// no quadratic fits: fitted, the jump's smoothed slope dominates the model at
    /// every σ while θ lies within σ of it. A level of n values or fewer is no cliff's
    /// side: a quadratic's stiff pair above the points along its valley, or a few noisy
    /// values among exact ones, make such a gap too. The fit reads values above the
    /// level as floors (`Auto::fit`), as it reads failed evaluations' stand-ins.
    /// A gap only more than [`SMOOTHED_CLIFF`] times the spreads is a cliff if the fit
    /// that reads the values above it as floors is smooth (the caller's test): a small
    /// step on a slope, where the slope's rise within reach is a sizeable share of the
    /// step, and not values that scatter about a rough f (a staircase of many steps,
    /// noise), which the floors leave as rough.
    /// Returns the gap's midpoint and whether the gap is more than [`CLIFF`] times the
    /// spreads; `None` where no gap qualifies, and on a noisy objective (declared, or
    /// unseeded noise found), whose draws at one point differ and whose robust fit sets
    /// outliers aside.
    /// `mem.r` serves as scratch (the fit writes it afresh).
    pub(super) fn cliff(&mut self, value: T) -> Option<(T, bool)> {
        if self.st.noisy || self.st.unseeded {
            return None;
        }
        self.refresh_reach();
        let limit = T::from_f64(2.0 * REACH);
        let wall = T::from_f64(WALL_GROUP);
        let mut count = 0;
        for k in 0..self.st.count {
            if self.mem.zs[k] <= limit && self.mem.gs[k] != wall && self.mem.credit[k] > T::ZERO {
                self.mem.r[count] = self.mem.fs[k] - value;
                count += 1;
            }
        }
        let sorted = &mut self.mem.r[..count];
        sorted.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(Ordering::Equal));
        let (&lowest, &highest) = (sorted.first()?, sorted.last()?);
        let n = self.theta.len();
        (n..count.saturating_sub(n + 1)).find_map(|k| {
            let (below, above) = (sorted[k], sorted[k + 1]);
            let gap = above - below;
            let spreads = (below - lowest) + (highest - above);
            let sure = gap > T::from_f64(CLIFF) * spreads;
            (below >= T::ZERO && below > lowest && gap > T::from_f64(SMOOTHED_CLIFF) * spreads)
                .then(|| (value + below + gap * T::HALF, sure))
        })
    }

    /// Whether [`Memory::zs`] holds the remembered points' z for the current θ, σ and
    /// metric.
    pub(super) fn reach_is_current(&self) -> bool {
        self.st.reach_key == Some((self.st.sigma, self.st.metric_changes))
            && *self.mem.zt == *self.theta
    }

    /// Brings [`Memory::zs`] (z of remembered point k at index k) up to date, computing
    /// it afresh only when θ, σ or the metric changed since it was filled: most
    /// iterations ask several times (ties, spread, counts, the memory's replacements).
    pub(super) fn refresh_reach(&mut self) {
        if !self.reach_is_current() {
            self.whiten_positions();
            for k in 0..self.st.count {
                self.mem.zs[k] = self.reach_of(k);
            }
            self.mem.zt.copy_from_slice(self.theta);
            self.st.reach_key = Some((self.st.sigma, self.st.metric_changes));
        }
    }

    /// z = ‖ys_k − yt‖/(σ√n) = ‖L⁻¹(x − θ)‖/(σ√n) of remembered point k, from positions
    /// brought up to date for θ ([`Auto::whiten_positions`]).
    pub(super) fn reach_of(&self, k: usize) -> T {
        let n = self.theta.len();
        let y = &self.mem.ys[k * n..(k + 1) * n];
        let sum = y
            .iter()
            .zip(self.mem.yt.iter())
            .fold(T::ZERO, |s, (&a, &b)| s + (a - b).sq());
        sum.sqrt() / (self.st.sigma * T::from_usize(n).sqrt())
    }

    /// Brings the whitened positions up to date for θ and the metric ([`Memory::ys`],
    /// [`Memory::yt`]), so that remembered point k's standardised offset
    /// u = L⁻¹(x_k − θ)/σ is (ys_k − yt)/σ, O(n) for each of the m points where the
    /// product costs O(n²). yt is computed afresh, O(n²), when θ moved; every ys_k,
    /// O(mn²) about the anchor a = θ, when the metric changed since they were computed
    /// or θ lies farther than [`ANCHOR_REACH`]·σ√n from the anchor in whitened units.
    pub(super) fn whiten_positions(&mut self) {
        let n = self.theta.len();
        let root_n = T::from_usize(n).sqrt();
        if self.st.positions == Some(self.st.metric_changes) {
            if *self.mem.ytheta != *self.theta {
                metric::whiten(
                    self.shape,
                    self.mem.li,
                    self.theta,
                    self.mem.ya,
                    self.mem.yt,
                );
                self.mem.ytheta.copy_from_slice(self.theta);
            }
            if norm(self.mem.yt) <= T::from_f64(ANCHOR_REACH) * self.st.sigma * root_n {
                return;
            }
        }
        self.mem.ya.copy_from_slice(self.theta);
        self.mem.ytheta.copy_from_slice(self.theta);
        self.mem.yt.fill(T::ZERO);
        metric::whiten_rows(
            self.shape,
            self.mem.li,
            self.mem.xs,
            self.st.count,
            self.mem.ya,
            self.mem.ys,
        );
        self.st.positions = Some(self.st.metric_changes);
    }

    /// ys_k = L⁻¹(x_k − a) for remembered point k.
    fn whiten_position(&mut self, k: usize) {
        let n = self.theta.len();
        metric::whiten(
            self.shape,
            self.mem.li,
            &self.mem.xs[k * n..(k + 1) * n],
            self.mem.ya,
            &mut self.mem.ys[k * n..(k + 1) * n],
        );
    }

    /// The slot (index into [`Memory::xs`], `fs`, …) of the remembered point that came
    /// in j-th of those still held ([`Memory::order`]).
    pub(super) fn slot(&self, j: usize) -> usize {
        self.mem.order[j].to_f64() as usize
    }

    /// Remembered points within z.
    pub(super) fn count_within(&mut self, z: T) -> usize {
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
    pub(super) fn count_around(&mut self, z: T) -> usize {
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
    pub(super) fn ties_within(&mut self, z: T) -> (usize, usize) {
        let Some(v) = self.st.value else {
            return (0, 0);
        };
        self.refresh_reach();
        let grain = self.grain();
        (0..self.st.count)
            .filter(|&k| {
                let reach = self.mem.zs[k];
                reach > T::ZERO && reach <= z
            })
            .fold((0, 0), |(near, ties), k| {
                (
                    near + 1,
                    ties + usize::from(ties_with(self.mem.fs[k], v, grain)),
                )
            })
    }

    /// max |f − f(θ)| over remembered points within z whose values are at most `cliff`
    /// ([`Auto::cliff`]; all with `None`), 0 when f(θ) is unknown; for a noisy objective
    /// the largest difference within a noise group, where values compare
    /// (max |f − f(θ)| where no group holds two such points).
    pub(super) fn spread(&mut self, z: T, cliff: Option<T>) -> T {
        let Some(v) = self.st.value else {
            return T::ZERO;
        };
        self.refresh_reach();
        let near =
            |k: &usize| self.mem.zs[*k] <= z && cliff.is_none_or(|level| self.mem.fs[*k] <= level);
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
}

/// The remembered points' whitened positions, values and noise groups, in slots
/// 0 … `count` − 1: what [`Points::floor_beside`] searches, borrowed apart from the fit's
/// rows; with `reach`, their z ([`Memory::zs`], current) and σ√n.
pub(super) struct Points<'a, T> {
    pub(super) ys: &'a [T],
    pub(super) fs: &'a [T],
    pub(super) gs: &'a [T],
    pub(super) count: usize,
    pub(super) reach: Option<(&'a [T], T)>,
    /// The relative precision of f's values ([`Auto::grain`]).
    pub(super) grain: T,
}

impl<T: Real> Points<'_, T> {
    /// The floor a point at whitened position `y` is read with where f there cannot be
    /// fitted (a failed evaluation, a value beyond a cliff): just above (by twice the tie
    /// width) the value of the nearest remembered point that is no stand-in and lies
    /// below `below`, where one lies within `limit` of `y` (whitened distance); else
    /// `None`. Above the tie width, so that no test of ties reads it as f's level.
    /// With `reach`, `z` is y's, and a point whose z differs from it by more than the
    /// nearest distance so far (over σ√n, with a margin for rounding) is passed over: by
    /// the triangle inequality it lies farther.
    pub(super) fn floor_beside(&self, y: &[T], z: T, limit: T, below: T) -> Option<T> {
        let n = y.len();
        let wall = T::from_f64(WALL_GROUP);
        let margin = T::from_f64(1.001);
        let (mut nearest, mut value) = (limit, None);
        for k in (0..self.count).filter(|&k| self.gs[k] != wall && self.fs[k] < below) {
            if let Some((zs, unit)) = self.reach {
                if (zs[k] - z).abs() * unit > nearest * margin {
                    continue;
                }
            }
            let d = distance(&self.ys[k * n..(k + 1) * n], y);
            if d <= nearest {
                (nearest, value) = (d, Some(self.fs[k]));
            }
        }
        let value = value?;
        let above = value + T::TWO * tie_width(value, self.grain);
        above.is_finite().then_some(above)
    }
}
