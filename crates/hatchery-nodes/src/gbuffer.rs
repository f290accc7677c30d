//! `GBuffer`: renders a mesh's depth and view-space normals (Fischer et al. 2005, §3.1).

use crate::value::GBuffer;
use crate::{Ctx, Value, mesh_pass};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

pub struct GBufferNode;

impl Node<Value, Ctx> for GBufferNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "GBuffer",
            category: "Rendering",
            doc: "Rasterises a mesh into a G-buffer: window-space depth in [0, 1] (1 where empty) and the \
                  view-space unit normal with coverage in w. The first layer of depth peeling.",
            inputs: vec![
                PortSpec::input("mesh", PortType::Mesh, "the surface"),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![PortSpec::output(
                "gbuffer",
                PortType::GBuffer,
                "depth + normal of the nearest surface",
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
        let pipeline = ctx
            .cached("gbuffer.pipeline", |gpu| {
                mesh_pass::mesh_pipeline(gpu, "gbuffer", NORMAL_FORMAT, None)
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let gpu = &ctx.gpu;
        let (w, h) = (camera.width, camera.height);
        let uniform = camera.uniform_buffer(gpu);
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gbuffer"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        let normal = gpu.render_target("gbuffer normal", w, h, NORMAL_FORMAT);
        let depth = mesh_pass::depth_target(gpu, "gbuffer depth", w, h);
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
        let camera = (*camera).clone();
        Ok(vec![Value::GBuffer(Arc::new(GBuffer {
            depth,
            normal,
            camera,
        }))])
    }
}
