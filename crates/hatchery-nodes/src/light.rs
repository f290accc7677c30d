//! `Light`: a directional light for the shading and illustration nodes.

use crate::camera::Camera;
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Unit vector towards the light.
    pub direction: Vec3,
    /// Whether `direction` is in view space (a headlight that follows the camera) or world space.
    pub view_space: bool,
    pub color: [f32; 3],
    pub intensity: f32,
    pub ambient: f32,
}

impl Light {
    /// Unit direction towards the light in the camera's view space.
    pub fn view_direction(&self, camera: &Camera) -> Vec3 {
        if self.view_space {
            self.direction
        } else {
            camera.view.transform_vector3(self.direction).normalize()
        }
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
            params: vec![
                ParamSpec::vec3(
                    "direction",
                    [0.4, 0.5, 1.0],
                    "vector towards the light (normalised)",
                ),
                ParamSpec::choice(
                    "space",
                    "view",
                    &["view", "world"],
                    "space the direction is given in",
                ),
                ParamSpec::color("color", [1.0, 1.0, 1.0, 1.0], "light colour (alpha unused)"),
                ParamSpec::float(
                    "intensity",
                    1.0,
                    0.0,
                    100.0,
                    "scale of the diffuse and specular terms",
                ),
                ParamSpec::float("ambient", 0.15, 0.0, 1.0, "ambient term added everywhere"),
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
        let direction = Vec3::from(p.vec3("direction"));
        if direction.length_squared() < 1e-12 {
            return Err(NodeError::new(
                "parameter `direction` must not be the zero vector",
            ));
        }
        let c = p.color("color");
        let light = Light {
            direction: direction.normalize(),
            view_space: p.choice("space") == "view",
            color: [c[0], c[1], c[2]],
            intensity: p.f32("intensity"),
            ambient: p.f32("ambient"),
        };
        Ok(vec![Value::Light(Arc::new(light))])
    }
}
