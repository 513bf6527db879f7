//! RISC-V start-up (riscv-rt), output and exit over semihosting (through the panic
//! handler's crate, riscv-panic/), and the peak stack use
//! from a paint this module lays down itself (riscv-rt has none).
//!
//! The first thing `main` does is fill the free stack, from `__estack` (the end of .bss;
//! there is no heap) up to its own stack pointer, with [`PAINT`]. Whatever the program
//! pushes later scrubs the paint off, so the lowest scrubbed word marks the deepest the
//! stack has reached. A frame that happened to store the paint value itself at its lowest
//! word would be missed: the figure can be low by such a run of words, never high.

use hodr_embedded::Storage;
use hodr_firmware_riscv_panic::{EXIT_FAILURE, EXIT_SUCCESS, exit, open_stdout, write};
use riscv_rt::entry;

/// The paint: a value that stack frames rarely hold.
const PAINT: u32 = 0xCCCC_CCCC;

unsafe extern "C" {
    /// The top of the stack region (riscv-rt's linker script; the stack grows down).
    static _stack_start: u32;
    /// The bottom of the stack region: the end of statically allocated RAM.
    static __estack: u32;
}

/// The workload's memory, in .bss.
static mut STORAGE: Storage = Storage::new();

#[entry]
fn main() -> ! {
    paint();
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

/// Where riscv-rt sends every exception, its `no-exceptions` feature leaving the
/// dispatch to the program: the firmware handles none, so it rests here, as riscv-rt's
/// default handlers would (QEMU's timeout then ends a test run).
#[unsafe(no_mangle)]
extern "C" fn _dispatch_exception() -> ! {
    loop {
        riscv::asm::wfi();
    }
}

/// Where riscv-rt sends every interrupt (feature `no-interrupts`): none is enabled, so
/// none arrives; should one, it rests here too.
#[unsafe(no_mangle)]
extern "C" fn _dispatch_core_interrupt() -> ! {
    loop {
        riscv::asm::wfi();
    }
}

/// The stack pointer.
#[inline(always)]
fn stack_pointer() -> usize {
    let sp: usize;
    // SAFETY: reads a register, touches no memory.
    unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
    sp
}

/// Paints the free stack below this function's frame.
#[inline(never)]
fn paint() {
    let bottom = (&raw const __estack) as usize;
    let sp = stack_pointer() & !3;
    let mut word = bottom;
    while word < sp {
        // SAFETY: `word` is 4-aligned (riscv-rt aligns the end of .bss) and lies between
        // the end of .bss and the stack pointer, memory no Rust object occupies; the loop
        // itself keeps its state in registers.
        unsafe { (word as *mut u32).write_volatile(PAINT) };
        word += 4;
    }
}

/// Bytes of stack used so far at most, and the size of the stack region.
fn peak() -> (usize, usize) {
    let bottom = (&raw const __estack) as usize;
    let top = (&raw const _stack_start) as usize;
    let sp = stack_pointer();
    let mut word = bottom;
    while word < sp {
        // SAFETY: as in `paint`; a volatile read has no side effects.
        let value = unsafe { (word as *const u32).read_volatile() };
        if value != PAINT {
            break;
        }
        word += 4;
    }
    (top - word, top - bottom)
}
