#!/usr/bin/env python3
"""Writes tests/fixtures/world/: one small asymmetric synthetic anatomy written by independent
writers (nibabel, SimpleITK, tifffile, VTK, ome-zarr-py) in several volume formats, and truth.json with, for each
file, the voxel -> world affine in RAS+ mm as an independent reader reports it and the world
centroid of the object's voxels. The truth comes from the writer side, never from hatchery.

Usage (Python 3.11):  pip install SimpleITK nibabel tifffile vtk numpy ome-zarr
                      python3 scripts/make_world_fixtures.py [WRITER...]

With writer names (e.g. `write_vti`), only those files are written again and their records
replaced in truth.json; each writer imports only its own library.

To add a format, write one `write_<format>(out_dir) -> dict` function that writes the file(s),
reads them back with an independent reader and returns `entry(...)`, and list it in WRITERS.
"""

import json
import sys
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent.parent / "tests" / "fixtures" / "world"

DIMS = (20, 16, 12)  # i, j, k
OBJECT_VALUE = 200
# Voxels above this count as the object (half the object value).
THRESHOLD = OBJECT_VALUE / 2


def anatomy() -> np.ndarray:
    """An off-centre box with a smaller knob on its +i side, indexed [i, j, k]: mirroring any
    axis moves the object's centroid, so a flipped reader is caught."""
    a = np.zeros(DIMS, np.uint8)
    a[4:12, 3:10, 2:8] = OBJECT_VALUE  # box
    a[12:15, 5:7, 4:6] = OBJECT_VALUE  # knob
    return a


def rotation(axis, degrees) -> np.ndarray:
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    t = np.radians(degrees)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(t) * k + (1 - np.cos(t)) * (k @ k)


def voxel_centroid(data_ijk: np.ndarray, affine: np.ndarray) -> list:
    """Mean world position (affine . ijk) of the voxels above THRESHOLD."""
    ijk = np.argwhere(data_ijk > THRESHOLD).astype(float)
    world = ijk @ affine[:3, :3].T + affine[:3, 3]
    return world.mean(axis=0).tolist()


def entry(name, fmt, writer, reader, data_ijk, affine, note, expected=None) -> dict:
    """One truth.json record; checks first that the independent reader got the anatomy back
    (`expected`: the voxel array written, default the anatomy as is)."""
    expected = anatomy() if expected is None else expected
    if not np.array_equal(np.asarray(data_ijk, float), expected.astype(float)):
        sys.exit(f"{name}: {reader} did not read back the anatomy that was written")
    return {
        "file": name,
        "format": fmt,
        "writer": writer,
        "reader": reader,
        "note": note,
        "dims": list(DIMS),
        "affine_ras": np.asarray(affine, float).tolist(),
        "centroid_ras": voxel_centroid(np.asarray(data_ijk), np.asarray(affine, float)),
        # Half the length of a voxel's diagonal, in mm.
        "half_voxel_diagonal": 0.5 * float(np.linalg.norm(np.linalg.norm(affine[:3, :3], axis=0))),
    }


# --- NIfTI (nibabel writes, nibabel reads: its affine is RAS+ already) -------------------------


def write_nifti(out, name, data, affine, note, qform=True) -> dict:
    """Writes and reads back with nibabel; `data` is the voxel array in the file's ijk order."""
    import nibabel
    img = nibabel.Nifti1Image(data, affine)
    img.set_sform(affine, code=2)
    if qform:
        img.set_qform(affine, code=1)
    else:
        img.set_qform(None, code=0)
    nibabel.save(img, out / name)
    back = nibabel.load(out / name)
    return entry(name, "nifti", f"nibabel {nibabel.__version__}", "nibabel",
                 back.get_fdata(), back.affine, note, expected=data)


def write_nifti_ras(out) -> dict:
    affine = np.diag([1.5, 1.2, 2.0, 1.0])
    affine[:3, 3] = [-14.0, -9.0, -11.0]
    return write_nifti(out, "nifti_ras.nii", anatomy(), affine, "uint8, axis-aligned RAS sform")


def write_nifti_las(out) -> dict:
    """The RAS copy's object in the same place of the world, stored radiologically: voxels
    mirrored along i, x axis negated (as a radiological scanner export of the same subject)."""
    affine = np.diag([-1.5, 1.2, 2.0, 1.0])
    affine[:3, 3] = [-14.0 + (DIMS[0] - 1) * 1.5, -9.0, -11.0]
    return write_nifti(out, "nifti_las.nii.gz", anatomy()[::-1].astype(np.int16), affine,
                       "int16, radiological (negative x) sform and qform; same world object as "
                       "nifti_ras.nii")


def write_nifti_oblique(out) -> dict:
    affine = np.eye(4)
    affine[:3, :3] = rotation([1.0, 0.4, 0.2], 25.0) @ np.diag([1.5, 1.2, 2.0])
    affine[:3, 3] = [-12.0, 6.0, -4.0]
    return write_nifti(out, "nifti_oblique.nii.gz", anatomy().astype(np.float32), affine,
                       "float32, rotated sform (code 2) and qform (code 1)")


def write_nifti2(out) -> dict:
    """NIfTI-2 (540-byte header, 64-bit dims, double transforms), as nibabel writes it."""
    import nibabel
    affine = np.eye(4)
    affine[:3, :3] = rotation([0.2, 1.0, -0.3], 20.0) @ np.diag([-1.1, 1.4, 1.8])
    affine[:3, 3] = [9.0, -5.0, 3.0]
    img = nibabel.Nifti2Image(anatomy().astype(np.int16), affine)
    img.set_sform(affine, code=2)
    img.set_qform(affine, code=1)
    nibabel.save(img, out / "nifti2_oblique.nii.gz")
    back = nibabel.load(out / "nifti2_oblique.nii.gz")
    assert isinstance(back, nibabel.Nifti2Image)
    return entry("nifti2_oblique.nii.gz", "nifti2", f"nibabel {nibabel.__version__}", "nibabel",
                 back.get_fdata(), back.affine, "int16, NIfTI-2, rotated sform and qform, x negated")


def write_nifti2_big_endian(out) -> dict:
    """NIfTI-2 stored big-endian (header and voxels byte-swapped), float32, axis-aligned."""
    import nibabel
    affine = np.diag([0.9, 1.1, 1.3, 1.0])
    affine[:3, 3] = [-4.0, 2.0, -7.0]
    header = nibabel.Nifti2Header().as_byteswapped(">")
    img = nibabel.Nifti2Image(anatomy().astype(">f4"), affine, header=header)
    img.set_sform(affine, code=1)
    nibabel.save(img, out / "nifti2_big_endian.nii")
    back = nibabel.load(out / "nifti2_big_endian.nii")
    assert back.header.endianness == ">", "written big-endian"
    return entry("nifti2_big_endian.nii", "nifti2", f"nibabel {nibabel.__version__}", "nibabel",
                 back.get_fdata(), back.affine, "float32 big-endian NIfTI-2, sform code 1")


# --- FreeSurfer MGH / MGZ (nibabel writes and reads: vox2ras from Mdc, delta and c_ras) ---------


def write_mgh(out, name, data, affine, note) -> dict:
    import nibabel
    nibabel.save(nibabel.MGHImage(data, affine), out / name)
    back = nibabel.load(out / name)
    return entry(name, "mgh", f"nibabel {nibabel.__version__}", "nibabel",
                 back.get_fdata(), back.affine, note)


def write_mgz(out) -> dict:
    affine = np.eye(4)
    affine[:3, :3] = rotation([-0.4, 0.3, 1.0], 28.0) @ np.diag([1.3, 0.9, 1.6])
    affine[:3, 3] = [-6.0, 11.0, 4.0]
    return write_mgh(out, "freesurfer_oblique.mgz", anatomy().astype(np.float32), affine,
                     "float32 MGZ (gzip), rotated vox2ras")


def write_mgh_coronal(out) -> dict:
    """FreeSurfer's conformed orientation (LIA: i → −R, j → −S, k → +A), uint8, uncompressed."""
    affine = np.array([[-1.0, 0, 0, 10.0], [0, 0, 1.0, -8.0], [0, -1.0, 0, 6.0], [0, 0, 0, 1]])
    return write_mgh(out, "freesurfer_coronal.mgh", anatomy(), affine,
                     "uint8 MGH, FreeSurfer's coronal LIA orientation")


# --- ITK formats (SimpleITK writes and reads; ITK's physical space is LPS) ---------------------


def sitk_image(data_ijk, spacing, direction_lps, origin_lps):
    import SimpleITK as sitk
    img = sitk.GetImageFromArray(np.ascontiguousarray(data_ijk.transpose(2, 1, 0)))
    img.SetSpacing([float(s) for s in spacing])
    img.SetDirection([float(v) for v in np.asarray(direction_lps).flatten()])
    img.SetOrigin([float(o) for o in origin_lps])
    return img


def sitk_truth(out, name, fmt, note) -> dict:
    """Reads a file back with SimpleITK and turns its LPS geometry into a RAS+ affine."""
    import SimpleITK as sitk
    img = sitk.ReadImage(str(out / name))
    direction = np.array(img.GetDirection()).reshape(3, 3)
    lps = np.eye(4)
    lps[:3, :3] = direction @ np.diag(img.GetSpacing())
    lps[:3, 3] = img.GetOrigin()
    ras = np.diag([-1.0, -1.0, 1.0, 1.0]) @ lps
    data = sitk.GetArrayFromImage(img).transpose(2, 1, 0)
    return entry(name, fmt, f"SimpleITK {sitk.Version_VersionString()}", "SimpleITK (LPS -> RAS)",
                 data, ras, note)


def write_nrrd(out) -> dict:
    import SimpleITK as sitk
    img = sitk_image(anatomy().astype(np.int16), [1.1, 0.9, 1.7],
                     rotation([0.3, -0.5, 1.0], 30.0), [5.0, -3.0, 20.0])
    sitk.WriteImage(img, str(out / "sitk.nrrd"))
    return sitk_truth(out, "sitk.nrrd", "nrrd",
                      "int16, attached raw, space left-posterior-superior, oblique")


def write_nhdr(out) -> dict:
    import SimpleITK as sitk
    img = sitk_image(anatomy().astype(np.uint16), [0.7, 1.3, 1.0],
                     np.diag([-1.0, 1.0, -1.0]), [-8.0, 4.0, 15.0])
    sitk.WriteImage(img, str(out / "sitk_gzip.nhdr"), useCompression=True)
    return sitk_truth(out, "sitk_gzip.nhdr", "nrrd",
                      "uint16, detached gzip data file, flipped axes in LPS")


def write_mha(out) -> dict:
    import SimpleITK as sitk
    img = sitk_image(anatomy(), [1.2, 1.0, 1.5], rotation([-0.2, 1.0, 0.4], 35.0),
                     [-10.0, 12.0, -6.0])
    sitk.WriteImage(img, str(out / "sitk.mha"), useCompression=True)
    return sitk_truth(out, "sitk.mha", "metaimage",
                      "uint8, LOCAL zlib-compressed data, oblique TransformMatrix")


def write_mhd(out) -> dict:
    import SimpleITK as sitk
    img = sitk_image(anatomy().astype(np.int16), [0.8, 0.8, 2.5], np.eye(3), [3.0, -7.0, -12.0])
    sitk.WriteImage(img, str(out / "sitk.mhd"))
    return sitk_truth(out, "sitk.mhd", "metaimage", "int16, raw data file beside the header")


# --- TIFF stack (tifffile writes an ImageJ hyperstack; no anatomical frame) --------------------


def write_tiff(out) -> dict:
    import tifffile
    spacing = [0.5, 0.5, 1.25]  # mm: XResolution/YResolution 2 px/mm, ImageJ spacing=1.25
    pages = np.ascontiguousarray(anatomy().astype(np.uint16).transpose(2, 1, 0))  # [z, y, x]
    name = "imagej_stack.tif"
    tifffile.imwrite(out / name, pages, imagej=True,
                     resolution=(1 / spacing[0], 1 / spacing[1]),
                     metadata={"spacing": spacing[2], "unit": "mm", "axes": "ZYX"})
    with tifffile.TiffFile(out / name) as tif:
        meta = tif.imagej_metadata
        page = tif.pages[0]
        x_res = page.tags["XResolution"].value
        y_res = page.tags["YResolution"].value
        back = tif.asarray().transpose(2, 1, 0)
    read = [x_res[1] / x_res[0], y_res[1] / y_res[0], float(meta["spacing"])]
    if meta.get("unit") != "mm" or not np.allclose(read, spacing):
        sys.exit(f"{name}: tifffile reads spacing {read} {meta.get('unit')}, wrote {spacing} mm")
    affine = np.diag(read + [1.0])
    return entry(name, "tiff", f"tifffile {tifffile.__version__}", "tifffile (ImageJ metadata)",
                 back, affine, "uint16 pages, ImageJ spacing/unit=mm, axis-aligned")


# --- VTK ImageData (VTK writes and reads; its world is taken as RAS+ as it stands) -------------


def write_vti(out) -> dict:
    """A mirroring, rotated Direction (determinant -1) and an extent that does not start at 0:
    point (i, j, k) of the extent lies at Origin + Direction . (Spacing * (i, j, k))."""
    import vtk
    from vtk.util import numpy_support

    name = "vtk_mirrored_offset.vti"
    extent_min = (3, -2, 5)
    direction = rotation([0.2, 1.0, 0.3], 20.0) @ np.diag([1.0, -1.0, 1.0])
    image = vtk.vtkImageData()
    image.SetExtent(extent_min[0], extent_min[0] + DIMS[0] - 1,
                    extent_min[1], extent_min[1] + DIMS[1] - 1,
                    extent_min[2], extent_min[2] + DIMS[2] - 1)
    image.SetSpacing(1.3, 0.9, 1.6)
    image.SetOrigin(-6.0, 4.0, -9.0)
    image.SetDirectionMatrix(*direction.flatten().tolist())
    values = numpy_support.numpy_to_vtk(anatomy().transpose(2, 1, 0).ravel(), deep=True,
                                        array_type=vtk.VTK_UNSIGNED_CHAR)
    values.SetName("anatomy")
    image.GetPointData().SetScalars(values)
    writer = vtk.vtkXMLImageDataWriter()  # VTK's defaults: appended raw data, zlib
    writer.SetFileName(str(out / name))
    writer.SetInputData(image)
    if not writer.Write():
        sys.exit(f"{name}: VTK could not write it")

    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(str(out / name))
    reader.Update()
    back = reader.GetOutput()
    e = back.GetExtent()

    def at(di, dj, dk):
        """VTK's world point of extent index (e0 + di, e1 + dj, e2 + dk)."""
        point = [0.0, 0.0, 0.0]
        back.TransformIndexToPhysicalPoint(e[0] + di, e[2] + dj, e[4] + dk, point)
        return np.array(point)

    affine = np.eye(4)
    for c, d in enumerate([(1, 0, 0), (0, 1, 0), (0, 0, 1)]):
        affine[:3, c] = at(*d) - at(0, 0, 0)
    affine[:3, 3] = at(0, 0, 0)
    dims = (e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1)
    data = numpy_support.vtk_to_numpy(back.GetPointData().GetScalars())
    data = data.reshape(dims[::-1]).transpose(2, 1, 0)
    return entry(name, "vti", f"VTK {vtk.vtkVersion.GetVTKVersion()}",
                 "VTK (TransformIndexToPhysicalPoint)", data, affine,
                 "uint8 point data, zlib, mirroring oblique Direction, extent from (3, -2, 5)")


# --- OME-Zarr (ome-zarr-py writes and reads back; no anatomical frame in the format) -----------

# hatchery's convention for OME-Zarr, which names axes but no anatomy: the space axes x, y, z are
# world R, A, S; a voxel's centre is scale * index + translation (the spec's), in the axis unit,
# converted to mm.
UNIT_MM = {"millimeter": 1.0, "micrometer": 1e-3, "nanometer": 1e-6, "centimeter": 10.0}


def labels_ijk() -> np.ndarray:
    """The anatomy as a label map: the box is object 1, its knob object 2."""
    a = np.zeros(DIMS, np.uint8)
    a[4:12, 3:10, 2:8] = 1
    a[12:15, 5:7, 4:6] = 2
    return a


def write_ome_zarr(out, name, version, unit, scale_zyx, translation_zyx, note) -> dict:
    """Writes the anatomy (array axes z, y, x) with a label image `organs` whose objects carry
    names, then reads both back with ome-zarr-py's Reader."""
    import shutil
    import zarr
    import ome_zarr
    from ome_zarr.format import FormatV04, FormatV05
    from ome_zarr.io import parse_url
    from ome_zarr.reader import Reader
    from ome_zarr.writer import write_multiscale, write_multiscale_labels
    fmt = {"0.4": FormatV04(), "0.5": FormatV05()}[version]
    path = out / name
    shutil.rmtree(path, ignore_errors=True)
    root = zarr.open_group(str(path), mode="w", zarr_format=2 if version == "0.4" else 3)
    axes = [{"name": a, "type": "space", "unit": unit} for a in "zyx"]
    # Zarr v2 stores as bioformats2raw and older ome-zarr-py wrote them (Blosc/LZ4, byte
    # shuffle); v3 with ome-zarr-py's default (zstd).
    storage = {"chunks": (8, 8, 8)}
    if version == "0.4":
        from numcodecs import Blosc
        storage["compressor"] = Blosc(cname="lz4", clevel=5, shuffle=Blosc.SHUFFLE)
    # Two levels: the second halves y and x (ome-zarr-py's default pyramid keeps z).
    transforms = [
        [{"type": "scale", "scale": list(scale_zyx)},
         {"type": "translation", "translation": list(translation_zyx)}],
        [{"type": "scale", "scale": [scale_zyx[0], 2 * scale_zyx[1], 2 * scale_zyx[2]]},
         {"type": "translation", "translation": list(translation_zyx)}],
    ]
    # Level 1 takes every second voxel along y and x (index 0 stays put: same translation).
    pyramid = lambda a: [np.ascontiguousarray(a.transpose(2, 1, 0)),
                         np.ascontiguousarray(a.transpose(2, 1, 0)[:, ::2, ::2])]
    write_multiscale(pyramid(anatomy()), root, fmt=fmt, axes=axes,
                     coordinate_transformations=transforms, storage_options=storage)
    write_multiscale_labels(pyramid(labels_ijk()), root, name="organs", fmt=fmt, axes=axes,
                            coordinate_transformations=transforms,
                            storage_options=storage,
                            label_metadata={"properties": [{"label-value": 1, "name": "box"},
                                                           {"label-value": 2, "name": "knob"}]})
    nodes = list(Reader(parse_url(str(path), fmt=fmt))())
    image = nodes[0]
    data = np.asarray(image.data[0]).transpose(2, 1, 0)
    ms = image.metadata
    axis_names = [a["name"] for a in ms["axes"]]
    scale = ms["coordinateTransformations"][0][0]["scale"]
    shift = ms["coordinateTransformations"][0][1]["translation"]
    affine = np.eye(4)
    for voxel_axis, axis in enumerate("xyz"):
        a = axis_names.index(axis)
        mm = UNIT_MM[ms["axes"][a]["unit"]]
        affine[voxel_axis, voxel_axis] = scale[a] * mm
        affine[voxel_axis, 3] = shift[a] * mm
    label = next(n for n in nodes if any(type(s).__name__ == "Label" for s in n.specs))
    back = np.asarray(label.data[0]).transpose(2, 1, 0)
    names = {str(v): p["name"] for v, p in label.metadata["properties"].items()}
    if not np.array_equal(back, labels_ijk()) or names != {"1": "box", "2": "knob"}:
        sys.exit(f"{name}: ome-zarr-py did not read back the label image and its names")
    record = entry(name, "ome-zarr", f"ome-zarr-py {ome_zarr.__version__}",
                   "ome-zarr-py Reader (axes x, y, z = R, A, S)", data, affine, note)
    record["labels"] = {"path": "labels/organs", "names": names,
                        "voxels": {str(v): int((labels_ijk() == v).sum()) for v in (1, 2)}}
    return record


def write_ome_zarr_v04(out) -> dict:
    return write_ome_zarr(out, "ome_v04.zarr", "0.4", "micrometer", (2000.0, 1500.0, 800.0),
                          (5000.0, -20000.0, 10000.0),
                          "OME-Zarr 0.4 (Zarr v2, Blosc LZ4 + shuffle), uint8, micrometre scale + translation, "
                          "labels/organs with names")


def write_ome_zarr_v05(out) -> dict:
    return write_ome_zarr(out, "ome_v05.zarr", "0.5", "millimeter", (2.0, 1.5, 0.8),
                          (5.0, -20.0, 10.0),
                          "OME-Zarr 0.5 (Zarr v3, zstd), uint8, millimetre scale + translation, "
                          "labels/organs with names")


WRITERS = [
    write_nifti_ras,
    write_nifti_las,
    write_nifti_oblique,
    write_nifti2,
    write_nifti2_big_endian,
    write_mgz,
    write_mgh_coronal,
    write_nrrd,
    write_nhdr,
    write_mha,
    write_mhd,
    write_tiff,
    write_vti,
    write_ome_zarr_v04,
    write_ome_zarr_v05,
]


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    chosen = [w for w in WRITERS if not sys.argv[1:] or w.__name__ in sys.argv[1:]]
    if len(chosen) != len(set(sys.argv[1:])):
        sys.exit(f"unknown writer; choose from {[w.__name__ for w in WRITERS]}")
    files = [write(OUT) for write in chosen]
    if sys.argv[1:]:
        # Keep the other formats' records (in WRITERS order) and replace the rewritten ones.
        old = json.loads((OUT / "truth.json").read_text())["files"]
        new = {f["file"]: f for f in files}
        files = [new.pop(f["file"], f) for f in old] + list(new.values())
    truth = {
        "about": "Written by scripts/make_world_fixtures.py. affine_ras: voxel -> world, RAS+ mm, "
                 "as the independent reader reports it. centroid_ras: mean of affine . ijk over "
                 "the voxels above threshold.",
        "object_value": OBJECT_VALUE,
        "threshold": THRESHOLD,
        "voxels_above": int((anatomy() > THRESHOLD).sum()),
        "files": files,
    }
    (OUT / "truth.json").write_text(json.dumps(truth, indent=1) + "\n")
    for f in files:
        size = (OUT / f["file"]).stat().st_size
        print(f"{f['file']:24} {size:6} bytes  centroid {np.round(f['centroid_ras'], 3)}")


if __name__ == "__main__":
    main()
