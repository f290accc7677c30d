//! The stored model: exactly what a graph file says, and its RON format (version 3).
//!
//! The document is written in one canonical layout (nodes sorted by id, parameters sorted by
//! name, edges sorted, groups sorted by id, frames in drawing order), so that load → save
//! reproduces a saved file byte for byte. Files are read by [`crate::load`] (older versions through
//! [`crate::migrate`]).

use crate::error::{ErrorKind, GraphError};
use crate::locate;
use serde::Deserialize;
use serde::de::{Deserializer, Error as _, MapAccess, Visitor};
use std::collections::BTreeMap;
use std::fmt::{self, Write as _};
use std::path::{Path, PathBuf};

/// The newest graph file format version this build reads and writes.
pub const FORMAT_VERSION: u32 = 3;

/// A graph as stored in a file. Two documents are equal when their files would be
/// (`base_dir`, where the file lies, is not compared).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphDocument {
    pub version: u32,
    /// One line on what the graph shows (version 3; `hatchery presets` lists it).
    #[serde(default)]
    pub description: String,
    /// The data files the graph reads, by name (version 3; see [`crate::inputs`]).
    #[serde(default)]
    pub inputs: Vec<InputDoc>,
    /// The parameters a figure's reader may change (version 3; see [`crate::controls`]).
    #[serde(default)]
    pub controls: Vec<ControlDoc>,
    #[serde(default)]
    pub nodes: Vec<NodeDoc>,
    #[serde(default)]
    pub edges: Vec<EdgeDoc>,
    /// Node groups (version 2): a node belongs to the group its `group` field names.
    #[serde(default)]
    pub groups: Vec<GroupDoc>,
    /// Labelled boxes drawn behind the nodes in the editor (version 2). Ignored by rendering.
    #[serde(default)]
    pub frames: Vec<FrameDoc>,
    /// The folder relative paths in the document resolve against (the graph file's folder);
    /// not stored in the file. Needed to read a node's own schema from a file it names.
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
}

impl PartialEq for GraphDocument {
    fn eq(&self, other: &Self) -> bool {
        self.version == other.version
            && self.description == other.description
            && self.inputs == other.inputs
            && self.controls == other.controls
            && self.nodes == other.nodes
            && self.edges == other.edges
            && self.groups == other.groups
            && self.frames == other.frames
    }
}

/// One node: a stable human-readable id, its kind, the parameters that differ from or restate
/// the defaults, and optionally where the editor shows it.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeDoc {
    pub id: String,
    pub kind: String,
    #[serde(default, deserialize_with = "unique_params")]
    pub params: BTreeMap<String, ron::Value>,
    #[serde(default)]
    pub editor: Option<EditorPos>,
    /// The group this node belongs to (version 2); `None` on the top level.
    #[serde(default)]
    pub group: Option<String>,
}

/// A node group: shown collapsed in the editor as one node whose ports are its members' ports
/// that are not connected inside the group. Rendering ignores groups (members are plain nodes).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDoc {
    /// Unique among node and group ids (the same rules as node ids).
    pub id: String,
    #[serde(default)]
    pub editor: Option<EditorPos>,
}

/// A frame: a labelled, coloured box behind nodes; dragging it moves the nodes inside it.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameDoc {
    pub label: String,
    /// Top-left corner and size, in editor (graph) units.
    pub x: f32,
    pub y: f32,
    pub w: f32,
    pub h: f32,
    /// RGBA, 0..1, written as a list like parameter colours.
    #[serde(deserialize_with = "rgba")]
    pub color: [f32; 4],
    /// The group whose inside shows the frame; `None` on the top level.
    #[serde(default)]
    pub group: Option<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EditorPos {
    pub x: f32,
    pub y: f32,
}

/// An edge from an output port to an input port, both by node id and port *name*.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeDoc {
    pub from: (String, String),
    pub to: (String, String),
}

/// One declared input as stored in the file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputDoc {
    /// Unique among the graph's inputs; the same rules as node ids.
    pub name: String,
    /// `volume`, `labels`, `mesh` or `names` (see [`crate::InputKind`]).
    #[serde(rename = "type")]
    pub kind: String,
    /// One line for `hatchery inputs` and the editor's Data panel.
    #[serde(default)]
    pub doc: String,
    /// The `(node, parameter)` pairs that take the input's path.
    pub to: Vec<(String, String)>,
}

/// A parameter a figure's reader may change (see [`crate::controls`]).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControlDoc {
    pub node: String,
    pub param: String,
    /// What the page writes next to it; the parameter's name when empty.
    #[serde(default)]
    pub label: String,
    /// A number's slider range, within the parameter's own (its whole range when not given).
    #[serde(default)]
    pub min: Option<f64>,
    #[serde(default)]
    pub max: Option<f64>,
}

fn rgba<'de, D: Deserializer<'de>>(d: D) -> Result<[f32; 4], D::Error> {
    let v: Vec<f32> = Vec::deserialize(d)?;
    <[f32; 4]>::try_from(v.as_slice())
        .map_err(|_| D::Error::custom(format!("expected 4 colour components, found {}", v.len())))
}

fn unique_params<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<BTreeMap<String, ron::Value>, D::Error> {
    struct UniqueMap;
    impl<'de> Visitor<'de> for UniqueMap {
        type Value = BTreeMap<String, ron::Value>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a map from parameter names to values")
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
            let mut out = BTreeMap::new();
            while let Some((key, value)) = map.next_entry::<String, ron::Value>()? {
                if out.contains_key(&key) {
                    return Err(A::Error::custom(format!("duplicate parameter `{key}`")));
                }
                out.insert(key, value);
            }
            Ok(out)
        }
    }
    d.deserialize_map(UniqueMap)
}

/// The folder of a file, `.` for a bare file name: where its relative paths resolve.
pub fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Where a document came from: needed to point errors at file:line:col.
#[derive(Clone, Debug, Default)]
pub struct Source {
    pub path: Option<PathBuf>,
    pub text: String,
}

impl Source {
    pub fn error(&self, offset: Option<usize>, kind: ErrorKind) -> GraphError {
        GraphError {
            file: self.path.clone(),
            position: offset.map(|o| locate::line_col(&self.text, o)),
            kind,
            group: None,
        }
    }
    pub fn node_offset(&self, node: &str) -> Option<usize> {
        locate::node_offset(&self.text, node)
    }
    pub fn param_offset(&self, node: &str, param: &str) -> Option<usize> {
        locate::param_offset(&self.text, node, param).or_else(|| self.node_offset(node))
    }
    pub fn edge_offset(&self, edge: &EdgeDoc, side: &str) -> Option<usize> {
        let (node, port) = if side == "from" { &edge.from } else { &edge.to };
        locate::edge_end_offset(&self.text, side, node, port)
    }
}

impl GraphDocument {
    /// The canonical RON text of this document.
    pub fn to_ron_string(&self) -> String {
        let mut nodes: Vec<&NodeDoc> = self.nodes.iter().collect();
        nodes.sort_by(|a, b| a.id.cmp(&b.id));
        let mut edges: Vec<&EdgeDoc> = self.edges.iter().collect();
        edges.sort();

        let mut out = String::new();
        out.push_str("(\n");
        let _ = writeln!(out, "    version: {},", self.version);
        // Sections of version 3, written only when used.
        if !self.description.is_empty() {
            let _ = writeln!(
                out,
                "    description: {},",
                string_literal(&self.description)
            );
        }
        if !self.inputs.is_empty() {
            out.push_str("    inputs: [\n");
            for i in &self.inputs {
                let to: Vec<String> =
                    i.to.iter()
                        .map(|(n, p)| format!("({}, {})", string_literal(n), string_literal(p)))
                        .collect();
                let _ = writeln!(
                    out,
                    "        (name: {}, type: {}, doc: {}, to: [{}]),",
                    string_literal(&i.name),
                    string_literal(&i.kind),
                    string_literal(&i.doc),
                    to.join(", ")
                );
            }
            out.push_str("    ],\n");
        }
        if !self.controls.is_empty() {
            out.push_str("    controls: [\n");
            for c in &self.controls {
                let mut fields = vec![
                    format!("node: {}", string_literal(&c.node)),
                    format!("param: {}", string_literal(&c.param)),
                ];
                if !c.label.is_empty() {
                    fields.push(format!("label: {}", string_literal(&c.label)));
                }
                for (name, value) in [("min", c.min), ("max", c.max)] {
                    if let Some(v) = value {
                        fields.push(format!("{name}: Some({})", float_literal(v)));
                    }
                }
                let _ = writeln!(out, "        ({}),", fields.join(", "));
            }
            out.push_str("    ],\n");
        }
        out.push_str("    nodes: [\n");
        for node in nodes {
            out.push_str("        (\n");
            let _ = writeln!(out, "            id: {},", string_literal(&node.id));
            let _ = writeln!(out, "            kind: {},", string_literal(&node.kind));
            if node.params.is_empty() {
                out.push_str("            params: {},\n");
            } else {
                out.push_str("            params: {\n");
                for (name, value) in &node.params {
                    let _ = writeln!(
                        out,
                        "                {}: {},",
                        string_literal(name),
                        value_literal(value)
                    );
                }
                out.push_str("            },\n");
            }
            if let Some(pos) = node.editor {
                let _ = writeln!(out, "            editor: {},", pos_literal(pos));
            }
            if let Some(group) = &node.group {
                let _ = writeln!(out, "            group: Some({}),", string_literal(group));
            }
            out.push_str("        ),\n");
        }
        out.push_str("    ],\n");
        out.push_str("    edges: [\n");
        for edge in edges {
            let _ = writeln!(
                out,
                "        (from: ({}, {}), to: ({}, {})),",
                string_literal(&edge.from.0),
                string_literal(&edge.from.1),
                string_literal(&edge.to.0),
                string_literal(&edge.to.1)
            );
        }
        out.push_str("    ],\n");
        // Sections of version 2, written only when used: files without them stay concise.
        if !self.groups.is_empty() {
            let mut groups: Vec<&GroupDoc> = self.groups.iter().collect();
            groups.sort_by(|a, b| a.id.cmp(&b.id));
            out.push_str("    groups: [\n");
            for g in groups {
                let editor = g.editor.map_or("None".into(), pos_literal);
                let _ = writeln!(
                    out,
                    "        (id: {}, editor: {editor}),",
                    string_literal(&g.id)
                );
            }
            out.push_str("    ],\n");
        }
        if !self.frames.is_empty() {
            out.push_str("    frames: [\n");
            for f in &self.frames {
                let color: Vec<String> = f.color.iter().map(|c| f32_literal(*c)).collect();
                let group = f.group.as_ref().map_or(String::new(), |g| {
                    format!(", group: Some({})", string_literal(g))
                });
                let _ = writeln!(
                    out,
                    "        (label: {}, x: {}, y: {}, w: {}, h: {}, color: [{}]{group}),",
                    string_literal(&f.label),
                    f32_literal(f.x),
                    f32_literal(f.y),
                    f32_literal(f.w),
                    f32_literal(f.h),
                    color.join(", ")
                );
            }
            out.push_str("    ],\n");
        }
        out.push_str(")\n");
        out
    }

    /// The group named `id`, if any.
    pub fn group(&self, id: &str) -> Option<&GroupDoc> {
        self.groups.iter().find(|g| g.id == id)
    }

    /// The node named `id`, if any.
    pub fn node(&self, id: &str) -> Option<&NodeDoc> {
        self.nodes.iter().find(|n| n.id == id)
    }

    /// Writes the canonical text atomically ([`crate::atomic::write_atomically`]), so a crash
    /// never leaves a half-written graph.
    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        crate::atomic::write_bytes_atomically(path, self.to_ron_string().as_bytes())
    }
}

fn string_literal(s: &str) -> String {
    ron::to_string(s).unwrap_or_else(|_| format!("{s:?}"))
}

fn pos_literal(pos: EditorPos) -> String {
    format!(
        "Some((x: {}, y: {}))",
        float_literal(pos.x as f64),
        float_literal(pos.y as f64)
    )
}

/// The shortest text that reads back as the same f32 (`0.3`, not `0.30000001192092896`).
fn f32_literal(x: f32) -> String {
    ron::to_string(&x).unwrap_or_else(|_| format!("{x:?}"))
}

fn float_literal(x: f64) -> String {
    ron::to_string(&x).unwrap_or_else(|_| format!("{x:?}"))
}

/// Parameter values inline: lists as `[a, b, c]`, everything else as RON writes it.
fn value_literal(value: &ron::Value) -> String {
    match value {
        ron::Value::Seq(items) => {
            format!(
                "[{}]",
                items
                    .iter()
                    .map(value_literal)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
        ron::Value::String(s) => string_literal(s),
        other => ron::to_string(other).unwrap_or_else(|_| "()".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_text_round_trips_byte_for_byte() {
        let text = r#"(
    version: 3,
    description: "a \"test\" graph",
    inputs: [
        (name: "volume", type: "volume", doc: "the scan", to: [("a", "path"), ("b", "path")]),
    ],
    nodes: [
        (
            id: "a",
            kind: "Camera",
            params: {
                "color": [1.0, 0.5, 0.0, 1.0],
                "count": 3,
                "name": "quote \" inside",
                "x": 0.1,
            },
            editor: Some((x: 10.5, y: -3.0)),
        ),
        (
            id: "b",
            kind: "Light",
            params: {},
            group: Some("lights"),
        ),
    ],
    edges: [
        (from: ("a", "camera"), to: ("b", "camera")),
    ],
    groups: [
        (id: "lights", editor: Some((x: 5.0, y: 6.0))),
        (id: "unplaced", editor: None),
    ],
    frames: [
        (label: "Inputs", x: -10.5, y: 0.0, w: 300.0, h: 120.0, color: [0.3, 0.5, 0.8, 0.25]),
        (label: "Inner", x: 0.0, y: 0.0, w: 10.0, h: 10.0, color: [1.0, 1.0, 1.0, 1.0], group: Some("lights")),
    ],
)
"#;
        let (doc, _) = GraphDocument::parse(text, None).unwrap();
        assert_eq!(doc.nodes.len(), 2);
        assert_eq!(doc.nodes[1].group.as_deref(), Some("lights"));
        assert_eq!(doc.frames[0].color[1], 0.5);
        assert_eq!(doc.inputs[0].to[1], ("b".to_owned(), "path".to_owned()));
        assert_eq!(doc.description, "a \"test\" graph");
        assert_eq!(doc.to_ron_string(), text);
    }

    #[test]
    fn saving_sorts_nodes_and_edges() {
        let text = r#"(version: 1, nodes: [(id: "z", kind: "K"), (id: "a", kind: "K")],
            edges: [(from: ("z", "o"), to: ("a", "i")), (from: ("a", "o"), to: ("z", "i"))])"#;
        let (doc, _) = GraphDocument::parse(text, None).unwrap();
        let saved = doc.to_ron_string();
        assert!(saved.find("\"a\"").unwrap() < saved.find("\"z\"").unwrap());
        let (again, _) = GraphDocument::parse(&saved, None).unwrap();
        assert_eq!(again.to_ron_string(), saved);
    }

    #[test]
    fn syntax_errors_have_line_and_column() {
        let err = GraphDocument::parse(
            "(\n version: 1,\n nodes: [ (id: \"a\" kind: \"K\") ],\n)",
            Some(Path::new("g.ron")),
        )
        .unwrap_err();
        assert_eq!(err.position.map(|p| p.0), Some(3), "{err}");
        assert!(err.to_string().starts_with("g.ron:3:"), "{err}");
    }

    #[test]
    fn duplicate_parameters_are_refused() {
        let err = GraphDocument::parse(
            "(version: 1, nodes: [(id: \"a\", kind: \"K\", params: {\"x\": 1, \"x\": 2})])",
            None,
        )
        .unwrap_err();
        assert!(err.to_string().contains("duplicate parameter `x`"), "{err}");
    }

    #[test]
    fn future_versions_are_refused_by_name() {
        let err =
            GraphDocument::parse("(version: 7, nodes: [], something_new: 3)", None).unwrap_err();
        assert!(
            matches!(err.kind, ErrorKind::UnsupportedVersion { found: 7, .. }),
            "{err}"
        );
    }

    #[test]
    fn save_is_atomic_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("g.ron");
        let doc = GraphDocument {
            version: 1,
            ..Default::default()
        };
        doc.save(&path).unwrap();
        doc.save(&path).unwrap();
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("g.ron")]);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), doc.to_ron_string());
    }
}
