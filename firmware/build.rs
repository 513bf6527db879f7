//! Puts the target's memory map where the linker finds it as `memory.x` (cortex-m-rt's
//! `link.x` includes it, and on RISC-V the firmware's own, `link-riscv.x`, which this
//! script puts there as `link.x`), links with `link.x`, and relinks when a map or the
//! RISC-V sections change.
//!
//! | target | machine (QEMU) | map |
//! |---|---|---|
//! | `thumbv7em-none-eabihf` | `mps2-an386` (Cortex-M4F) | `memory-mps2-an386.x` |
//! | `thumbv6m-none-eabi` | `microbit` (nRF51822, Cortex-M0) | `memory-microbit.x` |
//! | `riscv32imac-unknown-none-elf` | `virt` (RV32IMAC) | `memory-riscv-virt.x` |

use std::path::PathBuf;
use std::{env, fs};

fn main() {
    let target = env::var("TARGET").expect("cargo sets TARGET");
    let map = match target.as_str() {
        "thumbv7em-none-eabihf" => "memory-mps2-an386.x",
        "thumbv6m-none-eabi" => "memory-microbit.x",
        "riscv32imac-unknown-none-elf" => "memory-riscv-virt.x",
        other => panic!(
            "hodr-firmware has no memory map for {other}: \
             build for thumbv7em-none-eabihf, thumbv6m-none-eabi or riscv32imac-unknown-none-elf"
        ),
    };
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let text = fs::read(map).expect("the memory map is in the crate's directory");
    fs::write(out.join("memory.x"), text).expect("OUT_DIR is writable");
    // cortex-m-rt brings its link.x; on RISC-V the sections are the firmware's own.
    if target.starts_with("riscv") {
        let sections = fs::read("link-riscv.x").expect("link-riscv.x is in the crate's directory");
        fs::write(out.join("link.x"), sections).expect("OUT_DIR is writable");
    }
    println!("cargo:rustc-link-search={}", out.display());
    for map in [
        "memory-mps2-an386.x",
        "memory-microbit.x",
        "memory-riscv-virt.x",
        "link-riscv.x",
    ] {
        println!("cargo:rerun-if-changed={map}");
    }
    println!("cargo:rustc-link-arg=-Tlink.x");
}
