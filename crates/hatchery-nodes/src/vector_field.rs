//! `VectorField`: a vector field from three scalar volumes, its world x, y and z components
//! (velocity components saved as separate files, as many simulation codes write them).

use crate::value::vector_field::VectorField;
use crate::{Ctx, Value};
use hatchery_data::vector_field::VectorFieldData;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct VectorFieldNode;

impl Node<Value, Ctx> for VectorFieldNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "VectorField",
            category: "Data",
            doc: "A vector field U = (x, y, z) made of three scalar volumes on one grid, each the \
                  component along a world axis (e.g. velocity components a simulation wrote as \
                  separate files). Raycast's `vector` input reads it for Svakhine et al. 2005's \
                  vector enhancements; VectorOperator makes scalar fields of it (|U|, ∇·U, |∇×U|).",
            inputs: vec![
                PortSpec::input("x", PortType::Volume, "U_x, the component along world x"),
                PortSpec::input("y", PortType::Volume, "U_y, on the same grid"),
                PortSpec::input("z", PortType::Volume, "U_z, on the same grid"),
            ],
            outputs: vec![PortSpec::output(
                "field",
                PortType::VectorField,
                "the vector field",
            )],
            params: vec![],
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        _p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let [x, y, z] = ["x", "y", "z"].map(|port| inputs.require(port));
        let (x, y, z) = (x?.volume("x")?, y?.volume("y")?, z?.volume("z")?);
        for (port, c) in [("y", y), ("z", z)] {
            let what = format!("component {port}");
            crate::raycast::check_grid_at(port, &what, c.data.dims, &c.data.geometry, x)?;
        }
        let field = VectorFieldData::from_components(&x.data, &y.data, &z.data)
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::VectorField(Arc::new(VectorField::new(field)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(VectorFieldNode);
}
