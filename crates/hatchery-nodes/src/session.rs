//! A graph with its executor and GPU context: what the command line, the editor and the tests run.

use crate::{Ctx, Registry, RenderContext, Value, registry};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::executor::PassReport;
use hatchery_graph::{ExecError, Executor, Graph, GraphErrors, ParamValue};
use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    #[error(transparent)]
    Graph(#[from] GraphErrors),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Exec(#[from] ExecError),
    #[error("{0}")]
    Other(String),
}

pub struct Session {
    pub registry: Registry,
    pub graph: Graph,
    pub executor: Executor<Value>,
    pub ctx: Ctx,
}

impl Session {
    /// Loads and validates a graph file and opens the GPU.
    pub fn open(path: &Path, width: u32, height: u32) -> Result<Session, SessionError> {
        let registry = registry();
        let graph = Graph::load_file(path, &registry)?;
        Session::with_graph(registry, graph, width, height)
    }

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
            return Err(SessionError::Other(format!(
                "GPU error during the pass: {first}"
            )));
        }
        Ok(report)
    }

    /// Gives graph input `name` (issue 25) the file `path`: checks that the input exists and
    /// that the file can be read and is of the input's kind, then sets every parameter bound to
    /// it. A relative `path` is taken as it is (callers resolve it against their own folder).
    /// Errors are one line naming the input.
    pub fn set_input(&mut self, name: &str, path: &Path) -> Result<(), SessionError> {
        let input = self.graph.input(name).map_err(SessionError::Other)?.clone();
        crate::graph_inputs::check_input_file(name, input.kind, path)
            .map_err(SessionError::Other)?;
        let text = path.to_string_lossy();
        for (node, param) in &input.to {
            self.set_param_text(node, param, &text)?;
        }
        Ok(())
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
        let instance = self
            .graph
            .node(node)
            .ok_or_else(|| SessionError::Other(format!("no node `{node}` in the graph")))?;
        let schema = instance.schema(&self.registry).expect("validated kind");
        let spec = schema.param(param).ok_or_else(|| {
            let names: Vec<_> = schema.params.iter().map(|p| p.name).collect();
            SessionError::Other(format!(
                "node `{node}` ({}) has no parameter `{param}` (its parameters are: {})",
                instance.kind,
                names.join(", ")
            ))
        })?;
        spec.parse_cli(text)
            .map_err(|m| SessionError::Other(format!("node `{node}`, parameter `{param}`: {m}")))
    }

    /// The value on an output port from the last pass (run the node first).
    pub fn output(&self, node: &str, port: &str) -> Result<&Value, SessionError> {
        let instance = self
            .graph
            .node(node)
            .ok_or_else(|| SessionError::Other(format!("no node `{node}` in the graph")))?;
        let schema = instance.schema(&self.registry).expect("validated kind");
        let index = schema.output_index(port).ok_or_else(|| {
            SessionError::Other(format!(
                "node `{node}` ({}) has no output port `{port}` (its outputs are: {})",
                instance.kind,
                schema.output_names().join(", ")
            ))
        })?;
        self.executor.output(node, index).ok_or_else(|| {
            let fused = &self.executor.stats().get(node).map(|s| &s.fused_with);
            SessionError::Other(match fused {
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
        let picture = crate::export::to_rgba8(&value, &self.ctx.gpu)
            .map_err(|e| SessionError::Other(format!("{node}.{port}: {e}")))?;
        picture
            .save_with_format(path, image::ImageFormat::Png)
            .map_err(|e| SessionError::Other(format!("cannot write {}: {e}", path.display())))
    }

    /// Runs just what `node.port` needs and returns its value.
    pub fn evaluate(&mut self, node: &str, port: &str) -> Result<Value, SessionError> {
        if self.graph.node(node).is_none() {
            return Err(SessionError::Other(format!(
                "no node `{node}` in the graph"
            )));
        }
        self.run(&[node])?;
        self.output(node, port).cloned()
    }
}
