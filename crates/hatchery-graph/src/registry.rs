//! What a node kind is ([`Node`]), the context hooks ([`ExecContext`]), a node's inputs
//! ([`NodeInputs`]) and the registry of kinds the executor runs ([`Registry`]).

use crate::fusion::Fuser;
use crate::param::Params;
use crate::schema::{NodeError, NodeSchema, OwnSchema, SchemaLookup};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

/// A node kind's behaviour. `V` is the value type flowing along edges, `C` the context
/// (the GPU) a node runs in.
pub trait Node<V, C>: Send + Sync {
    fn schema(&self) -> NodeSchema;
    /// Turns inputs into one value per output port, in the schema's order.
    fn execute(
        &self,
        ctx: &mut C,
        inputs: &NodeInputs<V>,
        params: &Params,
    ) -> Result<Vec<V>, NodeError>;
    /// Whether each node of this kind reads its ports and parameters from a file
    /// ([`Node::own_schema`]); `schema` then gives only what every such node has.
    fn has_own_schema(&self) -> bool {
        false
    }
    /// The node's own schema, from the kind's parameters (`params` holds only those of
    /// `schema`, as written or defaulted, with the folder paths resolve against).
    fn own_schema(&self, _params: &Params) -> Option<OwnSchema> {
        None
    }
}

/// Hooks the executor calls around each node; the GPU context uses them for timestamps.
pub trait ExecContext {
    /// Anything outside parameters and inputs that frame-dependent nodes read (the frame size).
    fn frame_key(&self) -> u64 {
        0
    }
    /// How many rendered pixels one pixel of the designed figure is: parameters marked
    /// [`crate::ParamSpec::pixels`] are multiplied by it before a node reads them.
    fn pixel_scale(&self) -> f64 {
        1.0
    }
    /// Called at the start of a pass with the steps that will execute, in order (a fused
    /// pass by its last member, the node its time is reported under).
    fn begin_pass(&mut self, _planned: &[&str]) {}
    /// Asked between steps: `true` stops the pass with an error for which
    /// [`crate::ExecError::is_cancelled`] holds; what ran stays cached.
    fn cancelled(&self) -> bool {
        false
    }
    fn begin_node(&mut self, _node: &str) {}
    fn end_node(&mut self, _node: &str) {}
    /// Called at the end of a pass: GPU time per node, where the device could measure it.
    fn finish_pass(&mut self) -> Vec<(String, Duration)> {
        Vec::new()
    }
}

/// A registered node kind: its schema (computed once) and its behaviour.
type Entry<V, C> = (NodeSchema, Box<dyn Node<V, C>>);

/// All node kinds, by name.
pub struct Registry<V, C> {
    pub(crate) kinds: BTreeMap<&'static str, Entry<V, C>>,
    /// Kinds whose nodes have schemas of their own (read from a file).
    own: BTreeSet<&'static str>,
    /// What fuses image-space nodes into one pass, where the context can.
    pub(crate) fuser: Option<Box<dyn Fuser<V, C>>>,
}

impl<V, C> Default for Registry<V, C> {
    fn default() -> Self {
        Self {
            kinds: BTreeMap::new(),
            own: BTreeSet::new(),
            fuser: None,
        }
    }
}

impl<V, C> Registry<V, C> {
    /// Adds a node kind (its schema computed once, here); returns the kind's name.
    pub fn register(&mut self, node: impl Node<V, C> + 'static) -> &'static str {
        let schema = node.schema();
        let kind = schema.kind;
        if node.has_own_schema() {
            self.own.insert(kind);
        }
        self.kinds.insert(kind, (schema, Box::new(node)));
        kind
    }
    /// Sets what fuses pointwise image-space nodes into one pass ([`crate::fusion`]).
    pub fn set_fuser(&mut self, fuser: impl Fuser<V, C> + 'static) {
        self.fuser = Some(Box::new(fuser));
    }
    pub fn node(&self, kind: &str) -> Option<&dyn Node<V, C>> {
        self.kinds.get(kind).map(|(_, n)| n.as_ref())
    }
    pub fn schemas(&self) -> impl Iterator<Item = &NodeSchema> {
        self.kinds.values().map(|(s, _)| s)
    }
}

impl<V, C> SchemaLookup for Registry<V, C> {
    fn schema(&self, kind: &str) -> Option<&NodeSchema> {
        self.kinds.get(kind).map(|(s, _)| s)
    }
    fn kinds(&self) -> Vec<&'static str> {
        self.kinds.keys().copied().collect()
    }
    fn own_schema(
        &self,
        kind: &str,
        raw: &BTreeMap<String, ron::Value>,
        base_dir: Option<&Path>,
    ) -> Option<OwnSchema> {
        if !self.own.contains(kind) {
            return None;
        }
        let (schema, node) = self.kinds.get(kind)?;
        // The kind's parameters (the file's name among them); the file's own are not known yet.
        let values = schema
            .params
            .iter()
            .map(|p| {
                let value = raw.get(p.name).and_then(|r| p.convert(r).ok());
                (
                    p.name.to_owned(),
                    value.unwrap_or_else(|| p.default.clone()),
                )
            })
            .collect();
        node.own_schema(&Params::new(values, base_dir.map(Arc::from)))
    }
}

/// The values on a node's input ports, by the schema's port names.
pub struct NodeInputs<V> {
    names: Vec<&'static str>,
    values: Vec<Option<V>>,
}

impl<V> NodeInputs<V> {
    pub fn new(names: Vec<&'static str>, values: Vec<Option<V>>) -> Self {
        Self { names, values }
    }
    /// An optional input: `None` when nothing is connected.
    pub fn get(&self, name: &str) -> Option<&V> {
        let i = self.names.iter().position(|n| *n == name)?;
        self.values[i].as_ref()
    }
    /// A required input; an error naming the port when it is missing.
    pub fn require(&self, name: &str) -> Result<&V, NodeError> {
        self.get(name)
            .ok_or_else(|| NodeError::at_port(name, "input is not connected"))
    }
}
