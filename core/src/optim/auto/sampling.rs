//! An iteration's exploration: how many pairs it draws and where (`Auto::sample`: a
//! survey, or the pairs that the model still lacks within reach, along the sampling
//! frame's directions in the metric, mirrored into the box), and how a batch is
//! evaluated (`Auto::evaluate`: by noise seed, each distinct point once) and
//! remembered.

use rand_core::Rng;

use super::memory::{history_len, nearby_needed, survey_pairs, validating};
use super::model::Ridge;
use super::options::{AutoStep, NonFinite};
use super::{Auto, CHUNK, PLATEAU_WIDTH, REACH, VOTES, metric, reflect, room_along, ties_with};
use crate::error::Error;
use crate::objective::{Batch, NoiseSeed, Objective};
use crate::optim::vector::orthogonalise;
use crate::real::Real;
use crate::sample::normal;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// The centre's value and the samples the model needs; `Some(kind)` when the
    /// iteration ends here (a plateau, or the budget).
    pub(super) fn sample<O: Objective<T> + ?Sized>(
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
            survey_pairs(self.shape, n)
        } else if self.st.validate {
            (validating(self.shape, n) + 1)
                .saturating_sub(self.count_around(T::from_f64(REACH)))
                .div_ceil(2)
                .clamp(1, survey_pairs(self.shape, n))
        } else if self.st.resample {
            1
        } else {
            nearby_needed(self.shape, n)
                .saturating_sub(near)
                .div_ceil(2)
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
        // θ's value from the separability test, where it measured one, is not drawn
        // again.
        let known = if first {
            self.st.tested_centre.take()
        } else {
            None
        };
        let from = usize::from(known.is_some());
        let allowed = from + (rows - from).min(self.remaining());
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
            if let Some(f) = known {
                self.mem.stage_f[0] = f;
            }
            self.evaluate(objective, from, allowed, spent, |row| {
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
        // Remember the points and move θ to the lowest when it beats f(θ) — on unseeded
        // noise that every draw carries, by more than the noise's scale
        // (`Auto::dense_noise_scale`): a draw lower by less is as likely the noise's low
        // tail as f's, and θ would follow the luckiest draws to where f is no lower, the
        // run returning a point that the noise chose. Such noise moves θ by the model's
        // steps only, which its fit averages over many draws. (Where the noise shrinks
        // with f, the scale shrinks as the remembered points descend.)
        self.remember(allowed, group, survey);
        let margin = if self.st.unseeded && self.st.value.is_some() {
            self.dense_noise_scale().unwrap_or(T::ZERO)
        } else {
            T::ZERO
        };
        let mut lowest: Option<(usize, T)> = None;
        for row in 0..allowed {
            let f = self.mem.stage_f[row];
            if f.is_finite() && lowest.is_none_or(|(_, b)| f < b) {
                lowest = Some((row, f));
            }
        }
        let trust_samples = !self.st.noisy || self.st.shared.is_some() || self.st.value.is_none();
        if let Some((row, f)) = lowest {
            if trust_samples && self.st.value.is_none_or(|v| f < v - margin) {
                let (theta, stage) = (&mut *self.theta, &self.mem.stage);
                theta.copy_from_slice(&stage[row * n..(row + 1) * n]);
                let reference = self.st.value;
                self.st.gained |= reference.is_none_or(|v| self.clears_noise(f, v));
                self.st.value = Some(f);
                self.st.improved = true;
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
            let grain = self.grain();
            self.mem.stage_f[fresh]
                .iter()
                .filter(|f| f.is_finite())
                .fold((0, 0), |(near, ties), &f| {
                    (near + 1, ties + usize::from(ties_with(f, v, grain)))
                })
        };
        self.st.lattice = ties > 0 && ties < near;
        if near == 0 && allowed > usize::from(centre) && self.st.value.is_some() {
            // Every sample failed (NaN or ±∞) about a θ where f is finite: θ lies within
            // σ of where f stops being defined (a constraint that the objective enforces
            // by returning ∞, a renderer's invalid parameters). That is no plateau: a
            // wider σ would put still more samples outside, and the run would end up
            // sampling there at the widest scale. Look closer instead.
            if self.st.fail_scale <= T::ZERO || sigma < self.st.fail_scale {
                self.st.fail_scale = sigma;
            }
            self.st.sigma = sigma * T::HALF;
            return Ok(Some(AutoStep::Rejected));
        }
        if self.st.value.is_none() || 2 * ties > near || ties == near {
            // Ties say that f is flat here only where the values around θ differ by far
            // more than the width within which they tie (`tie_width`): by √ε of f(θ),
            // ε the precision of f's values (`Auto::grain`), and by at least 2¹⁴ ulps
            // (f32's √ε is only a few hundred tie widths). At a smooth minimum they tie
            // once σ is small enough that the arithmetic no longer resolves f. There,
            // right after the model at the scale above confirmed θ as its minimum, the
            // descent has converged where the rise of f about θ explains the ties (not
            // before: the models at the scales between may still move θ closer).
            if let Some(v) = self.st.value {
                let grain = self.grain();
                let flat = grain.sqrt().max(T::from_f64(16384.0) * grain);
                if self.spread(T::from_f64(2.0 * REACH), None) > flat * v.abs() {
                    self.st.tie_scale = self.st.tie_scale.max(sigma);
                } else {
                    self.st.rounded = self.st.confirmed && self.ties_are_rounding();
                }
            }
            self.st.sigma = self.widened_sigma(PLATEAU_WIDTH);
            return Ok(Some(AutoStep::Plateau));
        }
        Ok(None)
    }

    /// ‖t‖ for t ~ N(0, I) in n dimensions (a χ_n draw).
    pub(super) fn gaussian_length(&mut self, n: usize) -> T {
        (0..n)
            .fold(T::ZERO, |s, _| {
                s + normal::quantile(T::uniform_open(&mut self.rng)).sq()
            })
            .sqrt()
    }

    /// The next column of the sampling frame, drawing a new random orthonormal frame
    /// (Gram–Schmidt on Gaussian vectors) when the last is used up. A new frame's
    /// Gaussian draws are made at once, and column k is orthonormalised against the k
    /// before it when it is first used, O(kn): no iteration pays the whole frame's
    /// O(n³), which in thousands of dimensions takes seconds. (A column whose residual
    /// is shorter than 10⁻³ is drawn again at that point.)
    pub(super) fn next_direction(&mut self) -> usize {
        let n = self.theta.len();
        if self.st.frame_next >= n {
            for x in self.mem.frame[..n * n].iter_mut() {
                *x = normal::quantile(T::uniform_open(&mut self.rng));
            }
            self.st.frame_next = 0;
        }
        let k = self.st.frame_next;
        loop {
            let len = orthogonalise(self.mem.frame, k, n, 1, None);
            if len > T::from_f64(1e-3) {
                for x in self.mem.frame[k * n..(k + 1) * n].iter_mut() {
                    *x /= len;
                }
                break;
            }
            for x in self.mem.frame[k * n..(k + 1) * n].iter_mut() {
                *x = normal::quantile(T::uniform_open(&mut self.rng));
            }
        }
        self.st.frame_next += 1;
        k
    }

    /// Evaluates staged rows `from … rows − 1` with the given seeds (`seed(row)`), in
    /// chunks (rows before `from` keep the values staged for them); with
    /// [`NonFinite::Error`] the first chunk that leaves a point non-finite ends the batch
    /// with [`Error::NonFiniteObjective`], naming that point's first draw.
    ///
    /// A row equal to an earlier row of its chunk with the same seed (up to rounding) is
    /// not evaluated again but takes that row's value ([`Objective`]: equal seeds give
    /// equal noise), unless the objective draws unseeded noise, where a second draw is
    /// information: a pair whose halves the box folds onto one point (from a corner, or
    /// along an axis normal to a face) costs one evaluation. A row whose value failed
    /// (NaN or ±∞) is evaluated again as [`Auto::repeat_failures`] says, except with
    /// [`NonFinite::Error`].
    pub(super) fn evaluate<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        from: usize,
        rows: usize,
        spent: &mut usize,
        seed: impl Fn(usize) -> NoiseSeed,
    ) -> Result<(), Error> {
        let n = self.theta.len();
        let mut seeds = [0 as NoiseSeed; CHUNK];
        let mut start = from;
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
                if self.options.non_finite != NonFinite::Error {
                    self.repeat_failures(objective, start, &seeds[..distinct], spent)?;
                }
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
                    self.st.failed = Some(start + k);
                    return Err(Error::NonFiniteObjective { sample });
                }
            }
            start += len;
        }
        Ok(())
    }

    /// Evaluates again each failed row (NaN or ±∞) among the staged rows `start …
    /// start + seeds.len() − 1`, on its own seed, while the budget lasts and
    /// [`Failures::repeat`](super::failures::Failures::repeat) says so: once each while
    /// the run checks whether its failures are random (until
    /// [`FAILURE_CHECKS`](super::FAILURE_CHECKS) repeats have failed too), and once a
    /// repeat has returned a value, while the next is likely enough to. On an objective
    /// that fails at random, a failed evaluation says nothing about its point, and read
    /// as a wall ([`Auto::remember`]'s stand-ins) it rejected good trials and bent the
    /// model; on one whose failures are its points', the check costs
    /// [`FAILURE_CHECKS`](super::FAILURE_CHECKS) evaluations a run, and one more per
    /// doubling of its failures.
    fn repeat_failures<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        start: usize,
        seeds: &[NoiseSeed],
        spent: &mut usize,
    ) -> Result<(), Error> {
        let random = self.st.failures.random();
        for (k, &seed) in seeds.iter().enumerate() {
            self.repeat_failure(objective, start + k, seed, spent)?;
        }
        // Found random in this batch: the rows checked before are repeated as later
        // ones were.
        if !random && self.st.failures.random() {
            for (k, &seed) in seeds.iter().enumerate() {
                self.repeat_failure(objective, start + k, seed, spent)?;
            }
        }
        Ok(())
    }

    /// Staged row `row`, while it has failed, the budget lasts and the run's record of
    /// failures says it is worth it, evaluated again on `seed`; how its repeats ended
    /// goes into that record.
    fn repeat_failure<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        row: usize,
        seed: NoiseSeed,
        spent: &mut usize,
    ) -> Result<(), Error> {
        let n = self.theta.len();
        let mut repeats = 0;
        let mut first_failed = false;
        while !self.mem.stage_f[row].is_finite() && self.st.failures.repeat(repeats) {
            if self.remaining() == 0 {
                return Ok(());
            }
            repeats += 1;
            draw(
                objective,
                &self.mem.stage[row * n..(row + 1) * n],
                &[seed],
                &mut self.mem.stage_f[row..=row],
                &mut self.st.evaluations,
                spent,
            )?;
            if repeats == 1 {
                first_failed = !self.mem.stage_f[row].is_finite();
            }
        }
        let recovered = self.mem.stage_f[row].is_finite();
        self.st.failures.note(repeats, first_failed, recovered);
        Ok(())
    }

    /// Moves the distinct rows of the staged chunk `start … start + len − 1` (at most
    /// [`CHUNK`]) and their seeds to its front, in order, by swaps, and returns their
    /// number; `draws[k]` is where row k's value will be. A row repeats an earlier one,
    /// and shares its draw, where their seeds are equal, their coordinates equal up to
    /// rounding ([`same_point`]) and the objective draws no unseeded noise. With no row
    /// repeated nothing moves.
    pub(super) fn distinct_rows(
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
    pub(super) fn spread_distinct(&mut self, start: usize, len: usize, draws: &[u8; CHUNK]) {
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

    /// Draws the staged rows `start + k` for each k of `rows` in order (a row listed
    /// twice is drawn twice), in batches of min(m, [`CHUNK`]) rows, m =
    /// [`Auto::history_len`], gathered in the fit's row scratch; row k's draw is appended
    /// to its draws in the fit's Gram scratch (`gram[k·VOTES + counts[k]]`). Both scratch
    /// regions are free outside a fit; the objective ignores the seeds (unseeded noise).
    pub(super) fn draw_rows<O: Objective<T> + ?Sized>(
        &mut self,
        objective: &mut O,
        start: usize,
        rows: &[usize],
        counts: &mut [usize],
        spent: &mut usize,
    ) -> Result<(), Error> {
        let n = self.theta.len();
        let group = history_len(self.shape, n).min(CHUNK);
        debug_assert!(group * n <= self.mem.u.len());
        self.st.factored = 0;
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
