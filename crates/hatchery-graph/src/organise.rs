//! Organising big graphs: node groups and frames, as edits on the stored model.
//!
//! A group is a named set of nodes (`nodes[].group` names it; `groups` declares it and where the
//! editor draws it). The editor shows a group collapsed, as one node whose ports are its
//! members' ports that are not connected inside the group ([`exposed_ports`]); wires to those
//! ports are ordinary edges to the members, so rendering needs nothing for groups. Groups do not
//! nest. A frame is a labelled box behind nodes; dragging it moves the nodes inside it.

use crate::document::{GraphDocument, Source};
use crate::error::{ErrorKind, GraphError};
use crate::ids::check_node_id;
use crate::port::PortType;
use crate::reroute::{self, REROUTE};
use crate::schema::SchemaLookup;
use std::collections::BTreeSet;

/// One port of a node as the editor shows it; `ty` is `None` for a reroute that carries nothing
/// yet (it takes any type) or a port of an unknown kind.
#[derive(Clone, Debug, PartialEq)]
pub struct PortInfo {
    /// The node that really has the port (a member, for a group's port).
    pub node: String,
    pub port: String,
    pub ty: Option<PortType>,
    pub required: bool,
    pub doc: String,
}

/// The input (or output) ports of node `id`: its kind's, or a reroute's single port.
pub fn node_ports(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    id: &str,
    output: bool,
) -> Vec<PortInfo> {
    let Some(node) = doc.node(id) else {
        return vec![];
    };
    if node.kind == REROUTE {
        return vec![PortInfo {
            node: id.into(),
            port: (if output { reroute::OUT } else { reroute::IN }).into(),
            ty: reroute::reroute_type(doc, schemas, id),
            required: false,
            doc: "a waypoint: passes on what it is given".into(),
        }];
    }
    let Some(schema) = crate::schema::node_schema(schemas, doc, node) else {
        return vec![];
    };
    let ports = if output {
        &schema.outputs
    } else {
        &schema.inputs
    };
    ports
        .iter()
        .map(|p| PortInfo {
            node: id.into(),
            port: p.name.into(),
            ty: Some(p.ty),
            required: p.required,
            doc: p.doc.into(),
        })
        .collect()
}

/// The ids of group `group`'s members, sorted.
pub fn members<'a>(doc: &'a GraphDocument, group: &str) -> Vec<&'a str> {
    let mut ids: Vec<&str> = doc
        .nodes
        .iter()
        .filter(|n| n.group.as_deref() == Some(group))
        .map(|n| n.id.as_str())
        .collect();
    ids.sort_unstable();
    ids
}

/// The ports a collapsed group shows, members in id order: inputs not fed from inside the group;
/// outputs not consumed inside it, or also consumed outside it (so every wire crossing the
/// group's border has a port to end at).
pub fn exposed_ports(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    group: &str,
    output: bool,
) -> Vec<PortInfo> {
    let inside: BTreeSet<&str> = members(doc, group).into_iter().collect();
    let mut out = Vec::new();
    for &member in &inside {
        for p in node_ports(doc, schemas, member, output) {
            let end = (member.to_owned(), p.port.clone());
            let exposed = if output {
                let consumers: Vec<&str> = doc
                    .edges
                    .iter()
                    .filter(|e| e.from == end)
                    .map(|e| e.to.0.as_str())
                    .collect();
                consumers.iter().all(|c| !inside.contains(c))
                    || consumers.iter().any(|c| !inside.contains(c))
            } else {
                !doc.edges
                    .iter()
                    .any(|e| e.to == end && inside.contains(e.from.0.as_str()))
            };
            if exposed {
                out.push(p);
            }
        }
    }
    out
}

/// Whether `id` is taken by a node or a group.
pub fn id_taken(doc: &GraphDocument, id: &str) -> bool {
    doc.node(id).is_some() || doc.group(id).is_some()
}

/// Checks what validation needs of groups: valid, unique ids, and every `group` a node names
/// is declared.
pub fn check_groups(doc: &GraphDocument, source: &Source, errors: &mut Vec<GraphError>) {
    let mut seen = BTreeSet::new();
    for g in &doc.groups {
        let at = source.node_offset(&g.id);
        if let Err(reason) = check_node_id(&g.id) {
            let node = g.id.clone();
            errors.push(source.error(at, ErrorKind::BadNodeId { node, reason }));
        }
        if !seen.insert(g.id.as_str()) || doc.node(&g.id).is_some() {
            // Point at the second occurrence, as for nodes.
            let second = at.and_then(|first| {
                crate::locate::node_offset(&source.text[first + 1..], &g.id).map(|o| o + first + 1)
            });
            let node = g.id.clone();
            errors.push(source.error(second.or(at), ErrorKind::DuplicateId { node }));
        }
    }
    for n in &doc.nodes {
        if let Some(group) = &n.group
            && doc.group(group).is_none()
        {
            errors.push(source.error(
                source.node_offset(&n.id),
                ErrorKind::UnknownGroup {
                    node: n.id.clone(),
                    group: group.clone(),
                },
            ));
        }
    }
}

/// The frame colours the editor offers, RGBA (translucent so the grid shows through).
pub const FRAME_COLORS: [[f32; 4]; 4] = [
    [0.35, 0.45, 0.65, 0.35],
    [0.35, 0.6, 0.4, 0.35],
    [0.65, 0.45, 0.3, 0.35],
    [0.55, 0.35, 0.6, 0.35],
];
