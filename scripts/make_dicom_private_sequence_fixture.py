#!/usr/bin/env python3
"""Writes a copy of the DICOM series fixture whose slices each hold a private sequence of
undefined length stored with VR UN, as some scanners' exports do (PS3.5 6.2.2: the value of an
undefined-length UN element is a sequence encoded in Implicit VR Little Endian, whatever the
file's transfer syntax):

    python3 -m pip install pydicom SimpleITK numpy
    python3 scripts/make_dicom_private_sequence_fixture.py

Out: tests/fixtures/world/dicom_series_un_sequence/ — the slices of dicom_series/ rewritten by
pydicom in Explicit VR Little Endian with a private creator (0009,0010) and a private element
(0009,1001), VR UN, undefined length, holding one item of three implicit-VR code attributes.
Read in the file's explicit VR, the item's elements would be garbage (their 4-byte lengths
taken for a VR), so a reader must switch to implicit VR inside it.

The script checks that pydicom reads the private element as a sequence of one item with those
attributes, and that SimpleITK (GDCM) reads exactly the voxels of the uncompressed series.
"""

import struct
import sys
from pathlib import Path

import numpy as np
import pydicom
import SimpleITK as sitk
from pydicom.uid import ExplicitVRLittleEndian

WORLD = Path(__file__).resolve().parent.parent / "tests" / "fixtures" / "world"
SOURCE = WORLD / "dicom_series"
OUT = WORLD / "dicom_series_un_sequence"
PLACEHOLDER = b"HATCHERY-PLACEHOLDER"
CODES = [((0x0008, 0x0100), b"T-D0050 "), ((0x0008, 0x0102), b"SRT "), ((0x0008, 0x0104), b"Tissue")]


def implicit(tag, value: bytes) -> bytes:
    """An Implicit VR Little Endian element: tag, 4-byte length, value."""
    return struct.pack("<HHI", *tag, len(value)) + value


def un_sequence() -> bytes:
    """(0009,1001) UN of undefined length: one undefined-length item of implicit-VR elements."""
    item = b"".join(implicit(tag, value) for tag, value in CODES)
    return (
        struct.pack("<HH2sHI", 0x0009, 0x1001, b"UN", 0, 0xFFFFFFFF)
        + struct.pack("<HHI", 0xFFFE, 0xE000, 0xFFFFFFFF)
        + item
        + struct.pack("<HHI", 0xFFFE, 0xE00D, 0)
        + struct.pack("<HHI", 0xFFFE, 0xE0DD, 0)
    )


def main():
    sources = sorted(SOURCE.glob("*.dcm"))
    if not sources:
        sys.exit(f"no slices in {SOURCE}: run scripts/make_dicom_fixture.py first")
    OUT.mkdir(exist_ok=True)
    for src in sources:
        ds = pydicom.dcmread(src)
        pixels = ds.pixel_array
        ds.file_meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds.PixelData = pixels.astype("<i2").tobytes()
        ds["PixelData"].VR = "OW"
        ds.add_new(0x00090010, "LO", "HATCHERY TEST")
        ds.add_new(0x00091001, "UN", PLACEHOLDER)
        out = OUT / src.name
        pydicom.dcmwrite(out, ds, little_endian=True, implicit_vr=False, enforce_file_format=True)
        data = out.read_bytes()
        placeholder = struct.pack("<HH2sHI", 0x0009, 0x1001, b"UN", 0, len(PLACEHOLDER)) + PLACEHOLDER
        if data.count(placeholder) != 1:
            sys.exit(f"{out}: the placeholder element was not written once")
        out.write_bytes(data.replace(placeholder, un_sequence()))

        back = pydicom.dcmread(out)
        seq = back[0x00091001]
        items = seq.value if seq.VR == "SQ" else None
        if not items or len(items) != 1 or items[0].CodeMeaning != "Tissue":
            sys.exit(f"{out}: pydicom does not read the private sequence ({seq.VR}, {seq.value!r})")
        if not np.array_equal(back.pixel_array, pixels):
            sys.exit(f"{out}: pydicom reads other pixels")

    files = sitk.ImageSeriesReader.GetGDCMSeriesFileNames(str(OUT))
    reader = sitk.ImageSeriesReader()
    reader.SetFileNames(files)
    got = sitk.GetArrayFromImage(reader.Execute())
    files = sitk.ImageSeriesReader.GetGDCMSeriesFileNames(str(SOURCE))
    reader.SetFileNames(files)
    want = sitk.GetArrayFromImage(reader.Execute())
    if not np.array_equal(got, want):
        sys.exit("SimpleITK reads other voxels from the copy than from dicom_series/")
    size = sum(p.stat().st_size for p in OUT.glob("*.dcm"))
    print(f"{OUT.name}: {len(sources)} slices, {size} bytes; pydicom and SimpleITK read it")


if __name__ == "__main__":
    main()
