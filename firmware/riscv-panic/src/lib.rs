//! The RISC-V firmware's panic handler.
//!
//! A crate of its own for one reason: the firmware's other crates are built with RISC-V
//! call relaxation, and this one must not be (`../relax-exempt.sh` says why: with the
//! feature on the handler, every panic site keeps its message and location in .rodata).
//! It is linked for the handler alone and exports nothing.

#![no_std]
#![deny(missing_docs, unsafe_code)]

use riscv_semihosting::{debug, hio};

/// Reports the panic (without its message: formatting it would link `core::fmt`) and
/// makes QEMU exit with a failure status, so a test fails at once rather than timing out.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    if let Ok(mut stderr) = hio::hstderr() {
        let _ = stderr.write_all(b"panic\n");
    }
    debug::exit(debug::EXIT_FAILURE);
    loop {
        riscv::asm::wfi();
    }
}
