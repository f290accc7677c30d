//! A graph with its executor and GPU context: what the command line, the editor and the tests run.

use crate::export::ExportError;
use crate::memory_inputs::InputData;
#[cfg(not(target_arch = "wasm32"))]
use crate::registry;
use crate::{Ctx, Registry, RenderContext, Value};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::GraphDocument;
use hatchery_graph::executor::PassReport;
use hatchery_graph::{ExecError, Executor, Graph, GraphErrors, ParamError, ParamValue};
use std::collections::BTreeMap;
use std::path::Path;

/// Keys of input `name`'s in-memory data start with this.
fn memory_key_prefix(name: &str) -> String {
    format!("{}{name}#", crate::memory_inputs::MEMORY_PREFIX)
}

/// What can go wrong in a [`Session`]; each kind a caller may act on is its own variant.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// The graph cannot be read or is invalid.
    #[error(transparent)]
    Graph(#[from] GraphErrors),
    /// The GPU cannot be opened, or reported an error during a pass.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A node failed while running.
    #[error(transparent)]
    Exec(#[from] ExecError),
    /// The caller named a node or port the graph does not have.
    #[error("{0}")]
    NotFound(String),
    /// A port that holds no value: its node has not run, or ran in a fused pass that did not
    /// write it.
    #[error("{0}")]
    NoOutput(String),
    /// A graph input that cannot take what was given (no such input, a file or data of another
    /// kind, an unreadable file).
    #[error("{0}")]
    Input(String),
    /// A value a parameter cannot take.
    #[error("node `{node}`, parameter `{param}`: {source}")]
    Param {
        node: String,
        param: String,
        source: ParamError,
    },
    /// A value that cannot be read back or has no picture.
    #[error("{port}: {source}")]
    Export { port: String, source: ExportError },
    /// A file that cannot be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        path: std::path::PathBuf,
        source: std::io::Error,
    },
}

/// A graph opened for rendering: its node registry, the validated graph, the executor that
/// caches outputs between runs and the GPU context. What the CLI, the editor, the Python
/// package and library users run (see also `examples/session.rs`).
///
/// ```
/// use hatchery_nodes::{Session, SessionError, export};
///
/// // A procedural torus (no data files), rendered at 64×48 pixels.
/// let graph = concat!(env!("CARGO_MANIFEST_DIR"), "/../../graphs/shaded_surface.ron");
/// let mut session = Session::open(graph.as_ref(), 64, 48)?;
/// session.set_param_text("camera", "azimuth", "60")?;
/// // A value the parameter cannot take is refused, naming it.
/// let refused = session.set_param_text("camera", "azimuth", "sixty").unwrap_err();
/// assert!(refused.to_string().contains("azimuth"), "{refused}");
/// // Runs what `shaded.image` needs and reads it back: [height, width, RGBA].
/// let image = session.evaluate("shaded", "image")?;
/// let array = export::to_array(&image, &session.ctx.gpu).unwrap();
/// assert_eq!(array.shape, [48, 64, 4]);
/// assert!(array.data.iter().any(|&v| v < 0.9), "the torus is drawn");
/// # Ok::<(), SessionError>(())
/// ```
pub struct Session {
    pub registry: Registry,
    pub graph: Graph,
    pub executor: Executor<Value>,
    pub ctx: Ctx,
    /// What the parameters bound to in-memory inputs held before (node, param → value; `None`:
    /// the default), written back by [`Session::document`].
    memory_bound: BTreeMap<(String, String), Option<ParamValue>>,
    /// Counts in-memory data given, so each gets a key of its own.
    memory_count: u64,
}

impl Session {
    /// Loads and validates a graph file and opens the GPU.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn open(path: &Path, width: u32, height: u32) -> Result<Session, SessionError> {
        let registry = registry();
        let graph = Graph::load_file(path, &registry)?;
        Session::with_graph(registry, graph, width, height)
    }

    #[cfg(not(target_arch = "wasm32"))]
    pub fn with_graph(
        registry: Registry,
        graph: Graph,
        width: u32,
        height: u32,
    ) -> Result<Session, SessionError> {
        Session::with_gpu(registry, graph, GpuContext::new()?, width, height)
    }

    /// A session rendering on a device opened elsewhere (the editor's window device).
    pub fn with_gpu(
        registry: Registry,
        graph: Graph,
        gpu: GpuContext,
        width: u32,
        height: u32,
    ) -> Result<Session, SessionError> {
        let ctx = RenderContext::new(gpu, width, height)?;
        Ok(Session {
            registry,
            graph,
            executor: Executor::new(),
            ctx,
            memory_bound: BTreeMap::new(),
            memory_count: 0,
        })
    }

    /// Runs the graph for `targets` (all sinks when empty).
    pub fn run(&mut self, targets: &[&str]) -> Result<PassReport, SessionError> {
        let report = self
            .executor
            .run(&self.graph, &self.registry, &mut self.ctx, targets)?;
        let errors = self.ctx.gpu.take_uncaptured_errors();
        if let Some(first) = errors.first() {
            // What the pass cached may be garbage: the next pass starts afresh (and reports the
            // error again rather than serving those outputs).
            self.executor.clear();
            return Err(SessionError::Gpu(GpuError::Validation {
                what: "GPU error during the pass".into(),
                message: first.clone(),
            }));
        }
        Ok(report)
    }

    /// The declared input `name`, or [`SessionError::Input`] listing the graph's inputs.
    fn input(&self, name: &str) -> Result<hatchery_graph::GraphInput, SessionError> {
        self.graph
            .input(name)
            .cloned()
            .map_err(|e| SessionError::Input(e.to_string()))
    }

    /// Gives graph input `name` (issue 25) the file `path`: checks that the input exists and
    /// that the file can be read and is of the input's kind, then sets every parameter bound to
    /// it. A relative `path` is taken as it is (callers resolve it against their own folder).
    /// Errors are one line naming the input.
    pub fn set_input(&mut self, name: &str, path: &Path) -> Result<(), SessionError> {
        let input = self.input(name)?;
        crate::graph_inputs::check_input_file(name, input.kind, path)
            .map_err(|e| SessionError::Input(e.to_string()))?;
        let text = path.to_string_lossy();
        for (node, param) in &input.to {
            self.set_param_text(node, param, &text)?;
            self.memory_bound.remove(&(node.clone(), param.clone()));
        }
        self.ctx.drop_memory(&memory_key_prefix(name));
        Ok(())
    }

    /// Gives graph input `name` data held in memory (numpy arrays from Python): every parameter
    /// bound to it names the data by a new key (see [`crate::memory_inputs`]), so what reads it
    /// runs again. Errors, one line naming the input: no such input, data of another kind.
    pub fn set_input_data(&mut self, name: &str, data: InputData) -> Result<(), SessionError> {
        let input = self.input(name)?;
        if data.kind() != input.kind {
            return Err(SessionError::Input(format!(
                "input `{name}` takes a {}, not a {}",
                input.kind,
                data.kind()
            )));
        }
        self.memory_count += 1;
        let prefix = memory_key_prefix(name);
        let key = format!("{prefix}{}", self.memory_count);
        for (node, param) in &input.to {
            let before = self.explicit_param(node, param);
            self.graph
                .set_param(&self.registry, node, param, ParamValue::Path(key.clone()))
                .map_err(|e| SessionError::Graph(e.into()))?;
            self.memory_bound
                .entry((node.clone(), param.clone()))
                .or_insert(before);
        }
        self.ctx.put_memory(key, data, &prefix);
        Ok(())
    }

    /// A node's parameter as the file gave it (`None`: not written, the default).
    fn explicit_param(&self, node: &str, param: &str) -> Option<ParamValue> {
        let n = self.graph.node(node)?;
        n.explicit
            .contains(param)
            .then(|| n.params.get(param).cloned())
            .flatten()
    }

    /// The graph as a document to save: parameters bound to in-memory inputs hold what they
    /// held before the data was given (a key is meaningless outside this session).
    pub fn document(&self) -> GraphDocument {
        let mut doc = self.graph.to_document(&self.registry);
        for ((node, param), before) in &self.memory_bound {
            if let Some(n) = doc.nodes.iter_mut().find(|n| &n.id == node) {
                match before {
                    Some(value) => {
                        n.params.insert(param.clone(), value.to_ron());
                    }
                    None => {
                        n.params.remove(param);
                    }
                }
            }
        }
        doc
    }

    /// The graph inputs given data in memory (their names), for messages on save.
    pub fn memory_inputs(&self) -> Vec<String> {
        self.graph
            .inputs()
            .iter()
            .filter(|i| i.to.iter().any(|b| self.memory_bound.contains_key(b)))
            .map(|i| i.name.clone())
            .collect()
    }

    /// The graph input a node's parameter is bound to, if any (error messages name it).
    pub fn input_of(&self, node: &str) -> Option<&hatchery_graph::GraphInput> {
        self.graph
            .inputs()
            .iter()
            .find(|i| i.to.iter().any(|(n, _)| n == node))
    }

    /// Sets `node.param` from command-line text.
    pub fn set_param_text(
        &mut self,
        node: &str,
        param: &str,
        text: &str,
    ) -> Result<(), SessionError> {
        let value = self.parse_param(node, param, text)?;
        self.graph
            .set_param(&self.registry, node, param, value)
            .map_err(|e| SessionError::Graph(e.into()))
    }

    fn parse_param(&self, node: &str, param: &str, text: &str) -> Result<ParamValue, SessionError> {
        parse_param(&self.graph, &self.registry, node, param, text)
    }

    /// The value on an output port from the last pass (run the node first).
    pub fn output(&self, node: &str, port: &str) -> Result<&Value, SessionError> {
        let instance = self
            .graph
            .node(node)
            .ok_or_else(|| SessionError::NotFound(format!("no node `{node}` in the graph")))?;
        let schema = instance.schema(&self.registry).expect("validated kind");
        let index = schema.output_index(port).ok_or_else(|| {
            SessionError::NotFound(format!(
                "node `{node}` ({}) has no output port `{port}` (its outputs are: {})",
                instance.kind,
                schema.output_names().join(", ")
            ))
        })?;
        self.executor.output(node, index).ok_or_else(|| {
            let fused = &self.executor.stats().get(node).map(|s| &s.fused_with);
            SessionError::NoOutput(match fused {
                Some(pass) if !pass.is_empty() => format!(
                    "node `{node}` ran in a fused pass ({}) that did not write `{port}`: nothing \
                     outside the pass read it; run `{node}` as a target",
                    pass.join(", ")
                ),
                _ => format!("node `{node}` has not run yet"),
            })
        })
    }

    /// Renders `node.port` and writes it as a PNG picture (what `hatchery render --dump
    /// node.port=file.png` and the editor's *Export image* write; for an Image port the same
    /// pixels a SaveImage node would write). Errors: an unknown node or port, a failed node, a
    /// value without a picture, an unwritable file.
    pub fn export_png(&mut self, node: &str, port: &str, path: &Path) -> Result<(), SessionError> {
        let value = self.evaluate(node, port)?;
        let picture = crate::export::to_rgba8(&value, &self.ctx.gpu).map_err(|source| {
            SessionError::Export {
                port: format!("{node}.{port}"),
                source,
            }
        })?;
        crate::export::write_png(&picture, path).map_err(|source| SessionError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// The node and port a picture of the graph shows: `node`'s `port` (its first output when
    /// not given), else what the graph's one SaveImage node writes. Errors (one line): an
    /// unknown node or output, no or several SaveImage nodes, a SaveImage with nothing
    /// connected.
    pub fn picture_port(
        &self,
        node: Option<&str>,
        port: Option<&str>,
    ) -> Result<(String, String), SessionError> {
        let graph = &self.graph;
        if let Some(node) = node {
            let instance = graph
                .node(node)
                .ok_or_else(|| SessionError::NotFound(format!("no node `{node}` in the graph")))?;
            let schema = instance.schema(&self.registry).expect("validated kind");
            let port = match port {
                Some(p) if schema.output_index(p).is_some() => p.to_owned(),
                Some(p) => {
                    return Err(SessionError::NotFound(format!(
                        "node `{node}` ({}) has no output port `{p}` (its outputs are: {})",
                        instance.kind,
                        schema.output_names().join(", ")
                    )));
                }
                None => schema
                    .outputs
                    .first()
                    .ok_or_else(|| {
                        SessionError::NotFound(format!(
                            "node `{node}` ({}) has no outputs",
                            instance.kind
                        ))
                    })?
                    .name
                    .to_owned(),
            };
            return Ok((node.to_owned(), port));
        }
        let savers: Vec<&str> = graph
            .nodes()
            .filter(|n| n.kind == "SaveImage")
            .map(|n| n.id.as_str())
            .collect();
        let saver = match savers.as_slice() {
            [one] => *one,
            [] => {
                return Err(SessionError::NotFound(
                    "the graph has no SaveImage node: name what to render, e.g. \
                     render(node=\"composite\")"
                        .into(),
                ));
            }
            many => {
                return Err(SessionError::NotFound(format!(
                    "the graph has {} SaveImage nodes ({}): name one with render(node=...)",
                    many.len(),
                    many.join(", ")
                )));
            }
        };
        let sources = graph.input_sources(saver);
        let (source, index) = sources.get(&0).ok_or_else(|| {
            SessionError::NotFound(format!("SaveImage `{saver}` has nothing connected"))
        })?;
        let schema = graph
            .node(source)
            .and_then(|n| n.schema(&self.registry))
            .expect("validated edge");
        Ok(((*source).to_owned(), schema.outputs[*index].name.to_owned()))
    }

    /// Renders the picture [`Self::picture_port`] names and returns it as straight-alpha RGBA8,
    /// the pixels a SaveImage node writes, writing no file (the Python package's `render`, the
    /// batch items).
    pub fn render_picture(
        &mut self,
        node: Option<&str>,
        port: Option<&str>,
    ) -> Result<image::RgbaImage, SessionError> {
        let (node, port) = self.picture_port(node, port)?;
        let value = self.evaluate(&node, &port)?;
        crate::export::to_rgba8(&value, &self.ctx.gpu).map_err(|source| SessionError::Export {
            port: format!("{node}.{port}"),
            source,
        })
    }

    /// Runs just what `node.port` needs and returns its value.
    pub fn evaluate(&mut self, node: &str, port: &str) -> Result<Value, SessionError> {
        if self.graph.node(node).is_none() {
            return Err(SessionError::NotFound(format!(
                "no node `{node}` in the graph"
            )));
        }
        self.run(&[node])?;
        self.output(node, port).cloned()
    }
}

/// Parses `text` as `--set node.param=text` does. Errors, one line: no such node, no such
/// parameter (listing the node's), a value the parameter cannot take.
pub fn parse_param(
    graph: &Graph,
    registry: &Registry,
    node: &str,
    param: &str,
    text: &str,
) -> Result<ParamValue, SessionError> {
    let instance = graph
        .node(node)
        .ok_or_else(|| SessionError::NotFound(format!("no node `{node}` in the graph")))?;
    let schema = instance.schema(registry).expect("validated kind");
    let spec = schema.param(param).ok_or_else(|| {
        let names: Vec<_> = schema.params.iter().map(|p| p.name).collect();
        SessionError::NotFound(format!(
            "node `{node}` ({}) has no parameter `{param}` (its parameters are: {})",
            instance.kind,
            names.join(", ")
        ))
    })?;
    spec.parse_cli(text).map_err(|source| SessionError::Param {
        node: node.to_owned(),
        param: param.to_owned(),
        source,
    })
}
