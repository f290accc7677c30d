use std::sync::{Arc, Mutex};
use wgpu::util::DeviceExt;

use crate::error::GpuError;

/// What a "no data" voxel holds in a normalised volume texture: far below [0, 1], so a filtered
/// sample with any noticeable weight on one is below -0.5.
pub const NO_DATA_TEXEL: f32 = -1000.0;

/// The one device hatchery renders with. Clones share the device (wgpu handles are shared).
#[derive(Clone)]
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    /// Errors that escaped an error scope; kept so that they surface as node errors, not panics.
    uncaptured: Arc<Mutex<Vec<String>>>,
    /// When volumes are bricked and how large their pools grow (from the environment; a bad
    /// value surfaces when a volume is uploaded).
    volume_limits: Result<crate::VolumeLimits, String>,
    /// Read-backs of the browser build, which arrive between passes ([`crate::web_readback`]).
    #[cfg(target_arch = "wasm32")]
    pub(crate) web_readbacks: crate::web_readback::WebReadbacks,
}

#[cfg(not(target_arch = "wasm32"))]
fn backends_from_env() -> Option<wgpu::Backends> {
    match std::env::var("HATCHERY_BACKEND")
        .ok()?
        .to_ascii_lowercase()
        .as_str()
    {
        "vulkan" => Some(wgpu::Backends::VULKAN),
        "gl" | "gles" => Some(wgpu::Backends::GL),
        "metal" => Some(wgpu::Backends::METAL),
        "dx12" => Some(wgpu::Backends::DX12),
        _ => None,
    }
}

impl GpuContext {
    /// Opens the best adapter: a real GPU if there is one, else lavapipe (Vulkan) or llvmpipe (GL).
    /// `HATCHERY_BACKEND=vulkan|gl` restricts the choice. Not in the browser build, which opens
    /// its adapter for the page's canvas ([`Self::from_adapter_async`]).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn new() -> Result<Self, GpuError> {
        // Vulkan (or Metal/DX12) first; GL only if that finds nothing, since probing EGL on a
        // headless machine prints driver noise.
        let attempts = match backends_from_env() {
            Some(chosen) => vec![chosen],
            None => vec![wgpu::Backends::PRIMARY, wgpu::Backends::GL],
        };
        for &backends in &attempts {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            let adapter =
                pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::HighPerformance,
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    apply_limit_buckets: false,
                }));
            if let Ok(adapter) = adapter {
                return Self::from_adapter(&adapter);
            }
        }
        Err(GpuError::NoAdapter {
            tried: format!("{attempts:?}"),
        })
    }

    /// What hatchery asks of a device on `adapter`: timestamps and filterable floats where the
    /// adapter has them, and the adapter's own texture and buffer size limits (volumes are big).
    /// The editor gives this to eframe so that the window's device can render graphs too.
    pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
        // Timestamps are optional: used for per-node GPU times where the adapter has them.
        let wanted = wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
            | wgpu::Features::FLOAT32_FILTERABLE
            // 16-bit volumes uploaded as they are (R16Unorm), not narrowed to R16Float.
            | wgpu::Features::TEXTURE_FORMAT_16BIT_NORM
            // Two depth layers in one geometry pass (DepthLayers: a k-buffer of packed depth and
            // normal updated with 64-bit atomics); without them DepthLayers peels twice.
            | wgpu::Features::SHADER_INT64
            | wgpu::Features::SHADER_INT64_ATOMIC_ALL_OPS;
        let required_features = adapter.features() & wanted;
        let adapter_limits = adapter.limits();
        let required_limits = wgpu::Limits {
            max_texture_dimension_3d: adapter_limits.max_texture_dimension_3d,
            max_texture_dimension_2d: adapter_limits.max_texture_dimension_2d,
            max_buffer_size: adapter_limits.max_buffer_size,
            max_storage_buffer_binding_size: adapter_limits.max_storage_buffer_binding_size,
            ..wgpu::Limits::downlevel_defaults()
        }
        .using_resolution(adapter_limits.clone());
        wgpu::DeviceDescriptor {
            label: Some("hatchery"),
            required_features,
            required_limits,
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }
    }

    /// Opens a device on a chosen adapter.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn from_adapter(adapter: &wgpu::Adapter) -> Result<Self, GpuError> {
        pollster::block_on(Self::from_adapter_async(adapter))
    }

    /// [`Self::from_adapter`] without blocking: the browser build (crates/hatchery-web) awaits it,
    /// since a page cannot block on the device request.
    pub async fn from_adapter_async(adapter: &wgpu::Adapter) -> Result<Self, GpuError> {
        let adapter_info = adapter.get_info();
        let (device, queue) = adapter
            .request_device(&Self::device_descriptor(adapter))
            .await
            .map_err(|e| GpuError::Device {
                adapter: adapter_info.name.clone(),
                message: e.to_string(),
            })?;
        Ok(Self::from_device(adapter_info, device, queue))
    }

    /// Renders on a device opened elsewhere (the editor's window device, so that its previews
    /// are shown without copies). GPU errors that escape an error scope are collected and
    /// reported with the next pass instead of panicking.
    pub fn from_device(
        adapter_info: wgpu::AdapterInfo,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Self {
        let uncaptured = Arc::new(Mutex::new(Vec::new()));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            tracing::error!("GPU error: {error}");
            if let Ok(mut errors) = sink.lock() {
                errors.push(error.to_string());
            }
        }));
        Self {
            device,
            queue,
            adapter_info,
            uncaptured,
            volume_limits: crate::VolumeLimits::from_env().map_err(|e| e.to_string()),
            #[cfg(target_arch = "wasm32")]
            web_readbacks: Default::default(),
        }
    }

    /// When volumes are bricked and how large their pools grow (see [`crate::VolumeLimits`]).
    /// Errors: a malformed `HATCHERY_*` setting, named.
    pub fn volume_limits(&self) -> Result<crate::VolumeLimits, GpuError> {
        self.volume_limits
            .clone()
            .map_err(|message| GpuError::Setting { message })
    }

    /// Replaces the volume limits of this context (and of clones made after this call).
    pub fn set_volume_limits(&mut self, limits: crate::VolumeLimits) {
        self.volume_limits = Ok(limits);
    }

    /// One line naming the adapter, driver and backend (for logs and benchmark reports).
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!(
            "{} ({:?}, {} {}, {:?})",
            i.name, i.device_type, i.driver, i.driver_info, i.backend
        )
    }

    /// True on CPU drivers (lavapipe, llvmpipe): timings then are CPU timings.
    pub fn is_software(&self) -> bool {
        self.adapter_info.device_type == wgpu::DeviceType::Cpu
    }

    /// True on NVIDIA's data-centre compute parts (H100, H200, GH200, H800), whose graphics
    /// pipeline runs on a small part of the chip: there full-screen work belongs in compute
    /// shaders (measured in docs/benchmarks.md).
    pub fn is_compute_part(&self) -> bool {
        let name = self.adapter_info.name.to_ascii_uppercase();
        ["H100", "H200", "H800"]
            .iter()
            .any(|part| name.contains(part))
    }

    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(
            wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS,
        )
    }

    /// Runs `f` inside a validation error scope and turns any validation error into a
    /// [`GpuError::Validation`] naming `what` (a shader, a pipeline) instead of a panic.
    pub fn checked<T>(
        &self,
        what: &str,
        f: impl FnOnce(&wgpu::Device) -> T,
    ) -> Result<T, GpuError> {
        let scope = self.scope();
        let value = f(&self.device);
        match self.pop_now(scope) {
            None => Ok(value),
            Some(error) => Err(GpuError::Validation {
                what: what.to_owned(),
                message: first_line(&error.to_string()),
            }),
        }
    }

    /// Compiles a WGSL shader; errors name the shader and carry naga's message.
    pub fn shader(&self, name: &str, source: &str) -> Result<wgpu::ShaderModule, GpuError> {
        let scope = self.scope();
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        match self.pop_now(scope) {
            None => Ok(module),
            Some(error) => Err(GpuError::Validation {
                what: format!("shader {name}"),
                message: error
                    .to_string()
                    .lines()
                    .filter(|l| !l.trim().is_empty())
                    .collect::<Vec<_>>()
                    .join(" | "),
            }),
        }
    }

    /// A validation error scope. None in the browser, which cannot wait for a scope's verdict
    /// (a page's promises resolve only after the running task returns; scopes popped later
    /// would be popped out of order): there errors reach the uncaptured-error handler, which
    /// [`Self::take_uncaptured_errors`] reports once the page has let them arrive.
    fn scope(&self) -> Option<wgpu::ErrorScopeGuard> {
        #[cfg(not(target_arch = "wasm32"))]
        return Some(self.device.push_error_scope(wgpu::ErrorFilter::Validation));
        #[cfg(target_arch = "wasm32")]
        None
    }

    /// The error a [`Self::scope`] caught, waiting for the device to say.
    #[cfg(not(target_arch = "wasm32"))]
    fn pop_now(&self, scope: Option<wgpu::ErrorScopeGuard>) -> Option<wgpu::Error> {
        pollster::block_on(scope?.pop())
    }

    #[cfg(target_arch = "wasm32")]
    fn pop_now(&self, scope: Option<wgpu::ErrorScopeGuard>) -> Option<wgpu::Error> {
        drop(scope);
        None
    }

    /// Errors that escaped every scope since the last call.
    pub fn take_uncaptured_errors(&self) -> Vec<String> {
        self.uncaptured
            .lock()
            .map(|mut e| std::mem::take(&mut *e))
            .unwrap_or_default()
    }

    /// A 2-D texture usable as render target, shader input and copy source.
    pub fn render_target(
        &self,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> wgpu::Texture {
        self.texture_2d(label, width, height, format, wgpu::TextureUsages::empty())
    }

    /// A 2-D texture a compute shader writes (storage) and later passes read, copy or render
    /// into, like `render_target`.
    pub fn storage_target(
        &self,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> wgpu::Texture {
        self.texture_2d(
            label,
            width,
            height,
            format,
            wgpu::TextureUsages::STORAGE_BINDING,
        )
    }

    /// A one-level 2-D texture for rendering, sampling and copying, with `extra` usages.
    fn texture_2d(
        &self,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
        extra: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: extra
                | wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        })
    }

    /// Checks a 2-D size against the device's limit.
    pub fn check_2d_size(&self, what: &str, width: u32, height: u32) -> Result<(), GpuError> {
        let limit = self.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > limit || height > limit {
            return Err(GpuError::TooLarge {
                what: what.to_owned(),
                size: format!("{width}×{height}"),
                limit: format!("{limit}×{limit} and at least 1×1"),
            });
        }
        Ok(())
    }

    /// A 3-D texture of `format` filled slab by slab: `fill(z0, z1, out)` appends the tightly
    /// packed texels of slices `z0..z1` to `out`. Slabs are about 4 MB, so no CPU copy of the
    /// whole volume is ever made (the peak is the caller's voxels plus the texture plus one
    /// slab). Errors: a side over the device's 3-D texture limit, or a texture bigger than the
    /// device's buffer limit (checked before anything is allocated).
    pub fn volume_texture_by_slabs(
        &self,
        label: &str,
        dims: [u32; 3],
        format: wgpu::TextureFormat,
        mut fill: impl FnMut(u32, u32, &mut Vec<u8>),
    ) -> Result<wgpu::Texture, GpuError> {
        let limits = self.device.limits();
        let limit = limits.max_texture_dimension_3d;
        let size = || format!("{}×{}×{}", dims[0], dims[1], dims[2]);
        if dims.iter().any(|&d| d == 0 || d > limit) {
            return Err(GpuError::TooLarge {
                what: format!("the {label} texture"),
                size: size(),
                limit: format!("{limit} voxels per axis (max_texture_dimension_3d)"),
            });
        }
        let texel = format.block_copy_size(None).unwrap_or(4) as u64;
        let bytes = dims.iter().map(|&d| d as u64).product::<u64>() * texel;
        if bytes > limits.max_buffer_size {
            return Err(GpuError::TooLarge {
                what: format!("the {label} texture"),
                size: format!("{} ({bytes} bytes)", size()),
                limit: format!("{} bytes (max_buffer_size)", limits.max_buffer_size),
            });
        }
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: dims[0],
                height: dims[1],
                depth_or_array_layers: dims[2],
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D3,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let slice_bytes = dims[0] as u64 * dims[1] as u64 * texel;
        let per_slab = ((4u64 << 20) / slice_bytes.max(1)).clamp(1, dims[2] as u64) as u32;
        let mut slab = Vec::new();
        let mut z0 = 0;
        while z0 < dims[2] {
            let z1 = (z0 + per_slab).min(dims[2]);
            slab.clear();
            fill(z0, z1, &mut slab);
            debug_assert_eq!(slab.len() as u64, slice_bytes * (z1 - z0) as u64);
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: z0 },
                    aspect: wgpu::TextureAspect::All,
                },
                &slab,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(dims[0] * texel as u32),
                    rows_per_image: Some(dims[1]),
                },
                wgpu::Extent3d {
                    width: dims[0],
                    height: dims[1],
                    depth_or_array_layers: z1 - z0,
                },
            );
            // Hand each slab to the device and let its staging memory go before the next one
            // is staged (big volumes would otherwise be staged whole).
            self.queue.submit([]);
            if z1 < dims[2] {
                let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
            }
            z0 = z1;
        }
        Ok(texture)
    }

    /// A 2-D texture initialised with `data` (tightly packed rows), e.g. lookup tables.
    pub fn texture_2d_init(
        &self,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
        data: &[u8],
    ) -> wgpu::Texture {
        self.texture_init(
            label,
            [width, height, 1],
            wgpu::TextureDimension::D2,
            format,
            data,
        )
    }

    /// A 3-D texture of `size` texels (x fastest, then y, then z) initialised with `data`.
    pub fn texture_3d_init(
        &self,
        label: &str,
        size: [u32; 3],
        format: wgpu::TextureFormat,
        data: &[u8],
    ) -> wgpu::Texture {
        self.texture_init(label, size, wgpu::TextureDimension::D3, format, data)
    }

    fn texture_init(
        &self,
        label: &str,
        [width, height, depth]: [u32; 3],
        dimension: wgpu::TextureDimension,
        format: wgpu::TextureFormat,
        data: &[u8],
    ) -> wgpu::Texture {
        let desc = wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: depth,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        };
        self.device.create_texture_with_data(
            &self.queue,
            &desc,
            wgpu::util::TextureDataOrder::LayerMajor,
            data,
        )
    }

    /// A buffer initialised with `data`.
    pub fn buffer_init(&self, label: &str, data: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: data,
                usage,
            })
    }

    /// Blocks until the GPU has finished everything submitted so far.
    pub fn wait_idle(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

fn first_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" | ")
}
