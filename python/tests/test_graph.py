"""Graphs from files and text, saving, the node catalogue, parameters, and their errors."""

import numpy as np
import pytest

import hatchery


def test_load_save_reload_keeps_the_graph(repo, tmp_path):
    g = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    assert g.path.endswith("hidden_structures.ron")
    assert "Fischer" in g.description
    g["camera"]["azimuth"] = 61.5
    g.save(tmp_path / "copy.ron")
    again = hatchery.Graph.load(tmp_path / "copy.ron")
    assert again.get("camera", "azimuth") == 61.5
    assert sorted(again.nodes) == sorted(g.nodes)
    # Saved to another folder, relative paths are rewritten to name the same files.
    moved = again.get("save", "path")
    assert not moved.startswith("/") and (tmp_path / moved).resolve() == repo / "graphs" / "hidden_structures.png"
    again.set("save", "path", "hidden_structures.png")
    assert again.to_ron() == g.to_ron()
    again.validate()


def test_save_elsewhere_keeps_relative_paths_working(repo, tmp_path, shared):
    g = hatchery.Graph.load(repo / "graphs" / "brain_surface.ron")
    g.save(tmp_path / "moved.ron")
    moved = hatchery.Graph.load(tmp_path / "moved.ron")
    # The MRI is still found from the new folder.
    path = moved.get("mri", "path")
    assert (tmp_path / path).resolve() == (shared / "volumes" / "mni152_t1.nii.gz").resolve()


def test_from_ron_and_base_dir(repo):
    text = (repo / "graphs" / "shaded_surface.ron").read_text()
    g = hatchery.Graph.from_ron(text, base_dir=repo / "graphs")
    assert g.kind("surface") == "MarchingCubes"
    assert g.path is None
    assert g.render(size=(64, 48)).shape == (48, 64, 4)


def test_catalogue_lists_kinds_ports_and_parameters():
    kinds = {k["kind"]: k for k in hatchery.nodes()}
    assert len(kinds) > 40
    s = kinds["Silhouette"]
    assert s["inputs"][0]["type"] == "GBuffer" and s["outputs"][0]["name"] == "mask"
    p = {p["name"]: p for p in s["params"]}["depth_threshold"]
    assert p["kind"] == "float" and p["min"] == 0 and p["max"] == 100 and p["default"] == 0.001
    assert "Sobel" in p["doc"]
    pip = {p["name"]: p for p in s["params"]}["pip"]
    assert pip["kind"] == "choice" and "noise" in pip["choices"]
    reads = {p["name"]: p["reads"] for p in kinds["VolumeFile"]["params"]}
    assert reads["path"] == "volume"


def test_generated_kinds_module_matches_the_schemas(repo):
    from hatchery import _generate

    committed = (repo / "python" / "hatchery" / "kinds.py").read_text()
    assert committed == _generate.generate(), (
        "python/hatchery/kinds.py is stale: python -m hatchery._generate python/hatchery/kinds.py"
    )
    from hatchery import kinds

    assert kinds.Silhouette.depth_threshold == 0.001
    assert "Fischer" in kinds.Silhouette.__doc__


def test_parameters_read_and_write_python_types(repo):
    g = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    g.set("camera", "azimuth", 12)  # an int for a float
    assert g.get("camera", "azimuth") == 12.0
    g["camera"]["target"] = (0.1, 0.2, 0.3)
    assert g["camera"]["target"] == (0.1, 0.2, 0.3)
    g.set("camera", "elevation", np.float32(15.5))
    assert g.get("camera", "elevation") == 15.5
    node = g["camera"]
    assert node.kind == "Camera" and "azimuth" in list(node)
    assert "azimuth" in node.doc and "Parameters:" in node.doc


@pytest.mark.parametrize(
    "action, error, message",
    [
        (lambda g: g.set("camera", "azimuth", "sideways"), hatchery.ParamError,
         "node `camera`, parameter `azimuth`: cannot read `sideways` as a number in [-360, 360]"),
        (lambda g: g.set("camera", "azimuth", 999), hatchery.ParamError, "camera"),
        (lambda g: g.set("camera", "zoom", 1), hatchery.ParamError,
         "node `camera` (Camera) has no parameter `zoom` (its parameters are: azimuth"),
        (lambda g: g.set("nowhere", "x", 1), hatchery.ParamError, "no node `nowhere` in the graph"),
        (lambda g: g.set("camera", "azimuth", object()), hatchery.ParamError, "cannot take a object"),
        (lambda g: g.get("camera", "zoom"), hatchery.ParamError, "has no parameter `zoom`"),
        (lambda g: g.kind("nowhere"), hatchery.GraphError, "no node `nowhere` in the graph"),
        (lambda g: g.output("nowhere", "image"), hatchery.GraphError, "no node `nowhere`"),
        (lambda g: g.output("camera", "picture"), hatchery.GraphError,
         "node `camera` (Camera) has no output port `picture`"),
        (lambda g: g.set_input("volume", "x.nii"), hatchery.InputError, "the graph has no input `volume`"),
        (lambda g: g.export_svg("x.svg"), hatchery.GraphError, "no SaveSvg node"),
        (lambda g: g.render(size=(0, 10)), hatchery.RenderError, "at least 1×1"),
        (lambda g: g.render(size=(100000, 10)), hatchery.RenderError, "100000"),
    ],
)
def test_errors_raise_the_named_exception_with_one_line(repo, action, error, message):
    g = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    with pytest.raises(error) as caught:
        action(g)
    text = str(caught.value)
    assert message in text, text
    assert "\n" not in text, text
    assert isinstance(caught.value, hatchery.HatcheryError)


def test_bad_graph_text_names_line_and_node(tmp_path, repo):
    with pytest.raises(hatchery.GraphError) as caught:
        hatchery.Graph.from_ron("(version: 3, nodes: [ (id: \"a\", kind: \"NoSuchKind\") ], edges: [])")
    assert "NoSuchKind" in str(caught.value)
    bad = tmp_path / "bad.ron"
    bad.write_text("(\n  version: 3,\n  nodes: [\n    (id: \"a\" kind: \"Camera\"),\n  ],\n)\n")
    with pytest.raises(hatchery.GraphError) as caught:
        hatchery.Graph.load(bad)
    assert "bad.ron" in str(caught.value) and ":4:" in str(caught.value), str(caught.value)
    with pytest.raises(hatchery.GraphError) as caught:
        hatchery.Graph.load(tmp_path / "missing.ron")
    assert "missing.ron" in str(caught.value)
    # A cycle.
    text = (repo / "graphs" / "hidden_structures.ron").read_text()
    # front_lines feeds front_hatching; feeding it back closes a loop (types agree).
    cyclic = text.replace(
        '(from: ("with_secondary", "image"), to: ("front_lines", "image")),',
        '(from: ("front_hatching", "image"), to: ("front_lines", "image")),',
    )
    assert cyclic != text
    with pytest.raises(hatchery.GraphError) as caught:
        hatchery.Graph.from_ron(cyclic)
    assert "cycle" in str(caught.value), str(caught.value)
