#!/usr/bin/env bash
# Peak memory of loading and ray casting a big uint8 volume: writes an N³ uint8 NIfTI (default
# 800³ = 512 MB of voxels: a ball of 200 in a field of 20), a graph VolumeFile → Raycast →
# SaveImage (256×256, shaded DVR), and renders it with each given `hatchery` binary under
# /usr/bin/time, printing the peak RSS next to the voxel bytes. `--format vti` writes the same
# volume as VTK ImageData instead (raw appended data, UInt64 header, as vtkXMLImageDataWriter
# writes it uncompressed).
#
#   scripts/bench-memory.sh [--size N] [--format nii|vti] BIN [BIN...]
#
# Needs python3 (standard library only) and GNU time (/usr/bin/time). The volume is written to a
# temporary folder (N³ bytes of disk) and removed afterwards.
set -euo pipefail
n=800
format=nii
while [ $# -ge 2 ]; do
    case "$1" in
        --size) n=$2; shift 2 ;;
        --format) format=$2; shift 2 ;;
        *) break ;;
    esac
done
case "$format" in nii|vti) ;; *) echo "bench-memory: --format is nii or vti" >&2; exit 2 ;; esac
[ $# -ge 1 ] || { echo "usage: $0 [--size N] [--format nii|vti] BIN [BIN...]" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench-memory: /usr/bin/time (GNU time) is missing" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$n" "$work/big.$format" <<'EOF'
import struct, sys
n, path = int(sys.argv[1]), sys.argv[2]
c = (n - 1) / 2
if path.endswith(".vti"):
    e = f"0 {n - 1} 0 {n - 1} 0 {n - 1}"
    header = f"""<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <ImageData WholeExtent="{e}" Origin="{-c} {-c} {-c}" Spacing="1 1 1" Direction="1 0 0 0 1 0 0 0 1">
    <Piece Extent="{e}">
      <PointData Scalars="density">
        <DataArray type="UInt8" Name="density" format="appended" offset="0"/>
      </PointData>
    </Piece>
  </ImageData>
  <AppendedData encoding="raw">
   _""".encode() + struct.pack("<Q", n ** 3)
    footer = b"\n  </AppendedData>\n</VTKFile>\n"
else:
    header = bytearray(352)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 3, n, n, n, 1, 1, 1, 1)
    struct.pack_into("<hh", header, 70, 2, 8)            # datatype uint8, bitpix 8
    struct.pack_into("<8f", header, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", header, 108, 352.0)           # vox_offset
    struct.pack_into("<ff", header, 112, 1.0, 0.0)       # scl_slope, scl_inter
    struct.pack_into("<hh", header, 252, 0, 1)           # qform 0, sform 1
    for row, values in enumerate([(1, 0, 0, -c), (0, 1, 0, -c), (0, 0, 1, -c)]):
        struct.pack_into("<4f", header, 280 + 16 * row, *values)
    header[344:348] = b"n+1\0"
    footer = b""
r = 0.4 * n
with open(path, "wb") as f:
    f.write(header)
    for z in range(n):
        slab = bytearray(b"\x14" * (n * n))
        for y in range(n):
            d2 = r * r - (y - c) ** 2 - (z - c) ** 2
            if d2 > 0:
                half = d2 ** 0.5
                x0, x1 = max(0, int(c - half)), min(n, int(c + half) + 1)
                slab[y * n + x0:y * n + x1] = b"\xc8" * (x1 - x0)
        f.write(slab)
    f.write(footer)
EOF

cat >"$work/graph.ron" <<EOF
(
    version: 1,
    nodes: [
        (id: "camera", kind: "Camera", params: {"azimuth": 30.0, "elevation": 20.0, "distance": $((n * 3)).0, "far": $((n * 10)).0, "near": 1.0}),
        (id: "ray", kind: "Raycast", params: {"shading": "phong"}),
        (id: "save", kind: "SaveImage", params: {"path": "big.png"}),
        (id: "tf", kind: "TransferFunction1D", params: {"points": "0: 1 1 1 0; 100: 1 1 1 0; 200: 0.9 0.6 0.4 0.8; 255: 0.9 0.6 0.4 0.8", "preset": "custom"}),
        (id: "volume", kind: "VolumeFile", params: {"path": "big.$format"}),
    ],
    edges: [
        (from: ("camera", "camera"), to: ("ray", "camera")),
        (from: ("ray", "image"), to: ("save", "image")),
        (from: ("tf", "tf"), to: ("ray", "tf")),
        (from: ("volume", "volume"), to: ("ray", "volume")),
    ],
)
EOF

voxel_bytes=$(( n * n * n ))
echo "volume: ${n}³ uint8 ($format) = $(( voxel_bytes / 1024 / 1024 )) MiB of voxels"
for bin in "$@"; do
    start=$(date +%s.%N)
    /usr/bin/time -f "%M" -o "$work/rss" "$bin" render "$work/graph.ron" -o "$work/out.png" --size 256x256 \
        >"$work/log" 2>&1 || { echo "$bin failed:"; tail -n 5 "$work/log"; continue; }
    end=$(date +%s.%N)
    rss_kb=$(tail -n 1 "$work/rss")
    python3 -c "import sys; kb, b, t = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]); print(f'{sys.argv[4]}: peak RSS {kb / 1024:.0f} MiB = {kb * 1024 / b:.2f} x the voxel bytes; {t:.1f} s')" \
        "$rss_kb" "$voxel_bytes" "$(echo "$end - $start" | bc)" "$bin"
done
