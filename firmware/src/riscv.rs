//! RISC-V start-up, output and exit over semihosting (src/semihosting.rs), and the peak
//! stack use from a paint the start-up lays down.
//!
//! The start-up is the firmware's own (with `link-riscv.x`, its sections): set the stack
//! pointer, clear .bss, paint the stack, point every trap at a rest loop, and jump to
//! [`main`]. riscv-rt did the same and more — a trap entry saving the registers for
//! handlers, their dispatch, multi-hart and interrupt set-up — which the firmware,
//! enabling no interrupt and handling no exception, never used: 232 bytes of the minimal
//! build (and 1.1 KiB of unwind tables in flash, which link-riscv.x discards). The
//! firmware has no initialised statics, so there is no .data to copy: link-riscv.x
//! refuses a build that would have one.
//!
//! The paint: the start-up fills the whole stack region, from `__estack` (the end of
//! .bss; there is no heap) to `_stack_start`, with [`PAINT`] before any Rust code runs.
//! Whatever the program pushes later scrubs the paint off, so the lowest scrubbed word
//! marks the deepest the stack has reached. A frame that happened to store the paint
//! value itself at its lowest word would be missed: the figure can be low by such a run
//! of words, never high.

use crate::semihosting::{EXIT_FAILURE, EXIT_SUCCESS, exit, open_stdout, write};
use hodr_embedded::Storage;

core::arch::global_asm!(
    ".pushsection .text.start, \"ax\", @progbits",
    ".global _start",
    "_start:",
    // No global pointer: nothing is addressed relative to gp (the linker relaxes calls
    // only, as rust-lld does by default).
    "la sp, _stack_start",
    // .bss to zero, then the stack above it (t0 goes on from the end of .bss, 4-aligned)
    // to the paint.
    "la t0, __sbss",
    "la t1, __ebss",
    "1:",
    "bgeu t0, t1, 2f",
    "sw zero, 0(t0)",
    "addi t0, t0, 4",
    "j 1b",
    "2:",
    "li t1, {paint}",
    "3:",
    "bgeu t0, sp, 4f",
    "sw t1, 0(t0)",
    "addi t0, t0, 4",
    "j 3b",
    // Every trap (there are no interrupts enabled and no exception handled) rests; the
    // trap vector's address must be 4-aligned (direct mode).
    "4:",
    "la t0, 5f",
    "csrw mtvec, t0",
    "j main",
    ".balign 4",
    "5:",
    "wfi",
    "j 5b",
    ".popsection",
    paint = const PAINT,
);

/// The paint: a value that stack frames rarely hold.
const PAINT: u32 = 0xCCCC_CCCC;

unsafe extern "C" {
    /// The top of the stack region (link-riscv.x; the stack grows down).
    static _stack_start: u32;
    /// The bottom of the stack region: the end of statically allocated RAM.
    static __estack: u32;
}

/// The workload's memory, in .bss.
static mut STORAGE: Storage = Storage::new();

/// The program, entered from the start-up with an empty, painted stack and cleared
/// .bss.
#[unsafe(no_mangle)]
extern "C" fn main() -> ! {
    // SAFETY: `main` runs once, on the only hart, and nothing else refers to STORAGE.
    // (Through a raw pointer: a direct `&mut STORAGE` is refused by the 2024 edition.)
    #[allow(clippy::deref_addrof)]
    let storage = unsafe { &mut *(&raw mut STORAGE) };
    let stdout = open_stdout().then_some(write);
    let status = if crate::run_and_report(stdout, storage, peak) {
        EXIT_SUCCESS
    } else {
        EXIT_FAILURE
    };
    exit(status)
}

/// The stack pointer.
#[inline(always)]
fn stack_pointer() -> usize {
    let sp: usize;
    // SAFETY: reads a register, touches no memory.
    unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
    sp
}

/// Bytes of stack used so far at most, and the size of the stack region.
fn peak() -> (usize, usize) {
    let bottom = (&raw const __estack) as usize;
    let top = (&raw const _stack_start) as usize;
    let sp = stack_pointer();
    let mut word = bottom;
    while word < sp {
        // SAFETY: `word` is 4-aligned (link-riscv.x aligns the end of .bss) and lies
        // between the end of .bss and the stack pointer, memory no Rust object occupies;
        // a volatile read has no side effects.
        let value = unsafe { (word as *const u32).read_volatile() };
        if value != PAINT {
            break;
        }
        word += 4;
    }
    (top - word, top - bottom)
}
