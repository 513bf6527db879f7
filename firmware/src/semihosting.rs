//! The RISC-V firmware's semihosting calls: open the host's standard output, write to
//! it, exit, and the panic report. A few instructions each, written for this firmware's
//! uses in place of riscv-semihosting's general streams and their error handling, which
//! the firmware dropped.

use core::sync::atomic::{AtomicUsize, Ordering};

/// Semihosting operation SYS_OPEN: opens a file; its argument points to the name, the
/// mode and the name's length. The name `:tt` is the host's console.
const SYS_OPEN: usize = 0x01;
/// Semihosting operation SYS_WRITE0: writes the NUL-terminated string its argument
/// points to to the host's console (QEMU: its standard error).
const SYS_WRITE0: usize = 0x04;
/// Semihosting operation SYS_WRITE: writes to an open file; its argument points to the
/// handle, the address of the bytes and their count. Returns the count not written.
const SYS_WRITE: usize = 0x05;
/// SYS_OPEN's mode "w": for the console, its output (QEMU: the standard output).
const MODE_W: usize = 4;
/// Semihosting operation SYS_EXIT: ends the program with the reason its argument gives.
const SYS_EXIT: usize = 0x18;
/// SYS_EXIT's reason ADP_Stopped_ApplicationExit: a normal end (QEMU exits with 0).
pub(crate) const EXIT_SUCCESS: usize = 0x2_0026;
/// SYS_EXIT's reason ADP_Stopped_RunTimeErrorUnknown: a failure (QEMU exits with 1).
pub(crate) const EXIT_FAILURE: usize = 0x2_0023;

/// Makes semihosting call `op` with argument `arg` and returns the host's answer.
///
/// The call is the RISC-V semihosting sequence: `ebreak` between two no-op shifts that
/// tell a debugger or emulator this breakpoint is a request. The three must be 4-byte
/// instructions (no compressed forms) and lie in one page; the 16-byte alignment keeps
/// them in one.
///
/// # Safety
///
/// `arg` must be what `op` takes: for the operations made here, the address of a
/// parameter block whose addresses are readable (SYS_OPEN, SYS_WRITE), of a
/// NUL-terminated string (SYS_WRITE0), or an exit reason (SYS_EXIT).
#[unsafe(naked)]
unsafe extern "C" fn semihost(op: usize, arg: usize) -> usize {
    core::arch::naked_asm!(
        ".option push",
        ".option norvc",
        ".balign 16",
        "slli zero, zero, 0x1f",
        "ebreak",
        "srai zero, zero, 0x7",
        ".option pop",
        "ret",
    )
}

/// SYS_OPEN's parameter block: name, mode, the name's length (without its NUL).
#[repr(C)]
struct OpenBlock(*const u8, usize, usize);

// SAFETY: the block is read only, and its pointer is to a string literal.
unsafe impl Sync for OpenBlock {}

/// The block that opens the host's standard output: `:tt` for writing. A static, so the
/// call passes its address instead of building it.
static OPEN_STDOUT: OpenBlock = OpenBlock(c":tt".as_ptr().cast(), MODE_W, 3);

/// The semihosting handle of the host's standard output, once [`open_stdout`] has
/// opened it (the firmware has one hart and no interrupts: plain loads and stores).
static STDOUT: AtomicUsize = AtomicUsize::new(0);

/// Opens the host's standard output for [`write`]; false if the host refuses.
pub(crate) fn open_stdout() -> bool {
    // SAFETY: SYS_OPEN reads the block, and from it the NUL-terminated name.
    let handle = unsafe { semihost(SYS_OPEN, (&raw const OPEN_STDOUT) as usize) };
    STDOUT.store(handle, Ordering::Relaxed);
    handle as isize >= 0
}

/// Writes `bytes` to the host's standard output, which [`open_stdout`] must have opened
/// (before, the host refuses the write). A write the host refuses or leaves unfinished
/// is given up: a report has nowhere to say so.
// Out of line: inlined, every write of the report built the parameter block itself.
#[inline(never)]
pub(crate) fn write(bytes: &[u8]) {
    let block = [
        STDOUT.load(Ordering::Relaxed),
        bytes.as_ptr() as usize,
        bytes.len(),
    ];
    // SAFETY: SYS_WRITE reads the block, and from it `bytes`.
    unsafe { semihost(SYS_WRITE, block.as_ptr() as usize) };
}

/// Ends the program with `reason` ([`EXIT_SUCCESS`] or [`EXIT_FAILURE`]). Without a
/// debugger or emulator to end it, rests in a loop.
pub(crate) fn exit(reason: usize) -> ! {
    // SAFETY: SYS_EXIT takes the reason itself on a 32-bit target.
    unsafe { semihost(SYS_EXIT, reason) };
    loop {
        // SAFETY: waits for an interrupt; touches no memory.
        unsafe { core::arch::asm!("wfi", options(nomem, nostack)) };
    }
}

/// The panic handler's report (riscv-panic/ jumps here): "panic" on the host's console
/// (QEMU: its standard error), then exit with [`EXIT_FAILURE`].
#[unsafe(no_mangle)]
extern "C" fn hodr_panic() -> ! {
    // SAFETY: SYS_WRITE0 reads the string up to its NUL.
    unsafe { semihost(SYS_WRITE0, c"panic\n".as_ptr() as usize) };
    exit(EXIT_FAILURE)
}
