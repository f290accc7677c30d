//! `TransferFunction1D`: value → colour and opacity by linear interpolation between control points.

use crate::value::TransferFunction;
use crate::{Ctx, Value};
use hatchery_data::transfer_function::{self as tf, TransferFunction1D};
use hatchery_graph::{
    Widget,
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// A preset, or `custom` to use `points`.
    pub enum Preset {
        Custom = "custom",
        GreyRamp = "grey_ramp",
        Bone = "bone",
        SkinBone = "skin_bone",
        BrainMri = "brain_mri",
        Rainbow = "rainbow",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `TransferFunction1D`.
    pub struct TransferFunction1DParams {
        /// a preset, or `custom` to use `points`
        pub preset: Preset = Preset::GreyRamp;
        /// control points for `custom`; a value may be relative to the connected volume
        /// ("percentile(5): 0 0 0 0", "range(0.5): …", "otsu: …")
        pub points: String = "0: 0 0 0 0; 255: 1 1 1 1", widget(Widget::TransferFunction);
        /// value range of presets when no volume is connected
        pub range_min: f32 = 0.0, range(-1e12, 1e12);
        /// value range of presets when no volume is connected
        pub range_max: f32 = 255.0, range(-1e12, 1e12);
    }
}

pub struct TransferFunction1DNode;

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
            params: TransferFunction1DParams::specs(),
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
        let params = TransferFunction1DParams::read(p)?;
        let volume = match inputs.get("volume") {
            Some(v) => Some(v.volume("volume")?.clone()),
            None => None,
        };
        let range = match &volume {
            Some(v) => v.data.value_range,
            None => [params.range_min, params.range_max],
        };
        let points = match params.preset {
            Preset::Custom => {
                let text = crate::relative::resolve_point_values(
                    params.points.as_str(),
                    volume.as_ref().map(|v| &*v.data),
                )
                .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?;
                if text != params.points.as_str() {
                    // The editor's curve shows relative points where they resolved to.
                    ctx.note_resolved("points", text.clone());
                }
                tf::TransferFunction1D::parse_points(&text)
                    .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?
            }
            preset => TransferFunction1D::preset(preset.name(), range)
                .ok_or_else(|| NodeError::new(format!("unknown preset `{}`", preset.name())))?,
        };
        let function = TransferFunction1D::from_points(&points)
            .map_err(|e| NodeError::new(format!("parameter `points`: {e}")))?;
        Ok(vec![Value::TransferFunction(Arc::new(
            TransferFunction::Color(function),
        ))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(TransferFunction1DNode);
}
