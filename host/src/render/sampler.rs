//! Counter-based sample generation: every uniform number is a pure function of
//! (frame seed, pixel index, sample index, dimension).
//!
//! Nothing is carried from one pixel or sample to the next, so an image does not depend
//! on how pixels are spread over threads, and two renders with the same frame seed (the
//! two halves of an antithetic pair) see exactly the same noise.
//!
//! Two sequences are offered ([`Sequence`]):
//! * [`Sequence::Independent`]: each number is a 64-bit hash of its four coordinates;
//! * [`Sequence::Kronecker`]: the first [`KRONECKER_DIMS`] dimensions follow the R_d
//!   Kronecker sequence x_n = frac(s + n·α) (Roberts 2018, α_i = φ_d^−(i+1), φ_d the real
//!   root of x^(d+1) = x + 1) with a per-pixel random shift s (Cranley–Patterson
//!   rotation); later dimensions are hashed as above. Each point is still uniform on the
//!   unit cube, so estimates stay unbiased, while the samples of a pixel fill the pixel
//!   area and the light's area evenly: for the low-dimensional integrands of direct
//!   lighting this lowers the error markedly at equal sample count.
//!
//! The hash is SplitMix64's finaliser (Steele, Lea & Flood 2014), applied once per
//! coordinate; the top 24 bits make an `f32` in [0, 1).

/// Which low-discrepancy construction drives the first dimensions of each sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Sequence {
    /// Independent uniform numbers (plain Monte Carlo).
    Independent,
    /// Randomly shifted R_d Kronecker sequence over the first [`KRONECKER_DIMS`]
    /// dimensions, independent numbers after that. Default.
    #[default]
    Kronecker,
}

/// Dimensions covered by the Kronecker sequence (d of R_d): the two pixel coordinates
/// and the six numbers of the first path vertex.
pub const KRONECKER_DIMS: usize = 8;

/// α_i = φ₈^−(i+1) mod 1, φ₈ = 1.085070245491451… the real root of x⁹ = x + 1
/// (checked by a unit test).
const R8_ALPHA: [f64; KRONECKER_DIMS] = [
    0.921_599_319_633_982_9,
    0.849_345_305_949_820_2,
    0.782_756_056_097_671_3,
    0.721_387_448_738_993_6,
    0.664_830_181_950_351_3,
    0.612_707_043_357_580_7,
    0.564_670_394_293_295_7,
    0.520_399_851_198_154_1,
];

/// SplitMix64's output function: a bijective 64-bit mix with full avalanche.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The top 24 bits of `bits` as an `f32` in [0, 1) (exactly representable).
#[inline]
fn unit_f32(bits: u64) -> f32 {
    (bits >> 40) as f32 * (1.0 / 16_777_216.0)
}

#[inline]
fn salt(dim: usize) -> u64 {
    (dim as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// The per-pixel part of the sample streams: the pixel's key and its Kronecker shifts,
/// hashed once per pixel rather than once per sample.
#[derive(Clone, Copy, Debug)]
pub struct PixelSampler {
    sequence: Sequence,
    /// Hash of (frame seed, pixel).
    pixel_key: u64,
    /// Cranley–Patterson shifts s of the Kronecker dimensions.
    shifts: [f64; KRONECKER_DIMS],
}

impl PixelSampler {
    /// The sampler of pixel `pixel` in the frame with seed `seed`.
    #[inline]
    pub fn new(sequence: Sequence, seed: u64, pixel: u64) -> PixelSampler {
        let pixel_key = mix64(mix64(seed) ^ pixel);
        let mut shifts = [0.0; KRONECKER_DIMS];
        if sequence == Sequence::Kronecker {
            for (dim, s) in shifts.iter_mut().enumerate() {
                *s = (mix64(pixel_key ^ salt(dim)) >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0);
            }
        }
        PixelSampler {
            sequence,
            pixel_key,
            shifts,
        }
    }

    /// The stream of sample `index` of this pixel.
    #[inline]
    pub fn sample(&self, index: u32) -> SampleStream<'_> {
        SampleStream {
            pixel: self,
            sample_key: mix64(
                self.pixel_key ^ u64::from(index).wrapping_mul(0xD6E8_FEB8_6659_FD93),
            ),
            index: f64::from(index),
        }
    }
}

/// The uniform numbers of one sample of one pixel.
///
/// Dimensions are addressed explicitly (`get(dim)`), so a path that ends early or takes
/// a different branch does not shift the numbers its later vertices would use.
#[derive(Clone, Copy, Debug)]
pub struct SampleStream<'a> {
    pixel: &'a PixelSampler,
    /// Hash of (frame seed, pixel, sample): keys the independent dimensions.
    sample_key: u64,
    /// Sample index n within the pixel.
    index: f64,
}

impl SampleStream<'_> {
    /// The uniform number in [0, 1) of dimension `dim`.
    #[inline]
    pub fn get(&self, dim: usize) -> f32 {
        if self.pixel.sequence == Sequence::Kronecker && dim < KRONECKER_DIMS {
            let x = self.pixel.shifts[dim] + self.index * R8_ALPHA[dim];
            // x ≥ 0, so truncation is ⌊x⌋ (and inlines, unlike `floor` without SSE4.1);
            // x − ⌊x⌋ is in [0, 1), but rounding to f32 may give 1.0: clamp below 1.
            ((x - (x as u64) as f64) as f32).min(1.0 - f32::EPSILON / 2.0)
        } else {
            unit_f32(mix64(self.sample_key ^ salt(dim)))
        }
    }

    /// Dimensions `dim` and `dim + 1` as a pair.
    #[inline]
    pub fn get2(&self, dim: usize) -> (f32, f32) {
        (self.get(dim), self.get(dim + 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r8_constants_match_their_definition() {
        let mut phi = 2.0f64;
        for _ in 0..200 {
            phi = (1.0 + phi).powf(1.0 / 9.0);
        }
        for (i, &alpha) in R8_ALPHA.iter().enumerate() {
            let expected = phi.powi(-(i as i32 + 1)).fract();
            assert!((alpha - expected).abs() < 1e-15, "alpha[{i}]");
        }
    }

    #[test]
    fn numbers_are_uniform_and_in_range() {
        for sequence in [Sequence::Independent, Sequence::Kronecker] {
            let mut sum = 0.0f64;
            let count = 4096;
            let pixel = PixelSampler::new(sequence, 7, 3);
            for n in 0..count {
                let s = pixel.sample(n);
                for d in 0..12 {
                    let u = s.get(d);
                    assert!((0.0..1.0).contains(&u));
                    sum += f64::from(u);
                }
            }
            let mean = sum / (12.0 * f64::from(count));
            assert!((mean - 0.5).abs() < 0.01, "{sequence:?}: mean {mean}");
        }
    }

    #[test]
    fn same_coordinates_same_number() {
        let (pa, pb, pc) = (
            PixelSampler::new(Sequence::Kronecker, 11, 5),
            PixelSampler::new(Sequence::Kronecker, 11, 5),
            PixelSampler::new(Sequence::Kronecker, 12, 5),
        );
        let (a, b, c) = (pa.sample(2), pb.sample(2), pc.sample(2));
        assert_eq!(a.get(9), b.get(9));
        assert_eq!(a.get(1), b.get(1));
        assert_ne!(a.get(1), c.get(1));
    }
}
