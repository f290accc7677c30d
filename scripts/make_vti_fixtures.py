#!/usr/bin/env python3
"""Writes the VTK XML ImageData (.vti) fixtures of tests/fixtures/vti/ with VTK itself, and the
answers the reader must give in tests/fixtures/vti/truth.json, computed with VTK's own
vtkImageData (TransformContinuousIndexToPhysicalPoint, GetPoint).

    python3 -m venv /tmp/vtkenv && /tmp/vtkenv/bin/pip install vtk numpy
    /tmp/vtkenv/bin/python scripts/make_vti_fixtures.py

Every file is written by vtkXMLImageDataWriter, so the block layout, header types and compressed
streams are exactly VTK's (zlib, raw LZ4 blocks, one .xz stream per block for LZMA). The files
are small (a few KB) and committed; rerun this script only to change them.

The grid: WholeExtent 2 13 0 9 1 8 (12 x 10 x 8 points, 11 x 9 x 7 cells), a non-zero Origin,
Direction diag(-1, 1, 1) (mirrored x), point data with two arrays (`noise` Float64 first,
`density` Float32 second, active: `<PointData Scalars="density">`) and cell data `cells`
(Int16, active). `density` is a Gaussian blob away from the grid centre with a few NaN ("no
data") voxels.
"""

import json
import math
import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support
from vtkmodules.util.vtkAlgorithm import VTKPythonAlgorithmBase
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "vti")

EXTENT = (2, 13, 0, 9, 1, 8)
ORIGIN = (5.0, -3.0, 12.5)
SPACING = (0.8, 1.25, 2.0)
MIRROR_X = np.diag([-1.0, 1.0, 1.0])
THRESHOLD = 50.0


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


# Not symmetric, so a reader that takes Direction column-major instead of row-major fails.
ROTATED = rot_x(0.3) @ rot_z(0.5) @ MIRROR_X


def structured(extent, cells=False):
    """Structured coordinates (i, j, k) of every point (or cell corner) of an extent, i fastest,
    as VTK orders its arrays."""
    r = [np.arange(extent[2 * a], extent[2 * a + 1] + (0 if cells else 1)) for a in range(3)]
    k, j, i = np.meshgrid(r[2], r[1], r[0], indexing="ij")
    return np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1).astype(float)


def image(extent, origin, spacing, direction):
    im = vtk.vtkImageData()
    im.SetExtent(*extent)
    im.SetOrigin(*origin)
    im.SetSpacing(*spacing)
    m = vtk.vtkMatrix3x3()
    for r in range(3):
        for c in range(3):
            m.SetElement(r, c, float(direction[r][c]))
    im.SetDirectionMatrix(m)
    return im


def add(data, name, values, active=False):
    a = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=True)
    a.SetName(name)
    if active:
        data.SetScalars(a)
    else:
        data.AddArray(a)


def grid_values(extent):
    ijk = structured(extent)
    centre = np.array([9.3, 3.6, 5.2])
    d2 = (((ijk - centre) / np.array([2.0, 2.5, 1.8])) ** 2).sum(axis=1)
    density = (100.0 * np.exp(-0.5 * d2)).astype(np.float32)
    # "No data" at a few structured coordinates (so every piece of a split grid agrees).
    for nan in [(3, 0, 1), (5, 6, 2), (10, 3, 5)]:
        density[(ijk == nan).all(axis=1)] = np.nan
    noise = 0.01 * np.sin(ijk @ np.array([1.7, 2.3, 0.9]))
    cell_ijk = structured(extent, cells=True)
    cells = (cell_ijk @ np.array([1.0, 20.0, 300.0]) - 1000.0).astype(np.int16)
    return noise, density, cells


def filled(extent, origin, spacing, direction):
    im = image(extent, origin, spacing, direction)
    noise, density, cells = grid_values(extent)
    add(im.GetPointData(), "noise", noise)
    add(im.GetPointData(), "density", density, active=True)
    add(im.GetCellData(), "cells", cells, active=True)
    return im


class Pieces(VTKPythonAlgorithmBase):
    """A source that produces any sub-extent of the `filled` grid, so the writer can stream it
    in pieces (a plain vtkImageData input is always written whole, once per piece)."""

    def __init__(self):
        VTKPythonAlgorithmBase.__init__(
            self, nInputPorts=0, nOutputPorts=1, outputType="vtkImageData"
        )

    def RequestInformation(self, request, in_info, out_info):
        info = out_info.GetInformationObject(0)
        info.Set(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT(), EXTENT, 6)
        info.Set(vtk.vtkAlgorithm.CAN_PRODUCE_SUB_EXTENT(), 1)
        return 1

    def RequestData(self, request, in_info, out_info):
        info = out_info.GetInformationObject(0)
        extent = info.Get(vtkStreamingDemandDrivenPipeline.UPDATE_EXTENT())
        out = vtk.vtkImageData.GetData(out_info)
        out.ShallowCopy(filled(extent, ORIGIN, SPACING, MIRROR_X))
        return 1


def write(im, name, compressor="none", header="UInt32", mode="appended", encode=False,
          block=1024, pieces=1, big_endian=False):
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(os.path.join(OUT, name))
    if isinstance(im, VTKPythonAlgorithmBase):
        w.SetInputConnection(im.GetOutputPort())
    else:
        w.SetInputData(im)
    {
        "none": w.SetCompressorTypeToNone,
        "zlib": w.SetCompressorTypeToZLib,
        "lz4": w.SetCompressorTypeToLZ4,
        "lzma": w.SetCompressorTypeToLZMA,
    }[compressor]()
    {"UInt32": w.SetHeaderTypeToUInt32, "UInt64": w.SetHeaderTypeToUInt64}[header]()
    {
        "ascii": w.SetDataModeToAscii,
        "binary": w.SetDataModeToBinary,
        "appended": w.SetDataModeToAppended,
    }[mode]()
    w.SetEncodeAppendedData(1 if encode else 0)
    if big_endian:
        w.SetByteOrderToBigEndian()
    else:
        w.SetByteOrderToLittleEndian()
    # Small blocks, so arrays span several compressed blocks and end with a partial one.
    w.SetBlockSize(block)
    w.SetNumberOfPieces(pieces)
    if not w.Write():
        sys.exit(f"VTK could not write {name}")


def read(name):
    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(os.path.join(OUT, name))
    r.Update()
    return r.GetOutput()


def affine(im, cells):
    """Our voxel (i, j, k), counted from 0, to world: VTK's own index -> physical transform of
    the structured coordinate (extent lower corner + i, ...), + 0.5 for cell centres."""
    e = im.GetExtent()
    base = [e[0], e[2], e[4]]
    if cells:
        base = [b + 0.5 for b in base]

    def phys(ijk):
        out = [0.0, 0.0, 0.0]
        im.TransformContinuousIndexToPhysicalPoint([float(v) for v in ijk], out)
        return np.array(out)

    o = phys(base)
    cols = [phys([base[b] + (1 if a == b else 0) for b in range(3)]) - o for a in range(3)]
    m = np.eye(4)
    for a in range(3):
        m[:3, a] = cols[a]
    m[:3, 3] = o
    return m.tolist()


def truth_of(name, array, cells=False, threshold=THRESHOLD):
    """The reader's answers for `array` of file `name`, computed from what VTK reads back.
    `threshold` None: the middle of the value range."""
    im = read(name)
    data = im.GetCellData() if cells else im.GetPointData()
    values = numpy_support.vtk_to_numpy(data.GetArray(array)).astype(np.float64)
    if cells:
        centre = vtk.vtkCellCenters()
        centre.SetInputData(im)
        centre.Update()
        world = numpy_support.vtk_to_numpy(centre.GetOutput().GetPoints().GetData())
    else:
        world = np.array([im.GetPoint(p) for p in range(im.GetNumberOfPoints())])
    finite = values[np.isfinite(values)]
    if threshold is None:
        threshold = float(finite.min() + finite.max()) / 2
    above = np.nan_to_num(values, nan=-np.inf) > threshold
    e = im.GetExtent()
    dims = [e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1]
    if cells:
        dims = [d - 1 for d in dims]
    return {
        "array": array,
        "cells": cells,
        "dims": dims,
        "affine": affine(im, cells),
        "value_range": [float(finite.min()), float(finite.max())],
        "non_finite": int((~np.isfinite(values)).sum()),
        "threshold": threshold,
        "above": int(above.sum()),
        "centroid_above": world[above].mean(axis=0).tolist() if above.any() else None,
        "first": float(values[0]) if np.isfinite(values[0]) else None,
        "last": float(values[-1]),
    }


def main():
    os.makedirs(OUT, exist_ok=True)
    truth = {"vtk_version": vtk.vtkVersion.GetVTKVersion(), "files": {}}

    def record(name, *args, **kwargs):
        truth["files"].setdefault(name, []).append(truth_of(name, *args, **kwargs))

    base = filled(EXTENT, ORIGIN, SPACING, MIRROR_X)
    # Each compressor with each header type, in varied data modes (inline base64, appended
    # raw or base64) and byte orders; grid_*.vti differ only in how they store the same data.
    matrix = [
        ("none", "UInt32", "appended", False, False),
        ("none", "UInt64", "binary", False, True),
        ("zlib", "UInt32", "binary", False, False),
        ("zlib", "UInt64", "appended", True, False),
        ("lz4", "UInt32", "appended", False, False),
        ("lz4", "UInt64", "binary", False, True),
        ("lzma", "UInt32", "appended", True, True),
        ("lzma", "UInt64", "appended", False, False),
    ]
    for compressor, header, mode, encode, big_endian in matrix:
        name = f"grid_{compressor}_{header.lower()}.vti"
        write(base, name, compressor, header, mode, encode, big_endian=big_endian)
        record(name, "density")
        record(name, "noise", threshold=0.0)
        record(name, "cells", cells=True, threshold=0.0)

    write(base, "grid_ascii.vti", mode="ascii")
    record("grid_ascii.vti", "density")

    # Three pieces (sub-extents) in one file, assembled by VTK's reader into the whole extent.
    write(Pieces(), "grid_three_pieces.vti", "zlib", pieces=3)
    record("grid_three_pieces.vti", "density")
    record("grid_three_pieces.vti", "cells", cells=True, threshold=0.0)

    # Negative spacing along j and a rotation that is not symmetric.
    rotated = filled((-3, 8, 4, 13, 0, 7), (-20.0, 7.5, 3.0), (0.8, -1.25, 2.0), ROTATED)
    write(rotated, "rotated_negative_spacing.vti", "lz4", "UInt64")
    record("rotated_negative_spacing.vti", "density")
    record("rotated_negative_spacing.vti", "cells", cells=True, threshold=0.0)

    # Cell data only: the default array is the active cell array.
    cells_only = image(EXTENT, ORIGIN, SPACING, MIRROR_X)
    add(cells_only.GetCellData(), "cells", grid_values(EXTENT)[2], active=True)
    write(cells_only, "cells_only.vti", "zlib")
    record("cells_only.vti", "cells", cells=True, threshold=0.0)

    # Every scalar type VTK writes, one array each; none is active, so the first is read.
    typed = image(EXTENT, ORIGIN, SPACING, MIRROR_X)
    ijk = structured(EXTENT)
    ramp = ijk @ np.array([1.0, 12.0, 120.0])  # 122..1081, distinct per point
    types = {
        "u8": (ramp % 251).astype(np.uint8),
        "i8": ((ramp % 251) - 125).astype(np.int8),
        "u16": (ramp * 60).astype(np.uint16),
        "i16": (ramp * 30 - 20000).astype(np.int16),
        "i32": (ramp * 1000 - 400000).astype(np.int32),
        "u32": (ramp * 1000).astype(np.uint32),
        "i64": (ramp - 600).astype(np.int64),
        "u64": ramp.astype(np.uint64),
        "f32": (ramp / 7).astype(np.float32),
        "f64": ramp / 3,
    }
    for name, values in types.items():
        add(typed.GetPointData(), name, values)
    write(typed, "types.vti", "zlib", "UInt64")
    for name in types:
        record("types.vti", name, threshold=None)

    with open(os.path.join(OUT, "truth.json"), "w") as f:
        json.dump(truth, f, indent=1, sort_keys=True)
        f.write("\n")
    sizes = {n: os.path.getsize(os.path.join(OUT, n)) for n in sorted(os.listdir(OUT))}
    print(json.dumps(sizes, indent=1))


if __name__ == "__main__":
    main()
