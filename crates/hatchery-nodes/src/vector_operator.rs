//! `VectorOperator`: Svakhine, Jang, Ebert & Gaither 2005, Table 1's operators, a scalar field of
//! a vector field (`hatchery_data::vector_field`): to render, to classify with (a 2-D transfer
//! function's second field) or to enhance with.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::vector_field::Operator as DataOperator;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// Which operator.
    pub enum Operator {
        Magnitude = "magnitude",
        Divergence = "divergence",
        CurlMagnitude = "curl_magnitude",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `VectorOperator`.
    pub struct VectorOperatorParams {
        /// magnitude |U| (U's units), divergence ∇·U or curl_magnitude |∇×U| (U's units per
        /// world unit; Svakhine et al. 2005 Table 1)
        pub operator: Operator = Operator::Magnitude;
    }
}

pub struct VectorOperatorNode;

impl Node<Value, Ctx> for VectorOperatorNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "VectorOperator",
            category: "Volume",
            doc: "A scalar field of a vector field by one of Svakhine et al. 2005's Table 1 \
                  operators: the magnitude |U|, the divergence ∇·U or the curl's magnitude |∇×U| \
                  (vortex cores), on the field's grid. Derivatives are central differences (one-sided \
                  at the border) with respect to world coordinates, so rotated and anisotropic grids \
                  give the field's own numbers. Computed once on the CPU (data preparation). Render it, \
                  or give it to Raycast's `second` input: a 2-D transfer function over value × it, or \
                  enhancement by its gradient.",
            inputs: vec![PortSpec::input(
                "field",
                PortType::VectorField,
                "the vector field U",
            )],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "the operator's value at every voxel",
            )],
            params: VectorOperatorParams::specs(),
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
        let params = VectorOperatorParams::read(p)?;
        let field = inputs.require("field")?.vector_field("field")?;
        let op = match params.operator {
            Operator::Magnitude => DataOperator::Magnitude,
            Operator::Divergence => DataOperator::Divergence,
            Operator::CurlMagnitude => DataOperator::CurlMagnitude,
        };
        let volume = field
            .data
            .apply(op)
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Volume(Arc::new(Volume::new(volume)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(VectorOperatorNode);
}
