//! The objective of one new shape over the current canvas, with its best colour in
//! closed form.
//!
//! θ holds only the geometry. The shape's coverage c_p ∈ [0, 1] per pixel (tiny-skia's
//! anti-aliased rasteriser into a reused [`Mask`]) and the fixed opacity α give the
//! blend weight a_p = α·c_p, and compositing colour k over the canvas C gives
//! C + a_p(k − C). The k minimising Σ_p ‖C + a_p(k − C) − T‖² is, per channel,
//!
//! k = (Σ a_p(T − C) + Σ a_p² C) / Σ a_p²,
//!
//! clamped to [0, 1] and rounded to 8 bits as rendering will. The change of the squared
//! error then follows from five sums per channel collected in the same single pass
//! over the shape's pixel bounds:
//!
//! Δ = k²Σa² − 2kΣa²C + Σa²C² + 2kΣa(C − T) − 2ΣaC(C − T).
//!
//! The loss returned is the MSE of the whole image after adding the shape, so the
//! smoothed estimators see a plateau wherever the shape covers nothing.

use hodr_core::{Batch, NoiseSeed, Objective, Real};
use rayon::prelude::*;
use tiny_skia::{FillRule, Mask, Transform};

use super::encode;
use crate::color::Rgba;
use crate::shape::{PathScratch, Shape, ShapeKind};
use crate::target::Target;

/// One thread's reusable rasterisation state.
#[derive(Debug)]
pub(crate) struct Scratch {
    mask: Mask,
    path: PathScratch,
}

impl Scratch {
    pub(crate) fn new(width: u32, height: u32) -> Self {
        Scratch {
            // Sizes are checked by the target, so creation cannot fail.
            mask: Mask::new(width, height)
                .unwrap_or_else(|| unreachable!("size checked against MAX_SIDE")),
            path: PathScratch::default(),
        }
    }
}

/// The lowest loss seen among all evaluations, and where.
#[derive(Clone, Debug)]
pub(crate) struct Best {
    pub(crate) value: f64,
    pub(crate) theta: Vec<f64>,
}

/// The loss of adding one shape of `kind` to `canvas`, as a function of its geometry.
pub(crate) struct ShapeObjective<'a> {
    pub(crate) target: &'a Target,
    /// Current canvas, opaque RGBA.
    pub(crate) canvas: &'a [u8],
    pub(crate) kind: ShapeKind,
    pub(crate) unit: f64,
    pub(crate) alpha: f32,
    /// Σ over all pixels and channels of (C − T)², 8-bit units.
    pub(crate) base: f64,
    pub(crate) scratch: &'a mut [Scratch],
    pub(crate) best: Best,
    pub(crate) evaluations: u64,
}

impl ShapeObjective<'_> {
    /// The divisor turning a squared-error sum into the MSE over RGB in [0, 1].
    fn normaliser(&self) -> f64 {
        255.0 * 255.0 * 3.0 * (self.target.width() as f64 * self.target.height() as f64)
    }

    /// MSE after adding the shape at θ, and the shape's best colour.
    pub(crate) fn evaluate_with(
        &self,
        scratch: &mut Scratch,
        theta: impl Fn(usize) -> f64,
    ) -> (f64, Rgba) {
        let shape = Shape::new(
            encode::geometry(self.kind, self.unit, theta),
            Rgba::rgb(0.0, 0.0, 0.0),
        );
        let norm = self.normaliser();
        let unchanged = (self.base / norm, Rgba::new(0.0, 0.0, 0.0, self.alpha));
        let (w, h) = (self.target.width(), self.target.height());
        let Some(rect) = shape.pixel_rect(w, h) else {
            return unchanged;
        };
        let Some(path) = shape.path(&mut scratch.path) else {
            return unchanged;
        };
        let w = w as usize;
        let (x0, x1) = (rect.x0 as usize, rect.x1 as usize);
        for y in rect.y0 as usize..rect.y1 as usize {
            scratch.mask.data_mut()[y * w + x0..y * w + x1].fill(0);
        }
        scratch
            .mask
            .fill_path(&path, FillRule::Winding, true, Transform::identity());
        scratch.path.recycle(path);

        // Per channel: Σa², Σa²C, Σa²C², Σa(C − T), ΣaC(C − T) (Σa² shared).
        let alpha = f64::from(self.alpha) / 255.0;
        let (mut saa, mut s) = (0.0, [[0.0f64; 4]; 3]);
        let mask = scratch.mask.data();
        let target = self.target.rgb();
        for y in rect.y0 as usize..rect.y1 as usize {
            for x in x0..x1 {
                let cov = mask[y * w + x];
                if cov == 0 {
                    continue;
                }
                let a = alpha * f64::from(cov);
                let aa = a * a;
                saa += aa;
                let (ci, ti) = ((y * w + x) * 4, (y * w + x) * 3);
                for (k, sk) in s.iter_mut().enumerate() {
                    let c = f64::from(self.canvas[ci + k]);
                    let d = c - f64::from(target[ti + k]);
                    sk[0] += aa * c;
                    sk[1] += aa * c * c;
                    sk[2] += a * d;
                    sk[3] += a * c * d;
                }
            }
        }
        if saa <= 0.0 {
            return unchanged;
        }
        let mut delta = 0.0;
        let mut colour = [0.0f32; 3];
        for (k, sk) in s.iter().enumerate() {
            let best = ((sk[0] - sk[2]) / saa).clamp(0.0, 255.0).round();
            delta +=
                best * best * saa - 2.0 * best * sk[0] + sk[1] + 2.0 * best * sk[2] - 2.0 * sk[3];
            colour[k] = (best / 255.0) as f32;
        }
        (
            (self.base + delta).max(0.0) / norm,
            Rgba::new(colour[0], colour[1], colour[2], self.alpha),
        )
    }

    /// [`ShapeObjective::evaluate_with`] on the first scratch (not counted).
    pub(crate) fn evaluate_at(&mut self, theta: impl Fn(usize) -> f64) -> (f64, Rgba) {
        let scratch = std::mem::take(&mut self.scratch);
        let result = self.evaluate_with(&mut scratch[0], theta);
        self.scratch = scratch;
        result
    }

    fn record<T: Real>(&mut self, theta: &[T], value: f64) {
        if value < self.best.value {
            self.best.value = value;
            for (b, t) in self.best.theta.iter_mut().zip(theta) {
                *b = t.to_f64();
            }
        }
    }
}

impl<T: Real> Objective<T> for ShapeObjective<'_> {
    fn evaluate(&mut self, theta: &[T], _seed: NoiseSeed) -> T {
        self.evaluations += 1;
        let (value, _) = self.evaluate_at(|k| theta[k].to_f64());
        self.record(theta, value);
        T::from_f64(value)
    }

    fn deterministic(&self) -> bool {
        true
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, T>, out: &mut [T]) {
        self.evaluations += out.len() as u64;
        let scratch = std::mem::take(&mut self.scratch);
        let chunk = out.len().div_ceil(scratch.len()).max(1);
        {
            let this = &*self;
            out.par_chunks_mut(chunk)
                .zip(scratch.par_iter_mut())
                .enumerate()
                .for_each(|(c, (values, s))| {
                    for (j, v) in values.iter_mut().enumerate() {
                        let p = batch.point(c * chunk + j);
                        *v = T::from_f64(this.evaluate_with(s, |k| p[k].to_f64()).0);
                    }
                });
        }
        self.scratch = scratch;
        // In index order, so the best point does not depend on scheduling.
        for (k, v) in out.iter().enumerate() {
            self.record(batch.point(k), v.to_f64());
        }
    }
}
