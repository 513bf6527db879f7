//! The RISC-V firmware's panic handler.
//!
//! A crate of its own for one reason: the firmware's other crates are built with RISC-V
//! call relaxation, and the panic handler must not be (`../relax-exempt.sh` says why:
//! with the feature on the handler, every panic site keeps its message and location in
//! .rodata). So that nothing here pays for the missing relaxation, the handler is one
//! jump to the firmware's `hodr_panic` (src/semihosting.rs), which reports and exits.

#![no_std]
#![deny(missing_docs, unsafe_code)]

#[allow(unsafe_code)]
unsafe extern "C" {
    /// The firmware's report of a panic: says "panic" and exits with a failure status.
    fn hodr_panic() -> !;
}

/// Reports the panic (without its message: formatting it would link `core::fmt`) through
/// the firmware, which makes QEMU exit with a failure status, so a test fails at once
/// rather than timing out. A jump (4 bytes, whatever the distance in a 1 MiB program),
/// where a call from this crate would be auipc + jalr.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: `hodr_panic` takes nothing and does not return.
    #[allow(unsafe_code)]
    unsafe {
        core::arch::asm!("j {}", sym hodr_panic, options(noreturn, nostack))
    }
}
