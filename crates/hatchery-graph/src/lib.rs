//! The graph model of hatchery.
//!
//! Two models, converted both ways:
//! - [`document::GraphDocument`] is what a `.ron` file says: nodes by id, ports by *name*,
//!   sorted, with the raw parameter values as written. It is stable on disk.
//! - [`graph::Graph`] is the validated runtime graph (petgraph) the [`executor::Executor`] runs:
//!   ports by index, typed parameters. Reordering a node's ports never breaks saved files.
#![forbid(unsafe_code)]
// Load errors carry the file, position and the full node/port context; they are rare and cold,
// so their size is not worth boxing.
#![allow(clippy::result_large_err)]

pub mod atomic;
pub mod controls;
pub mod document;
pub mod edit;
pub mod error;
pub mod executor;
pub mod fusion;
pub mod graph;
pub mod ids;
pub mod input_kind;
pub mod inputs;
pub mod load;
mod locate;
pub mod migrate;
pub mod node_params;
pub mod organise;
pub mod param;
pub mod port;
pub mod rebase;
pub mod registry;
pub mod reroute;
pub mod schema;

pub use document::{
    EdgeDoc, EditorPos, FORMAT_VERSION, FrameDoc, GraphDocument, GroupDoc, NodeDoc,
};
pub use error::{EditError, ErrorKind, GraphError, GraphErrors, ParamError};
pub use executor::{ExecContext, ExecError, Executor, NodeInputs, NodeStats, Registry};
pub use graph::{Graph, NodeInstance};
pub use inputs::{GraphInput, InputDoc, InputKind};
pub use node_params::{DataValue, FilePath, Group, ParamField};
pub use param::{ParamKind, ParamSpec, ParamValue, Params, RelativeValue, Widget};
pub use port::PortType;
pub use schema::{
    NodeError, NodeSchema, OwnSchema, PortSpec, SchemaLookup, SchemaRef, intern, node_schema,
};
