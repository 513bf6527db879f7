//! Caller-provided memory for the estimators.
//!
//! hodr-core never allocates. A [`Workspace`] borrows slices that the caller owns: `Vec`s
//! on a host (n = 1024 and more, chosen at run time), `static` or stack arrays on a
//! microcontroller, or a [`FixedWorkspace`] for small n known at compile time.
//!
//! Least-squares ([`crate::GradientMethod::Regression`]) estimates also need an n×n
//! moment matrix; a caller who wants them passes [`Workspace::moments_len`] more floats.
//!
//! The batch capacity `rows` is how many objective evaluations are prepared and handed
//! to [`crate::Objective::evaluate_batch`] at once. Estimates do not depend on it: points
//! are drawn in the same order whatever the capacity, so a bigger workspace only lets a
//! host evaluate more in parallel.

use crate::error::Error;
#[cfg(feature = "newton-cg")]
use crate::estimate::Lowest;
use crate::objective::NoiseSeed;
use crate::real::Real;

/// The smallest batch capacity: one group of common-random-number HVP points
/// (θ+εu ∓ τ, θ−εu ∓ τ).
pub const MIN_ROWS: usize = 4;

/// Scratch vectors of length n kept beside the batch: the two shifted centres θ ± εu of a
/// central-difference HVP, and a direction buffer.
pub const SCRATCH_VECTORS: usize = 3;

/// Borrowed buffers for estimating derivatives of an n-dimensional objective.
#[derive(Debug)]
pub struct Workspace<'a, T> {
    pub(crate) dim: usize,
    pub(crate) batch: BatchBuffers<'a, T>,
    // Part of the memory layout whatever the features, so that `buffer_len` means the
    // same in every build; only the HVP estimators read it.
    #[cfg_attr(not(feature = "hvp"), allow(dead_code))]
    pub(crate) scratch: &'a mut [T],
    /// The moment region of the regression estimators: empty, or
    /// [`Workspace::moments_len`] floats (an n×n matrix and an n-vector).
    #[cfg_attr(not(feature = "regression"), allow(dead_code))]
    pub(crate) moments: &'a mut [T],
}

/// The part of a workspace that holds one batch of evaluations.
#[derive(Debug)]
pub(crate) struct BatchBuffers<'a, T> {
    /// `rows × dim` points, row-major.
    pub(crate) points: &'a mut [T],
    /// `groups × dim` standardised offsets t = τ/σ, one per antithetic group.
    pub(crate) offsets: &'a mut [T],
    /// `rows` objective values.
    pub(crate) values: &'a mut [T],
    /// `rows` noise seeds.
    pub(crate) seeds: &'a mut [NoiseSeed],
    /// Row of the point that last gave a non-finite value, if any.
    pub(crate) failed: Option<usize>,
    /// Sum and count of the objective values of the current estimate.
    pub(crate) value_sum: T,
    pub(crate) value_count: usize,
    /// n floats: the point of the current estimate's lowest sample (meaningful only
    /// while `lowest` is set). Part of the memory layout whatever the features, so that
    /// [`Workspace::buffer_len`] does not depend on them; written only with `newton-cg`.
    #[cfg_attr(not(feature = "newton-cg"), allow(dead_code))]
    pub(crate) lowest_point: &'a mut [T],
    /// The current estimate's lowest sample, its point in `lowest_point`.
    #[cfg(feature = "newton-cg")]
    pub(crate) lowest: Option<Lowest<T>>,
    /// The highest value among the current estimate's samples.
    #[cfg(feature = "newton-cg")]
    pub(crate) highest: Option<T>,
}

impl<T: Real> BatchBuffers<'_, T> {
    /// Starts a new estimate: forgets the failed point, the value tally and the lowest
    /// and highest samples.
    pub(crate) fn begin(&mut self) {
        self.failed = None;
        self.value_sum = T::ZERO;
        self.value_count = 0;
        #[cfg(feature = "newton-cg")]
        {
            self.lowest = None;
            self.highest = None;
        }
    }

    /// Notes the first `used` rows of the batch (all finite), the first of them the
    /// estimate's evaluation number `first_sample`, as candidates for the lowest and
    /// highest sample. Ties keep the earlier sample.
    #[cfg(feature = "newton-cg")]
    pub(crate) fn note_extremes(&mut self, used: usize, first_sample: usize) {
        let dim = self.lowest_point.len();
        for row in 0..used {
            let v = self.values[row];
            if self.highest.is_none_or(|h| v > h) {
                self.highest = Some(v);
            }
            if self.lowest.is_none_or(|low| v < low.value) {
                self.lowest = Some(Lowest {
                    value: v,
                    seed: self.seeds[row],
                    sample: first_sample + row,
                });
                self.lowest_point
                    .copy_from_slice(&self.points[row * dim..(row + 1) * dim]);
            }
        }
    }

    /// Mean of the objective values of the current estimate, if any.
    pub(crate) fn mean_value(&self) -> Option<T> {
        (self.value_count > 0).then(|| self.value_sum / T::from_usize(self.value_count))
    }
}

impl<'a, T: Real> Workspace<'a, T> {
    /// Length of the `T` buffer that [`Workspace::new`] needs for dimension `dim` and
    /// batch capacity `rows`: `dim·(rows + rows/2 + 4) + rows` (the batch, its offsets
    /// and values, three scratch vectors and the lowest sample of an estimate).
    pub const fn buffer_len(dim: usize, rows: usize) -> usize {
        dim * (rows + rows / 2 + SCRATCH_VECTORS + 1) + rows
    }

    /// Floats of the optional moment region that least-squares estimates need:
    /// `dim² + dim` (the n×n sample moment matrix Σttᵀ and one n-vector).
    pub const fn moments_len(dim: usize) -> usize {
        dim * dim + dim
    }

    /// A workspace for dimension `dim` carved from one buffer. The batch capacity is
    /// `seeds.len()` evaluations. An excess of at least [`Workspace::moments_len`] floats
    /// beyond [`Workspace::buffer_len`] becomes the moment region (so least-squares
    /// estimates are possible); any other excess is left unused.
    ///
    /// # Errors
    /// [`Error::WorkspaceTooSmall`] when `seeds.len() < MIN_ROWS` or `buffer` is shorter
    /// than [`Workspace::buffer_len`]; [`Error::DimensionMismatch`] when `dim == 0`.
    pub fn new(dim: usize, buffer: &'a mut [T], seeds: &'a mut [NoiseSeed]) -> Result<Self, Error> {
        let rows = seeds.len();
        if dim == 0 {
            return Err(Error::DimensionMismatch {
                expected: 1,
                found: 0,
            });
        }
        if rows < MIN_ROWS {
            return Err(Error::WorkspaceTooSmall {
                needed: MIN_ROWS,
                available: rows,
            });
        }
        let needed = Self::buffer_len(dim, rows);
        if buffer.len() < needed {
            return Err(Error::WorkspaceTooSmall {
                needed,
                available: buffer.len(),
            });
        }
        let (points, rest) = buffer.split_at_mut(rows * dim);
        let (offsets, rest) = rest.split_at_mut(rows / 2 * dim);
        let (values, rest) = rest.split_at_mut(rows);
        let (scratch, rest) = rest.split_at_mut(SCRATCH_VECTORS * dim);
        let (lowest_point, rest) = rest.split_at_mut(dim);
        let moments_len = Self::moments_len(dim);
        let moments = if rest.len() >= moments_len {
            &mut rest[..moments_len]
        } else {
            &mut []
        };
        Ok(Workspace {
            dim,
            batch: BatchBuffers {
                points,
                offsets,
                values,
                seeds,
                failed: None,
                value_sum: T::ZERO,
                value_count: 0,
                lowest_point,
                #[cfg(feature = "newton-cg")]
                lowest: None,
                #[cfg(feature = "newton-cg")]
                highest: None,
            },
            scratch,
            moments,
        })
    }

    /// The dimension n this workspace serves.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Batch capacity: evaluations prepared per call of `evaluate_batch`.
    #[inline]
    pub fn rows(&self) -> usize {
        self.batch.seeds.len()
    }

    /// The point at which the objective last returned a non-finite value, if the latest
    /// estimate failed with [`Error::NonFiniteObjective`].
    pub fn failed_point(&self) -> Option<&[T]> {
        self.batch
            .failed
            .map(|row| &self.batch.points[row * self.dim..(row + 1) * self.dim])
    }

    /// The point of the latest estimate's lowest sample, [`crate::Report::lowest`]
    /// (length n); unspecified when that is `None`. Kept until the next estimate.
    #[cfg(feature = "newton-cg")]
    pub fn lowest_point(&self) -> &[T] {
        self.batch.lowest_point
    }

    /// The standardised offset t of the latest estimate's one antithetic pair θ ∓ σt,
    /// [`crate::Report::pair`] (length n); unspecified when that is `None`. Kept until
    /// the next estimate.
    #[cfg(feature = "newton-cg")]
    pub fn pair_offset(&self) -> &[T] {
        &self.batch.offsets[..self.dim]
    }
}

/// Inline storage for a workspace of compile-time dimension `N` and batch capacity `R`
/// (`R ≥ MIN_ROWS`). Memory: `(2R + 4)·N + R` floats and `R` seeds. It has no moment
/// region: for least-squares estimates, carve a [`Workspace`] from a buffer instead.
///
/// ```
/// use hodr_core::FixedWorkspace;
/// let mut storage = FixedWorkspace::<f32, 2, 8>::new();
/// let ws = storage.workspace();
/// assert_eq!((ws.dim(), ws.rows()), (2, 8));
/// ```
#[derive(Clone, Debug)]
pub struct FixedWorkspace<T, const N: usize, const R: usize> {
    points: [[T; N]; R],
    offsets: [[T; N]; R],
    values: [T; R],
    seeds: [NoiseSeed; R],
    scratch: [[T; N]; SCRATCH_VECTORS],
    lowest_point: [T; N],
}

impl<T: Real, const N: usize, const R: usize> FixedWorkspace<T, N, R> {
    const VALID: () = assert!(
        N > 0 && R >= MIN_ROWS,
        "FixedWorkspace needs N ≥ 1 and R ≥ MIN_ROWS"
    );

    /// Zeroed storage. Usable in a `static` initialiser.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        FixedWorkspace {
            points: [[T::ZERO; N]; R],
            offsets: [[T::ZERO; N]; R],
            values: [T::ZERO; R],
            seeds: [0; R],
            scratch: [[T::ZERO; N]; SCRATCH_VECTORS],
            lowest_point: [T::ZERO; N],
        }
    }

    /// A workspace borrowing this storage.
    pub fn workspace(&mut self) -> Workspace<'_, T> {
        Workspace {
            dim: N,
            batch: BatchBuffers {
                points: self.points.as_flattened_mut(),
                offsets: self.offsets.as_flattened_mut(),
                values: &mut self.values,
                seeds: &mut self.seeds,
                failed: None,
                value_sum: T::ZERO,
                value_count: 0,
                lowest_point: &mut self.lowest_point,
                #[cfg(feature = "newton-cg")]
                lowest: None,
                #[cfg(feature = "newton-cg")]
                highest: None,
            },
            scratch: self.scratch.as_flattened_mut(),
            moments: &mut [],
        }
    }
}

impl<T: Real, const N: usize, const R: usize> Default for FixedWorkspace<T, N, R> {
    fn default() -> Self {
        Self::new()
    }
}
