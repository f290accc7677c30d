//! Migrations of older graph files to the current format, as pure functions on the document.
//!
//! | version | what it added |
//! |---|---|
//! | 1 | nodes, edges, editor positions |
//! | 2 | node groups (`groups`, `nodes[].group`), frames (`frames`), `Reroute` nodes |
//!
//! Version 2 only adds optional sections, so a version 1 document is a valid version 2 document
//! once its version says so; the migration exists so that every load goes through one place and
//! later formats add their step here.

use crate::document::GraphDocument;

/// Version 1 → 2: the same graph, with nothing grouped, no frames and no reroutes.
pub fn v1_to_v2(mut doc: GraphDocument) -> GraphDocument {
    debug_assert_eq!(doc.version, 1);
    doc.version = 2;
    doc
}

/// Brings a parsed document of any supported version to [`crate::FORMAT_VERSION`]; documents of the
/// current (or an unknown, refused earlier) version pass through unchanged.
pub fn to_current(doc: GraphDocument) -> GraphDocument {
    if doc.version == 1 { v1_to_v2(doc) } else { doc }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_1_text_loads_as_version_2_and_saves_as_version_2() {
        let v1 = "(version: 1, nodes: [(id: \"c\", kind: \"Camera\", params: {\"azimuth\": 3.0})], \
                  edges: [(from: (\"c\", \"camera\"), to: (\"s\", \"camera\"))])";
        let (doc, _) = GraphDocument::parse(v1, None).unwrap();
        assert_eq!(doc.version, 2);
        assert!(doc.groups.is_empty() && doc.frames.is_empty());
        assert_eq!(doc.nodes[0].group, None);
        let saved = doc.to_ron_string();
        assert!(saved.contains("version: 2,"), "{saved}");
        let (again, _) = GraphDocument::parse(&saved, None).unwrap();
        assert_eq!(again, doc);
    }
}
