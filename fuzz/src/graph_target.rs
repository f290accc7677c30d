//! What the `graph` fuzz target does with one input: parse it as a graph file, validate it
//! against a small stand-in node registry, and check that what is saved loads again.
//!
//! This file is compiled twice: by the fuzz crate (`fuzz/src/lib.rs`) and by
//! `crates/hatchery-graph/tests/fuzz_corpus.rs` (`#[path]`), so the replay test runs exactly
//! what the fuzzer ran. It uses only `hatchery_graph` and `std`.

use hatchery_graph::{
    Graph, GraphDocument, NodeSchema, ParamSpec, PortSpec, PortType, SchemaLookup,
};

/// A few node kinds as the real registry (hatchery-nodes, which needs the GPU crates) has
/// them, with every parameter kind and several port types; the seed graphs use these names.
pub struct Schemas(Vec<NodeSchema>);

impl SchemaLookup for Schemas {
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
        category: "Fuzz",
        doc: "",
        inputs,
        outputs,
        params,
        frame_dependent: false,
        sink: kind == "SaveImage",
    }
}

impl Default for Schemas {
    fn default() -> Self {
        use PortType::*;
        let (i, o) = (PortSpec::input, PortSpec::output);
        Schemas(vec![
            schema(
                "Camera",
                vec![],
                vec![o("camera", Camera, "")],
                vec![
                    ParamSpec::float("azimuth", 0.0, -360.0, 360.0, ""),
                    ParamSpec::float("elevation", 0.0, -90.0, 90.0, ""),
                    ParamSpec::float("distance", 3.0, 0.1, 10000.0, ""),
                    ParamSpec::choice("projection", "perspective", &["perspective", "ortho"], ""),
                ],
            ),
            schema(
                "Light",
                vec![],
                vec![o("light", Light, "")],
                vec![ParamSpec::vec3("direction", [0.0, 0.0, 1.0], "")],
            ),
            schema(
                "ProceduralVolume",
                vec![],
                vec![o("volume", Volume, "")],
                vec![
                    ParamSpec::int("resolution", 64, 2, 512, ""),
                    ParamSpec::choice("shape", "sphere", &["sphere", "shells", "torus"], ""),
                ],
            ),
            schema(
                "VolumeFile",
                vec![],
                vec![o("volume", Volume, "")],
                vec![
                    ParamSpec::path("path", "", ""),
                    ParamSpec::text("array", "", ""),
                ],
            ),
            schema(
                "MarchingCubes",
                vec![i("volume", Volume, "")],
                vec![o("mesh", Mesh, "")],
                vec![
                    ParamSpec::float("iso", 0.5, -1e9, 1e9, ""),
                    ParamSpec::bool("smooth", true, ""),
                ],
            ),
            schema(
                "ShadedSurface",
                vec![
                    i("mesh", Mesh, ""),
                    i("camera", Camera, ""),
                    i("light", Light, ""),
                    PortSpec::optional("background", Image, ""),
                ],
                vec![o("image", Image, "")],
                vec![ParamSpec::color("color", [1.0; 4], "")],
            ),
            schema(
                "SaveImage",
                vec![i("image", Image, "")],
                vec![],
                vec![ParamSpec::path("path", "out.png", "")],
            ),
        ])
    }
}

/// Parses `data` as a graph file (UTF-8 only: `GraphDocument::load` refuses anything else
/// before parsing). Whatever parses must save to text that parses to the same text again, and
/// a graph that validates must save to a document that validates again. Returns the parse or validation error, if any (for people looking at a corpus); panics only
/// on a bug.
pub fn graph(schemas: &Schemas, data: &[u8]) -> Result<(), String> {
    let text = std::str::from_utf8(data).map_err(|e| format!("not UTF-8: {e}"))?;
    let (doc, source) = GraphDocument::parse(text, None).map_err(|e| e.to_string())?;
    let saved = doc.to_ron_string();
    let (again, _) = GraphDocument::parse(&saved, None)
        .unwrap_or_else(|e| panic!("saved document does not parse: {e}\n{saved}"));
    assert_eq!(again.to_ron_string(), saved, "saving is not a fixed point");

    let graph = Graph::from_document(&doc, &source, schemas, None).map_err(|e| e.to_string())?;
    let saved = graph.to_document(schemas).to_ron_string();
    let (doc, source) = GraphDocument::parse(&saved, None)
        .unwrap_or_else(|e| panic!("saved graph does not parse: {e}\n{saved}"));
    if let Err(e) = Graph::from_document(&doc, &source, schemas, None) {
        panic!("saved graph does not validate: {e}\n{saved}");
    }
    Ok(())
}
