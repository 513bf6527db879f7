//! The RISC-V firmware's panic handler, and the semihosting numbers it shares with the
//! firmware's own calls (src/semihosting.rs).
//!
//! A crate of its own for one reason: the firmware's other crates are built with RISC-V
//! call relaxation, and the panic handler must not be (`../relax-exempt.sh` says why:
//! with the feature on the handler, every panic site keeps its message and location in
//! .rodata). It calls nothing, so that no call of this crate goes unrelaxed: its two
//! semihosting requests are written out in place.

#![no_std]
#![deny(missing_docs, unsafe_code)]

/// Semihosting operation SYS_OPEN: opens a file; its argument points to the name, the
/// mode and the name's length. The name `:tt` is the host's console.
pub const SYS_OPEN: usize = 0x01;
/// Semihosting operation SYS_WRITE0: writes the NUL-terminated string its argument
/// points to to the host's console (QEMU: its standard error).
pub const SYS_WRITE0: usize = 0x04;
/// Semihosting operation SYS_WRITE: writes to an open file; its argument points to the
/// handle, the address of the bytes and their count. Returns the count not written.
pub const SYS_WRITE: usize = 0x05;
/// SYS_OPEN's mode "w": for the console, its output (QEMU: the standard output).
pub const MODE_W: usize = 4;
/// Semihosting operation SYS_EXIT: ends the program with the reason its argument gives.
pub const SYS_EXIT: usize = 0x18;
/// SYS_EXIT's reason ADP_Stopped_ApplicationExit: a normal end (QEMU exits with 0).
pub const EXIT_SUCCESS: usize = 0x2_0026;
/// SYS_EXIT's reason ADP_Stopped_RunTimeErrorUnknown: a failure (QEMU exits with 1).
pub const EXIT_FAILURE: usize = 0x2_0023;

/// Reports the panic (without its message: formatting it would link `core::fmt`) and
/// makes QEMU exit with a failure status, so a test fails at once rather than timing out.
///
/// Two semihosting requests, each the RISC-V sequence `ebreak` between two no-op shifts
/// that tell a debugger or emulator the breakpoint is a request: SYS_WRITE0 of "panic",
/// then SYS_EXIT. The shifts and `ebreak` must be 4-byte instructions (no compressed
/// forms) in one page; each sequence starts 16-aligned, which keeps it in one.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: SYS_WRITE0 reads the NUL-terminated message a1 points to; SYS_EXIT takes
    // the reason itself on a 32-bit target and does not return (the rest loop is for a
    // host that lets it).
    #[allow(unsafe_code)]
    unsafe {
        core::arch::asm!(
            ".option push",
            ".option norvc",
            ".balign 16",
            "slli zero, zero, 0x1f",
            "ebreak",
            "srai zero, zero, 0x7",
            "li a0, {exit}",
            "li a1, {failure}",
            ".balign 16",
            "slli zero, zero, 0x1f",
            "ebreak",
            "srai zero, zero, 0x7",
            ".option pop",
            "1:",
            "wfi",
            "j 1b",
            exit = const SYS_EXIT,
            failure = const EXIT_FAILURE,
            in("a0") SYS_WRITE0,
            in("a1") c"panic\n".as_ptr(),
            options(noreturn, nostack),
        )
    }
}
