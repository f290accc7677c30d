//! `ObjectStyles`: the object table of a segmented volume — for every object its transfer
//! function, rendering mode and local compositing mode (two-level volume rendering, Hadwiger
//! §2.2–2.4) and an importance value (importance-driven rendering).

use crate::value::{Compositing, ObjectStyle, RenderMode, TransferFunction};
use crate::{Ctx, Value};
use hatchery_data::transfer_function::{TransferFunction1D, TransferFunction1D as Tf};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamError, Params, PortSpec, PortType, Widget,
    executor::Node,
};
use std::sync::Arc;

const MODES: &[(&str, RenderMode)] = &[
    ("dvr", RenderMode::Dvr),
    ("shaded_dvr", RenderMode::ShadedDvr),
    ("tone", RenderMode::Tone),
    ("contours", RenderMode::Contours),
    ("mip", RenderMode::Mip),
    ("iso", RenderMode::Iso),
];
const COMPOSITING: &[(&str, Compositing)] = &[
    ("over", Compositing::Over),
    ("mip", Compositing::Mip),
    ("iso", Compositing::Iso),
    ("sum", Compositing::Sum),
];

/// One row of the `objects` table before its transfer function is resolved.
#[derive(Debug, PartialEq)]
pub struct Row {
    pub id: u16,
    pub mode: RenderMode,
    pub compositing: Compositing,
    /// `tf=NAME`: a preset name, or `1`–`3` for the inputs tf1–tf3; `None`: the `tf` input,
    /// else the grey ramp.
    pub tf: Option<String>,
    pub iso: Option<f32>,
    pub importance: f32,
    pub enabled: bool,
}

/// Parses "ID: mode compositing [tf=…] [iso=…] [importance=…] [off]; …". Errors name the row.
/// Rows whose objects are named ("liver: iso iso; …") with the labels' ids put in.
pub fn named_rows(
    text: &str,
    objects: &std::collections::BTreeMap<u16, String>,
) -> Result<String, NodeError> {
    hatchery_data::segmentation::ids_for_names(text, ';', Some(':'), objects)
        .map_err(|e| NodeError::new(format!("`objects`: {e}")))
}

/// Errors: [`ParamError`] naming the row that does not parse.
pub fn parse_rows(text: &str) -> Result<Vec<Row>, ParamError> {
    let mut rows: Vec<Row> = Vec::new();
    for (n, part) in text.split(';').map(str::trim).enumerate() {
        if part.is_empty() {
            continue;
        }
        let at = |m: String| ParamError(format!("object row {} `{part}`: {m}", n + 1));
        let (id, rest) = part
            .split_once(':')
            .ok_or_else(|| at("expected `ID: mode compositing …`".into()))?;
        let id: u16 = id
            .trim()
            .parse()
            .ok()
            .filter(|&id| id > 0)
            .ok_or_else(|| at(format!("`{}` is not an object id 1–65535", id.trim())))?;
        if rows.iter().any(|r| r.id == id) {
            return Err(at(format!("object {id} is listed twice")));
        }
        let mut words = rest.split_whitespace();
        let mode = pick(words.next(), MODES, "rendering mode").map_err(at)?;
        let compositing = pick(words.next(), COMPOSITING, "compositing mode").map_err(at)?;
        let mut row = Row {
            id,
            mode,
            compositing,
            tf: None,
            iso: None,
            importance: 1.0,
            enabled: true,
        };
        for word in words {
            let number = |v: &str| {
                v.parse::<f32>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| at(format!("`{word}`: not a number")))
            };
            match word.split_once('=') {
                Some(("tf", v)) => row.tf = Some(v.to_string()),
                Some(("iso", v)) => row.iso = Some(number(v)?),
                Some(("importance", v)) => row.importance = number(v)?,
                None if word == "off" => row.enabled = false,
                _ => {
                    return Err(at(format!(
                        "unknown setting `{word}` (tf=…, iso=…, importance=…, off)"
                    )));
                }
            }
        }
        rows.push(row);
    }
    Ok(rows)
}

/// The names of the rendering modes and compositing modes, in table order.
pub fn mode_names() -> Vec<&'static str> {
    MODES.iter().map(|(n, _)| *n).collect()
}
pub fn compositing_names() -> Vec<&'static str> {
    COMPOSITING.iter().map(|(n, _)| *n).collect()
}
fn name_of<T: PartialEq>(table: &[(&'static str, T)], value: &T) -> &'static str {
    table
        .iter()
        .find(|(_, v)| v == value)
        .map_or("?", |(n, _)| *n)
}
/// The rendering mode called `name`.
pub fn mode_named(name: &str) -> Option<RenderMode> {
    MODES.iter().find(|(n, _)| *n == name).map(|(_, m)| *m)
}
/// The compositing mode called `name`.
pub fn compositing_named(name: &str) -> Option<Compositing> {
    COMPOSITING
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, m)| *m)
}

/// The `objects` text of rows (what `parse_rows` reads back).
pub fn format_rows(rows: &[Row]) -> String {
    rows.iter()
        .map(|r| {
            let mut text = format!(
                "{}: {} {}",
                r.id,
                name_of(MODES, &r.mode),
                name_of(COMPOSITING, &r.compositing)
            );
            if let Some(tf) = &r.tf {
                text += &format!(" tf={tf}");
            }
            if let Some(iso) = r.iso {
                text += &format!(" iso={iso}");
            }
            if r.importance != 1.0 {
                text += &format!(" importance={}", r.importance);
            }
            if !r.enabled {
                text += " off";
            }
            text
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The value of `word` in a (name, value) table; errors list the names.
fn pick<T: Copy>(word: Option<&str>, table: &[(&str, T)], what: &str) -> Result<T, String> {
    let word = word.ok_or_else(|| format!("missing the {what}"))?;
    table
        .iter()
        .find(|(name, _)| *name == word)
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
            format!("unknown {what} `{word}` (one of {})", names.join(", "))
        })
}

hatchery_graph::node_params! {
    /// Parameters of `ObjectStyles`.
    pub struct ObjectStylesParams {
        /// "ID: mode compositing [tf=…] [iso=…] [importance=…] [off]; …"
        pub objects: String = "1: shaded_dvr over", widget(Widget::ObjectTable);
    }
}

pub struct ObjectStylesNode;

impl Node<Value, Ctx> for ObjectStylesNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ObjectStyles",
            category: "Volume",
            doc: "The object table of a segmented volume for TwoLevelRaycast: one row per object, \
                  \"ID: mode compositing [tf=…] [iso=…] [importance=…] [off]; …\". Rendering \
                  modes: dvr, shaded_dvr, tone (cool-to-warm by N·L), contours (gradient \
                  magnitude × (1 − |N·V|)^8), mip, iso. Local compositing: over, mip, iso \
                  (first hit of iso=…), sum. tf=PRESET uses a TransferFunction1D preset over the \
                  volume's range, tf=1…3 the inputs tf1–tf3; default: the `tf` input, else the \
                  grey ramp. Objects not listed are not drawn. Names come from the labels.",
            inputs: vec![
                PortSpec::input(
                    "labels",
                    PortType::Labels,
                    "the segmented volume (names, ids)",
                ),
                PortSpec::optional("volume", PortType::Volume, "value range for presets"),
                PortSpec::optional(
                    "tf",
                    PortType::TransferFunction,
                    "default transfer function",
                ),
                PortSpec::optional("tf1", PortType::TransferFunction, "transfer function tf=1"),
                PortSpec::optional("tf2", PortType::TransferFunction, "transfer function tf=2"),
                PortSpec::optional("tf3", PortType::TransferFunction, "transfer function tf=3"),
            ],
            outputs: vec![PortSpec::output(
                "styles",
                PortType::ObjectStyles,
                "per-object transfer function, rendering and compositing mode",
            )],
            params: ObjectStylesParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = ObjectStylesParams::read(p)?;
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        let range = match inputs.get("volume") {
            Some(v) => v.volume("volume")?.data.value_range,
            None => [0.0, 255.0],
        };
        let color_tf = |port: &str| -> Result<Option<TransferFunction1D>, NodeError> {
            match inputs.get(port) {
                None => Ok(None),
                Some(v) => match v.transfer_function(port)?.as_ref() {
                    TransferFunction::Color(f) => Ok(Some(f.clone())),
                    TransferFunction::Style { .. } => Err(NodeError::at_port(
                        port,
                        "a style transfer function: ObjectStyles takes colour transfer functions",
                    )),
                    TransferFunction::TwoD(_) => Err(NodeError::at_port(
                        port,
                        "a 2-D transfer function: ObjectStyles takes 1-D colour transfer functions",
                    )),
                },
            }
        };
        let preset = |name: &str| -> Result<TransferFunction1D, String> {
            let points = Tf::preset(name, range).ok_or_else(|| {
                format!(
                    "unknown transfer function `{name}` (a preset: {}, or 1–3 for tf1–tf3)",
                    hatchery_data::transfer_function::PRESETS.join(", ")
                )
            })?;
            Tf::from_points(&points).map_err(|e| e.to_string())
        };
        let default = match color_tf("tf")? {
            Some(f) => f,
            None => preset("grey_ramp").map_err(NodeError::new)?,
        };
        let rows = parse_rows(&named_rows(params.objects.as_str(), &labels.data.objects)?)
            .map_err(|e| NodeError::new(format!("`objects`: {e}")))?;
        let mut styles = Vec::new();
        for row in rows {
            let tf = match row.tf.as_deref() {
                None => default.clone(),
                Some(k @ ("1" | "2" | "3")) => color_tf(&format!("tf{k}"))?.ok_or_else(|| {
                    NodeError::new(format!(
                        "`objects`: object {} uses tf={k}: connect input tf{k}",
                        row.id
                    ))
                })?,
                Some(name) => preset(name)
                    .map_err(|e| NodeError::new(format!("`objects`, object {}: {e}", row.id)))?,
            };
            let name = labels
                .data
                .objects
                .get(&row.id)
                .cloned()
                .unwrap_or_else(|| format!("object {} (not in the labels)", row.id));
            styles.push(ObjectStyle {
                id: row.id,
                name,
                enabled: row.enabled,
                iso: row.iso.unwrap_or((tf.domain[0] + tf.domain[1]) * 0.5),
                tf,
                mode: row.mode,
                compositing: row.compositing,
                importance: row.importance,
            });
        }
        Ok(vec![Value::ObjectStyles(Arc::new(styles))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(ObjectStylesNode);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_parse_with_settings_and_errors_name_the_row() {
        let rows = parse_rows(
            "1: tone over; 7: contours mip tf=skin importance=0.2; 3: iso iso iso=80 off",
        )
        .unwrap();
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[1].id, 7);
        assert_eq!(rows[1].mode, RenderMode::Contours);
        assert_eq!(rows[1].compositing, Compositing::Mip);
        assert_eq!(rows[1].tf.as_deref(), Some("skin"));
        assert_eq!(rows[1].importance, 0.2);
        assert_eq!(rows[2].iso, Some(80.0));
        assert!(!rows[2].enabled);
        let e = parse_rows("1: tone over; 2: glow over").unwrap_err().to_string();
        assert!(e.contains("row 2") && e.contains("glow"), "{e}");
        assert!(
            parse_rows("1: tone over; 1: dvr over")
                .unwrap_err().to_string()
                .contains("twice")
        );
        assert!(parse_rows("0: tone over").is_err());
    }

    #[test]
    fn formatted_rows_read_back_as_the_same_rows() {
        let text =
            "13: tone over tf=1; 10: iso iso tf=2 iso=0.5 importance=0.25 off; 11: contours mip";
        let rows = parse_rows(text).unwrap();
        assert_eq!(format_rows(&rows), text);
        assert_eq!(parse_rows(&format_rows(&rows)).unwrap(), rows);
    }
}
