"""An interactive view of a graph in Jupyter: drag to orbit the camera, the wheel to zoom, a
slider per chosen parameter.

Built on jupyter_rfb (a remote frame buffer widget, what pygfx uses in notebooks) and ipywidgets:
``pip install hatchery[widget]``. Frames are rendered in the kernel by the graph's renderer and
sent to the browser as images; only what a change touches runs again.

>>> view = g.widget(params=["silhouette.threshold", "hatching.frequency"])
>>> view    # the last expression of a cell shows it
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

try:
    import ipywidgets
    import jupyter_rfb
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "hatchery's Jupyter view needs ipywidgets and jupyter_rfb: pip install 'hatchery[widget]'"
    ) from e

#: Degrees the camera turns per pixel dragged (the editor's viewport turns as much).
DEGREES_PER_PIXEL = 0.4


class Frame(jupyter_rfb.RemoteFrameBuffer):
    """The picture: renders the graph at the widget's size and turns its camera on drags."""

    def __init__(self, view: "View", **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._view = view
        self._drag: Optional[Tuple[float, float, float, float]] = None
        self.frames = 0

    def get_frame(self):
        w, h = self._view.frame_size()
        self.frames += 1
        return self._view.graph.render(size=(w, h), node=self._view.node, port=self._view.port)

    def handle_event(self, event: Dict[str, Any]) -> None:
        kind = event.get("event_type") or event.get("type")
        camera = self._view.camera
        if kind == "resize":
            self._view.resized(event)
        elif camera is None:
            return
        elif kind == "pointer_down" and event.get("button", 1) == 1:
            g = self._view.graph
            self._drag = (
                event["x"],
                event["y"],
                float(g.get(camera, "azimuth")),
                float(g.get(camera, "elevation")),
            )
        elif kind == "pointer_move" and self._drag is not None:
            x0, y0, azimuth, elevation = self._drag
            dx, dy = event["x"] - x0, event["y"] - y0
            g = self._view.graph
            g.set(camera, "azimuth", round((azimuth - dx * DEGREES_PER_PIXEL + 180.0) % 360.0 - 180.0, 3))
            g.set(camera, "elevation", round(min(89.0, max(-89.0, elevation + dy * DEGREES_PER_PIXEL)), 3))
            self.request_draw()
        elif kind == "pointer_up":
            self._drag = None
        elif kind == "wheel":
            self._view.zoom(float(event.get("dy", 0.0)))
            self.request_draw()


class View:
    """A Frame over sliders, one per ``"node.param"`` (floats and ints as sliders with the
    parameter's range, bools as checkboxes, choices as drop-downs)."""

    def __init__(
        self,
        graph,
        params: Sequence[str] = (),
        size: Tuple[int, int] = (480, 360),
        camera: Optional[str] = None,
        node: Optional[str] = None,
        port: Optional[str] = None,
    ) -> None:
        self.graph = graph
        self.size = (int(size[0]), int(size[1]))
        self.node, self.port = node, port
        self.camera = camera if camera is not None else _only_camera(graph)
        self._resize: Optional[Dict[str, Any]] = None
        self.frame = Frame(self, css_width=f"{self.size[0]}px", css_height=f"{self.size[1]}px")
        self.controls: Dict[str, Any] = {name: self._control(name) for name in params}
        self.box = ipywidgets.VBox([self.frame, *self.controls.values()])

    def frame_size(self) -> Tuple[int, int]:
        """The pixels to render: the widget's size in the browser (times its pixel ratio)."""
        if self._resize:
            ratio = float(self._resize.get("pixel_ratio", self._resize.get("ratio", 1.0)) or 1.0)
            return (
                max(1, int(self._resize["width"] * ratio)),
                max(1, int(self._resize["height"] * ratio)),
            )
        return self.size

    def resized(self, event: Dict[str, Any]) -> None:
        self._resize = event

    def zoom(self, dy: float) -> None:
        """The wheel: `fill` of a framing camera, `distance` of a fixed one (a notch ≈ 10 %)."""
        g, camera = self.graph, self.camera
        factor = 1.1 ** (dy / 100.0)
        if g.get(camera, "framing") == "fit":
            g.set(camera, "fill", min(20.0, max(0.05, float(g.get(camera, "fill")) / factor)))
        else:
            g.set(camera, "distance", float(g.get(camera, "distance")) * factor)

    def _control(self, name: str):
        node, _, param = name.partition(".")
        spec = next((p for p in self.graph.schema(node)["params"] if p["name"] == param), None)
        if spec is None:
            from . import ParamError

            raise ParamError(f"node `{node}` has no parameter `{param}`")
        value = self.graph.get(node, param)
        common = dict(description=name, continuous_update=True, style={"description_width": "initial"})
        if spec["kind"] == "float" and not isinstance(value, str):
            lo, hi = _slider_range(spec, float(value))
            w = ipywidgets.FloatSlider(value=float(value), min=lo, max=hi, step=(hi - lo) / 200.0, **common)
        elif spec["kind"] == "int":
            lo, hi = _slider_range(spec, float(value))
            w = ipywidgets.IntSlider(value=int(value), min=int(lo), max=int(hi), **common)
        elif spec["kind"] == "bool":
            w = ipywidgets.Checkbox(value=bool(value), description=name)
        elif spec["kind"] == "choice":
            w = ipywidgets.Dropdown(options=spec["choices"], value=value, description=name)
        else:
            w = ipywidgets.Text(value=str(value), description=name, continuous_update=False)

        def changed(change: Dict[str, Any]) -> None:
            self.graph.set(node, param, change["new"])
            self.frame.request_draw()

        w.observe(changed, names="value")
        return w

    def _repr_mimebundle_(self, **kwargs: Any):
        return self.box._repr_mimebundle_(**kwargs)

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.box)


def _only_camera(graph) -> Optional[str]:
    cameras: List[str] = [n for n in graph.nodes if graph.kind(n) == "Camera"]
    return cameras[0] if len(cameras) == 1 else None


def _slider_range(spec: Dict[str, Any], value: float) -> Tuple[float, float]:
    """The parameter's range, narrowed around the value where it is vast (1e-5..1e6)."""
    lo, hi = float(spec["min"]), float(spec["max"])
    if hi - lo > 1000.0:
        lo, hi = max(lo, min(0.0, value * 2.0)), min(hi, max(1.0, abs(value) * 4.0))
    return lo, hi
