#!/usr/bin/env python3
"""Writes the DICOM series fixture that crates/hatchery-data/tests/dicom.rs reads, and its truth.

    python3 -m pip install SimpleITK pydicom numpy
    python3 scripts/make_dicom_fixture.py

Out (repo root):
  tests/fixtures/world/dicom_series/*.dcm   12 single-frame CT slices of a 20 x 16 x 12 int16 volume
  tests/fixtures/world/dicom_truth.json     voxel -> world affine (RAS+ mm) and the object centroid

The object is asymmetric (an off-centre box with a knob on its +i side) so that a flipped or
transposed axis moves the centroid. The grid is oblique (rotated about two axes, LPS origin far
from 0) with three different spacings, so swapping PixelSpacing's two values or the row and
column cosines changes the affine.

To catch readers that sort by anything but position, file names are shuffled relative to slice
order and InstanceNumber runs in yet another order. The slices cycle through the three
uncompressed transfer syntaxes (implicit VR little endian, explicit VR little endian, explicit VR
big endian), so one series exercises all of them.

The slices are written with pydicom (tags set by hand, nothing derived by the writer). The
truth affine is what SimpleITK (ITK + GDCM, an independent reader) makes of the written files:
ImageSeriesReader on the GDCM-sorted file list, turned from LPS to RAS by negating the x and y
rows. The centroid is computed with numpy on the writer's side: the mean world position (RAS+)
of the voxels above half the object value, through the same affine. The script checks that
SimpleITK reads back exactly the written voxels and fails otherwise.
"""

import json
import random
from pathlib import Path

import numpy as np
import pydicom
import SimpleITK as sitk
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.uid import (
    CTImageStorage,
    ExplicitVRBigEndian,
    ExplicitVRLittleEndian,
    ImplicitVRLittleEndian,
    PYDICOM_IMPLEMENTATION_UID,
    generate_uid,
)

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "fixtures" / "world"
SERIES_DIR = OUT / "dicom_series"

NI, NJ, NK = 20, 16, 12  # columns (i, along the row cosines), rows (j), slices (k)
SPACING = (0.7, 0.9, 1.5)  # mm between columns, rows, slices: all different on purpose
ORIGIN_LPS = np.array([-31.5, 12.25, 47.0])  # centre of voxel (0, 0, 0)
BACKGROUND, OBJECT = -100, 1000


def rotation(axis, degrees):
    a = np.radians(degrees)
    c, s = np.cos(a), np.sin(a)
    x, y, z = np.eye(3)[axis]
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * k + (1 - c) * (k @ k)


# Columns: the LPS directions of i (row cosines), j (column cosines) and k (their cross product).
DIRECTION = rotation(2, 25.0) @ rotation(0, -15.0)


def make_volume():
    """int16 voxels indexed [k, j, i]: an off-centre box and a knob sticking out on its +i side."""
    v = np.full((NK, NJ, NI), BACKGROUND, dtype=np.int16)
    v[2:8, 3:10, 4:12] = OBJECT  # box: i 4..11, j 3..9, k 2..7
    v[4:6, 5:8, 12:16] = OBJECT  # knob: i 12..15, j 5..7, k 4..5
    return v


def slice_dataset(volume, k, uids, instance_number, syntax):
    rows_cosines = DIRECTION[:, 0]
    cols_cosines = DIRECTION[:, 1]
    position = ORIGIN_LPS + DIRECTION[:, 2] * SPACING[2] * k

    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = CTImageStorage
    meta.MediaStorageSOPInstanceUID = generate_uid(entropy_srcs=[uids["series"], str(k)])
    meta.TransferSyntaxUID = syntax
    meta.ImplementationClassUID = PYDICOM_IMPLEMENTATION_UID

    ds = Dataset()
    ds.file_meta = meta
    ds.SOPClassUID = CTImageStorage
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = "CT"
    ds.PatientName = "Hatchery^Fixture"
    ds.PatientID = "hatchery-dicom-fixture"
    ds.StudyInstanceUID = uids["study"]
    ds.SeriesInstanceUID = uids["series"]
    ds.FrameOfReferenceUID = uids["frame"]
    ds.SeriesNumber = 1
    ds.InstanceNumber = instance_number
    ds.ImagePositionPatient = [f"{x:.6f}" for x in position]
    ds.ImageOrientationPatient = [f"{x:.8f}" for x in (*rows_cosines, *cols_cosines)]
    # PixelSpacing is (distance between rows, distance between columns) = (j spacing, i spacing).
    ds.PixelSpacing = [f"{SPACING[1]}", f"{SPACING[0]}"]
    ds.SliceThickness = f"{SPACING[2]}"
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.Rows = NJ
    ds.Columns = NI
    ds.BitsAllocated = 16
    ds.BitsStored = 16
    ds.HighBit = 15
    ds.PixelRepresentation = 1
    ds.RescaleSlope = "1"
    ds.RescaleIntercept = "0"
    pixels = volume[k]  # [j, i]: row-major, i fastest, as DICOM stores a frame
    big = syntax == ExplicitVRBigEndian
    ds.PixelData = pixels.astype(">i2" if big else "<i2").tobytes()
    ds["PixelData"].VR = "OW"
    return ds


def main():
    volume = make_volume()
    uids = {
        name: generate_uid(entropy_srcs=["hatchery dicom fixture", name])
        for name in ("study", "series", "frame")
    }
    rng = random.Random(20261130)
    names = [f"IM{n:04d}.dcm" for n in rng.sample(range(1000, 10000), NK)]
    # InstanceNumber neither follows position nor the file names: k = 0 gets 7, k = 1 gets 3, ...
    instance_numbers = [(7 + 5 * k) % NK + 1 for k in range(NK)]
    syntaxes = [ImplicitVRLittleEndian, ExplicitVRLittleEndian, ExplicitVRBigEndian]

    SERIES_DIR.mkdir(parents=True, exist_ok=True)
    for old in SERIES_DIR.glob("*.dcm"):
        old.unlink()
    for k in range(NK):
        syntax = syntaxes[k % 3]
        ds = slice_dataset(volume, k, uids, instance_numbers[k], syntax)
        ds.save_as(
            SERIES_DIR / names[k],
            implicit_vr=syntax == ImplicitVRLittleEndian,
            little_endian=syntax != ExplicitVRBigEndian,
            enforce_file_format=True,
        )
    assert sorted(names) != names, "file names must not follow slice order"

    # Read back with SimpleITK: GDCM sorts the files by position along the slice normal.
    files = sitk.ImageSeriesReader.GetGDCMSeriesFileNames(str(SERIES_DIR))
    assert len(files) == NK, files
    reader = sitk.ImageSeriesReader()
    reader.SetFileNames(files)
    image = reader.Execute()
    read = sitk.GetArrayFromImage(image)  # [k, j, i]
    assert read.shape == volume.shape, read.shape
    assert np.array_equal(read, volume), "SimpleITK reads other voxels than were written"
    # And pydicom agrees on every slice, whichever transfer syntax it has.
    for k, name in enumerate(names):
        assert np.array_equal(pydicom.dcmread(SERIES_DIR / name).pixel_array, volume[k]), name

    lps_to_ras = np.diag([-1.0, -1.0, 1.0])
    direction = np.array(image.GetDirection()).reshape(3, 3)
    linear = lps_to_ras @ direction @ np.diag(image.GetSpacing())
    origin = lps_to_ras @ np.array(image.GetOrigin())
    affine = np.eye(4)
    affine[:3, :3] = linear
    affine[:3, 3] = origin
    # The written geometry and ITK's reading of it must agree (to the digits written).
    written = np.eye(4)
    written[:3, :3] = lps_to_ras @ DIRECTION @ np.diag(SPACING)
    written[:3, 3] = lps_to_ras @ ORIGIN_LPS
    assert np.allclose(affine, written, atol=1e-5), (affine, written)

    # Centroid of the object from the writer's array, through the affine.
    k, j, i = np.nonzero(volume > OBJECT / 2)
    ijk1 = np.stack([i, j, k, np.ones_like(i)]).astype(float)
    centroid = (affine @ ijk1)[:3].mean(axis=1)

    truth = {
        "about": "Written by scripts/make_dicom_fixture.py. affine: voxel (i, j, k, 1) -> world "
        "RAS+ mm as SimpleITK reads dicom_series/ (LPS x and y negated); centroid: mean RAS+ "
        "position of the voxels above half the object value (numpy, writer side).",
        "dims": [NI, NJ, NK],
        "spacing": list(SPACING),
        "affine": affine.tolist(),
        "centroid": centroid.tolist(),
        "object_voxels": int(len(i)),
        "value_range": [BACKGROUND, OBJECT],
        "iso": OBJECT / 2,
        "files_in_slice_order": [Path(f).name for f in files],
        "instance_numbers_in_slice_order": instance_numbers,
    }
    (OUT / "dicom_truth.json").write_text(json.dumps(truth, indent=2) + "\n")
    total = sum(p.stat().st_size for p in SERIES_DIR.iterdir())
    print(f"wrote {NK} slices ({total} bytes) to {SERIES_DIR}")
    print(f"centroid (RAS+ mm): {centroid}")


if __name__ == "__main__":
    main()
