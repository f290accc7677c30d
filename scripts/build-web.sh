#!/usr/bin/env bash
# The browser build (docs/web.md): crates/hatchery-web compiled for wasm32-unknown-unknown and
# bound to JavaScript by wasm-bindgen, written to target/web-pkg (hatchery_web.js and
# hatchery_web_bg.wasm), where `hatchery export-web` finds it. Installs the wasm32 target (rustup)
# and the wasm-bindgen CLI of the version Cargo.lock pins (into target/tools) when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
target_dir="${CARGO_TARGET_DIR:-target}"

if ! rustc --print target-libdir --target wasm32-unknown-unknown >/dev/null 2>&1 ||
    [ ! -d "$(rustc --print target-libdir --target wasm32-unknown-unknown)" ]; then
    command -v rustup >/dev/null 2>&1 || {
        echo "build-web: the wasm32-unknown-unknown target is missing and rustup is not here to add it" >&2
        exit 1
    }
    rustup target add wasm32-unknown-unknown
fi

# wasm-bindgen's CLI must be the exact version of the wasm-bindgen crate the build links.
version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, "", $0); print; exit }' Cargo.lock)
bindgen="$target_dir/tools/bin/wasm-bindgen"
if [ ! -x "$bindgen" ] || [ "$("$bindgen" --version | awk '{print $2}')" != "$version" ]; then
    echo "build-web: installing wasm-bindgen-cli $version into $target_dir/tools" >&2
    # --locked first (the versions its authors tested); the registry may lack one of them.
    cargo install --quiet --locked wasm-bindgen-cli --version "=$version" --root "$target_dir/tools" ||
        cargo install --quiet wasm-bindgen-cli --version "=$version" --root "$target_dir/tools"
fi

# Not incremental: incremental builds split the code into many more units, which makes the module
# about a quarter larger and slower to start (the native build keeps its incremental profile).
CARGO_INCREMENTAL=0 cargo build --release -p hatchery-web --target wasm32-unknown-unknown
"$bindgen" --target web --no-typescript --out-dir "$target_dir/web-pkg" \
    "$target_dir/wasm32-unknown-unknown/release/hatchery_web.wasm"
echo "build-web: wrote $target_dir/web-pkg ($(du -h "$target_dir/web-pkg/hatchery_web_bg.wasm" | cut -f1) of wasm)" >&2
