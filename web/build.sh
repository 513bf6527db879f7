#!/usr/bin/env bash
# Builds the web demo into web/dist: hodr-web for wasm32-unknown-unknown (release),
# wasm-bindgen's JavaScript glue (--target web, loaded as an ES module) and the static
# front end in www/. Needs the wasm32 target and wasm-bindgen-cli of the lockfile's
# wasm-bindgen version (web/README.md).
set -euo pipefail
cd "$(dirname "$0")"

want=$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p')
have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have" != "$want" ]; then
    echo "wasm-bindgen-cli $want is needed (found '${have:-none}'):" >&2
    echo "  rustup target add wasm32-unknown-unknown" >&2
    echo "  cargo install wasm-bindgen-cli --version $want --locked" >&2
    exit 1
fi

cargo build --release --locked --target wasm32-unknown-unknown --lib
rm -rf dist
mkdir -p dist
wasm-bindgen --target web --no-typescript --out-dir dist/pkg \
    target/wasm32-unknown-unknown/release/hodr_web.wasm
cp www/* dist/
echo "built web/dist ($(du -sh dist | cut -f1))"
