//! `TransferFunction2D`: colour and opacity over the data value × a second coordinate (gradient
//! magnitude or Laplacian), drawn by Kniss et al.'s rectangle and triangle widgets (Svakhine,
//! Jang, Ebert & Gaither 2005 §3.3). Baked by `hatchery_data::transfer_function_2d`; `Raycast`
//! classifies DVR samples with it (docs/transfer_functions_2d.md).

use crate::value::TransferFunction;
use crate::{Ctx, Value};
use hatchery_data::transfer_function_2d::{self as tf2d, SecondAxis};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// The second axis of a 2-D transfer function.
    pub enum Axis {
        GradientMagnitude = "gradient_magnitude",
        Laplacian = "laplacian",
        SecondField = "second_field",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `TransferFunction2D`.
    pub struct TransferFunction2DParams {
        /// the second axis: gradient_magnitude (|∇f| as a fraction of the volume's largest, 0..1),
        /// laplacian (∇²f by second differences, data units per voxel²) or second_field (the
        /// value of the field on Raycast's `second` input, its data units)
        pub axis: Axis = Axis::GradientMagnitude;
        /// first data value of the table (data units)
        pub value_min: f32 = 0.0, range(-1e12, 1e12);
        /// last data value of the table (data units)
        pub value_max: f32 = 255.0, range(-1e12, 1e12);
        /// first second-axis coordinate of the table (a fraction of the largest gradient for
        /// gradient_magnitude, data units per voxel² for laplacian, the second field's data units
        /// for second_field)
        pub second_min: f32 = 0.0, range(-1e12, 1e12);
        /// last second-axis coordinate of the table (same units as second_min)
        pub second_max: f32 = 1.0, range(-1e12, 1e12);
        /// widgets, ';'-separated: "rect V0..V1 x S0..S1: r g b a" (a box) or "tri C x S0..S1
        /// width W: r g b a" (Kniss's triangle: apex at value C and S0, W data units wide at
        /// S1, opacity falling from the centre line to the edges); overlaps take the largest
        /// opacity and the opacity-weighted mean colour
        pub widgets: String = "tri 128 x 0..1 width 60: 1 1 1 0.5";
    }
}

pub struct TransferFunction2DNode;

impl Node<Value, Ctx> for TransferFunction2DNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "TransferFunction2D",
            category: "Volume",
            doc: "A 2-D transfer function (Kniss et al. 2002; Svakhine et al. 2005 §3.3): colour and \
                  opacity per voxel of path over the data value × a second coordinate — the gradient \
                  magnitude as a fraction of the volume's largest, the Laplacian in data units per \
                  voxel², or a second field's value (Raycast's `second` input: another variable, or \
                  a vector field's |U| or |∇×U| from VectorOperator) — drawn by rectangle and triangle widgets (`widgets`) and baked into a \
                  256×256 table. `Raycast` (mode dvr) classifies each sample with it; the other \
                  consumers of `tf` refuse it (docs/transfer_functions_2d.md).",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "tf",
                PortType::TransferFunction,
                "the 2-D transfer function",
            )],
            params: TransferFunction2DParams::specs(),
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
        let params = TransferFunction2DParams::read(p)?;
        let widgets = tf2d::parse_widgets(&params.widgets)
            .map_err(|e| NodeError::new(format!("parameter `widgets`: {e}")))?;
        let axis = match params.axis {
            Axis::GradientMagnitude => SecondAxis::GradientMagnitude,
            Axis::Laplacian => SecondAxis::Laplacian,
            Axis::SecondField => SecondAxis::SecondField,
        };
        let function = tf2d::TransferFunction2D::new(
            axis,
            [params.value_min, params.value_max],
            [params.second_min, params.second_max],
            &widgets,
        )
        .map_err(|e| NodeError::new(format!("parameters `value_*`/`second_*`: {e}")))?;
        Ok(vec![Value::TransferFunction(Arc::new(
            TransferFunction::TwoD(function),
        ))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(TransferFunction2DNode);
}
