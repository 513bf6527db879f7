//! The photograph-like test image that ships with the crate, drawn procedurally.
//!
//! A landscape: a sky graded from deep blue to a hazy horizon, a soft sun with a glow,
//! two ranges of hills with smooth silhouettes and shading, a lake that reflects the
//! sky, a few dark soft-edged trees, and a fine smooth texture (value noise) on the
//! ground. Everything is a smooth function of the pixel centre, evaluated in f64 and
//! rounded once, so the image is identical on every machine. Like a photograph it has
//! gradients, soft edges, high-contrast details and texture, which is what the
//! image-to-shapes fitting benchmark needs; unlike one, it needs no licence and no file.

use crate::error::Error;
use crate::target::Target;

/// The side used by the fitting benchmark.
pub const BENCHMARK_SIDE: u32 = 128;

/// The landscape at `size` × `size` pixels.
///
/// # Errors
/// [`Error::InvalidSize`] unless 1 ≤ size ≤ [`crate::MAX_SIDE`].
pub fn landscape(size: u32) -> Result<Target, Error> {
    crate::scene::check_size(size, size)?;
    let n = size as usize;
    let mut rgb = Vec::with_capacity(n * n * 3);
    for j in 0..n {
        for i in 0..n {
            // Pixel centre in [0, 1]², y down.
            let (x, y) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let c = shade(x, y);
            rgb.extend(c.map(|v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8));
        }
    }
    Target::from_rgb8(size, size, rgb)
}

type Colour = [f64; 3];

fn mix(a: Colour, b: Colour, t: f64) -> Colour {
    let t = t.clamp(0.0, 1.0);
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Deterministic lattice hash in [0, 1).
fn hash(i: i64, j: i64) -> f64 {
    let mut h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h ^= h >> 29;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 32;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Smooth value noise at frequency `f`.
fn noise(x: f64, y: f64, f: f64) -> f64 {
    let (u, v) = (x * f, y * f);
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = (u - i, v - j);
    let (su, sv) = (fu * fu * (3.0 - 2.0 * fu), fv * fv * (3.0 - 2.0 * fv));
    let (i, j) = (i as i64, j as i64);
    let a = hash(i, j) + (hash(i + 1, j) - hash(i, j)) * su;
    let b = hash(i, j + 1) + (hash(i + 1, j + 1) - hash(i, j + 1)) * su;
    a + (b - a) * sv
}

fn sky(x: f64, y: f64) -> Colour {
    let zenith = [0.18, 0.35, 0.72];
    let horizon = [0.86, 0.80, 0.70];
    let mut c = mix(zenith, horizon, (y / 0.55).powf(1.6));
    // Sun at (0.72, 0.22) with a wide glow.
    let d = ((x - 0.72).powi(2) + (y - 0.22).powi(2)).sqrt();
    c = mix(c, [1.0, 0.93, 0.75], 0.55 * (-d * d / 0.02).exp());
    c = mix(c, [1.0, 0.98, 0.9], 1.0 - smoothstep(0.045, 0.06, d));
    // Soft clouds.
    let cloud =
        smoothstep(0.55, 0.8, noise(x * 1.6, y * 4.0, 3.0)) * (1.0 - smoothstep(0.2, 0.45, y));
    mix(c, [0.95, 0.95, 0.97], 0.7 * cloud)
}

fn shade(x: f64, y: f64) -> Colour {
    let far =
        0.50 - 0.06 * (x * 7.0 + 0.4).sin() - 0.03 * (x * 17.0).sin() - 0.02 * noise(x, 0.0, 9.0);
    let near = 0.66 - 0.10 * (x * 3.4 + 2.0).sin() - 0.025 * (x * 23.0 + 1.0).sin();
    let shore = 0.80 + 0.02 * (x * 11.0).sin();
    let mut c = sky(x, y);
    if y > far {
        // Distant hills: hazy blue-green, lighter towards the top.
        let t = smoothstep(far, far + 0.15, y);
        let hill = mix([0.45, 0.55, 0.62], [0.30, 0.42, 0.40], t);
        c = mix(c, hill, smoothstep(far, far + 0.008, y));
    }
    if y > near {
        let t = (y - near) / 0.3;
        let grass = mix([0.38, 0.55, 0.20], [0.20, 0.36, 0.10], t);
        let tex = 0.10 * (noise(x, y, 24.0) - 0.5) + 0.06 * (noise(x, y, 61.0) - 0.5);
        let lit = 0.08 * (x * 3.4 + 2.0).cos();
        let g = grass.map(|v| v * (1.0 + tex + lit));
        c = mix(c, g, smoothstep(near, near + 0.01, y));
    }
    if y > shore && x > 0.38 {
        // A lake reflecting the sky, with ripples; soft left bank.
        let mirror = sky(x, 2.0 * shore - y);
        let ripple = 0.06 * ((y - shore) * 140.0 + 6.0 * noise(x, y, 8.0)).sin();
        let water = mix(mirror, [0.10, 0.24, 0.38], 0.6).map(|v| v * (1.0 + ripple));
        let edge = smoothstep(shore, shore + 0.01, y) * smoothstep(0.38, 0.45, x);
        c = mix(c, water, edge);
    }
    // Trees: dark ellipses with soft edges and a trunk, standing on the near hills.
    for &(tx, ty, r) in &[(0.12, 0.70, 0.06), (0.22, 0.74, 0.045), (0.86, 0.72, 0.05)] {
        let d = (((x - tx) / (0.7 * r)).powi(2) + ((y - ty) / r).powi(2)).sqrt();
        let foliage = mix(
            [0.10, 0.24, 0.08],
            [0.22, 0.40, 0.15],
            (ty - y) / r * 0.5 + 0.3 * noise(x, y, 40.0),
        );
        c = mix(c, foliage, 1.0 - smoothstep(0.85, 1.0, d));
        let trunk = (x - tx).abs() < 0.008 && y > ty + 0.6 * r && y < ty + 1.6 * r;
        if trunk {
            c = [0.25, 0.17, 0.10];
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn landscape_is_deterministic_and_varied() {
        let a = landscape(64).unwrap();
        assert_eq!(a, landscape(64).unwrap());
        let distinct: std::collections::HashSet<_> = a.rgb().chunks(3).collect();
        assert!(distinct.len() > 500, "{} colours", distinct.len());
        assert!(landscape(0).is_err());
    }
}
