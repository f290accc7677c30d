//! Migrations of older graph files to the current format, as pure functions on the document.
//!
//! | version | what it added |
//! |---|---|
//! | 1 | nodes, edges, editor positions |
//! | 2 | node groups (`groups`, `nodes[].group`), frames (`frames`), `Reroute` nodes |
//! | 3 | graph inputs (`inputs`), a `description`, data-relative parameter values |
//!
//! Versions 2 and 3 only add optional sections (and, in 3, values that older files cannot
//! hold), so an older document is a valid current document once its version says so; the
//! migrations exist so that every load goes through one place and later formats add their step
//! here.

use crate::document::GraphDocument;

/// Version 1 → 2: the same graph, with nothing grouped, no frames and no reroutes.
pub fn v1_to_v2(mut doc: GraphDocument) -> GraphDocument {
    debug_assert_eq!(doc.version, 1);
    doc.version = 2;
    doc
}

/// Version 2 → 3: the same graph, declaring no inputs.
pub fn v2_to_v3(mut doc: GraphDocument) -> GraphDocument {
    debug_assert_eq!(doc.version, 2);
    doc.version = 3;
    doc
}

/// Brings a parsed document of any supported version to [`crate::FORMAT_VERSION`]; documents of the
/// current (or an unknown, refused earlier) version pass through unchanged.
pub fn to_current(mut doc: GraphDocument) -> GraphDocument {
    if doc.version == 1 {
        doc = v1_to_v2(doc);
    }
    if doc.version == 2 {
        doc = v2_to_v3(doc);
    }
    doc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_1_text_loads_as_the_current_version_and_saves_so() {
        let v1 = "(version: 1, nodes: [(id: \"c\", kind: \"Camera\", params: {\"azimuth\": 3.0})], \
                  edges: [(from: (\"c\", \"camera\"), to: (\"s\", \"camera\"))])";
        let (doc, _) = GraphDocument::parse(v1, None).unwrap();
        assert_eq!(doc.version, crate::FORMAT_VERSION);
        assert!(doc.groups.is_empty() && doc.frames.is_empty() && doc.inputs.is_empty());
        assert_eq!(doc.nodes[0].group, None);
        let saved = doc.to_ron_string();
        assert!(saved.contains("version: 3,"), "{saved}");
        let (again, _) = GraphDocument::parse(&saved, None).unwrap();
        assert_eq!(again, doc);
    }
}
