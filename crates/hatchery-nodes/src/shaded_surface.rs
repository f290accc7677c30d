//! `ShadedSurface`: Blinn–Phong shaded mesh, the standard rendering illustrations are compared with.

use crate::value::Image;
use crate::{Ctx, Value, mesh_pass};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

crate::uniform_block! {
    /// `Shading` of shaders/shaded_surface.wgsl: base colour, view-space light direction, light
    /// colour and intensity, Blinn–Phong terms.
    pub struct ShadingUniform in "shaded_surface" as "Shading" {
        pub base_color: [f32; 4],
        pub light_dir: [f32; 3],
        pub two_sided: u32,
        pub light_color: [f32; 3],
        pub intensity: f32,
        pub ambient: f32,
        pub specular: f32,
        pub shininess: f32,
        pub pad0: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `ShadedSurface`.
    pub struct ShadedSurfaceParams {
        /// surface colour (alpha = opacity)
        pub color: [f32; 4] = [0.85, 0.78, 0.7, 1.0];
        /// colour where there is no surface
        pub background: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
        /// strength of the specular highlight
        pub specular: f32 = 0.25, range(0.0, 10.0);
        /// Blinn–Phong exponent
        pub shininess: f32 = 32.0, range(1.0, 1024.0);
        /// light back faces with the flipped normal
        pub two_sided: bool = true;
    }
}

pub struct ShadedSurfaceNode;

impl Node<Value, Ctx> for ShadedSurfaceNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ShadedSurface",
            category: "Rendering",
            doc: "Blinn–Phong shaded mesh over a background colour: ambient + diffuse max(n·l, 0) + \
                  specular max(n·h, 0)^shininess, lit from the Light input. Output is premultiplied RGBA.",
            inputs: vec![
                PortSpec::input("mesh", PortType::Mesh, "the surface"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input("light", PortType::Light, "the light"),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the shaded picture",
            )],
            params: ShadedSurfaceParams::specs(),
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
        let params = ShadedSurfaceParams::read(p)?;
        let mesh = inputs.require("mesh")?.mesh("mesh")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let light = inputs.require("light")?.light("light")?.clone();
        let pipeline = ctx
            .cached("shaded_surface.pipeline", |gpu| {
                mesh_pass::mesh_pipeline(
                    gpu,
                    "shaded_surface",
                    IMAGE_FORMAT,
                    Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                )
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let gpu = &ctx.gpu;
        let l = light.view_direction(&camera);
        let shading = ShadingUniform {
            base_color: params.color,
            light_dir: l.to_array(),
            two_sided: params.two_sided.into(),
            light_color: [light.color[0], light.color[1], light.color[2]],
            intensity: light.intensity,
            ambient: light.ambient,
            specular: params.specular,
            shininess: params.shininess,
            pad0: 0.0,
        };
        let camera_buf = camera.uniform_buffer(gpu);
        let shading_buf = gpu.buffer_init(
            "shading",
            bytemuck::bytes_of(&shading),
            wgpu::BufferUsages::UNIFORM,
        );
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shaded surface"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: shading_buf.as_entire_binding(),
                },
            ],
        });
        let bg = params.background.map(f64::from);
        // Premultiplied background.
        let clear = wgpu::Color {
            r: bg[0] * bg[3],
            g: bg[1] * bg[3],
            b: bg[2] * bg[3],
            a: bg[3],
        };
        let texture =
            gpu.render_target("shaded surface", camera.width, camera.height, IMAGE_FORMAT);
        let depth =
            mesh_pass::depth_target(gpu, "shaded surface depth", camera.width, camera.height);
        let work =
            mesh_pass::draw_mesh(gpu, &pipeline, &bind_group, &mesh, &texture, clear, &depth);
        ctx.submit(work);
        Ok(vec![Value::Image(Arc::new(Image { texture }))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(ShadedSurfaceNode)
        .program("shaded_surface", shaders::mesh(shaders::part!("shaded_surface.wgsl")))
        .uniform(ShadingUniform::layout())
        .uniform_in("shaded_surface", crate::camera::CameraUniform::layout());
}
