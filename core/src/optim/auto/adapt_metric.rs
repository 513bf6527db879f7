//! How the sampling metric C learns the objective's shape: towards the model's
//! curvature (`Auto::learn_metric`: after a step that confirmed its model, a closely
//! fitted determined model, or a stall on a shape the metric has not learnt,
//! `Auto::stalled_on_shape`), along the evolution path of accepted steps
//! (`Auto::follow_path`), and by stretching the parameter axes that a survey along them
//! found flat (`Auto::stretch_flat_axes`; `Auto::axes_orthogonal` says when a survey may
//! run along them).

use rand_core::Rng;

use super::memory::memory_determines_model;
use super::model::Shape;
use super::{
    AXIS_COHERENCE, Auto, FLAT_STRETCH, STALLED_ANISOTROPY, eigen, lower_median, metric, ties_with,
};
use crate::real::Real;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// Counts a change of the sampling metric, made next: the prior, saved in the
    /// standardised units of the metric about to go, is first put in parameter units.
    pub(super) fn change_metric(&mut self) {
        self.prior_to_parameters();
        self.st.metric_changes = self.st.metric_changes.wrapping_add(1);
    }

    /// Whether an accepted step teaches the metric its direction ([`Auto::follow_path`]):
    /// a full model on a deterministic objective that has shown neither ties nor
    /// roughness since the last restart. (On a lattice, or where f is rough at some
    /// scale, steps go where the cells or wells let them, not along a valley: on the
    /// step ellipsoid and on Rastrigin the path cost runs.)
    pub(super) fn follows_path(&self) -> bool {
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
    pub(super) fn follow_path(&mut self, sigma: T) {
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
        self.change_metric();
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

    /// Whether the run has stalled on a shape the metric has not learnt: no fit can be
    /// determined (a full model from n = 15), the last n model steps went unconfirmed,
    /// and the model's curvature in whitened coordinates is anisotropic — its largest
    /// |eigenvalue| at least [`STALLED_ANISOTROPY`] times the median one. O(n³) (the
    /// eigenvalues alone), with the trust region's scratch (`a`, `v`, `lambda`).
    pub(super) fn stalled_on_shape(&mut self) -> bool {
        let n = self.theta.len();
        if self.shape != Shape::Full
            || memory_determines_model(self.shape, n)
            || self.st.unconfirmed < n
        {
            return false;
        }
        self.mem.a[..n * n].copy_from_slice(&self.mem.h[..n * n]);
        eigen::eigenvalues(self.mem.a, self.mem.v, n);
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
    pub(super) fn axes_orthogonal(&self) -> bool {
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
    pub(super) fn stretch_flat_axes(&mut self, first_axis: usize, pairs: usize, centre: usize) {
        let n = self.theta.len();
        let Some(v) = self.st.value else {
            return;
        };
        let grain = self.grain();
        let factors = &mut self.mem.gx[..n];
        factors.fill(T::ONE);
        let (mut flat, mut moving) = (0, 0);
        for p in 0..pairs {
            let halves = &self.mem.stage_f[centre + 2 * p..centre + 2 * p + 2];
            if halves.iter().all(|&f| ties_with(f, v, grain)) {
                factors[(first_axis + p) % n] = T::from_f64(FLAT_STRETCH);
                flat += 1;
            } else if !halves.iter().any(|&f| ties_with(f, v, grain)) {
                moving += 1;
            }
        }
        if flat == 0 || moving == 0 {
            return;
        }
        self.change_metric();
        metric::stretch(
            self.mem.c,
            self.mem.l,
            self.mem.li,
            &self.mem.gx[..n],
            self.mem.a,
            self.mem.v,
        );
    }

    /// Moves the sampling metric towards the shape of the prior's curvature H₀ by
    /// `weight` of the metric's rate.
    pub(super) fn learn_metric(&mut self, weight: f64) {
        let n = self.theta.len();
        self.change_metric();
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
