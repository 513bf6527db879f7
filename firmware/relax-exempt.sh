#!/usr/bin/env bash
# Runs the compiler for the RISC-V panic handler's crate (riscv-panic/) without call
# relaxation, while every other crate keeps it. Cargo calls it as
# `build.rustc-workspace-wrapper` (.cargo/config.toml), for workspace members only (this
# crate and riscv-panic): $1 is the compiler (rustc, or clippy-driver), the rest its
# arguments. For the crate named hodr_firmware_riscv_panic it passes them on without
# `-C target-feature=+relax`; everything else it runs unchanged.
#
# Why: relaxation (.cargo/config.toml, riscv32imac only) marks each call so that the
# linker may shorten it from auipc + jalr to one jal. The standard library is prebuilt
# without the feature, and LLVM's argument promotion, which drops the panic handler's
# unused `PanicInfo` argument early enough for the panic paths' own arguments to die
# after it, acts only where every caller has the callee's exact target features. core's
# `panic_fmt` calls the panic handler; with the feature on the handler, the argument
# stayed, and every panic site kept its message template and source location in .rodata
# (908 B in the minimal build at 097b2f3, more than relaxation saved). The handler
# therefore lives in a crate of its own, built as the standard library is.
set -euo pipefail
exempt=false
for arg in "$@"; do
    if [[ $arg == hodr_firmware_riscv_panic ]]; then
        exempt=true
    fi
done
if ! $exempt; then
    exec "$@"
fi
args=()
while (($#)); do
    if [[ $1 == -C && ${2-} == target-feature=+relax ]]; then
        shift 2
        continue
    fi
    if [[ $1 == -Ctarget-feature=+relax ]]; then
        shift
        continue
    fi
    args+=("$1")
    shift
done
exec "${args[@]}"
