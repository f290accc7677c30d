"""Graph inputs from numpy: volumes with affines, label maps with names, meshes; and their errors."""

import nibabel as nib
import numpy as np
import pytest

import hatchery
from conftest import assert_pictures_close, blob, oblique_affine

SIZE = (160, 120)


def brain_graph(repo):
    return hatchery.Graph.load(repo / "graphs" / "brain_surface.ron")


@pytest.mark.parametrize("dtype", [np.float32, np.int16, np.uint8])
def test_numpy_volume_renders_as_the_same_nifti_by_path(repo, tmp_path, dtype):
    data = blob(dtype=np.float32)
    data = (data * (1.0 if dtype == np.float32 else 0.9)).astype(dtype)
    affine = oblique_affine()
    path = tmp_path / "blob.nii.gz"
    nib.save(nib.Nifti1Image(data, affine), path)

    by_path = brain_graph(repo)
    by_path.set_input("volume", path)
    a = by_path.render(size=SIZE)

    in_memory = brain_graph(repo)
    in_memory.set_input("volume", data, affine=affine)
    b = in_memory.render(size=SIZE)
    drawn = np.abs(a.astype(int) - a[0, 0].astype(int)).max(axis=2) > 8
    assert drawn.mean() > 0.05, "the blob's surface fills part of the frame"
    assert_pictures_close(a, b, tmp_path, what=f"{np.dtype(dtype).name} array vs NIfTI file")

    # A nibabel image is taken with its affine; SimpleITK's [k, j, i] order with order="kji".
    img = brain_graph(repo)
    img.set_input("volume", nib.load(path))
    assert_pictures_close(a, img.render(size=SIZE), tmp_path, what="nibabel image")
    kji = brain_graph(repo)
    kji.set_input("volume", np.ascontiguousarray(data.transpose(2, 1, 0)), affine=affine, order="kji")
    assert_pictures_close(a, kji.render(size=SIZE), tmp_path, what="order=kji")


def test_the_affine_places_the_volume(repo, tmp_path):
    """With a fixed camera, moving the volume by its affine moves the picture."""
    data = blob()
    g = brain_graph(repo)
    g["camera"]["framing"] = "fixed"
    g["camera"]["target"] = (0.0, 0.0, 0.0)
    g["camera"]["distance"] = 150.0
    centred = np.diag([1.0, 1.0, 1.0, 1.0])
    centred[:3, 3] = -np.array(data.shape) / 2.0
    g.set_input("volume", data, affine=centred)
    middle = g.render(size=SIZE)
    moved = centred.copy()
    moved[0, 3] += 20.0  # 20 mm to the right (+x, RAS)
    g.set_input("volume", data, affine=moved)
    right = g.render(size=SIZE)

    def centre_x(p):
        # Columns holding something other than the background colour of the corner.
        drawn = np.abs(p.astype(int) - p[0, 0].astype(int)).max(axis=2) > 8
        cols = np.nonzero(drawn.any(axis=0))[0]
        assert len(cols) > 0, "the volume is in the frame"
        return (cols.min() + cols.max()) / 2.0

    assert abs(centre_x(right) - centre_x(middle)) > 5, "the volume moved in the picture"


def test_only_what_reads_the_input_runs_again(repo):
    g = brain_graph(repo)
    g.set_input("volume", blob())
    g.render(size=SIZE)
    g["camera"]["azimuth"] = 50
    g.render(size=SIZE)
    assert "mri" not in g.last_ran and "camera" in g.last_ran
    g.set_input("volume", blob() * 0.5)
    g.render(size=SIZE)
    assert "mri" in g.last_ran


def test_saving_keeps_the_files_of_inputs_given_arrays(repo, tmp_path):
    g = brain_graph(repo)
    before = g.get("mri", "path")
    g.set_input("volume", blob())
    with pytest.warns(UserWarning, match="volume"):
        g.save(tmp_path / "saved.ron")
    text = (tmp_path / "saved.ron").read_text()
    assert "memory:" not in text
    saved = hatchery.Graph.load(tmp_path / "saved.ron")
    assert (tmp_path / saved.get("mri", "path")).resolve() == (repo / "graphs" / before).resolve()


def test_labels_with_names_drive_annotations_from_labels(repo, tmp_path):
    ids = np.zeros((48, 44, 40), np.uint16)
    ids[4:20, 4:40, 4:36] = 1
    ids[24:44, 6:20, 8:30] = 2
    ids[26:42, 24:40, 10:34] = 3
    ids[8:16, 10:20, 10:20] = 4
    names = {1: "skeleton", 2: "liver", 3: "lung", 4: "stomach"}
    g = hatchery.Graph.load(repo / "graphs" / "two_level_frog.ron")
    g.set_input("labels", ids, affine=np.diag([2.0, 2.0, 2.5, 1.0]), names=names)
    annotations = g.output("annotations", "annotations", size=SIZE)
    assert sorted(annotations["text"]) == sorted(names.values())
    assert sorted(annotations["object"]) == [1, 2, 3, 4]
    assert annotations["table"].shape == (4, 7)
    labels = g.output("tissues", "labels")
    assert labels["names"] == names
    assert labels["ids"].shape == (40, 44, 48)
    # Names as their own input (a dict), over ids without names.
    g2 = hatchery.Graph.load(repo / "graphs" / "two_level_frog.ron")
    g2.set_input("labels", ids)
    g2.set_input("names", {1: "liver", 2: "skeleton", 3: "stomach", 4: "lung"})
    a2 = g2.output("annotations", "annotations", size=SIZE)
    assert dict(zip(a2["object"], a2["text"])) == {1: "liver", 2: "skeleton", 3: "stomach", 4: "lung"}
    picture = g.render(size=SIZE)
    assert picture.shape == (120, 160, 4)


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            f.write(f"v {float(v[0])!r} {float(v[1])!r} {float(v[2])!r}\n")
        for t in faces:
            f.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")


def torus(n=24, m=12, big=30.0, small=10.0):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n, endpoint=False), np.linspace(0, 2 * np.pi, m, endpoint=False), indexing="ij")
    x = (big + small * np.cos(v)) * np.cos(u)
    y = (big + small * np.cos(v)) * np.sin(u)
    z = small * np.sin(v) + 0.2 * x  # tilted, so the view is not symmetric
    vertices = np.stack([x, y, z], -1).reshape(-1, 3).astype(np.float32)
    faces = []
    for a in range(n):
        for b in range(m):
            p, q = a * m + b, ((a + 1) % n) * m + b
            r, s = ((a + 1) % n) * m + (b + 1) % m, a * m + (b + 1) % m
            faces += [(p, q, r), (p, r, s)]
    return vertices, np.array(faces, np.int64)


def test_numpy_mesh_renders_as_the_same_obj_file(repo, tmp_path):
    vertices, faces = torus()
    path = tmp_path / "torus.obj"
    write_obj(path, vertices, faces)
    a_graph = hatchery.Graph.load(repo / "graphs" / "bunny_surface.ron")
    a_graph.set_input("mesh", path)
    a = a_graph.render(size=SIZE)
    b_graph = hatchery.Graph.load(repo / "graphs" / "bunny_surface.ron")
    b_graph.set_input("mesh", (vertices, faces))
    b = b_graph.render(size=SIZE)
    drawn = np.abs(a.astype(int) - a[0, 0].astype(int)).max(axis=2) > 8
    assert drawn.mean() > 0.05, "the torus fills part of the frame"
    assert_pictures_close(a, b, tmp_path, what="mesh arrays vs OBJ file")
    mesh = b_graph.output("bunny", "mesh") if "bunny" in b_graph else None
    if mesh is not None:
        assert mesh["vertices"].shape == vertices.shape


@pytest.mark.parametrize(
    "value, kwargs, message",
    [
        (np.zeros((4, 4)), {}, "input `volume`: a volume is a 3-D array, got shape (4, 4)"),
        (np.zeros((4, 4, 4), np.complex64), {}, "voxels of type complex64 are not kept"),
        (np.zeros((4, 4, 4), np.int64) + 2**40, {}, "do not fit float32 exactly"),
        (np.zeros((4, 4, 4), np.float32), {"affine": np.eye(3)}, "the affine must be 4×4"),
        (np.zeros((4, 4, 4), np.float32), {"affine": np.zeros((4, 4))}, "input `volume`: the affine's last row"),
        (np.zeros((4, 4, 1), np.float32), {}, "at least 2 along every axis"),
        (np.zeros((4, 4, 4), np.float32), {"order": "zyx"}, "order must be"),
        (np.zeros((4, 4, 4), np.float32), {"names": {1: "a"}}, "names go with a labels input"),
    ],
)
def test_bad_volume_arrays_raise_input_error(repo, value, kwargs, message):
    g = brain_graph(repo)
    with pytest.raises(hatchery.InputError) as caught:
        g.set_input("volume", value, **kwargs)
    assert message in str(caught.value), str(caught.value)
    assert "\n" not in str(caught.value)


def test_input_errors_name_the_input(repo, tmp_path):
    g = brain_graph(repo)
    obj = tmp_path / "m.obj"
    obj.write_text("v 0 0 0\n")
    cases = [
        (lambda: g.set_input("nope", "x.nii"), "the graph has no input `nope` (its inputs: volume)"),
        (lambda: g.set_input("volume", obj), "input `volume` takes a volume file"),
        (lambda: g.set_input("volume", tmp_path / "no.nii"), "input `volume`: cannot read"),
    ]
    frog = hatchery.Graph.load(repo / "graphs" / "two_level_frog.ron")
    cases += [
        (lambda: frog.set_input("labels", np.full((4, 4, 4), 1.5)), "holds 1.5: a label map holds whole numbers"),
        (lambda: frog.set_input("labels", np.full((4, 4, 4), 70000)), "whole numbers 0–65535"),
        (lambda: frog.set_input("labels", np.ones((4, 4, 4), np.uint8), names={0: "air"}), "object id 0"),
        (lambda: frog.set_input("names", ["liver"]), "input `names` takes a names table"),
    ]
    mesh = hatchery.Graph.load(repo / "graphs" / "bunny_surface.ron")
    cases += [
        (lambda: mesh.set_input("mesh", np.zeros((3, 3))), "input `mesh` takes a mesh"),
        (lambda: mesh.set_input("mesh", (np.zeros((3, 2)), np.zeros((1, 3), int))), "vertices must be (n, 3)"),
        (lambda: mesh.set_input("mesh", (np.zeros((3, 3)), np.array([[0, 1, 5]]))), "input `mesh`:"),
        (lambda: mesh.set_input("mesh", (np.full((3, 3), np.nan), np.array([[0, 1, 2]]))), "non-finite"),
    ]
    for action, message in cases:
        with pytest.raises(hatchery.InputError) as caught:
            action()
        assert message in str(caught.value), str(caught.value)
        assert "\n" not in str(caught.value)


def test_a_node_failing_on_an_input_file_raises_input_error(repo, tmp_path):
    bad = tmp_path / "broken.nii.gz"
    bad.write_bytes(b"not a nifti file at all")
    g = brain_graph(repo)
    g.set_input("volume", bad)
    with pytest.raises(hatchery.InputError) as caught:
        g.render(size=SIZE)
    assert str(caught.value).startswith("input `volume`: "), str(caught.value)
    assert "broken.nii.gz" in str(caught.value)
