//! Node schemas: what a node kind takes, gives and is tuned by, declared once next to its code.

use crate::param::ParamSpec;
use crate::port::PortType;
use std::fmt;

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
}

/// An error raised by a node's `execute`, optionally naming the port it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeError {
    pub port: Option<String>,
    pub message: String,
}

impl NodeError {
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            port: None,
            message: message.into(),
        }
    }
    pub fn at_port(port: &str, message: impl Into<String>) -> Self {
        Self {
            port: Some(port.to_owned()),
            message: message.into(),
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
