//! Coordinates searched in log₁₀: a parameter that matters in proportion to its size (a
//! rate constant, a learning rate, a regularisation weight) and whose box spans decades.
//!
//! An optimiser searches u, with uᵢ = log₁₀ xᵢ on the coordinates a mask marks and
//! uᵢ = xᵢ on the others, so that a step along a marked coordinate is a factor and a
//! scale there is in decades (1: a factor of 10). [`to_log`] and [`bounds_to_log`] put
//! the start and the box in u, [`LogScaled`] hands the objective x = 10^u, and
//! [`from_log`] turns the optimiser's result back into x:
//!
//! ```
//! use hodr_core::Objective;
//! use hodr_core::log_scale::{LogScaled, bounds_to_log, from_log, to_log};
//!
//! // A rate k in [1e-8, 1] and a share in [0, 1].
//! let f = |x: &[f64]| (x[0].log10() + 5.0).powi(2) + (x[1] - 0.5).powi(2);
//! let mask = [true, false];
//! let (mut lower, mut upper) = ([1e-8, 0.0], [1.0, 1.0]);
//! bounds_to_log(&mask, &mut lower, &mut upper)?;
//! assert_eq!((lower, upper), ([-8.0, 0.0], [0.0, 1.0]));
//! let mut theta: [f64; 2] = [1e-3, 0.9];
//! to_log(&mask, &mut theta)?;
//! assert!((theta[0] + 3.0).abs() < 1e-12);
//! // An optimiser searches θ in that box (`Auto::new(&mut theta, …).with_bounds(&lower,
//! // &upper)`, σ₀ in decades at the rate) on `objective`, which hands f the rate itself:
//! let mut points = [0.0; 2];
//! let mut objective = LogScaled::new(f, &mask, &mut points)?;
//! assert!((objective.evaluate(&theta, 0) - f(&[1e-3, 0.9])).abs() < 1e-12);
//! from_log(&mask, &mut theta);
//! assert!((theta[0] / 1e-3 - 1.0).abs() < 1e-12 && theta[1] == 0.9);
//! # Ok::<(), hodr_core::Error>(())
//! ```

use crate::error::Error;
use crate::objective::{Batch, NoiseSeed, Objective};
use crate::real::Real;

/// Whether x > 0 (false for NaN).
fn positive<T: Real>(x: T) -> bool {
    x.partial_cmp(&T::ZERO) == Some(core::cmp::Ordering::Greater)
}

/// Checks that `len` (a slice's length) is the mask's n.
fn same_dim(mask: &[bool], len: usize) -> Result<(), Error> {
    if len == mask.len() {
        Ok(())
    } else {
        Err(Error::DimensionMismatch {
            expected: mask.len(),
            found: len,
        })
    }
}

/// Writes u for the point `x` in place: log₁₀ xᵢ where `mask[i]`, xᵢ elsewhere.
///
/// # Errors
/// [`Error::DimensionMismatch`] when `x` and `mask` differ in length;
/// [`Error::InvalidEntry`] (`"x"`, the coordinate) for a marked xᵢ that is not > 0 and
/// finite. `x` is unchanged on error.
pub fn to_log<T: Real>(mask: &[bool], x: &mut [T]) -> Result<(), Error> {
    same_dim(mask, x.len())?;
    if let Some(index) = (0..x.len()).find(|&i| mask[i] && !(positive(x[i]) && x[i].is_finite())) {
        return Err(Error::InvalidEntry { name: "x", index });
    }
    for (xi, _) in x.iter_mut().zip(mask).filter(|(_, m)| **m) {
        *xi = xi.log10();
    }
    Ok(())
}

/// Writes x for the point `u` in place: 10^uᵢ where `mask[i]`, uᵢ elsewhere (a slice
/// shorter or longer than the mask is transformed as far as both reach). 10^uᵢ is held
/// within the positive normal floats, [`Real::MIN_POSITIVE`] to [`Real::MAX`], so that
/// however far a search strays in u (σ₀ in the hundreds of decades, a start at 10³⁰⁰)
/// the objective sees a finite x > 0, never 0 or ∞; a NaN stays NaN.
pub fn from_log<T: Real>(mask: &[bool], u: &mut [T]) {
    for (ui, _) in u.iter_mut().zip(mask).filter(|(_, m)| **m) {
        let x = ui.exp10();
        *ui = if x < T::MIN_POSITIVE {
            T::MIN_POSITIVE
        } else if x > T::MAX {
            T::MAX
        } else {
            x
        };
    }
}

/// Writes a box in u in place: a marked coordinate's lower limit at or below 0 becomes
/// −∞ (x > 0 stays open), any other its log₁₀; its upper limit its log₁₀ (+∞ stays +∞).
///
/// # Errors
/// [`Error::DimensionMismatch`] when a side and `mask` differ in length;
/// [`Error::InvalidEntry`] (`"upper"`, the coordinate) for a marked upper limit at or
/// below 0 or NaN, which leaves no x > 0. The box is unchanged on error.
pub fn bounds_to_log<T: Real>(
    mask: &[bool],
    lower: &mut [T],
    upper: &mut [T],
) -> Result<(), Error> {
    same_dim(mask, lower.len())?;
    same_dim(mask, upper.len())?;
    if let Some(index) = (0..upper.len()).find(|&i| mask[i] && !positive(upper[i])) {
        return Err(Error::InvalidEntry {
            name: "upper",
            index,
        });
    }
    for i in (0..mask.len()).filter(|&i| mask[i]) {
        lower[i] = if positive(lower[i]) {
            lower[i].log10()
        } else {
            -T::INFINITY
        };
        upper[i] = upper[i].log10();
    }
    Ok(())
}

/// An objective over u that evaluates `inner` at x = 10^u on the coordinates `mask`
/// marks ([`from_log`]). A batch goes to `inner`'s [`Objective::evaluate_batch`] in
/// chunks of as many points as `points` holds (n floats each), so that an objective that
/// evaluates a batch in parallel still does; [`Objective::deterministic`] and
/// [`Objective::cancelled`] are `inner`'s. The points it is asked for must have the
/// mask's n coordinates (longer ones panic, as slice indexing does).
pub struct LogScaled<'a, T, O> {
    inner: O,
    mask: &'a [bool],
    points: &'a mut [T],
}

impl<'a, T: Real, O: Objective<T>> LogScaled<'a, T, O> {
    /// `inner` seen through `mask` (one entry per coordinate), with `points` the scratch
    /// for the points it receives: at least n floats, one point; a multiple of n holds
    /// that many points of a batch at once.
    ///
    /// # Errors
    /// [`Error::WorkspaceTooSmall`] when `points` holds fewer than n floats.
    pub fn new(inner: O, mask: &'a [bool], points: &'a mut [T]) -> Result<Self, Error> {
        if points.len() < mask.len() {
            return Err(Error::WorkspaceTooSmall {
                needed: mask.len(),
                available: points.len(),
            });
        }
        Ok(LogScaled {
            inner,
            mask,
            points,
        })
    }

    /// The objective it wraps.
    pub fn into_inner(self) -> O {
        self.inner
    }

    /// The objective it wraps, to read what it kept between evaluations.
    pub fn inner(&self) -> &O {
        &self.inner
    }

    /// The objective it wraps, mutably.
    pub fn inner_mut(&mut self) -> &mut O {
        &mut self.inner
    }

    /// Points of a batch `points` holds at once: ⌊len/n⌋, at least 1 (n = 0: any).
    fn rows(&self) -> usize {
        match self.mask.len() {
            0 => usize::MAX,
            n => self.points.len() / n,
        }
    }
}

impl<T: Real, O: Objective<T>> Objective<T> for LogScaled<'_, T, O> {
    fn evaluate(&mut self, u: &[T], seed: NoiseSeed) -> T {
        let x = &mut self.points[..u.len()];
        x.copy_from_slice(u);
        from_log(self.mask, x);
        self.inner.evaluate(x, seed)
    }

    fn evaluate_batch(&mut self, batch: &Batch<'_, T>, out: &mut [T]) {
        let n = batch.dim();
        let rows = self.rows();
        let mut first = 0;
        while first < batch.len() {
            let count = rows.min(batch.len() - first);
            let x = &mut self.points[..count * n];
            x.copy_from_slice(&batch.points()[first * n..(first + count) * n]);
            for point in x.chunks_exact_mut(n.max(1)) {
                from_log(self.mask, point);
            }
            let seeds = &batch.seeds()[first..first + count];
            // x holds count·n floats for count seeds, as `Batch::new` asks.
            if let Ok(chunk) = Batch::new(x, seeds, n) {
                self.inner
                    .evaluate_batch(&chunk, &mut out[first..first + count]);
            }
            first += count;
        }
    }

    fn deterministic(&self) -> bool {
        self.inner.deterministic()
    }

    fn cancelled(&mut self) -> bool {
        self.inner.cancelled()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MASK: [bool; 3] = [true, false, true];

    fn bowl(x: &[f64]) -> f64 {
        (libm::log10(x[0]) + 5.0).powi(2) + (x[1] - 0.5).powi(2) + (libm::log10(x[2]) + 1.0).powi(2)
    }

    /// (θ, evaluations, value) of Auto from u₀ on `objective` (budget 150).
    #[cfg(feature = "auto")]
    fn run<O: Objective<f64>>(objective: &mut O) -> ([f64; 3], usize, Option<f64>) {
        use crate::optim::{Auto, AutoOptions};
        use rand_xoshiro::Xoshiro256PlusPlus;
        use rand_xoshiro::rand_core::SeedableRng;
        const BUFFER: usize = Auto::<f64, Xoshiro256PlusPlus>::buffer_len(3);
        let (mut lower, mut upper) = ([1e-8, 0.0, 1e-6], [1.0, 1.0, 10.0]);
        bounds_to_log(&MASK, &mut lower, &mut upper).unwrap();
        let mut theta = [0.3, 0.9, 2.0];
        to_log(&MASK, &mut theta).unwrap();
        let mut buffer = [0.0; BUFFER];
        let mut auto = Auto::new(
            &mut theta,
            1.0,
            &mut buffer,
            Xoshiro256PlusPlus::seed_from_u64(7),
        )
        .unwrap()
        .with_bounds(&lower, &upper)
        .unwrap()
        .with_options(AutoOptions::default().with_max_evaluations(150).unwrap());
        auto.run(objective, |_, _| {}).unwrap();
        let (evaluations, value) = (auto.evaluations(), auto.value());
        (theta, evaluations, value)
    }

    #[test]
    #[cfg(feature = "auto")]
    fn a_run_through_log_scaled_is_the_run_on_f_of_ten_to_the_u() {
        let mut by_hand = |u: &[f64]| {
            let mut x = [u[0], u[1], u[2]];
            from_log(&MASK, &mut x);
            bowl(&x)
        };
        let expected = run(&mut by_hand);
        // One point of scratch, and room for a whole batch: the same run, in which f
        // sees x itself: inside the box, the share untransformed.
        for rows in [1, 64] {
            let mut points = [0.0; 3 * 64];
            let inside = |x: &[f64]| {
                assert!(
                    x[0] > 0.0 && x[0] <= 1.0 && (0.0..=1.0).contains(&x[1]),
                    "{x:?}"
                );
                bowl(x)
            };
            let mut scaled = LogScaled::new(inside, &MASK, &mut points[..3 * rows]).unwrap();
            assert_eq!(run(&mut scaled), expected);
        }
        let mut x = expected.0;
        from_log(&MASK, &mut x);
        assert!(
            (x[0] / 1e-5 - 1.0).abs() < 1e-3 && (x[2] / 0.1 - 1.0).abs() < 1e-3,
            "{x:?}"
        );
    }

    /// Records the size of each batch it is handed (at most four batches).
    struct Sizes([usize; 4], usize);

    impl Objective<f64> for Sizes {
        fn evaluate(&mut self, x: &[f64], _: NoiseSeed) -> f64 {
            x[0]
        }
        fn evaluate_batch(&mut self, batch: &Batch<'_, f64>, out: &mut [f64]) {
            self.0[self.1] = batch.len();
            self.1 += 1;
            for (k, v) in out.iter_mut().enumerate() {
                *v = batch.point(k)[0] + batch.seed(k) as f64;
            }
        }
    }

    #[test]
    fn a_batch_goes_to_the_objective_in_chunks_the_scratch_holds() {
        let mut u = [0.0; 21];
        for (k, point) in u.chunks_exact_mut(3).enumerate() {
            point.copy_from_slice(&[k as f64 - 3.0, 0.5, 0.0]);
        }
        let seeds: [u64; 7] = core::array::from_fn(|k| 100 * k as u64);
        let batch = Batch::new(&u, &seeds, 3).unwrap();
        let mut points = [0.0; 10];
        let mut scaled = LogScaled::new(Sizes([0; 4], 0), &MASK, &mut points).unwrap();
        let mut out = [0.0; 7];
        scaled.evaluate_batch(&batch, &mut out);
        for (k, &v) in out.iter().enumerate() {
            let x = libm::pow(10.0, k as f64 - 3.0);
            assert!(
                (v - (x + 100.0 * k as f64)).abs() <= 1e-12 * (1.0 + v.abs()),
                "{k}: {v}"
            );
        }
        let sizes = scaled.into_inner();
        assert_eq!(sizes.0[..sizes.1], [3, 3, 1]);
    }

    #[test]
    fn coordinates_round_trip_in_both_precisions() {
        let mut x = [1e-300, 3.0, 7e12];
        let start = x;
        to_log(&MASK, &mut x).unwrap();
        assert!((x[0] + 300.0).abs() < 1e-12 && x[1] == 3.0);
        assert!((x[2] - libm::log10(7e12)).abs() < 1e-12);
        from_log(&MASK, &mut x);
        for (a, b) in x.iter().zip(start) {
            assert!((a / b - 1.0).abs() < 1e-12, "{a} against {b}");
        }
        let mut y = [2.5e-30f32, -1.0, 4e20];
        to_log(&MASK, &mut y).unwrap();
        from_log(&MASK, &mut y);
        assert!((y[0] / 2.5e-30 - 1.0).abs() < 1e-5 && y[1] == -1.0);
        assert!((y[2] / 4e20 - 1.0).abs() < 1e-5);
    }

    #[test]
    fn the_objective_sees_a_finite_positive_x_however_far_u_strays() {
        let mut u = [-400.0, 5.0, 400.0];
        from_log(&MASK, &mut u);
        assert_eq!(u, [f64::MIN_POSITIVE, 5.0, f64::MAX]);
        let mut v = [-60.0f32, 0.0, 60.0];
        from_log(&MASK, &mut v);
        assert_eq!(v, [f32::MIN_POSITIVE, 0.0, f32::MAX]);
        let mut w = [f64::NAN, 0.0, 2.0];
        from_log(&MASK, &mut w);
        assert!(w[0].is_nan() && w[2] == 100.0);
    }

    #[test]
    fn bad_input_is_a_typed_error_and_changes_nothing() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let mut x = [1.0, 1.0, bad];
            assert_eq!(
                to_log(&MASK, &mut x),
                Err(Error::InvalidEntry {
                    name: "x",
                    index: 2
                })
            );
            assert_eq!(x[..2], [1.0, 1.0]);
        }
        // A negative value where the mask is false is any coordinate's.
        assert!(to_log(&MASK, &mut [1.0, -4.0, 1.0]).is_ok());
        let (mut lower, mut upper) = ([0.0, -1.0, -5.0], [1.0, 1.0, 0.0]);
        assert_eq!(
            bounds_to_log(&MASK, &mut lower, &mut upper),
            Err(Error::InvalidEntry {
                name: "upper",
                index: 2
            })
        );
        assert_eq!((lower, upper), ([0.0, -1.0, -5.0], [1.0, 1.0, 0.0]));
        upper[2] = f64::INFINITY;
        bounds_to_log(&MASK, &mut lower, &mut upper).unwrap();
        assert_eq!(lower, [f64::NEG_INFINITY, -1.0, f64::NEG_INFINITY]);
        assert_eq!(upper, [0.0, 1.0, f64::INFINITY]);
        assert_eq!(
            to_log(&MASK, &mut [1.0, 1.0]),
            Err(Error::DimensionMismatch {
                expected: 3,
                found: 2
            })
        );
        assert!(matches!(
            LogScaled::new(bowl, &MASK, &mut [0.0; 2]),
            Err(Error::WorkspaceTooSmall {
                needed: 3,
                available: 2
            })
        ));
    }
}
