//! Inline storage for an [`Auto`] run whose dimension is known at compile time.

use rand_core::Rng;

use super::{Auto, buffer_len};
use crate::error::Error;
use crate::real::Real;

/// θ and the buffer of an [`Auto`] run in dimension `N`, inline: `N + LEN` floats, and
/// usable in a `static` initialiser. `LEN` must be at least [`buffer_len`]`(N)`; a
/// smaller one does not compile. Everything else the run keeps between iterations lives
/// in the [`Auto`] value itself, whose size does not depend on n. It holds the default
/// model's buffer, which from n = 15 to [`FULL_MODEL_MAX_DIM`](super::FULL_MODEL_MAX_DIM)
/// is the full model's (1 111 904 floats at n = 100, 13 times the diagonal model's); a
/// run that wants the diagonal model there passes a buffer of
/// [`AutoModel::Diagonal`](super::AutoModel::Diagonal)`.buffer_len(n)` floats to
/// [`Auto::with_model`].
///
/// ```
/// use hodr_core::optim::auto::{FixedAuto, buffer_len};
/// use rand_xoshiro::Xoshiro128PlusPlus;
/// use rand_xoshiro::rand_core::SeedableRng;
///
/// let mut memory = FixedAuto::<f32, 2, { buffer_len(2) }>::new();
/// let rng = Xoshiro128PlusPlus::seed_from_u64(1);
/// let mut auto = memory.start(&[1.0, -2.0], 0.5, rng)?;
/// let mut f = |x: &[f32]| x[0] * x[0] + 10.0 * x[1] * x[1];
/// auto.run(&mut f, |_, _| {})?;
/// assert!(auto.theta().iter().all(|v| v.abs() < 1e-3));
/// # Ok::<(), hodr_core::Error>(())
/// ```
///
/// ```compile_fail
/// // 10 floats are too few for n = 2.
/// let memory = hodr_core::optim::auto::FixedAuto::<f32, 2, 10>::new();
/// ```
#[derive(Clone, Debug)]
pub struct FixedAuto<T, const N: usize, const LEN: usize> {
    theta: [T; N],
    buffer: [T; LEN],
}

impl<T: Real, const N: usize, const LEN: usize> FixedAuto<T, N, LEN> {
    const VALID: () = assert!(
        N > 0 && LEN >= buffer_len(N),
        "FixedAuto needs N ≥ 1 and LEN ≥ buffer_len(N)"
    );

    /// Zeroed storage.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        FixedAuto {
            theta: [T::ZERO; N],
            buffer: [T::ZERO; LEN],
        }
    }

    /// A run from `x0` with scale `sigma0` and default options, in this storage (θ starts
    /// as a copy of `x0` and ends as the best point found).
    ///
    /// # Errors
    /// As [`Auto::new`].
    pub fn start<R: Rng>(
        &mut self,
        x0: &[T; N],
        sigma0: T,
        rng: R,
    ) -> Result<Auto<'_, T, R>, Error> {
        self.theta = *x0;
        Auto::new(&mut self.theta, sigma0, &mut self.buffer, rng)
    }
}

impl<T: Real, const N: usize, const LEN: usize> Default for FixedAuto<T, N, LEN> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form in [`buffer_len`]'s docs is what the regions add up to.
    #[test]
    fn the_documented_formula_is_the_buffer_length() {
        for n in 1..300 {
            let m = super::super::history_len(super::super::model::Shape::for_dim(n), n);
            let full = n <= super::super::FULL_MODEL_MAX_DIM;
            let (h, f, p) = if full {
                (n * n, n * n, n + 1)
            } else {
                (n, 0, 1)
            };
            let r = 2 * n.min(m / 2) + 2;
            let formula = m * (3 * n + 9)
                + m * m
                + m * p
                + p * p
                + p
                + 32 * n
                + 8 * h
                + r * (n + 1)
                + n * n
                + 2 * f;
            assert_eq!(buffer_len(n), formula, "n = {n}");
        }
    }
}
