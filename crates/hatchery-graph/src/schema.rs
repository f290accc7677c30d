//! Node schemas: what a node kind takes, gives and is tuned by, declared once next to its code.

use crate::document::{GraphDocument, NodeDoc};
use crate::param::ParamSpec;
use crate::port::PortType;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::ops::Deref;
use std::path::Path;
use std::sync::{Arc, Mutex};

/// One input or output port.
#[derive(Clone, Debug)]
pub struct PortSpec {
    pub name: &'static str,
    pub ty: PortType,
    /// Inputs only: a required input must be connected for the graph to be valid.
    pub required: bool,
    pub doc: &'static str,
}

impl PortSpec {
    pub fn input(name: &'static str, ty: PortType, doc: &'static str) -> Self {
        Self {
            name,
            ty,
            required: true,
            doc,
        }
    }
    pub fn optional(name: &'static str, ty: PortType, doc: &'static str) -> Self {
        Self {
            name,
            ty,
            required: false,
            doc,
        }
    }
    pub fn output(name: &'static str, ty: PortType, doc: &'static str) -> Self {
        Self {
            name,
            ty,
            required: false,
            doc,
        }
    }
}

/// Everything the loader, the executor, the editor and `hatchery nodes` know of a node kind.
#[derive(Clone, Debug)]
pub struct NodeSchema {
    /// Name used in graph files, e.g. `"MarchingCubes"`.
    pub kind: &'static str,
    /// Catalogue section, e.g. "Data", "Geometry", "Rendering", "Output".
    pub category: &'static str,
    /// One paragraph: what the node does, and the paper section it implements.
    pub doc: &'static str,
    pub inputs: Vec<PortSpec>,
    pub outputs: Vec<PortSpec>,
    pub params: Vec<ParamSpec>,
    /// The output depends on the frame size (re-run when the render size changes).
    pub frame_dependent: bool,
    /// The node has an effect outside the graph (writes a file): it always runs and is a target.
    pub sink: bool,
}

impl NodeSchema {
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|p| p.name == name)
    }
    pub fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|p| p.name == name)
    }
    pub fn param(&self, name: &str) -> Option<&ParamSpec> {
        self.params.iter().find(|p| p.name == name)
    }
    pub fn input_names(&self) -> Vec<&'static str> {
        self.inputs.iter().map(|p| p.name).collect()
    }
    pub fn output_names(&self) -> Vec<&'static str> {
        self.outputs.iter().map(|p| p.name).collect()
    }
}

/// Looks up node schemas by kind name; implemented by the executor's registry.
pub trait SchemaLookup {
    fn schema(&self, kind: &str) -> Option<&NodeSchema>;
    fn kinds(&self) -> Vec<&'static str>;
    /// For kinds whose ports and parameters come from a file that a parameter names
    /// (`CustomShader`): the node's own schema, given its parameters as written and the folder
    /// relative paths resolve against. `None` for every other kind.
    fn own_schema(
        &self,
        _kind: &str,
        _params: &BTreeMap<String, ron::Value>,
        _base_dir: Option<&Path>,
    ) -> Option<OwnSchema> {
        None
    }
}

/// A node's own schema, read from a file (a custom shader's declarations).
#[derive(Clone, Debug, Default)]
pub struct OwnSchema {
    /// The ports and parameters the file declares — while the file is broken, those of its
    /// last good version, so that the editor keeps showing the node's wires. `None` when it
    /// was never readable: the kind's schema stands in.
    pub schema: Option<Arc<NodeSchema>>,
    /// Why the file cannot be used now (`file:line:col: message`); the node is invalid while set.
    pub error: Option<String>,
    /// Changes whenever the file's content does: the executor re-runs the node.
    pub fingerprint: u64,
}

/// A schema borrowed from the registry (a kind's) or shared (a node's own).
#[derive(Clone, Debug)]
pub enum SchemaRef<'a> {
    Kind(&'a NodeSchema),
    Own(Arc<NodeSchema>),
}

impl Deref for SchemaRef<'_> {
    type Target = NodeSchema;
    fn deref(&self) -> &NodeSchema {
        match self {
            SchemaRef::Kind(s) => s,
            SchemaRef::Own(s) => s,
        }
    }
}

/// The schema node `node` of `doc` uses: its own where its kind reads one from a file
/// (resolving paths against `doc.base_dir`), else its kind's. `None` for an unknown kind.
pub fn node_schema<'a>(
    schemas: &'a dyn SchemaLookup,
    doc: &GraphDocument,
    node: &NodeDoc,
) -> Option<SchemaRef<'a>> {
    let kind = schemas.schema(&node.kind)?;
    match schemas.own_schema(&node.kind, &node.params, doc.base_dir.as_deref()) {
        Some(OwnSchema {
            schema: Some(own), ..
        }) => Some(SchemaRef::Own(own)),
        _ => Some(SchemaRef::Kind(kind)),
    }
}

/// A `&'static str` equal to `name`. Schemas name ports and parameters with static strings;
/// a schema read from a file (a custom shader's bindings) interns its names here. Each distinct
/// name is stored once for the life of the process, so the memory is bounded by the names a
/// user writes, not by how often files are re-read.
pub fn intern(name: &str) -> &'static str {
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut names = NAMES
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(&known) = names.get(name) {
        return known;
    }
    let leaked: &'static str = Box::leak(name.to_owned().into_boxed_str());
    names.insert(leaked);
    leaked
}

/// An error raised by a node's `execute`, optionally naming the port it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeError {
    pub port: Option<String>,
    pub message: String,
}

impl NodeError {
    /// A node error with `message` (any text or error, shown as it displays).
    pub fn new(message: impl fmt::Display) -> Self {
        Self {
            port: None,
            message: message.to_string(),
        }
    }
    /// A node error about port `port`.
    pub fn at_port(port: &str, message: impl fmt::Display) -> Self {
        Self {
            port: Some(port.to_owned()),
            message: message.to_string(),
        }
    }
}

impl fmt::Display for NodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.port {
            Some(port) => write!(f, "port `{port}`: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for NodeError {}
