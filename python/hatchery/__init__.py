"""hatchery from Python: illustrative-visualization graphs driven from numpy and Jupyter.

The same graphs (RON files), the same nodes and the same renderer as the ``hatchery`` command
line and the node editor: a graph loaded here renders the pixels ``hatchery render`` writes.

>>> import hatchery
>>> g = hatchery.Graph.load("graphs/shaded_surface.ron")
>>> picture = g.render(size=(320, 240))      # an (h, w, 4) uint8 array
>>> g["camera"]["azimuth"] = 60              # as --set camera.azimuth=60
>>> picture = g.render(size=(320, 240))      # only what depends on the camera runs again

Arrays are given to a graph's declared inputs (``g.inputs``) with :meth:`Graph.set_input`.
World coordinates are RAS+ millimetres; see docs/python.md for how nibabel's and ITK's
voxel → world transforms map onto them.
"""

from __future__ import annotations

import os
import warnings
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np


def _runtime_dir() -> None:
    # Mesa's drivers print "XDG_RUNTIME_DIR is invalid" when it is unset (headless machines,
    # CI); give them a private folder, as the command line does, before the GPU opens.
    if "XDG_RUNTIME_DIR" not in os.environ:
        import tempfile

        path = os.path.join(tempfile.gettempdir(), f"hatchery-runtime-{os.getuid() if hasattr(os, 'getuid') else 'user'}")
        try:
            os.makedirs(path, mode=0o700, exist_ok=True)
            os.environ["XDG_RUNTIME_DIR"] = path
        except OSError:
            pass


_runtime_dir()

from . import _hatchery  # noqa: E402
from ._hatchery import (  # noqa: E402
    FORMAT_VERSION,
    GraphError,
    HatcheryError,
    InputError,
    JobError,
    ParamError,
    RenderError,
    adapter,
)

__all__ = [
    "FORMAT_VERSION",
    "Graph",
    "GraphError",
    "HatcheryError",
    "InputError",
    "JobError",
    "Node",
    "ParamError",
    "Picture",
    "RenderError",
    "adapter",
    "affine_from_itk",
    "nodes",
]

Size = Tuple[int, int]
PathLike = Union[str, "os.PathLike[str]"]


def nodes() -> List[Dict[str, Any]]:
    """The node catalogue: one dict per kind (``kind``, ``category``, ``doc``, ``inputs``,
    ``outputs``, ``params``), as ``hatchery nodes`` prints it. Each parameter has ``name``,
    ``kind`` (float, int, bool, choice, color, vec3, path, text), ``default``, ``doc``, ``min`` /
    ``max`` (numbers), ``choices`` (choice), ``relative`` (takes "percentile(60)"...) and
    ``reads`` (the graph-input kind a path parameter reads)."""
    return _hatchery.nodes()


class Picture(np.ndarray):
    """An (h, w, 4) uint8 RGBA picture (straight alpha, what SaveImage writes) that shows itself
    inline in Jupyter. It is a numpy array: slice it, plot it with ``plt.imshow``."""

    def __new__(cls, pixels: np.ndarray) -> "Picture":
        return np.asarray(pixels, dtype=np.uint8).view(cls)

    def png(self) -> bytes:
        """The picture as PNG bytes."""
        a = np.ascontiguousarray(self, dtype=np.uint8)
        if a.ndim != 3 or a.shape[2] != 4:
            raise ValueError(f"a picture is (h, w, 4), this is {a.shape}")
        return _hatchery.png_bytes(a.reshape(-1), a.shape[1], a.shape[0])

    def _repr_png_(self) -> bytes:
        return self.png()

    def save(self, path: PathLike) -> None:
        """Writes the picture as a PNG file."""
        with open(os.fspath(path), "wb") as f:
            f.write(self.png())


def affine_from_itk(
    origin: Sequence[float], spacing: Sequence[float], direction: Sequence[float]
) -> np.ndarray:
    """The 4×4 voxel → world affine (RAS+ mm) of an ITK / SimpleITK image, whose origin and
    direction are in LPS+: ``affine_from_itk(img.GetOrigin(), img.GetSpacing(),
    img.GetDirection())``. Use it with the array of ``sitk.GetArrayFromImage(img)`` and
    ``order="kji"`` (SimpleITK's arrays are indexed [k, j, i])."""
    d = np.asarray(direction, dtype=np.float64).reshape(3, 3)
    lps = np.eye(4)
    lps[:3, :3] = d @ np.diag(np.asarray(spacing, dtype=np.float64))
    lps[:3, 3] = np.asarray(origin, dtype=np.float64)
    return np.diag([-1.0, -1.0, 1.0, 1.0]) @ lps


class Node(Mapping[str, Any]):
    """One node of a graph, as a dict of its parameters: ``g["camera"]["azimuth"] = 60``."""

    def __init__(self, graph: "Graph", node: str) -> None:
        self._graph = graph
        self.id = node
        self.kind = graph.kind(node)

    def __getitem__(self, param: str) -> Any:
        return self._graph.get(self.id, param)

    def __setitem__(self, param: str, value: Any) -> None:
        self._graph.set(self.id, param, value)

    def __iter__(self) -> Iterator[str]:
        return iter(self._graph.params(self.id))

    def __len__(self) -> int:
        return len(self._graph.params(self.id))

    @property
    def doc(self) -> str:
        """The kind's documentation: what it does, its ports and parameters (hatchery.kinds)."""
        from . import kinds

        cls = getattr(kinds, self.kind, None)
        return (cls.__doc__ or "") if cls is not None else self._graph.schema(self.id)["doc"]

    def __repr__(self) -> str:
        return f"<hatchery.Node {self.id} ({self.kind}) {self._graph.params(self.id)}>"


class Graph:
    """A graph and the renderer that runs it.

    Build one with :meth:`load` or :meth:`from_ron`. Before the first render nothing needs a GPU.
    Every method may be called from several threads (they run one at a time per graph, with the
    GIL released while rendering); see docs/python.md.
    """

    def __init__(self, native: "_hatchery.Graph") -> None:
        self._g = native

    # -- files --------------------------------------------------------------------------------

    @classmethod
    def load(cls, path: PathLike) -> "Graph":
        """Loads and validates a graph file (raises GraphError naming the file, line and node)."""
        return cls(_hatchery.Graph.load(os.fspath(path)))

    @classmethod
    def from_ron(cls, text: str, base_dir: Optional[PathLike] = None) -> "Graph":
        """Parses graph text; relative paths in it resolve against ``base_dir`` (default: the
        working directory). Raises GraphError."""
        return cls(_hatchery.Graph.from_ron(text, None if base_dir is None else os.fspath(base_dir)))

    def save(self, path: PathLike) -> None:
        """Writes the graph as RON (atomically). Inputs given arrays are saved with the files they
        had (a warning names them); relative paths stay valid when saved to another folder."""
        unsaved = self._g.save(os.fspath(path))
        if unsaved:
            warnings.warn(
                f"{os.fspath(path)}: input(s) {', '.join(unsaved)} hold arrays, which a graph file "
                "cannot hold: it keeps their files",
                stacklevel=2,
            )

    def to_ron(self) -> str:
        """The graph as RON text."""
        return self._g.to_ron()

    def copy(self) -> "Graph":
        """An independent graph with the same nodes, parameters and folder (one per worker of a
        thread pool sweeps in parallel). Inputs given arrays are not copied: the copy has their
        files; give it the arrays again."""
        base = os.path.dirname(os.path.abspath(self.path)) if self.path else None
        return Graph.from_ron(self.to_ron(), base_dir=base)

    def validate(self) -> None:
        """Checks the graph as a file is checked; raises GraphError listing every problem."""
        self._g.validate()

    @property
    def path(self) -> Optional[str]:
        """The file loaded from or last saved to."""
        p = self._g.path
        return None if p is None else os.fspath(p)

    @property
    def description(self) -> str:
        return self._g.description

    @property
    def pixel_scale(self) -> float:
        """Rendered pixels per pixel of the designed figure (default 1): hatching cells, line
        widths and label sizes are multiplied by it, as ``hatchery render --scale`` does. To
        render the figure designed at (w, h) for print at 3× its resolution:
        ``g.pixel_scale = 3; g.render(size=(3 * w, 3 * h))``. Raises RenderError for a value
        that is not a positive number up to 64."""
        return self._g.pixel_scale

    @pixel_scale.setter
    def pixel_scale(self, scale: float) -> None:
        self._g.pixel_scale = float(scale)

    # -- nodes and parameters -----------------------------------------------------------------

    @property
    def nodes(self) -> List[str]:
        """Node ids, in execution order."""
        return self._g.node_ids()

    def kind(self, node: str) -> str:
        return self._g.kind(node)

    def schema(self, node: str) -> Dict[str, Any]:
        """The node's kind as :func:`nodes` lists it."""
        return self._g.schema(node)

    def __getitem__(self, node: str) -> Node:
        return Node(self, node)

    def __contains__(self, node: str) -> bool:
        return node in self._g.node_ids()

    def set(self, node: str, param: str, value: Any) -> None:
        """Sets a parameter: float, int, bool, str (a choice, a path, "percentile(60)"), or a
        tuple for colours and vectors; parsed as ``--set node.param=value``. Raises ParamError."""
        self._g.set(node, param, value)

    def get(self, node: str, param: str) -> Any:
        """A parameter's value. Raises ParamError."""
        return self._g.get(node, param)

    def params(self, node: str) -> Dict[str, Any]:
        """Every parameter of a node: {name: value}."""
        return self._g.params(node)

    # -- inputs -------------------------------------------------------------------------------

    @property
    def inputs(self) -> List[Dict[str, Any]]:
        """The declared inputs: ``{name, type, doc, to, default}`` (type: volume, labels, mesh,
        names; ``to``: the (node, parameter) pairs the input sets)."""
        return self._g.inputs()

    def set_input(
        self,
        name: str,
        value: Any,
        affine: Optional[Any] = None,
        names: Optional[Mapping[int, str]] = None,
        order: str = "ijk",
    ) -> None:
        """Gives graph input ``name`` its data. ``value`` is

        - a path (str or os.PathLike): a file, as ``hatchery render --input name=path``;
        - a 3-D numpy array for a volume or labels input, indexed ``[i, j, k]`` (nibabel's order;
          ``order="kji"`` for SimpleITK's ``GetArrayFromImage``), with ``affine`` the 4×4
          voxel → world matrix in RAS+ mm (nibabel's ``img.affine``; :func:`affine_from_itk`
          for ITK). Voxel types kept: uint8, int8, uint16, int16, float32 (bool becomes uint8,
          float64 float32, wider integers the narrowest type that holds them exactly);
        - a nibabel image (its data and affine);
        - for labels: whole numbers 0–65535 with ``names`` {id: name};
        - for a mesh: ``(vertices, faces)`` or ``(vertices, faces, normals)`` arrays, or an
          object with ``vertices`` and ``faces`` (a trimesh mesh); positions in world mm;
        - for names: a dict {id: name}.

        Raises InputError with the command line's one-line message.
        """
        kind = self._input_kind(name)
        if isinstance(value, (str, os.PathLike)):
            self._g.set_input_path(name, os.fspath(value))
            return
        if hasattr(value, "dataobj") and hasattr(value, "affine"):  # a nibabel image
            if affine is None:
                affine = value.affine
            value = np.asanyarray(value.dataobj)
        if kind == "mesh":
            self._set_mesh(name, value)
        elif kind == "names":
            if not isinstance(value, Mapping):
                raise InputError(f"input `{name}` takes a names table: a dict {{id: name}}")
            self._g.set_input_names(name, {int(k): str(v) for k, v in value.items()})
        elif kind in ("volume", "labels"):
            flat, dims = _voxels(name, value, order)
            a = _affine(name, affine)
            if kind == "labels":
                ids = _label_ids(name, flat)
                table = None if names is None else {int(k): str(v) for k, v in names.items()}
                self._g.set_input_labels(name, ids, dims, a, table)
            else:
                if names is not None:
                    raise InputError(f"input `{name}` is a volume: names go with a labels input")
                self._g.set_input_volume(name, _volume_voxels(name, flat), dims, a)

    def _input_kind(self, name: str) -> str:
        for i in self._g.inputs():
            if i["name"] == name:
                return i["type"]
        known = ", ".join(i["name"] for i in self._g.inputs()) or "none"
        raise InputError(f"the graph has no input `{name}` (its inputs: {known})")

    def _set_mesh(self, name: str, value: Any) -> None:
        if hasattr(value, "vertices") and hasattr(value, "faces"):
            parts = [value.vertices, value.faces]
            normals = getattr(value, "vertex_normals", None)
            if normals is not None:
                parts.append(normals)
        elif isinstance(value, (tuple, list)) and len(value) in (2, 3):
            parts = list(value)
        else:
            raise InputError(
                f"input `{name}` takes a mesh: (vertices, faces[, normals]) arrays or a trimesh"
            )
        vertices = np.asarray(parts[0])
        faces = np.asarray(parts[1])
        if vertices.ndim != 2 or vertices.shape[1] != 3:
            raise InputError(f"input `{name}`: vertices must be (n, 3), got {vertices.shape}")
        if faces.ndim != 2 or faces.shape[1] != 3:
            raise InputError(f"input `{name}`: faces must be (m, 3) triangles, got {faces.shape}")
        if faces.size and (not np.issubdtype(faces.dtype, np.integer) or faces.min() < 0):
            raise InputError(f"input `{name}`: faces must be non-negative integer indices")
        normals = None
        if len(parts) == 3 and parts[2] is not None:
            normals = np.ascontiguousarray(np.asarray(parts[2], dtype=np.float32).reshape(-1))
        self._g.set_input_mesh(
            name,
            np.ascontiguousarray(vertices, dtype=np.float32).reshape(-1),
            np.ascontiguousarray(faces, dtype=np.uint32).reshape(-1),
            normals,
        )

    # -- rendering ----------------------------------------------------------------------------

    def render(
        self, size: Optional[Size] = None, node: Optional[str] = None, port: Optional[str] = None
    ) -> Picture:
        """Renders the picture at ``size`` = (width, height) (default 1024×768) and returns it
        as an (h, w, 4) uint8 array: what the graph's SaveImage node writes (or ``node.port``),
        without writing a file. Only what changed since the last call runs again. Raises
        RenderError (a node failed), InputError (a node reading an input failed), GraphError."""
        pixels, w, h = self._g.render_rgba8(_size(size), node, port)
        self._warn()
        return Picture(np.asarray(pixels).reshape(h, w, 4))

    def _warn(self) -> None:
        # What the command line prints on stderr (a constant volume, an iso value with no
        # surface) as Python warnings, for the nodes that just ran.
        found = self._g.warnings()
        for node in self._g.last_ran():
            if node in found:
                warnings.warn(f"{node}: {found[node]}", RuntimeWarning, stacklevel=3)

    def output(self, node: str, port: str, size: Optional[Size] = None) -> Any:
        """The data on ``node.port`` in the layouts of ``--dump node.port=x.npy`` (float32):
        Image (h, w, 4) premultiplied RGBA, Mask (h, w), GBuffer (h, w, 4) depth and normal,
        Volume (k, j, i), Importance (h, w, 4). A Mesh gives ``{vertices, normals, faces}``,
        Labels ``{ids (k, j, i) uint16, names}``, Annotations ``{text, object, table}`` (table:
        --dump's N × 7 rows of anchor x, y, z, shown, label x, y, leader opacity)."""
        return self._g.output(node, port, _size(size))

    def run(self, size: Optional[Size] = None) -> List[str]:
        """Runs the SaveImage and SaveSvg nodes (writing their files, as ``hatchery render``)
        and returns the paths written."""
        return [os.fspath(p) for p in self._g.run(_size(size))]

    def export_svg(self, path: PathLike, size: Optional[Size] = None) -> None:
        """Writes the graph's SVG figure (its one SaveSvg node) to ``path``."""
        self._g.export_svg(os.fspath(path), _size(size))

    @property
    def last_ran(self) -> List[str]:
        """The nodes the last render ran (the rest came from the cache)."""
        return self._g.last_ran()

    @property
    def warnings(self) -> Dict[str, str]:
        """The last render's warnings by node id."""
        return self._g.warnings()

    @property
    def resolved(self) -> Dict[str, Dict[str, str]]:
        """Data-relative parameters as resolved by the last render: node → param → text."""
        return self._g.resolved()

    def widget(self, params: Sequence[str] = (), size: Size = (480, 360), camera: Optional[str] = None):
        """An interactive view for Jupyter (needs ``pip install hatchery[widget]``): drag to
        orbit the camera, a slider per ``"node.param"`` in ``params``. See hatchery.widget."""
        from .widget import View

        return View(self, params=params, size=size, camera=camera)

    def __repr__(self) -> str:
        where = self.path or "from text"
        return f"<hatchery.Graph {where}: {len(self.nodes)} nodes>"


def _size(size: Optional[Size]) -> Optional[Tuple[int, int]]:
    if size is None:
        return None
    try:
        w, h = size
        w, h = int(w), int(h)
    except (TypeError, ValueError):
        raise RenderError(f"size must be (width, height), got {size!r}") from None
    if w < 1 or h < 1:
        raise RenderError(f"size must be at least 1×1 pixels, got {w}×{h}")
    return (w, h)


def _voxels(name: str, value: Any, order: str) -> Tuple[np.ndarray, Tuple[int, int, int]]:
    """A flat buffer, i fastest, and dims (i, j, k) of a 3-D array."""
    a = np.asanyarray(value)
    if a.ndim == 4 and a.shape[3] == 1:
        a = a[..., 0]
    if a.ndim != 3:
        raise InputError(f"input `{name}`: a volume is a 3-D array, got shape {a.shape}")
    if order == "ijk":
        return np.ravel(a, order="F"), (a.shape[0], a.shape[1], a.shape[2])
    if order == "kji":
        return np.ravel(a, order="C"), (a.shape[2], a.shape[1], a.shape[0])
    raise InputError(f"input `{name}`: order must be \"ijk\" (nibabel) or \"kji\" (SimpleITK), got {order!r}")


_KEPT = (np.uint8, np.int8, np.uint16, np.int16, np.float32)


def _volume_voxels(name: str, flat: np.ndarray) -> np.ndarray:
    """Voxels in a type the loaders keep, converted without loss where that is possible."""
    if flat.dtype == np.bool_:
        return flat.astype(np.uint8)
    if flat.dtype.type in _KEPT:
        return np.ascontiguousarray(flat)
    if np.issubdtype(flat.dtype, np.floating):
        return np.ascontiguousarray(flat, dtype=np.float32)  # as the loaders narrow float64
    if np.issubdtype(flat.dtype, np.integer):
        lo, hi = (int(flat.min()), int(flat.max())) if flat.size else (0, 0)
        for t in (np.uint8, np.int8, np.uint16, np.int16):
            if np.iinfo(t).min <= lo and hi <= np.iinfo(t).max:
                return flat.astype(t)
        if max(abs(lo), abs(hi)) <= 2**24:
            return flat.astype(np.float32)
        raise InputError(
            f"input `{name}`: {flat.dtype} values in [{lo}, {hi}] do not fit float32 exactly "
            "(|v| ≤ 2^24); rescale them first"
        )
    raise InputError(
        f"input `{name}`: voxels of type {flat.dtype} are not kept (uint8, int8, uint16, int16, float32)"
    )


def _label_ids(name: str, flat: np.ndarray) -> np.ndarray:
    """Object ids as uint16; raises InputError naming the first voxel that is not an id."""
    if flat.dtype == np.uint16:
        return np.ascontiguousarray(flat)
    if flat.dtype == np.bool_:
        return flat.astype(np.uint16)
    if not (np.issubdtype(flat.dtype, np.integer) or np.issubdtype(flat.dtype, np.floating)):
        raise InputError(f"input `{name}`: object ids must be whole numbers, got {flat.dtype}")
    bad = ~((flat >= 0) & (flat <= 65535))
    if np.issubdtype(flat.dtype, np.floating):
        bad |= ~np.isfinite(flat) | (np.floor(flat) != flat)
    if bad.any():
        first = int(np.argmax(bad))
        raise InputError(
            f"input `{name}`: voxel {first} (flat, i fastest) holds {flat[first]}: a label map holds "
            "whole numbers 0–65535 (object ids)"
        )
    return flat.astype(np.uint16)


def _affine(name: str, affine: Any) -> Optional[List[List[float]]]:
    if affine is None:
        return None
    a = np.asarray(affine, dtype=np.float64)
    if a.shape != (4, 4):
        raise InputError(f"input `{name}`: the affine must be 4×4, got shape {a.shape}")
    return a.tolist()
