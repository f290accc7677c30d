//! `DepthPeel`: the next layer of a mesh behind a previous G-buffer (Fischer et al. 2005, §3.1).

use crate::gbuffer::NORMAL_FORMAT;
use crate::value::GBuffer;
use crate::{Ctx, Value, mesh_pass};
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
        let pipeline = ctx
            .cached("depth_peel.pipeline", |gpu| {
                mesh_pass::mesh_pipeline(gpu, "depth_peel", NORMAL_FORMAT, None)
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let gpu = &ctx.gpu;
        let uniform = camera.uniform_buffer(gpu);
        let previous_view = previous.depth.create_view(&Default::default());
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("depth peel"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&previous_view),
                },
            ],
        });
        let normal = gpu.render_target("peeled normal", w, h, NORMAL_FORMAT);
        let depth = mesh_pass::depth_target(gpu, "peeled depth", w, h);
        let work = mesh_pass::draw_mesh(
            gpu,
            &pipeline,
            &bind_group,
            &mesh,
            &normal,
            wgpu::Color::TRANSPARENT,
            &depth,
        );
        ctx.submit(work);
        Ok(vec![Value::GBuffer(Arc::new(GBuffer {
            depth,
            normal,
            camera: (*camera).clone(),
        }))])
    }
}
