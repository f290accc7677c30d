//! What an undo or redo step changed, said in the status line ("Undid camera.azimuth,
//! camera.elevation"): found by comparing the two documents, so every kind of edit is named
//! without each one carrying a label.

use hatchery_graph::GraphDocument;
use std::collections::BTreeSet;

/// At most this many things are named; more are counted.
const NAMED: usize = 3;

/// A short description of what differs from `before` to `after`.
pub fn describe(before: &GraphDocument, after: &GraphDocument) -> String {
    let ids = |d: &GraphDocument| {
        d.nodes
            .iter()
            .map(|n| n.id.clone())
            .collect::<BTreeSet<_>>()
    };
    let (was, now) = (ids(before), ids(after));
    let mut parts: Vec<String> = Vec::new();
    let added: Vec<&String> = now.difference(&was).collect();
    let removed: Vec<&String> = was.difference(&now).collect();
    if !added.is_empty() {
        parts.push(format!("adding {}", list(&added)));
    }
    if !removed.is_empty() {
        parts.push(format!("removing {}", list(&removed)));
    }
    let mut params = Vec::new();
    let mut moved = Vec::new();
    for n in &after.nodes {
        let Some(old) = before.node(&n.id) else {
            continue;
        };
        let names: BTreeSet<&String> = n.params.keys().chain(old.params.keys()).collect();
        params.extend(
            names
                .into_iter()
                .filter(|p| n.params.get(*p) != old.params.get(*p))
                .map(|p| format!("{}.{p}", n.id)),
        );
        if n.editor != old.editor || n.group != old.group {
            moved.push(n.id.clone());
        }
    }
    if !params.is_empty() {
        parts.push(list(&params.iter().collect::<Vec<_>>()));
    }
    let wires = |d: &GraphDocument| d.edges.iter().cloned().collect::<BTreeSet<_>>();
    let (w0, w1) = (wires(before), wires(after));
    let show =
        |e: &hatchery_graph::EdgeDoc| format!("{}.{} -> {}.{}", e.from.0, e.from.1, e.to.0, e.to.1);
    let new_wires: Vec<String> = w1.difference(&w0).map(show).collect();
    let old_wires: Vec<String> = w0.difference(&w1).map(show).collect();
    if added.is_empty() && removed.is_empty() {
        if !new_wires.is_empty() {
            parts.push(format!(
                "the wire {}",
                list(&new_wires.iter().collect::<Vec<_>>())
            ));
        }
        if !old_wires.is_empty() {
            parts.push(format!(
                "removing the wire {}",
                list(&old_wires.iter().collect::<Vec<_>>())
            ));
        }
    }
    if parts.is_empty() && !moved.is_empty() {
        parts.push(format!(
            "moving {}",
            list(&moved.iter().collect::<Vec<_>>())
        ));
    }
    if before.groups != after.groups {
        parts.push("the groups".into());
    }
    if before.frames != after.frames {
        parts.push("the frames".into());
    }
    if before.inputs != after.inputs || before.description != after.description {
        parts.push("the graph's inputs".into());
    }
    if parts.is_empty() {
        "a change".into()
    } else {
        parts.join("; ")
    }
}

fn list(items: &[&String]) -> String {
    let shown: Vec<&str> = items.iter().take(NAMED).map(|s| s.as_str()).collect();
    match items.len().saturating_sub(NAMED) {
        0 => shown.join(", "),
        more => format!("{} and {more} more", shown.join(", ")),
    }
}
