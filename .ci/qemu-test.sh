#!/usr/bin/env bash
# hodr-core on a Cortex-M4F: builds firmware/ for each feature set, runs it under QEMU
# (mps2-an386, semihosting) and checks its report against the host reference built from
# the same code (hodr-embedded), then prints the size and stack table of
# the top-level BENCHMARKS.md ("hodr-core on a microcontroller").
#
# Needs qemu-system-arm on the PATH; installs the Rust target and llvm-tools itself.
# Exits non-zero when a build fails, the firmware fails or hangs, or a report differs.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v qemu-system-arm >/dev/null; then
    echo "qemu-system-arm not found: apt-get install qemu-system-arm" >&2
    exit 1
fi
rustup target add thumbv7em-none-eabihf
rustup component add llvm-tools
llvm_bin="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"

# The firmware is a workspace of its own: the host workspace's fmt and clippy skip it.
(cd firmware && cargo fmt --check && cargo clippy --release --locked -- -D warnings)

# name, then the cargo feature flags shared by the firmware and its host reference.
configs=(
    "minimal|--no-default-features"
    "ncg|--no-default-features --features ncg"
    "full|"
)
out=firmware/target/qemu-test
mkdir -p "$out"
table="| features | hodr-core features | .text | .rodata | .data | .bss | peak stack |
|---|---|---|---|---|---|---|"
for config in "${configs[@]}"; do
    name=${config%%|*}
    read -r -a flags <<<"${config#*|}"
    echo "== $name: ${flags[*]:-default features}"
    # -D warnings reaches hodr-core and hodr-embedded (path dependencies), whose
    # feature-gated code the host workspace's clippy only sees with every feature.
    (cd firmware && RUSTFLAGS="-D warnings" cargo build --release --locked "${flags[@]}")
    elf="$out/hodr-firmware-$name"
    cp firmware/target/thumbv7em-none-eabihf/release/hodr-firmware "$elf"

    # QEMU exits with the firmware's semihosting exit status; a hang hits the timeout.
    if ! timeout 120 qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic \
        -semihosting-config enable=on,target=native -kernel "$elf" >"$out/$name.log"; then
        echo "firmware ($name) failed or timed out; its output:" >&2
        cat "$out/$name.log" >&2
        exit 1
    fi
    cat "$out/$name.log"
    cargo run --quiet --locked -p hodr-embedded --example host_reference "${flags[@]}" \
        -- --check "$out/$name.log"

    sizes=$("$llvm_bin/llvm-size" -A "$elf")
    section() { awk -v s="$1" '$1 == s { print $2 }' <<<"$sizes"; }
    core_features=$(case $name in
        minimal) echo "none (gradient, Adam)" ;;
        ncg) echo "hvp, aggregate, cg" ;;
        full) echo "all (+ hessian)" ;;
    esac)
    stack=$(sed -n 's/^stack peak=\([0-9]*\) bytes.*/\1/p' "$out/$name.log")
    table+="
| $name | $core_features | $(section .text) | $(section .rodata) | $(section .data) | $(section .bss) | $stack |"
done

echo
echo "Sizes in bytes (llvm-size -A), peak stack in bytes (painted stack):"
echo "$table"
