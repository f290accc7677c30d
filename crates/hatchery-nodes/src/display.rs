//! Pictures of values for screens: what the editor's viewport and pin thumbnails show. Frame
//! textures (images, masks, G-buffers) are drawn on the GPU straight into an opaque Rgba8Unorm
//! texture that egui can sample without a copy to the CPU; the small CPU-side values (volumes,
//! transfer functions, style sets) are drawn by [`export::to_rgba8`] and uploaded.

use crate::export::{self, ExportError};
use crate::screen_pass;
use crate::{Ctx, Value};

crate::uniform_block! {
    /// `Display` of shaders/display.wgsl: what the texture holds (0 image, 1 mask, 2 normals),
    /// the checkerboard cell in pixels and the output size.
    pub struct DisplayUniforms in "display" as "Display" {
        /// A [`Shows`] code.
        pub mode: u32,
        pub checker: f32,
        pub out_width: f32,
        pub out_height: f32,
    }
}

crate::gpu_enum! {
    /// What a display texture is made from.
    pub enum Shows in "display" {
        /// A premultiplied image.
        Image = 0 as "SHOW_IMAGE",
        /// A mask, shown grey.
        Mask = 1 as "SHOW_MASK",
        /// A G-buffer's normals (n·0.5 + 0.5).
        Normals = 2 as "SHOW_NORMALS",
    }
}

/// Format of display textures: display (sRGB-encoded) values, opaque, as egui draws textures.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Side of a checkerboard square behind transparent pixels, in display pixels.
pub const CHECKER: u32 = 8;

/// The checkerboard grey at display pixel (x, y) (as `display.wgsl` draws it).
pub fn checkerboard(x: u32, y: u32) -> f32 {
    if ((x / CHECKER) + (y / CHECKER)).is_multiple_of(2) {
        0.9
    } else {
        0.75
    }
}

/// The largest size with the aspect ratio of `source` that fits in `bound`.
pub fn fit(source: (u32, u32), bound: (u32, u32)) -> (u32, u32) {
    let (sw, sh) = (source.0.max(1) as f64, source.1.max(1) as f64);
    let scale = (bound.0 as f64 / sw).min(bound.1 as f64 / sh);
    (
        ((sw * scale).round() as u32).max(1),
        ((sh * scale).round() as u32).max(1),
    )
}

/// The size of the texture a value is drawn from (`None` for values without a picture).
pub fn source_size(value: &Value) -> Option<(u32, u32)> {
    let t = match value {
        Value::Image(i) => &i.texture,
        Value::Mask(m) => &m.texture,
        Value::GBuffer(g) => &g.normal,
        Value::Importance(i) => &i.buffer,
        Value::Volume(v) => return Some((v.data.dims[0], v.data.dims[1])),
        Value::Labels(l) => return Some((l.data.dims[0], l.data.dims[1])),
        Value::VectorField(f) => return Some((f.data.dims[0], f.data.dims[1])),
        Value::TransferFunction(_) => return Some((256, 32)),
        Value::StyleSet(s) => {
            let size = s.maps.first().map_or(1, |m| m.size);
            return Some((size * s.maps.len().max(1) as u32, size));
        }
        Value::Mesh(_)
        | Value::Camera(_)
        | Value::Light(_)
        | Value::ObjectStyles(_)
        | Value::Annotations(_)
        | Value::Strokes(_) => {
            return None;
        }
    };
    Some((t.width(), t.height()))
}

/// A display texture of `value`, scaled (aspect kept) to fit in `bound`.
pub fn display_texture(
    ctx: &mut Ctx,
    value: &Value,
    bound: (u32, u32),
) -> Result<wgpu::Texture, ExportError> {
    let no_picture = || {
        ExportError::NoSuchForm(format!(
            "a {} value has no picture; preview a port that feeds a renderer",
            value.port_type()
        ))
    };
    let size = fit(source_size(value).ok_or_else(no_picture)?, bound);
    let (texture, mode) = match value {
        Value::Image(i) => (&i.texture, Shows::Image),
        Value::Mask(m) => (&m.texture, Shows::Mask),
        Value::GBuffer(g) => (&g.normal, Shows::Normals),
        _ => return upload_picture(ctx, value, size),
    };
    let uniform = DisplayUniforms {
        mode: mode.code(),
        checker: CHECKER as f32,
        out_width: size.0 as f32,
        out_height: size.1 as f32,
    };
    screen_pass::render(
        ctx,
        "display",
        DISPLAY_FORMAT,
        size,
        &[texture],
        Some(bytemuck::bytes_of(&uniform)),
    )
    .map_err(ExportError::Gpu)
}

/// Small CPU-side values: drawn on the CPU, over the checkerboard, then uploaded.
fn upload_picture(
    ctx: &mut Ctx,
    value: &Value,
    size: (u32, u32),
) -> Result<wgpu::Texture, ExportError> {
    let picture = export::to_rgba8(value, &ctx.gpu)?;
    let picture = image::imageops::resize(
        &picture,
        size.0,
        size.1,
        image::imageops::FilterType::Triangle,
    );
    let mut bytes = Vec::with_capacity(picture.len());
    for (x, y, p) in picture.enumerate_pixels() {
        let a = p[3] as f32 / 255.0;
        let back = checkerboard(x, y) * 255.0;
        for c in &p.0[..3] {
            bytes.push((*c as f32 * a + back * (1.0 - a)).round() as u8);
        }
        bytes.push(255);
    }
    ctx.gpu.check_2d_size("the picture", size.0, size.1)?;
    Ok(ctx
        .gpu
        .texture_2d_init("display", size.0, size.1, DISPLAY_FORMAT, &bytes))
}



/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.program("display", shaders::screen(shaders::part!("display.wgsl")))
        .uniform(DisplayUniforms::layout())
        .gpu_enum(Shows::wgsl());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_keeps_the_aspect_ratio() {
        assert_eq!(fit((640, 480), (160, 160)), (160, 120));
        assert_eq!(fit((100, 400), (160, 160)), (40, 160));
        assert_eq!(fit((0, 0), (10, 10)), (10, 10));
    }

    #[test]
    fn checkerboard_alternates_every_square() {
        assert_eq!(checkerboard(0, 0), 0.9);
        assert_eq!(checkerboard(CHECKER, 0), 0.75);
        assert_eq!(checkerboard(CHECKER, CHECKER), 0.9);
    }
}
