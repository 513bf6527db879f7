#!/usr/bin/env bash
# hodr-core on microcontrollers: builds firmware/ for each target and feature set, runs
# it under QEMU (semihosting) and checks that its report equals, bit for bit, the host
# reference built from the same code (hodr-embedded), then prints the size and stack
# table of the top-level BENCHMARKS.md ("hodr-core on a microcontroller").
#
# Targets: Cortex-M4F (mps2-an386), Cortex-M0 (microbit), RISC-V RV32IMAC (virt).
# Needs qemu-system-arm and qemu-system-riscv32 on the PATH; installs the Rust targets
# and llvm-tools itself. With --count, also counts the instructions each firmware
# executes (QEMU's exec log, one instruction per translation block: slow) and divides by
# its objective evaluations.
# Exits non-zero when a build fails, a firmware fails or hangs, a report differs, or a
# build outgrows its size bound (after printing the table): the minimal build at most
# 6 KiB of .text on every target, the ncg build (FR22 + OurHVPA) at most 16 KiB on the
# Cortex-M0, the goals of the issue "hodr-core on the smallest targets".
set -euo pipefail
cd "$(dirname "$0")/.."

count=false
if [ "${1:-}" = "--count" ]; then count=true; fi

for qemu in qemu-system-arm qemu-system-riscv32; do
    if ! command -v "$qemu" >/dev/null; then
        echo "$qemu not found: apt-get install qemu-system-arm qemu-system-misc" >&2
        exit 1
    fi
done
rustup target add thumbv7em-none-eabihf thumbv6m-none-eabi riscv32imac-unknown-none-elf
rustup component add llvm-tools
llvm_bin="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
# One instruction per translation block, for --count: QEMU 8.1 replaced -singlestep
# (gone in 10.0) by the TCG option one-insn-per-tb.
read -r qemu_major qemu_minor < <(qemu-system-arm --version |
    sed -n 's/^QEMU emulator version \([0-9]*\)\.\([0-9]*\).*/\1 \2/p')
if [ "$qemu_major" -gt 8 ] || { [ "$qemu_major" -eq 8 ] && [ "$qemu_minor" -ge 1 ]; }; then
    one_insn_per_tb=(-accel tcg,one-insn-per-tb=on)
else
    one_insn_per_tb=(-singlestep)
fi

# The firmware is a workspace of its own: the host workspace's fmt and clippy skip it.
(cd firmware && cargo fmt --check)

# name, Rust target, QEMU command (the ELF follows).
targets=(
    "Cortex-M4F|thumbv7em-none-eabihf|qemu-system-arm -machine mps2-an386 -cpu cortex-m4"
    "Cortex-M0|thumbv6m-none-eabi|qemu-system-arm -machine microbit"
    "RV32IMAC|riscv32imac-unknown-none-elf|qemu-system-riscv32 -machine virt -bios none"
)
# name, then the cargo feature flags shared by the firmware and its host reference.
configs=(
    "minimal|--no-default-features"
    "auto|--no-default-features --features auto"
    "ncg|--no-default-features --features ncg"
    "full|"
)
out=firmware/target/qemu-test
mkdir -p "$out"
header="| target | features | methods | .text | .rodata | .data | .bss | peak stack |"
rule="|---|---|---|---|---|---|---|---|"
if $count; then
    header+=" instructions | evaluations | instructions per evaluation |"
    rule+="---|---|---|"
fi
table="$header
$rule"
oversized=""
for target in "${targets[@]}"; do
    IFS='|' read -r arch triple qemu_command <<<"$target"
    read -r -a qemu <<<"$qemu_command"
    (cd firmware && cargo clippy --release --locked --target "$triple" -- -D warnings)
    for config in "${configs[@]}"; do
        name=${config%%|*}
        read -r -a flags <<<"${config#*|}"
        echo "== $arch $name: ${flags[*]:-default features}"
        # -D warnings reaches hodr-core and hodr-embedded (path dependencies), whose
        # feature-gated code the host workspace's clippy only sees with every feature.
        # Given as the target's rustflags, it joins firmware/.cargo/config.toml's, where
        # RUSTFLAGS would replace them.
        (cd firmware && cargo build --release --locked --target "$triple" \
            --config "target.$triple.rustflags = ['-D', 'warnings']" "${flags[@]}")
        elf="$out/hodr-firmware-$triple-$name"
        cp "firmware/target/$triple/release/hodr-firmware" "$elf"
        log="$out/$triple-$name.log"

        # QEMU exits with the firmware's semihosting exit status; a hang hits the timeout.
        if ! timeout 300 "${qemu[@]}" -nographic -semihosting-config enable=on,target=native \
            -kernel "$elf" >"$log"; then
            echo "firmware ($arch, $name) failed or timed out; its output:" >&2
            cat "$log" >&2
            exit 1
        fi
        cat "$log"
        check=$(cargo run --quiet --locked -p hodr-embedded --example host_reference \
            "${flags[@]}" -- --check "$log")
        echo "$check"
        if ! grep -q "bit-identical" <<<"$check"; then
            echo "firmware ($arch, $name) is not bit-identical to the host" >&2
            exit 1
        fi

        sizes=$("$llvm_bin/llvm-size" -A "$elf")
        section() { awk -v s="$1" '$1 == s { print $2 }' <<<"$sizes"; }
        methods=$(sed -n 's/^run [A-Z]* \([^ ]*\) .*/\1/p' "$log" | sort -u | paste -sd, -)
        stack=$(sed -n 's/^stack peak=\([0-9]*\) bytes.*/\1/p' "$log")
        row="| $arch | $name | $methods | $(section .text) | $(section .rodata) | $(section .data) | $(section .bss) | $stack |"
        if $count; then
            # One translation block per instruction, each logged as one "Trace" line.
            instructions=$(timeout 3600 "${qemu[@]}" -nographic "${one_insn_per_tb[@]}" \
                -semihosting-config enable=on,target=native -d exec,nochain -D /dev/stderr \
                -kernel "$elf" 2>&1 >/dev/null | grep -c '^Trace')
            evaluations=$(sed -n 's/^run .* evaluations=\([0-9]*\) .*/\1/p' "$log" |
                awk '{ s += $1 } END { print s }')
            row+=" $instructions | $evaluations | $((instructions / evaluations)) |"
        fi
        table+="
$row"
        bound=""
        if [ "$name" = minimal ]; then bound=6144; fi
        if [ "$name" = ncg ] && [ "$triple" = thumbv6m-none-eabi ]; then bound=16384; fi
        if [ -n "$bound" ] && [ "$(section .text)" -gt "$bound" ]; then
            oversized+="firmware ($arch, $name): .text $(section .text) B exceeds its bound of $bound B
"
        fi
    done
done

echo
echo "Sizes in bytes (llvm-size -A), peak stack in bytes (painted stack):"
echo "$table"
if [ -n "$oversized" ]; then
    printf '%s' "$oversized" >&2
    exit 1
fi
