#!/usr/bin/env bash
# Out-of-core benchmark (issue 30): makes procedural uint16 OME-Zarr pyramids of N³ voxels
# (scripts/make-ome-zarr.py; 2048³ is 16 GiB on disk) and renders each with `hatchery render`
# under GNU time, under a host budget (HATCHERY_HOST_BUDGET_MB, default 4096 here):
#   preview — a 256² frame of the whole volume: the level held in memory (the first picture an
#             interactive view shows);
#   whole   — a 1024² frame of the whole volume: the level its pixels need, within the budget;
#   close   — a 1024² close-up through a 6° cone: a region of the finest level.
# Prints one line per render: size, view, seconds, peak RSS, and which level and region was read.
#
#   scripts/bench-out-of-core.sh [--sizes "512 1024 2048"] [--budget MB] [--work DIR] BIN
#
# The pyramids are kept in DIR (default /tmp/hatchery-ooc) for reruns; delete it afterwards.
# Needs python3 with numpy (a venv is made in DIR when it is missing) and /usr/bin/time.
set -euo pipefail
sizes="512 1024 2048"
budget=4096
work=/tmp/hatchery-ooc
while [ $# -ge 2 ]; do
    case "$1" in
        --sizes) sizes=$2; shift 2 ;;
        --budget) budget=$2; shift 2 ;;
        --work) work=$2; shift 2 ;;
        *) break ;;
    esac
done
[ $# -eq 1 ] || { echo "usage: $0 [--sizes \"512 1024 2048\"] [--budget MB] [--work DIR] BIN" >&2; exit 2; }
bin=$(realpath "$1")
[ -x /usr/bin/time ] || { echo "bench-out-of-core: /usr/bin/time (GNU time) is missing" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
python=python3
if ! python3 -c "import numpy" 2>/dev/null; then
    [ -x "$work/venv/bin/python" ] || { python3 -m venv "$work/venv" && "$work/venv/bin/pip" install -q numpy; }
    python="$work/venv/bin/python"
fi

graph() { # $1 volume, $2 camera params
    cat <<EOF
(
    version: 3,
    nodes: [
        (id: "volume", kind: "VolumeFile", params: {"path": "$1"}),
        (id: "camera", kind: "Camera", params: {$2, "up": "z", "near": 1.0, "far": 20000.0}),
        (id: "tf", kind: "TransferFunction1D", params: {"preset": "custom",
            "points": "range(0.3): 0.8 0.6 0.5 0.0; range(0.6): 0.9 0.5 0.3 0.2; range(1): 1 1 0.9 1"}),
        (id: "ray", kind: "Raycast", params: {"shading": "phong"}),
        (id: "paper", kind: "Fill", params: {"color": (1.0, 1.0, 1.0, 1.0)}),
        (id: "over", kind: "Over", params: {}),
        (id: "save", kind: "SaveImage", params: {"path": "out.png"}),
    ],
    edges: [
        (from: ("volume", "volume"), to: ("camera", "volume")),
        (from: ("camera", "camera"), to: ("ray", "camera")),
        (from: ("volume", "volume"), to: ("ray", "volume")),
        (from: ("volume", "volume"), to: ("tf", "volume")),
        (from: ("tf", "tf"), to: ("ray", "tf")),
        (from: ("paper", "image"), to: ("over", "back")),
        (from: ("ray", "image"), to: ("over", "front")),
        (from: ("over", "image"), to: ("save", "image")),
    ],
)
EOF
}

echo "# hatchery $("$bin" --version | cut -d' ' -f2), budget ${budget} MiB, $(nproc) cores, $(free -g | awk '/Mem/{print $2}') GiB"
for n in $sizes; do
    zarr="$work/gyroid_$n.zarr"
    if [ ! -f "$zarr/.zattrs" ]; then
        "$python" "$here/make-ome-zarr.py" "$n" "$zarr" >&2
    fi
    disk=$(du -sh "$zarr" | cut -f1)
    whole='"framing": "fit", "azimuth": 30.0, "elevation": 25.0, "fov": 30.0'
    # 30 % of the radius above the ball's top, looking down through a 6° cone.
    close="\"framing\": \"fixed\", \"target\": (0.0, 0.0, $((n * 45 / 100))), \"distance\": $((n * 15 / 100)), \"azimuth\": 30.0, \"elevation\": 89.0, \"fov\": 6.0"
    for view in preview whole close; do
        case $view in
            preview) cam=$whole; size=256x256 ;;
            whole) cam=$whole; size=1024x1024 ;;
            close) cam=$close; size=1024x1024 ;;
        esac
        graph "$zarr" "$cam" > "$work/$view.ron"
        log="$work/$view-$n.log"
        HATCHERY_HOST_BUDGET_MB=$budget /usr/bin/time -v "$bin" -v render "$work/$view.ron" \
            -o "$work/$view-$n.png" --size "$size" > "$log" 2>&1 || { tail -20 "$log" >&2; exit 1; }
        secs=$(awk -F': ' '/Elapsed \(wall clock\)/{n=split($2,t,":"); s=0; for(i=1;i<=n;i++) s=s*60+t[i]; print s}' "$log")
        rss=$(awk -F': ' '/Maximum resident set size/{printf "%.0f", $2/1024}' "$log")
        read_=$(grep -o 'lod=[0-9]* lo=\[[0-9, ]*\] size=\[[0-9, ]*\]' "$log" | tail -1 || true)
        took=$(grep -o 'seconds=[0-9.]*' "$log" | tail -1 | cut -d= -f2 || true)
        [ -z "$took" ] || read_="$read_ in $(printf '%.2f' "$took") s"
        streamed=$(grep -q "exceed the host budget" "$log" && echo streamed || echo "in memory")
        echo "N=$n ($disk on disk) $view $size: ${secs} s, peak RSS ${rss} MiB, $streamed, read: ${read_:-the preview level only}"
    done
done
