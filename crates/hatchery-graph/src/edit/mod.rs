//! Editing operations on the stored model, for the node editor.
//!
//! Every function works on a [`GraphDocument`], not on the validated [`crate::Graph`], so that a
//! graph with errors can still be opened, edited and saved. Each either changes the document
//! and succeeds, or refuses with a one-line reason and leaves the document as it was.

use crate::document::{
    EdgeDoc, EditorPos, FORMAT_VERSION, FrameDoc, GraphDocument, GroupDoc, NodeDoc,
};
use crate::error::EditError;
use crate::ids::check_node_id;
use crate::organise::{FRAME_COLORS, id_taken};
use crate::param::ParamValue;
use crate::port::PortType;
use crate::reroute;
use crate::schema::{SchemaLookup, SchemaRef, node_schema};
use std::collections::{BTreeMap, BTreeSet};

/// `ShadedSurface` → `shaded_surface`, `TransferFunction1D` → `transfer_function1_d`.
pub fn snake_case(kind: &str) -> String {
    let mut out = String::new();
    for (i, c) in kind.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
            out.push(c);
        }
    }
    if out.is_empty() { "node".into() } else { out }
}

/// The first `base_N` (N ≥ 1) that no node or group of `doc` and no id in `taken` uses.
pub fn fresh_id(doc: &GraphDocument, base: &str, taken: &BTreeSet<String>) -> String {
    let used = |id: &str| taken.contains(id) || id_taken(doc, id);
    (1..)
        .map(|n| format!("{base}_{n}"))
        .find(|id| !used(id))
        .expect("unbounded")
}

fn node<'a>(doc: &'a GraphDocument, id: &str) -> Result<&'a NodeDoc, EditError> {
    doc.nodes
        .iter()
        .find(|n| n.id == id)
        .ok_or_else(|| EditError::NotFound(format!("no node `{id}` in the graph")))
}

fn schema_of<'a>(
    doc: &GraphDocument,
    schemas: &'a dyn SchemaLookup,
    id: &str,
) -> Result<SchemaRef<'a>, EditError> {
    let n = node(doc, id)?;
    node_schema(schemas, doc, n).ok_or_else(|| {
        EditError::NotFound(format!("node `{id}` has the unknown kind `{}`", n.kind))
    })
}

/// Adds a node of `kind` with default parameters at `position`; returns its new id.
pub fn add_node(
    doc: &mut GraphDocument,
    schemas: &dyn SchemaLookup,
    kind: &str,
    position: EditorPos,
) -> Result<String, EditError> {
    let schema = schemas
        .schema(kind)
        .ok_or_else(|| EditError::NotFound(format!("unknown node kind `{kind}`")))?;
    let id = fresh_id(doc, &snake_case(schema.kind), &BTreeSet::new());
    doc.nodes.push(NodeDoc {
        id: id.clone(),
        kind: schema.kind.to_owned(),
        params: BTreeMap::new(),
        editor: Some(position),
        group: None,
    });
    Ok(id)
}

/// Adds a reroute node (see [`crate::reroute`]) at `position`; returns its new id.
pub fn add_reroute(doc: &mut GraphDocument, position: EditorPos) -> String {
    let id = fresh_id(doc, "reroute", &BTreeSet::new());
    doc.nodes.push(NodeDoc {
        id: id.clone(),
        kind: reroute::REROUTE.to_owned(),
        params: BTreeMap::new(),
        editor: Some(position),
        group: None,
    });
    id
}

/// Removes a node, every edge touching it, its controls and the input bindings to it (an input
/// left bound to nothing goes too); returns the node, or `None` if there was none.
pub fn remove_node(doc: &mut GraphDocument, id: &str) -> Option<NodeDoc> {
    let index = doc.nodes.iter().position(|n| n.id == id)?;
    doc.edges.retain(|e| e.from.0 != id && e.to.0 != id);
    doc.controls.retain(|c| c.node != id);
    for input in &mut doc.inputs {
        input.to.retain(|(node, _)| node != id);
    }
    doc.inputs.retain(|i| !i.to.is_empty());
    Some(doc.nodes.remove(index))
}

/// Renames a node, updating the edges, input bindings and controls that name it.
pub fn rename_node(doc: &mut GraphDocument, old: &str, new: &str) -> Result<(), EditError> {
    if old == new {
        return node(doc, old).map(|_| ());
    }
    check_node_id(new)
        .map_err(|r| EditError::Refused(format!("`{new}` is not a valid id: {r}")))?;
    if id_taken(doc, new) {
        return Err(EditError::Refused(format!(
            "a node or group `{new}` already exists"
        )));
    }
    let index = doc
        .nodes
        .iter()
        .position(|n| n.id == old)
        .ok_or_else(|| EditError::NotFound(format!("no node `{old}` in the graph")))?;
    doc.nodes[index].id = new.to_owned();
    let names = doc
        .edges
        .iter_mut()
        .flat_map(|e| [&mut e.from.0, &mut e.to.0])
        .chain(
            doc.inputs
                .iter_mut()
                .flat_map(|i| i.to.iter_mut().map(|(n, _)| n)),
        )
        .chain(doc.controls.iter_mut().map(|c| &mut c.node));
    for name in names {
        if name == old {
            *name = new.to_owned();
        }
    }
    Ok(())
}

/// Sets a parameter after checking its type and range; the document stores `value.to_ron()`.
pub fn set_param(
    doc: &mut GraphDocument,
    schemas: &dyn SchemaLookup,
    node_id: &str,
    name: &str,
    value: ParamValue,
) -> Result<(), EditError> {
    let schema = schema_of(doc, schemas, node_id)?;
    let spec = schema.param(name).ok_or_else(|| {
        EditError::NotFound(format!(
            "node `{node_id}` ({}) has no parameter `{name}`",
            schema.kind
        ))
    })?;
    spec.check(&value).map_err(|source| EditError::Param {
        node: node_id.to_owned(),
        param: name.to_owned(),
        source,
    })?;
    let n = doc
        .nodes
        .iter_mut()
        .find(|n| n.id == node_id)
        .expect("found above");
    n.params.insert(name.to_owned(), value.to_ron());
    Ok(())
}

/// Moves a node (or a group's collapsed node) in the editor; false if there is no such node.
pub fn move_node(doc: &mut GraphDocument, id: &str, position: EditorPos) -> bool {
    match doc.nodes.iter_mut().find(|n| n.id == id) {
        Some(n) => {
            n.editor = Some(position);
            true
        }
        None => move_group(doc, id, position),
    }
}

/// The type of `node.port`, an output when `output` is true.
pub fn port_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    node_id: &str,
    port: &str,
    output: bool,
) -> Result<PortType, EditError> {
    let schema = schema_of(doc, schemas, node_id)?;
    let (ports, side) = if output {
        (&schema.outputs, "output")
    } else {
        (&schema.inputs, "input")
    };
    ports
        .iter()
        .find(|p| p.name == port)
        .map(|p| p.ty)
        .ok_or_else(|| {
            EditError::NotFound(format!(
                "node `{node_id}` ({}) has no {side} port `{port}` (its {side}s are: {})",
                schema.kind,
                ports.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
            ))
        })
}

/// The type at one end of a new wire: a reroute's is what flows through it (`None`: any yet;
/// an input's is what it feeds, since the new wire replaces what fed it).
fn end_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    (node, port): (&str, &str),
    output: bool,
) -> Result<Option<PortType>, EditError> {
    if !reroute::is_reroute(doc, node) {
        return port_type(doc, schemas, node, port, output).map(Some);
    }
    let expected = if output { reroute::OUT } else { reroute::IN };
    if port != expected {
        let side = if output { "output" } else { "input" };
        return Err(EditError::NotFound(format!(
            "node `{node}` (Reroute) has no {side} port `{port}` (its {side}s are: {expected})"
        )));
    }
    Ok(if output {
        reroute::reroute_type(doc, schemas, node)
    } else {
        reroute::downstream_type(doc, schemas, node)
    })
}

/// Whether `to` can be reached from `from` along the document's edges.
fn reaches(doc: &GraphDocument, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from];
    while let Some(n) = stack.pop() {
        if n == to {
            return true;
        }
        if seen.insert(n) {
            stack.extend(
                doc.edges
                    .iter()
                    .filter(|e| e.from.0 == n)
                    .map(|e| e.to.0.as_str()),
            );
        }
    }
    false
}

/// Connects an output to an input. An existing edge into that input is replaced and returned.
/// Refuses (with the reason) unknown nodes or ports, mismatched types and cycles.
pub fn connect(
    doc: &mut GraphDocument,
    schemas: &dyn SchemaLookup,
    from: (&str, &str),
    to: (&str, &str),
) -> Result<Option<EdgeDoc>, EditError> {
    let out_ty = end_type(doc, schemas, from, true)?;
    let in_ty = end_type(doc, schemas, to, false)?;
    if let (Some(out_ty), Some(in_ty)) = (out_ty, in_ty)
        && out_ty != in_ty
    {
        return Err(EditError::TypeMismatch(format!(
            "type mismatch: `{}.{}` gives {out_ty} but `{}.{}` takes {in_ty}",
            from.0, from.1, to.0, to.1
        )));
    }
    if from.0 == to.0 || reaches(doc, to.0, from.0) {
        return Err(EditError::Cycle(format!(
            "connecting `{}.{}` to `{}.{}` would create a cycle",
            from.0, from.1, to.0, to.1
        )));
    }
    let edge = EdgeDoc {
        from: (from.0.to_owned(), from.1.to_owned()),
        to: (to.0.to_owned(), to.1.to_owned()),
    };
    let replaced = doc
        .edges
        .iter()
        .position(|e| e.to == edge.to)
        .map(|i| doc.edges.remove(i));
    // Files with errors may hold several edges into one input: one remains.
    doc.edges.retain(|e| e.to != edge.to);
    doc.edges.push(edge);
    Ok(replaced)
}

/// Removes the edge `from → to`; false if there was none.
pub fn disconnect(doc: &mut GraphDocument, from: (&str, &str), to: (&str, &str)) -> bool {
    let before = doc.edges.len();
    doc.edges.retain(|e| {
        !(e.from.0 == from.0 && e.from.1 == from.1 && e.to.0 == to.0 && e.to.1 == to.1)
    });
    doc.edges.len() != before
}

/// Kinds with an input (`as_input`) or an output of `port_type`, sorted: what a wire dropped on
/// empty canvas may connect to.
pub fn compatible_kinds(
    schemas: &dyn SchemaLookup,
    port_type: PortType,
    as_input: bool,
) -> Vec<&'static str> {
    let mut kinds: Vec<&'static str> = schemas
        .kinds()
        .into_iter()
        .filter(|k| {
            schemas.schema(k).is_some_and(|s| {
                let ports = if as_input { &s.inputs } else { &s.outputs };
                ports.iter().any(|p| p.ty == port_type)
            })
        })
        .collect();
    kinds.sort_unstable();
    kinds
}

/// The RON text of the nodes `ids` and the edges between them (a graph document of its own).
pub fn copy_nodes(doc: &GraphDocument, ids: &[&str]) -> String {
    let chosen: BTreeSet<&str> = ids.iter().copied().collect();
    let sub = GraphDocument {
        version: FORMAT_VERSION,
        nodes: doc
            .nodes
            .iter()
            .filter(|n| chosen.contains(n.id.as_str()))
            .cloned()
            .collect(),
        edges: doc
            .edges
            .iter()
            .filter(|e| chosen.contains(e.from.0.as_str()) && chosen.contains(e.to.0.as_str()))
            .cloned()
            .collect(),
        ..Default::default()
    };
    sub.to_ron_string()
}

/// `name_12` → `name`; ids without a numeric suffix stay as they are.
fn id_base(id: &str) -> &str {
    match id.rsplit_once('_') {
        Some((base, n))
            if !base.is_empty() && !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) =>
        {
            base
        }
        _ => id,
    }
}

/// Pastes text made by [`copy_nodes`], moved by `offset`; ids that clash get fresh ones (edges
/// follow). Returns the ids of the pasted nodes.
pub fn paste_nodes(
    doc: &mut GraphDocument,
    text: &str,
    offset: EditorPos,
) -> Result<Vec<String>, EditError> {
    let (sub, _) = GraphDocument::parse(text, None)
        .map_err(|e| EditError::Refused(format!("cannot paste: {e}")))?;
    let mut renamed = BTreeMap::new();
    let mut taken = BTreeSet::new();
    let mut nodes = Vec::new();
    for mut n in sub.nodes {
        let clash = taken.contains(&n.id) || doc.nodes.iter().any(|m| m.id == n.id);
        let id = if clash {
            fresh_id(doc, id_base(&n.id), &taken)
        } else {
            n.id.clone()
        };
        taken.insert(id.clone());
        renamed.insert(n.id.clone(), id.clone());
        n.id = id;
        // The target may not have the group: pasted nodes land on the top level.
        n.group = None;
        let at = n.editor.unwrap_or(EditorPos { x: 0.0, y: 0.0 });
        n.editor = Some(EditorPos {
            x: at.x + offset.x,
            y: at.y + offset.y,
        });
        nodes.push(n);
    }
    let mut edges = Vec::new();
    for mut e in sub.edges {
        match (renamed.get(&e.from.0), renamed.get(&e.to.0)) {
            (Some(f), Some(t)) => {
                e.from.0 = f.clone();
                e.to.0 = t.clone();
                edges.push(e);
            }
            _ => {
                return Err(EditError::Refused(
                    "cannot paste: an edge names a node that is not pasted".into(),
                ));
            }
        }
    }
    let ids = nodes.iter().map(|n| n.id.clone()).collect();
    doc.nodes.extend(nodes);
    doc.edges.extend(edges);
    Ok(ids)
}

/// Groups nodes `ids` (all on the top level) into a new group placed at their top-left; returns
/// the group's id (`group_N`).
pub fn group_nodes(doc: &mut GraphDocument, ids: &[String]) -> Result<String, EditError> {
    if ids.is_empty() {
        return Err(EditError::Refused("select the nodes to group first".into()));
    }
    for id in ids {
        if doc.group(id).is_some() {
            return Err(EditError::Refused(format!(
                "`{id}` is a group: groups do not nest"
            )));
        }
        match doc.node(id) {
            None => return Err(EditError::NotFound(format!("no node `{id}` in the graph"))),
            Some(n) if n.group.is_some() => {
                return Err(EditError::Refused(format!(
                    "`{id}` is already in a group: groups do not nest"
                )));
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
pub fn ungroup(doc: &mut GraphDocument, group: &str) -> Result<Vec<String>, EditError> {
    let index = doc
        .groups
        .iter()
        .position(|g| g.id == group)
        .ok_or_else(|| EditError::NotFound(format!("no group `{group}` in the graph")))?;
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
pub fn remove_group(doc: &mut GraphDocument, group: &str) -> Result<(), EditError> {
    for id in ungroup(doc, group)? {
        remove_node(doc, &id);
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
mod tests;
