//! `CustomShader`: a researcher's own image-space pass, written as a WGSL fragment shader in a
//! file. Its inputs, parameters and output are read from the shader's declarations (see
//! [`reflect`] and docs/custom_shader.md), so each node has a schema of its own; the file is
//! re-read whenever it changes on disk (the editor watches it), and a broken file is an error on
//! the node naming file:line:col while the last good version's ports stay.

pub mod reflect;

use crate::screen_pass::{IMAGE_FORMAT, MASK_FORMAT};
use crate::value::{Image, Mask};
use crate::{Ctx, Value};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::{
    Widget,
    NodeError, NodeInputs, NodeSchema, OwnSchema, ParamValue, Params, PortType, executor::Node,
};
use reflect::{MemberType, Reflection, Resource};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

/// What identifies a version of a file without reading it: modification and status-change
/// times, length, inode. The status-change time moves on every write, also when a tool
/// restores the modification time (`cp -p`, `rsync -t`).
pub type Stamp = (SystemTime, i64, i64, u64, u64);

/// The file's stamp; `None` if it cannot be looked at.
#[cfg(not(target_arch = "wasm32"))]
pub fn stamp(path: &Path) -> Option<Stamp> {
    let m = std::fs::metadata(path).ok()?;
    let modified = m.modified().unwrap_or(SystemTime::UNIX_EPOCH);
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        Some((modified, m.ctime(), m.ctime_nsec(), m.len(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        Some((modified, 0, 0, m.len(), 0))
    }
}

/// In the browser a file is what the page fetched (hatchery_data::files): it never changes.
#[cfg(target_arch = "wasm32")]
pub fn stamp(path: &Path) -> Option<Stamp> {
    hatchery_data::files::is_file(path).then_some((SystemTime::UNIX_EPOCH, 0, 0, 0, 0))
}

/// Shader files larger than this are refused (a device file or a log picked by mistake).
const MAX_SOURCE_BYTES: u64 = 1 << 20;

/// What a shader file said the last time it was read.
struct Cached {
    /// The file's stamp when read: it is read again when the stamp changes.
    stamp: Option<Stamp>,
    /// The current version, if it is valid.
    current: Result<Arc<Reflection>, String>,
    /// The last valid version (its ports stay on the node while the file is broken).
    last_good: Option<Arc<Reflection>>,
}

hatchery_graph::node_params! {
    /// The declared parameter of `CustomShader`; the rest follow its shader's declarations
    /// (`own_schema`) and are read by those names.
    pub struct CustomShaderParams {
        /// the WGSL file (relative to the graph file's folder); ports and parameters follow its
        /// declarations
        pub shader: PathBuf = "", widget(Widget::ShaderFile);
    }
}

#[derive(Default)]
pub struct CustomShaderNode {
    files: Mutex<HashMap<PathBuf, Cached>>,
}

const DOC: &str = "A fragment shader of your own (WGSL file): its texture bindings become \
    input ports (Image, Mask, GBuffer), its uniform struct's members parameters, its result the \
    output (vec4 → image, f32 → mask). Re-read when the file changes. See docs/custom_shader.md.";

impl CustomShaderNode {
    /// The shader at `path`, re-read if it changed since the last call.
    fn read(&self, path: &Path) -> (Result<Arc<Reflection>, String>, Option<Arc<Reflection>>) {
        let mut files = self.files.lock().unwrap_or_else(|p| p.into_inner());
        let stamp = stamp(path);
        let entry = files.entry(path.to_path_buf()).or_insert(Cached {
            stamp: None,
            current: Err(String::new()),
            last_good: None,
        });
        let fresh = stamp.is_some() && entry.stamp == stamp;
        if !fresh {
            entry.stamp = stamp;
            entry.current = read_source(path)
                .and_then(|source| reflect_deep(path, source, self.schema()))
                .map(Arc::new);
            if let Ok(good) = &entry.current {
                entry.last_good = Some(good.clone());
            }
        }
        (entry.current.clone(), entry.last_good.clone())
    }

    fn shader_path(params: &Params) -> Result<PathBuf, String> {
        let path = CustomShaderParams::read(params)
            .map_err(|e| e.message)?
            .shader;
        if path.as_os_str().is_empty() {
            return Err("no shader file: set `shader` to a .wgsl file".into());
        }
        Ok(path)
    }
}

impl Node<Value, Ctx> for CustomShaderNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "CustomShader",
            category: "Compositing",
            doc: DOC,
            inputs: vec![],
            outputs: vec![],
            params: CustomShaderParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn has_own_schema(&self) -> bool {
        true
    }

    fn own_schema(&self, params: &Params) -> Option<OwnSchema> {
        let path = match Self::shader_path(params) {
            Ok(path) => path,
            Err(message) => {
                return Some(OwnSchema {
                    error: Some(message),
                    ..Default::default()
                });
            }
        };
        let (current, last_good) = self.read(&path);
        Some(match current {
            Ok(r) => OwnSchema {
                schema: Some(r.schema.clone()),
                error: None,
                fingerprint: r.fingerprint,
            },
            Err(message) => OwnSchema {
                schema: last_good.map(|r| r.schema.clone()),
                error: Some(message),
                fingerprint: 0,
            },
        })
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        params: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let path = Self::shader_path(params).map_err(NodeError::new)?;
        let shader = self.read(&path).0.map_err(NodeError::new)?;
        let (width, height) = ctx.size();
        // Every input texture has the frame's size (the shader addresses pixels by position).
        let mut views = Vec::new();
        for (binding, resource) in &shader.bindings {
            let (port, texture) = match resource {
                Resource::Texture { port } => match inputs.require(port)? {
                    Value::Image(i) => (*port, i.texture.clone()),
                    Value::Mask(m) => (*port, m.texture.clone()),
                    other => {
                        return Err(NodeError::at_port(
                            port,
                            format!("expected an image or a mask, got {}", other.port_type()),
                        ));
                    }
                },
                Resource::Depth { port } => {
                    (*port, inputs.require(port)?.gbuffer(port)?.depth.clone())
                }
                Resource::Normal { port } => {
                    (*port, inputs.require(port)?.gbuffer(port)?.normal.clone())
                }
                Resource::Sampler | Resource::Uniform => continue,
            };
            crate::screen_pass::frame_sized(ctx, port, &texture)?;
            views.push((*binding, texture.create_view(&Default::default())));
        }
        let format = match shader.output {
            PortType::Mask => MASK_FORMAT,
            _ => IMAGE_FORMAT,
        };
        let key = format!("custom_shader:{:016x}:{format:?}", shader.fingerprint);
        let pipeline = ctx
            .cached(&key, |gpu| {
                on_big_stack(|| pipeline(gpu, &path, &shader, format)).unwrap_or_else(|| {
                    Err(GpuError::Validation {
                        what: format!("shader {}", path.display()),
                        message: "the shader compiler failed on this file".into(),
                    })
                })
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let sampler = ctx
            .cached("custom_shader:sampler", |gpu| {
                Ok(gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some("custom shader sampler"),
                    mag_filter: wgpu::FilterMode::Linear,
                    min_filter: wgpu::FilterMode::Linear,
                    ..Default::default()
                }))
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let uniform = shader.uniform.as_ref().map(|u| {
            ctx.gpu.buffer_init(
                "custom shader parameters",
                &uniform_bytes(u, params),
                wgpu::BufferUsages::UNIFORM,
            )
        });
        let mut entries = Vec::new();
        for (binding, resource) in &shader.bindings {
            let resource = match resource {
                Resource::Sampler => wgpu::BindingResource::Sampler(&sampler),
                Resource::Uniform => uniform.as_ref().expect("made above").as_entire_binding(),
                _ => {
                    let view = &views
                        .iter()
                        .find(|(b, _)| b == binding)
                        .expect("made above")
                        .1;
                    wgpu::BindingResource::TextureView(view)
                }
            };
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource,
            });
        }
        let label = format!("custom shader {}", path.display());
        let bind_group = ctx
            .gpu
            .checked(&label, |device| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&label),
                    layout: &pipeline.1,
                    entries: &entries,
                })
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let texture = crate::screen_pass::draw(
            ctx,
            &label,
            &pipeline.0,
            &[&bind_group],
            format,
            (width, height),
        );
        Ok(vec![match shader.output {
            PortType::Mask => Value::Mask(Arc::new(Mask { texture })),
            _ => Value::Image(Arc::new(Image { texture })),
        }])
    }
}

/// The text of a shader file the page fetched, at most [`MAX_SOURCE_BYTES`], UTF-8.
#[cfg(target_arch = "wasm32")]
fn read_source(path: &Path) -> Result<String, String> {
    let fail = |why: String| format!("{}: cannot read the shader: {why}", path.display());
    let bytes = hatchery_data::files::read(path).map_err(|e| fail(e.to_string()))?;
    if bytes.len() as u64 > MAX_SOURCE_BYTES {
        return Err(fail(format!(
            "{} bytes; a shader file has at most {MAX_SOURCE_BYTES}",
            bytes.len()
        )));
    }
    String::from_utf8(bytes).map_err(|e| fail(e.to_string()))
}

/// The text of a shader file: a regular file of at most [`MAX_SOURCE_BYTES`], UTF-8.
#[cfg(not(target_arch = "wasm32"))]
fn read_source(path: &Path) -> Result<String, String> {
    let fail = |why: String| format!("{}: cannot read the shader: {why}", path.display());
    let meta = std::fs::metadata(path).map_err(|e| fail(e.to_string()))?;
    if !meta.is_file() {
        return Err(fail("not a regular file".into()));
    }
    if meta.len() > MAX_SOURCE_BYTES {
        return Err(fail(format!(
            "{} bytes; a shader file has at most {MAX_SOURCE_BYTES}",
            meta.len()
        )));
    }
    std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))
}

/// Runs `f` on a thread with a large stack. naga's parser recurses on nested expressions: a
/// machine-written shader with a very long expression (30,000 terms) overflows a normal
/// thread's stack and aborts the process. With the size cap above, 256 MiB is room for any file
/// accepted (the memory is only reserved, not used, unless the recursion goes deep). Used for
/// our reading of the file and for wgpu's (which parses the text again). `None` if the thread
/// could not start or `f` panicked.
#[cfg(not(target_arch = "wasm32"))]
fn on_big_stack<T: Send>(f: impl FnOnce() -> T + Send) -> Option<T> {
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("hatchery-shader".into())
            .stack_size(256 << 20)
            .spawn_scoped(scope, f)
            .ok()?
            .join()
            .ok()
    })
}

/// The browser build has one thread: the parse runs on the page's stack (shaders nested deeply
/// enough to need more trap there instead of aborting a process).
#[cfg(target_arch = "wasm32")]
fn on_big_stack<T: Send>(f: impl FnOnce() -> T + Send) -> Option<T> {
    Some(f())
}

fn reflect_deep(path: &Path, source: String, base: NodeSchema) -> Result<Reflection, String> {
    on_big_stack(|| reflect::reflect(path, &source, &base)).unwrap_or_else(|| {
        Err(format!(
            "{}: the shader compiler failed on this file",
            path.display()
        ))
    })
}

/// The render pipeline: our full-frame vertex stage, the file's fragment stage.
fn pipeline(
    gpu: &GpuContext,
    path: &Path,
    shader: &Reflection,
    format: wgpu::TextureFormat,
) -> Result<(wgpu::RenderPipeline, wgpu::BindGroupLayout), GpuError> {
    let vertex = gpu.shader("custom_shader_vertex", VERTEX_SHADER)?;
    let name = path.display().to_string();
    let fragment = gpu.shader(&name, &shader.source)?;
    // The layout lists every declared binding, used or not (a layout derived from the shader
    // would drop unused ones, and the bind group would no longer fit it). Masks are R32Float,
    // which not every adapter can filter: read them with textureLoad.
    let entries: Vec<wgpu::BindGroupLayoutEntry> = shader
        .bindings
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupLayoutEntry {
            binding: *binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: match resource {
                Resource::Texture { port } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float {
                        filterable: shader.mask_ports.iter().all(|m| m != port),
                    },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Resource::Normal { .. } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Resource::Depth { .. } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Depth,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Resource::Sampler => {
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
                }
                Resource::Uniform => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            },
            count: None,
        })
        .collect();
    gpu.checked(&format!("pipeline of {name}"), |device| {
        let group = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &entries,
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&name),
            bind_group_layouts: &[Some(&group)],
            immediate_size: 0,
        });
        let stages = crate::screen_pass::Stages {
            vertex: &vertex,
            fragment: &fragment,
            entry: &shader.entry_point,
            constants: &[],
        };
        let pipeline = crate::screen_pass::fullscreen_pipeline(
            device,
            &name,
            Some(&layout),
            stages,
            &[format],
            None,
        );
        (pipeline, group)
    })
}

/// The uniform struct's bytes: each member's parameter at its offset (naga's layout).
fn uniform_bytes(uniform: &reflect::Uniform, params: &Params) -> Vec<u8> {
    let mut bytes = vec![0u8; uniform.size as usize];
    for m in &uniform.members {
        // Matched on the stored value, not read with the typed getters: the file may have
        // changed a member's type since the graph was validated.
        let scalar = match params.get(m.name) {
            Some(ParamValue::Float(x)) => Some(*x),
            Some(ParamValue::Int(i)) => Some(*i as f64),
            _ => None,
        };
        let words: Vec<[u8; 4]> = match (m.ty, scalar, params.get(m.name)) {
            (MemberType::F32, Some(x), _) => vec![(x as f32).to_le_bytes()],
            (MemberType::I32, Some(x), _) => vec![(x.round() as i32).to_le_bytes()],
            (MemberType::U32, Some(x), _) => vec![(x.round().max(0.0) as u32).to_le_bytes()],
            (MemberType::Vec3, _, Some(ParamValue::Vec3(v))) => {
                v.iter().map(|x| (*x as f32).to_le_bytes()).collect()
            }
            (MemberType::Vec4, _, Some(ParamValue::Color(c))) => {
                c.iter().map(|x| (*x as f32).to_le_bytes()).collect()
            }
            _ => continue,
        };
        for (i, word) in words.iter().enumerate() {
            let at = m.offset as usize + 4 * i;
            bytes[at..at + 4].copy_from_slice(word);
        }
    }
    bytes
}

const VERTEX_SHADER: &str = crate::shaders::shader_file!("custom_shader_vertex.wgsl");

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(CustomShaderNode::default())
        // The vertex stage of every CustomShader (the fragment stage is the user's file).
        .program(
            "custom_shader_vertex",
            vec![shaders::part!("custom_shader_vertex.wgsl")],
        );
}
