//! `hatchery._hatchery.Graph`: a graph and the [`Session`] that renders it.
//!
//! Thread safety: every method locks the graph's one mutex, with the GIL released while it
//! waits and while it renders, so a Graph can be shared by Python threads (calls on one graph
//! run one at a time; graphs render concurrently on the one shared GPU device).
//!
//! Over 600 lines: the `Graph` class is one Python-facing type whose methods (load, edit, render,
//! export, bind inputs) share its lock and error mapping.

use hatchery_graph::executor::PassReport;
use hatchery_graph::{Graph as GraphModel, GraphDocument, GraphErrors};
use hatchery_nodes::Registry;
use hatchery_nodes::memory_inputs::InputData;
use hatchery_nodes::{Session, SessionError, Value};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard};

use crate::errors::{GraphError, InputError, ParamError, RenderError, render_error};

/// The frame size when none is given (the command line's default).
const DEFAULT_SIZE: (u32, u32) = (1024, 768);

/// Before the first render a graph needs no GPU; the session opens on first use.
// One per Graph, so the size of its variants does not matter.
#[allow(clippy::large_enum_variant)]
enum State {
    Closed {
        registry: Registry,
        graph: GraphModel,
    },
    Open(Box<Session>),
    /// Only while the session is being opened.
    Opening,
}

struct Inner {
    state: State,
    /// The file the graph was loaded from or last saved to.
    path: Option<PathBuf>,
    last: Option<PassReport>,
    /// Seconds the last `render_rgba8` spent in Rust (the pass and the read-back).
    last_seconds: f64,
    /// Lengths in pixels of the designed figure are multiplied by this (`render --scale`).
    pixel_scale: f64,
}

impl Inner {
    fn graph(&self) -> &GraphModel {
        match &self.state {
            State::Closed { graph, .. } => graph,
            State::Open(s) => &s.graph,
            State::Opening => unreachable!("the session opens under the lock"),
        }
    }

    fn registry(&self) -> &Registry {
        match &self.state {
            State::Closed { registry, .. } => registry,
            State::Open(s) => &s.registry,
            State::Opening => unreachable!("the session opens under the lock"),
        }
    }

    /// The session, opened (on the shared GPU) at `size` if it is not open yet; an open one is
    /// resized to `size` when given.
    fn session(&mut self, size: Option<(u32, u32)>) -> PyResult<&mut Session> {
        if let State::Closed { .. } = self.state {
            let gpu = crate::shared_gpu().map_err(RenderError::new_err)?;
            let (w, h) = size.unwrap_or(DEFAULT_SIZE);
            gpu.check_2d_size("the frame", w, h)
                .map_err(|e| RenderError::new_err(e.to_string()))?;
            let State::Closed { registry, graph } =
                std::mem::replace(&mut self.state, State::Opening)
            else {
                unreachable!()
            };
            let session = Session::with_gpu(registry, graph, gpu, w, h)
                .expect("the size was checked and the GPU is open");
            self.state = State::Open(Box::new(session));
        }
        let State::Open(session) = &mut self.state else {
            unreachable!()
        };
        session.ctx.set_pixel_scale(self.pixel_scale);
        if let Some((w, h)) = size
            && session.ctx.size() != (w, h)
        {
            session
                .ctx
                .set_size(w, h)
                .map_err(|e| RenderError::new_err(e.to_string()))?;
        }
        Ok(session)
    }

    fn set_text(&mut self, node: &str, param: &str, text: &str) -> Result<(), String> {
        let value = hatchery_nodes::parse_param(self.graph(), self.registry(), node, param, text)
            .map_err(|e| e.to_string())?;
        let (registry, graph) = match &mut self.state {
            State::Closed { registry, graph } => (&*registry, graph),
            State::Open(s) => (&s.registry, &mut s.graph),
            State::Opening => unreachable!(),
        };
        graph
            .set_param(registry, node, param, value)
            .map_err(|e| GraphErrors::from(e).to_string())
    }

    fn document(&self) -> GraphDocument {
        match &self.state {
            State::Open(s) => s.document(),
            _ => self.graph().to_document(self.registry()),
        }
    }

    /// Runs `targets` at `size`, naming the graph input a failed node reads.
    fn run(&mut self, targets: &[&str], size: Option<(u32, u32)>) -> PyResult<()> {
        let session = self.session(size)?;
        match session.run(targets) {
            Ok(report) => {
                self.last = Some(report);
                Ok(())
            }
            Err(SessionError::Exec(exec)) => Err(match session.input_of(&exec.node) {
                Some(input) => InputError::new_err(format!("input `{}`: {exec}", input.name)),
                None => RenderError::new_err(exec.to_string()),
            }),
            Err(e) => Err(render_error(e)),
        }
    }

    fn sinks(&self, kind: &str) -> Vec<String> {
        self.graph()
            .nodes()
            .filter(|n| n.kind == kind)
            .map(|n| n.id.clone())
            .collect()
    }
}

fn graph_error(e: impl std::fmt::Display) -> PyErr {
    GraphError::new_err(e.to_string())
}

#[pyclass(module = "hatchery._hatchery", name = "Graph", frozen)]
pub struct Graph {
    inner: Mutex<Inner>,
}

impl Graph {
    fn new(registry: Registry, graph: GraphModel, path: Option<PathBuf>) -> Self {
        Graph {
            inner: Mutex::new(Inner {
                state: State::Closed { registry, graph },
                path,
                last: None,
                last_seconds: 0.0,
                pixel_scale: 1.0,
            }),
        }
    }

    /// The lock, waited for without the GIL (another thread may hold it while rendering).
    fn lock(&self, py: Python<'_>) -> MutexGuard<'_, Inner> {
        // A panic while the lock was held leaves the graph as it was; go on with it.
        use pyo3::sync::MutexExt;
        self.inner
            .lock_py_attached(py)
            .unwrap_or_else(|e| e.into_inner())
    }

    /// Runs `f` on the graph with the GIL released (rendering, GPU read-back).
    fn detached<T: Send>(&self, py: Python<'_>, f: impl FnOnce(&mut Inner) -> T + Send) -> T {
        py.detach(|| {
            let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
            f(&mut inner)
        })
    }
}

#[pymethods]
impl Graph {
    /// Loads and validates a graph file; relative paths in it resolve against its folder.
    /// Raises GraphError (the message names the file, line and node).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Graph> {
        py.detach(|| {
            let registry = hatchery_nodes::registry();
            let graph = GraphModel::load_file(&path, &registry).map_err(graph_error)?;
            Ok(Graph::new(registry, graph, Some(path)))
        })
    }

    /// Parses and validates graph text; relative paths resolve against `base_dir` (default:
    /// the working directory). Raises GraphError.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_ron(text: &str, base_dir: Option<PathBuf>) -> PyResult<Graph> {
        let registry = hatchery_nodes::registry();
        let (doc, source) = GraphDocument::parse(text, None).map_err(graph_error)?;
        let graph = GraphModel::from_document(&doc, &source, &registry, base_dir.as_deref())
            .map_err(graph_error)?;
        Ok(Graph::new(registry, graph, None))
    }

    /// The graph as RON text (what `save` writes).
    fn to_ron(&self, py: Python<'_>) -> String {
        self.lock(py).document().to_ron_string()
    }

    /// Writes the graph (atomically). Parameters bound to inputs given arrays keep the paths
    /// they held; relative paths are rewritten to name the same files from a new folder.
    /// Returns the names of inputs whose arrays were not saved. Raises GraphError.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<Vec<String>> {
        self.detached(py, |inner| {
            let mut doc = inner.document();
            if let Some(folder) = std::path::absolute(&path)
                .ok()
                .and_then(|p| p.parent().map(Path::to_path_buf))
            {
                hatchery_graph::rebase::rebase_paths(&mut doc, inner.registry(), &folder);
            }
            doc.save(&path)
                .map_err(|e| GraphError::new_err(format!("cannot save {}: {e}", path.display())))?;
            inner.path = Some(path);
            Ok(match &inner.state {
                State::Open(s) => s.memory_inputs(),
                _ => Vec::new(),
            })
        })
    }

    /// Checks the graph again as a file would be checked (kinds, edges, types, cycles,
    /// parameters). Raises GraphError listing every problem.
    fn validate(&self, py: Python<'_>) -> PyResult<()> {
        let inner = self.lock(py);
        let text = inner.document().to_ron_string();
        let (doc, source) =
            GraphDocument::parse(&text, inner.path.as_deref()).map_err(graph_error)?;
        GraphModel::from_document(&doc, &source, inner.registry(), inner.graph().base_dir())
            .map(|_| ())
            .map_err(graph_error)
    }

    /// The file the graph was loaded from or last saved to.
    #[getter]
    fn path(&self, py: Python<'_>) -> Option<PathBuf> {
        self.lock(py).path.clone()
    }

    /// How many rendered pixels one pixel of the designed figure is: hatching cells, line
    /// widths and label sizes (the parameters in pixels) are multiplied by it, as `hatchery
    /// render --scale` does; render at the designed size times it. Raises RenderError for a
    /// value that is not a positive number up to 64.
    #[getter]
    fn pixel_scale(&self, py: Python<'_>) -> f64 {
        self.lock(py).pixel_scale
    }

    #[setter]
    fn set_pixel_scale(&self, py: Python<'_>, scale: f64) -> PyResult<()> {
        if !(scale.is_finite() && scale > 0.0 && scale <= 64.0) {
            return Err(RenderError::new_err(format!(
                "pixel_scale must be a positive number up to 64, got {scale}"
            )));
        }
        self.lock(py).pixel_scale = scale;
        Ok(())
    }

    /// The graph's one-line description.
    #[getter]
    fn description(&self, py: Python<'_>) -> String {
        self.lock(py).graph().description().to_owned()
    }

    /// Node ids in execution (topological) order.
    fn node_ids(&self, py: Python<'_>) -> Vec<String> {
        let inner = self.lock(py);
        inner
            .graph()
            .topological_order()
            .into_iter()
            .map(String::from)
            .collect()
    }

    /// A node's kind. Raises GraphError for an unknown node.
    fn kind(&self, py: Python<'_>, node: &str) -> PyResult<String> {
        let inner = self.lock(py);
        inner
            .graph()
            .node(node)
            .map(|n| n.kind.clone())
            .ok_or_else(|| GraphError::new_err(format!("no node `{node}` in the graph")))
    }

    /// A node's kind as `hatchery.nodes()` lists it (a custom shader's own ports included).
    fn schema<'py>(&self, py: Python<'py>, node: &str) -> PyResult<Bound<'py, PyDict>> {
        let inner = self.lock(py);
        let instance = inner
            .graph()
            .node(node)
            .ok_or_else(|| GraphError::new_err(format!("no node `{node}` in the graph")))?;
        let schema = instance.schema(inner.registry()).expect("validated kind");
        crate::catalogue::schema_dict(py, schema)
    }

    /// The graph's declared inputs: dicts `{name, type, doc, to: [(node, param)], default}`.
    fn inputs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let inner = self.lock(py);
        let list = PyList::empty(py);
        for input in inner.graph().inputs() {
            let d = PyDict::new(py);
            d.set_item("name", &input.name)?;
            d.set_item("type", input.kind.to_string())?;
            d.set_item("doc", &input.doc)?;
            d.set_item("to", &input.to)?;
            d.set_item("default", &input.default)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Gives input `name` a file (as `--input name=path`). Raises InputError.
    fn set_input_path(&self, py: Python<'_>, name: &str, path: PathBuf) -> PyResult<()> {
        self.detached(py, |inner| {
            let session = inner.session(None)?;
            session
                .set_input(name, &path)
                .map_err(|e| InputError::new_err(e.to_string()))
        })
    }

    /// Gives input `name` a volume: a flat buffer (i fastest) of uint8/int8/uint16/int16/
    /// float32 voxels, `dims` (i, j, k) and an optional 4×4 voxel → world affine (RAS+ mm).
    /// Raises InputError.
    #[pyo3(signature = (name, voxels, dims, affine=None))]
    fn set_input_volume(
        &self,
        py: Python<'_>,
        name: &str,
        voxels: &Bound<'_, PyAny>,
        dims: [u32; 3],
        affine: Option<[[f64; 4]; 4]>,
    ) -> PyResult<()> {
        let data = crate::inputs::volume(voxels, dims, affine)
            .map_err(|e| InputError::new_err(format!("input `{name}`: {e}")))?;
        self.give(py, name, InputData::Volume(Arc::new(data)))
    }

    /// Gives input `name` a label map: a flat uint16 id buffer (i fastest), `dims`, an optional
    /// affine and optional names {id: name}. Raises InputError.
    #[pyo3(signature = (name, ids, dims, affine=None, names=None))]
    fn set_input_labels(
        &self,
        py: Python<'_>,
        name: &str,
        ids: PyReadonlyArray1<'_, u16>,
        dims: [u32; 3],
        affine: Option<[[f64; 4]; 4]>,
        names: Option<BTreeMap<i64, String>>,
    ) -> PyResult<()> {
        let data = crate::inputs::labels(&ids, dims, affine, names)
            .map_err(|e| InputError::new_err(format!("input `{name}`: {e}")))?;
        self.give(py, name, InputData::Labels(Arc::new(data)))
    }

    /// Gives input `name` a mesh: flat float32 positions (world mm), uint32 triangle indices,
    /// optional float32 normals. Raises InputError.
    #[pyo3(signature = (name, vertices, faces, normals=None))]
    fn set_input_mesh(
        &self,
        py: Python<'_>,
        name: &str,
        vertices: PyReadonlyArray1<'_, f32>,
        faces: PyReadonlyArray1<'_, u32>,
        normals: Option<PyReadonlyArray1<'_, f32>>,
    ) -> PyResult<()> {
        let data = crate::inputs::mesh(&vertices, &faces, normals.as_ref())
            .map_err(|e| InputError::new_err(format!("input `{name}`: {e}")))?;
        self.give(py, name, InputData::Mesh(Arc::new(data)))
    }

    /// Gives a `names` input an id → name table. Raises InputError.
    fn set_input_names(
        &self,
        py: Python<'_>,
        name: &str,
        names: BTreeMap<i64, String>,
    ) -> PyResult<()> {
        let table = crate::inputs::name_table(names)
            .map_err(|e| InputError::new_err(format!("input `{name}`: {e}")))?;
        self.give(py, name, InputData::Names(Arc::new(table)))
    }

    /// Sets `node.param` from a Python value, parsed as `--set node.param=value` is.
    /// Raises ParamError (unknown node or parameter, a value it cannot take).
    fn set(
        &self,
        py: Python<'_>,
        node: &str,
        param: &str,
        value: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let text = crate::params::to_text(value, &format!("node `{node}`, parameter `{param}`"))?;
        let mut inner = self.lock(py);
        inner
            .set_text(node, param, &text)
            .map_err(ParamError::new_err)
    }

    /// A parameter's value (its default when the file does not set it). Raises ParamError.
    fn get<'py>(&self, py: Python<'py>, node: &str, param: &str) -> PyResult<Bound<'py, PyAny>> {
        let inner = self.lock(py);
        let instance = inner
            .graph()
            .node(node)
            .ok_or_else(|| ParamError::new_err(format!("no node `{node}` in the graph")))?;
        match instance.params.get(param) {
            Some(v) => crate::params::to_python(py, v),
            None => {
                let schema = instance.schema(inner.registry()).expect("validated kind");
                let names: Vec<_> = schema.params.iter().map(|p| p.name).collect();
                Err(ParamError::new_err(format!(
                    "node `{node}` ({}) has no parameter `{param}` (its parameters are: {})",
                    instance.kind,
                    names.join(", ")
                )))
            }
        }
    }

    /// Every parameter of a node with its value: {name: value}. Raises ParamError.
    fn params<'py>(&self, py: Python<'py>, node: &str) -> PyResult<Bound<'py, PyDict>> {
        let inner = self.lock(py);
        let instance = inner
            .graph()
            .node(node)
            .ok_or_else(|| ParamError::new_err(format!("no node `{node}` in the graph")))?;
        let d = PyDict::new(py);
        for (name, value) in instance.params.values() {
            d.set_item(name, crate::params::to_python(py, value)?)?;
        }
        Ok(d)
    }

    /// Renders the picture (the node and port given, else what the one SaveImage writes) at
    /// `size` (w, h) and returns `(rgba8 bytes, width, height)`, the pixels SaveImage writes.
    /// Writes no file. Raises GraphError (what to render), RenderError, InputError.
    #[pyo3(signature = (size=None, node=None, port=None))]
    fn render_rgba8(
        &self,
        py: Python<'_>,
        size: Option<(u32, u32)>,
        node: Option<String>,
        port: Option<String>,
    ) -> PyResult<(Py<PyAny>, u32, u32)> {
        let (pixels, w, h) = self.detached(py, |inner| -> PyResult<_> {
            let start = std::time::Instant::now();
            let (node, port) = inner
                .session(size)?
                .picture_port(node.as_deref(), port.as_deref())
                .map_err(render_error)?;
            let value = output_after_run(inner, &node, &port, size)?;
            let session = inner.session(None)?;
            let picture = hatchery_nodes::export::to_rgba8(&value, &session.ctx.gpu)
                .map_err(|e| RenderError::new_err(format!("{node}.{port}: {e}")))?;
            let (w, h) = picture.dimensions();
            inner.last_seconds = start.elapsed().as_secs_f64();
            Ok((picture.into_raw(), w, h))
        })?;
        Ok((PyArray1::from_vec(py, pixels).into_any().unbind(), w, h))
    }

    /// The data on `node.port` after running what it needs, as `--dump node.port=x.npy`
    /// writes it (a float32 array). A mesh gives `{vertices, normals, faces}`, a label map
    /// `{ids (k, j, i) uint16, names}`, annotations `{text, object, table (N × 7)}`. Raises GraphError, RenderError, InputError.
    #[pyo3(signature = (node, port, size=None))]
    fn output<'py>(
        &self,
        py: Python<'py>,
        node: &str,
        port: &str,
        size: Option<(u32, u32)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let value = self.detached(py, |inner| output_after_run(inner, node, port, size))?;
        match &value {
            Value::Mesh(m) => {
                let d = PyDict::new(py);
                let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
                let n = m.data.positions.len();
                d.set_item(
                    "vertices",
                    PyArray1::from_vec(py, flat(&m.data.positions)).reshape([n, 3])?,
                )?;
                d.set_item(
                    "normals",
                    PyArray1::from_vec(py, flat(&m.data.normals)).reshape([n, 3])?,
                )?;
                let t = m.data.indices.len() / 3;
                d.set_item(
                    "faces",
                    PyArray1::from_slice(py, &m.data.indices).reshape([t, 3])?,
                )?;
                Ok(d.into_any())
            }
            Value::Labels(l) => {
                let d = PyDict::new(py);
                let [x, y, z] = l.data.dims.map(|v| v as usize);
                d.set_item(
                    "ids",
                    PyArray1::from_slice(py, &l.data.ids).reshape([z, y, x])?,
                )?;
                d.set_item("names", &l.data.objects)?;
                Ok(d.into_any())
            }
            Value::Annotations(a) => {
                // The labels' texts and objects, with --dump's N × 7 table beside them.
                let d = PyDict::new(py);
                let texts: Vec<&str> = a.anchors.iter().map(|x| x.text.as_str()).collect();
                let objects: Vec<u16> = a.anchors.iter().map(|x| x.object).collect();
                d.set_item("text", texts)?;
                d.set_item("object", objects)?;
                let array = self.detached(py, |inner| -> PyResult<_> {
                    let session = inner.session(None)?;
                    hatchery_nodes::export::to_array(&value, &session.ctx.gpu)
                        .map_err(|e| RenderError::new_err(format!("{node}.{port}: {e}")))
                })?;
                d.set_item(
                    "table",
                    PyArray1::from_vec(py, array.data).reshape(array.shape)?,
                )?;
                Ok(d.into_any())
            }
            _ => {
                let array = self.detached(py, |inner| -> PyResult<_> {
                    let session = inner.session(None)?;
                    hatchery_nodes::export::to_array(&value, &session.ctx.gpu)
                        .map_err(|e| RenderError::new_err(format!("{node}.{port}: {e}")))
                })?;
                Ok(PyArray1::from_vec(py, array.data)
                    .reshape(array.shape)?
                    .into_any())
            }
        }
    }

    /// Runs every SaveImage and SaveSvg node (writing their files, as `hatchery render`
    /// does) and returns the paths written. Raises RenderError, InputError.
    #[pyo3(signature = (size=None))]
    fn run(&self, py: Python<'_>, size: Option<(u32, u32)>) -> PyResult<Vec<PathBuf>> {
        self.detached(py, |inner| {
            let mut sinks = inner.sinks("SaveImage");
            sinks.extend(inner.sinks("SaveSvg"));
            if sinks.is_empty() {
                return Err(GraphError::new_err(
                    "the graph has no SaveImage or SaveSvg node: nothing to write",
                ));
            }
            let targets: Vec<&str> = sinks.iter().map(String::as_str).collect();
            inner.run(&targets, size)?;
            Ok(sinks
                .iter()
                .filter_map(|s| inner.graph().node(s).map(|n| n.params.path("path")))
                .collect())
        })
    }

    /// Writes the SVG figure of the graph's one SaveSvg node to `path` (the node's own path is
    /// left as it was). Raises GraphError (no or several SaveSvg), RenderError, InputError.
    #[pyo3(signature = (path, size=None))]
    fn export_svg(&self, py: Python<'_>, path: PathBuf, size: Option<(u32, u32)>) -> PyResult<()> {
        self.detached(py, |inner| {
            let savers = inner.sinks("SaveSvg");
            let saver = match savers.as_slice() {
                [one] => one.clone(),
                [] => return Err(GraphError::new_err("the graph has no SaveSvg node")),
                many => {
                    return Err(GraphError::new_err(format!(
                        "the graph has {} SaveSvg nodes ({})",
                        many.len(),
                        many.join(", ")
                    )));
                }
            };
            let before = inner
                .graph()
                .node(&saver)
                .map(|n| n.params.text("path").to_owned());
            let abs = std::path::absolute(&path)
                .map_err(|e| GraphError::new_err(format!("{}: {e}", path.display())))?;
            inner
                .set_text(&saver, "path", &abs.to_string_lossy())
                .map_err(GraphError::new_err)?;
            let result = inner.run(&[&saver], size);
            if let Some(before) = before {
                inner
                    .set_text(&saver, "path", &before)
                    .map_err(GraphError::new_err)?;
            }
            result
        })
    }

    /// The nodes that ran in the last render (the others were served from the cache).
    fn last_ran(&self, py: Python<'_>) -> Vec<String> {
        self.lock(py)
            .last
            .as_ref()
            .map(|r| r.executed.clone())
            .unwrap_or_default()
    }

    /// Seconds the last render spent in Rust: the pass and the read-back, without Python's
    /// share (benchmarks compare it with the wall time of `render`).
    fn last_seconds(&self, py: Python<'_>) -> f64 {
        self.lock(py).last_seconds
    }

    /// Warnings of the last render, by node id.
    fn warnings(&self, py: Python<'_>) -> BTreeMap<String, String> {
        match &self.lock(py).state {
            State::Open(s) => s.ctx.warnings().clone(),
            _ => BTreeMap::new(),
        }
    }

    /// Data-relative parameters as the last render resolved them: node → param → text.
    fn resolved(&self, py: Python<'_>) -> BTreeMap<String, BTreeMap<String, String>> {
        match &self.lock(py).state {
            State::Open(s) => s.ctx.resolved().clone(),
            _ => BTreeMap::new(),
        }
    }
}

impl Graph {
    fn give(&self, py: Python<'_>, name: &str, data: InputData) -> PyResult<()> {
        self.detached(py, |inner| {
            inner
                .session(None)?
                .set_input_data(name, data)
                .map_err(|e| InputError::new_err(e.to_string()))
        })
    }
}

/// Runs what `node.port` needs and returns its value. Errors name the node or input.
fn output_after_run(
    inner: &mut Inner,
    node: &str,
    port: &str,
    size: Option<(u32, u32)>,
) -> PyResult<Value> {
    if inner.graph().node(node).is_none() {
        return Err(GraphError::new_err(format!(
            "no node `{node}` in the graph"
        )));
    }
    inner.run(&[node], size)?;
    let session = inner.session(None)?;
    session
        .output(node, port)
        .cloned()
        .map_err(|e| GraphError::new_err(e.to_string()))
}
