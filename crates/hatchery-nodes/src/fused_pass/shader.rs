//! The fragment or compute shader of a fused group, written stage by stage: each stage's call
//! with its arguments (texels at the pixel, textures, constants, earlier stages' values), the
//! textures bound once, the uniform blocks in one struct, an output per kept value.

use super::{Arg, Stage, StageInputs, fusable};
use crate::kernel::Kernel;
use crate::screen_pass::{self, IMAGE_FORMAT, MASK_FORMAT};
use crate::{Ctx, Value};
use hatchery_graph::fusion::{Member, Source};
use hatchery_graph::{NodeError, NodeSchema, PortType};

/// One texture bound by the pass and its WGSL type.
pub(super) struct Binding {
    pub(super) texture: wgpu::Texture,
    wgsl: &'static str,
}

/// The fragment shader of a group, built stage by stage.
#[derive(Default)]
pub(super) struct Shader {
    libraries: Vec<&'static str>,
    uniform_fields: Vec<String>,
    pub(super) uniform_bytes: Vec<u8>,
    pub(super) bindings: Vec<Binding>,
    body: Vec<String>,
    /// (member, format) per colour target.
    pub(super) targets: Vec<(usize, wgpu::TextureFormat)>,
}

impl Shader {
    /// The name of `texture` bound as `wgsl` (bound once however many stages read it).
    fn bind(&mut self, texture: &wgpu::Texture, wgsl: &'static str) -> String {
        let index = match self
            .bindings
            .iter()
            .position(|b| b.texture == *texture && b.wgsl == wgsl)
        {
            Some(i) => i,
            None => {
                self.bindings.push(Binding {
                    texture: texture.clone(),
                    wgsl,
                });
                self.bindings.len() - 1
            }
        };
        format!("t{index}")
    }

    /// Appends member `i`'s call.
    fn stage(
        &mut self,
        ctx: &Ctx,
        i: usize,
        member: &Member<'_, Value>,
        schema: &NodeSchema,
        stage: Stage,
        read_later: bool,
    ) -> Result<(), NodeError> {
        if !self.libraries.contains(&stage.library) {
            self.libraries.push(stage.library);
        }
        let mut args = vec!["p".to_owned()];
        if let Some((wgsl_struct, bytes)) = stage.uniform {
            // Each block at the next multiple of 16 bytes, on both sides (WGSL's uniform
            // layout wants struct members there; `@align` says so rather than relying on it).
            self.uniform_bytes
                .resize(self.uniform_bytes.len().next_multiple_of(16), 0);
            self.uniform_fields
                .push(format!("@align(16) u{i}: {wgsl_struct}"));
            self.uniform_bytes.extend_from_slice(&bytes);
            args.push(format!("fused.u{i}"));
        }
        for arg in stage.args {
            args.push(match arg {
                Arg::At(port) => self.at(ctx, member, schema, port, Part::Both)?,
                Arg::NormalAt(port) => self.at(ctx, member, schema, port, Part::Normal)?,
                Arg::DepthAt(port) => self.at(ctx, member, schema, port, Part::Depth)?,
                Arg::Textures(port) => {
                    let index = port_index(schema, port)?;
                    match &member.inputs[index] {
                        Source::External(Value::GBuffer(g)) => {
                            screen_pass::frame_sized(ctx, port, &g.depth)?;
                            screen_pass::frame_sized(ctx, port, &g.normal)?;
                            let depth = self.bind(&g.depth, "texture_depth_2d");
                            let normal = self.bind(&g.normal, "texture_2d<f32>");
                            format!("{depth}, {normal}")
                        }
                        Source::Absent => {
                            return Err(NodeError::at_port(port, "input is not connected"));
                        }
                        _ => {
                            return Err(NodeError::at_port(
                                port,
                                "a G-buffer from outside the pass is needed here",
                            ));
                        }
                    }
                }
                Arg::Texture(texture) => self.bind(&texture, "texture_2d<f32>"),
                Arg::Constant(text) => text,
            });
        }
        let call = format!("{}({})", stage.function, args.join(", "));
        // Images read by later stages are rounded as their Rgba16Float target would round them
        // (a target rounds by itself).
        let (value, format) = match stage.output {
            PortType::Image if read_later => (format!("as_rgba16float({call})"), IMAGE_FORMAT),
            PortType::Image => (call, IMAGE_FORMAT),
            _ => (call, MASK_FORMAT),
        };
        self.body.push(format!("    let v{i} = {value};"));
        if member.keep.first().copied().unwrap_or(false) {
            self.targets.push((i, format));
        }
        Ok(())
    }

    /// The WGSL expression of input `port` at the pixel.
    fn at(
        &mut self,
        ctx: &Ctx,
        member: &Member<'_, Value>,
        schema: &NodeSchema,
        port: &'static str,
        part: Part,
    ) -> Result<String, NodeError> {
        let index = port_index(schema, port)?;
        let spec = &schema.inputs[index];
        Ok(match &member.inputs[index] {
            Source::Absent if spec.required => {
                return Err(NodeError::at_port(port, "input is not connected"));
            }
            Source::Absent if spec.ty == PortType::GBuffer => match part {
                Part::Depth => "1.0".to_owned(),
                _ => "1.0, vec4<f32>(0.0)".to_owned(),
            },
            Source::Absent => "vec4<f32>(0.0)".to_owned(),
            Source::Member { member, .. } => format!("v{member}"),
            Source::External(Value::GBuffer(g)) => {
                screen_pass::frame_sized(ctx, port, &g.depth)?;
                screen_pass::frame_sized(ctx, port, &g.normal)?;
                match part {
                    Part::Normal => {
                        let normal = self.bind(&g.normal, "texture_2d<f32>");
                        format!("1.0, textureLoad({normal}, p, 0)")
                    }
                    Part::Depth => {
                        let depth = self.bind(&g.depth, "texture_depth_2d");
                        format!("textureLoad({depth}, p, 0)")
                    }
                    Part::Both => {
                        let depth = self.bind(&g.depth, "texture_depth_2d");
                        let normal = self.bind(&g.normal, "texture_2d<f32>");
                        format!("textureLoad({depth}, p, 0), textureLoad({normal}, p, 0)")
                    }
                }
            }
            Source::External(value @ (Value::Mask(_) | Value::Image(_))) => {
                let texture = match value {
                    Value::Mask(mask) => &mask.texture,
                    Value::Image(image) => &image.texture,
                    _ => unreachable!("matched above"),
                };
                screen_pass::frame_sized(ctx, port, texture)?;
                let name = self.bind(texture, "texture_2d<f32>");
                format!("textureLoad({name}, p, 0)")
            }
            Source::External(other) => {
                return Err(NodeError::at_port(
                    port,
                    format!("expected a picture, got a {}", other.port_type()),
                ));
            }
        })
    }

    /// The whole WGSL source, with a fragment entry point `fs_main` (one colour target per
    /// output) or a compute entry point `cs_main` over 8×8-pixel tiles (one storage texture per
    /// output, bound after the inputs).
    pub(super) fn source(&self, kernel: Kernel) -> Result<String, NodeError> {
        let mut text = String::from(crate::shaders::FULLSCREEN);
        for library in &self.libraries {
            let parts = crate::kinds::programs()
                .iter()
                .find(|(name, _)| name == library)
                .map(|(_, parts)| parts)
                .ok_or_else(|| NodeError::new(format!("no shader library {library}")))?;
            for &(file, part) in parts {
                if file != "fullscreen.wgsl" {
                    text.push_str(part);
                }
            }
        }
        text.push_str("\n// The fused pass (crates/hatchery-nodes/src/fused_pass/).\n");
        let mut binding = 0;
        for (i, b) in self.bindings.iter().enumerate() {
            text.push_str(&format!(
                "@group(0) @binding({binding}) var t{i}: {};\n",
                b.wgsl
            ));
            binding += 1;
        }
        if kernel == Kernel::Compute {
            for (k, (_, format)) in self.targets.iter().enumerate() {
                let texel = if *format == IMAGE_FORMAT {
                    "rgba16float"
                } else {
                    "r32float"
                };
                text.push_str(&format!(
                    "@group(0) @binding({binding}) var o{k}: texture_storage_2d<{texel}, write>;\n"
                ));
                binding += 1;
            }
        }
        if !self.uniform_fields.is_empty() {
            text.push_str(&format!(
                "struct Fused {{\n    {},\n}};\n@group(0) @binding({binding}) var<uniform> fused: Fused;\n",
                self.uniform_fields.join(",\n    "),
            ));
        }
        let body = self.body.join("\n");
        match kernel {
            Kernel::Fragment => {
                let outputs: Vec<String> = (0..self.targets.len())
                    .map(|k| format!("    @location({k}) o{k}: vec4<f32>,"))
                    .collect();
                text.push_str(&format!(
                    "struct FusedOut {{\n{}\n}};\n\n@fragment\nfn fs_main(in: ScreenOut) -> FusedOut {{\n    let p = pixel_of(in.position);\n{body}\n    var out: FusedOut;\n",
                    outputs.join("\n"),
                ));
                for (k, (member, _)) in self.targets.iter().enumerate() {
                    text.push_str(&format!("    out.o{k} = v{member};\n"));
                }
                text.push_str("    return out;\n}\n");
            }
            Kernel::Compute => {
                text.push_str(&format!(
                    "\n@compute @workgroup_size(8, 8, 1)\nfn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {{\n    if any(id.xy >= textureDimensions(o0)) {{\n        return;\n    }}\n    let p = vec2<i32>(id.xy);\n{body}\n"
                ));
                for (k, (member, _)) in self.targets.iter().enumerate() {
                    text.push_str(&format!("    textureStore(o{k}, p, v{member});\n"));
                }
                text.push_str("}\n");
            }
        }
        Ok(text)
    }
}

/// What of a G-buffer port a stage reads at the pixel.
#[derive(Clone, Copy, PartialEq)]
enum Part {
    Both,
    Normal,
    Depth,
}

fn port_index(schema: &NodeSchema, port: &str) -> Result<usize, NodeError> {
    schema
        .input_index(port)
        .ok_or_else(|| NodeError::new(format!("stage argument names no input port `{port}`")))
}

pub(super) fn build(
    ctx: &mut Ctx,
    group: &[Member<'_, Value>],
) -> Result<Shader, (usize, NodeError)> {
    let mut shader = Shader::default();
    for (i, member) in group.iter().enumerate() {
        let node = fusable(member.kind)
            .ok_or_else(|| (i, NodeError::new("this node kind has no fused stage")))?;
        let schema = node.schema();
        let inputs = StageInputs {
            names: schema.inputs.iter().map(|p| p.name).collect(),
            sources: &member.inputs,
        };
        let stage = node
            .stage(ctx, &inputs, member.params)
            .map_err(|e| (i, e))?;
        let read_later = group[i + 1..].iter().any(|later| {
            later
                .inputs
                .iter()
                .any(|s| matches!(s, Source::Member { member, .. } if *member == i))
        });
        shader
            .stage(ctx, i, member, &schema, stage, read_later)
            .map_err(|e| (i, e))?;
    }
    if shader.targets.is_empty() {
        return Err((
            group.len().saturating_sub(1),
            NodeError::new("a fused pass with no output"),
        ));
    }
    Ok(shader)
}
