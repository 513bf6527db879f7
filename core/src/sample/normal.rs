//! The standard normal distribution N₁(0, 1): quantile, CDF and density.
//!
//! The quantile is Wichura's algorithm AS 241 (Applied Statistics 37(3), 1988): rational
//! approximations on three ranges of p. `f64` uses PPND16 (about 1e-16 relative), `f32`
//! PPND7 (about 1e-7, so an `f32` build never needs software doubles). Inverse-CDF
//! sampling keeps a sample a monotone function of its uniform number, which is what
//! antithetic pairs and low-discrepancy sequences need; Box–Muller would not.

use crate::real::Real;

/// Φ⁻¹(ξ): the standard normal quantile.
///
/// ξ is clamped to [`Real::MIN_POSITIVE`], 1 − ε/2] first (NaN is treated as 0), so the
/// result is finite for every input: about −37.5 (`f64`) or −13 (`f32`) at ξ = 0.
#[inline]
pub fn quantile<T: Real>(xi: T) -> T {
    T::normal_quantile_open(clamp_open(xi))
}

/// Φ(x) = ½·erfc(−x/√2).
#[inline]
pub fn cdf<T: Real>(x: T) -> T {
    T::HALF * (-x * T::from_f64(core::f64::consts::FRAC_1_SQRT_2)).erfc()
}

/// φ(x) = e^{−x²/2}/√(2π).
#[inline]
pub fn pdf<T: Real>(x: T) -> T {
    (-T::HALF * x.sq()).exp() * T::from_f64(0.398_942_280_401_432_7)
}

/// Clamps ξ into the open unit interval, to the extreme representable values.
#[inline]
pub(crate) fn clamp_open<T: Real>(xi: T) -> T {
    xi.max(T::MIN_POSITIVE).min(T::ONE - T::HALF * T::EPSILON)
}

/// AS 241 PPND16 for p ∈ (0, 1).
// The published coefficients are kept digit for digit, so they can be checked against
// the paper; rounding to f64 happens at compile time.
#[allow(clippy::excessive_precision)]
pub(crate) fn ppnd16(p: f64) -> f64 {
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180625 - q * q;
        let num = ((((((2.509_080_928_730_122_7e3 * r + 3.343_057_558_358_812_8e4) * r
            + 6.726_577_092_700_870_1e4)
            * r
            + 4.592_195_393_154_987_1e4)
            * r
            + 1.373_169_376_550_946_1e4)
            * r
            + 1.971_590_950_306_551_4e3)
            * r
            + 1.331_416_678_917_843_8e2)
            * r
            + 3.387_132_872_796_366_6;
        let den = ((((((5.226_495_278_852_854_6e3 * r + 2.872_908_573_572_194_3e4) * r
            + 3.930_789_580_009_271e4)
            * r
            + 2.121_379_430_158_659_7e4)
            * r
            + 5.394_196_021_424_751e3)
            * r
            + 6.871_870_074_920_579e2)
            * r
            + 4.231_333_070_160_091e1)
            * r
            + 1.0;
        return q * num / den;
    }
    let tail = if q < 0.0 { p } else { 1.0 - p };
    let mut r = libm::sqrt(-libm::log(tail));
    let x = if r <= 5.0 {
        r -= 1.6;
        let num = ((((((7.745_450_142_783_414e-4 * r + 2.272_384_498_926_918_4e-2) * r
            + 2.417_807_251_774_506e-1)
            * r
            + 1.270_458_252_452_368_4)
            * r
            + 3.647_848_324_763_204_5)
            * r
            + 5.769_497_221_460_691)
            * r
            + 4.630_337_846_156_545)
            * r
            + 1.423_437_110_749_683_5;
        let den = ((((((1.050_750_071_644_416_8e-9 * r + 5.475_938_084_995_345e-4) * r
            + 1.519_866_656_361_645_7e-2)
            * r
            + 1.481_039_764_274_800_8e-1)
            * r
            + 6.897_673_349_851e-1)
            * r
            + 1.676_384_830_183_803_8)
            * r
            + 2.053_191_626_637_758_8)
            * r
            + 1.0;
        num / den
    } else {
        r -= 5.0;
        let num = ((((((2.010_334_399_292_288_1e-7 * r + 2.711_555_568_743_487_6e-5) * r
            + 1.242_660_947_388_078_4e-3)
            * r
            + 2.653_218_952_657_612_3e-2)
            * r
            + 2.965_605_718_285_049e-1)
            * r
            + 1.784_826_539_917_291_3)
            * r
            + 5.463_784_911_164_114)
            * r
            + 6.657_904_643_501_103_8;
        let den = ((((((2.044_263_103_389_939_8e-15 * r + 1.421_511_758_316_445_9e-7) * r
            + 1.846_318_317_510_054_7e-5)
            * r
            + 7.868_691_311_456_133e-4)
            * r
            + 1.487_536_129_085_061_5e-2)
            * r
            + 1.369_298_809_227_358e-1)
            * r
            + 5.998_322_065_558_88e-1)
            * r
            + 1.0;
        num / den
    };
    if q < 0.0 { -x } else { x }
}

/// AS 241 PPND7 for p ∈ (0, 1), in single precision.
#[allow(clippy::excessive_precision)]
pub(crate) fn ppnd7(p: f32) -> f32 {
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180625 - q * q;
        let num = ((5.910_937_5e1 * r + 1.592_911_3e2) * r + 5.043_427e1) * r + 3.387_132_7;
        let den = ((6.718_756_4e1 * r + 7.875_776e1) * r + 1.789_517e1) * r + 1.0;
        return q * num / den;
    }
    let tail = if q < 0.0 { p } else { 1.0 - p };
    let mut r = Real::sqrt(-libm::logf(tail));
    let x = if r <= 5.0 {
        r -= 1.6;
        let num = ((1.702_382_1e-1 * r + 1.306_728_5) * r + 2.756_815_4) * r + 1.423_437_3;
        let den = (1.202_113_3e-1 * r + 7.370_016_4e-1) * r + 1.0;
        num / den
    } else {
        r -= 5.0;
        let num = ((1.733_720_4e-2 * r + 4.286_829_4e-1) * r + 3.081_226_3) * r + 6.657_905;
        let den = (1.225_820_2e-2 * r + 2.419_789_4e-1) * r + 1.0;
        num / den
    };
    if q < 0.0 { -x } else { x }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ(Φ⁻¹(ξ)) = ξ to 1e-12 (f64) and 1e-5 (f32) absolute, and to 1e-9 relative in the
    /// lower tail of f64 where absolute error says nothing.
    #[test]
    fn round_trip() {
        for i in 1..20_000 {
            let xi = i as f64 / 20_000.0;
            let x = quantile(xi);
            assert!((cdf(x) - xi).abs() < 1e-12, "f64 ξ={xi}");
            let xf = xi as f32;
            assert!((cdf(quantile(xf)) - xf).abs() < 1e-5, "f32 ξ={xf}");
        }
        let mut xi = 1e-300;
        while xi < 0.1 {
            let back = cdf(quantile(xi));
            assert!(((back - xi) / xi).abs() < 1e-9, "tail ξ={xi}: {back}");
            xi *= 7.3;
        }
    }

    #[test]
    fn monotone_and_finite_at_the_ends() {
        let probes64 = [
            0.0,
            f64::MIN_POSITIVE,
            1e-300,
            0.5 - f64::EPSILON,
            0.5,
            0.5 + f64::EPSILON,
            1.0 - f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
            1.0,
        ];
        let mut last = f64::NEG_INFINITY;
        for &xi in &probes64 {
            let x = quantile(xi);
            assert!(x.is_finite() && x >= last, "ξ={xi} → {x}");
            last = x;
        }
        assert_eq!(quantile(0.5f64), 0.0);
        let probes32 = [
            0.0f32,
            f32::MIN_POSITIVE,
            0.5 - f32::EPSILON,
            0.5,
            0.5 + f32::EPSILON,
            1.0 - f32::EPSILON,
            1.0,
        ];
        let mut last = f32::NEG_INFINITY;
        for &xi in &probes32 {
            let x = quantile(xi);
            assert!(x.is_finite() && x >= last, "ξ={xi} → {x}");
            last = x;
        }
        // Dense monotonicity sweep across the region boundaries (0.075, 0.925, e^-25).
        let mut prev = quantile(1e-12f64);
        for i in 1..100_000 {
            let x = quantile(i as f64 / 100_000.0);
            assert!(x > prev);
            prev = x;
        }
        let mut prev = quantile(1e-7f32);
        for i in 1..100_000 {
            let x = quantile(i as f32 / 100_000.0);
            assert!(x >= prev);
            prev = x;
        }
    }

    #[test]
    fn symmetric() {
        for i in 1..1024 {
            let xi = i as f64 / 2048.0; // exact, so 1 − ξ is exact
            assert_eq!(quantile(xi), -quantile(1.0 - xi), "ξ={xi}");
        }
    }
}
