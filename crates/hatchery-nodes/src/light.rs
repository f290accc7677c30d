//! `Light`: a directional light for the shading and illustration nodes.

use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub use crate::value::light::Light;

hatchery_graph::param_choice! {
    /// The space a light direction is given in.
    pub enum LightSpace {
        View = "view",
        World = "world",
    }
}

hatchery_graph::node_params! {
    /// The parameters of `Light`.
    pub struct LightParams {
        /// vector towards the light (normalised)
        pub direction: [f32; 3] = [0.4, 0.5, 1.0];
        /// space the direction is given in
        pub space: LightSpace = LightSpace::View;
        /// light colour (alpha unused)
        pub color: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
        /// scale of the diffuse and specular terms
        pub intensity: f32 = 1.0, range(0.0, 100.0);
        /// ambient term added everywhere
        pub ambient: f32 = 0.15, range(0.0, 1.0);
    }
}

pub struct LightNode;

impl Node<Value, Ctx> for LightNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Light",
            category: "Scene",
            doc: "Directional light. In view space the light follows the camera (the usual choice for \
                  illustration); in world space it stays fixed to the data.",
            inputs: vec![],
            outputs: vec![PortSpec::output("light", PortType::Light, "the light")],
            params: LightParams::specs(),
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
        let p = LightParams::read(p)?;
        let direction = Vec3::from(p.direction);
        if direction.length_squared() < 1e-12 {
            return Err(NodeError::new(
                "parameter `direction` must not be the zero vector",
            ));
        }
        let c = p.color;
        let light = Light {
            direction: direction.normalize(),
            view_space: p.space == LightSpace::View,
            color: [c[0], c[1], c[2]],
            intensity: p.intensity,
            ambient: p.ambient,
        };
        Ok(vec![Value::Light(Arc::new(light))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(LightNode);
}
