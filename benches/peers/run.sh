#!/bin/sh
# hatchery vs VTK vs pygfx on the shared MRI at hatchery's camera, interleaved round by round:
#   benches/peers/run.sh [ROUNDS] [FRAMES] [SIZE]      (defaults 3, 5, 512x512)
# Creates a virtual environment with the pinned peers (PEERS_VENV, default /tmp/hatchery-peers)
# on first use; builds hatchery; needs ../shared/data/volumes/mni152_t1.nii.gz.
set -eu
cd "$(dirname "$0")/../.."
venv=${PEERS_VENV:-/tmp/hatchery-peers}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q -r benches/peers/requirements.txt
fi
cargo build --release --bin hatchery
"$venv/bin/python" benches/peers/run.py target/release/hatchery "$@"
