//! `StyleSet`: lit-sphere maps (Bruckner & Gröller 2007, §3.1), procedural or painted (PNG).

use crate::value::StyleSet;
use crate::{Ctx, Value};
use hatchery_data::lit_sphere::{self, LitSphere};
use hatchery_graph::{
    ParamError, Widget,
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `StyleSet`.
    pub struct StyleSetParams {
        /// styles in order: name[:r,g,b] or a PNG or JPEG path
        pub styles: String = "shaded:0.9,0.85,0.8, toon2:0.85,0.3,0.25, gooch:0.6,0.7,0.9",
            widget(Widget::StyleList);
    }
}

pub struct StyleSetNode;

const SIZE: u32 = 128;

impl Node<Value, Ctx> for StyleSetNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "StyleSet",
            category: "Volume",
            doc: "A list of lit-sphere styles (sphere maps indexed by the eye-space normal, §3.1): \
                  `styles` names them in order, comma-separated — procedural ones (shaded, toon2, \
                  toon3, gooch, metal, ink_rim, flat), each optionally tinted as name:r,g,b, or a path \
                  to a square PNG or JPEG with a power-of-two size (relative to the graph file). Style k of a \
                  StyleTransferFunction is the k-th entry. Each keeps its own mip chain.",
            inputs: vec![],
            outputs: vec![PortSpec::output("styles", PortType::StyleSet, "the styles")],
            params: StyleSetParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = StyleSetParams::read(p)?;
        let mut names = Vec::new();
        let mut maps = Vec::new();
        for entry in split_entries(params.styles.as_str()) {
            let lower = entry.to_ascii_lowercase();
            let map = if [".png", ".jpg", ".jpeg"].iter().any(|e| lower.ends_with(e)) {
                let path = resolve(p, &entry);
                let picture = crate::context::read_image(&path)
                    .map_err(|e| NodeError::new(format!("style {}: {e}", path.display())))?
                    .resize_exact(SIZE, SIZE, image::imageops::FilterType::Triangle)
                    .to_rgba8();
                lit_sphere::from_rgba8(SIZE, SIZE, picture.as_raw())
                    .map_err(|e| NodeError::new(format!("style {}: {e}", path.display())))?
            } else {
                procedural(&entry)?
            };
            names.push(entry);
            maps.push(map);
        }
        if maps.is_empty() {
            return Err(NodeError::new("parameter `styles` names no style"));
        }
        Ok(vec![Value::StyleSet(Arc::new(StyleSet::new(names, maps)))])
    }
}

/// Splits "shaded:0.9,0.8,0.7, toon2, a.png" into entries: a comma followed by a name starts a
/// new entry, a comma followed by a number continues the colour.
pub fn split_entries(text: &str) -> Vec<String> {
    let mut entries: Vec<String> = Vec::new();
    for part in text.split(',') {
        let part = part.trim();
        if part.is_empty() {
            continue;
        }
        let continues_colour =
            part.parse::<f32>().is_ok() && entries.last().is_some_and(|e| e.contains(':'));
        match entries.last_mut() {
            Some(last) if continues_colour => {
                last.push(',');
                last.push_str(part);
            }
            _ => entries.push(part.to_owned()),
        }
    }
    entries
}

fn resolve(p: &Params, path: &str) -> std::path::PathBuf {
    let path = std::path::PathBuf::from(path);
    match p.base_dir() {
        Some(base) if path.is_relative() => base.join(path),
        _ => path,
    }
}

/// Default tint of a procedural style written without a colour.
pub const DEFAULT_TINT: [f32; 3] = [0.85, 0.85, 0.85];

/// A procedural entry "name[:r,g,b]" as its name and tint (each channel in [0, 1]).
/// Errors: a colour that is not three numbers in [0, 1], as a [`ParamError`] naming the entry.
pub fn parse_procedural(entry: &str) -> Result<(String, [f32; 3]), ParamError> {
    let Some((name, rgb)) = entry.split_once(':') else {
        return Ok((entry.trim().to_owned(), DEFAULT_TINT));
    };
    let values: Vec<f32> = rgb
        .split(',')
        .map(|v| v.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| ParamError(format!("style `{entry}`: colour must be r,g,b numbers")))?;
    if values.len() != 3 || values.iter().any(|v| !(0.0..=1.0).contains(v)) {
        return Err(ParamError(format!(
            "style `{entry}`: colour must be three numbers in [0, 1]"
        )));
    }
    Ok((name.trim().to_owned(), [values[0], values[1], values[2]]))
}

/// Writes a procedural entry the way [`parse_procedural`] reads it.
pub fn format_procedural(name: &str, tint: [f32; 3]) -> String {
    format!("{name}:{},{},{}", tint[0], tint[1], tint[2])
}

fn procedural(entry: &str) -> Result<LitSphere, NodeError> {
    let (name, colour) = parse_procedural(entry).map_err(NodeError::new)?;
    lit_sphere::procedural(&name, SIZE, colour).ok_or_else(|| {
        NodeError::new(format!(
            "unknown style `{name}` (procedural styles: {}; or a .png or .jpg path)",
            lit_sphere::STYLES.join(", ")
        ))
    })
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(StyleSetNode);
}

#[cfg(test)]
mod tests {
    #[test]
    fn procedural_entries_round_trip() {
        let text = super::format_procedural("gooch", [0.6, 0.7, 0.9]);
        assert_eq!(text, "gooch:0.6,0.7,0.9");
        assert_eq!(
            super::parse_procedural(&text).unwrap(),
            ("gooch".to_owned(), [0.6, 0.7, 0.9])
        );
        assert_eq!(
            super::parse_procedural("toon2").unwrap(),
            ("toon2".to_owned(), super::DEFAULT_TINT)
        );
        assert!(super::parse_procedural("toon2:1,2").is_err());
    }

    #[test]
    fn entries_split_on_names_not_on_colour_components() {
        assert_eq!(
            super::split_entries("shaded:0.9,0.8,0.7, toon2, ink_rim:0,0,0, maps/a.png"),
            vec!["shaded:0.9,0.8,0.7", "toon2", "ink_rim:0,0,0", "maps/a.png"]
        );
    }
}
