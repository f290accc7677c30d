//! `DepthPeel`: the next layer of a mesh behind a previous G-buffer (Fischer et al. 2005, §3.1).

use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct DepthPeelNode;

impl Node<Value, Ctx> for DepthPeelNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "DepthPeel",
            category: "Rendering",
            doc: "Depth peeling (Fischer et al. 2005, §3.1): rasterises the mesh again, keeping only \
                  fragments strictly behind the previous layer's depth, then the nearest of those. \
                  Chain peels for layers 3, 4, …",
            inputs: vec![
                PortSpec::input(
                    "mesh",
                    PortType::Mesh,
                    "the surface (the same mesh as the previous layer)",
                ),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input(
                    "previous",
                    PortType::GBuffer,
                    "the layer in front (GBuffer or another DepthPeel)",
                ),
            ],
            outputs: vec![PortSpec::output(
                "gbuffer",
                PortType::GBuffer,
                "depth + normal of the next layer",
            )],
            params: vec![],
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        _p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let mesh = inputs.require("mesh")?.mesh("mesh")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let previous = inputs.require("previous")?.gbuffer("previous")?.clone();
        let (w, h) = (camera.width, camera.height);
        if (previous.depth.width(), previous.depth.height()) != (w, h) {
            return Err(NodeError::at_port(
                "previous",
                "layer size differs from the camera's frame size",
            ));
        }
        let layer = crate::gbuffer::render_layer(ctx, &mesh, &camera, Some(&previous))?;
        Ok(vec![Value::GBuffer(Arc::new(layer))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(DepthPeelNode)
        .program("depth_peel", shaders::mesh(shaders::part!("depth_peel.wgsl")))
        .uniform_in("depth_peel", crate::camera::CameraUniform::layout());
}
