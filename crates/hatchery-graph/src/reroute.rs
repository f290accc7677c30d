//! Reroute nodes: waypoints that tidy long wires. A `Reroute` has one input `in` and one output
//! `out` and takes the type of what flows through it. It is stored in the document like any
//! node (so it keeps its place in the editor) and resolved away before validation: every edge
//! out of a reroute becomes an edge from the output that feeds it, so the executor and the CLI
//! never see one and every node kind works with them unchanged.

use crate::document::{EdgeDoc, GraphDocument, Source};
use crate::error::{ErrorKind, GraphError};
use crate::port::PortType;
use crate::schema::SchemaLookup;
use std::collections::{BTreeMap, BTreeSet};

/// The kind name of reroute nodes.
pub const REROUTE: &str = "Reroute";
/// A reroute's only input.
pub const IN: &str = "in";
/// A reroute's only output.
pub const OUT: &str = "out";

/// Whether node `id` of `doc` is a reroute.
pub fn is_reroute(doc: &GraphDocument, id: &str) -> bool {
    doc.node(id).is_some_and(|n| n.kind == REROUTE)
}

/// The output feeding reroute `id`, through chains of reroutes: `None` when the chain ends
/// unconnected or loops.
pub fn source_of(doc: &GraphDocument, id: &str) -> Option<(String, String)> {
    let mut seen = BTreeSet::new();
    let mut at = id.to_owned();
    loop {
        if !seen.insert(at.clone()) {
            return None;
        }
        let edge = doc.edges.iter().find(|e| e.to.0 == at && e.to.1 == IN)?;
        if !is_reroute(doc, &edge.from.0) {
            return Some(edge.from.clone());
        }
        at = edge.from.0.clone();
    }
}

/// The type of a plain node's port, `None` for unknown nodes, kinds or ports.
fn plain_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    (node, port): (&str, &str),
    output: bool,
) -> Option<PortType> {
    let schema = crate::schema::node_schema(schemas, doc, doc.node(node)?)?;
    let ports = if output {
        &schema.outputs
    } else {
        &schema.inputs
    };
    ports.iter().find(|p| p.name == port).map(|p| p.ty)
}

/// The type of what reroute `id` feeds: the first plain input reached downstream.
pub fn downstream_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    id: &str,
) -> Option<PortType> {
    let mut seen = BTreeSet::new();
    let mut stack = vec![id.to_owned()];
    while let Some(at) = stack.pop() {
        if !seen.insert(at.clone()) {
            continue;
        }
        for e in doc.edges.iter().filter(|e| e.from.0 == at) {
            if is_reroute(doc, &e.to.0) {
                stack.push(e.to.0.clone());
            } else if let Some(ty) = plain_type(doc, schemas, (&e.to.0, &e.to.1), false) {
                return Some(ty);
            }
        }
    }
    None
}

/// The type flowing through reroute `id`: what feeds it, else what it feeds, else `None` (it
/// takes any type).
pub fn reroute_type(doc: &GraphDocument, schemas: &dyn SchemaLookup, id: &str) -> Option<PortType> {
    source_of(doc, id)
        .and_then(|(n, p)| plain_type(doc, schemas, (&n, &p), true))
        .or_else(|| downstream_type(doc, schemas, id))
}

/// The document with its reroutes resolved away (see the module comment). Problems with the
/// reroutes themselves (wrong port names, parameters, two wires into one, a loop of reroutes,
/// bad or duplicate ids) are added to `errors`; a reroute fed by nothing feeds nothing.
pub fn flatten(
    doc: &GraphDocument,
    source: &Source,
    errors: &mut Vec<GraphError>,
) -> GraphDocument {
    let reroutes: BTreeSet<&str> = doc
        .nodes
        .iter()
        .filter(|n| n.kind == REROUTE)
        .map(|n| n.id.as_str())
        .collect();
    if reroutes.is_empty() {
        return doc.clone();
    }
    for n in doc.nodes.iter().filter(|n| n.kind == REROUTE) {
        let at = source.node_offset(&n.id);
        if let Err(reason) = crate::ids::check_node_id(&n.id) {
            let node = n.id.clone();
            errors.push(source.error(at, ErrorKind::BadNodeId { node, reason }));
        }
        if doc.nodes.iter().filter(|m| m.id == n.id).count() > 1 {
            let node = n.id.clone();
            errors.push(source.error(at, ErrorKind::DuplicateId { node }));
        }
        for param in n.params.keys() {
            errors.push(source.error(
                source.param_offset(&n.id, param),
                ErrorKind::UnknownParam {
                    node: n.id.clone(),
                    kind: REROUTE.into(),
                    param: param.clone(),
                    available: vec![],
                },
            ));
        }
    }
    let mut into: BTreeMap<&str, Vec<(String, String)>> = BTreeMap::new();
    for e in &doc.edges {
        for (output, (node, port)) in [(true, &e.from), (false, &e.to)] {
            let expected = if output { OUT } else { IN };
            if reroutes.contains(node.as_str()) && port != expected {
                errors.push(source.error(
                    source.edge_offset(e, if output { "from" } else { "to" }),
                    ErrorKind::UnknownPort {
                        node: node.clone(),
                        kind: REROUTE.into(),
                        port: port.clone(),
                        output,
                        available: vec![expected],
                    },
                ));
            }
        }
        if reroutes.contains(e.to.0.as_str()) {
            into.entry(&e.to.0).or_default().push(e.from.clone());
        }
    }
    for (node, sources) in into.into_iter().filter(|(_, s)| s.len() > 1) {
        errors.push(source.error(
            source.node_offset(node),
            ErrorKind::MultipleInputs {
                node: node.to_owned(),
                port: IN.into(),
                sources,
            },
        ));
    }
    // A loop made only of reroutes never reaches a plain output.
    let mut looped = BTreeSet::new();
    for &r in &reroutes {
        let mut path = vec![r];
        let mut at = r;
        while let Some(e) = doc.edges.iter().find(|e| e.to.0 == at && e.to.1 == IN) {
            if !reroutes.contains(e.from.0.as_str()) {
                break;
            }
            at = e.from.0.as_str();
            if let Some(start) = path.iter().position(|&p| p == at) {
                let mut nodes: Vec<String> = path[start..].iter().map(|s| s.to_string()).collect();
                nodes.sort();
                looped.insert(nodes);
                break;
            }
            path.push(at);
        }
    }
    for nodes in looped {
        errors.push(source.error(source.node_offset(&nodes[0]), ErrorKind::Cycle { nodes }));
    }

    let mut flat = doc.clone();
    flat.nodes.retain(|n| n.kind != REROUTE);
    flat.edges = doc
        .edges
        .iter()
        .filter(|e| !reroutes.contains(e.to.0.as_str()))
        .filter_map(|e| {
            if !reroutes.contains(e.from.0.as_str()) {
                return Some(e.clone());
            }
            source_of(doc, &e.from.0).map(|from| EdgeDoc {
                from,
                to: e.to.clone(),
            })
        })
        .collect();
    flat
}
