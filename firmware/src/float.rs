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
#[cfg(target_arch = "arm")]
mod aeabi {
    use super::softfloat;
    use super::softfloat::{EQUAL, GREATER, LESS, UNORDERED};

    /// a + b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fadd(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::add(a.to_bits(), b.to_bits()))
    }

    /// a − b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fsub(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::sub(a.to_bits(), b.to_bits()))
    }

    /// a · b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fmul(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::mul(a.to_bits(), b.to_bits()))
    }

    /// a / b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fdiv(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::div(a.to_bits(), b.to_bits()))
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

    /// 1 if a = b, else 0 (also when unordered).
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmpeq(a: f32, b: f32) -> i32 {
        is(a, b, EQUAL)
    }

    /// 1 if a < b, else 0.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmplt(a: f32, b: f32) -> i32 {
        is(a, b, LESS)
    }

    /// 1 if a ≤ b, else 0.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmple(a: f32, b: f32) -> i32 {
        is(a, b, LESS | EQUAL)
    }

    /// 1 if a ≥ b, else 0.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmpge(a: f32, b: f32) -> i32 {
        is(a, b, EQUAL | GREATER)
    }

    /// 1 if a > b, else 0.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmpgt(a: f32, b: f32) -> i32 {
        is(a, b, GREATER)
    }

    /// 1 if a or b is a NaN, else 0.
    #[unsafe(no_mangle)]
    pub extern "C" fn __aeabi_fcmpun(a: f32, b: f32) -> i32 {
        is(a, b, UNORDERED)
    }

    /// 1 if a and b compare with an outcome in `set`, else 0: the routine every
    /// comparison above calls, only the set differing.
    fn is(a: f32, b: f32, set: u32) -> i32 {
        i32::from(softfloat::compare_is(a.to_bits(), b.to_bits(), set))
    }
}

/// libgcc's names, as RISC-V uses them.
#[cfg(target_arch = "riscv32")]
mod libgcc {
    use super::softfloat;

    /// a + b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __addsf3(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::add(a.to_bits(), b.to_bits()))
    }

    /// a − b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __subsf3(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::sub(a.to_bits(), b.to_bits()))
    }

    /// a · b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __mulsf3(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::mul(a.to_bits(), b.to_bits()))
    }

    /// a / b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __divsf3(a: f32, b: f32) -> f32 {
        f32::from_bits(softfloat::div(a.to_bits(), b.to_bits()))
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __floatsisf(i: i32) -> f32 {
        f32::from_bits(softfloat::from_i32(i))
    }

    /// The integer, rounded to nearest.
    #[unsafe(no_mangle)]
    pub extern "C" fn __floatunsisf(u: u32) -> f32 {
        f32::from_bits(softfloat::from_u32(u))
    }

    /// Zero if a = b; nonzero if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __eqsf2(a: f32, b: f32) -> i32 {
        softfloat::compare_le(a.to_bits(), b.to_bits())
    }

    /// Nonzero if a ≠ b or unordered; zero if a = b.
    #[unsafe(no_mangle)]
    pub extern "C" fn __nesf2(a: f32, b: f32) -> i32 {
        softfloat::compare_le(a.to_bits(), b.to_bits())
    }

    /// Negative if a < b; zero or positive if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __ltsf2(a: f32, b: f32) -> i32 {
        softfloat::compare_le(a.to_bits(), b.to_bits())
    }

    /// Zero or negative if a ≤ b; positive if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __lesf2(a: f32, b: f32) -> i32 {
        softfloat::compare_le(a.to_bits(), b.to_bits())
    }

    /// Zero or positive if a ≥ b; negative if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __gesf2(a: f32, b: f32) -> i32 {
        softfloat::compare_ge(a.to_bits(), b.to_bits())
    }

    /// Positive if a > b; zero or negative if not or unordered.
    #[unsafe(no_mangle)]
    pub extern "C" fn __gtsf2(a: f32, b: f32) -> i32 {
        softfloat::compare_ge(a.to_bits(), b.to_bits())
    }

    /// Nonzero if a or b is a NaN.
    #[unsafe(no_mangle)]
    pub extern "C" fn __unordsf2(a: f32, b: f32) -> i32 {
        i32::from(softfloat::compare(a.to_bits(), b.to_bits()).is_none())
    }
}
