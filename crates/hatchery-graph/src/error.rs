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
            Syntax { .. } | UnsupportedVersion { .. } | Io { .. } | BadInput { .. } => None,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ErrorKind {
    Io {
        message: String,
    },
    Syntax {
        message: String,
    },
    UnsupportedVersion {
        found: u32,
        supported: u32,
    },
    DuplicateId {
        node: String,
    },
    BadNodeId {
        node: String,
        reason: String,
    },
    UnknownKind {
        node: String,
        kind: String,
        known: Vec<&'static str>,
    },
    /// An edge refers to a node id that does not exist.
    UnknownNode {
        missing: String,
        edge_to: (String, String),
    },
    UnknownPort {
        node: String,
        kind: String,
        port: String,
        output: bool,
        available: Vec<&'static str>,
    },
    TypeMismatch {
        from: (String, String),
        from_ty: PortType,
        to: (String, String),
        to_ty: PortType,
    },
    Cycle {
        nodes: Vec<String>,
    },
    MultipleInputs {
        node: String,
        port: String,
        sources: Vec<(String, String)>,
    },
    MissingInput {
        node: String,
        port: String,
        ty: PortType,
    },
    UnknownParam {
        node: String,
        kind: String,
        param: String,
        available: Vec<&'static str>,
    },
    BadParam {
        node: String,
        param: String,
        message: String,
    },
    /// A node names a group that the file does not declare.
    UnknownGroup {
        node: String,
        group: String,
    },
    /// A node whose ports come from a file (a custom shader) cannot read or use it; the
    /// message names the file, line and column.
    NodeDefinition {
        node: String,
        message: String,
    },
    /// A graph input (version 3) that is declared wrongly.
    BadInput {
        input: String,
        reason: String,
    },
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use ErrorKind::*;
        match self {
            Io { message } => write!(f, "{message}"),
            Syntax { message } => write!(f, "syntax error: {message}"),
            UnsupportedVersion { found, supported } => write!(
                f,
                "unsupported graph format version {found} (this hatchery reads versions 1 to {supported})"
            ),
            DuplicateId { node } => write!(f, "node `{node}`: duplicate node id"),
            BadNodeId { node, reason } => write!(f, "node `{node}`: invalid node id: {reason}"),
            UnknownKind { node, kind, known } => {
                write!(
                    f,
                    "node `{node}`: unknown node kind `{kind}` (known kinds: {})",
                    list(known)
                )
            }
            UnknownNode { missing, edge_to } => write!(
                f,
                "edge into `{}.{}`: no node with id `{missing}`",
                edge_to.0, edge_to.1
            ),
            UnknownPort {
                node,
                kind,
                port,
                output,
                available,
            } => write!(
                f,
                "node `{node}` ({kind}) has no {} port `{port}` (its {} are: {})",
                if *output { "output" } else { "input" },
                if *output { "outputs" } else { "inputs" },
                list(available)
            ),
            TypeMismatch {
                from,
                from_ty,
                to,
                to_ty,
            } => write!(
                f,
                "edge `{}.{}` -> `{}.{}`: type mismatch: output is {from_ty}, input expects {to_ty}",
                from.0, from.1, to.0, to.1
            ),
            Cycle { nodes } => write!(
                f,
                "cycle through nodes {}",
                nodes
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(" -> ")
            ),
            MultipleInputs {
                node,
                port,
                sources,
            } => write!(
                f,
                "node `{node}`, input `{port}`: {} edges lead into one input ({})",
                sources.len(),
                sources
                    .iter()
                    .map(|(n, p)| format!("`{n}.{p}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            MissingInput { node, port, ty } => {
                write!(
                    f,
                    "node `{node}`: required input `{port}` ({ty}) is not connected"
                )
            }
            UnknownParam {
                node,
                kind,
                param,
                available,
            } => write!(
                f,
                "node `{node}` ({kind}) has no parameter `{param}` (its parameters are: {})",
                list(available)
            ),
            BadParam {
                node,
                param,
                message,
            } => write!(f, "node `{node}`, parameter `{param}`: {message}"),
            UnknownGroup { node, group } => write!(
                f,
                "node `{node}`: no group with id `{group}` (declare it in `groups`)"
            ),
            NodeDefinition { node, message } => write!(f, "node `{node}`: {message}"),
            BadInput { input, reason } => write!(f, "input `{input}`: {reason}"),
        }
    }
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
