#!/usr/bin/env python3
"""Writes compressed copies of the DICOM series fixture (scripts/make_dicom_fixture.py), as
archives hold them, with other tools' encoders:

    python3 -m pip install pydicom python-gdcm numpy
    python3 scripts/make_dicom_compressed_fixtures.py [FOLDER...]   (default: all)

Out (repo root, next to tests/fixtures/world/dicom_series/):
  dicom_series_rle/    RLE Lossless (1.2.840.10008.1.2.5), pydicom's own RLE encoder
  dicom_series_jpegll/ JPEG Lossless, first-order prediction (1.2.840.10008.1.2.4.70), GDCM
  dicom_series_j2k/    JPEG 2000 Lossless (1.2.840.10008.1.2.4.90), GDCM (OpenJPEG)
  dicom_series_rle32/  32-bit signed copies (stored values × 100), RLE Lossless by GDCM
                       (pydicom's RLE encoder stops at 16 bits)
  dicom_series_be32/   the same 32-bit values in Explicit VR Big Endian (OW), by pydicom
  dicom_series_jls/    JPEG-LS Lossless (1.2.840.10008.1.2.4.80), GDCM (CharLS)
  dicom_series_jlsnear/ JPEG-LS Near-Lossless (1.2.840.10008.1.2.4.81), NEAR = 3, GDCM (CharLS)

All but the near-lossless one are lossless, so crates/hatchery-data/tests/dicom.rs expects
exactly the voxels and the geometry of the uncompressed series. The script decodes every written
file again (pydicom, which uses GDCM for JPEG) and fails unless it gives back the original pixels
(near-lossless: within NEAR of them, and not all equal to them).
"""

import sys
from pathlib import Path

import gdcm
import numpy as np
import pydicom
from pydicom.uid import (
    ExplicitVRBigEndian,
    JPEG2000Lossless,
    JPEGLosslessSV1,
    JPEGLSLossless,
    JPEGLSNearLossless,
    RLELossless,
)

WORLD = Path(__file__).resolve().parent.parent / "tests" / "fixtures" / "world"
SOURCE = WORLD / "dicom_series"


def write_rle(src: Path, out: Path) -> None:
    ds = pydicom.dcmread(src)
    # From the decoded pixels in native byte order: compressing a big-endian slice's raw bytes
    # would swap them.
    pixels = ds.pixel_array
    pixels = pixels.astype(pixels.dtype.newbyteorder("="))
    ds.compress(RLELossless, arr=pixels, encoding_plugin="pydicom")
    # dcmwrite, not save_as: the big-endian slices become little endian (as RLE requires).
    pydicom.dcmwrite(out, ds, enforce_file_format=True)


def as_int32(ds):
    """The slice as 32-bit signed samples: stored values × 100 (beyond 16 bits)."""
    pixels = ds.pixel_array.astype(np.int32) * 100
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 32, 32, 31, 1
    return pixels


def write_rle32(src: Path, out: Path) -> None:
    ds = pydicom.dcmread(src)
    pixels = as_int32(ds)
    ds.file_meta.TransferSyntaxUID = pydicom.uid.ExplicitVRLittleEndian
    ds.PixelData = pixels.astype("<i4").tobytes()
    ds["PixelData"].VR = "OW"
    plain = out.with_suffix(".plain")
    pydicom.dcmwrite(plain, ds, little_endian=True, implicit_vr=False, enforce_file_format=True)
    gdcm_change(plain, out, gdcm.TransferSyntax.RLELossless)
    plain.unlink()


def write_be32(src: Path, out: Path) -> None:
    ds = pydicom.dcmread(src)
    pixels = as_int32(ds)
    ds.file_meta.TransferSyntaxUID = ExplicitVRBigEndian
    ds.PixelData = pixels.astype(">i4").tobytes()
    ds["PixelData"].VR = "OW"
    pydicom.dcmwrite(out, ds, little_endian=False, implicit_vr=False, enforce_file_format=True)


def write_jpeg_lossless(src: Path, out: Path) -> None:
    gdcm_change(src, out, gdcm.TransferSyntax.JPEGLosslessProcess14_1)


def write_j2k(src: Path, out: Path) -> None:
    gdcm_change(src, out, gdcm.TransferSyntax.JPEG2000Lossless)


def write_jls(src: Path, out: Path) -> None:
    gdcm_change(src, out, gdcm.TransferSyntax.JPEGLSLossless)


NEAR = 3


def write_jls_near(src: Path, out: Path) -> None:
    codec = gdcm.JPEGLSCodec()
    codec.SetLossless(False)
    codec.SetLossyError(NEAR)
    gdcm_change(src, out, gdcm.TransferSyntax.JPEGLSNearLossless, codec)


def gdcm_change(src: Path, out: Path, syntax, codec=None) -> None:
    """Re-encodes `src` into `out` in transfer syntax `syntax` with GDCM (with `codec`'s
    settings where given)."""
    reader = gdcm.ImageReader()
    reader.SetFileName(str(src))
    if not reader.Read():
        sys.exit(f"GDCM cannot read {src}")
    change = gdcm.ImageChangeTransferSyntax()
    change.SetTransferSyntax(gdcm.TransferSyntax(syntax))
    change.SetInput(reader.GetImage())
    if codec is not None:
        change.SetUserCodec(codec)
    if not change.Change():
        sys.exit(f"GDCM cannot compress {src}")
    writer = gdcm.ImageWriter()
    writer.SetFile(reader.GetFile())
    writer.SetImage(change.GetOutput())
    writer.SetFileName(str(out))
    if not writer.Write():
        sys.exit(f"GDCM cannot write {out}")


def main():
    sources = sorted(SOURCE.glob("*.dcm"))
    if not sources:
        sys.exit(f"no slices in {SOURCE}: run scripts/make_dicom_fixture.py first")
    for folder, syntax, write, scale in [
        ("dicom_series_rle", RLELossless, write_rle, 1),
        ("dicom_series_jpegll", JPEGLosslessSV1, write_jpeg_lossless, 1),
        ("dicom_series_j2k", JPEG2000Lossless, write_j2k, 1),
        ("dicom_series_rle32", RLELossless, write_rle32, 100),
        ("dicom_series_be32", ExplicitVRBigEndian, write_be32, 100),
        ("dicom_series_jls", JPEGLSLossless, write_jls, 1),
        ("dicom_series_jlsnear", JPEGLSNearLossless, write_jls_near, 1),
    ]:
        if sys.argv[1:] and folder not in sys.argv[1:]:
            continue
        out_dir = WORLD / folder
        out_dir.mkdir(exist_ok=True)
        lossy = False
        for src in sources:
            out = out_dir / src.name
            write(src, out)
            back = pydicom.dcmread(out)
            if back.file_meta.TransferSyntaxUID != syntax:
                sys.exit(f"{out}: written as {back.file_meta.TransferSyntaxUID}, not {syntax}")
            want = pydicom.dcmread(src).pixel_array.astype(np.int64) * scale
            got = back.pixel_array.astype(np.int64)
            if syntax == JPEGLSNearLossless:
                if np.abs(got - want).max() > NEAR:
                    sys.exit(f"{out}: decodes further than {NEAR} from the pixels of {src}")
                lossy |= not np.array_equal(got, want)
            elif not np.array_equal(got, want):
                sys.exit(f"{out}: does not decode to the pixels of {src}")
        if syntax == JPEGLSNearLossless and not lossy:
            sys.exit(f"{folder}: near-lossless coding gave back every pixel exactly")
        size = sum(p.stat().st_size for p in out_dir.glob("*.dcm"))
        print(f"{folder}: {len(sources)} slices, {size} bytes, {syntax.name}")


if __name__ == "__main__":
    main()
