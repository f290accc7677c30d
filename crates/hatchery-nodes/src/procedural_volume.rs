//! `ProceduralVolume`: the built-in data sets, needing no file.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::procedural;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct ProceduralVolumeNode;

impl Node<Value, Ctx> for ProceduralVolumeNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ProceduralVolume",
            category: "Data",
            doc: "Analytic distance fields on a resolution³ grid over [-1, 1]³ (positive inside, iso 0 \
                  is the surface): three nested spherical shells (centre radii 0.8, 0.5, 0.2, \
                  half-thickness 0.05), a sphere, a torus in the xy plane, an engine-like block (a box with \
                  two vertical bores and a horizontal one) and the two pistons that sit in its bores.",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "the generated scalar field",
            )],
            params: vec![
                ParamSpec::choice(
                    "shape",
                    "shells",
                    &["shells", "sphere", "torus", "engine_block", "pistons"],
                    "which field to generate",
                ),
                ParamSpec::int("resolution", 96, 4, 512, "voxels along each axis"),
                ParamSpec::float(
                    "radius",
                    0.7,
                    0.01,
                    1.0,
                    "sphere radius, or torus major radius",
                ),
                ParamSpec::float("minor_radius", 0.25, 0.01, 1.0, "torus tube radius"),
            ],
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
        let res = p.int("resolution") as u32;
        let data = match p.choice("shape") {
            "sphere" => procedural::sphere(res, p.f32("radius")),
            "torus" => procedural::torus(res, p.f32("radius"), p.f32("minor_radius")),
            "engine_block" => procedural::engine_block(res),
            "pistons" => procedural::pistons(res),
            _ => procedural::shells(res),
        }
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Volume(Arc::new(Volume::new(data)))])
    }
}
