//! `TransferFunction1D`: value → colour and opacity by linear interpolation between control points.

use crate::value::TransferFunction;
use crate::{Ctx, Value};
use hatchery_data::transfer_function::{self as tf, TransferFunction1D};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct TransferFunction1DNode;

const PRESETS: &[&str] = &[
    "custom",
    "grey_ramp",
    "bone",
    "skin_bone",
    "brain_mri",
    "rainbow",
];

impl Node<Value, Ctx> for TransferFunction1DNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "TransferFunction1D",
            category: "Volume",
            doc: "A 1-D transfer function: colour and opacity (per voxel of path) per data value, linear \
                  between control points, sampled into a 256-entry table. Either a preset spread over the \
                  volume's value range, or `points` as \"value: r g b a; value: r g b a; …\" in data units.",
            inputs: vec![PortSpec::optional(
                "volume",
                PortType::Volume,
                "sets the value range of presets (and resolves relative point values)",
            )],
            outputs: vec![PortSpec::output(
                "tf",
                PortType::TransferFunction,
                "the transfer function",
            )],
            params: vec![
                ParamSpec::choice(
                    "preset",
                    "grey_ramp",
                    PRESETS,
                    "a preset, or `custom` to use `points`",
                ),
                ParamSpec::text(
                    "points",
                    "0: 0 0 0 0; 255: 1 1 1 1",
                    "control points for `custom`; a value may be relative to the connected volume (\"percentile(5): 0 0 0 0\", \"range(0.5): …\", \"otsu: …\")",
                ),
                ParamSpec::float(
                    "range_min",
                    0.0,
                    -1e12,
                    1e12,
                    "value range of presets when no volume is connected",
                ),
                ParamSpec::float(
                    "range_max",
                    255.0,
                    -1e12,
                    1e12,
                    "value range of presets when no volume is connected",
                ),
            ],
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let volume = match inputs.get("volume") {
            Some(v) => Some(v.volume("volume")?.clone()),
            None => None,
        };
        let range = match &volume {
            Some(v) => v.data.value_range,
            None => [p.f32("range_min"), p.f32("range_max")],
        };
        let points = match p.choice("preset") {
            "custom" => {
                let text = crate::relative::resolve_point_values(
                    p.text("points"),
                    volume.as_ref().map(|v| &*v.data),
                )
                .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?;
                if text != p.text("points") {
                    // The editor's curve shows relative points where they resolved to.
                    ctx.note_resolved("points", text.clone());
                }
                tf::TransferFunction1D::parse_points(&text)
                    .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?
            }
            name => TransferFunction1D::preset(name, range)
                .ok_or_else(|| NodeError::new(format!("unknown preset `{name}`")))?,
        };
        let function = TransferFunction1D::from_points(&points)
            .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?;
        Ok(vec![Value::TransferFunction(Arc::new(
            TransferFunction::Color(function),
        ))])
    }
}
