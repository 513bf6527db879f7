//! Counter-based sample generation: every uniform number is a pure function of
//! (frame seed, pixel index, sample index, dimension).
//!
//! Nothing is carried from one pixel or sample to the next, so an image does not depend
//! on how pixels are spread over threads, and two renders with the same frame seed (the
//! two halves of an antithetic pair) see exactly the same noise.
//!
//! Three sequences are offered ([`Sequence`]):
//! * [`Sequence::Independent`]: each number is a 64-bit hash of its four coordinates;
//! * [`Sequence::Kronecker`]: the first [`SEQUENCE_DIMS`] dimensions follow the R_d
//!   Kronecker sequence x_n = frac(s + n·α) (Roberts 2018, α_i = φ_d^−(i+1), φ_d the real
//!   root of x^(d+1) = x + 1) with a per-pixel random shift s (Cranley–Patterson
//!   rotation); later dimensions are hashed as above. Each point is still uniform on the
//!   unit cube, so estimates stay unbiased, while the samples of a pixel fill the pixel
//!   area and the light's area evenly: for the low-dimensional integrands of direct
//!   lighting this lowers the error markedly at equal sample count.
//! * [`Sequence::PaddedR2`]: the same dimensions taken as four pairs, each pair following
//!   the 2-D Kronecker sequence R₂ (α = (1/g, 1/g²), g the plastic number) with its own
//!   per-pixel shift and its own order of the samples: pair p uses index n ⊕ m_p, with a
//!   per-pixel random mask m_p below the next power of two ≥ spp (a permutation of the
//!   pixel's samples when spp is a power of two). Every 2-D projection is then a
//!   well-spread R₂ set, and different pairs are decorrelated ("padding").
//! * [`Sequence::PaddedSobol`]: the same four pairs, each the 2-D Sobol sequence with
//!   Owen scrambling, its samples in a per-pixel Owen-scrambled order (see
//!   [`super::sobol`]). For spp = 2^k each pair's points form a (0, k, 2)-net: stratified
//!   in every elementary box of area 1/spp, not only in a square grid.
//!
//! The hash is SplitMix64's finaliser (Steele, Lea & Flood 2014), applied once per
//! coordinate; the top 24 bits make an `f32` in [0, 1).

use super::sobol;

/// Which low-discrepancy construction drives the first dimensions of each sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Sequence {
    /// Independent uniform numbers (plain Monte Carlo).
    Independent,
    /// Randomly shifted R_d Kronecker sequence over the first [`SEQUENCE_DIMS`]
    /// dimensions, independent numbers after that.
    Kronecker,
    /// Randomly shifted and permuted R₂ sequences over the first [`SEQUENCE_DIMS`]
    /// dimensions in pairs, independent numbers after that.
    PaddedR2,
    /// Owen-scrambled, shuffled 2-D Sobol points over the first [`SEQUENCE_DIMS`]
    /// dimensions in pairs, independent numbers after that. Default: it gave the lowest
    /// error at equal samples on SHADOW and CBOX (docs/notes/2026-11-23-benchmarks-before-auto.md, section "hodr-host path
    /// tracer").
    #[default]
    PaddedSobol,
}

/// Dimensions covered by the low-discrepancy sequences (d of R_d for
/// [`Sequence::Kronecker`], four 2-D pairs for the padded ones): the two pixel
/// coordinates and the six numbers of the first path vertex.
pub const SEQUENCE_DIMS: usize = 8;

/// α_i = φ₈^−(i+1) mod 1, φ₈ = 1.085070245491451… the real root of x⁹ = x + 1
/// (checked by a unit test).
const R8_ALPHA: [f64; SEQUENCE_DIMS] = [
    0.921_599_319_633_982_9,
    0.849_345_305_949_820_2,
    0.782_756_056_097_671_3,
    0.721_387_448_738_993_6,
    0.664_830_181_950_351_3,
    0.612_707_043_357_580_7,
    0.564_670_394_293_295_7,
    0.520_399_851_198_154_1,
];

/// α = (1/g, 1/g²), g = 1.324717957244746… the plastic number, the real root of
/// x³ = x + 1 (checked by a unit test).
const R2_ALPHA: [f64; 2] = [0.754_877_666_246_692_7, 0.569_840_290_998_053_3];

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
    shifts: [f64; SEQUENCE_DIMS],
    /// [`Sequence::PaddedR2`]: the index mask of each dimension pair.
    masks: [u32; SEQUENCE_DIMS / 2],
    /// [`Sequence::PaddedSobol`]: per dimension pair, the seeds of the index shuffle
    /// and of the two coordinates' scrambles.
    owen: [[u32; 3]; SEQUENCE_DIMS / 2],
    /// [`Sequence::PaddedSobol`]: log₂ of the shuffled block, ⌈log₂ spp⌉.
    bits: u32,
}

impl PixelSampler {
    /// The sampler of pixel `pixel` in the frame with seed `seed`, which will draw
    /// `spp` samples (used by [`Sequence::PaddedR2`] to size its permutations).
    #[inline]
    pub fn new(sequence: Sequence, seed: u64, pixel: u64, spp: u32) -> PixelSampler {
        let pixel_key = mix64(mix64(seed) ^ pixel);
        let mut shifts = [0.0; SEQUENCE_DIMS];
        let mut masks = [0u32; SEQUENCE_DIMS / 2];
        if matches!(sequence, Sequence::Kronecker | Sequence::PaddedR2) {
            for (dim, s) in shifts.iter_mut().enumerate() {
                *s = (mix64(pixel_key ^ salt(dim)) >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0);
            }
        }
        if sequence == Sequence::PaddedR2 {
            // Masks below 2^⌈log₂ spp⌉, so that n ⊕ m stays among the first indices.
            let range = spp.max(1).next_power_of_two() - 1;
            for (pair, m) in masks.iter_mut().enumerate() {
                *m = (mix64(pixel_key ^ salt(SEQUENCE_DIMS + pair)) as u32) & range;
            }
        }
        let mut owen = [[0u32; 3]; SEQUENCE_DIMS / 2];
        if sequence == Sequence::PaddedSobol {
            for (pair, seeds) in owen.iter_mut().enumerate() {
                let a = mix64(pixel_key ^ salt(2 * SEQUENCE_DIMS + pair));
                let b = mix64(a);
                *seeds = [a as u32, (a >> 32) as u32, b as u32];
            }
        }
        PixelSampler {
            sequence,
            pixel_key,
            shifts,
            masks,
            owen,
            bits: spp.max(1).next_power_of_two().trailing_zeros(),
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
            index,
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
    index: u32,
}

impl SampleStream<'_> {
    /// The uniform number in [0, 1) of dimension `dim`.
    #[inline(always)]
    pub fn get(&self, dim: usize) -> f32 {
        let x = match self.pixel.sequence {
            Sequence::PaddedSobol if dim < SEQUENCE_DIMS => {
                let (x, y) = self.sobol_pair(dim / 2);
                return if dim.is_multiple_of(2) { x } else { y };
            }
            Sequence::Kronecker if dim < SEQUENCE_DIMS => {
                self.pixel.shifts[dim] + f64::from(self.index) * R8_ALPHA[dim]
            }
            Sequence::PaddedR2 if dim < SEQUENCE_DIMS => {
                let index = self.index ^ self.pixel.masks[dim / 2];
                self.pixel.shifts[dim] + f64::from(index) * R2_ALPHA[dim % 2]
            }
            _ => return unit_f32(mix64(self.sample_key ^ salt(dim))),
        };
        // x ≥ 0, so truncation is ⌊x⌋ (and inlines, unlike `floor` without SSE4.1);
        // x − ⌊x⌋ is in [0, 1), but rounding to f32 may give 1.0: clamp below 1.
        ((x - (x as i64) as f64) as f32).min(1.0 - f32::EPSILON / 2.0)
    }

    /// Dimensions `dim` and `dim + 1` as a pair. Pairs that start at an even dimension
    /// below [`SEQUENCE_DIMS`] are the 2-D point sets of the padded sequences.
    #[inline(always)]
    pub fn get2(&self, dim: usize) -> (f32, f32) {
        if self.pixel.sequence == Sequence::PaddedSobol
            && dim < SEQUENCE_DIMS
            && dim.is_multiple_of(2)
        {
            return self.sobol_pair(dim / 2);
        }
        (self.get(dim), self.get(dim + 1))
    }

    /// [`Sequence::PaddedSobol`]: this sample's point of dimension pair `pair`.
    #[inline(always)]
    fn sobol_pair(&self, pair: usize) -> (f32, f32) {
        let [shuffle_seed, x_seed, y_seed] = self.pixel.owen[pair];
        let index = sobol::shuffle(self.index, self.pixel.bits, shuffle_seed);
        let (x, y) = sobol::point(index, (x_seed, y_seed));
        (unit_f32_from_u32(x), unit_f32_from_u32(y))
    }
}

/// The top 24 bits of a 32-bit fraction as an `f32` in [0, 1).
#[inline]
fn unit_f32_from_u32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
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
    fn r2_constants_match_their_definition() {
        let mut g = 1.5f64;
        for _ in 0..200 {
            g = (1.0 + g).cbrt();
        }
        assert!((R2_ALPHA[0] - 1.0 / g).abs() < 1e-15);
        assert!((R2_ALPHA[1] - 1.0 / (g * g)).abs() < 1e-15);
    }

    /// With a power-of-two spp, every pair of PaddedR2 takes exactly the first spp
    /// indices of R₂ (in some order): the masks permute them.
    #[test]
    fn padded_masks_permute_power_of_two_sample_sets() {
        let spp = 16u32;
        let pixel = PixelSampler::new(Sequence::PaddedR2, 3, 9, spp);
        for &m in &pixel.masks {
            let mut seen: Vec<u32> = (0..spp).map(|n| n ^ m).collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..spp).collect::<Vec<_>>());
        }
    }

    #[test]
    fn numbers_are_uniform_and_in_range() {
        for sequence in [
            Sequence::Independent,
            Sequence::Kronecker,
            Sequence::PaddedR2,
            Sequence::PaddedSobol,
        ] {
            let mut sum = 0.0f64;
            let count = 4096;
            let pixel = PixelSampler::new(sequence, 7, 3, count);
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
            PixelSampler::new(Sequence::Kronecker, 11, 5, 4),
            PixelSampler::new(Sequence::Kronecker, 11, 5, 4),
            PixelSampler::new(Sequence::Kronecker, 12, 5, 4),
        );
        let (a, b, c) = (pa.sample(2), pb.sample(2), pc.sample(2));
        assert_eq!(a.get(9), b.get(9));
        assert_eq!(a.get(1), b.get(1));
        assert_ne!(a.get(1), c.get(1));
    }
}
