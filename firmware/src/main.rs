//! # hodr-firmware
//!
//! hodr-core on microcontrollers that QEMU emulates — the Arm MPS2 AN386 board
//! (Cortex-M4F, hardware `f32`), the BBC micro:bit (nRF51822, Cortex-M0, `f32` in
//! software) and the RISC-V `virt` machine (RV32IMAC, `f32` in software): QUAD and a
//! 1-D plateau minimised in `f32` with FR22 (Adam), OurHVPA (feature `ncg`) and OurH
//! (feature `hessian`), exactly as `hodr-embedded`'s host reference runs them. All
//! memory is static (`hodr_embedded::Storage` in .bss) or stack; there is no heap and
//! no allocator.
//!
//! Prints one report line per run and then the peak stack use over semihosting, and
//! exits QEMU with status 0 (1 after a panic).
//!
//! ```sh
//! cd firmware && cargo run --release                                        # Cortex-M4F
//! cd firmware && cargo run --release --target thumbv6m-none-eabi             # Cortex-M0
//! cd firmware && cargo run --release --target riscv32imac-unknown-none-elf   # RISC-V
//! ```

#![no_std]
#![no_main]
#![deny(missing_docs, unsafe_code)]

#[cfg(target_arch = "arm")]
#[allow(unsafe_code)]
mod arm;
// The Cortex-M4F computes `f32` in hardware and calls no such routines.
#[cfg(not(target_abi = "eabihf"))]
#[allow(unsafe_code)]
mod float;
#[allow(unsafe_code)]
mod mem;
#[cfg(target_arch = "riscv32")]
#[allow(unsafe_code)]
mod riscv;
#[cfg(target_arch = "riscv32")]
#[allow(unsafe_code)]
mod semihosting;
// The RISC-V panic handler, in a crate of its own (built without call relaxation, see
// relax-exempt.sh); linked for the handler alone.
#[cfg(target_arch = "riscv32")]
use hodr_firmware_riscv_panic as _;

use hodr_embedded::report::write_decimal;
use hodr_embedded::{Output, Storage, run_all};

/// Runs every problem with every compiled-in method, writing the report to `stdout`,
/// then the peak stack use that `stack_peak` measures afterwards (bytes used, bytes of
/// the stack region). Returns false, having run nothing, when there is no `stdout`
/// (the host refused the semihosting stream).
fn run_and_report(
    stdout: Option<impl FnMut(&[u8])>,
    storage: &mut Storage,
    stack_peak: impl Fn() -> (usize, usize),
) -> bool {
    let Some(mut out) = stdout else {
        return false;
    };
    run_all(&mut out, storage);
    let (used, size) = stack_peak();
    out.write(b"stack peak=");
    write_decimal(&mut out, used);
    out.write(b" bytes of ");
    write_decimal(&mut out, size);
    out.write(b"\n");
    true
}
