//! Cortex-M start-up (cortex-m-rt), output and exit over semihosting, and the peak
//! stack use from the paint that cortex-m-rt's `paint-stack` feature lays down.
//!
//! The reset handler fills the whole stack region, `_stack_end` (the end of .bss) up to
//! `_stack_start` (the top of RAM), with [`STACK_PAINT_VALUE`] before any Rust code runs.
//! Whatever the program has pushed since has scrubbed the paint off, so the lowest
//! scrubbed word marks the deepest the stack has reached. A frame that happened to store
//! the paint value itself at its lowest word would be missed: the figure can be low by
//! such a run of words, never high.

use cortex_m_rt::{STACK_PAINT_VALUE, entry};
use cortex_m_semihosting::{debug, hio};
use hodr_embedded::Storage;

#[entry]
fn main() -> ! {
    // cortex-m-rt hands `static mut`s declared at the top of the entry function to it as
    // `&'static mut`: the storage lives in .bss, not on the stack.
    static mut STORAGE: Storage = Storage::new();

    // Nowhere to report a failed write to the host's stdout: drop it.
    let stdout = hio::hstdout().ok().map(|mut stream| {
        move |bytes: &[u8]| {
            let _ = stream.write_all(bytes);
        }
    });
    let status = if crate::run_and_report(stdout, STORAGE, peak) {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    };
    debug::exit(status);
    // Without a debugger or emulator to end the program, rest here.
    loop {
        cortex_m::asm::wfi();
    }
}

/// Reports the panic (without its message: formatting it would link `core::fmt`) and
/// makes QEMU exit with a failure status, so a test fails at once rather than timing out.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    if let Ok(mut stderr) = hio::hstderr() {
        let _ = stderr.write_all(b"panic\n");
    }
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

unsafe extern "C" {
    /// The top of the stack region (cortex-m-rt's linker script; the stack grows down).
    static _stack_start: u32;
    /// The bottom of the stack region: the end of statically allocated RAM.
    static _stack_end: u32;
}

/// Bytes of stack used so far at most, and the size of the stack region.
fn peak() -> (usize, usize) {
    let bottom = (&raw const _stack_end) as usize;
    let top = (&raw const _stack_start) as usize;
    // Live frames, this one included, lie at or above the stack pointer; stop there.
    let sp = cortex_m::register::msp::read() as usize;
    let mut word = bottom;
    while word < sp {
        // SAFETY: `word` is 4-aligned (cortex-m-rt asserts `_stack_end % 4 == 0`) and
        // within the RAM region between the end of .bss and the stack pointer, which no
        // Rust object occupies; a volatile read of it has no side effects.
        let value = unsafe { (word as *const u32).read_volatile() };
        if value != STACK_PAINT_VALUE {
            break;
        }
        word += 4;
    }
    (top - word, top - bottom)
}
