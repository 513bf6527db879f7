//! Owen-scrambled 2-D Sobol points, shuffled per pixel: the construction behind
//! [`super::Sequence::PaddedSobol`] (Burley 2020, "Practical Hash-based Owen
//! Scrambling").
//!
//! * **Points.** The 2-D Sobol sequence: x_n is the van der Corput radical inverse of n,
//!   y_n uses the direction numbers of the primitive polynomial x + 1 (m₁ = 1,
//!   m_i = m_{i−1} ⊕ 2m_{i−1}). Its first 2^k points form a (0, k, 2)-net: every box
//!   [a/2^i, (a+1)/2^i) × [b/2^(k−i), (b+1)/2^(k−i)) holds exactly one point.
//! * **Owen scrambling.** Read a coordinate as a binary fraction 0.d₁d₂d₃…; nested
//!   uniform scrambling flips digit d_j according to a random function of d₁…d_{j−1}.
//!   It keeps the net property and makes each point uniform on [0, 1)², so estimates
//!   stay unbiased. Here it is hashed (Laine & Karras 2011; Burley's constants): on the
//!   bit-reversed value (d₁ in bit 0) every operation below changes bit j only as a
//!   function of bits < j — adding a seed (carries), multiplying by an odd number, and
//!   x ⊕ x·c for an even c.
//! * **Shuffling.** Each pixel and dimension pair takes the sample indices in its own
//!   Owen-scrambled order, so that pairs are not correlated with one another
//!   ("padding"). Scrambling the index least significant digit first would save two bit
//!   reversals but gives a larger error (docs/notes/2026-11-23-benchmarks-before-auto.md).
//!
//! Everything works on the bit-reversed form of the coordinates, where the van der
//! Corput coordinate is the index itself and Sobol's second coordinate is an XOR of
//! reversed direction numbers (tabulated for indices below 256), so each coordinate
//! costs one reversal at the end. Index shuffles of up to 256 samples reverse through a
//! byte table: x86-64 has no bit-reversal instruction.

/// Bit-reversed direction numbers of Sobol's second dimension: entry i is m_{i+1}
/// (the rows of Pascal's triangle mod 2, which are palindromes: reversing the i + 1
/// digits of m_{i+1} gives m_{i+1} again).
const DIRECTIONS: [u32; 32] = directions();

const fn directions() -> [u32; 32] {
    let mut d = [0u32; 32];
    d[0] = 1;
    let mut i = 1;
    while i < 32 {
        d[i] = d[i - 1] ^ (d[i - 1] << 1);
        i += 1;
    }
    d
}

/// Owen scrambling of a bit-reversed 32-bit fraction (digit d₁ in bit 0): bit j of the
/// result is bit j of `x` flipped by a hash of `seed` and bits 0…j−1.
#[inline(always)]
fn scramble_reversed(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3D20_ADEA);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6C56);
    x ^= x.wrapping_mul(0x53A2_2864);
    x
}

/// Each byte value with its bits in reverse order.
const REVERSED_BYTES: [u8; 256] = reversed_bytes();

const fn reversed_bytes() -> [u8; 256] {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u8).reverse_bits();
        i += 1;
    }
    t
}

/// Sobol's second coordinate, bit-reversed, of every index below 256.
const SECOND_BELOW_256: [u32; 256] = second_below_256();

const fn second_below_256() -> [u32; 256] {
    let mut t = [0u32; 256];
    let mut i = 1;
    while i < 256 {
        // Index i differs from i with its lowest set bit cleared by that bit's direction.
        let low = (i as u32).trailing_zeros() as usize;
        t[i] = t[i & (i - 1)] ^ DIRECTIONS[low];
        i += 1;
    }
    t
}

/// The low `bits` bits of `x` in reverse order (bit i to bit `bits` − 1 − i).
#[inline(always)]
fn reverse_low(x: u32, bits: u32) -> u32 {
    if bits <= 8 {
        u32::from(REVERSED_BYTES[(x & 0xFF) as usize]) >> (8 - bits)
    } else {
        x.reverse_bits() >> (32 - bits)
    }
}

/// A permutation of the sample indices: the low `bits` bits of `n` (the pixel's
/// 2^bits samples) are Owen-scrambled as a `bits`-digit fraction, higher bits are kept.
/// For spp = 2^bits this permutes 0…spp − 1.
#[inline(always)]
pub fn shuffle(n: u32, bits: u32, seed: u32) -> u32 {
    if bits == 0 {
        return n;
    }
    let low = n & (u32::MAX >> (32 - bits));
    // The digits of `low`, most significant first, from bit 0 up (the reversed form);
    // the scrambled value's low `bits` bits depend only on them, and reversed back they
    // are the permuted index.
    let permuted = reverse_low(scramble_reversed(reverse_low(low, bits), seed), bits);
    (n ^ low) | permuted
}

/// Point `index` of the 2-D Sobol sequence, each coordinate Owen-scrambled with its own
/// seed, as 32-bit fractions (value / 2³²).
#[inline(always)]
pub fn point(index: u32, seeds: (u32, u32)) -> (u32, u32) {
    let mut y = SECOND_BELOW_256[(index & 0xFF) as usize];
    let mut high = index & !0xFF;
    while high != 0 {
        y ^= DIRECTIONS[high.trailing_zeros() as usize];
        high &= high - 1;
    }
    (
        scramble_reversed(index, seeds.0).reverse_bits(),
        scramble_reversed(y, seeds.1).reverse_bits(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unscrambled Sobol coordinates (seed 0 still scrambles, so compare the
    /// unscrambled construction directly): y for n = 0…7 is 0, ½, ¾, ¼, 5/8, 1/8, 3/8, 7/8.
    #[test]
    fn second_dimension_matches_sobol() {
        let expected = [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
        for (n, &e) in expected.iter().enumerate() {
            let mut y = 0u32;
            for (i, d) in DIRECTIONS.iter().enumerate() {
                if n >> i & 1 == 1 {
                    y ^= d;
                }
            }
            let value = f64::from(y.reverse_bits()) / 4_294_967_296.0;
            assert_eq!(value, e, "n = {n}");
        }
    }

    /// The tables agree with their definitions: the Sobol table with the XOR of
    /// direction numbers, the byte reversal with `reverse_bits` for every width.
    #[test]
    fn tables_match_definitions() {
        for n in 0..256u32 {
            let direct = (0..8)
                .filter(|i| n >> i & 1 == 1)
                .fold(0, |y, i| y ^ DIRECTIONS[i]);
            assert_eq!(SECOND_BELOW_256[n as usize], direct, "n = {n}");
        }
        for bits in 1..=32u32 {
            for x in [0u32, 1, 0x5A, 0xFF, 0x1234_5678, u32::MAX] {
                let x = if bits < 32 { x & ((1 << bits) - 1) } else { x };
                assert_eq!(
                    reverse_low(x, bits),
                    x.reverse_bits() >> (32 - bits),
                    "{bits}"
                );
            }
        }
    }

    /// Bit j of a scrambled reversed fraction depends only on bits ≤ j: changing bit j
    /// of the input never changes bits below j of the output (nested scrambling).
    #[test]
    fn scrambling_is_nested() {
        let mut state = 0x0123_4567_89AB_CDEF_u64;
        for _ in 0..2000 {
            state = super::super::sampler::mix64(state);
            let (x, seed, j) = (state as u32, (state >> 32) as u32, (state >> 59) as u32);
            let a = scramble_reversed(x, seed);
            let b = scramble_reversed(x ^ (1 << j), seed);
            let below = (1u32 << j) - 1;
            assert_eq!(a & below, b & below);
            assert_ne!(a & (1 << j), b & (1 << j), "bit j itself must flip");
        }
    }

    #[test]
    fn shuffle_permutes_each_power_of_two_block() {
        for bits in 0..12u32 {
            for seed in [0u32, 1, 0xDEAD_BEEF] {
                let spp = 1u32 << bits;
                let mut seen: Vec<u32> = (0..spp).map(|n| shuffle(n, bits, seed)).collect();
                seen.sort_unstable();
                assert_eq!(seen, (0..spp).collect::<Vec<_>>());
                // Higher bits are kept.
                let n = 5 * spp + 3 % spp;
                assert_eq!(shuffle(n, bits, seed) >> bits, 5);
            }
        }
    }

    /// The top `digits` binary digits of a 32-bit fraction.
    fn top(v: u32, digits: u32) -> usize {
        (u64::from(v) >> (32 - digits)) as usize
    }

    /// The first 2^k scrambled points (in shuffled order) form a (0, k, 2)-net: every
    /// elementary box of area 2^−k holds exactly one of them.
    #[test]
    fn scrambled_points_form_nets() {
        for k in [2u32, 4, 6, 10] {
            for seed in [3u32, 0x9E37_79B9] {
                let count = 1usize << k;
                let points: Vec<(u32, u32)> = (0..count as u32)
                    .map(|n| point(shuffle(n, k, seed), (seed ^ 0x55, seed.rotate_left(7))))
                    .collect();
                for i in 0..=k {
                    let mut boxes = vec![0u32; count];
                    for &(x, y) in &points {
                        let (a, b) = (top(x, i), top(y, k - i));
                        boxes[(a << (k - i)) | b] += 1;
                    }
                    assert!(boxes.iter().all(|&c| c == 1), "k = {k}, split {i}");
                }
            }
        }
    }
}
