#!/usr/bin/env bash
# Every preset in the browser (docs/web.md's table): exports each graph of graphs/ at SIZE
# (default 320x240) into target/web-presets/ and opens each in headless Chromium with WebGPU
# (tests/web/presets.mjs): whether it draws, its first picture's time, its distance from the
# native render. A report, not a test; run scripts/web-test.sh first (it installs what this needs).
set -euo pipefail
cd "$(dirname "$0")/.."
target_dir="${CARGO_TARGET_DIR:-target}"
size="${1:-320x240}"
out="$target_dir/web-presets"
rm -rf "$out"
mkdir -p "$out"
dirs=()
for graph in graphs/*.ron; do
    name=$(basename "$graph" .ron)
    if "$target_dir/release/hatchery" export-web "$graph" -o "$out/$name" --size "$size" 2>"$out/$name.log"; then
        dirs+=("$out/$name")
    else
        echo "| $name | not exported: $(grep '^error' "$out/$name.log" | head -1) | | |"
    fi
done
WEB_TOOLS="$target_dir/web-tools" node tests/web/presets.mjs "${dirs[@]}"
