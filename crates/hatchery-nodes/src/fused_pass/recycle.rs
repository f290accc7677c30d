//! Render targets of earlier fused passes, drawn into again once nothing else holds them.
//!
//! A re-run of a pass (the editor's θ drag re-runs one halftone pass per frame, an orbit the
//! whole chain) would otherwise allocate fresh full-frame textures each time, and a fresh
//! texture is zero-filled and cleared before the pass writes every pixel of it anyway. Every
//! output a pass hands out is also kept here; once its holders (the executor's cache, a preview)
//! let go of it, [`Recycled::targets`] hands its texture to the next pass of that format and
//! size, which loads it (`LoadOp::Load`) instead of clearing. Only for passes that write every
//! pixel (no `discard`).

use crate::value::{Image, Mask};
use crate::{Ctx, Value};
use std::sync::{Arc, Mutex};

/// Outputs handed out (the most recently used last).
#[derive(Default)]
pub(super) struct Recycled(Mutex<Vec<Value>>);

/// How many free textures the pool keeps for later passes (each a frame: 6 MiB at 1024×768 in
/// Rgba16Float); beyond that the oldest go.
const MAX_FREE: usize = 6;

/// One output texture of a pass: the value handed out, and whether its texture holds an earlier
/// picture (load it: every pixel is written again) or is new (clear it).
pub(super) struct Target {
    pub(super) value: Value,
    pub(super) recycled: bool,
}

impl Target {
    pub(super) fn texture(&self) -> &wgpu::Texture {
        texture_of(&self.value).expect("targets are images or masks")
    }
}

fn texture_of(value: &Value) -> Option<&wgpu::Texture> {
    match value {
        Value::Image(i) => Some(&i.texture),
        Value::Mask(m) => Some(&m.texture),
        _ => None,
    }
}

/// Whether only the pool holds `value` (so drawing into its texture changes no value anyone
/// can see).
fn free(value: &Value) -> bool {
    match value {
        Value::Image(i) => Arc::strong_count(i) == 1,
        Value::Mask(m) => Arc::strong_count(m) == 1,
        _ => false,
    }
}

impl Recycled {
    /// The device's pool.
    pub(super) fn of(ctx: &mut Ctx) -> Result<Arc<Self>, hatchery_gpu::GpuError> {
        ctx.cached("fused pass targets", |_| Ok(Self::default()))
    }

    /// One target per format, `size` (width, height) and with the `needs` usage (render
    /// attachment or storage): a free kept one, else a new texture (made by `make`) wrapped as
    /// an image (`image_format`) or a mask. Each is kept for later passes.
    pub(super) fn targets(
        &self,
        formats: &[wgpu::TextureFormat],
        size: (u32, u32),
        needs: wgpu::TextureUsages,
        image_format: wgpu::TextureFormat,
        mut make: impl FnMut(wgpu::TextureFormat) -> wgpu::Texture,
    ) -> Vec<Target> {
        let mut kept = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let fits = |v: &Value, format: wgpu::TextureFormat| {
            texture_of(v).is_some_and(|t| {
                t.format() == format
                    && (t.width(), t.height()) == size
                    && t.usage().contains(needs)
                    && free(v)
            })
        };
        let mut targets = Vec::with_capacity(formats.len());
        for &format in formats {
            let target = match kept.iter().position(|v| fits(v, format)) {
                Some(i) => Target {
                    value: kept.remove(i),
                    recycled: true,
                },
                None => {
                    let texture = make(format);
                    Target {
                        value: if format == image_format {
                            Value::Image(Arc::new(Image { texture }))
                        } else {
                            Value::Mask(Arc::new(Mask { texture }))
                        },
                        recycled: false,
                    }
                }
            };
            targets.push(target);
        }
        kept.extend(targets.iter().map(|t| t.value.clone()));
        // Free textures of another frame size are of no more use; of the rest keep MAX_FREE.
        kept.retain(|v| !free(v) || texture_of(v).is_some_and(|t| (t.width(), t.height()) == size));
        while kept.iter().filter(|v| free(v)).count() > MAX_FREE {
            let oldest = kept.iter().position(free).expect("counted above");
            kept.remove(oldest);
        }
        targets
    }
}
