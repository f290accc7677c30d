"""Rendering through Python as the command line renders: pictures, --set, outputs, SVG, threads."""

import subprocess
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import hatchery
from conftest import assert_pictures_close, read_png

SIZE = (160, 120)


def test_render_equals_the_cli_and_set_changes_it_as_cli_set(repo, tmp_path, hatchery_bin):
    graph = repo / "graphs" / "hidden_structures.ron"
    out = tmp_path / "cli.png"
    subprocess.run([hatchery_bin, "render", graph, "--size", "160x120", "-o", out], check=True, capture_output=True)
    g = hatchery.Graph.load(graph)
    plain = g.render(size=SIZE)
    assert_pictures_close(read_png(out), plain, tmp_path, what="render() vs hatchery render")

    sets = ["camera.azimuth=75", "silhouette1.depth_threshold=0.02"]
    args = [hatchery_bin, "render", graph, "--size", "160x120", "-o", tmp_path / "set.png"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, capture_output=True)
    for s in sets:
        node_param, value = s.split("=")
        node, param = node_param.split(".")
        g.set(node, param, float(value))
    changed = g.render(size=SIZE)
    assert np.abs(changed.astype(int) - plain.astype(int)).max() > 50, "the change shows"
    assert_pictures_close(read_png(tmp_path / "set.png"), changed, tmp_path, what="set() vs --set")
    assert "camera" in g.last_ran


def test_pixel_scale_is_the_cli_scale(repo, tmp_path, hatchery_bin):
    graph = repo / "graphs" / "default.ron"
    out = tmp_path / "scaled.png"
    subprocess.run(
        [hatchery_bin, "render", graph, "--size", "160x120", "--scale", "2", "-o", out],
        check=True,
        capture_output=True,
    )
    g = hatchery.Graph.load(graph)
    plain = g.render(size=(320, 240))
    g.pixel_scale = 2
    assert g.pixel_scale == 2.0
    scaled = g.render(size=(320, 240))
    assert_pictures_close(read_png(out), scaled, tmp_path, what="pixel_scale 2 vs --scale 2")
    assert np.abs(scaled.astype(int) - plain.astype(int)).max() > 128, "the hatching changed"
    with pytest.raises(hatchery.RenderError, match="pixel_scale"):
        g.pixel_scale = 0


def test_picture_is_an_array_that_shows_as_png(repo):
    g = hatchery.Graph.load(repo / "graphs" / "shaded_surface.ron")
    p = g.render(size=(64, 48))
    assert isinstance(p, np.ndarray) and p.shape == (48, 64, 4) and p.dtype == np.uint8
    png = p._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    from io import BytesIO

    from PIL import Image

    assert (np.asarray(Image.open(BytesIO(png))) == p).all()


def test_outputs_have_the_dump_layouts(repo, tmp_path, hatchery_bin):
    graph = repo / "graphs" / "hidden_structures.ron"
    subprocess.run(
        [hatchery_bin, "render", graph, "--size", "160x120", "-o", tmp_path / "x.png",
         "--dump", f"layer1.gbuffer={tmp_path / 'g.npy'}"],
        check=True, capture_output=True,
    )
    g = hatchery.Graph.load(graph)
    gbuffer = g.output("layer1", "gbuffer", size=SIZE)
    assert gbuffer.shape == (120, 160, 4) and gbuffer.dtype == np.float32
    np.testing.assert_allclose(gbuffer, np.load(tmp_path / "g.npy"), atol=1e-6)
    mask = g.output("silhouette1", "mask", size=SIZE)
    assert mask.shape == (120, 160) and set(np.unique(mask)) <= {0.0, 1.0}
    mesh = g.output("block_surface", "mesh")
    assert mesh["vertices"].shape[1] == 3 and mesh["faces"].max() < len(mesh["vertices"])
    volume = g.output("block", "volume")
    assert volume.ndim == 3


def test_export_svg_and_run_write_files(repo, tmp_path):
    g = hatchery.Graph.load(repo / "graphs" / "default.ron")
    before = g.get("vector", "path") if "vector" in g else None
    g.export_svg(tmp_path / "figure.svg", size=SIZE)
    text = (tmp_path / "figure.svg").read_text()
    assert text.startswith("<?xml") or text.startswith("<svg"), text[:40]
    assert "<svg" in text and "inkscape:groupmode" in text
    if before is not None:
        assert g.get("vector", "path") == before


def test_copies_render_in_parallel_as_the_original(repo):
    g = hatchery.Graph.load(repo / "graphs" / "shaded_surface.ron")
    copies = [g.copy() for _ in range(3)]
    for k, c in enumerate(copies):
        c["camera"]["azimuth"] = 20.0 * k
    with ThreadPoolExecutor(max_workers=3) as pool:
        pictures = list(pool.map(lambda c: c.render(size=(48, 36)), copies))
    for k, picture in enumerate(pictures):
        g["camera"]["azimuth"] = 20.0 * k
        assert (picture == g.render(size=(48, 36))).all()
    assert g.get("camera", "azimuth") == 40.0 and copies[0].get("camera", "azimuth") == 0.0


def test_threads_render_without_deadlock_and_as_one_thread_does(repo):
    g = hatchery.Graph.load(repo / "graphs" / "shaded_surface.ron")
    other = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    sizes = [(64 + 8 * i, 48) for i in range(6)]
    alone = [g.render(size=s) for s in sizes]
    alone_other = other.render(size=SIZE)

    def work(i):
        if i % 3 == 2:
            return "other", other.render(size=SIZE)
        return i, g.render(size=sizes[i])

    with ThreadPoolExecutor(max_workers=4) as pool:
        results = list(pool.map(work, range(6)))
    for key, picture in results:
        if key == "other":
            assert (picture == alone_other).all()
        else:
            assert (picture == alone[key]).all()


def test_a_failing_node_raises_render_error(tmp_path):
    text = """(
        version: 3,
        nodes: [
            (id: "mri", kind: "VolumeFile", params: {"path": "missing.nii.gz"}),
            (id: "surface", kind: "MarchingCubes"),
        ],
        edges: [(from: ("mri", "volume"), to: ("surface", "volume"))],
    )"""
    g = hatchery.Graph.from_ron(text, base_dir=tmp_path)
    try:
        g.output("surface", "mesh")
    except hatchery.RenderError as e:
        message = str(e)
    else:
        raise AssertionError("a missing file fails the node")
    assert message.startswith("node `mri` (VolumeFile): "), message
    assert "missing.nii.gz" in message and "\n" not in message


def test_the_gil_is_released_while_rendering(repo):
    """Python code runs while another thread is inside a render: a loop in this thread takes
    steps between the moment the native call starts and the moment it returns."""
    import threading
    import time

    g = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    g.render(size=(64, 48))
    span = {}

    def render():
        span["start"] = time.perf_counter()
        g._g.set("camera", "azimuth", 50.0)
        g._g.render_rgba8((1024, 768), None, None)
        span["end"] = time.perf_counter()

    steps = []
    worker = threading.Thread(target=render)
    worker.start()
    while worker.is_alive():
        steps.append(time.perf_counter())
    worker.join()
    inside = [t for t in steps if span["start"] < t < span["end"]]
    assert len(inside) > 10, f"{len(inside)} steps while rendering {span['end'] - span['start']:.3f} s"
