//! Graph inputs (format version 3): the named data files a graph reads, so a preset can be
//! pointed at anyone's data (`hatchery render g.ron --input volume=my_t1.nii.gz`).
//!
//! An input is bound to one or more path parameters in the file (`to: [("mri", "path")]`); its
//! default is what the first of them holds, so the file keeps one source of truth and a graph
//! without inputs renders exactly as before. Setting an input sets every bound parameter.

pub use crate::document::InputDoc;
use crate::document::{GraphDocument, Source};
use crate::error::{EditError, ErrorKind, GraphError};
pub use crate::input_kind::InputKind;
use crate::param::ParamKind;
use crate::schema::SchemaLookup;
use std::path::{Path, PathBuf};

/// A validated input, as `hatchery inputs` lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphInput {
    pub name: String,
    pub kind: InputKind,
    pub doc: String,
    pub to: Vec<(String, String)>,
    /// The path the file holds (in the first bound parameter), as written there.
    pub default: String,
}

impl GraphInput {
    /// The default resolved against the graph's folder (empty stays empty).
    pub fn default_path(&self, base_dir: Option<&Path>) -> PathBuf {
        let p = PathBuf::from(&self.default);
        match base_dir {
            Some(base) if !self.default.is_empty() && p.is_relative() => base.join(p),
            _ => p,
        }
    }
}

/// Checks the document's inputs against its nodes: unique names, known kinds, bindings to
/// existing path parameters that read that kind of file. Returns the valid inputs.
pub fn check(
    doc: &GraphDocument,
    source: &Source,
    schemas: &dyn SchemaLookup,
    errors: &mut Vec<GraphError>,
) -> Vec<GraphInput> {
    let mut valid = Vec::new();
    for (index, input) in doc.inputs.iter().enumerate() {
        let at = crate::locate::input_offset(&source.text, &input.name);
        let mut fail = |reason: String| {
            errors.push(source.error(
                at,
                ErrorKind::BadInput {
                    input: input.name.clone(),
                    reason,
                },
            ))
        };
        if let Err(reason) = crate::ids::check_node_id(&input.name) {
            fail(format!("invalid name: {reason}"));
            continue;
        }
        if doc.inputs[..index].iter().any(|i| i.name == input.name) {
            fail("declared twice".into());
            continue;
        }
        let Some(kind) = InputKind::parse(&input.kind) else {
            let known: Vec<&str> = InputKind::ALL.iter().map(|k| k.name()).collect();
            fail(format!(
                "unknown type `{}` (types are: {})",
                input.kind,
                known.join(", ")
            ));
            continue;
        };
        if input.to.is_empty() {
            fail("bound to no parameter (`to` is empty)".into());
            continue;
        }
        let mut ok = true;
        for (node, param) in &input.to {
            if let Err(reason) = check_binding(doc, schemas, kind, node, param) {
                fail(reason);
                ok = false;
            }
        }
        if !ok {
            continue;
        }
        let (node, param) = &input.to[0];
        let default = doc
            .node(node)
            .and_then(|n| n.params.get(param))
            .and_then(|v| match v {
                ron::Value::String(s) => Some(s.clone()),
                _ => None,
            })
            .unwrap_or_default();
        valid.push(GraphInput {
            name: input.name.clone(),
            kind,
            doc: input.doc.clone(),
            to: input.to.clone(),
            default,
        });
    }
    valid
}

fn check_binding(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    kind: InputKind,
    node: &str,
    param: &str,
) -> Result<(), String> {
    let n = doc
        .node(node)
        .ok_or_else(|| format!("bound to `{node}.{param}`, but there is no node `{node}`"))?;
    let schema = schemas
        .schema(&n.kind)
        .ok_or_else(|| format!("bound to `{node}.{param}` of unknown kind `{}`", n.kind))?;
    let spec = schema.param(param).ok_or_else(|| {
        format!(
            "bound to `{node}.{param}`, but {} has no parameter `{param}`",
            n.kind
        )
    })?;
    if spec.kind != ParamKind::Path {
        return Err(format!(
            "bound to `{node}.{param}`, which is not a file path ({})",
            spec.kind.type_name()
        ));
    }
    match spec.reads {
        // A label map is a volume file too (frog presets read it both ways).
        Some(reads) if reads == kind || (kind, reads) == (InputKind::Labels, InputKind::Volume) => {
            Ok(())
        }
        Some(reads) => Err(format!(
            "a {kind} input bound to `{node}.{param}`, which reads a {reads} file"
        )),
        None => Err(format!(
            "bound to `{node}.{param}`, which is not a data file (it is written, or not data)"
        )),
    }
}

/// Sets every parameter bound to input `name` to `value` in the document (the editor's Data
/// panel and [`crate::Graph`] users). Errors: no such input (the message lists the inputs).
pub fn set_in_document(doc: &mut GraphDocument, name: &str, value: &str) -> Result<(), EditError> {
    let input = doc
        .inputs
        .iter()
        .find(|i| i.name == name)
        .ok_or_else(|| {
            EditError::NotFound(unknown_input(
                doc.inputs.iter().map(|i| i.name.as_str()),
                name,
            ))
        })?
        .clone();
    for (node, param) in &input.to {
        let n = doc
            .nodes
            .iter_mut()
            .find(|n| &n.id == node)
            .ok_or_else(|| EditError::NotFound(format!("input `{name}`: no node `{node}`")))?;
        n.params
            .insert(param.clone(), ron::Value::String(value.to_owned()));
    }
    Ok(())
}

/// "no input `x` (this graph's inputs are: a, b)".
pub fn unknown_input<'a>(names: impl Iterator<Item = &'a str>, name: &str) -> String {
    let names: Vec<&str> = names.collect();
    if names.is_empty() {
        format!("no input `{name}`: this graph declares no inputs")
    } else {
        format!(
            "no input `{name}` (this graph's inputs are: {})",
            names.join(", ")
        )
    }
}
