//! Drawing annotations over an image (VolumeShop §6.3 visual conventions, §6.4 annotations):
//! a small GPU 2-D vector renderer, [`Canvas`], shared by every overlay node (the
//! `AnnotationOverlay` node, annotation_overlay.rs, draws laid-out labels with it).
//!
//! Units: pixels with the origin at the image's top-left corner and y down; a pixel's centre is
//! at (x + 0.5, y + 0.5).
//!
//! Design: every primitive is one instanced quad (shaders/overlay.wgsl) whose fragment shader
//! computes the primitive's coverage analytically — the distance to a segment (anti-aliased
//! lines with round caps), to a centre (discs), to three edges (triangles, filled convex
//! polygons) — and writes the premultiplied colour times coverage, blended "over" a copy of the
//! input image. Drawing order is call order. Text is the one thing rasterised on the CPU: each
//! string's glyph coverage (`label_font::rasterize`) goes into one R8Unorm atlas, cell by cell,
//! at the exact sub-pixel offset it will have on screen, so the GPU copies texels one to one
//! (no resampling blur). The halo is the coverage dilated by a disc in the fragment shader
//! rather than a second CPU-rasterised channel: the atlas stays one channel, and the halo width
//! stays a drawing parameter, exact for any width, without rasterising the text again.

use crate::label_font;
use crate::screen_pass::IMAGE_FORMAT;
use crate::value::Image;
use crate::{Ctx, Value};
use glam::Vec2;
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::NodeError;
use std::sync::Arc;

crate::uniform_block! {
    /// `Overlay` of shaders/overlay.wgsl: the frame size in pixels.
    pub struct OverlayUniforms in "overlay" as "Overlay" {
        pub frame: [f32; 2],
        pub pad0: f32,
        pub pad1: f32,
    }
}

/// Largest halo the shader dilates by, pixels.
pub const MAX_HALO: f32 = 8.0;

pub(crate) const SEGMENT: f32 = 0.0;
pub(crate) const DISC: f32 = 1.0;
pub(crate) const TRIANGLE: f32 = 2.0;
pub(crate) const TEXT: f32 = 3.0;
/// An exclusion rectangle that excludes nothing (min > max).
pub(crate) const NO_CLIP: [f32; 4] = [1.0, 1.0, 0.0, 0.0];

/// One instanced quad of shaders/overlay.wgsl (`Primitive`, locations 0–6).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Primitive {
    /// p0, p1.
    a: [f32; 4],
    /// p2, size (half width, radius or halo radius), kind.
    b: [f32; 4],
    /// Premultiplied colour.
    color: [f32; 4],
    /// Triangle: edge mask; text: atlas origin (x, y) and cell size (w, h) in texels.
    extra: [f32; 4],
    /// Premultiplied halo colour (text).
    halo: [f32; 4],
    /// Rectangles (min x, min y, max x, max y) where nothing of this primitive is drawn.
    clip0: [f32; 4],
    clip1: [f32; 4],
}

pub(crate) const ATTRIBUTES: [wgpu::VertexAttribute; 7] = wgpu::vertex_attr_array![
    0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4,
    4 => Float32x4, 5 => Float32x4, 6 => Float32x4
];

/// Straight RGBA (0–1) to premultiplied, times `opacity`.
pub(crate) fn premultiplied(color: [f32; 4], opacity: f32) -> [f32; 4] {
    let a = (color[3] * opacity).clamp(0.0, 1.0);
    [color[0] * a, color[1] * a, color[2] * a, a]
}

pub(crate) fn finite(points: &[Vec2]) -> bool {
    points.iter().all(|p| p.is_finite())
}

/// A string waiting for its atlas cell.
pub(crate) struct PendingText {
    primitive: usize,
    text: String,
    size: f32,
    origin: Vec2,
    pad: f32,
}

/// A list of 2-D primitives to draw over an image. Colours are straight RGBA in [0, 1];
/// lengths are pixels. Non-finite coordinates are skipped (never a panic).
pub struct Canvas {
    width: u32,
    height: u32,
    primitives: Vec<Primitive>,
    texts: Vec<PendingText>,
}

impl Canvas {
    /// An empty canvas for an image of `width` × `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            primitives: Vec::new(),
            texts: Vec::new(),
        }
    }

    /// Number of primitives so far (text strings included).
    pub fn len(&self) -> usize {
        self.primitives.len()
    }

    pub fn is_empty(&self) -> bool {
        self.primitives.is_empty()
    }

    fn push(&mut self, a: [f32; 4], b: [f32; 4], color: [f32; 4], extra: [f32; 4]) -> usize {
        self.primitives.push(Primitive {
            a,
            b,
            color,
            extra,
            halo: [0.0; 4],
            clip0: NO_CLIP,
            clip1: NO_CLIP,
        });
        self.primitives.len() - 1
    }

    /// An anti-aliased segment from `a` to `b`, `width` pixels wide, with round caps.
    pub fn line(&mut self, a: Vec2, b: Vec2, width: f32, color: [f32; 4]) {
        if !finite(&[a, b]) || width.is_nan() || width <= 0.0 || color[3] <= 0.0 {
            return;
        }
        self.push(
            [a.x, a.y, b.x, b.y],
            [0.0, 0.0, width * 0.5, SEGMENT],
            premultiplied(color, 1.0),
            [0.0; 4],
        );
    }

    /// Connected segments through `points`. Round joins; where a translucent polyline bends,
    /// the joints overlap and come out slightly darker.
    pub fn polyline(&mut self, points: &[Vec2], width: f32, color: [f32; 4]) {
        for pair in points.windows(2) {
            self.line(pair[0], pair[1], width, color);
        }
    }

    /// The outline of the axis-aligned rectangle `[min, max]`.
    pub fn rect_outline(&mut self, min: Vec2, max: Vec2, width: f32, color: [f32; 4]) {
        let corners = [
            min,
            Vec2::new(max.x, min.y),
            max,
            Vec2::new(min.x, max.y),
            min,
        ];
        self.polyline(&corners, width, color);
    }

    /// A filled, anti-aliased disc.
    pub fn disc(&mut self, centre: Vec2, radius: f32, color: [f32; 4]) {
        if !finite(&[centre]) || radius.is_nan() || radius <= 0.0 || color[3] <= 0.0 {
            return;
        }
        self.push(
            [centre.x, centre.y, 0.0, 0.0],
            [0.0, 0.0, radius, DISC],
            premultiplied(color, 1.0),
            [0.0; 4],
        );
    }

    /// A filled, anti-aliased triangle.
    pub fn triangle(&mut self, [p0, p1, p2]: [Vec2; 3], color: [f32; 4]) {
        self.triangle_edges([p0, p1, p2], color, 0b111);
    }

    fn triangle_edges(&mut self, [p0, p1, p2]: [Vec2; 3], color: [f32; 4], edges: u32) -> usize {
        if !finite(&[p0, p1, p2]) || color[3] <= 0.0 {
            return usize::MAX;
        }
        self.push(
            [p0.x, p0.y, p1.x, p1.y],
            [p2.x, p2.y, 0.0, TRIANGLE],
            premultiplied(color, 1.0),
            [edges as f32, 0.0, 0.0, 0.0],
        )
    }

    /// A filled convex polygon (vertices in order, either orientation), anti-aliased on its
    /// outline only (the fan of triangles has no seams), leaving out the inside of up to two
    /// axis-aligned rectangles `(min, max)`.
    pub fn convex_polygon(
        &mut self,
        points: &[Vec2],
        color: [f32; 4],
        excluding: [Option<(Vec2, Vec2)>; 2],
    ) {
        let n = points.len();
        let clip = |r: Option<(Vec2, Vec2)>| r.map_or(NO_CLIP, |(a, b)| [a.x, a.y, b.x, b.y]);
        for i in 1..n.saturating_sub(1) {
            // Edge 0: p0 → pi, edge 1: pi → pi+1, edge 2: pi+1 → p0.
            let edges = u32::from(i == 1) | 0b010 | (u32::from(i + 2 == n) << 2);
            let at = self.triangle_edges([points[0], points[i], points[i + 1]], color, edges);
            if let Some(p) = self.primitives.get_mut(at) {
                p.clip0 = clip(excluding[0]);
                p.clip1 = clip(excluding[1]);
            }
        }
    }

    /// `text` set at `size` pixels with its baseline's left end at `origin`, over a halo of
    /// `halo_width` pixels (0: none, at most [`MAX_HALO`]) in `halo_color`.
    pub fn text(
        &mut self,
        text: &str,
        size: f32,
        origin: Vec2,
        color: [f32; 4],
        halo_color: [f32; 4],
        halo_width: f32,
    ) {
        if text.is_empty() || !finite(&[origin]) || !(size > 0.0 && size.is_finite()) {
            return;
        }
        let halo_width = if halo_color[3] > 0.0 {
            halo_width.clamp(0.0, MAX_HALO)
        } else {
            0.0
        };
        let primitive = self.primitives.len();
        self.primitives.push(Primitive {
            a: [0.0; 4],
            b: [0.0, 0.0, halo_width, TEXT],
            color: premultiplied(color, 1.0),
            extra: [0.0; 4],
            halo: premultiplied(halo_color, 1.0),
            clip0: NO_CLIP,
            clip1: NO_CLIP,
        });
        self.texts.push(PendingText {
            primitive,
            text: text.to_owned(),
            size,
            origin,
            pad: halo_width.ceil() + 1.0,
        });
    }

    /// Rasterises the pending strings into one coverage atlas (shelf packing) and points their
    /// primitives at their cells. Strings wholly outside the image are dropped.
    fn atlas(&mut self, max_side: u32) -> Result<(u32, u32, Vec<u8>), String> {
        let frame = Vec2::new(self.width as f32, self.height as f32);
        // (primitive, screen origin of the cell, cell size, baseline in the cell).
        let mut cells = Vec::new();
        for t in &self.texts {
            let [w, _] = label_font::measure(&t.text, t.size);
            let ascent = label_font::ascent(t.size);
            let descent = (label_font::measure("", t.size)[1] - ascent).max(0.0);
            let lo = (t.origin - Vec2::new(t.pad + 1.0, ascent + t.pad + 1.0)).floor();
            let hi = (t.origin + Vec2::new(w + t.pad + 1.0, descent + t.pad + 1.0)).ceil();
            if hi.x <= 0.0 || hi.y <= 0.0 || lo.x >= frame.x || lo.y >= frame.y {
                self.primitives[t.primitive].color = [0.0; 4];
                self.primitives[t.primitive].halo = [0.0; 4];
                continue;
            }
            let size = hi - lo;
            if size.x > max_side as f32 || size.y > max_side as f32 {
                // Name the text by its start: the offending one may be very long.
                let shown: String = t.text.chars().take(40).collect();
                let more = if t.text.chars().count() > 40 {
                    "…"
                } else {
                    ""
                };
                return Err(format!(
                    "the text `{shown}{more}` ({} characters) at {} px is {}×{} px, more than \
                     the GPU's {max_side} px",
                    t.text.chars().count(),
                    t.size,
                    size.x,
                    size.y
                ));
            }
            cells.push((
                t.primitive,
                lo,
                size.as_uvec2(),
                t.origin - lo,
                &t.text,
                t.size,
            ));
        }
        // Shelves of cells left to right, rows top to bottom.
        let width = cells
            .iter()
            .map(|c| c.2.x)
            .max()
            .unwrap_or(1)
            .max(256)
            .min(max_side);
        let (mut x, mut y, mut shelf) = (0u32, 0u32, 0u32);
        let mut placed = Vec::with_capacity(cells.len());
        for c in &cells {
            if x + c.2.x > width {
                (x, y, shelf) = (0, y + shelf, 0);
            }
            placed.push((x, y));
            x += c.2.x;
            shelf = shelf.max(c.2.y);
        }
        let height = (y + shelf).max(1);
        if height > max_side {
            return Err(format!(
                "the label texts need a {width}×{height} atlas, more than the GPU's {max_side} px"
            ));
        }
        let mut coverage = vec![0.0f32; (width * height) as usize];
        let mut cell_coverage = Vec::new();
        for (c, &(x, y)) in cells.iter().zip(&placed) {
            let (primitive, lo, size, baseline, text, font_size) = *c;
            cell_coverage.clear();
            cell_coverage.resize((size.x * size.y) as usize, 0.0);
            let origin = [baseline.x, baseline.y];
            label_font::rasterize(text, font_size, origin, &mut cell_coverage, size.x, size.y);
            for row in 0..size.y {
                let src = (row * size.x) as usize;
                let dst = ((y + row) * width + x) as usize;
                coverage[dst..dst + size.x as usize]
                    .copy_from_slice(&cell_coverage[src..src + size.x as usize]);
            }
            let p = &mut self.primitives[primitive];
            p.a = [lo.x, lo.y, 0.0, 0.0];
            p.extra = [x as f32, y as f32, size.x as f32, size.y as f32];
        }
        let bytes = coverage
            .iter()
            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
            .collect();
        Ok((width, height, bytes))
    }

    /// Draws the primitives over `image` (which must be `width` × `height`), returning the new
    /// image; `port` names the image input in errors.
    pub fn draw_over(
        mut self,
        ctx: &mut Ctx,
        image: &Arc<Image>,
        port: &str,
    ) -> Result<Value, NodeError> {
        let texture = &image.texture;
        if texture.format() != IMAGE_FORMAT {
            return Err(NodeError::at_port(
                port,
                format!(
                    "expected an {IMAGE_FORMAT:?} image, got {:?}",
                    texture.format()
                ),
            ));
        }
        if (texture.width(), texture.height()) != (self.width, self.height) {
            return Err(NodeError::at_port(
                port,
                format!(
                    "the image is {}×{}, the drawing is for {}×{}",
                    texture.width(),
                    texture.height(),
                    self.width,
                    self.height
                ),
            ));
        }
        if self.primitives.is_empty() {
            return Ok(Value::Image(image.clone()));
        }
        let max_side = ctx.gpu.device.limits().max_texture_dimension_2d;
        let (aw, ah, atlas) = self
            .atlas(max_side)
            .map_err(|e| NodeError::at_port("annotations", e))?;
        let pipeline = ctx
            .cached("overlay:pipeline", pipeline)
            .map_err(|e| NodeError::new(e.to_string()))?;
        let gpu = &ctx.gpu;
        let atlas = gpu.texture_2d_init(
            "overlay atlas",
            aw,
            ah,
            wgpu::TextureFormat::R8Unorm,
            &atlas,
        );
        let atlas_view = atlas.create_view(&Default::default());
        let uniforms = OverlayUniforms {
            frame: [self.width as f32, self.height as f32],
            pad0: 0.0,
            pad1: 0.0,
        };
        let uniform = gpu.buffer_init(
            "overlay",
            bytemuck::bytes_of(&uniforms),
            wgpu::BufferUsages::UNIFORM,
        );
        let instances = gpu.buffer_init(
            "overlay primitives",
            bytemuck::cast_slice(&self.primitives),
            wgpu::BufferUsages::VERTEX,
        );
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("overlay"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&atlas_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: uniform.as_entire_binding(),
                },
            ],
        });
        let output = gpu.render_target("overlay", self.width, self.height, IMAGE_FORMAT);
        let output_view = output.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_texture(
            texture.as_image_copy(),
            output.as_image_copy(),
            texture.size(),
        );
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("overlay"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &output_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.set_vertex_buffer(0, instances.slice(..));
            pass.draw(0..6, 0..self.primitives.len() as u32);
        }
        let work = encoder.finish();
        ctx.submit(work);
        Ok(Value::Image(Arc::new(Image { texture: output })))
    }
}

pub(crate) fn pipeline(gpu: &GpuContext) -> Result<wgpu::RenderPipeline, GpuError> {
    let source = crate::kinds::source("overlay").ok_or_else(|| GpuError::Validation {
        what: "shader overlay".into(),
        message: "no such shader program".into(),
    })?;
    let module = gpu.shader("overlay", &source)?;
    gpu.checked("pipeline overlay", |device| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("overlay"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<Primitive>() as u64,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &ATTRIBUTES,
                })],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: IMAGE_FORMAT,
                    blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        })
    })
}

/// Reads a width parameter (pixels) and rejects non-finite values by name.
/// Parameter `name`'s value `v` as a length in pixels (finite, not negative).
pub fn pixels(name: &str, v: f32) -> Result<f32, NodeError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(NodeError::new(format!(
            "parameter `{name}`: {v} is not a length in pixels"
        )))
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    // Instanced quads with their own vertex stage.
    k.program("overlay", vec![shaders::part!("overlay.wgsl")])
        .uniform(OverlayUniforms::layout());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_oversized_label_is_named_by_its_start_only() {
        let mut canvas = Canvas::new(64, 64);
        let long = "structure ".repeat(50);
        canvas.text(&long, 200.0, Vec2::new(1.0, 40.0), [0.0; 4], [0.0; 4], 0.0);
        let e = canvas.atlas(1024).expect_err("wider than the atlas limit");
        assert!(e.contains("500 characters") && e.contains('…'), "{e}");
        assert!(e.len() < 200, "the whole label is in the message: {e}");
    }
}
