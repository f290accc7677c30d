//! Editing operations on the stored model, for the node editor.
//!
//! Every function works on a [`GraphDocument`], not on the validated [`crate::Graph`], so that a
//! graph with errors can still be opened, edited and saved. Each either changes the document
//! and succeeds, or refuses with a one-line reason and leaves the document as it was.

use crate::document::{EdgeDoc, EditorPos, FORMAT_VERSION, GraphDocument, NodeDoc};
use crate::graph::check_node_id;
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
    let used = |id: &str| taken.contains(id) || crate::organise::id_taken(doc, id);
    (1..)
        .map(|n| format!("{base}_{n}"))
        .find(|id| !used(id))
        .expect("unbounded")
}

fn node<'a>(doc: &'a GraphDocument, id: &str) -> Result<&'a NodeDoc, String> {
    doc.nodes
        .iter()
        .find(|n| n.id == id)
        .ok_or_else(|| format!("no node `{id}` in the graph"))
}

fn schema_of<'a>(
    doc: &GraphDocument,
    schemas: &'a dyn SchemaLookup,
    id: &str,
) -> Result<SchemaRef<'a>, String> {
    let n = node(doc, id)?;
    node_schema(schemas, doc, n)
        .ok_or_else(|| format!("node `{id}` has the unknown kind `{}`", n.kind))
}

/// Adds a node of `kind` with default parameters at `position`; returns its new id.
pub fn add_node(
    doc: &mut GraphDocument,
    schemas: &dyn SchemaLookup,
    kind: &str,
    position: EditorPos,
) -> Result<String, String> {
    let schema = schemas
        .schema(kind)
        .ok_or_else(|| format!("unknown node kind `{kind}`"))?;
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

/// Removes a node and every edge touching it; returns the node, or `None` if there was none.
pub fn remove_node(doc: &mut GraphDocument, id: &str) -> Option<NodeDoc> {
    let index = doc.nodes.iter().position(|n| n.id == id)?;
    doc.edges.retain(|e| e.from.0 != id && e.to.0 != id);
    Some(doc.nodes.remove(index))
}

/// Renames a node, updating the edges that name it.
pub fn rename_node(doc: &mut GraphDocument, old: &str, new: &str) -> Result<(), String> {
    if old == new {
        return node(doc, old).map(|_| ());
    }
    check_node_id(new).map_err(|r| format!("`{new}` is not a valid id: {r}"))?;
    if crate::organise::id_taken(doc, new) {
        return Err(format!("a node or group `{new}` already exists"));
    }
    let index = doc
        .nodes
        .iter()
        .position(|n| n.id == old)
        .ok_or_else(|| format!("no node `{old}` in the graph"))?;
    doc.nodes[index].id = new.to_owned();
    for e in &mut doc.edges {
        for end in [&mut e.from.0, &mut e.to.0] {
            if end == old {
                *end = new.to_owned();
            }
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
) -> Result<(), String> {
    let schema = schema_of(doc, schemas, node_id)?;
    let spec = schema.param(name).ok_or_else(|| {
        format!(
            "node `{node_id}` ({}) has no parameter `{name}`",
            schema.kind
        )
    })?;
    spec.check(&value)
        .map_err(|m| format!("node `{node_id}`, parameter `{name}`: {m}"))?;
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
        None => crate::organise::move_group(doc, id, position),
    }
}

/// The type of `node.port`, an output when `output` is true.
pub fn port_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    node_id: &str,
    port: &str,
    output: bool,
) -> Result<PortType, String> {
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
            format!(
                "node `{node_id}` ({}) has no {side} port `{port}` (its {side}s are: {})",
                schema.kind,
                ports.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
            )
        })
}

/// The type at one end of a new wire: a reroute's is what flows through it (`None`: any yet;
/// an input's is what it feeds, since the new wire replaces what fed it).
fn end_type(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    (node, port): (&str, &str),
    output: bool,
) -> Result<Option<PortType>, String> {
    if !reroute::is_reroute(doc, node) {
        return port_type(doc, schemas, node, port, output).map(Some);
    }
    let expected = if output { reroute::OUT } else { reroute::IN };
    if port != expected {
        let side = if output { "output" } else { "input" };
        return Err(format!(
            "node `{node}` (Reroute) has no {side} port `{port}` (its {side}s are: {expected})"
        ));
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
) -> Result<Option<EdgeDoc>, String> {
    let out_ty = end_type(doc, schemas, from, true)?;
    let in_ty = end_type(doc, schemas, to, false)?;
    if let (Some(out_ty), Some(in_ty)) = (out_ty, in_ty)
        && out_ty != in_ty
    {
        return Err(format!(
            "type mismatch: `{}.{}` gives {out_ty} but `{}.{}` takes {in_ty}",
            from.0, from.1, to.0, to.1
        ));
    }
    if from.0 == to.0 || reaches(doc, to.0, from.0) {
        return Err(format!(
            "connecting `{}.{}` to `{}.{}` would create a cycle",
            from.0, from.1, to.0, to.1
        ));
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
) -> Result<Vec<String>, String> {
    let (sub, _) = GraphDocument::parse(text, None).map_err(|e| format!("cannot paste: {e}"))?;
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
            _ => return Err("cannot paste: an edge names a node that is not pasted".into()),
        }
    }
    let ids = nodes.iter().map(|n| n.id.clone()).collect();
    doc.nodes.extend(nodes);
    doc.edges.extend(edges);
    Ok(ids)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::param::ParamSpec;
    use crate::schema::{NodeSchema, PortSpec};

    struct Fake(Vec<NodeSchema>);

    impl SchemaLookup for Fake {
        fn schema(&self, kind: &str) -> Option<&NodeSchema> {
            self.0.iter().find(|s| s.kind == kind)
        }
        fn kinds(&self) -> Vec<&'static str> {
            self.0.iter().map(|s| s.kind).collect()
        }
    }

    fn schema(
        kind: &'static str,
        inputs: Vec<PortSpec>,
        outputs: Vec<PortSpec>,
        params: Vec<ParamSpec>,
    ) -> NodeSchema {
        NodeSchema {
            kind,
            category: "Test",
            doc: "",
            inputs,
            outputs,
            params,
            frame_dependent: false,
            sink: false,
        }
    }

    fn fake() -> Fake {
        Fake(vec![
            schema(
                "MeshSource",
                vec![],
                vec![PortSpec::output("mesh", PortType::Mesh, "")],
                vec![ParamSpec::int("count", 3, 1, 10, "")],
            ),
            schema(
                "ShadeMesh",
                vec![
                    PortSpec::input("mesh", PortType::Mesh, ""),
                    PortSpec::optional("under", PortType::Image, ""),
                ],
                vec![PortSpec::output("image", PortType::Image, "")],
                vec![
                    ParamSpec::float("gain", 1.0, 0.0, 2.0, ""),
                    ParamSpec::choice("mode", "a", &["a", "b"], ""),
                ],
            ),
            schema(
                "Blur",
                vec![PortSpec::input("image", PortType::Image, "")],
                vec![PortSpec::output("image", PortType::Image, "")],
                vec![],
            ),
        ])
    }

    const ORIGIN: EditorPos = EditorPos { x: 0.0, y: 0.0 };

    fn doc_with(s: &Fake, kinds: &[&str]) -> (GraphDocument, Vec<String>) {
        let mut doc = GraphDocument {
            version: FORMAT_VERSION,
            ..Default::default()
        };
        let ids = kinds
            .iter()
            .map(|k| add_node(&mut doc, s, k, ORIGIN).unwrap())
            .collect();
        (doc, ids)
    }

    #[test]
    fn added_nodes_get_readable_fresh_ids() {
        let s = fake();
        let (mut doc, ids) = doc_with(&s, &["ShadeMesh", "ShadeMesh", "MeshSource"]);
        assert_eq!(ids, ["shade_mesh_1", "shade_mesh_2", "mesh_source_1"]);
        assert_eq!(doc.nodes[1].editor, Some(ORIGIN));
        assert!(doc.nodes[1].params.is_empty());
        remove_node(&mut doc, "shade_mesh_1").unwrap();
        assert_eq!(
            add_node(&mut doc, &s, "ShadeMesh", ORIGIN).unwrap(),
            "shade_mesh_1"
        );
        assert!(
            add_node(&mut doc, &s, "Nope", ORIGIN)
                .unwrap_err()
                .contains("unknown node kind")
        );
        assert_eq!(snake_case("TransferFunction1D"), "transfer_function1_d");
    }

    #[test]
    fn connect_checks_types_ports_and_cycles_and_replaces() {
        let s = fake();
        let (mut doc, _) = doc_with(&s, &["MeshSource", "ShadeMesh", "Blur", "Blur"]);
        assert_eq!(
            connect(
                &mut doc,
                &s,
                ("mesh_source_1", "mesh"),
                ("shade_mesh_1", "mesh")
            ),
            Ok(None)
        );
        let err =
            connect(&mut doc, &s, ("mesh_source_1", "mesh"), ("blur_1", "image")).unwrap_err();
        assert!(
            err.contains("type mismatch") && err.contains("Mesh") && err.contains("Image"),
            "{err}"
        );
        let err =
            connect(&mut doc, &s, ("mesh_source_1", "nope"), ("blur_1", "image")).unwrap_err();
        assert!(err.contains("no output port `nope`"), "{err}");
        connect(&mut doc, &s, ("shade_mesh_1", "image"), ("blur_1", "image")).unwrap();
        connect(&mut doc, &s, ("blur_1", "image"), ("blur_2", "image")).unwrap();
        let err =
            connect(&mut doc, &s, ("blur_2", "image"), ("shade_mesh_1", "under")).unwrap_err();
        assert!(err.contains("cycle"), "{err}");
        let err = connect(&mut doc, &s, ("blur_1", "image"), ("blur_1", "image")).unwrap_err();
        assert!(err.contains("cycle"), "{err}");
        let edges_before = doc.edges.clone();
        // Replacing the wire into blur_2.image.
        let replaced =
            connect(&mut doc, &s, ("shade_mesh_1", "image"), ("blur_2", "image")).unwrap();
        assert_eq!(
            replaced.unwrap().from,
            ("blur_1".to_string(), "image".to_string())
        );
        assert_eq!(doc.edges.len(), edges_before.len());
        assert_eq!(doc.edges.iter().filter(|e| e.to.0 == "blur_2").count(), 1);
        assert!(disconnect(
            &mut doc,
            ("shade_mesh_1", "image"),
            ("blur_2", "image")
        ));
        assert!(!disconnect(
            &mut doc,
            ("shade_mesh_1", "image"),
            ("blur_2", "image")
        ));
    }

    #[test]
    fn set_param_checks_range_and_type_and_stores_ron() {
        let s = fake();
        let (mut doc, _) = doc_with(&s, &["ShadeMesh"]);
        set_param(&mut doc, &s, "shade_mesh_1", "gain", ParamValue::Float(1.5)).unwrap();
        assert_eq!(
            doc.nodes[0].params["gain"],
            ron::Value::Number(ron::Number::new(1.5))
        );
        let err =
            set_param(&mut doc, &s, "shade_mesh_1", "gain", ParamValue::Float(3.0)).unwrap_err();
        assert!(err.contains("out of range"), "{err}");
        let err =
            set_param(&mut doc, &s, "shade_mesh_1", "gain", ParamValue::Bool(true)).unwrap_err();
        assert!(err.contains("expected"), "{err}");
        let err = set_param(
            &mut doc,
            &s,
            "shade_mesh_1",
            "mode",
            ParamValue::Choice("z".into()),
        )
        .unwrap_err();
        assert!(err.contains("not one of"), "{err}");
        assert!(set_param(&mut doc, &s, "shade_mesh_1", "nope", ParamValue::Int(1)).is_err());
        assert!(set_param(&mut doc, &s, "ghost", "gain", ParamValue::Float(1.0)).is_err());
        assert_eq!(doc.nodes[0].params.len(), 1);
    }

    #[test]
    fn rename_updates_edges_and_remove_drops_them() {
        let s = fake();
        let (mut doc, _) = doc_with(&s, &["MeshSource", "ShadeMesh"]);
        connect(
            &mut doc,
            &s,
            ("mesh_source_1", "mesh"),
            ("shade_mesh_1", "mesh"),
        )
        .unwrap();
        rename_node(&mut doc, "mesh_source_1", "bunny").unwrap();
        assert_eq!(doc.edges[0].from.0, "bunny");
        assert!(rename_node(&mut doc, "bunny", "shade_mesh_1").is_err());
        assert!(rename_node(&mut doc, "bunny", "has space").is_err());
        assert!(move_node(&mut doc, "bunny", EditorPos { x: 5.0, y: 6.0 }));
        assert_eq!(doc.nodes[0].editor, Some(EditorPos { x: 5.0, y: 6.0 }));
        assert!(remove_node(&mut doc, "bunny").is_some());
        assert!(doc.edges.is_empty());
        assert!(remove_node(&mut doc, "bunny").is_none());
    }

    #[test]
    fn compatible_kinds_by_port_type_and_side() {
        let s = fake();
        assert_eq!(
            compatible_kinds(&s, PortType::Image, true),
            ["Blur", "ShadeMesh"]
        );
        assert_eq!(
            compatible_kinds(&s, PortType::Image, false),
            ["Blur", "ShadeMesh"]
        );
        assert_eq!(compatible_kinds(&s, PortType::Mesh, false), ["MeshSource"]);
        assert_eq!(compatible_kinds(&s, PortType::Mesh, true), ["ShadeMesh"]);
        assert!(compatible_kinds(&s, PortType::Volume, true).is_empty());
    }

    #[test]
    fn copy_paste_keeps_internal_edges_and_renames_clashes() {
        let s = fake();
        let (mut doc, _) = doc_with(&s, &["MeshSource", "ShadeMesh", "Blur"]);
        connect(
            &mut doc,
            &s,
            ("mesh_source_1", "mesh"),
            ("shade_mesh_1", "mesh"),
        )
        .unwrap();
        connect(&mut doc, &s, ("shade_mesh_1", "image"), ("blur_1", "image")).unwrap();
        set_param(&mut doc, &s, "mesh_source_1", "count", ParamValue::Int(7)).unwrap();
        let text = copy_nodes(&doc, &["mesh_source_1", "shade_mesh_1"]);
        let (sub, _) = GraphDocument::parse(&text, None).unwrap();
        assert_eq!(sub.nodes.len(), 2);
        assert_eq!(sub.edges.len(), 1, "only the internal edge");

        let ids = paste_nodes(&mut doc, &text, EditorPos { x: 10.0, y: 20.0 }).unwrap();
        assert_eq!(ids, ["mesh_source_2", "shade_mesh_2"]);
        assert_eq!(doc.nodes.len(), 5);
        let pasted = doc.nodes.iter().find(|n| n.id == "mesh_source_2").unwrap();
        assert_eq!(pasted.editor, Some(EditorPos { x: 10.0, y: 20.0 }));
        assert!(
            matches!(&pasted.params["count"], ron::Value::Number(n) if n.into_f64() == 7.0),
            "{:?}",
            pasted.params
        );
        assert!(doc.edges.contains(&EdgeDoc {
            from: ("mesh_source_2".into(), "mesh".into()),
            to: ("shade_mesh_2".into(), "mesh".into()),
        }));
        assert_eq!(doc.edges.len(), 3);
        // Pasting into an empty document keeps the ids.
        let mut empty = GraphDocument {
            version: 1,
            ..Default::default()
        };
        assert_eq!(
            paste_nodes(&mut empty, &text, ORIGIN).unwrap(),
            ["mesh_source_1", "shade_mesh_1"]
        );
        assert!(paste_nodes(&mut doc, "not ron", ORIGIN).is_err());
    }
}
