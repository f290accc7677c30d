"""`hatchery convert IN OUT.zarr` as other tools read it: ome-zarr-py (the OME-NGFF reference
reader) gets back the voxels, their world placement, the pyramid and the label image with its
object names."""

import subprocess

import nibabel as nib
import numpy as np
from ome_zarr.io import parse_url
from ome_zarr.reader import Reader


def read_back(path):
    """(image node, label node) as ome-zarr-py's Reader yields them."""
    nodes = list(Reader(parse_url(str(path)))())
    image = next(n for n in nodes if type(n.specs[0]).__name__ == "Multiscales")
    label = next(n for n in nodes if any(type(s).__name__ == "Label" for s in n.specs))
    return image, label


def placement(metadata, level):
    """Per array axis (z, y, x): scale and translation of a level, in mm."""
    assert [a["name"] for a in metadata["axes"]] == ["z", "y", "x"]
    assert {a["unit"] for a in metadata["axes"]} == {"millimeter"}
    scale, translation = metadata["coordinateTransformations"][level]
    assert scale["type"] == "scale" and translation["type"] == "translation"
    return np.array(scale["scale"]), np.array(translation["translation"])


def test_ome_zarr_py_reads_what_convert_writes(repo, tmp_path, hatchery_bin):
    # A mirrored (LAS) NIfTI: convert must reorder it so that x runs along R with a positive scale,
    # as nibabel's closest canonical (RAS+) orientation does.
    source = repo / "tests" / "fixtures" / "world" / "nifti_las.nii.gz"
    img = nib.load(source)
    canonical = nib.as_closest_canonical(img)
    data = np.asarray(canonical.dataobj)
    assert not np.allclose(img.affine, canonical.affine), "the fixture is stored mirrored"
    # A label map on its grid (box 1, the rest of the object 2) with names.
    raw = np.asarray(img.dataobj)
    labels = np.where(raw > 100, 2, 0).astype(np.uint16)
    labels[: raw.shape[0] // 2][raw[: raw.shape[0] // 2] > 100] = 1
    nib.save(nib.Nifti1Image(labels, img.affine), tmp_path / "organs.nii.gz")
    (tmp_path / "names.csv").write_text("id,name\n1,left part\n2,right part\n")

    out = tmp_path / "converted.zarr"
    run = subprocess.run(
        [hatchery_bin, "convert", source, out, "--labels", tmp_path / "organs.nii.gz",
         "--names", tmp_path / "names.csv", "--chunk", "8"],
        capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "level 1" in run.stdout, run.stdout

    image, label = read_back(out)
    level0 = np.asarray(image.data[0])
    # Array axes z, y, x: transpose nibabel's canonical [i, j, k].
    np.testing.assert_array_equal(level0, data.transpose(2, 1, 0))
    scale, translation = placement(image.metadata, 0)
    np.testing.assert_allclose(scale[::-1], np.diag(canonical.affine)[:3], rtol=1e-6)
    np.testing.assert_allclose(translation[::-1], canonical.affine[:3, 3], atol=1e-4)

    # Level 1 halves every axis of at least 4 voxels: each voxel the mean of its 2×2×2 block,
    # centred on the block.
    level1 = np.asarray(image.data[1]).astype(float)
    assert level1.shape == tuple((n + 1) // 2 for n in level0.shape)
    block = level0[:2, :2, :2].astype(float).mean()
    assert abs(level1[0, 0, 0] - block) <= 0.5 + 1e-9, (level1[0, 0, 0], block)
    scale1, translation1 = placement(image.metadata, 1)
    np.testing.assert_allclose(scale1, 2 * scale, rtol=1e-6)
    np.testing.assert_allclose(translation1, translation + scale / 2, atol=1e-4)

    # The label image: same grid, canonical order, names as properties.
    expected = np.asarray(nib.as_closest_canonical(nib.Nifti1Image(labels, img.affine)).dataobj)
    np.testing.assert_array_equal(np.asarray(label.data[0]), expected.transpose(2, 1, 0))
    names = {int(k): v["name"] for k, v in label.metadata["properties"].items()}
    assert names == {1: "left part", 2: "right part"}
    np.testing.assert_allclose(placement(label.metadata, 0)[1], translation, atol=1e-6)


def test_convert_refuses_labels_on_another_grid(repo, tmp_path, hatchery_bin):
    source = repo / "tests" / "fixtures" / "world" / "nifti_ras.nii"
    nib.save(nib.Nifti1Image(np.zeros((4, 4, 4), np.uint8), np.eye(4)), tmp_path / "small.nii.gz")
    run = subprocess.run(
        [hatchery_bin, "convert", source, tmp_path / "x.zarr", "--labels", tmp_path / "small.nii.gz"],
        capture_output=True, text=True)
    assert run.returncode != 0
    assert "not on the volume's grid" in run.stderr, run.stderr
    assert not (tmp_path / "x.zarr").exists(), "nothing is written when the input is refused"
