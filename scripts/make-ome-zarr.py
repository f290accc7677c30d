#!/usr/bin/env python3
"""Writes a procedural uint16 OME-Zarr 0.4 image of N³ voxels (Zarr v2, uncompressed 64³
chunks, "/" separated, a 2×2×2-mean pyramid down to 64³) without holding it in memory: z-slabs
of 64 slices are made, written and averaged into the coarser levels one at a time. For the
out-of-core benchmark (scripts/bench-out-of-core.sh); 2048³ is 16 GiB of voxels on disk.

The field: a gyroid lattice (sin x cos y + sin y cos z + sin z cos x, period N/8 voxels) plus a
fine one (period 24 voxels, a third of the amplitude) inside a ball of radius 0.45 N, values
0..4000, 0 outside; 1 mm voxels centred on the world origin.

    python3 scripts/make-ome-zarr.py N OUT.zarr

Needs numpy. Zarr v2 is written by hand (its chunk files are the raw C-order bytes when no
compressor is set), so no Zarr library is needed; ome-zarr-py and hatchery read it.
"""
import json
import os
import sys
import time

import numpy as np

CHUNK = 64


def levels_for(n):
    dims = [n]
    while dims[-1] > CHUNK:
        dims.append((dims[-1] + 1) // 2)
    return dims


def write_json(path, value):
    with open(path, "w") as f:
        json.dump(value, f, indent=1)


def write_slab(out, level, z0, slab):
    """Chunks of `slab` (z, y, x) starting at level-`level` slice z0 (a multiple of CHUNK)."""
    nz, ny, nx = slab.shape
    cz = z0 // CHUNK
    for cy in range(0, ny, CHUNK):
        for cx in range(0, nx, CHUNK):
            block = np.zeros((CHUNK, CHUNK, CHUNK), dtype="<u2")
            part = slab[:, cy:cy + CHUNK, cx:cx + CHUNK]
            block[: part.shape[0], : part.shape[1], : part.shape[2]] = part
            folder = os.path.join(out, str(level), str(cz), str(cy // CHUNK))
            os.makedirs(folder, exist_ok=True)
            with open(os.path.join(folder, str(cx // CHUNK)), "wb") as f:
                f.write(block.tobytes())


def gyroid(x, z, period):
    """sin x cos y + sin y cos z + sin z cos x on the grid x (= y) × z, from 1-D tables."""
    w = 2 * np.pi / period
    sx, cx = np.sin(x * w), np.cos(x * w)
    sz, cz = np.sin(z * w), np.cos(z * w)
    return (sx[None, None, :] * cx[None, :, None]
            + sx[None, :, None] * cz[:, None, None]
            + sz[:, None, None] * cx[None, None, :])


def field(n, z0, z1):
    c = (n - 1) / 2
    x = np.arange(n, dtype=np.float32) - c
    z = np.arange(z0, z1, dtype=np.float32) - c
    # A lattice of period N/8 (the same picture at every size) with a fine one of 24 voxels on it
    # (detail that only the finest levels hold).
    g = gyroid(x, z, n / 8) + 0.35 * gyroid(x, z, 24.0)
    r2 = x[None, None, :] ** 2 + x[None, :, None] ** 2 + z[:, None, None] ** 2
    inside = r2 < (0.45 * n) ** 2
    v = np.clip((g + 1.5) * (4000 / 3.0), 0, 4000) * inside
    return v.astype("<u2")


def halve(a):
    """2×2×2 means (rounded, as hatchery's pyramid), odd edges averaged over what is there."""
    a = a.astype(np.float32)
    for axis in range(3):
        n = a.shape[axis]
        if n < 2:
            continue
        even = np.take(a, range(0, n - n % 2, 2), axis=axis) + np.take(a, range(1, n, 2), axis=axis)
        if n % 2:
            even = np.concatenate([even / 2, np.take(a, [n - 1], axis=axis)], axis=axis)
        else:
            even = even / 2
        a = even
    return np.floor(a + 0.5).astype("<u2")


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    dims = levels_for(n)
    os.makedirs(out, exist_ok=True)
    write_json(os.path.join(out, ".zgroup"), {"zarr_format": 2})
    c = (n - 1) / 2
    datasets = []
    for k, d in enumerate(dims):
        s = float(2 ** k)
        # Level k voxel 0 is centred on level-0 voxels 0 .. 2^k − 1.
        t = -c + (s - 1) / 2
        datasets.append({"path": str(k), "coordinateTransformations": [
            {"type": "scale", "scale": [s, s, s]},
            {"type": "translation", "translation": [t, t, t]}]})
        os.makedirs(os.path.join(out, str(k)), exist_ok=True)
        write_json(os.path.join(out, str(k), ".zarray"), {
            "zarr_format": 2, "shape": [d, d, d], "chunks": [CHUNK] * 3, "dtype": "<u2",
            "compressor": None, "fill_value": 0, "order": "C", "filters": None,
            "dimension_separator": "/"})
    axes = [{"name": a, "type": "space", "unit": "millimeter"} for a in "zyx"]
    write_json(os.path.join(out, ".zattrs"), {"multiscales": [{
        "version": "0.4", "name": f"gyroid {n}", "axes": axes, "datasets": datasets}]})
    # Per level, slices made but not yet written (a chunk's depth at a time).
    pending = [None] * len(dims)
    written = [0] * len(dims)
    started = time.time()

    def push(level, slab, last):
        p = slab if pending[level] is None else np.concatenate([pending[level], slab])
        while p.shape[0] >= CHUNK or (last and p.shape[0] > 0):
            write_slab(out, level, written[level], p[:CHUNK])
            written[level] += min(CHUNK, p.shape[0])
            p = p[CHUNK:]
        pending[level] = p if p.shape[0] else None

    step = 2 ** (len(dims) - 1) * 2  # a slab halves evenly down to the coarsest level
    step = max(CHUNK, step)
    for z0 in range(0, n, step):
        z1 = min(n, z0 + step)
        slab = field(n, z0, z1)
        last = z1 == n
        for k in range(len(dims)):
            push(k, slab, last)
            if k + 1 < len(dims):
                slab = halve(slab)
        done = z1 / n
        print(f"make-ome-zarr: {done:.0%} after {time.time() - started:.0f} s", file=sys.stderr,
              flush=True)
    print(f"make-ome-zarr: {n}³ uint16, {len(dims)} levels in {time.time() - started:.0f} s")


if __name__ == "__main__":
    main()
