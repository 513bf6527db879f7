//! Image losses over RGB in [0, 1], computed exactly in integers.
//!
//! Rendered and target pixels are 8-bit, so a loss is an integer sum of per-channel
//! errors divided by a constant: sums over disjoint regions add exactly, which is what
//! lets the cached evaluation replace a region's error without any rounding drift, and
//! makes a plateau exactly flat.

/// Which image loss to minimise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Loss {
    /// Mean over pixels and the three channels of the squared difference, channels in
    /// [0, 1]. Default.
    #[default]
    Mse,
    /// Mean over pixels and the three channels of the absolute difference.
    L1,
}

impl Loss {
    /// Σ of the integer channel errors between an opaque RGBA row and an RGB row of the
    /// same pixel count.
    pub(crate) fn row_error(self, rgba: &[u8], rgb: &[u8]) -> u64 {
        let pixels = rgba.chunks_exact(4).zip(rgb.chunks_exact(3));
        match self {
            Loss::Mse => pixels
                .map(|(a, b)| {
                    let d = |i: usize| (i32::from(a[i]) - i32::from(b[i])).pow(2) as u32;
                    u64::from(d(0) + d(1) + d(2))
                })
                .sum(),
            Loss::L1 => pixels
                .map(|(a, b)| {
                    let d = |i: usize| a[i].abs_diff(b[i]) as u32;
                    u64::from(d(0) + d(1) + d(2))
                })
                .sum(),
        }
    }

    /// The divisor turning an error sum over `pixels` pixels into the loss.
    pub(crate) fn normaliser(self, pixels: u64) -> f64 {
        let per_channel = match self {
            Loss::Mse => 255.0 * 255.0,
            Loss::L1 => 255.0,
        };
        per_channel * 3.0 * pixels as f64
    }
}
