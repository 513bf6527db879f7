//! The float abstraction: one sealed trait over `f32` and `f64`, backed by `libm`.
//!
//! Every algorithm in hodr-core is generic over [`Real`], so the same code runs in double
//! precision on a workstation and in single precision on a microcontroller whose FPU has
//! no doubles. The trait is sealed: its method set can grow without breaking callers, and
//! the per-precision choices (which normal quantile approximation, how many random bits a
//! uniform number takes) stay in this file.
//!
//! Rejected: `num-traits::Float`. It would pull a larger surface than we use, and the
//! precision-specific pieces (the normal quantile and the uniform draw) still need a
//! trait of our own.

use core::fmt::{Debug, Display};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use rand_core::Rng;

use crate::sample::normal;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point type hodr-core computes in: `f32` or `f64`.
///
/// Transcendental functions come from `libm`, so results are the same on every target
/// (no dependence on the platform's C library).
pub trait Real:
    sealed::Sealed
    + Copy
    + Default
    + Debug
    + Display
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// ½.
    const HALF: Self;
    /// Machine epsilon: the gap between 1 and the next larger float.
    const EPSILON: Self;
    /// The smallest positive normal value.
    const MIN_POSITIVE: Self;
    /// The largest finite value.
    const MAX: Self;
    /// +∞.
    const INFINITY: Self;
    /// Number of significand bits (24 for `f32`, 53 for `f64`).
    const MANTISSA_DIGITS: u32;

    /// Converts from `f64`, rounding to nearest.
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64` (exact).
    fn to_f64(self) -> f64;
    /// Converts a count, rounding to nearest.
    fn from_usize(n: usize) -> Self;

    /// |x|.
    fn abs(self) -> Self;
    /// √x.
    fn sqrt(self) -> Self;
    /// eˣ.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// log₁₀ x.
    fn log10(self) -> Self;
    /// 10ˣ; at an integer x from −15 to 15 (`f32`: −7 to 7) the float nearest 10ˣ, so
    /// that it and [`Real::log10`] take decimal powers to their exponents and back.
    fn exp10(self) -> Self;
    /// ln(1 + x), accurate for small x.
    fn ln_1p(self) -> Self;
    /// ln x for x in [½, 1], to full relative precision near 1.
    ///
    /// `f64`: `ln_1p(x − 1)`, x − 1 being exact there (libm's `log` and `log1p` differ
    /// in the last bit for about 3 in 10⁸ such x). `f32`: `ln(x)` itself, which for
    /// every such x equals libm's `log1pf(x − 1)` bit for bit (tested for all of them),
    /// so that a build taking logarithms only here and in [`Real::ln`] links one.
    fn ln_near_one(self) -> Self;
    /// Complementary error function erfc(x) = 1 − erf(x).
    fn erfc(self) -> Self;
    /// The larger of two values; if one is NaN, the other; of equal values (±0), `self`.
    /// libm's `fmax` without its canonicalising multiplication by 1, which changes no
    /// non-NaN value but costs a software multiply where `f32` has no FPU.
    fn max(self, other: Self) -> Self;
    /// The smaller of two values; if one is NaN, the other; of equal values (±0), `other`.
    /// libm's `fmin` without its canonicalising multiplication by 1 (see [`Real::max`]).
    fn min(self, other: Self) -> Self;
    /// True when neither infinite nor NaN.
    fn is_finite(self) -> bool;

    /// The standard normal quantile Φ⁻¹(p) for p ∈ (0, 1).
    ///
    /// `f64`: Wichura's AS 241 (PPND16), relative error about 1e-16.
    /// `f32`: AS 241's PPND7, relative error about 1e-7, all in single precision.
    /// p must lie strictly inside (0, 1); callers clamp (see [`crate::sample::normal`]).
    fn normal_quantile_open(p: Self) -> Self;

    /// A uniform number in the open interval (0, 1) on the grid (k + ½)·2⁻ᵐ, m the
    /// significand width, so ξ and 1 − ξ are equally likely and 0 and 1 never occur.
    fn uniform_open<R: Rng + ?Sized>(rng: &mut R) -> Self;

    /// x², written once.
    #[inline]
    fn sq(self) -> Self {
        self * self
    }

    /// +1 for x > 0, −1 for x < 0, 0 for x = 0 (and for NaN).
    #[inline]
    fn sign(self) -> Self {
        if self > Self::ZERO {
            Self::ONE
        } else if self < Self::ZERO {
            -Self::ONE
        } else {
            Self::ZERO
        }
    }
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const EPSILON: Self = f64::EPSILON;
    const MIN_POSITIVE: Self = f64::MIN_POSITIVE;
    const MAX: Self = f64::MAX;
    const INFINITY: Self = f64::INFINITY;
    const MANTISSA_DIGITS: u32 = f64::MANTISSA_DIGITS;

    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn from_usize(n: usize) -> Self {
        n as f64
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabs(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::exp(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::log(self)
    }
    #[inline]
    fn log10(self) -> Self {
        libm::log10(self)
    }
    #[inline]
    fn exp10(self) -> Self {
        libm::exp10(self)
    }
    #[inline]
    fn ln_1p(self) -> Self {
        libm::log1p(self)
    }
    #[inline]
    fn ln_near_one(self) -> Self {
        libm::log1p(self - 1.0)
    }
    #[inline]
    fn erfc(self) -> Self {
        libm::erfc(self)
    }
    #[inline]
    fn max(self, other: Self) -> Self {
        if self.is_nan() || self < other {
            other
        } else {
            self
        }
    }
    #[inline]
    fn min(self, other: Self) -> Self {
        if other.is_nan() || self < other {
            self
        } else {
            other
        }
    }
    #[inline]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline]
    fn normal_quantile_open(p: Self) -> Self {
        normal::ppnd16(p)
    }
    #[inline]
    fn uniform_open<R: Rng + ?Sized>(rng: &mut R) -> Self {
        // 53 random bits k, ξ = (k + ½)·2⁻⁵³: exact, symmetric about ½, never 0 or 1.
        let k = rng.next_u64() >> 11;
        (k as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const EPSILON: Self = f32::EPSILON;
    const MIN_POSITIVE: Self = f32::MIN_POSITIVE;
    const MAX: Self = f32::MAX;
    const INFINITY: Self = f32::INFINITY;
    const MANTISSA_DIGITS: u32 = f32::MANTISSA_DIGITS;

    #[inline]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn from_usize(n: usize) -> Self {
        n as f32
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabsf(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        // Bare metal has no hardware square root in libm's reach: its software one is a
        // table and Goldschmidt iterations. Where the hard-float ABI promises an FPU
        // (the Cortex-M4F), its VSQRT; elsewhere the bit-by-bit root, a few dozen
        // instructions. Both are correctly rounded, so equal to libm's bit for bit.
        #[cfg(all(target_os = "none", target_arch = "arm", target_abi = "eabihf"))]
        return sqrt_vfp(self);
        #[cfg(all(
            target_os = "none",
            not(all(target_arch = "arm", target_abi = "eabihf"))
        ))]
        return sqrt_f32(self);
        #[cfg(not(target_os = "none"))]
        libm::sqrtf(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::expf(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::logf(self)
    }
    #[inline]
    fn log10(self) -> Self {
        libm::log10f(self)
    }
    #[inline]
    fn exp10(self) -> Self {
        libm::exp10f(self)
    }
    #[inline]
    fn ln_1p(self) -> Self {
        libm::log1pf(self)
    }
    #[inline]
    fn ln_near_one(self) -> Self {
        libm::logf(self)
    }
    #[inline]
    fn erfc(self) -> Self {
        libm::erfcf(self)
    }
    // Where `f32` is software on Arm (the Cortex-M0), each of these is two library calls
    // (NaN test and comparison) with Thumb-1's register moves around them: once out of
    // line, every use is one call (on RV32IMAC, with more argument registers, inlining
    // stays smaller).
    #[cfg_attr(
        all(target_os = "none", target_arch = "arm", not(target_abi = "eabihf")),
        inline(never)
    )]
    #[cfg_attr(
        not(all(target_os = "none", target_arch = "arm", not(target_abi = "eabihf"))),
        inline
    )]
    fn max(self, other: Self) -> Self {
        if self.is_nan() || self < other {
            other
        } else {
            self
        }
    }
    #[cfg_attr(
        all(target_os = "none", target_arch = "arm", not(target_abi = "eabihf")),
        inline(never)
    )]
    #[cfg_attr(
        not(all(target_os = "none", target_arch = "arm", not(target_abi = "eabihf"))),
        inline
    )]
    fn min(self, other: Self) -> Self {
        if other.is_nan() || self < other {
            self
        } else {
            other
        }
    }
    #[inline]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline]
    fn normal_quantile_open(p: Self) -> Self {
        normal::ppnd7(p)
    }
    #[inline]
    fn uniform_open<R: Rng + ?Sized>(rng: &mut R) -> Self {
        // 24 random bits k, ξ = (k + ½)·2⁻²⁴: exact in f32, symmetric, never 0 or 1.
        let k = rng.next_u32() >> 8;
        (k as f32 + 0.5) * (1.0 / (1u32 << 24) as f32)
    }
}

/// √x for `f32` by the FPU's VSQRT instruction (Arm VFP, present wherever the hard-float
/// ABI is): correctly rounded, as IEEE 754 prescribes, so bit for bit libm's `sqrtf` for
/// every non-NaN x (a negative x gives the default NaN, `f32::NAN`, as libm returns; a NaN
/// x its quieted self, as the host's SSE root does, where libm on bare metal returns
/// `f32::NAN`).
///
/// (`target_feature = "vfp2"` would be the direct test, but Arm's FPU features are
/// unstable, invisible to `cfg`, and without them `asm!` takes no operand in a VFP
/// register; the `eabihf` ABI passes floats in VFP registers, so it implies them. The
/// operand therefore travels in a core register and the instruction works in `s0`,
/// which the block declares clobbered.)
#[cfg(all(target_os = "none", target_arch = "arm", target_abi = "eabihf"))]
#[allow(unsafe_code)]
#[inline(never)]
fn sqrt_vfp(x: f32) -> f32 {
    let bits: u32;
    // SAFETY: VMOV and VSQRT.F32 move and compute between a core register and `s0`
    // (declared clobbered); they touch no memory, no stack and no APSR flags (only
    // FPSCR's sticky exception bits, which Rust does not model).
    unsafe {
        core::arch::asm!(
            "vmov s0, {x}",
            "vsqrt.f32 s0, s0",
            "vmov {x}, s0",
            x = inout(reg) x.to_bits() => bits,
            out("s0") _,
            options(pure, nomem, nostack, preserves_flags),
        );
    }
    f32::from_bits(bits)
}

/// √x for `f32`, correctly rounded (to nearest), in integer arithmetic: bit for bit
/// libm's `sqrtf`, whose result IEEE 754 prescribes (±0 → ±0, +∞ → +∞, and a NaN or
/// negative x → [`f32::NAN`], as libm returns).
#[cfg_attr(
    not(any(
        all(
            target_os = "none",
            not(all(target_arch = "arm", target_abi = "eabihf"))
        ),
        test
    )),
    allow(dead_code)
)]
#[inline(never)]
fn sqrt_f32(x: f32) -> f32 {
    let bits = x.to_bits();
    if bits << 1 == 0 || bits == f32::INFINITY.to_bits() {
        return x;
    }
    if bits > f32::INFINITY.to_bits() {
        return f32::NAN;
    }
    // x = m·2^(e − 23) with m a 24-bit integer, subnormals normalised (by a loop: the
    // Cortex-M0 and RV32IMAC count leading zeros only in a library routine).
    let (mut m, mut e) = (bits & 0x007f_ffff, (bits >> 23) as i32 - 127);
    if e == -127 {
        e = -126;
    } else {
        m |= 0x0080_0000;
    }
    while m < 0x0080_0000 {
        m <<= 1;
        e -= 1;
    }
    if e % 2 != 0 {
        m <<= 1;
        e -= 1;
    }
    // √x = √(m·2²⁵)·2^((e − 48)/2). Digit by digit, one bit a time from the top:
    // `root` gathers the 25 bits of ⌊√(m·2²⁵)⌋ (the significand and one bit below it),
    // `rest` the remainder, scaled to keep it in 32 bits.
    let mut rest = m << 1;
    let (mut root, mut twice_root) = (0u32, 0u32);
    let mut bit = 1u32 << 24;
    while bit != 0 {
        let trial = twice_root + bit;
        if trial <= rest {
            rest -= trial;
            twice_root = trial + bit;
            root += bit;
        }
        rest <<= 1;
        bit >>= 1;
    }
    // Round on the bit below the significand. Half-way cannot happen: that bit set with
    // nothing left over would make m·2²⁵, an even number, an odd square.
    let q = (root + 1) >> 1;
    // q·2^k for q in [2²³, 2²⁴]: a carry out of the significand (q = 2²⁴) raises the
    // exponent, as it should.
    let k = (e - 46) / 2;
    f32::from_bits((((k + 149) as u32) << 23) + q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn uniform_is_open_and_symmetric_grid() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        for _ in 0..10_000 {
            let a = f64::uniform_open(&mut rng);
            assert!(a > 0.0 && a < 1.0);
            // 1 − ξ is on the same grid: (2⁵³ − 1 − k + ½)·2⁻⁵³.
            let b = f32::uniform_open(&mut rng);
            assert!(b > 0.0 && b < 1.0);
        }
    }

    /// Bit for bit what libm's fmax/fmin return, NaN aside (both NaN: some NaN).
    #[test]
    fn max_and_min_are_libms() {
        let values = [
            0.0f32,
            -0.0,
            1.0,
            -2.5,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for &a in &values {
            for &b in &values {
                let (max, min) = (Real::max(a, b), Real::min(a, b));
                let (fmax, fmin) = (libm::fmaxf(a, b), libm::fminf(a, b));
                assert!(max.to_bits() == fmax.to_bits() || max.is_nan() && fmax.is_nan());
                assert!(min.to_bits() == fmin.to_bits() || min.is_nan() && fmin.is_nan());
                let (a, b) = (f64::from(a), f64::from(b));
                let (max, min) = (Real::max(a, b), Real::min(a, b));
                let (fmax, fmin) = (libm::fmax(a, b), libm::fmin(a, b));
                assert!(max.to_bits() == fmax.to_bits() || max.is_nan() && fmax.is_nan());
                assert!(min.to_bits() == fmin.to_bits() || min.is_nan() && fmin.is_nan());
            }
        }
    }

    fn assert_sqrt_is_libms(bits: u32) {
        let x = f32::from_bits(bits);
        let (ours, libms) = (sqrt_f32(x), libm::sqrtf(x));
        assert!(
            ours.to_bits() == libms.to_bits() || ours.is_nan() && libms.is_nan(),
            "√{x:e} ({bits:#x}): {ours:e}, libm {libms:e}"
        );
    }

    /// Every 997th bit pattern, the subnormals and the first normals densely, and the
    /// neighbours of every power of two.
    #[test]
    fn sqrt_is_libms() {
        for bits in (0..=u32::MAX).step_by(997) {
            assert_sqrt_is_libms(bits);
        }
        for bits in 0..0x0100_0000 {
            assert_sqrt_is_libms(bits);
        }
        for e in 0..=255u32 {
            for d in 0..4 {
                assert_sqrt_is_libms((e << 23).wrapping_sub(2).wrapping_add(d));
            }
        }
    }

    #[test]
    fn decimal_powers_go_to_their_exponents_and_back() {
        let powers: [f64; 31] = [
            1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3,
            1e-2, 1e-1, 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13,
            1e14, 1e15,
        ];
        for (k, &p) in (-15..=15).zip(powers.iter()) {
            assert_eq!(p.log10(), k as f64, "{p:e}");
            assert_eq!((k as f64).exp10(), p, "{k}");
        }
        let powers: [f32; 15] = [
            1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7,
        ];
        for (k, &p) in (-7..=7).zip(powers.iter()) {
            assert_eq!(p.log10(), k as f32, "{p:e}");
            assert_eq!((k as f32).exp10(), p, "{k}");
        }
    }

    /// `f32`'s `ln_near_one` (libm's `logf`) against `log1pf(x − 1)`, which `f64`'s
    /// form takes: equal for every x in [½, 1].
    #[test]
    fn ln_near_one_is_log1p_in_f32() {
        for bits in 0.5f32.to_bits()..=1.0f32.to_bits() {
            let x = f32::from_bits(bits);
            assert_eq!(
                x.ln_near_one().to_bits(),
                libm::log1pf(x - 1.0).to_bits(),
                "{x:e}"
            );
        }
    }

    /// All 2³² inputs: `cargo test -p hodr-core --release -- --ignored sqrt`.
    #[test]
    #[ignore = "exhaustive: 2³² inputs, run in release"]
    fn sqrt_is_libms_everywhere() {
        for bits in 0..=u32::MAX {
            assert_sqrt_is_libms(bits);
        }
    }

    #[test]
    fn sign_of_zero_and_nan_is_zero() {
        assert_eq!(0.0f64.sign(), 0.0);
        assert_eq!(f64::NAN.sign(), 0.0);
        assert_eq!((-3.0f32).sign(), -1.0);
    }
}
