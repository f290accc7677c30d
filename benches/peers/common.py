"""Shared by the peer benchmarks: the volume as hatchery places it, and hatchery's camera.

Reads an uncompressed-or-gzip NIfTI-1 with uint8 voxels and an sform (the shared MRI), so that
the voxels land where hatchery puts them (RAS+ mm), and the camera JSON that
`hatchery render GRAPH --dump camera.camera=cam.json` writes.
"""

import gzip
import json
import math
import struct

import numpy as np


def read_nifti_u8(path):
    """(voxels as a z, y, x uint8 array, 4x4 voxel -> world affine from the sform)."""
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "rb") as f:
        data = f.read()
    dims = struct.unpack("<8h", data[40:56])
    datatype = struct.unpack("<h", data[70:72])[0]
    if datatype != 2:
        raise SystemExit(f"{path}: only uint8 NIfTI volumes are read here (datatype {datatype})")
    offset = int(struct.unpack("<f", data[108:112])[0])
    srow = [struct.unpack("<4f", data[280 + 16 * i: 296 + 16 * i]) for i in range(3)]
    nx, ny, nz = dims[1:4]
    voxels = np.frombuffer(data[offset:offset + nx * ny * nz], np.uint8).reshape(nz, ny, nx)
    affine = np.array(list(srow) + [(0.0, 0.0, 0.0, 1.0)], dtype=np.float64)
    return voxels, affine


def read_camera(path):
    with open(path) as f:
        return json.load(f)


def orbit(camera, degrees):
    """The camera's eye turned by `degrees` about its up axis through the target (what
    `hatchery bench --scenario orbit:camera` does to the azimuth)."""
    eye = np.array(camera["eye"], dtype=np.float64)
    target = np.array(camera["target"], dtype=np.float64)
    axis = np.array(camera["up"], dtype=np.float64)
    axis /= np.linalg.norm(axis)
    v = eye - target
    a = math.radians(degrees)
    # Rodrigues' rotation of v about the axis.
    v = v * math.cos(a) + np.cross(axis, v) * math.sin(a) + axis * np.dot(axis, v) * (1 - math.cos(a))
    return target + v


def parse_tf(text):
    """hatchery's "value: r g b a; …" points -> [(value, r, g, b, a)]."""
    points = []
    for part in text.split(";"):
        part = part.strip()
        if not part:
            continue
        value, rgba = part.split(":")
        points.append((float(value), *[float(x) for x in rgba.split()]))
    return points
