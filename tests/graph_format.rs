//! The RON graph format: byte-exact round trips, and one fixture per class of bad input whose
//! error must name the right file, line, node, port or parameter.

mod common;

use hatchery_graph::{Graph, GraphDocument, ParamValue};
use std::path::Path;

#[test]
fn every_preset_round_trips_byte_for_byte_through_both_models() {
    let registry = hatchery_nodes::registry();
    let mut count = 0;
    for entry in std::fs::read_dir(common::repo_root().join("graphs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "ron") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let (doc, _) = GraphDocument::load(&path).unwrap();
        assert_eq!(
            doc.to_ron_string(),
            text,
            "{}: stored model does not round-trip",
            path.display()
        );
        // Through the runtime graph and back, too.
        let graph = Graph::load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
        let again = graph.to_document(&registry);
        assert_eq!(
            again.to_ron_string(),
            text,
            "{}: runtime graph does not round-trip",
            path.display()
        );
        count += 1;
    }
    assert!(count >= 2, "expected the presets in graphs/");
}

#[test]
fn saving_after_an_edit_writes_a_file_that_loads_back_equal() {
    let registry = hatchery_nodes::registry();
    let mut graph = Graph::load_file(
        &common::repo_root().join("graphs/shaded_surface.ron"),
        &registry,
    )
    .unwrap();
    graph
        .set_param(&registry, "camera", "azimuth", ParamValue::Float(75.5))
        .unwrap();
    graph
        .set_param(&registry, "light", "ambient", ParamValue::Float(0.3))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("edited.ron");
    graph.to_document(&registry).save(&path).unwrap();
    let reloaded = Graph::load_file(&path, &registry).unwrap();
    assert_eq!(
        reloaded.node("camera").unwrap().params.float("azimuth"),
        75.5
    );
    assert_eq!(reloaded.node("light").unwrap().params.float("ambient"), 0.3);
    assert_eq!(
        reloaded.to_document(&registry),
        graph.to_document(&registry)
    );
}

#[test]
fn set_param_refuses_out_of_range_and_wrong_types() {
    let registry = hatchery_nodes::registry();
    let mut graph = Graph::load_file(
        &common::repo_root().join("graphs/shaded_surface.ron"),
        &registry,
    )
    .unwrap();
    let err = graph
        .set_param(&registry, "shells", "resolution", ParamValue::Int(9999))
        .unwrap_err();
    assert!(err.to_string().contains("parameter `resolution`"), "{err}");
    let err = graph
        .set_param(&registry, "camera", "azimuth", ParamValue::Text("x".into()))
        .unwrap_err();
    assert!(err.to_string().contains("expected a number"), "{err}");
    let err = graph
        .set_param(&registry, "camera", "zoom", ParamValue::Float(1.0))
        .unwrap_err();
    assert!(err.to_string().contains("has no parameter `zoom`"), "{err}");
}

/// (fixture, line, column or 0 for any, substrings the first error must contain)
const BAD: &[(&str, usize, usize, &[&str])] = &[
    ("syntax_error.ron", 7, 13, &["syntax error", "comma"]),
    (
        "unknown_version.ron",
        2,
        5,
        &["unsupported graph format version 9"],
    ),
    (
        "unknown_kind.ron",
        10,
        17,
        &[
            "node `blur`",
            "unknown node kind `GaussianBlurr`",
            "MarchingCubes",
        ],
    ),
    (
        "unknown_port.ron",
        16,
        0,
        &[
            "node `surface`",
            "no input port `field`",
            "its inputs are: volume",
        ],
    ),
    (
        "type_mismatch.ron",
        16,
        0,
        &[
            "`camera.camera` -> `surface.volume`",
            "output is Camera",
            "expects Volume",
        ],
    ),
    ("cycle.ron", 5, 17, &["cycle", "`move`", "`turn`"]),
    (
        "duplicate_id.ron",
        10,
        17,
        &["node `camera`", "duplicate node id"],
    ),
    (
        "two_edges_into_one_input.ron",
        21,
        0,
        &[
            "node `surface`, input `volume`",
            "2 edges",
            "`a.volume`",
            "`b.volume`",
        ],
    ),
    (
        "missing_input.ron",
        10,
        17,
        &["node `gbuffer`", "required input `mesh`"],
    ),
    (
        "param_wrong_type.ron",
        8,
        17,
        &[
            "node `camera`, parameter `azimuth`",
            "expected a number",
            "\"left\"",
        ],
    ),
    (
        "param_out_of_range.ron",
        8,
        17,
        &[
            "node `shells`, parameter `resolution`",
            "out of range [4, 512]",
        ],
    ),
    (
        "unknown_param.ron",
        8,
        17,
        &["node `surface`", "no parameter `isovalue`", "iso"],
    ),
    (
        "unknown_node_in_edge.ron",
        11,
        0,
        &["no node with id `volume`", "surface.volume"],
    ),
    (
        "bad_choice.ron",
        8,
        17,
        &["parameter `projection`", "\"fisheye\"", "perspective"],
    ),
    (
        "duplicate_param.ron",
        9,
        0,
        &["duplicate parameter `azimuth`"],
    ),
    (
        "unknown_group.ron",
        11,
        17,
        &["node `light`", "no group with id `lights`"],
    ),
    (
        "group_id_clash.ron",
        13,
        0,
        &["`views`", "duplicate node id"],
    ),
    (
        "cycle_through_group.ron",
        5,
        17,
        &["cycle", "`move`", "`turn`", "(in group `spin`)"],
    ),
    ("reroute_loop.ron", 5, 17, &["cycle", "`a`", "`b`"]),
    (
        "reroute_type_mismatch.ron",
        22,
        0,
        &[
            "`camera.camera` -> `surface.volume`",
            "output is Camera",
            "expects Volume",
        ],
    ),
    (
        "reroute_bad_port.ron",
        16,
        0,
        &["node `hop` (Reroute) has no input port `input`", "in"],
    ),
    (
        "custom_shader_error.ron",
        5,
        17,
        &[
            "node `mine`",
            "custom_shader_error.wgsl:6:5: expected `;`, found \"return\"",
        ],
    ),
];

#[test]
fn every_bad_fixture_fails_with_a_located_message() {
    let registry = hatchery_nodes::registry();
    let dir = common::repo_root().join("tests/fixtures/bad");
    let mut listed: Vec<&str> = BAD.iter().map(|b| b.0).collect();
    listed.sort();
    let mut present: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".ron"))
        .collect();
    present.sort();
    assert_eq!(
        present, listed,
        "every fixture in tests/fixtures/bad must have an expectation here"
    );

    for (file, line, col, needles) in BAD {
        let path = dir.join(file);
        let errors = Graph::load_file(&path, &registry).expect_err(file);
        let first = errors.first();
        let message = errors.to_string();
        assert_eq!(
            first.file.as_deref(),
            Some(path.as_path()),
            "{file}: {message}"
        );
        let (l, c) = first
            .position
            .unwrap_or_else(|| panic!("{file}: no position in {message}"));
        assert_eq!(l, *line, "{file}: wrong line in {message}");
        if *col != 0 {
            assert_eq!(c, *col, "{file}: wrong column in {message}");
        }
        assert!(
            message.starts_with(&format!("{}:{line}:", path.display())),
            "{file}: {message}"
        );
        for needle in *needles {
            assert!(
                message.contains(needle),
                "{file}: `{needle}` missing from: {message}"
            );
        }
    }
}

#[test]
fn a_missing_file_is_named() {
    let registry = hatchery_nodes::registry();
    let err = Graph::load_file(Path::new("no/such/graph.ron"), &registry).unwrap_err();
    let message = err.to_string();
    assert!(
        message.starts_with("no/such/graph.ron: cannot read graph file"),
        "{message}"
    );
}

#[test]
fn reroutes_resolve_through_chains_and_grouped_nodes_run_as_plain_nodes() {
    let registry = hatchery_nodes::registry();
    let text = r#"(version: 2, nodes: [
        (id: "shells", kind: "ProceduralVolume", group: Some("inputs")),
        (id: "r1", kind: "Reroute"),
        (id: "r2", kind: "Reroute"),
        (id: "idle", kind: "Reroute"),
        (id: "surface", kind: "MarchingCubes"),
    ], edges: [
        (from: ("shells", "volume"), to: ("r1", "in")),
        (from: ("r1", "out"), to: ("r2", "in")),
        (from: ("r2", "out"), to: ("surface", "volume")),
    ], groups: [(id: "inputs", editor: None)])"#;
    let (doc, source) = GraphDocument::parse(text, None).unwrap();
    assert_eq!(
        hatchery_graph::reroute::reroute_type(&doc, &registry, "r2"),
        Some(hatchery_graph::PortType::Volume)
    );
    assert_eq!(
        hatchery_graph::reroute::reroute_type(&doc, &registry, "idle"),
        None
    );
    let graph = Graph::from_document(&doc, &source, &registry, None).unwrap();
    assert_eq!(graph.node_ids().collect::<Vec<_>>(), ["shells", "surface"]);
    assert_eq!(graph.input_sources("surface")[&0], ("shells", 0));
    assert_eq!(
        graph.node("shells").unwrap().group.as_deref(),
        Some("inputs")
    );
    let saved = graph.to_document(&registry);
    assert_eq!(saved.groups, doc.groups, "groups survive the runtime graph");
    assert_eq!(saved.edges.len(), 1);
}
