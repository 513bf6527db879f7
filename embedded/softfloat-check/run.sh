#!/usr/bin/env bash
# Checks hodr_embedded::softfloat against compiler-builtins' own f32 routines, bit for bit,
# NaN results and comparison values included: compiler-builtins is the same Rust code on
# every target, so its host build stands for the firmware targets'. The host's libgcc
# defines the same symbol names, so the objects defining them are taken out of the
# toolchain's compiler-builtins rlib, their symbols renamed to cb__*, and linked into
# the check program. Usage: bash embedded/softfloat-check/run.sh [RANDOM_PAIRS]
set -euo pipefail
cd "$(dirname "$0")"
sysroot=$(rustc --print sysroot)
host=$(rustc -vV | sed -n 's/^host: //p')
bin="$sysroot/lib/rustlib/$host/bin"
rlib=$(ls "$sysroot/lib/rustlib/$host/lib/"libcompiler_builtins-*.rlib)
out=target/compiler-builtins
rm -rf "$out" && mkdir -p "$out"
symbols=(__addsf3 __subsf3 __mulsf3 __divsf3 __lesf2 __gesf2 __eqsf2 __ltsf2 __nesf2 __gtsf2
    __unordsf2 __floatsisf __floatunsisf)
renames=()
objects=()
for s in "${symbols[@]}"; do
    renames+=(--redefine-sym "$s=cb$s")
    member=$("$bin/llvm-nm" -A "$rlib" 2>/dev/null | sed -n "s/^[^:]*:\([^:]*\): [0-9a-f]* [TW] $s\$/\1/p")
    (cd "$out" && "$bin/llvm-ar" x "$rlib" "$member")
    objects+=("$member")
done
for o in "${objects[@]}"; do
    "$bin/llvm-objcopy" "${renames[@]}" "$out/$o"
done
(cd "$out" && "$bin/llvm-ar" rcs libcb.a "${objects[@]}")
RUSTFLAGS="-L $PWD/$out" cargo run --release --quiet -- "$@"
