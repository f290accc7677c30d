//! `ProceduralVectorField`: built-in vector fields, needing no file (see
//! `hatchery_data::vector_field`).

use crate::value::vector_field::VectorField;
use crate::{Ctx, Value};
use hatchery_data::vector_field;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// Which field to generate.
    pub enum Shape { Convection = "convection", Abc = "abc" }
}

hatchery_graph::node_params! {
    /// Parameters of `ProceduralVectorField`.
    pub struct ProceduralVectorFieldParams {
        /// which field: convection (the velocity of Rayleigh–Bénard rolls, ProceduralVolume
        /// convection's flow) or abc (the Arnold–Beltrami–Childress flow, whose curl is π·U)
        pub shape: Shape = Shape::Convection;
        /// voxels along each axis
        pub resolution: u32 = 96, range(4, 512);
        /// abc: the coefficients A, B, C
        pub abc: [f32; 3] = [1.0, 0.8, 0.6];
    }
}

pub struct ProceduralVectorFieldNode;

impl Node<Value, Ctx> for ProceduralVectorFieldNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ProceduralVectorField",
            category: "Data",
            doc: "Analytic vector fields on a resolution³ grid over [-1, 1]³ (the grid of \
                  ProceduralVolume): convection, the velocity of Rayleigh–Bénard convection rolls \
                  (U = (∂ψ/∂y, −∂ψ/∂x, 0) of ψ = a(z)·sin(2π(x + 1))·sin(π(y + 1)/2), four rolls \
                  across x, divergence-free), the flow of ProceduralVolume's convection \
                  temperature; abc, the Arnold–Beltrami–Childress flow U = (A sin πz + C cos πy, \
                  B sin πx + A cos πz, C sin πy + B cos πx), a Beltrami field (∇×U = π·U).",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "field",
                PortType::VectorField,
                "the generated vector field",
            )],
            params: ProceduralVectorFieldParams::specs(),
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
        let params = ProceduralVectorFieldParams::read(p)?;
        let res = params.resolution;
        let [a, b, c] = params.abc;
        let data = match params.shape {
            Shape::Convection => vector_field::convection_rolls(res),
            Shape::Abc => vector_field::abc_flow(res, a, b, c),
        }
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::VectorField(Arc::new(VectorField::new(data)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(ProceduralVectorFieldNode);
}
