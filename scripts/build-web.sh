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
# The cargo profile: release for the page you host; web-smoke (Cargo.toml) for CI's smoke test.
profile=${WEB_PROFILE:-release}

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
cp web/index.html "$out/"
cp -r lessons presets assets "$out/"
(cd "$out" && find lessons presets assets -type f | LC_ALL=C sort > files.txt)
echo "== $out: $(du -sh "$out" | cut -f1); texplore_bg.wasm $(wc -c < "$out/texplore_bg.wasm") bytes, $(gzip -9 -c "$out/texplore_bg.wasm" | wc -c) gzipped"
