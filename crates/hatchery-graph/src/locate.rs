//! Finds where a node, parameter or edge is written in a graph file, so that errors found after
//! parsing (unknown kind, bad edge, ...) still point at a line and column.

/// 1-based (line, column) of a byte offset.
pub(crate) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Offsets of every string literal `"s"` in the text.
fn quoted(text: &str, s: &str) -> Vec<usize> {
    let needle = format!("\"{s}\"");
    text.match_indices(&needle).map(|(i, _)| i).collect()
}

/// The text just before `offset`, without trailing white space.
fn before(text: &str, offset: usize) -> &str {
    text[..offset].trim_end()
}

/// The text from `offset`, without leading white space.
fn after(text: &str, offset: usize) -> &str {
    text[offset..].trim_start()
}

/// Where `id: "node"` is written.
pub(crate) fn node_offset(text: &str, node: &str) -> Option<usize> {
    quoted(text, node).into_iter().find(|&i| {
        let b = before(text, i);
        b.ends_with(':') && b[..b.len() - 1].trim_end().ends_with("id")
    })
}

/// Where `name: "input"` of a graph input is written.
pub(crate) fn input_offset(text: &str, input: &str) -> Option<usize> {
    quoted(text, input).into_iter().find(|&i| {
        let b = before(text, i);
        b.ends_with(':') && b[..b.len() - 1].trim_end().ends_with("name")
    })
}

/// Where the control of `node.param` is written: its `node: "node"` within the parentheses
/// that also hold `"param"` (fields in any order).
pub(crate) fn control_offset(text: &str, node: &str, param: &str) -> Option<usize> {
    let section = text.find("controls:")?;
    quoted(text, node).into_iter().find(|&i| {
        if i <= section || !before(text, i).ends_with(':') {
            return false;
        }
        let open = text[section..i].rfind('(').map_or(section, |o| section + o);
        let close = text[i..].find(')').map_or(text.len(), |c| i + c);
        text[open..close].contains(&format!("\"{param}\""))
    })
}

/// Where parameter `"param":` of a node is written (first one after the node's id).
pub(crate) fn param_offset(text: &str, node: &str, param: &str) -> Option<usize> {
    let start = node_offset(text, node)?;
    let next_node = text[start + 1..]
        .find("id:")
        .map_or(text.len(), |i| start + 1 + i);
    quoted(text, param)
        .into_iter()
        .find(|&i| i > start && i < next_node && after(text, i + param.len() + 2).starts_with(':'))
}

/// Where `side: ("node", "port")` of an edge is written; `side` is "from" or "to".
pub(crate) fn edge_end_offset(text: &str, side: &str, node: &str, port: &str) -> Option<usize> {
    quoted(text, node).into_iter().find(|&i| {
        let b = before(text, i);
        let Some(b) = b.strip_suffix('(') else {
            return false;
        };
        let Some(b) = b.trim_end().strip_suffix(':') else {
            return false;
        };
        if !b.trim_end().ends_with(side) {
            return false;
        }
        let rest = after(text, i + node.len() + 2);
        rest.strip_prefix(',')
            .is_some_and(|r| r.trim_start().starts_with(&format!("\"{port}\"")))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "(\n  version: 1,\n  nodes: [\n    (id: \"a\", kind: \"K\", params: {\"x\": 1}),\n    (id: \"b\", kind: \"K\", params: {\"x\": 2}),\n  ],\n  edges: [(from: (\"a\", \"out\"), to: (\"b\", \"in\"))],\n)\n";

    #[test]
    fn finds_nodes_params_and_edges() {
        assert_eq!(
            node_offset(TEXT, "b").map(|o| line_col(TEXT, o)),
            Some((5, 10))
        );
        assert_eq!(
            param_offset(TEXT, "b", "x").map(|o| line_col(TEXT, o)),
            Some((5, 35))
        );
        assert_eq!(
            edge_end_offset(TEXT, "to", "b", "in").map(|o| line_col(TEXT, o).0),
            Some(7)
        );
        assert_eq!(edge_end_offset(TEXT, "from", "b", "in"), None);
        assert_eq!(node_offset(TEXT, "zzz"), None);
    }
}
