//! The `f32` run-time routines the compiler calls on the targets without an FPU
//! (Cortex-M0, RV32IMAC) — addition, subtraction, multiplication, division, the
//! comparisons and the integer-to-float conversions — by `hodr_embedded::softfloat`.
//! They replace compiler-builtins' (whose definitions are weak so that a program can),
//! which are built for speed and were a third of the minimal build; results are the
//! same bit for bit (the module's contract and host tests). The routines the firmware
//! does not name here (float-to-integer conversions, `f64`) stay compiler-builtins'.
//!
//! Arm's run-time ABI names the routines `__aeabi_*` and has its comparisons return a
//! truth value; RISC-V uses libgcc's names, whose comparisons return a number the
//! compiler compares with zero. Both pass `f32` in integer registers, as `u32`.

use hodr_embedded::softfloat;

/// The Arm run-time ABI's forms (ARMv6-M: `thumbv6m-none-eabi`).
///
/// The arithmetic and comparison entry points are Thumb-1 assembly: each puts its
/// variant into registers (b's sign flipped for a difference, r2 the quotient flag or
/// the set of outcomes to test) and joins a tail shared with its kin that calls the
/// Rust routine. Written in Rust, each was a frame of its own (push, call, pop: 10 to 16
/// bytes), since LLVM makes no tail calls in Thumb-1; together 60 bytes more.
#[cfg(target_arch = "arm")]
mod aeabi {
    use super::softfloat;
    use super::softfloat::{EQUAL, GREATER, LESS, UNORDERED};

    core::arch::global_asm!(
        ".pushsection .text.hodr_aeabi_float, \"ax\", %progbits",
        ".p2align 1",
        // a − b = a + (−b).
        ".global __aeabi_fsub",
        ".type __aeabi_fsub, %function",
        ".thumb_func",
        "__aeabi_fsub:",
        "movs r2, #1",
        "lsls r2, r2, #31",
        "eors r1, r2",
        ".global __aeabi_fadd",
        ".type __aeabi_fadd, %function",
        ".thumb_func",
        "__aeabi_fadd:",
        "push {{r7, lr}}",
        "bl {add}",
        "pop {{r7, pc}}",
        // a · b and a / b: r2 = divide.
        ".global __aeabi_fmul",
        ".type __aeabi_fmul, %function",
        ".thumb_func",
        "__aeabi_fmul:",
        "movs r2, #0",
        "b 2f",
        ".global __aeabi_fdiv",
        ".type __aeabi_fdiv, %function",
        ".thumb_func",
        "__aeabi_fdiv:",
        "movs r2, #1",
        "2:",
        "push {{r7, lr}}",
        "bl {mul_or_div}",
        "pop {{r7, pc}}",
        // The comparisons, 1 or 0: r2 = the outcomes that make them true.
        ".global __aeabi_fcmpeq",
        ".type __aeabi_fcmpeq, %function",
        ".thumb_func",
        "__aeabi_fcmpeq:",
        "movs r2, #{equal}",
        "b 3f",
        ".global __aeabi_fcmplt",
        ".type __aeabi_fcmplt, %function",
        ".thumb_func",
        "__aeabi_fcmplt:",
        "movs r2, #{less}",
        "b 3f",
        ".global __aeabi_fcmple",
        ".type __aeabi_fcmple, %function",
        ".thumb_func",
        "__aeabi_fcmple:",
        "movs r2, #{less_or_equal}",
        "b 3f",
        ".global __aeabi_fcmpge",
        ".type __aeabi_fcmpge, %function",
        ".thumb_func",
        "__aeabi_fcmpge:",
        "movs r2, #{greater_or_equal}",
        "b 3f",
        ".global __aeabi_fcmpgt",
        ".type __aeabi_fcmpgt, %function",
        ".thumb_func",
        "__aeabi_fcmpgt:",
        "movs r2, #{greater}",
        "b 3f",
        ".global __aeabi_fcmpun",
        ".type __aeabi_fcmpun, %function",
        ".thumb_func",
        "__aeabi_fcmpun:",
        "movs r2, #{unordered}",
        "3:",
        "push {{r7, lr}}",
        "bl {compare_is}",
        "pop {{r7, pc}}",
        ".popsection",
        add = sym add,
        mul_or_div = sym mul_or_div,
        compare_is = sym compare_is,
        equal = const EQUAL,
        less = const LESS,
        less_or_equal = const LESS | EQUAL,
        greater_or_equal = const GREATER | EQUAL,
        greater = const GREATER,
        unordered = const UNORDERED,
    );

    /// a + b, for `__aeabi_fadd` and `__aeabi_fsub`.
    extern "C" fn add(a: u32, b: u32) -> u32 {
        softfloat::add(a, b)
    }

    /// a · b, or a / b if `divide`, for `__aeabi_fmul` and `__aeabi_fdiv`.
    extern "C" fn mul_or_div(a: u32, b: u32, divide: bool) -> u32 {
        softfloat::mul_or_div(a, b, divide)
    }

    /// 1 if a and b compare with an outcome in `set`, else 0, for the comparisons.
    extern "C" fn compare_is(a: u32, b: u32, set: u32) -> i32 {
        i32::from(softfloat::compare_is(a, b, set))
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_i2f(i: i32) -> f32 {
        f32::from_bits(softfloat::from_i32(i))
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_ui2f(u: u32) -> f32 {
        f32::from_bits(softfloat::from_u32(u))
    }
}

/// libgcc's names, as RISC-V uses them.
///
/// The soft-float ABI (ilp32) passes and returns an `f32` in an integer register, as a
/// `u32`; these definitions say `u32` so that each is a tail call to its routine (with
/// `f32` the bit casts kept LLVM from one, and each entry point paid a frame of its own:
/// 64 bytes in all).
#[cfg(target_arch = "riscv32")]
mod libgcc {
    use super::softfloat;

    /// a + b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __addsf3(a: u32, b: u32) -> u32 {
        softfloat::add(a, b)
    }

    /// a − b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __subsf3(a: u32, b: u32) -> u32 {
        softfloat::sub(a, b)
    }

    /// a · b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __mulsf3(a: u32, b: u32) -> u32 {
        softfloat::mul(a, b)
    }

    /// a / b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __divsf3(a: u32, b: u32) -> u32 {
        softfloat::div(a, b)
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __floatsisf(i: i32) -> u32 {
        softfloat::from_i32(i)
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __floatunsisf(u: u32) -> u32 {
        softfloat::from_u32(u)
    }

    /// −1, 0 or 1 as a < b, a = b or a > b, and `unordered` when a or b is a NaN: the
    /// comparisons' one body, each entry point a tail call to it with its `unordered`
    /// (out of line: inlined, each entry point carried a copy).
    #[inline(never)]
    fn compare_or(a: u32, b: u32, unordered: i32) -> i32 {
        softfloat::compare(a, b).unwrap_or(unordered)
    }

    /// Zero if a = b; nonzero if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __eqsf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, 1)
    }

    /// Nonzero if a ≠ b or unordered; zero if a = b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __nesf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, 1)
    }

    /// Negative if a < b; zero or positive if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __ltsf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, 1)
    }

    /// Zero or negative if a ≤ b; positive if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __lesf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, 1)
    }

    /// Zero or positive if a ≥ b; negative if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __gesf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, -1)
    }

    /// Positive if a > b; zero or negative if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __gtsf2(a: u32, b: u32) -> i32 {
        compare_or(a, b, -1)
    }

    /// Nonzero if a or b is a NaN.
    #[unsafe(no_mangle)]
    pub extern "C" fn __unordsf2(a: u32, b: u32) -> i32 {
        i32::from(softfloat::compare(a, b).is_none())
    }
}
