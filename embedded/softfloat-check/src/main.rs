//! hodr_embedded::softfloat against compiler-builtins' own routines (linked by run.sh
//! under the names cb__*), bit for bit: every pair of special values, random pairs
//! (a quarter with a ±∞/NaN first operand, a quarter with a ±∞/NaN second one, a quarter
//! with equal exponents), and every 7th 32-bit integer converted.

use hodr_embedded::softfloat;

#[link(name = "cb", kind = "static")]
unsafe extern "C" {
    fn cb__addsf3(a: f32, b: f32) -> f32;
    fn cb__subsf3(a: f32, b: f32) -> f32;
    fn cb__mulsf3(a: f32, b: f32) -> f32;
    fn cb__divsf3(a: f32, b: f32) -> f32;
    fn cb__lesf2(a: f32, b: f32) -> i32;
    fn cb__ltsf2(a: f32, b: f32) -> i32;
    fn cb__eqsf2(a: f32, b: f32) -> i32;
    fn cb__nesf2(a: f32, b: f32) -> i32;
    fn cb__gesf2(a: f32, b: f32) -> i32;
    fn cb__gtsf2(a: f32, b: f32) -> i32;
    fn cb__unordsf2(a: f32, b: f32) -> i32;
    fn cb__floatsisf(i: i32) -> f32;
    fn cb__floatunsisf(i: u32) -> f32;
}

/// Panics unless every routine agrees with compiler-builtins' on (a, b).
fn check(a: u32, b: u32) {
    let (fa, fb) = (f32::from_bits(a), f32::from_bits(b));
    // SAFETY: the cb__ functions are compiler-builtins' routines of these signatures.
    let theirs = unsafe {
        [
            cb__addsf3(fa, fb).to_bits(),
            cb__subsf3(fa, fb).to_bits(),
            cb__mulsf3(fa, fb).to_bits(),
            cb__divsf3(fa, fb).to_bits(),
        ]
    };
    let ours = [
        softfloat::add(a, b),
        softfloat::sub(a, b),
        softfloat::mul(a, b),
        softfloat::div(a, b),
    ];
    for ((o, t), name) in ours.iter().zip(theirs).zip(["+", "-", "*", "/"]) {
        assert_eq!(
            *o, t,
            "{a:#010x} {name} {b:#010x}: ours {o:#010x}, compiler-builtins {t:#010x}"
        );
    }
    let (le, ge) = (softfloat::compare_le(a, b), softfloat::compare_ge(a, b));
    let unordered = i32::from(softfloat::compare(a, b).is_none());
    // SAFETY: as above.
    let theirs = unsafe {
        [
            cb__lesf2(fa, fb),
            cb__ltsf2(fa, fb),
            cb__eqsf2(fa, fb),
            cb__nesf2(fa, fb),
            cb__gesf2(fa, fb),
            cb__gtsf2(fa, fb),
            i32::from(cb__unordsf2(fa, fb) != 0),
        ]
    };
    assert_eq!(
        [le, le, le, le, ge, ge, unordered],
        theirs,
        "{a:#010x} <> {b:#010x}"
    );
}

fn main() {
    let pairs: u64 = std::env::args()
        .nth(1)
        .map_or(100_000_000, |n| n.parse().expect("RANDOM_PAIRS is a count"));
    let specials: Vec<u32> = [
        0u32,
        1,
        0x7f_ffff,
        0x80_0000,
        0x3f80_0000,
        0x7f7f_ffff,
        0x7f80_0000,
        0x7f80_0001,
        0x7fa0_0000,
        0x7fc0_0000,
        0x7fc0_1234,
        0x7fff_ffff,
        0x7f81_2345,
    ]
    .iter()
    .flat_map(|&m| [m, m | 0x8000_0000])
    .collect();
    for &a in &specials {
        for &b in &specials {
            check(a, b);
        }
    }
    // xorshift64: any fixed stream will do.
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for k in 0..pairs {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let (mut a, mut b) = (state as u32, (state >> 32) as u32);
        match k % 4 {
            0 => {}
            1 => a |= 0x7f80_0000,
            2 => b |= 0x7f80_0000,
            _ => b = (b & !(0xff << 23)) | (a & (0xff << 23)),
        }
        check(a, b);
    }
    for i in (0..=u32::MAX).step_by(7) {
        // SAFETY: as above.
        let theirs = unsafe {
            (
                cb__floatsisf(i as i32).to_bits(),
                cb__floatunsisf(i).to_bits(),
            )
        };
        assert_eq!(
            (softfloat::from_i32(i as i32), softfloat::from_u32(i)),
            theirs,
            "{i:#x}"
        );
    }
    println!(
        "softfloat agrees with compiler-builtins: {} special pairs, {pairs} random pairs, every 7th integer",
        specials.len() * specials.len()
    );
}
