//! Auto's side of the local model (the `model` module holds the regression): which
//! remembered points a fit uses and how they are weighted, the prior it starts from
//! (the last model, moved to the current θ and σ), the ridge it is held by, and the
//! decrease a step is predicted to bring.

use rand_core::Rng;

use super::memory::{Points, memory_determines_model};
use super::model::{self, Ridge, Shape};
use super::{
    Auto, BY_COLUMNS_MIN_DIM, EXACT, FIT_WIDTH, REACH, SMOOTH, SavedPrior, WALL_GROUP, metric,
};
use crate::optim::vector::{dot, norm, transpose};
use crate::real::Real;

/// How far the prior must miss the points to be dropped: its weighted RMS residual over
/// the points a fit uses, more than this many times theirs about f(θ) (the flat model's,
/// over the drawn values: floors left out).
/// A prior carried from the last iteration, whose θ and σ differ by at most the factors
/// one step allows, misses a smooth f's points by less; one fitted where f was no
/// quadratic — a wall where f grows by orders of magnitude, which a shrinking σ has
/// since left — predicts values the points contradict by those orders, and carried on,
/// it holds every later fit with it.
const REFUTED: f64 = 16.0;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Writes remembered point k's standardised offset u = L⁻¹(x − θ)/σ to `gx` (as the
    /// fit computes it) and returns its reach ‖u‖/√n.
    pub(super) fn offset_of(&mut self, k: usize) -> T {
        let n = self.theta.len();
        self.whiten_positions();
        let y = &self.mem.ys[k * n..(k + 1) * n];
        for ((u, &yk), &t) in self.mem.gx.iter_mut().zip(y).zip(self.mem.yt.iter()) {
            *u = (yk - t) / self.st.sigma;
        }
        norm(self.mem.gx) / T::from_usize(n).sqrt()
    }

    /// The model step's fit: [`Auto::fit`] with values scaled by their spread within 2ρ.
    /// Where it is rough (noise above [`SMOOTH`]) it may be a quadratic fitted across a
    /// cliff ([`Auto::cliff`]): fitted again with the values beyond it as floors (scaled
    /// by the spread below it), which stands where the gap is sure or the refit smooth;
    /// otherwise the first fit is made again, the prior as it was. Returns the scale,
    /// noise level and points of the fit that stands; `None` where a fit failed.
    pub(super) fn fit_about_cliffs(&mut self, value: T) -> Option<(T, T, usize)> {
        let limit = T::from_f64(2.0 * REACH);
        let scale = self.spread(limit, None);
        let first = self.fit(value, scale, None)?;
        if first.0 <= T::from_f64(SMOOTH) {
            return Some((scale, first.0, first.1));
        }
        let Some((cliff, sure)) = self.cliff(value) else {
            return Some((scale, first.0, first.1));
        };
        let had_prior = self.st.has_prior;
        let below = self.spread(limit, Some(cliff));
        let (noise, fitted) = self.fit(value, below, Some(cliff))?;
        if sure || noise <= T::from_f64(SMOOTH) {
            return Some((below, noise, fitted));
        }
        self.st.has_prior = had_prior;
        let (noise, fitted) = self.fit(value, scale, None)?;
        Some((scale, noise, fitted))
    }

    /// Fits the model around θ to the remembered points within 2ρ, values scaled by
    /// `scale`, from the prior moved to θ and σ — unless the points refute the prior
    /// ([`REFUTED`]), when the fit starts from zero and the prior is forgotten; or unless
    /// the prior predicts them to rounding ([`EXACT`]; deterministic objectives only),
    /// when it is the fit and no system is solved. Values above `cliff` ([`Auto::cliff`])
    /// are read as failed evaluations' stand-ins are: floors just above the nearest
    /// point's below it. Returns the fit's noise level (the weighted RMS residual, as
    /// `model::fit` gives it) and the number of points fitted; `None` when the fit failed,
    /// or when `scale` is not positive and finite: values that do not spread (no point
    /// within 2ρ, or every one at f(θ)) give nothing to fit, and the prior moved to the
    /// scale F = 0 would be infinite — saved, it would fail every later fit.
    pub(super) fn fit(&mut self, value: T, scale: T, cliff: Option<T>) -> Option<(T, usize)> {
        if !(scale > T::ZERO && scale.is_finite()) {
            return None;
        }
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let shape = self.shape;
        self.whiten_positions();
        self.move_prior(scale);
        let limit = T::from_f64(2.0 * REACH);
        let width = T::from_f64(if memory_determines_model(shape, n) {
            FIT_WIDTH
        } else {
            REACH
        });
        let mut m = 0;
        // Σ wᵢ(m₀(uᵢ) − vᵢ)² and Σ wᵢvᵢ², vᵢ the scaled (f − f(θ)): the prior's misfit
        // and that of the flat model f(θ), the latter over drawn values only: a floor
        // the prior puts above its value takes the prior's own there, and would judge a
        // wild prior against itself.
        let (mut misfit, mut spread) = (T::ZERO, T::ZERO);
        // The same sums over the points remembered since the last fit, which the prior
        // has not seen: (misfit, spread, points).
        let mut unseen = (T::ZERO, T::ZERO, 0);
        let first_unseen = self.st.count.saturating_sub(self.st.unfitted);
        let root_n = T::from_usize(n).sqrt();
        // From BY_COLUMNS_MIN_DIM coordinates on, H by columns for the prior's values
        // below (the same sums as by rows, in contiguous passes that vectorise); below
        // it the transpose costs more than it saves.
        let by_columns = shape == Shape::Full && n >= BY_COLUMNS_MIN_DIM;
        if by_columns {
            transpose(self.mem.h, n, self.mem.v);
        }
        // ω (`model::deviation_share`): none on a quadratic unless θ is on a face. The
        // system's rows depend on it, so a change keeps none of them.
        let axis_free = self.st.quadratic && !self.on_face();
        if axis_free != self.st.factored_axis_free {
            self.st.factored = 0;
            self.st.factored_axis_free = axis_free;
        }
        // Rows of the last fit's system that this fit keeps: those before the first
        // row that differs from the one in its place (`model::fit`'s `reuse`).
        let mut kept = self.st.factored;
        let same = |a: &[T], b: &[T]| {
            a.iter()
                .zip(b)
                .all(|(x, y)| x.to_f64().to_bits() == y.to_f64().to_bits())
        };
        // Points the reach cache puts clearly beyond the limit are passed over unseen
        // (its z is computed another way, equal to the fit's up to rounding; the margin
        // leaves every point near the limit to the fit's own z).
        let known_far = self.reach_is_current().then(|| limit * T::from_f64(1.001));
        let wall = T::from_f64(WALL_GROUP);
        let grain = self.grain();
        for j in 0..self.st.count {
            let k = self.slot(j);
            if known_far.is_some_and(|far| self.mem.zs[k] > far) {
                continue;
            }
            // Row m of u = L⁻¹(x − θ)/σ = (ys_k − yt)/σ, kept if z = ‖u‖/√n is within
            // the limit.
            let y = &self.mem.ys[k * n..(k + 1) * n];
            let row = &mut *self.mem.gx;
            for ((ri, &yk), &t) in row.iter_mut().zip(y).zip(self.mem.yt.iter()) {
                *ri = (yk - t) / sigma;
            }
            let z = norm(row) / root_n;
            if z > limit {
                continue;
            }
            let credit = self.mem.credit[k];
            if credit <= T::ZERO {
                continue;
            }
            let sw = (-(z / width).sq() / T::from_f64(4.0)).exp() * credit.sqrt();
            let quadratic = if by_columns {
                Shape::half_quadratic_by_columns(self.mem.v, row, self.mem.lambda)
            } else {
                shape.half_quadratic(self.mem.h, row)
            };
            let prior = dot(self.mem.g, row) + quadratic;
            // Values beyond the cliff are floors as stand-ins are, in their own noise
            // groups: a group weighs in the system only on a noisy objective, which
            // has no cliff, so the system keeps its rows whether a cliff is found.
            let id = self.mem.gs[k];
            let (f, floor) = match cliff {
                Some(level) if self.mem.fs[k] > level && id != wall => {
                    let points = Points {
                        ys: self.mem.ys,
                        fs: self.mem.fs,
                        gs: self.mem.gs,
                        count: self.st.count,
                        reach: known_far.map(|_| (&*self.mem.zs, sigma * root_n)),
                        grain,
                    };
                    let y = &self.mem.ys[k * n..(k + 1) * n];
                    match points.floor_beside(y, z, limit * sigma * root_n, level) {
                        Some(floor) => (floor, true),
                        None => continue,
                    }
                }
                _ => (self.mem.fs[k], id == wall),
            };
            let mut v = (f - value) / scale;
            if floor && v < prior {
                // A failed evaluation's stand-in (`Auto::stand_in`), or a value beyond
                // a cliff (`Auto::cliff`), is a floor: it holds the model up where the
                // prior puts f below it, and pulls on nothing where the prior has f at
                // or above it.
                v = prior;
            }
            let slot = &mut self.mem.u[m * n..(m + 1) * n];
            if m < kept && !(same(slot, row) && same(&[self.mem.sw[m], self.mem.gid[m]], &[sw, id]))
            {
                kept = m;
            }
            slot.copy_from_slice(row);
            self.mem.sw[m] = sw;
            self.mem.gid[m] = id;
            self.mem.r[m] = sw * (v - prior);
            misfit += self.mem.r[m].sq();
            let drawn = if floor { T::ZERO } else { (sw * v).sq() };
            spread += drawn;
            if j >= first_unseen {
                unseen = (
                    unseen.0 + self.mem.r[m].sq(),
                    unseen.1 + drawn,
                    unseen.2 + 1,
                );
            }
            m += 1;
        }
        // A second pass at this θ (below) compares its rows with these, which the
        // system does not hold beyond `kept`.
        self.st.factored = kept.min(m);
        self.st.prior_misfit = (self.st.has_prior && unseen.1 > T::ZERO && unseen.2 >= n)
            .then(|| (unseen.0 / unseen.1).sqrt());
        if self.st.has_prior && spread > T::ZERO && misfit > T::from_f64(REFUTED).sq() * spread {
            self.st.has_prior = false;
            return self.fit(value, scale, cliff);
        }
        // The prior predicts every point to rounding (EXACT): it is the fit, which could
        // change it by no more than that. The system is not factored, so the next fit
        // keeps none of its rows.
        let exact = self.st.has_prior
            && !self.st.noisy
            && !self.st.unseeded
            && spread > T::ZERO
            && misfit <= T::from_f64(EXACT).sq() * spread;
        if exact {
            self.st.factored = 0;
            let noise = model::noise_level(&self.mem.sw[..m], misfit, shape.coefficients(n));
            return Some((noise, m));
        }
        let ridge = self.ridge();
        let fitted = model::fit(
            shape,
            T::from_f64(model::deviation_share(shape, n, axis_free)),
            n,
            m,
            self.mem.u,
            self.mem.sw,
            self.st.noisy.then_some(&self.mem.gid[..m]),
            self.mem.r,
            model::Scratch {
                gram: self.mem.gram,
                kp: self.mem.kp,
                norms: self.mem.norms,
                schur: self.mem.schur,
                beta: self.mem.beta,
                rows: self.mem.sw.len(),
            },
            self.mem.g,
            self.mem.h,
            ridge,
            self.st.factored,
        );
        self.st.factored = if fitted.is_some() { m } else { 0 };
        fitted.map(|noise| (noise, m))
    }

    /// Writes the prior, moved to θ and σ with values scaled by `scale`, to the model
    /// (`g`, `h`, standardised units); zero without one.
    pub(super) fn move_prior(&mut self, scale: T) {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let shape = self.shape;
        let hl = shape.hessian_len(n);
        if self.st.has_prior && self.st.saved.metric == self.st.metric_changes {
            // The prior saved at σₚ and Fₚ under this metric, moved to θ, σ and F:
            // g = (σFₚ/(σₚF))(gₚ + Hₚ L⁻¹(θ − c₀)/σₚ), H = (σ²Fₚ/(σₚ²F))Hₚ, O(n²).
            let (sigma_p, scale_p) = (self.st.saved.sigma, self.st.saved.scale);
            metric::whiten(shape, self.mem.li, self.theta, self.mem.c0, self.mem.s);
            for si in self.mem.s.iter_mut() {
                *si /= sigma_p;
            }
            shape.apply(self.mem.hp, self.mem.s, self.mem.g);
            let ratio = sigma * scale_p / (sigma_p * scale);
            for (gi, &gp) in self.mem.g.iter_mut().zip(self.mem.gp.iter()) {
                *gi = ratio * (gp + *gi);
            }
            let ratio = ratio * sigma / sigma_p;
            for (hi, &hp) in self.mem.h[..hl].iter_mut().zip(self.mem.hp.iter()) {
                *hi = ratio * hp;
            }
        } else if self.st.has_prior {
            // The prior in standardised units: g = σLᵀ(g₀ + H₀(θ − c₀))/F, H = σ²LᵀH₀L/F.
            self.prior_to_parameters();
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
    }

    /// The ridge of the next fit ([`Ridge`]); all but [`Ridge::Prior`] make the fit
    /// reproduce a quadratic where its points determine it, and a survey's pairs stay on
    /// their lines to let them. A full model's fits where the memory determines the model
    /// (n ≤ 14), and above that its first fit after a survey that has no prior: the
    /// survey's pairs fix the model along their lines and the least change from zero
    /// fixes the rest, so that a round bowl's first model is exact at every n. Later fits
    /// of a full model above n = 14, and every fit of a diagonal one, lean on the prior
    /// they carry and keep its weakly determined part.
    pub(super) fn ridge(&self) -> Ridge {
        if memory_determines_model(self.shape, self.theta.len()) {
            Ridge::Determined
        } else if self.shape == Shape::Full && !self.st.has_prior {
            Ridge::Survey
        } else {
            Ridge::Prior
        }
    }

    /// −(gᵀs + ½sᵀHs) of the model for the step in `s` (standardised units).
    pub(super) fn predicted_decrease(&self) -> T {
        -(dot(self.mem.g, self.mem.s) + self.shape.half_quadratic(self.mem.h, self.mem.s))
    }

    /// Keeps this iteration's model, at θ in the standardised units of σ, the scale F and
    /// the metric, as the next prior. Its parameter units, which a change of the metric
    /// needs, wait for [`Auto::prior_to_parameters`]. A model with a coefficient that is
    /// not finite is no prior: every fit from it would fail.
    pub(super) fn save_prior(&mut self, scale: T, sigma: T) {
        let hl = self.shape.hessian_len(self.theta.len());
        if self
            .mem
            .g
            .iter()
            .chain(&self.mem.h[..hl])
            .any(|c| !c.is_finite())
        {
            self.st.has_prior = false;
            return;
        }
        self.mem.c0.copy_from_slice(self.theta);
        self.mem.gp.copy_from_slice(self.mem.g);
        self.mem.hp.copy_from_slice(&self.mem.h[..hl]);
        self.st.saved = SavedPrior {
            sigma,
            scale,
            metric: self.st.metric_changes,
        };
        self.st.in_parameters = false;
        self.st.has_prior = true;
    }

    /// Puts the saved prior in parameter units at c₀, g₀ = Fₚ L⁻ᵀgₚ/σₚ and
    /// H₀ = Fₚ L⁻ᵀHₚL⁻¹/σₚ² (O(n³) for a full model), unless they are there already;
    /// L must still be the metric it was saved under.
    pub(super) fn prior_to_parameters(&mut self) {
        if !self.st.has_prior || self.st.in_parameters {
            return;
        }
        let n = self.theta.len();
        let SavedPrior { sigma, scale, .. } = self.st.saved;
        metric::apply_transposed(self.shape, self.mem.li, self.mem.gp, self.mem.g0);
        for g0 in self.mem.g0.iter_mut() {
            *g0 = scale * *g0 / sigma;
        }
        metric::congruence(
            self.shape,
            self.mem.li,
            self.mem.hp,
            n,
            self.mem.a,
            self.mem.h0,
        );
        for k in 0..self.shape.hessian_len(n) {
            self.mem.h0[k] = scale * self.mem.h0[k] / (sigma * sigma);
        }
        self.st.in_parameters = true;
    }
}
