//! `GBuffer`: renders a mesh's depth and view-space normals (Fischer et al. 2005, §3.1).

use crate::camera::Camera;
use crate::value::{GBuffer, Mesh};
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
        let layer = render_layer(ctx, &mesh, &camera, None)?;
        Ok(vec![Value::GBuffer(Arc::new(layer))])
    }
}

/// Rasterises one G-buffer layer of `mesh`: the nearest surface, or with `previous` the nearest
/// surface strictly behind that layer (depth peeling). Shared by GBuffer and DepthPeel.
pub fn render_layer(
    ctx: &mut Ctx,
    mesh: &Mesh,
    camera: &Camera,
    previous: Option<&GBuffer>,
) -> Result<GBuffer, NodeError> {
    let (program, key) = match previous {
        None => ("gbuffer", "gbuffer.pipeline"),
        Some(_) => ("depth_peel", "depth_peel.pipeline"),
    };
    let pipeline = ctx
        .cached(key, |gpu| {
            mesh_pass::mesh_pipeline(gpu, program, NORMAL_FORMAT, None)
        })
        .map_err(|e| NodeError::new(e.to_string()))?;
    let gpu = &ctx.gpu;
    let (w, h) = (camera.width, camera.height);
    let uniform = camera.uniform_buffer(gpu);
    let previous_view = previous.map(|p| p.depth.create_view(&Default::default()));
    let mut entries = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: uniform.as_entire_binding(),
    }];
    if let Some(view) = &previous_view {
        entries.push(wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::TextureView(view),
        });
    }
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(program),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let normal = gpu.render_target(program, w, h, NORMAL_FORMAT);
    let depth = mesh_pass::depth_target(gpu, program, w, h);
    let work = mesh_pass::draw_mesh(
        gpu,
        &pipeline,
        &bind_group,
        mesh,
        &normal,
        wgpu::Color::TRANSPARENT,
        &depth,
    );
    ctx.submit(work);
    Ok(GBuffer {
        depth,
        normal,
        camera: camera.clone(),
    })
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(GBufferNode)
        .program("gbuffer", shaders::mesh(shaders::part!("gbuffer.wgsl")))
        .uniform(crate::camera::CameraUniform::layout());
}
