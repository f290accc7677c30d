#!/usr/bin/env bash
# Installs what hatchery needs at run time on a Debian machine: a Vulkan driver. Machines without
# a GPU get Mesa's software driver (lavapipe). Does nothing when a Vulkan driver is already there.
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

if have_vulkan_driver; then
    exit 0
fi

echo "install-deps: no Vulkan driver found; installing Mesa's software driver (lavapipe)" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends mesa-vulkan-drivers libvulkan1 >/dev/null
have_vulkan_driver || { echo "install-deps: the Vulkan driver is still missing after installing" >&2; exit 1; }
