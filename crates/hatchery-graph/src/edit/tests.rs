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
            .to_string()
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
    let err = connect(&mut doc, &s, ("mesh_source_1", "mesh"), ("blur_1", "image"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("type mismatch") && err.contains("Mesh") && err.contains("Image"),
        "{err}"
    );
    let err = connect(&mut doc, &s, ("mesh_source_1", "nope"), ("blur_1", "image"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("no output port `nope`"), "{err}");
    connect(&mut doc, &s, ("shade_mesh_1", "image"), ("blur_1", "image")).unwrap();
    connect(&mut doc, &s, ("blur_1", "image"), ("blur_2", "image")).unwrap();
    let err = connect(&mut doc, &s, ("blur_2", "image"), ("shade_mesh_1", "under"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("cycle"), "{err}");
    let err = connect(&mut doc, &s, ("blur_1", "image"), ("blur_1", "image"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("cycle"), "{err}");
    let edges_before = doc.edges.clone();
    // Replacing the wire into blur_2.image.
    let replaced = connect(&mut doc, &s, ("shade_mesh_1", "image"), ("blur_2", "image")).unwrap();
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
    let err = set_param(&mut doc, &s, "shade_mesh_1", "gain", ParamValue::Float(3.0))
        .unwrap_err()
        .to_string();
    assert!(err.contains("out of range"), "{err}");
    let err = set_param(&mut doc, &s, "shade_mesh_1", "gain", ParamValue::Bool(true))
        .unwrap_err()
        .to_string();
    assert!(err.contains("expected"), "{err}");
    let err = set_param(
        &mut doc,
        &s,
        "shade_mesh_1",
        "mode",
        ParamValue::Choice("z".into()),
    )
    .unwrap_err()
    .to_string();
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

/// Groups and frames (moved with their writers from organise.rs).
mod groups {
    use crate::edit::*;
    use crate::organise::members;
    use crate::{EditorPos, GraphDocument};

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
        let err = group_nodes(&mut d, &["a".into(), "c".into()])
            .unwrap_err()
            .to_string();
        assert!(err.contains("do not nest"), "{err}");
        let err = group_nodes(&mut d, std::slice::from_ref(&g))
            .unwrap_err()
            .to_string();
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
