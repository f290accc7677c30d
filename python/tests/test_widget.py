"""The Jupyter view, driven headlessly through the messages the browser sends (jupyter_rfb's
event path): a drag orbits the camera, the wheel zooms, a slider sets its parameter."""

import numpy as np
import pytest

import hatchery

pytest.importorskip("jupyter_rfb", reason="the widget's optional dependencies (pip install 'hatchery[widget]')")


def message(frame, **event):
    # What jupyter_rfb's JavaScript sends for a pointer event (x, y in CSS pixels).
    event.setdefault("buttons", [1] if event["type"] != "pointer_up" else [])
    event.setdefault("modifiers", [])
    event.setdefault("timestamp", 0.0)
    frame._rfb_handle_msg(frame, event, [])


def test_drag_orbits_wheel_zooms_sliders_set(repo):
    g = hatchery.Graph.load(repo / "graphs" / "hidden_structures.ron")
    view = g.widget(params=["camera.elevation", "hatching.cell"], size=(120, 90))
    assert view.camera == "camera"
    first = view.frame.get_frame()
    assert first.shape == (90, 120, 4)

    azimuth, elevation = g.get("camera", "azimuth"), g.get("camera", "elevation")
    message(view.frame, type="pointer_down", x=60, y=40, button=1)
    message(view.frame, type="pointer_move", x=85, y=50, button=0)
    message(view.frame, type="pointer_up", x=85, y=50, button=1)
    assert g.get("camera", "azimuth") == pytest.approx(azimuth - 25 * 0.4)
    assert g.get("camera", "elevation") == pytest.approx(elevation + 10 * 0.4)
    turned = view.frame.get_frame()
    assert "camera" in g.last_ran and "block_surface" not in g.last_ran

    distance = g.get("camera", "distance")
    fill = g.get("camera", "fill") if g.get("camera", "framing") == "fit" else None
    message(view.frame, type="wheel", x=60, y=40, dx=0.0, dy=100.0, button=0)
    if fill is None:
        assert g.get("camera", "distance") == pytest.approx(distance * 1.1)
    else:
        assert g.get("camera", "fill") == pytest.approx(fill / 1.1)

    slider = view.controls["camera.elevation"]
    slider.value = 5.0
    assert g.get("camera", "elevation") == 5.0
    message(view.frame, type="resize", width=100, height=50, pixel_ratio=2.0)
    assert view.frame.get_frame().shape == (100, 200, 4)
    assert np.abs(turned.astype(int) - first.astype(int)).max() > 50, "the drag turned the view"
    with pytest.raises(hatchery.ParamError):
        g.widget(params=["camera.zoom"])
