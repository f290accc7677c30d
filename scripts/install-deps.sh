#!/usr/bin/env bash
# Installs what hatchery needs on a Debian machine: a Vulkan driver (machines without a GPU get
# Mesa's software driver, lavapipe; nothing is installed when a driver is already there), and
# for the editor's scripted check (scripts/editor-smoke.sh) an X server (Xvfb) and xdotool, and
# for the Python package's tests a Python 3 with venv, and ffmpeg for video export.
set -euo pipefail

if ! command -v cargo >/dev/null 2>&1; then
    echo "install-deps: cargo not found; install a Rust toolchain (https://rustup.rs) first" >&2
    exit 1
fi

have_vulkan_driver() {
    # A loader plus at least one installable client driver (ICD) manifest.
    local libs manifests
    libs=$(ldconfig -p 2>/dev/null || true)
    manifests=$(find /usr/share/vulkan/icd.d /etc/vulkan/icd.d -name '*.json' 2>/dev/null || true)
    [[ "$libs" == *libvulkan.so.1* && -n "$manifests" ]]
}

# The browser build (scripts/build-web.sh, docs/web.md) compiles for wasm32.
if command -v rustup >/dev/null 2>&1 &&
    ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi

packages=()
if ! have_vulkan_driver; then
    echo "install-deps: no Vulkan driver found; installing Mesa's software driver (lavapipe)" >&2
    packages+=(mesa-vulkan-drivers libvulkan1)
fi
command -v Xvfb >/dev/null 2>&1 || packages+=(xvfb)
command -v xdotool >/dev/null 2>&1 || packages+=(xdotool)
# Video export (MP4/WebM of `hatchery render --orbit` and batch animations) goes through ffmpeg.
command -v ffmpeg >/dev/null 2>&1 || packages+=(ffmpeg)
# The Python package's tests (scripts/python-tests.sh) build it in a virtual environment.
if ! command -v python3 >/dev/null 2>&1; then
    packages+=(python3 python3-venv python3-pip)
elif ! python3 -c "import venv, ensurepip" >/dev/null 2>&1; then
    packages+=(python3-venv)
fi
if [ ${#packages[@]} -eq 0 ]; then
    exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
have_vulkan_driver || { echo "install-deps: the Vulkan driver is still missing after installing" >&2; exit 1; }
