#!/usr/bin/env bash
# Runs the compiler for this crate (hodr-firmware) without RISC-V call relaxation, while
# its dependencies keep it. Cargo calls it as `build.rustc-workspace-wrapper`
# (.cargo/config.toml), for workspace members only, which here is this crate alone:
# $1 is the compiler (rustc, or clippy-driver), the rest its arguments. It passes them on
# without `-C target-feature=+relax` and changes nothing else.
#
# Why: relaxation (`.cargo/config.toml`, riscv32imac only) marks each call so that the
# linker may shorten it from auipc + jalr to one jal. The standard library is prebuilt
# without the feature, and LLVM's argument promotion, which drops the panic handler's
# unused `PanicInfo` argument early enough for the panic paths' own arguments to die
# after it, acts only where every caller has the callee's exact target features. core's
# `panic_fmt` calls this crate's panic handler; with the feature on here, the argument
# stayed, and every panic site kept its message template and source location in .rodata
# (908 B in the minimal build at 097b2f3, more than relaxation saved). Without the feature on this crate
# the panic paths are what they were, and the rest of the code (hodr-core,
# hodr-embedded: the dependencies; this crate's `main` cannot inline them across the
# feature difference) is relaxed.
set -euo pipefail
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
