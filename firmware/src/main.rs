//! # hodr-firmware
//!
//! hodr-core on a Cortex-M4F, the Arm MPS2 AN386 board that QEMU emulates: QUAD and a
//! 1-D plateau minimised in `f32` with FR22 (Adam), OurHVPA (feature `ncg`) and OurH
//! (feature `hessian`), exactly as `hodr-embedded`'s host reference runs them. All
//! memory is static (`hodr_embedded::Storage` in .bss) or stack; there is no heap and
//! no allocator.
//!
//! Prints one report line per run and then the peak stack use over semihosting, and
//! exits QEMU with status 0 (1 after a panic).
//!
//! ```sh
//! cd firmware && cargo run --release    # needs qemu-system-arm
//! ```

#![no_std]
#![no_main]
#![deny(missing_docs, unsafe_code)]

#[allow(unsafe_code)]
mod stack;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hio};
use hodr_embedded::report::write_decimal;
use hodr_embedded::{Output, Storage, run_all};

#[entry]
fn main() -> ! {
    // cortex-m-rt hands `static mut`s declared at the top of the entry function to it as
    // `&'static mut`: the storage lives in .bss, not on the stack.
    static mut STORAGE: Storage = Storage::new();

    let status = match hio::hstdout() {
        Ok(mut stdout) => {
            // Nowhere to report a failed write to the host's stdout: drop it.
            let mut out = |bytes: &[u8]| {
                let _ = stdout.write_all(bytes);
            };
            run_all(&mut out, STORAGE);
            let (used, size) = stack::peak();
            out.write(b"stack peak=");
            write_decimal(&mut out, used);
            out.write(b" bytes of ");
            write_decimal(&mut out, size);
            out.write(b"\n");
            debug::EXIT_SUCCESS
        }
        Err(()) => debug::EXIT_FAILURE,
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
