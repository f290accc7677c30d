//! Validation helpers below the graph model: what a node id may be.

/// Node ids are used on the command line as `node.param`, so they are plain identifiers.
pub(crate) fn check_node_id(id: &str) -> Result<(), String> {
    if id.is_empty() {
        return Err("ids must not be empty".into());
    }
    if let Some(c) = id
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_' || *c == '-'))
    {
        return Err(format!(
            "character '{c}' is not allowed (use letters, digits, '_' and '-')"
        ));
    }
    Ok(())
}
