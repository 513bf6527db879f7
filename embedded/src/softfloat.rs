//! Single-precision arithmetic in integer instructions, small rather than fast: the
//! firmware links these in place of compiler-builtins' `f32` routines on the targets
//! without an FPU (Cortex-M0, RV32IMAC), where they were a third of the minimal build.
//!
//! Every function takes and returns `f32` bit patterns and computes the correctly
//! rounded IEEE 754 result (round to nearest, ties to even; subnormals kept, overflow to
//! ±∞), so for any non-NaN result it equals, bit for bit, the hardware's and
//! compiler-builtins'. NaN results follow compiler-builtins' rules too: a NaN operand
//! comes back quieted (the first one if both are NaN; sums and differences clear its
//! sign), an invalid operation (∞ − ∞, 0·∞, 0/0, ∞/∞) gives [`DEFAULT_NAN`]. The
//! comparisons return what compiler-builtins' do, for every input, NaN included.
//!
//! One rounding routine serves every operation: each computes its exact result as
//! `m·2^(e − 158)` with `m` a 32-bit integer whose lowest bit also records ("sticks")
//! any nonzero bits shifted out below it, and the routine normalises `m`, rounds it to
//! 24 bits and packs the exponent. Normalisation shifts one bit a step: neither target
//! counts leading zeros in one instruction.
//!
//! Tested on the host against the native `f32` operations and the NaN rules above: edge
//! cases, every pair of them, and random pairs (10⁸ of each operation, and every
//! integer converted, in ignored tests:
//! `cargo test -p hodr-embedded --release -- --ignored softfloat`). Every result, NaN
//! rules and comparison values included, is also checked against compiler-builtins' own
//! routines (its host build, whose code is the targets') by
//! `bash embedded/softfloat-check/run.sh`, a program of its own because calling them
//! takes the `unsafe` this workspace forbids.

/// The sign bit.
const SIGN: u32 = 0x8000_0000;
/// +∞; a magnitude above it is a NaN.
const INFINITY: u32 = 0x7f80_0000;
/// The significand's hidden bit.
const HIDDEN: u32 = 0x0080_0000;
/// The bit that makes a NaN quiet.
const QUIET: u32 = 0x0040_0000;

/// The NaN of an invalid operation, as compiler-builtins returns it (and as Arm's FPUs
/// do): positive, quiet, no payload.
pub const DEFAULT_NAN: u32 = 0x7fc0_0000;

/// a + b.
pub fn add(a: u32, b: u32) -> u32 {
    let (x, y) = (a & !SIGN, b & !SIGN);
    if x > INFINITY || y > INFINITY {
        // compiler-builtins returns the NaN's magnitude, quieted.
        return nan(x, y);
    }
    // |a| ≥ |b| from here on.
    let (a, b, x, y) = if x < y { (b, a, y, x) } else { (a, b, x, y) };
    if x == INFINITY {
        // ∞ − ∞ is the only invalid sum; b is then −a.
        return if a ^ b == SIGN { DEFAULT_NAN } else { a };
    }
    if y == 0 {
        // ±0 + ±0 is −0 only when both are; a nonzero a is exact.
        return if x == 0 { a & b } else { a };
    }
    let (ea, ma) = unpack(x);
    let (eb, mb) = unpack(y);
    // Seven bits of headroom below the 24-bit significands: with the sticky bit, more
    // than the guard and round bits a correctly rounded sum needs (a shift of b by two
    // or more leaves at most one bit of cancellation, a shift by less loses nothing).
    let (ma, mb) = (ma << 7, shift_right_sticky(mb << 7, (ea - eb) as u32));
    let m = if (a ^ b) & SIGN == 0 {
        ma + mb
    } else {
        ma - mb
    };
    if m == 0 {
        // x − x is +0 when rounding to nearest.
        return 0;
    }
    // a = ma·2^(ea − 157): the leading bit at 30 stands for 2^(ea − 127).
    round(a & SIGN, ea + 1, m)
}

/// a − b: a + (−b).
pub fn sub(a: u32, b: u32) -> u32 {
    add(a, b ^ SIGN)
}

/// a · b.
pub fn mul(a: u32, b: u32) -> u32 {
    mul_or_div(a, b, false)
}

/// a / b.
pub fn div(a: u32, b: u32) -> u32 {
    mul_or_div(a, b, true)
}

/// a · b, or a / b if `divide`: one routine, the special cases being the same once b's
/// zero and infinity trade places for a quotient (x/0 is x·∞, x/∞ is x·0, 0/0 and ∞/∞
/// are 0·∞).
pub fn mul_or_div(a: u32, b: u32, divide: bool) -> u32 {
    let sign = (a ^ b) & SIGN;
    let (x, y) = (a & !SIGN, b & !SIGN);
    if x > INFINITY || y > INFINITY {
        return nan(a, b);
    }
    let (x_zero, x_infinite) = (x == 0, x == INFINITY);
    let (y_zero, y_infinite) = if divide {
        (y == INFINITY, y == 0)
    } else {
        (y == 0, y == INFINITY)
    };
    if x_infinite || y_infinite {
        return if x_zero || y_zero {
            DEFAULT_NAN
        } else {
            sign | INFINITY
        };
    }
    if x_zero || y_zero {
        return sign;
    }
    let (ea, ma) = unpack(x);
    let (eb, mb) = unpack(y);
    let (e, m) = if divide {
        // a/b = q·2^(ea − eb − 31) for q = ⌊ma/mb·2³¹⌋ in [2³⁰, 2³²), the remainder
        // sticking: restoring division, one quotient bit a step (no divide instruction
        // on the M0), 32 steps counted by a marker bit that q starts with and the last
        // step shifts out.
        let e = ea - eb + 127;
        let (mut q, mut r) = (1u32, ma);
        loop {
            let last = q >> 31 != 0;
            q <<= 1;
            if r >= mb {
                r -= mb;
                q |= 1;
            }
            r <<= 1;
            if last {
                break;
            }
        }
        (e, q | u32::from(r != 0))
    } else {
        // Both significands in [2²³, 2²⁴): the product p is in [2⁴⁶, 2⁴⁸), its top 32
        // bits keep 30 or more below the leading one, the other 16 stick;
        // a·b = p·2^(ea + eb − 300).
        (ea + eb - 126, product(ma, mb))
    };
    round(sign, e, m)
}

/// ⌊p/2¹⁶⌋ for the product p = ma·mb of two 24-bit significands, its lowest bit or-ed
/// with any nonzero bits of p mod 2¹⁶ (sticky).
///
/// Thumb-1 multiplies only 32 by 32 bits into 32, so a 64-bit product is a library call
/// (`__aeabi_lmul`, which nothing else in the minimal firmware needs); there the
/// significands are multiplied in 12-bit halves. RISC-V's `mulhu` gives the high word
/// directly.
#[cfg(target_arch = "arm")]
fn product(ma: u32, mb: u32) -> u32 {
    product_by_halves(ma, mb)
}

/// See the Arm form.
#[cfg(not(target_arch = "arm"))]
fn product(ma: u32, mb: u32) -> u32 {
    product_wide(ma, mb)
}

/// [`product`] in 64-bit arithmetic.
#[cfg_attr(all(target_arch = "arm", not(test)), allow(dead_code))]
fn product_wide(ma: u32, mb: u32) -> u32 {
    let p = u64::from(ma) * u64::from(mb);
    (p >> 16) as u32 | u32::from(p as u16 != 0)
}

/// [`product`] from four 12-by-12-bit products: with a = a₁2¹² + a₀ and b = b₁2¹² + b₀,
/// p = a₁b₁2²⁴ + (a₁b₀ + a₀b₁)2¹² + a₀b₀, and the middle sum's low four bits go with
/// the low product below bit 16.
#[cfg_attr(not(any(target_arch = "arm", test)), allow(dead_code))]
fn product_by_halves(ma: u32, mb: u32) -> u32 {
    let (a1, a0, b1, b0) = (ma >> 12, ma & 0xfff, mb >> 12, mb & 0xfff);
    let middle = a1 * b0 + a0 * b1;
    let low = ((middle & 0xf) << 12) + a0 * b0;
    (((a1 * b1) << 8) + (middle >> 4) + (low >> 16)) | u32::from(low as u16 != 0)
}

/// The integer i, rounded to nearest.
pub fn from_i32(i: i32) -> u32 {
    if i == 0 {
        return 0;
    }
    round(i as u32 & SIGN, 158, i.unsigned_abs())
}

/// The integer u, rounded to nearest.
pub fn from_u32(u: u32) -> u32 {
    if u == 0 {
        return 0;
    }
    round(0, 158, u)
}

/// How a and b compare: `Some(-1)`, `Some(0)` or `Some(1)` for a < b, a = b (±0 equal)
/// and a > b; `None` when either is a NaN.
pub fn compare(a: u32, b: u32) -> Option<i32> {
    if a & !SIGN > INFINITY || b & !SIGN > INFINITY {
        return None;
    }
    let (ka, kb) = (order_key(a), order_key(b));
    Some(i32::from(ka > kb) - i32::from(ka < kb))
}

/// A comparison's outcome a < b, as a bit of the sets [`compare_is`] takes.
pub const LESS: u32 = 1;
/// A comparison's outcome a = b (±0 equal).
pub const EQUAL: u32 = 2;
/// A comparison's outcome a > b.
pub const GREATER: u32 = 4;
/// A comparison's outcome when a or b is a NaN.
pub const UNORDERED: u32 = 8;

/// Whether a and b compare with one of the outcomes in `set` (bits [`LESS`], [`EQUAL`],
/// [`GREATER`], [`UNORDERED`]): one routine for every truth-valued comparison.
pub fn compare_is(a: u32, b: u32, set: u32) -> bool {
    let outcome = match compare(a, b) {
        Some(order) => 1 << (order + 1),
        None => UNORDERED,
    };
    set & outcome != 0
}

/// A float's place in the order of the reals as an integer: its magnitude, negated for
/// a negative sign (so ±0 both give 0).
fn order_key(a: u32) -> i32 {
    let magnitude = (a & !SIGN) as i32;
    if a & SIGN == 0 { magnitude } else { -magnitude }
}

/// compiler-builtins' `__lesf2` (also its `__eqsf2`, `__ltsf2`, `__nesf2`): −1, 0 or 1
/// as a < b, a = b or a > b, and 1 when unordered.
pub fn compare_le(a: u32, b: u32) -> i32 {
    compare(a, b).unwrap_or(1)
}

/// compiler-builtins' `__gesf2` (also its `__gtsf2`): −1, 0 or 1 as a < b, a = b or
/// a > b, and −1 when unordered.
pub fn compare_ge(a: u32, b: u32) -> i32 {
    compare(a, b).unwrap_or(-1)
}

/// The result of an operation with a NaN operand: a, quieted, if it is a NaN, else b,
/// quieted.
fn nan(a: u32, b: u32) -> u32 {
    (if a & !SIGN > INFINITY { a } else { b }) | QUIET
}

/// A finite nonzero magnitude as (biased exponent, 24-bit significand in [2²³, 2²⁴)):
/// x = m·2^(e − 150). Subnormals are normalised, their exponent going below 1.
fn unpack(x: u32) -> (i32, u32) {
    let (mut e, mut m) = ((x >> 23) as i32, x & (HIDDEN - 1));
    if e == 0 {
        e = 1;
    } else {
        m |= HIDDEN;
    }
    while m < HIDDEN {
        m <<= 1;
        e -= 1;
    }
    (e, m)
}

/// m shifted right by n bits, any bits shifted out or-ed into the lowest bit.
fn shift_right_sticky(m: u32, n: u32) -> u32 {
    if n == 0 {
        m
    } else if n < 32 {
        m >> n | u32::from(m << (32 - n) != 0)
    } else {
        u32::from(m != 0)
    }
}

/// The float nearest to m·2^(e − 158), with the given sign: m ≠ 0, its lowest bit sticky
/// (standing for any nonzero bits below it). The rounding of every operation: ties to
/// even, overflow to ±∞, results below the normal range subnormal or ±0.
fn round(sign: u32, mut e: i32, mut m: u32) -> u32 {
    // Leading bit to bit 31, standing for 2^(e − 127).
    while m & SIGN == 0 {
        m <<= 1;
        e -= 1;
    }
    if e >= 255 {
        return sign | INFINITY;
    }
    if e < 1 {
        // Subnormal: the exponent stays at the minimum, the significand loses bits.
        m = shift_right_sticky(m, (1 - e) as u32);
        e = 1;
    }
    // 24 bits stay, 8 decide: more than half up, exactly half to even.
    let rest = m & 0xff;
    m >>= 8;
    if rest + (m & 1) > 0x80 {
        m += 1;
    }
    // The hidden bit (or a carry out of the significand) adds to the exponent field:
    // a subnormal rounding up to 2²³ becomes the least normal, 2²⁴ a binade up, 254
    // carrying into 255 becomes ∞.
    sign | ((((e - 1) as u32) << 23) + m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::Xoshiro128PlusPlus;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};
    use std::vec::Vec;

    /// The result compiler-builtins gives where the IEEE result is a NaN: a NaN operand
    /// quieted (the first one if both are), else the default NaN. (Sums pass their
    /// operands' magnitudes.)
    fn expected_nan(a: u32, b: u32) -> u32 {
        if a & !SIGN > INFINITY {
            a | QUIET
        } else if b & !SIGN > INFINITY {
            b | QUIET
        } else {
            DEFAULT_NAN
        }
    }

    /// One of the four operations on bit patterns.
    type Operation = fn(u32, u32) -> u32;

    /// Checks the four operations on (a, b) against the host's.
    fn check_arithmetic(a: u32, b: u32) {
        let (fa, fb) = (f32::from_bits(a), f32::from_bits(b));
        let cases: [(&str, Operation, f32); 4] = [
            ("+", add, fa + fb),
            ("−", sub, fa - fb),
            ("·", mul, fa * fb),
            ("/", div, fa / fb),
        ];
        for (name, op, native) in cases {
            let ours = op(a, b);
            let expected = if !native.is_nan() {
                native.to_bits()
            } else if name == "+" || name == "−" {
                expected_nan(a & !SIGN, b & !SIGN)
            } else {
                expected_nan(a, b)
            };
            assert_eq!(
                ours, expected,
                "{a:#010x} {name} {b:#010x} ({fa:e} {name} {fb:e}): {ours:#010x}, expected {expected:#010x}"
            );
        }
        let expected = fa.partial_cmp(&fb).map(|o| o as i32);
        assert_eq!(compare(a, b), expected, "{a:#010x} <> {b:#010x}");
        assert_eq!(compare_le(a, b), expected.unwrap_or(1));
        assert_eq!(compare_ge(a, b), expected.unwrap_or(-1));
        for set in 0..16 {
            let outcome = expected.map_or(UNORDERED, |o| [LESS, EQUAL, GREATER][(o + 1) as usize]);
            assert_eq!(compare_is(a, b, set), set & outcome != 0);
        }
    }

    /// Signs, zeros, subnormals at both ends, the normal range's ends, one and its
    /// neighbours, values whose sums and products round half-way, infinities, NaNs
    /// quiet and signalling, with and without payloads.
    fn edge_cases() -> Vec<u32> {
        let magnitudes = [
            0x0000_0000,
            0x0000_0001,
            0x0000_0002,
            0x0000_0003,
            0x0040_0000,
            0x007f_ffff,
            0x0080_0000,
            0x0080_0001,
            0x00ff_ffff,
            0x0100_0000,
            0x0c00_0000,
            0x3380_0000,
            0x3400_0000,
            0x3f7f_ffff,
            0x3f80_0000,
            0x3f80_0001,
            0x3fc0_0000,
            0x3fff_ffff,
            0x4040_0000,
            0x4b00_0000,
            0x4b7f_ffff,
            0x4b80_0000,
            0x4b80_0001,
            0x5f00_0000,
            0x7f00_0000,
            0x7f7f_fffe,
            0x7f7f_ffff,
            0x7f80_0000,
            0x7f80_0001,
            0x7fa0_0000,
            0x7fc0_0000,
            0x7fc0_1234,
            0x7fff_ffff,
        ];
        magnitudes.iter().flat_map(|&m| [m, m | SIGN]).collect()
    }

    #[test]
    fn edge_cases_pairwise() {
        let edges = edge_cases();
        for &a in &edges {
            for &b in &edges {
                check_arithmetic(a, b);
            }
        }
    }

    /// A random bit pattern; with probability ½ one whose exponent is near `near`'s
    /// (within ±31), where sums cancel and round in every way.
    fn random_pair(rng: &mut Xoshiro128PlusPlus) -> (u32, u32) {
        let a = rng.next_u32();
        let b = rng.next_u32();
        if b & 1 == 0 {
            return (a, b);
        }
        let shift = (b >> 1 & 63) as i32 - 31;
        let e = ((a >> 23 & 0xff) as i32 + shift).clamp(0, 255) as u32;
        (a, b & !(0xff << 23) | e << 23)
    }

    fn random_pairs(seed: u64, pairs: u64) {
        let mut rng = Xoshiro128PlusPlus::seed_from_u64(seed);
        for _ in 0..pairs {
            let (a, b) = random_pair(&mut rng);
            check_arithmetic(a, b);
        }
    }

    #[test]
    fn random_pairs_agree() {
        random_pairs(1, 1_000_000);
    }

    /// 10⁸ random pairs: `cargo test -p hodr-embedded --release -- --ignored softfloat`.
    #[test]
    #[ignore = "10⁸ pairs, about a minute in release"]
    fn softfloat_random_pairs_agree_at_length() {
        random_pairs(2, 100_000_000);
    }

    /// Both forms of the significand product (the host's `mul` takes the 64-bit one, the
    /// Cortex-M0's the other), on the extremes and random significands.
    fn products(seed: u64, pairs: u64) {
        let ends = [HIDDEN, HIDDEN + 1, 2 * HIDDEN - 1];
        for &a in &ends {
            for &b in &ends {
                assert_eq!(product_by_halves(a, b), product_wide(a, b), "{a:#x}·{b:#x}");
            }
        }
        let mut rng = Xoshiro128PlusPlus::seed_from_u64(seed);
        for _ in 0..pairs {
            let (a, b) = (rng.next_u32() >> 8 | HIDDEN, rng.next_u32() >> 8 | HIDDEN);
            assert_eq!(product_by_halves(a, b), product_wide(a, b), "{a:#x}·{b:#x}");
        }
    }

    #[test]
    fn products_agree() {
        products(3, 1_000_000);
    }

    /// 10⁹ random pairs: `cargo test -p hodr-embedded --release -- --ignored softfloat`.
    #[test]
    #[ignore = "10⁹ pairs, some seconds in release"]
    fn softfloat_products_agree_at_length() {
        products(4, 1_000_000_000);
    }

    fn check_conversions(i: u32) {
        assert_eq!(
            from_i32(i as i32),
            (i as i32 as f32).to_bits(),
            "{i:#x} as i32"
        );
        assert_eq!(from_u32(i), (i as f32).to_bits(), "{i:#x} as u32");
    }

    #[test]
    fn conversions_agree() {
        for i in (0..=u32::MAX).step_by(9_973) {
            check_conversions(i);
        }
        for k in 0..32 {
            for d in 0..5 {
                check_conversions((1u32 << k).wrapping_add(d).wrapping_sub(2));
                check_conversions((0x0100_0001u32 << (k % 8)).wrapping_add(d) ^ (1 << 31));
            }
        }
    }

    /// Every integer: `cargo test -p hodr-embedded --release -- --ignored softfloat`.
    #[test]
    #[ignore = "2³² integers, about a minute in release"]
    fn softfloat_conversions_agree_everywhere() {
        for i in 0..=u32::MAX {
            check_conversions(i);
        }
    }
}
