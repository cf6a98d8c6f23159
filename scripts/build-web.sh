#!/usr/bin/env bash
# Builds texplore for the browser: a folder (default target/web, or $1) that any static file
# server can serve (python3 -m http.server -d target/web), holding index.html, the wasm module
# and its JavaScript glue (wasm-bindgen), and the shipped lessons, presets and assets with their
# list (files.txt), which the page fetches before the window starts.
#
# Needs the wasm32-unknown-unknown target and wasm-bindgen-cli at the version Cargo.lock pins
# (installed here with cargo if missing or different).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/web}
target_dir=${CARGO_TARGET_DIR:-target}
# The cargo profile: web (Cargo.toml: release, its dependencies optimised for size) for the page
# you host; web-smoke for CI's browser test.
profile=${WEB_PROFILE:-web}

version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
if ! command -v wasm-bindgen >/dev/null 2>&1 || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$version" ]; then
  echo "== installing wasm-bindgen-cli $version (the version Cargo.lock pins)"
  # Only the wasm-bindgen binary, without TLS (it downloads nothing here): half the build.
  cargo install wasm-bindgen-cli --version "$version" --no-default-features --bin wasm-bindgen
fi
if command -v rustup >/dev/null 2>&1; then
  rustup target add wasm32-unknown-unknown >/dev/null
fi

cargo build --profile "$profile" --target wasm32-unknown-unknown --no-default-features --features web \
  --bin texplore-web
rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out" --out-name texplore \
  "$target_dir/wasm32-unknown-unknown/$profile/texplore-web.wasm"
wasm="$out/texplore_bg.wasm"
# WASM_OPT=1: binaryen's optimiser for size (measured in docs/performance.md#the-page).
if [ "${WASM_OPT:-0}" != 0 ] && command -v wasm-opt >/dev/null 2>&1; then
  wasm-opt ${WASM_OPT_FLAGS:--Oz} --enable-simd --enable-bulk-memory --enable-sign-ext \
    --enable-nontrapping-float-to-int --enable-mutable-globals --enable-reference-types \
    --enable-multivalue -o "$wasm.opt" "$wasm"
  mv "$wasm.opt" "$wasm"
fi
# The page fetches the module gzipped and decompresses it itself (web/index.html), so a plain
# static server (python3 -m http.server) sends a third of its bytes; the uncompressed file is for
# browsers without DecompressionStream.
gzip -9 -n -k "$wasm"
cp web/index.html web/worker.js "$out/"
cp -r lessons presets assets "$out/"
# The shipped files and their sizes: the page fetches the small ones before the window starts
# and the others when a scene needs them (src/gui/web/mod.rs).
(cd "$out" && find lessons presets assets -type f | LC_ALL=C sort | while read -r f; do
  printf '%s %s\n' "$f" "$(wc -c < "$f")"; done > files.txt)
echo "== $out: $(du -sh "$out" | cut -f1); texplore_bg.wasm $(wc -c < "$wasm") bytes, texplore_bg.wasm.gz $(wc -c < "$wasm.gz") bytes"
