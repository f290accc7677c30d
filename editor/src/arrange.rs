//! *Arrange*: a layered layout of the graph (Sugiyama-style, simplified): each node goes to the
//! column of its topological rank (longest path from a source), columns left to right; within a
//! column nodes are ordered by the mean row of their inputs (fewer crossings) and stacked
//! without overlap using their drawn sizes.

use hatchery_graph::{EditorPos, GraphDocument};
use std::collections::BTreeMap;

/// Gap between columns and between nodes in a column (graph units).
const GAP: f32 = 40.0;
/// Size assumed for a node that has not been drawn yet.
pub const DEFAULT_SIZE: [f32; 2] = [220.0, 120.0];

/// New top-left positions for every node of `doc`, given each node's size (width, height; graph
/// units). Nodes on a cycle (not a valid graph, but the editor can hold one) go to the column
/// after their ranked inputs.
pub fn layered_layout(
    doc: &GraphDocument,
    sizes: &BTreeMap<String, [f32; 2]>,
) -> BTreeMap<String, EditorPos> {
    let ids: Vec<&str> = doc.nodes.iter().map(|n| n.id.as_str()).collect();
    let inputs = |id: &str| -> Vec<&str> {
        doc.edges
            .iter()
            .filter(|e| e.to.0 == id)
            .map(|e| e.from.0.as_str())
            .filter(|from| ids.contains(from))
            .collect()
    };
    // Rank = longest path from a source, by relaxation (at most one pass per node).
    let mut rank: BTreeMap<&str, usize> = ids.iter().map(|&id| (id, 0)).collect();
    for _ in 0..ids.len() {
        let mut changed = false;
        for &id in &ids {
            let r = inputs(id).iter().map(|&i| rank[i] + 1).max().unwrap_or(0);
            let r = r.min(ids.len());
            if r > rank[id] {
                rank.insert(id, r);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let columns = rank.values().copied().max().unwrap_or(0) + 1;
    // Whole units keep the saved files tidy.
    let size = |id: &str| {
        sizes
            .get(id)
            .copied()
            .unwrap_or(DEFAULT_SIZE)
            .map(f32::ceil)
    };

    let mut out = BTreeMap::new();
    // Row (centre y) of every placed node, for ordering the next columns.
    let mut centre_y: BTreeMap<&str, f32> = BTreeMap::new();
    let mut x = 0.0f32;
    for column in 0..columns {
        // By the mean row of the inputs already placed; sources keep the file's order.
        let mut members: Vec<(&str, f32)> = ids
            .iter()
            .copied()
            .filter(|id| rank[id] == column)
            .map(|id| {
                let rows: Vec<f32> = inputs(id)
                    .iter()
                    .filter_map(|i| centre_y.get(i).copied())
                    .collect();
                let key = if rows.is_empty() {
                    f32::INFINITY
                } else {
                    rows.iter().sum::<f32>() / rows.len() as f32
                };
                (id, key)
            })
            .collect();
        members.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut y = 0.0f32;
        let mut width = 0.0f32;
        for (id, wanted) in members {
            let [w, h] = size(id);
            // Keep near the inputs' row where there is room.
            if wanted.is_finite() {
                y = y.max((wanted - h / 2.0).round());
            }
            out.insert(id.to_owned(), EditorPos { x, y });
            centre_y.insert(id, y + h / 2.0);
            y += h + GAP;
            width = width.max(w);
        }
        x += width + GAP * 2.0;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(text: &str) -> GraphDocument {
        GraphDocument::parse(text, None).unwrap().0
    }

    #[test]
    fn columns_follow_ranks_and_nothing_overlaps() {
        let d = doc(r#"(version: 1, nodes: [
            (id: "a", kind: "Camera"), (id: "b", kind: "Camera"), (id: "c", kind: "Camera"),
            (id: "d", kind: "Camera"), (id: "e", kind: "Camera")],
            edges: [
              (from: ("a", "x"), to: ("c", "y")), (from: ("b", "x"), to: ("c", "z")),
              (from: ("c", "x"), to: ("d", "y")), (from: ("a", "x"), to: ("d", "z"))])"#);
        let sizes: BTreeMap<String, [f32; 2]> = [("c".to_string(), [300.0, 200.0])].into();
        let p = layered_layout(&d, &sizes);
        assert!(p["a"].x == p["b"].x && p["a"].x < p["c"].x && p["c"].x < p["d"].x);
        // d's rank is 2 (through c), not 1 (directly from a).
        assert!(p["d"].x > p["c"].x + 300.0);
        let rect = |id: &str| {
            let [w, h] = sizes.get(id).copied().unwrap_or(DEFAULT_SIZE);
            (p[id].x, p[id].y, p[id].x + w, p[id].y + h)
        };
        let ids = ["a", "b", "c", "d", "e"];
        for (i, a) in ids.iter().enumerate() {
            for b in &ids[i + 1..] {
                let (ra, rb) = (rect(a), rect(b));
                let overlap = ra.0 < rb.2 && rb.0 < ra.2 && ra.1 < rb.3 && rb.1 < ra.3;
                assert!(!overlap, "{a} {ra:?} overlaps {b} {rb:?}");
            }
        }
    }
}
