//! Controls (format version 3): the parameters a figure's reader may change, declared in the
//! graph so that every figure made from it offers the same ones (`hatchery export-web` shows them
//! as sliders, toggles, menus and colour pickers; docs/web.md).
//!
//! `controls: [(node: "hatching", param: "theta", label: "hatching angle", min: Some(0.0),
//! max: Some(90.0))]`.
//! A control names a number, integer, switch, choice or colour parameter; a number's slider
//! spans the parameter's own range unless `min`/`max` narrow it.

pub use crate::document::ControlDoc;
use crate::document::{GraphDocument, Source};
use crate::error::{ErrorKind, GraphError};
use crate::param::ParamKind;
use crate::schema::SchemaLookup;

/// What a control shows: a slider, a switch, a menu or a colour picker.
#[derive(Clone, Debug, PartialEq)]
pub enum ControlKind {
    /// A slider from `min` to `max` (integers step by one).
    Slider {
        min: f64,
        max: f64,
        integer: bool,
    },
    Toggle,
    Menu(&'static [&'static str]),
    Colour,
}

/// A validated control.
#[derive(Clone, Debug, PartialEq)]
pub struct Control {
    pub node: String,
    pub param: String,
    /// What the page writes next to it (the parameter's name where the file gives none).
    pub label: String,
    pub kind: ControlKind,
}

/// Checks the document's controls against its nodes; returns the valid ones and pushes one
/// error per wrong one (naming the control's node and parameter, at its line).
pub fn check(
    doc: &GraphDocument,
    source: &Source,
    schemas: &dyn SchemaLookup,
    errors: &mut Vec<GraphError>,
) -> Vec<Control> {
    let mut valid = Vec::new();
    for (index, control) in doc.controls.iter().enumerate() {
        let name = format!("{}.{}", control.node, control.param);
        let at = crate::locate::control_offset(&source.text, &control.node, &control.param);
        let fail = |errors: &mut Vec<GraphError>, reason: String| {
            errors.push(source.error(
                at,
                ErrorKind::BadControl {
                    control: name.clone(),
                    reason,
                },
            ))
        };
        if doc.controls[..index]
            .iter()
            .any(|c| (&c.node, &c.param) == (&control.node, &control.param))
        {
            fail(errors, "declared twice".into());
            continue;
        }
        match control_kind(doc, schemas, control) {
            Ok(kind) => valid.push(Control {
                node: control.node.clone(),
                param: control.param.clone(),
                label: if control.label.is_empty() {
                    control.param.replace('_', " ")
                } else {
                    control.label.clone()
                },
                kind,
            }),
            Err(reason) => fail(errors, reason),
        }
    }
    valid
}

fn control_kind(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    control: &ControlDoc,
) -> Result<ControlKind, String> {
    let (node, param) = (&control.node, &control.param);
    let n = doc
        .node(node)
        .ok_or_else(|| format!("there is no node `{node}`"))?;
    let schema = schemas
        .schema(&n.kind)
        .ok_or_else(|| format!("node `{node}` is of unknown kind `{}`", n.kind))?;
    let spec = schema.param(param).ok_or_else(|| {
        format!(
            "{} has no parameter `{param}` (its parameters are: {})",
            n.kind,
            schema
                .params
                .iter()
                .map(|p| p.name)
                .collect::<Vec<_>>()
                .join(", ")
        )
    })?;
    let range = |lo: f64, hi: f64, integer: bool| {
        let min = control.min.unwrap_or(lo);
        let max = control.max.unwrap_or(hi);
        if min.is_nan() || max.is_nan() || min >= max || min < lo || max > hi {
            return Err(format!(
                "min {min} and max {max} must be increasing and within the parameter's range \
                 [{lo}, {hi}]"
            ));
        }
        if integer && (min.fract() != 0.0 || max.fract() != 0.0) {
            return Err(format!(
                "min {min} and max {max} must be whole numbers for an integer"
            ));
        }
        Ok(ControlKind::Slider { min, max, integer })
    };
    let no_range = || {
        if control.min.is_some() || control.max.is_some() {
            Err(format!(
                "`min` and `max` are for numbers; `{param}` is a {} parameter",
                spec.kind.type_name()
            ))
        } else {
            Ok(())
        }
    };
    match spec.kind {
        ParamKind::Float { min, max } => range(min, max, false),
        ParamKind::Int { min, max } => range(min as f64, max as f64, true),
        ParamKind::Bool => no_range().map(|()| ControlKind::Toggle),
        ParamKind::Choice(names) => no_range().map(|()| ControlKind::Menu(names)),
        ParamKind::Color => no_range().map(|()| ControlKind::Colour),
        ParamKind::Vec3 | ParamKind::Path | ParamKind::Text => Err(format!(
            "`{param}` is a {} parameter; controls are for numbers, switches, choices and colours",
            spec.kind.type_name()
        )),
    }
}
