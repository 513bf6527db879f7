//! Straight-alpha RGBA colours with channels in [0, 1].

/// A colour with straight (not premultiplied) alpha. Every channel is meant to lie in
/// [0, 1]; rendering clamps values outside that range (and maps NaN to 0), so a
/// parameter vector may push a colour past its range without failing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rgba {
    /// Red, in [0, 1].
    pub r: f32,
    /// Green, in [0, 1].
    pub g: f32,
    /// Blue, in [0, 1].
    pub b: f32,
    /// Opacity, in [0, 1] (1 = opaque).
    pub a: f32,
}

impl Rgba {
    /// An opaque colour.
    pub const fn rgb(r: f32, g: f32, b: f32) -> Self {
        Rgba { r, g, b, a: 1.0 }
    }

    /// A colour with opacity `a`.
    pub const fn new(r: f32, g: f32, b: f32, a: f32) -> Self {
        Rgba { r, g, b, a }
    }

    /// An opaque colour from 8-bit channels.
    pub fn from_rgb8([r, g, b]: [u8; 3]) -> Self {
        let f = |v: u8| f32::from(v) / 255.0;
        Rgba::rgb(f(r), f(g), f(b))
    }

    /// True when no channel is NaN or infinite.
    pub fn is_finite(&self) -> bool {
        [self.r, self.g, self.b, self.a]
            .iter()
            .all(|v| v.is_finite())
    }

    /// The same colour with every channel clamped to [0, 1] (NaN becomes 0).
    pub fn clamped(self) -> Self {
        Rgba {
            r: unit(self.r),
            g: unit(self.g),
            b: unit(self.b),
            a: unit(self.a),
        }
    }

    /// The colour channels rounded to 8 bits (after clamping), alpha ignored.
    pub fn to_rgb8(self) -> [u8; 3] {
        let c = self.clamped();
        let q = |v: f32| (v * 255.0 + 0.5) as u8;
        [q(c.r), q(c.g), q(c.b)]
    }

    pub(crate) fn to_skia(self) -> tiny_skia::Color {
        let c = self.clamped();
        // In range after clamping, so the constructor cannot fail.
        tiny_skia::Color::from_rgba(c.r, c.g, c.b, c.a).unwrap_or(tiny_skia::Color::BLACK)
    }
}

/// Clamps to [0, 1]; NaN becomes 0.
pub(crate) fn unit(v: f32) -> f32 {
    if v > 0.0 { v.min(1.0) } else { 0.0 }
}
