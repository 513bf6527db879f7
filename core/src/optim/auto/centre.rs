//! The centre of a flat minimum. Where f is constant on a neighbourhood of the point a
//! descent ends at — a rasteriser without anti-aliasing, whose image does not change
//! until an edge crosses a pixel centre; coordinates rounded before f — every point of
//! that piece is as low as θ, and θ is wherever the descent happened to enter it, often
//! near an edge. The centre of the piece is the better answer: the limit of the
//! smoothed objective's minimum as σ → 0 where the piece is symmetric about the
//! truth (a pixel's width about a shape's true edge), and the point farthest from the
//! higher values around it.
//!
//! `Auto::centre` finds the piece's extent along each parameter axis from θ, all axes
//! and both directions in one batch per round: a probe whose value equals f(θ) exactly
//! lies inside (the inner bound moves out), a higher or non-finite one outside (the
//! outer bound moves in); only exact equality counts, so that θ's value stays its own
//! and no lower point is passed over. A side's first probe goes as far along its axis as the farthest
//! remembered point with f(θ)'s value lies from θ (an axis no tied point moved along
//! shows no extent and is not searched); it grows ×4 until a probe lies outside, then
//! bisects — geometrically while the bounds differ by more than 4×, arithmetically
//! after — until they agree to [`RESOLUTION`] of the outer one. A side that ties at the
//! box's face ends there; one still tying at [`PLATEAU_WIDTH`]·sᵢ (sᵢ the coordinate's
//! start scale) is open, and its coordinate keeps θ's value (a flat direction has no
//! centre); one whose outer bound falls below [`RESOLUTION`]² of its first probe puts
//! θ on the edge. θ then moves to the midpoint of the two edges on every axis that has
//! both, where that point keeps f(θ): a piece that is not a box in the parameter axes
//! may not hold it. A probe below f(θ) ends the search: the descent was not over
//! (`Auto::step` restarts it from there). Probes are staged in batches of the stage's
//! rows, cut to the budget's remainder, which ends the search.

use rand_core::Rng;

use super::{Auto, PLATEAU_WIDTH, tie_width, ties_with};
use crate::error::Error;
use crate::objective::Objective;
use crate::real::Real;

/// How closely a side's bounds agree before its edge is taken as their midpoint, as a
/// fraction of the outer bound: the edge is then known to within 1/32 of its distance
/// from θ, the centre to within 1/32 of the piece's width.
const RESOLUTION: f64 = 1.0 / 16.0;

/// How far from θ, as a multiple of the farthest tie, the untied points lie that
/// [`Auto::rounding_explains`] reads f's rise from: near enough that a far basin's value
/// close to f(θ) does not pass for a flat direction.
const ROUNDING_REACH: f64 = 64.0;

/// How far past the rounding extent √(w/q) ties may reach and still be rounding's
/// ([`Auto::rounding_explains`]): ties lie along f's flattest directions near θ, which
/// the untied points may not have sampled, so q may overstate their curvature.
const ROUNDING_SLACK: f64 = 4.0;

/// What a search for the centre found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Centring {
    /// θ is at the centre of its flat piece, or stayed (no coordinate's piece had two
    /// edges, or the centre was higher).
    Done,
    /// A probe was below f(θ) and θ moved there.
    Lower,
    /// The budget ran out; θ is unchanged.
    OutOfBudget,
}

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Whether the descent that just ended rests on a flat piece of f worth centring:
    /// the objective's values are exact (deterministic, or voted), f(θ) is finite and
    /// lower than every earlier descent's, and a remembered point other than θ has
    /// exactly its value farther from θ than f's rounding explains
    /// ([`Auto::rounding_explains`]: a smooth f ties only where its rise near its
    /// minimum falls below its resolution). Never where the descent ended because its
    /// ties are rounding's ([`Auto::ties_are_rounding`], this iteration): the exact ties
    /// may lie too close to θ for an untied point to be near enough to tell.
    pub(super) fn rests_on_flat_piece(&self) -> bool {
        if !self.options.centre
            || self.st.rounded
            || self.st.noisy
            || (self.st.unseeded && !self.st.voting)
        {
            return false;
        }
        let Some(value) = self.st.best_value.or(self.st.value) else {
            return false;
        };
        if self.st.record.is_some_and(|r| r <= value) {
            return false;
        }
        let theta: &[T] = if self.st.best_value.is_some() {
            self.mem.best
        } else {
            self.theta
        };
        let tied = (0..self.st.count)
            .filter(|&k| self.mem.fs[k] == value)
            .fold(T::ZERO, |d, k| d.max(self.scaled_distance(theta, k)));
        tied > T::ZERO && !self.rounding_explains(theta, value, tied)
    }

    /// Whether the remembered points that tie with f(θ) (within [`tie_width`], θ aside)
    /// do so by f's rounding alone ([`Auto::rounding_explains`]), on an objective whose
    /// values are exact: θ is at a smooth minimum that T resolves no further at this σ,
    /// not on a flat piece. False where none ties.
    pub(super) fn ties_are_rounding(&self) -> bool {
        if self.st.noisy || self.st.unseeded {
            return false;
        }
        let Some(value) = self.st.value else {
            return false;
        };
        let grain = self.grain();
        let tied = (0..self.st.count)
            .filter(|&k| ties_with(self.mem.fs[k], value, grain))
            .fold(T::ZERO, |d, k| d.max(self.scaled_distance(self.theta, k)));
        tied > T::ZERO && self.rounding_explains(self.theta, value, tied)
    }

    /// Whether f's rounding alone explains ties with `value` out to `tied` from θ (in
    /// start-scale units, [`Auto::scaled_distance`]): a smooth f at its minimum rises
    /// as q·d² at distance d, and its values tie with f(θ) while that rise is below its
    /// resolution, out to √(w/q) for w = [`tie_width`] of f(θ). q is taken as the least
    /// rise per squared distance, (f(x) − f(θ))/d², over the remembered points that do
    /// not tie and lie within [`ROUNDING_REACH`]·`tied` (the flattest direction seen
    /// near θ), and rounding explains the ties when `tied` ≤ [`ROUNDING_SLACK`]·√(w/q).
    /// A flat piece's ties are not explained: the values past its edge lie a jump J
    /// above f(θ), so √(w/q) ≤ ROUNDING_REACH·`tied`·√(w/J), far inside the piece for
    /// any jump above about 10⁶ ulps of f(θ). With no untied point that near, or f(θ) = 0
    /// (w = 0), the ties count as a flat piece.
    fn rounding_explains(&self, theta: &[T], value: T, tied: T) -> bool {
        let reach = T::from_f64(ROUNDING_REACH) * tied;
        let least = (0..self.st.count)
            .filter(|&k| self.mem.fs[k] != value && self.mem.fs[k].is_finite())
            .filter_map(|k| {
                let d = self.scaled_distance(theta, k);
                (d > T::ZERO && d <= reach).then(|| (self.mem.fs[k] - value).abs() / d.sq())
            })
            .fold(T::MAX, T::min);
        let width = tie_width(value, self.grain());
        least < T::MAX
            && width > T::ZERO
            && tied <= T::from_f64(ROUNDING_SLACK) * (width / least).sqrt()
    }

    /// ‖(x_k − θ)/s‖ for remembered point k, s the coordinates' start scales
    /// ([`Auto::start_scale`]).
    fn scaled_distance(&self, theta: &[T], k: usize) -> T {
        let n = theta.len();
        let x = &self.mem.xs[k * n..(k + 1) * n];
        x.iter()
            .zip(theta)
            .enumerate()
            .fold(T::ZERO, |s, (i, (&xi, &ti))| {
                s + ((xi - ti) / self.start_scale(i)).sq()
            })
            .sqrt()
    }

    /// Moves θ (the descent's best point) to the centre of the flat piece of f it lies
    /// on, as the module says, within the budget.
    ///
    /// # Errors
    /// As [`Auto::step`]: a non-finite value under [`NonFinite::Error`](super::NonFinite::Error), a cancelled
    /// objective.
    pub(super) fn centre<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        spent: &mut usize,
    ) -> Result<Centring, Error> {
        self.restore_best();
        let Some(value) = self.st.value else {
            return Ok(Centring::Done);
        };
        let n = self.theta.len();
        let rows = self.mem.stage_f.len();
        // Per side k = 2i + s ([`Memory::bracket`](super::memory::Memory::bracket)): the
        // inner bound (ties), the outer bound (higher; T::MAX while none is known), the
        // first probe's distance, the room to the face.
        self.tied_extent(value);
        for i in 0..n {
            let first = self.mem.bracket[4 * n + 2 * i];
            for side in 0..2 {
                let k = 2 * i + side;
                let room = if side == 0 {
                    self.theta[i] - self.mem.lower[i]
                } else {
                    self.mem.upper[i] - self.theta[i]
                };
                self.mem.bracket[k] = T::ZERO;
                self.mem.bracket[2 * n + k] = T::MAX;
                self.mem.bracket[4 * n + k] = first;
                self.mem.bracket[6 * n + k] = room;
            }
        }
        loop {
            // Every open side's next probe, in chunks of the stage's rows; side k's
            // probe distance is kept at 8n + k while its row is out (zero otherwise).
            let mut pending = false;
            let mut k = 0;
            while k < 2 * n {
                let start = k;
                let mut staged = 0;
                let cap = rows.min(self.remaining());
                while k < 2 * n && staged < cap {
                    if let Some(t) = self.side(k).next_probe(self.open_width(k / 2)) {
                        let i = k / 2;
                        let row = &mut self.mem.stage[staged * n..(staged + 1) * n];
                        row.copy_from_slice(self.theta);
                        let x = if k % 2 == 0 { row[i] - t } else { row[i] + t };
                        row[i] = x.max(self.mem.lower[i]).min(self.mem.upper[i]);
                        self.mem.bracket[8 * n + k] = t;
                        staged += 1;
                    }
                    k += 1;
                }
                if staged == 0 {
                    if cap == 0 && k < 2 * n {
                        return Ok(Centring::OutOfBudget);
                    }
                    continue;
                }
                pending = true;
                self.evaluate(objective, 0, staged, spent, |_| 0)?;
                let mut lowest: Option<(usize, T)> = None;
                let mut r = 0;
                for side in start..k {
                    let t = core::mem::replace(&mut self.mem.bracket[8 * n + side], T::ZERO);
                    if t == T::ZERO {
                        continue;
                    }
                    let f = self.mem.stage_f[r];
                    if f == value {
                        self.mem.bracket[side] = t;
                    } else if f < value {
                        if lowest.is_none_or(|(_, l)| f < l) {
                            lowest = Some((r, f));
                        }
                    } else {
                        self.mem.bracket[2 * n + side] = t;
                    }
                    r += 1;
                }
                if let Some((r, f)) = lowest {
                    self.theta
                        .copy_from_slice(&self.mem.stage[r * n..(r + 1) * n]);
                    self.st.value = Some(f);
                    return Ok(Centring::Lower);
                }
            }
            if !pending {
                break;
            }
        }
        // The centre: on each axis with both edges found, the midpoint of the edges.
        self.mem.stage[..n].copy_from_slice(self.theta);
        let mut moved = false;
        for i in 0..n {
            let (Some(below), Some(above)) = (self.side(2 * i).edge(), self.side(2 * i + 1).edge())
            else {
                continue;
            };
            let shift = T::HALF * (above - below);
            if shift != T::ZERO {
                let x = self.theta[i] + shift;
                self.mem.stage[i] = x.max(self.mem.lower[i]).min(self.mem.upper[i]);
                moved = true;
            }
        }
        if !moved {
            return Ok(Centring::Done);
        }
        if self.remaining() == 0 {
            return Ok(Centring::OutOfBudget);
        }
        self.evaluate(objective, 0, 1, spent, |_| 0)?;
        let f = self.mem.stage_f[0];
        if f == value {
            self.mem.origin.copy_from_slice(self.theta);
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.centred = true;
        } else if f < value {
            self.theta.copy_from_slice(&self.mem.stage[..n]);
            self.st.value = Some(f);
            return Ok(Centring::Lower);
        }
        Ok(Centring::Done)
    }

    /// The first probes' distance along each coordinate i, written to both its sides'
    /// slots (4n + 2i, 4n + 2i + 1): the farthest that a remembered point whose value
    /// is exactly f(θ) = `value` lies from θ along it. Zero where no tied point moved it: f's piece
    /// shows no extent along that axis, which is then not searched.
    fn tied_extent(&mut self, value: T) {
        let n = self.theta.len();
        self.mem.bracket[4 * n..6 * n].fill(T::ZERO);
        for k in 0..self.st.count {
            if self.mem.fs[k] != value {
                continue;
            }
            for i in 0..n {
                let d = (self.mem.xs[k * n + i] - self.theta[i]).abs();
                let slot = &mut self.mem.bracket[4 * n + 2 * i];
                *slot = slot.max(d);
            }
        }
        for i in 0..n {
            self.mem.bracket[4 * n + 2 * i + 1] = self.mem.bracket[4 * n + 2 * i];
        }
    }

    /// How far a side of coordinate i's axis may still tie before it counts as open:
    /// [`PLATEAU_WIDTH`] times the coordinate's start scale.
    fn open_width(&self, i: usize) -> T {
        T::from_f64(PLATEAU_WIDTH) * self.start_scale(i)
    }

    /// Side k's bracket ([`Memory::bracket`](super::memory::Memory::bracket)).
    fn side(&self, k: usize) -> Side<T> {
        let n = self.theta.len();
        let b = &self.mem.bracket;
        Side {
            inner: b[k],
            outer: b[2 * n + k],
            first: b[4 * n + k],
            room: b[6 * n + k],
        }
    }
}

/// One side of one axis in the search for a flat piece's edges: the inner bound (a probe
/// there tied), the outer bound (higher; `T::MAX` while none is known), the first
/// probe's distance (zero: the side is not searched) and the room to the box's face.
#[derive(Clone, Copy)]
struct Side<T> {
    inner: T,
    outer: T,
    first: T,
    room: T,
}

impl<T: Real> Side<T> {
    /// The distance of the side's next probe, or `None` once it is settled: not
    /// searched, tied at the box's face or at `open` (its widest), or its bounds agree
    /// to [`RESOLUTION`] of the outer one (or the outer fell below [`RESOLUTION`]² of the
    /// first probe: θ is on the edge).
    fn next_probe(&self, open: T) -> Option<T> {
        let Side {
            inner,
            outer,
            first,
            room,
        } = *self;
        let resolution = T::from_f64(RESOLUTION);
        if first == T::ZERO || inner >= room || inner >= open {
            return None;
        }
        if outer == T::MAX {
            let t = if inner == T::ZERO {
                first
            } else {
                T::from_f64(4.0) * inner
            };
            return Some(t.min(room));
        }
        if outer - inner <= resolution * outer || outer <= resolution * resolution * first {
            return None;
        }
        Some(if inner == T::ZERO {
            outer * T::HALF * T::HALF
        } else if outer > T::from_f64(4.0) * inner {
            (inner * outer).sqrt()
        } else {
            T::HALF * (inner + outer)
        })
    }

    /// The side's edge, its distance from θ: the face where the side tied there, the
    /// midpoint of its bounds, or `None` where it is open (still tying at its widest) or
    /// was not searched.
    fn edge(&self) -> Option<T> {
        if self.first == T::ZERO || (self.outer == T::MAX && self.inner < self.room) {
            None
        } else if self.inner >= self.room {
            Some(self.room)
        } else {
            Some(T::HALF * (self.inner + self.outer))
        }
    }
}
