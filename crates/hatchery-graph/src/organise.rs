//! Organising big graphs: node groups and frames, as edits on the stored model.
//!
//! A group is a named set of nodes (`nodes[].group` names it; `groups` declares it and where the
//! editor draws it). The editor shows a group collapsed, as one node whose ports are its
//! members' ports that are not connected inside the group ([`exposed_ports`]); wires to those
//! ports are ordinary edges to the members, so rendering needs nothing for groups. Groups do not
//! nest. A frame is a labelled box behind nodes; dragging it moves the nodes inside it.

use crate::document::{EditorPos, FrameDoc, GraphDocument, GroupDoc, Source};
use crate::error::{ErrorKind, GraphError};
use crate::graph::check_node_id;
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

/// Groups nodes `ids` (all on the top level) into a new group placed at their top-left; returns
/// the group's id (`group_N`).
pub fn group_nodes(doc: &mut GraphDocument, ids: &[String]) -> Result<String, String> {
    if ids.is_empty() {
        return Err("select the nodes to group first".into());
    }
    for id in ids {
        if doc.group(id).is_some() {
            return Err(format!("`{id}` is a group: groups do not nest"));
        }
        match doc.node(id) {
            None => return Err(format!("no node `{id}` in the graph")),
            Some(n) if n.group.is_some() => {
                return Err(format!("`{id}` is already in a group: groups do not nest"));
            }
            Some(_) => {}
        }
    }
    let gid = (1..)
        .map(|n| format!("group_{n}"))
        .find(|g| !id_taken(doc, g))
        .expect("unbounded");
    let chosen: BTreeSet<&String> = ids.iter().collect();
    let mut corner: Option<EditorPos> = None;
    for n in doc.nodes.iter_mut().filter(|n| chosen.contains(&n.id)) {
        n.group = Some(gid.clone());
        if let Some(p) = n.editor {
            let c = corner.get_or_insert(p);
            c.x = c.x.min(p.x);
            c.y = c.y.min(p.y);
        }
    }
    doc.groups.push(GroupDoc {
        id: gid.clone(),
        editor: corner,
    });
    Ok(gid)
}

/// Dissolves group `group`: its members (returned) and frames go back to the top level.
pub fn ungroup(doc: &mut GraphDocument, group: &str) -> Result<Vec<String>, String> {
    let index = doc
        .groups
        .iter()
        .position(|g| g.id == group)
        .ok_or_else(|| format!("no group `{group}` in the graph"))?;
    doc.groups.remove(index);
    let mut freed = Vec::new();
    for n in doc.nodes.iter_mut() {
        if n.group.as_deref() == Some(group) {
            n.group = None;
            freed.push(n.id.clone());
        }
    }
    for f in doc.frames.iter_mut() {
        if f.group.as_deref() == Some(group) {
            f.group = None;
        }
    }
    Ok(freed)
}

/// Deletes group `group` with its members, their edges and its frames.
pub fn remove_group(doc: &mut GraphDocument, group: &str) -> Result<(), String> {
    for id in ungroup(doc, group)? {
        crate::edit::remove_node(doc, &id);
    }
    Ok(())
}

/// Moves a group's collapsed node in the editor; false if there is no such group.
pub fn move_group(doc: &mut GraphDocument, group: &str, to: EditorPos) -> bool {
    match doc.groups.iter_mut().find(|g| g.id == group) {
        Some(g) => {
            g.editor = Some(to);
            true
        }
        None => false,
    }
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

/// Adds a frame (`Frame N`) covering `min`..`max` in the given group level; returns its index.
pub fn add_frame(
    doc: &mut GraphDocument,
    min: EditorPos,
    max: EditorPos,
    group: Option<&str>,
) -> usize {
    let n = doc.frames.len();
    let label = (1..)
        .map(|i| format!("Frame {i}"))
        .find(|l| doc.frames.iter().all(|f| &f.label != l))
        .expect("unbounded");
    doc.frames.push(FrameDoc {
        label,
        x: min.x,
        y: min.y,
        w: (max.x - min.x).max(1.0),
        h: (max.y - min.y).max(1.0),
        color: FRAME_COLORS[n % FRAME_COLORS.len()],
        group: group.map(str::to_owned),
    });
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(text: &str) -> GraphDocument {
        GraphDocument::parse(text, None).unwrap().0
    }

    const CHAIN: &str = r#"(version: 2, nodes: [
        (id: "a", kind: "K", editor: Some((x: 50.0, y: 10.0))),
        (id: "b", kind: "K", editor: Some((x: 20.0, y: 40.0))),
        (id: "c", kind: "K")],
        edges: [(from: ("a", "o"), to: ("b", "i")), (from: ("b", "o"), to: ("c", "i"))])"#;

    #[test]
    fn grouping_places_the_group_at_the_members_corner_and_ungrouping_restores() {
        let mut d = doc(CHAIN);
        let before = d.clone();
        let g = group_nodes(&mut d, &["a".into(), "b".into()]).unwrap();
        assert_eq!(g, "group_1");
        assert_eq!(members(&d, &g), ["a", "b"]);
        assert_eq!(
            d.group(&g).unwrap().editor,
            Some(EditorPos { x: 20.0, y: 10.0 })
        );
        let err = group_nodes(&mut d, &["a".into(), "c".into()]).unwrap_err();
        assert!(err.contains("do not nest"), "{err}");
        let err = group_nodes(&mut d, std::slice::from_ref(&g)).unwrap_err();
        assert!(err.contains("do not nest"), "{err}");
        assert_eq!(ungroup(&mut d, &g).unwrap(), ["a", "b"]);
        assert_eq!(d, before);
        assert!(ungroup(&mut d, &g).is_err());
    }

    #[test]
    fn removing_a_group_removes_its_members_and_their_edges() {
        let mut d = doc(CHAIN);
        let g = group_nodes(&mut d, &["b".into()]).unwrap();
        remove_group(&mut d, &g).unwrap();
        assert_eq!(d.nodes.len(), 2);
        assert!(d.edges.is_empty() && d.groups.is_empty());
    }

    #[test]
    fn frames_get_fresh_labels_and_cycle_colours() {
        let mut d = doc(CHAIN);
        let p = |x, y| EditorPos { x, y };
        assert_eq!(add_frame(&mut d, p(0.0, 0.0), p(10.0, 20.0), None), 0);
        assert_eq!(add_frame(&mut d, p(0.0, 0.0), p(-5.0, 20.0), Some("g")), 1);
        assert_eq!(d.frames[0].label, "Frame 1");
        assert_eq!(d.frames[1].label, "Frame 2");
        assert_eq!(d.frames[1].w, 1.0, "never negative");
        assert_ne!(d.frames[0].color, d.frames[1].color);
        assert_eq!(d.frames[1].group.as_deref(), Some("g"));
    }
}
