//! The model's step: the trust-region subproblem in the metric's coordinates
//! (`Auto::trust_step`), and where that step would leave the box, the same problem
//! with the coordinates it pushes out held on their bounds (`Auto::held_step`).

use rand_core::Rng;

use super::memory::memory_determines_model;
use super::model::Shape;
use super::{Auto, metric, trust};
use crate::optim::vector::{axpy, dot, norm, orthogonalise};
use crate::real::Real;

impl<'b, T: Real, R: Rng> Auto<'b, T, R> {
    /// How the step reads the model's negative curvature: a full model its memory cannot
    /// determine (n from 15) reflects the faint negative eigenvalues
    /// ([`trust::Curvature::Reflect`]); a determined one, whose negative curvature the
    /// points show, and the diagonal model take H as fitted.
    fn curvature(&self) -> trust::Curvature {
        if self.shape == Shape::Full && !memory_determines_model(self.shape, self.theta.len()) {
            trust::Curvature::Reflect
        } else {
            trust::Curvature::AsFitted
        }
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
    pub(super) fn trust_step(&mut self, radius: T) -> bool {
        let n = self.theta.len();
        let sigma = self.st.sigma;
        let curvature = self.curvature();
        let m = &mut self.mem;
        if !trust::solve(
            self.shape,
            curvature,
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
    pub(super) fn held_step(&mut self, radius: T) -> bool {
        let n = self.theta.len();
        let shape = self.shape;
        let curvature = self.curvature();
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
                curvature,
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
}
