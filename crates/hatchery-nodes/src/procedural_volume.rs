//! `ProceduralVolume`: the built-in data sets, needing no file.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::procedural;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// Which field to generate.
    pub enum Shape {
        Shells = "shells",
        Sphere = "sphere",
        Torus = "torus",
        EngineBlock = "engine_block",
        Pistons = "pistons",
        Plume = "plume",
        Convection = "convection",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `ProceduralVolume`.
    pub struct ProceduralVolumeParams {
        /// which field to generate
        pub shape: Shape = Shape::Shells;
        /// voxels along each axis
        pub resolution: u32 = 96, range(4, 512);
        /// sphere radius, or torus major radius
        pub radius: f32 = 0.7, range(0.01, 1.0);
        /// torus tube radius
        pub minor_radius: f32 = 0.25, range(0.01, 1.0);
    }
}

pub struct ProceduralVolumeNode;

impl Node<Value, Ctx> for ProceduralVolumeNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ProceduralVolume",
            category: "Data",
            doc: "Analytic distance fields on a resolution³ grid over [-1, 1]³ (positive inside, iso 0 \
                  is the surface): three nested spherical shells (centre radii 0.8, 0.5, 0.2, \
                  half-thickness 0.05), a sphere, a torus in the xy plane, an engine-like block (a box with \
                  two vertical bores and a horizontal one) and the two pistons that sit in its bores; and one \
                  density field, not a distance: plume, the air around a hot plume rising along +y \
                  from a small heated ball (1 in still air, lower where it is hot), a subject for \
                  Schlieren; and convection, the temperature of Rayleigh–Bénard convection rolls \
                  between a hot floor (y = −1, 1) and a cold lid (y = 1, 0), whose velocity \
                  ProceduralVectorField's convection gives (Svakhine et al. 2005 Fig. 4's subject).",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "the generated scalar field",
            )],
            params: ProceduralVolumeParams::specs(),
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
        let params = ProceduralVolumeParams::read(p)?;
        let res = params.resolution;
        let data = match params.shape {
            Shape::Sphere => procedural::sphere(res, params.radius),
            Shape::Torus => procedural::torus(res, params.radius, params.minor_radius),
            Shape::EngineBlock => procedural::engine_block(res),
            Shape::Pistons => procedural::pistons(res),
            Shape::Plume => procedural::plume(res),
            Shape::Convection => procedural::convection(res),
            Shape::Shells => procedural::shells(res),
        }
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Volume(Arc::new(Volume::new(data)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(ProceduralVolumeNode);
}
