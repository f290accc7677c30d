//! The runtime graph: validated, typed, ports by index, in a petgraph graph.

use crate::EditorPos;
use crate::document::{
    EdgeDoc, FORMAT_VERSION, FrameDoc, GraphDocument, GroupDoc, NodeDoc, Source,
};
use crate::error::{ErrorKind, GraphError, GraphErrors};
use crate::ids::check_node_id;
use crate::param::{ParamValue, Params};
use crate::schema::{NodeSchema, SchemaLookup};
use petgraph::Direction;
use petgraph::stable_graph::{NodeIndex, StableDiGraph};
use petgraph::visit::{EdgeRef, IntoEdgeReferences};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;

/// One node of the runtime graph.
#[derive(Clone, Debug)]
pub struct NodeInstance {
    pub id: String,
    pub kind: String,
    /// Every parameter of the kind: the file's values, defaults for the rest.
    pub params: Params,
    /// Parameters written in the file or set since; only these are saved.
    pub explicit: BTreeSet<String>,
    pub editor: Option<EditorPos>,
    /// The group the node belongs to (editor organisation only).
    pub group: Option<String>,
    /// The node's own schema where its kind reads one from a file (`CustomShader`).
    pub own_schema: Option<Arc<NodeSchema>>,
    /// What that file said when the graph was validated (the executor's cache key includes it).
    pub fingerprint: u64,
}

impl NodeInstance {
    /// The schema this node uses: its own, else its kind's.
    pub fn schema<'a>(&'a self, schemas: &'a dyn SchemaLookup) -> Option<&'a NodeSchema> {
        self.own_schema
            .as_deref()
            .or_else(|| schemas.schema(&self.kind))
    }
}

/// An edge between port indices (the file stores names; see [`Graph::to_document`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Wire {
    pub from_port: usize,
    pub to_port: usize,
}

/// A validated graph.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    graph: StableDiGraph<NodeInstance, Wire>,
    ids: BTreeMap<String, NodeIndex>,
    base_dir: Option<Arc<Path>>,
    /// The document's groups and frames, kept for [`Graph::to_document`]; rendering ignores them.
    groups: Vec<GroupDoc>,
    frames: Vec<FrameDoc>,
    description: String,
    /// The declared inputs as written, and the validated ones.
    input_docs: Vec<crate::inputs::InputDoc>,
    inputs: Vec<crate::inputs::GraphInput>,
    /// The declared controls as written, and the validated ones.
    control_docs: Vec<crate::controls::ControlDoc>,
    controls: Vec<crate::controls::Control>,
}

impl Graph {
    /// Loads, parses and validates a graph file. Relative paths in it resolve against its folder.
    pub fn load_file(path: &Path, schemas: &dyn SchemaLookup) -> Result<Graph, GraphErrors> {
        let (doc, source) = GraphDocument::load(path)?;
        Graph::from_document(&doc, &source, schemas, doc.base_dir.as_deref())
    }

    /// Validates a document and builds the runtime graph, reporting every problem found.
    /// Reroute nodes are resolved away first (see [`crate::reroute`]); groups only organise the
    /// editor, so their members are validated and run as plain nodes.
    pub fn from_document(
        doc: &GraphDocument,
        source: &Source,
        schemas: &dyn SchemaLookup,
        base_dir: Option<&Path>,
    ) -> Result<Graph, GraphErrors> {
        let mut errors = Vec::new();
        let base_dir: Option<Arc<Path>> = base_dir.map(Arc::from);
        let mut graph = Graph {
            base_dir: base_dir.clone(),
            groups: doc.groups.clone(),
            frames: doc.frames.clone(),
            description: doc.description.clone(),
            input_docs: doc.inputs.clone(),
            control_docs: doc.controls.clone(),
            ..Default::default()
        };
        graph.inputs = crate::inputs::check(doc, source, schemas, &mut errors);
        graph.controls = crate::controls::check(doc, source, schemas, &mut errors);
        // Version 2 only adds optional sections, so a version 1 document validates as it is.
        if doc.version == 0 || doc.version > FORMAT_VERSION {
            errors.push(source.error(
                None,
                ErrorKind::UnsupportedVersion {
                    found: doc.version,
                    supported: FORMAT_VERSION,
                },
            ));
        }
        crate::organise::check_groups(doc, source, &mut errors);
        let doc = &crate::reroute::flatten(doc, source, &mut errors);
        // Nodes whose kind is unknown: edges touching them are not reported again.
        let mut unusable = BTreeSet::new();

        for node in &doc.nodes {
            let at = source.node_offset(&node.id);
            if let Err(reason) = check_node_id(&node.id) {
                errors.push(source.error(
                    at,
                    ErrorKind::BadNodeId {
                        node: node.id.clone(),
                        reason,
                    },
                ));
            }
            if graph.ids.contains_key(&node.id) {
                // Point at the second occurrence.
                let second = at.and_then(|first| {
                    crate::locate::node_offset(&source.text[first + 1..], &node.id)
                        .map(|o| o + first + 1)
                });
                errors.push(source.error(
                    second.or(at),
                    ErrorKind::DuplicateId {
                        node: node.id.clone(),
                    },
                ));
                continue;
            }
            let Some(kind_schema) = schemas.schema(&node.kind) else {
                errors.push(source.error(
                    at,
                    ErrorKind::UnknownKind {
                        node: node.id.clone(),
                        kind: node.kind.clone(),
                        known: schemas.kinds(),
                    },
                ));
                unusable.insert(node.id.clone());
                continue;
            };
            // A kind that reads its ports from a file: the file's problems are the node's.
            let own = schemas.own_schema(&node.kind, &node.params, base_dir.as_deref());
            if let Some(message) = own.as_ref().and_then(|o| o.error.clone()) {
                errors.push(source.error(
                    at,
                    ErrorKind::NodeDefinition {
                        node: node.id.clone(),
                        message,
                    },
                ));
            }
            let own_schema = own.as_ref().and_then(|o| o.schema.clone());
            let schema = own_schema.as_deref().unwrap_or(kind_schema);
            let mut values: BTreeMap<String, ParamValue> = schema
                .params
                .iter()
                .map(|p| (p.name.to_owned(), p.default.clone()))
                .collect();
            for (name, raw) in &node.params {
                let at = source.param_offset(&node.id, name);
                match schema.param(name) {
                    // A value for a parameter the node's file no longer declares (a renamed
                    // shader uniform): kept in the document, not used — not an error, or an
                    // edit of the shader would break the graph.
                    None if own_schema.is_some() => {}
                    None => errors.push(source.error(
                        at,
                        ErrorKind::UnknownParam {
                            node: node.id.clone(),
                            kind: node.kind.clone(),
                            param: name.clone(),
                            available: schema.params.iter().map(|p| p.name).collect(),
                        },
                    )),
                    Some(spec) => match spec.convert(raw) {
                        Ok(value) => {
                            values.insert(name.clone(), value);
                        }
                        Err(message) => errors.push(source.error(
                            at,
                            ErrorKind::BadParam {
                                node: node.id.clone(),
                                param: name.clone(),
                                message: message.to_string(),
                            },
                        )),
                    },
                }
            }
            let instance = NodeInstance {
                id: node.id.clone(),
                kind: node.kind.clone(),
                params: Params::new(values, base_dir.clone()),
                explicit: node.params.keys().cloned().collect(),
                editor: node.editor,
                group: node.group.clone(),
                own_schema,
                fingerprint: own.map_or(0, |o| o.fingerprint),
            };
            let index = graph.graph.add_node(instance);
            graph.ids.insert(node.id.clone(), index);
        }

        // Edges: endpoints, port names, types.
        let mut into_input: BTreeMap<(String, String), Vec<(String, String)>> = BTreeMap::new();
        // Inputs some edge tried to reach: a broken edge is reported once, not also as "missing".
        let attempted: BTreeSet<&(String, String)> = doc.edges.iter().map(|e| &e.to).collect();
        for edge in &doc.edges {
            let at_to = source.edge_offset(edge, "to");
            let at_from = source.edge_offset(edge, "from");
            let mut ends = Vec::new();
            for (side, (node, port), at) in [("from", &edge.from, at_from), ("to", &edge.to, at_to)]
            {
                if unusable.contains(node) {
                    continue;
                }
                let Some(&index) = graph.ids.get(node) else {
                    errors.push(source.error(
                        at,
                        ErrorKind::UnknownNode {
                            missing: node.clone(),
                            edge_to: edge.to.clone(),
                        },
                    ));
                    continue;
                };
                let kind = graph.graph[index].kind.clone();
                let schema = graph.graph[index]
                    .schema(schemas)
                    .expect("kind checked above");
                let output = side == "from";
                let ports = if output {
                    &schema.outputs
                } else {
                    &schema.inputs
                };
                match ports.iter().position(|p| p.name == port) {
                    Some(i) => ends.push((index, i, ports[i].ty)),
                    None => errors.push(source.error(
                        at,
                        ErrorKind::UnknownPort {
                            node: node.clone(),
                            kind,
                            port: port.clone(),
                            output,
                            available: ports.iter().map(|p| p.name).collect(),
                        },
                    )),
                }
            }
            let [(from, from_port, from_ty), (to, to_port, to_ty)] = ends[..] else {
                continue;
            };
            if from_ty != to_ty {
                errors.push(source.error(
                    at_to,
                    ErrorKind::TypeMismatch {
                        from: edge.from.clone(),
                        from_ty,
                        to: edge.to.clone(),
                        to_ty,
                    },
                ));
                continue;
            }
            into_input
                .entry(edge.to.clone())
                .or_default()
                .push(edge.from.clone());
            graph.graph.add_edge(from, to, Wire { from_port, to_port });
        }
        for ((node, port), sources) in into_input {
            if sources.len() > 1 {
                let second = EdgeDoc {
                    from: sources[1].clone(),
                    to: (node.clone(), port.clone()),
                };
                errors.push(source.error(
                    source.edge_offset(&second, "to"),
                    ErrorKind::MultipleInputs {
                        node,
                        port,
                        sources,
                    },
                ));
            }
        }

        // Required inputs.
        for index in graph.graph.node_indices() {
            let node = &graph.graph[index];
            let schema = node.schema(schemas).expect("kind checked above");
            let connected: BTreeSet<usize> = graph
                .graph
                .edges_directed(index, Direction::Incoming)
                .map(|e| e.weight().to_port)
                .collect();
            for (i, port) in schema.inputs.iter().enumerate() {
                let tried = attempted.contains(&(node.id.clone(), port.name.to_owned()));
                if port.required && !connected.contains(&i) && !tried {
                    errors.push(source.error(
                        source.node_offset(&node.id),
                        ErrorKind::MissingInput {
                            node: node.id.clone(),
                            port: port.name.to_owned(),
                            ty: port.ty,
                        },
                    ));
                }
            }
        }

        // Cycles: report each strongly connected component with more than one node (or a self-loop).
        for component in petgraph::algo::tarjan_scc(&graph.graph) {
            let self_loop =
                component.len() == 1 && graph.graph.contains_edge(component[0], component[0]);
            if component.len() > 1 || self_loop {
                let mut nodes: Vec<String> = component
                    .iter()
                    .map(|&i| graph.graph[i].id.clone())
                    .collect();
                nodes.sort();
                errors
                    .push(source.error(source.node_offset(&nodes[0]), ErrorKind::Cycle { nodes }));
            }
        }

        // Say which group a node is in: the editor shows groups collapsed.
        for e in &mut errors {
            e.group = e.node().and_then(|n| doc.node(n)?.group.clone());
        }
        if errors.is_empty() {
            Ok(graph)
        } else {
            Err(GraphErrors(errors))
        }
    }

    /// The stored model of this graph (ports by name, explicit parameters only). Reroutes were
    /// resolved away on loading, so their edges come back as direct ones.
    pub fn to_document(&self, schemas: &dyn SchemaLookup) -> GraphDocument {
        let mut nodes: Vec<NodeDoc> = self
            .graph
            .node_weights()
            .map(|n| NodeDoc {
                id: n.id.clone(),
                kind: n.kind.clone(),
                params: n
                    .explicit
                    .iter()
                    .filter_map(|name| n.params.get(name).map(|v| (name.clone(), v.to_ron())))
                    .collect(),
                editor: n.editor,
                group: n.group.clone(),
            })
            .collect();
        nodes.sort_by(|a, b| a.id.cmp(&b.id));
        let mut edges: Vec<EdgeDoc> = self
            .graph
            .edge_references()
            .map(|e| {
                let (from, to) = (&self.graph[e.source()], &self.graph[e.target()]);
                let from_port =
                    from.schema(schemas).expect("validated").outputs[e.weight().from_port].name;
                let to_port =
                    to.schema(schemas).expect("validated").inputs[e.weight().to_port].name;
                EdgeDoc {
                    from: (from.id.clone(), from_port.into()),
                    to: (to.id.clone(), to_port.into()),
                }
            })
            .collect();
        edges.sort();
        GraphDocument {
            version: FORMAT_VERSION,
            description: self.description.clone(),
            inputs: self.input_docs.clone(),
            controls: self.control_docs.clone(),
            nodes,
            edges,
            groups: self.groups.clone(),
            frames: self.frames.clone(),
            base_dir: self.base_dir.as_deref().map(Path::to_path_buf),
        }
    }

    pub fn base_dir(&self) -> Option<&Path> {
        self.base_dir.as_deref()
    }

    /// The graph's one-line description (empty when the file has none).
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The declared inputs (see [`crate::inputs`]), in file order.
    pub fn inputs(&self) -> &[crate::inputs::GraphInput] {
        &self.inputs
    }

    /// The declared controls (see [`crate::controls`]), in file order.
    pub fn controls(&self) -> &[crate::controls::Control] {
        &self.controls
    }

    /// The input named `name`, or an error that lists the graph's inputs.
    pub fn input(&self, name: &str) -> Result<&crate::inputs::GraphInput, crate::EditError> {
        self.inputs.iter().find(|i| i.name == name).ok_or_else(|| {
            crate::EditError::NotFound(crate::inputs::unknown_input(
                self.inputs.iter().map(|i| i.name.as_str()),
                name,
            ))
        })
    }

    pub fn node(&self, id: &str) -> Option<&NodeInstance> {
        self.ids.get(id).map(|&i| &self.graph[i])
    }

    pub fn node_ids(&self) -> impl Iterator<Item = &str> {
        self.ids.keys().map(String::as_str)
    }

    pub fn nodes(&self) -> impl Iterator<Item = &NodeInstance> {
        self.ids.values().map(|&i| &self.graph[i])
    }

    /// Sets one parameter, checking it against the kind's schema.
    pub fn set_param(
        &mut self,
        schemas: &dyn SchemaLookup,
        node: &str,
        param: &str,
        value: ParamValue,
    ) -> Result<(), GraphError> {
        let index = *self.ids.get(node).ok_or_else(|| {
            GraphError::new(ErrorKind::UnknownNode {
                missing: node.into(),
                edge_to: (node.into(), param.into()),
            })
        })?;
        let instance = &mut self.graph[index];
        // The kind's own parameters of a node with a schema of its own name the file its ports
        // come from: changing one needs the whole graph validated again.
        let kind_param = schemas
            .schema(&instance.kind)
            .is_some_and(|k| k.param(param).is_some());
        if instance.own_schema.is_some() && kind_param {
            return Err(GraphError::new(ErrorKind::BadParam {
                node: node.into(),
                param: param.into(),
                message: "it decides the node's ports; change it in the graph file or the editor"
                    .into(),
            }));
        }
        let own = instance.own_schema.clone();
        let schema = match &own {
            Some(own) => own.as_ref(),
            None => schemas.schema(&instance.kind).expect("validated"),
        };
        let spec = schema.param(param).ok_or_else(|| {
            GraphError::new(ErrorKind::UnknownParam {
                node: node.into(),
                kind: instance.kind.clone(),
                param: param.into(),
                available: schema.params.iter().map(|p| p.name).collect(),
            })
        })?;
        spec.check(&value).map_err(|message| {
            GraphError::new(ErrorKind::BadParam {
                node: node.into(),
                param: param.into(),
                message: message.to_string(),
            })
        })?;
        instance.params.set(param, value);
        instance.explicit.insert(param.to_owned());
        Ok(())
    }

    /// This graph with every parameter marked [`crate::ParamSpec::pixels`] multiplied by
    /// `scale` (integers rounded, at least 1 where they were): what the nodes of a render at
    /// `scale` times the designed size read. Relative values are left as they are.
    pub fn with_pixel_scale(&self, schemas: &dyn SchemaLookup, scale: f64) -> Graph {
        let mut scaled = self.clone();
        for instance in scaled.graph.node_weights_mut() {
            let own = instance.own_schema.clone();
            let Some(schema) = own.as_deref().or_else(|| schemas.schema(&instance.kind)) else {
                continue;
            };
            for spec in schema.params.iter().filter(|p| p.pixels) {
                let value = match instance.params.get(spec.name) {
                    Some(ParamValue::Float(v)) => ParamValue::Float(v * scale),
                    Some(&ParamValue::Int(v)) => {
                        let s = (v as f64 * scale).round() as i64;
                        ParamValue::Int(if v >= 1 { s.max(1) } else { s })
                    }
                    _ => continue,
                };
                instance.params.set(spec.name, value);
            }
        }
        scaled
    }

    /// Node ids in an order where every node comes after its inputs.
    pub fn topological_order(&self) -> Vec<&str> {
        // Validation refused cycles, so toposort succeeds.
        petgraph::algo::toposort(&self.graph, None)
            .map(|order| {
                order
                    .into_iter()
                    .map(|i| self.graph[i].id.as_str())
                    .collect()
            })
            .unwrap_or_default()
    }

    /// For each input port of a node (by index), the (node id, output port index) feeding it.
    pub fn input_sources(&self, id: &str) -> BTreeMap<usize, (&str, usize)> {
        let Some(&index) = self.ids.get(id) else {
            return BTreeMap::new();
        };
        self.graph
            .edges_directed(index, Direction::Incoming)
            .map(|e| {
                (
                    e.weight().to_port,
                    (self.graph[e.source()].id.as_str(), e.weight().from_port),
                )
            })
            .collect()
    }

    /// Whether any edge leaves node `id`.
    pub fn has_consumers(&self, id: &str) -> bool {
        self.ids.get(id).is_some_and(|&i| {
            self.graph
                .edges_directed(i, Direction::Outgoing)
                .next()
                .is_some()
        })
    }
}
