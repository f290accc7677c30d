//! Older formats load unchanged: every preset as it was committed in version 1
//! (tests/fixtures/v1_presets/, copies of graphs/ before groups came) loads, saves in the current
//! version, and the saved file renders exactly what the version 1 file renders; every preset as
//! it was committed in version 2 (tests/fixtures/v2_presets/, before inputs, framing and
//! relative values) loads and saves with only its version line changed.

mod common;

use hatchery_graph::{Graph, GraphDocument, SchemaLookup};
use hatchery_nodes::{Session, export};
use std::path::Path;

/// Small pictures: the comparison is about the graph, not the resolution.
const W: u32 = 128;
const H: u32 = 96;

/// Every picture a graph's SaveImage nodes would write, by saver id.
fn render(text: &str, base: &Path, name: &str) -> Vec<(String, image::RgbaImage)> {
    let registry = hatchery_nodes::registry();
    let (doc, source) = GraphDocument::parse(text, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    let graph = Graph::from_document(&doc, &source, &registry, Some(base))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut session = Session::with_graph(registry, graph, W, H).expect("GPU available");
    common::savers(&session)
        .into_iter()
        .map(|saver| {
            let (node, port) = {
                let (node, port) = session.graph.input_sources(&saver)[&0];
                (node.to_owned(), port)
            };
            session
                .run(&[&node])
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let value = session.executor.output(&node, port).unwrap().clone();
            (saver, export::to_rgba8(&value, &session.ctx.gpu).unwrap())
        })
        .collect()
}

fn current() -> String {
    format!("\n    version: {},\n", hatchery_graph::FORMAT_VERSION)
}

#[test]
fn every_v2_preset_loads_and_saves_with_only_its_version_changed() {
    let dir = common::repo_root().join("tests/fixtures/v2_presets");
    let base = common::repo_root().join("graphs");
    let registry = hatchery_nodes::registry();
    let files = common::ron_files(&dir);
    assert!(files.len() >= 28, "the version 2 presets are missing");
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let v2 = std::fs::read_to_string(&path).unwrap();
        assert!(
            v2.contains("\n    version: 2,\n"),
            "{name} is not version 2"
        );
        let (doc, source) = GraphDocument::parse(&v2, Some(&path)).unwrap();
        assert_eq!(doc.version, hatchery_graph::FORMAT_VERSION, "{name}");
        assert!(
            doc.inputs.is_empty() && doc.description.is_empty(),
            "{name}"
        );
        let saved = doc.to_ron_string();
        assert_eq!(
            saved,
            v2.replacen("\n    version: 2,\n", &current(), 1),
            "{name}"
        );
        // It validates against today's node kinds (parameters of version 2 still exist).
        Graph::from_document(&doc, &source, &registry, Some(&base))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn every_v1_preset_loads_saves_in_the_current_version_and_renders_identically() {
    let dir = common::repo_root().join("tests/fixtures/v1_presets");
    // Paths in the presets are relative to graphs/, where they were written.
    let base = common::repo_root().join("graphs");
    let files = common::ron_files(&dir);
    assert!(files.len() >= 14, "the version 1 presets are missing");
    let registry = hatchery_nodes::registry();
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let v1 = std::fs::read_to_string(&path).unwrap();
        assert!(
            v1.contains("\n    version: 1,\n"),
            "{name} is not version 1"
        );
        let (doc, _) = GraphDocument::parse(&v1, Some(&path)).unwrap();
        assert_eq!(doc.version, hatchery_graph::FORMAT_VERSION, "{name}");
        let v2 = doc.to_ron_string();
        // Nothing but the version changes: no groups, frames, reroutes or inputs appear.
        assert_eq!(
            v2,
            v1.replacen("\n    version: 1,\n", &current(), 1),
            "{name}"
        );
        // The saved file loads back to the same document, through the runtime graph too.
        let (again, source) = GraphDocument::parse(&v2, None).unwrap();
        assert_eq!(again, doc, "{name}");
        let graph = Graph::from_document(&again, &source, &registry, Some(&base)).unwrap();
        assert_eq!(graph.to_document(&registry).to_ron_string(), v2, "{name}");
        assert!(registry.kinds().len() > 10);

        let before = render(&v1, &base, &name);
        let after = render(&v2, &base, &name);
        assert_eq!(before.len(), after.len(), "{name}: savers differ");
        assert!(!before.is_empty(), "{name}: nothing rendered");
        for ((saver, a), (_, b)) in before.iter().zip(&after) {
            assert_eq!(a.dimensions(), b.dimensions(), "{name}: {saver}");
            common::assert_images_close(
                &format!("migration_{name}_{saver}"),
                &common::rgba8_pixels(a),
                &common::rgba8_pixels(b),
                a.width(),
                1.0,
            );
        }
    }
}
