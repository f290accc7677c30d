//! Errors of loading and validating a graph: each names the file, the line and column where it
//! could be found, and the node, port or parameter concerned.

use crate::port::PortType;
use std::fmt;
use std::path::PathBuf;

#[derive(Clone, Debug, PartialEq)]
pub struct GraphError {
    /// The graph file, when the graph came from one.
    pub file: Option<PathBuf>,
    /// 1-based line and column in that file, when known.
    pub position: Option<(usize, usize)>,
    pub kind: ErrorKind,
    /// The group of the node concerned, if it is in one (said after the message).
    pub group: Option<String>,
}

impl GraphError {
    pub fn new(kind: ErrorKind) -> Self {
        Self {
            file: None,
            position: None,
            kind,
            group: None,
        }
    }

    /// The node this error concerns, if any (the editor puts a badge on it).
    pub fn node(&self) -> Option<&str> {
        use ErrorKind::*;
        match &self.kind {
            DuplicateId { node }
            | UnknownKind { node, .. }
            | UnknownPort { node, .. }
            | MissingInput { node, .. }
            | MultipleInputs { node, .. }
            | UnknownParam { node, .. }
            | BadParam { node, .. }
            | BadNodeId { node, .. }
            | UnknownGroup { node, .. }
            | NodeDefinition { node, .. } => Some(node),
            UnknownNode { edge_to, .. } => Some(&edge_to.0),
            TypeMismatch { to, .. } => Some(&to.0),
            Cycle { nodes } => nodes.first().map(String::as_str),
            BadControl { control, .. } => control.split('.').next(),
            Syntax { .. } | UnsupportedVersion { .. } | Io { .. } | BadInput { .. } => None,
        }
    }
}

/// What is wrong with a graph; the messages are the text users see (one line each).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    #[error("{message}")]
    Io { message: String },
    #[error("syntax error: {message}")]
    Syntax { message: String },
    #[error(
        "unsupported graph format version {found} (this hatchery reads versions 1 to {supported})"
    )]
    UnsupportedVersion { found: u32, supported: u32 },
    #[error("node `{node}`: duplicate node id")]
    DuplicateId { node: String },
    #[error("node `{node}`: invalid node id: {reason}")]
    BadNodeId { node: String, reason: String },
    #[error(
        "node `{node}`: unknown node kind `{kind}` (known kinds: {})",
        list(known)
    )]
    UnknownKind {
        node: String,
        kind: String,
        known: Vec<&'static str>,
    },
    /// An edge refers to a node id that does not exist.
    #[error("edge into `{}.{}`: no node with id `{missing}`", edge_to.0, edge_to.1)]
    UnknownNode {
        missing: String,
        edge_to: (String, String),
    },
    #[error(
        "node `{node}` ({kind}) has no {} port `{port}` (its {} are: {})",
        side(*output), side(*output).to_owned() + "s", list(available)
    )]
    UnknownPort {
        node: String,
        kind: String,
        port: String,
        output: bool,
        available: Vec<&'static str>,
    },
    #[error(
        "edge `{}.{}` -> `{}.{}`: type mismatch: output is {from_ty}, input expects {to_ty}",
        from.0, from.1, to.0, to.1
    )]
    TypeMismatch {
        from: (String, String),
        from_ty: PortType,
        to: (String, String),
        to_ty: PortType,
    },
    #[error("cycle through nodes {}", joined(nodes.iter().map(|n| format!("`{n}`")), " -> "))]
    Cycle { nodes: Vec<String> },
    #[error(
        "node `{node}`, input `{port}`: {} edges lead into one input ({})",
        sources.len(),
        joined(sources.iter().map(|(n, p)| format!("`{n}.{p}`")), ", ")
    )]
    MultipleInputs {
        node: String,
        port: String,
        sources: Vec<(String, String)>,
    },
    #[error("node `{node}`: required input `{port}` ({ty}) is not connected")]
    MissingInput {
        node: String,
        port: String,
        ty: PortType,
    },
    #[error(
        "node `{node}` ({kind}) has no parameter `{param}` (its parameters are: {})",
        list(available)
    )]
    UnknownParam {
        node: String,
        kind: String,
        param: String,
        available: Vec<&'static str>,
    },
    #[error("node `{node}`, parameter `{param}`: {message}")]
    BadParam {
        node: String,
        param: String,
        message: String,
    },
    /// A node names a group that the file does not declare.
    #[error("node `{node}`: no group with id `{group}` (declare it in `groups`)")]
    UnknownGroup { node: String, group: String },
    /// A node whose ports come from a file (a custom shader) cannot read or use it; the
    /// message names the file, line and column.
    #[error("node `{node}`: {message}")]
    NodeDefinition { node: String, message: String },
    /// A graph input (version 3) that is declared wrongly.
    #[error("input `{input}`: {reason}")]
    BadInput { input: String, reason: String },
    /// A control (version 3) that names no suitable parameter.
    #[error("control `{control}`: {reason}")]
    BadControl { control: String, reason: String },
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

fn side(output: bool) -> &'static str {
    if output { "output" } else { "input" }
}

fn joined(items: impl Iterator<Item = String>, separator: &str) -> String {
    items.collect::<Vec<_>>().join(separator)
}

/// A value refused for a parameter: wrong type, out of range, or text that does not parse
/// ([`crate::ParamSpec::convert`], [`crate::ParamSpec::check`], [`crate::RelativeValue::parse`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct ParamError(pub String);

/// Why an edit of a graph document ([`crate::edit`], [`crate::inputs::set_in_document`]) was
/// refused; the document is left as it was. Messages are one line.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EditError {
    /// A node, group, port, kind or input the edit names does not exist.
    #[error("{0}")]
    NotFound(String),
    /// A wire between ports of different types.
    #[error("{0}")]
    TypeMismatch(String),
    /// A wire that would close a cycle.
    #[error("{0}")]
    Cycle(String),
    /// A value refused for a parameter.
    #[error("node `{node}`, parameter `{param}`: {source}")]
    Param {
        node: String,
        param: String,
        source: ParamError,
    },
    /// Anything else the document's rules refuse: an id taken or invalid, nested groups, text
    /// that is not a graph when pasting, …
    #[error("{0}")]
    Refused(String),
}

impl fmt::Display for GraphError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.position) {
            (Some(file), Some((line, col))) => write!(f, "{}:{line}:{col}: ", file.display())?,
            (Some(file), None) => write!(f, "{}: ", file.display())?,
            (None, Some((line, col))) => write!(f, "{line}:{col}: ")?,
            (None, None) => {}
        }
        write!(f, "{}", self.kind)?;
        match &self.group {
            Some(group) => write!(f, " (in group `{group}`)"),
            None => Ok(()),
        }
    }
}

impl std::error::Error for GraphError {}

/// All errors found in one graph (validation reports every problem, not only the first).
#[derive(Clone, Debug, PartialEq)]
pub struct GraphErrors(pub Vec<GraphError>);

impl GraphErrors {
    pub fn first(&self) -> &GraphError {
        &self.0[0]
    }
}

impl From<GraphError> for GraphErrors {
    fn from(e: GraphError) -> Self {
        GraphErrors(vec![e])
    }
}

impl fmt::Display for GraphErrors {
    /// One line: the first error, and how many more there are.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0.as_slice() {
            [] => write!(f, "no errors"),
            [one] => write!(f, "{one}"),
            [first, rest @ ..] => write!(f, "{first} (and {} more)", rest.len()),
        }
    }
}

impl std::error::Error for GraphErrors {}

impl From<String> for ParamError {
    fn from(message: String) -> Self {
        ParamError(message)
    }
}

impl From<&str> for ParamError {
    fn from(message: &str) -> Self {
        ParamError(message.to_owned())
    }
}
