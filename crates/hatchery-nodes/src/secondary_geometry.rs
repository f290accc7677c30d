//! `SecondaryGeometry`: intensity of user-chosen inner geometry, attenuated by the number of
//! iso-surface layers in front of it (Fischer et al. 2005, §3.2, eq. 1–2).

use crate::gbuffer::NORMAL_FORMAT;
use crate::screen_pass::MASK_FORMAT;
use crate::value::{GBuffer, Mask};
use crate::{Ctx, Value, mesh_pass};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `Secondary` of shaders/secondary_geometry.wgsl: the view-space light direction and α, β
    /// of Fischer eq. 10.
    pub struct SecondaryUniforms in "secondary_geometry" as "Secondary" {
        pub light_dir: [f32; 3],
        pub two_sided: u32,
        pub alpha: f32,
        pub beta: f32,
        pub pad0: f32,
        pub pad1: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `SecondaryGeometry`.
    pub struct SecondaryGeometryParams {
        /// how much of the secondary geometry shows behind one surface layer (α)
        pub alpha: f32 = 0.7, range(0.0, 1.0);
        /// how much shows behind two surface layers, less than behind one (β < α)
        pub beta: f32 = 0.21, range(0.0, 1.0);
        /// light back faces with the flipped normal
        pub two_sided: bool = true;
    }
}

pub struct SecondaryGeometryNode;

fn pipeline(
    gpu: &hatchery_gpu::GpuContext,
) -> Result<wgpu::RenderPipeline, hatchery_gpu::GpuError> {
    mesh_pass::mesh_pipeline_with(
        gpu,
        "secondary_geometry",
        &[Some(MASK_FORMAT.into()), Some(NORMAL_FORMAT.into())],
        mesh_pass::depth_state(),
    )
}

impl Node<Value, Ctx> for SecondaryGeometryNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "SecondaryGeometry",
            category: "Illustration",
            doc: "Renders secondary geometry S with its own depth test. Intensity I_S = max(n · lightDir, 0) \
                  (eq. 1) times 1 in front of layer 1, α between layers 1 and 2, β behind layer 2 \
                  (eq. 2, Fischer et al. 2005 §3.2). Outputs the intensity (0 where no S) and S's own \
                  G-buffer (its depth for eq. 10).",
            inputs: vec![
                PortSpec::input("mesh", PortType::Mesh, "the secondary geometry S"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input("light", PortType::Light, "the light"),
                PortSpec::input(
                    "layer1",
                    PortType::GBuffer,
                    "first iso-surface layer (GBuffer)",
                ),
                PortSpec::input(
                    "layer2",
                    PortType::GBuffer,
                    "second iso-surface layer (DepthPeel)",
                ),
            ],
            outputs: vec![
                PortSpec::output("intensity", PortType::Mask, "attenuated intensity I_S"),
                PortSpec::output("gbuffer", PortType::GBuffer, "depth and normal of S"),
            ],
            params: SecondaryGeometryParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let mesh = inputs.require("mesh")?.mesh("mesh")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let light = inputs.require("light")?.light("light")?.clone();
        let layer1 = inputs.require("layer1")?.gbuffer("layer1")?.clone();
        let layer2 = inputs.require("layer2")?.gbuffer("layer2")?.clone();
        let (w, h) = (camera.width, camera.height);
        for (port, layer) in [("layer1", &layer1), ("layer2", &layer2)] {
            if (layer.depth.width(), layer.depth.height()) != (w, h) {
                return Err(NodeError::at_port(
                    port,
                    "layer size differs from the camera's frame size",
                ));
            }
        }
        let pipeline = ctx
            .cached("secondary_geometry.pipeline", pipeline)
            .map_err(|e| NodeError::new(e.to_string()))?;
        let gpu = &ctx.gpu;
        let l = light.view_direction(&camera);
        let own = SecondaryGeometryParams::read(p)?;
        let params = SecondaryUniforms {
            light_dir: l.to_array(),
            two_sided: own.two_sided.into(),
            alpha: own.alpha,
            beta: own.beta,
            pad0: 0.0,
            pad1: 0.0,
        };
        let camera_buf = camera.uniform_buffer(gpu);
        let params_buf = gpu.buffer_init(
            "secondary",
            bytemuck::bytes_of(&params),
            wgpu::BufferUsages::UNIFORM,
        );
        let (d1, d2) = (
            layer1.depth.create_view(&Default::default()),
            layer2.depth.create_view(&Default::default()),
        );
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("secondary geometry"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&d1),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&d2),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: params_buf.as_entire_binding(),
                },
            ],
        });
        let intensity = gpu.render_target("secondary intensity", w, h, MASK_FORMAT);
        let normal = gpu.render_target("secondary normal", w, h, NORMAL_FORMAT);
        let depth = mesh_pass::depth_target(gpu, "secondary depth", w, h);
        let work = mesh_pass::draw_mesh_targets(
            gpu,
            &pipeline,
            &bind_group,
            &mesh,
            &[&intensity, &normal],
            &depth,
        );
        ctx.submit(work);
        Ok(vec![
            Value::Mask(Arc::new(Mask { texture: intensity })),
            Value::GBuffer(Arc::new(GBuffer {
                depth,
                normal,
                camera: (*camera).clone(),
            })),
        ])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(SecondaryGeometryNode)
        .program("secondary_geometry", shaders::mesh(shaders::part!("secondary_geometry.wgsl")))
        .uniform(SecondaryUniforms::layout())
        .uniform_in("secondary_geometry", crate::camera::CameraUniform::layout());
}
