//! Reading textures and buffers back to the CPU (for tests, `--dump`, saving images and vector
//! output), and bind groups from binding lists.

use crate::context::GpuContext;
use crate::error::GpuError;

/// Texels of a 2-D texture as f32, row-major from the top row, `channels` per texel.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureData {
    pub width: u32,
    pub height: u32,
    pub channels: u32,
    pub data: Vec<f32>,
}

impl TextureData {
    pub fn texel(&self, x: u32, y: u32) -> &[f32] {
        let c = self.channels as usize;
        let i = (y as usize * self.width as usize + x as usize) * c;
        &self.data[i..i + c]
    }
}

/// Bytes per texel and channel count of the formats hatchery reads back.
fn layout(format: wgpu::TextureFormat) -> Option<(u32, u32)> {
    use wgpu::TextureFormat::*;
    Some(match format {
        R32Float | Depth32Float => (4, 1),
        Rg32Float => (8, 2),
        Rgba32Float => (16, 4),
        Rgba16Float => (8, 4),
        R16Float => (2, 1),
        Rgba8Unorm | Rgba8UnormSrgb | Bgra8Unorm => (4, 4),
        R8Unorm => (1, 1),
        _ => return None,
    })
}

impl GpuContext {
    /// Copies a 2-D texture to the CPU and converts its texels to f32.
    pub fn read_texture(&self, texture: &wgpu::Texture) -> Result<TextureData, GpuError> {
        let format = texture.format();
        let what = format!("a {format:?} texture");
        let (bytes_per_texel, channels) = layout(format).ok_or_else(|| GpuError::Readback {
            what: what.clone(),
            message: "format not supported".into(),
        })?;
        let (width, height) = (texture.width(), texture.height());
        let unpadded = width * bytes_per_texel;
        let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: padded as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let aspect = if format.is_depth_stencil_format() {
            wgpu::TextureAspect::DepthOnly
        } else {
            wgpu::TextureAspect::All
        };
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        let bytes = self
            .staged_bytes(
                crate::web_readback::ReadKey::Texture(texture.clone()),
                &buffer,
            )
            .map_err(|message| GpuError::Readback {
                what: what.clone(),
                message,
            })?;

        let mut data = Vec::with_capacity((width * height * channels) as usize);
        for row in 0..height as usize {
            let line = &bytes[row * padded as usize..row * padded as usize + unpadded as usize];
            convert_row(format, line, &mut data);
        }
        Ok(TextureData {
            width,
            height,
            channels,
            data,
        })
    }

    /// The first `bytes` of a COPY_SRC buffer (rounded up to the 4-byte copy alignment, at most
    /// the whole buffer), copied into a staging buffer and read back, waiting for the GPU.
    pub fn read_buffer(&self, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, GpuError> {
        let size = (bytes.div_ceil(4).max(1) * 4).min(buffer.size());
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([encoder.finish()]);
        self.staged_bytes(
            crate::web_readback::ReadKey::Buffer(buffer.clone(), size),
            &staging,
        )
        .map_err(|message| GpuError::Readback {
            what: buffer_name(buffer),
            message,
        })
    }

    /// The contents of `staging`, a MAP_READ copy of what `key` names: natively mapped at once;
    /// in the browser from [`crate::web_readback`] (an error the first time, asking the page to
    /// run the pass again once the copy has arrived).
    #[cfg(not(target_arch = "wasm32"))]
    fn staged_bytes(
        &self,
        _key: crate::web_readback::ReadKey,
        staging: &wgpu::Buffer,
    ) -> Result<Vec<u8>, String> {
        self.map_bytes(staging)
    }

    #[cfg(target_arch = "wasm32")]
    fn staged_bytes(
        &self,
        key: crate::web_readback::ReadKey,
        staging: &wgpu::Buffer,
    ) -> Result<Vec<u8>, String> {
        self.web_readbacks.read(key, staging)
    }

    /// A bind group of `layout` from (binding number, resource) pairs.
    pub fn bind_group(
        &self,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        bindings: &[(u32, wgpu::BindingResource)],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = bindings
            .iter()
            .map(|(binding, resource)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.clone(),
            })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        })
    }

    /// Maps a MAP_READ buffer and returns a copy of its contents, waiting for the GPU.
    /// Errors: [`GpuError::Readback`] when the device is lost or the mapping fails.
    pub fn map_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        self.map_bytes(buffer)
            .map_err(|message| GpuError::Readback {
                what: buffer_name(buffer),
                message,
            })
    }

    /// The browser cannot wait for a mapping inside a pass (its promise resolves only after the
    /// running task returns); [`Self::read_texture`] and [`Self::read_buffer`] go through
    /// [`crate::web_readback`] there instead.
    #[cfg(target_arch = "wasm32")]
    fn map_bytes(&self, _buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
        Err("mapping a GPU buffer inside a pass is not available in the browser build".into())
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn map_bytes(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |result| {
            let _ = tx.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| e.to_string())?;
        rx.recv()
            .map_err(|e| e.to_string())?
            .map_err(|e| e.to_string())?;
        let bytes = buffer
            .get_mapped_range(..)
            .map_err(|e| e.to_string())?
            .to_vec();
        buffer.unmap();
        Ok(bytes)
    }
}

/// Read-backs in the browser, between passes (see [`crate::web_readback`]).
#[cfg(target_arch = "wasm32")]
impl GpuContext {
    /// Whether the last pass asked for read-backs that have not been collected.
    pub fn readbacks_pending(&self) -> bool {
        self.web_readbacks.pending()
    }

    /// Keeps the read-backs that have arrived for the next pass. Returns whether every one has
    /// (call again after letting the page's event loop run). Errors: a failed mapping.
    pub fn collect_readbacks(&self) -> Result<bool, GpuError> {
        self.web_readbacks
            .collect()
            .map_err(|(what, message)| GpuError::Readback { what, message })
    }

    /// Forgets the arrived read-backs: the next picture reads afresh.
    pub fn forget_readbacks(&self) {
        self.web_readbacks.forget();
    }
}

fn buffer_name(buffer: &wgpu::Buffer) -> String {
    format!("a buffer of {} bytes", buffer.size())
}

fn convert_row(format: wgpu::TextureFormat, line: &[u8], out: &mut Vec<f32>) {
    use wgpu::TextureFormat::*;
    match format {
        R32Float | Depth32Float | Rg32Float | Rgba32Float => out.extend(
            line.chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        ),
        Rgba16Float | R16Float => out.extend(
            line.chunks_exact(2)
                .map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32()),
        ),
        Bgra8Unorm => {
            for px in line.chunks_exact(4) {
                out.extend([px[2], px[1], px[0], px[3]].map(|v| v as f32 / 255.0));
            }
        }
        _ => out.extend(line.iter().map(|&v| v as f32 / 255.0)),
    }
}
