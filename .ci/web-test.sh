#!/usr/bin/env bash
# The web demo (web/README.md): hodr-web's formatting, lints (native and wasm32) and
# native tests, the wasm build, then the page in headless Chromium checked against the
# native reference (web/test/browser_test.py; screenshots in web/target/web-test/).
# Installs the wasm32 target, wasm-bindgen-cli of the lockfile's wasm-bindgen version,
# and Debian's chromium and chromium-driver when they are missing.
set -euo pipefail
cd "$(dirname "$0")/.."

rustup target add wasm32-unknown-unknown

(
    cd web
    cargo fmt --check
    cargo clippy --locked --all-targets -- -D warnings
    cargo clippy --locked --target wasm32-unknown-unknown --all-targets -- -D warnings
    cargo test --locked --release
)

want=$(grep -A1 '^name = "wasm-bindgen"$' web/Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p')
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$want" ]; then
    # --locked first; a registry mirror that lacks one of the CLI's locked dependencies
    # (webpki-roots 1.0.11 on this project's sandbox) gets a fresh resolution instead.
    cargo install wasm-bindgen-cli --version "$want" --locked \
        || cargo install wasm-bindgen-cli --version "$want"
fi

if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
    as_root=()
    if [ "$(id -u)" -ne 0 ]; then as_root=(sudo -n); fi
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
        chromium chromium-driver
fi

bash web/build.sh
python3 web/test/browser_test.py
