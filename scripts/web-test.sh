#!/usr/bin/env bash
# The browser test (docs/web.md): builds the browser build, exports graphs/default.ron (and
# graphs/brain_surface.ron, a NIfTI file, where ../shared/data is there) with
# `hatchery export-web`, and drives it in headless Chromium with WebGPU (tests/web/check.mjs):
# the canvas against the native render of the same graph and size, a drag and a control that
# must change the picture, and the poster without WebGPU. Installs Debian's chromium and the
# test's two npm packages (playwright-core, pngjs: tests/web/package-lock.json) when missing;
# skips, saying why, where it cannot.
set -euo pipefail
cd "$(dirname "$0")/.."
target_dir="${CARGO_TARGET_DIR:-target}"
skip() {
    echo "web-test: SKIPPED: $*" >&2
    exit 0
}

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
if ! command -v chromium >/dev/null 2>&1 || ! command -v node >/dev/null 2>&1; then
    missing=()
    command -v chromium >/dev/null 2>&1 || missing+=(chromium)
    command -v node >/dev/null 2>&1 || missing+=(nodejs npm)
    echo "web-test: installing ${missing[*]} from Debian" >&2
    { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
        $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; } ||
        skip "could not install ${missing[*]} (apt-get failed)"
fi

scripts/build-web.sh
cargo build --release --bin hatchery

tools="$target_dir/web-tools"
mkdir -p "$tools"
cp tests/web/package.json tests/web/package-lock.json "$tools/"
(cd "$tools" && npm ci --silent --no-audit --no-fund) || skip "npm could not install playwright-core and pngjs"

out="$target_dir/web-test"
rm -rf "$out"
mkdir -p "$out"
size=480x360
"$target_dir/release/hatchery" export-web graphs/default.ron -o "$out/default" --size "$size"
render() {
    "$target_dir/release/hatchery" render graphs/default.ron --size "$size" "$@" 2>&1 | tail -1
}
render -o "$out/native.png"
# The page's hatching-angle slider moved to 180°, then a drag of (160, 40) pixels: the page turns
# the camera by 180° per canvas width (480 px), so azimuth 35° − 60° and elevation 25° + 15°.
control=hatching.theta=180
render -o "$out/native-control.png" --set "$control"
# After the drag the test compares the hatched picture before the labels (the label layout starts
# from its last frame, so labels placed during a drag differ from a fresh render's).
render -o "$out/native-dragged-labelled.png" --set "$control" --set camera.azimuth=-25 \
    --set camera.elevation=40 --dump "front_hatching.image=$out/native-dragged.png"
WEB_TOOLS="$tools" node tests/web/check.mjs --dir "$out/default" --out "$out" \
    --native "$out/native.png" \
    --control "$control" --control-native "$out/native-control.png" \
    --drag 160,40 --drag-port front_hatching.image --drag-native "$out/native-dragged.png"

# A figure with a data file: the MNI template (NIfTI, gzip) read by the loaders from what the
# page fetched. Where ../shared/data is not beside the checkout, say so and stop here.
mri=../shared/data/volumes/mni152_t1.nii.gz
if [ ! -f "$mri" ]; then
    echo "web-test: the data-file figure is skipped: $mri is missing" >&2
    exit 0
fi
mkdir -p "$out/brain"
"$target_dir/release/hatchery" export-web graphs/brain_surface.ron -o "$out/brain/figure" --size 320x240
"$target_dir/release/hatchery" render graphs/brain_surface.ron --size 320x240 -o "$out/brain/native.png" 2>&1 | tail -1
# Then the white-matter map dropped on the page, as a reader gives the figure their own data.
wm=../shared/data/volumes/mni152_wm.nii.gz
"$target_dir/release/hatchery" render graphs/brain_surface.ron --size 320x240 --input "volume=$wm" \
    -o "$out/brain/native-dropped.png" 2>&1 | tail -1
WEB_TOOLS="$tools" node tests/web/check.mjs --dir "$out/brain/figure" --out "$out/brain" \
    --native "$out/brain/native.png" --opened-only --drop "$wm" --drop-native "$out/brain/native-dropped.png"
