//! The font of annotation labels: Ubuntu Light (the open font egui ships, through the
//! `epaint_default_fonts` crate), measured and rasterised with `ab_glyph`.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use std::sync::OnceLock;

/// The label font's family name, as SVG text names it (with generic fallbacks).
pub const FAMILY: &str = "'Ubuntu Light', Ubuntu, 'DejaVu Sans', sans-serif";

/// The label font's file (TrueType), e.g. for an SVG renderer's font database, so that an
/// SVG's <text> is set in the font the picture's labels were.
pub fn data() -> &'static [u8] {
    epaint_default_fonts::UBUNTU_LIGHT
}

fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(data()).expect("the bundled font parses"))
}

/// Width and height (pixels) of `text` set at `size` pixels: the advance widths with kerning,
/// and ascent − descent.
pub fn measure(text: &str, size: f32) -> [f32; 2] {
    let f = font().as_scaled(PxScale::from(size));
    let mut width = 0.0;
    let mut previous = None;
    for c in text.chars() {
        let id = f.glyph_id(c);
        if let Some(p) = previous {
            width += f.kern(p, id);
        }
        width += f.h_advance(id);
        previous = Some(id);
    }
    [width, f.ascent() - f.descent()]
}

/// Coverage (0–1) of `text` set at `size` pixels with its baseline's left end at `origin`
/// (pixels, y down), added into `coverage` (`width` × `height`, row-major) by maximum.
pub fn rasterize(
    text: &str,
    size: f32,
    origin: [f32; 2],
    coverage: &mut [f32],
    width: u32,
    height: u32,
) {
    let scale = PxScale::from(size);
    let f = font().as_scaled(scale);
    let mut x = origin[0];
    let mut previous = None;
    for c in text.chars() {
        let id = f.glyph_id(c);
        if let Some(p) = previous {
            x += f.kern(p, id);
        }
        let glyph = id.with_scale_and_position(scale, ab_glyph::point(x, origin[1]));
        x += f.h_advance(id);
        previous = Some(id);
        let Some(outline) = font().outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, c| {
            let px = bounds.min.x as i32 + gx as i32;
            let py = bounds.min.y as i32 + gy as i32;
            if px >= 0 && py >= 0 && (px as u32) < width && (py as u32) < height {
                let at = py as usize * width as usize + px as usize;
                coverage[at] = coverage[at].max(c);
            }
        });
    }
}

/// The SVG `font-size` (the em size, pixels) of text set here at `size` pixels: ab_glyph's
/// `PxScale` is the height from descent to ascent, SVG's font size the em square, so the same
/// glyphs in an SVG need `size × units_per_em / (ascent − descent)`.
pub fn svg_font_size(size: f32) -> f32 {
    let f = font();
    size * f.units_per_em().unwrap_or(1000.0) / f.height_unscaled()
}

/// The baseline's distance below a label box's top edge at `size` pixels (the ascent).
pub fn ascent(size: f32) -> f32 {
    font().as_scaled(PxScale::from(size)).ascent()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wider_text_measures_wider_and_draws_ink_inside_its_box() {
        let [w1, h] = measure("liver", 14.0);
        let [w2, _] = measure("liver and kidneys", 14.0);
        assert!(
            w1 > 14.0 && w2 > 2.5 * w1 && (12.0..20.0).contains(&h),
            "{w1} {w2} {h}"
        );
        let (width, height) = (64u32, 24u32);
        let mut coverage = vec![0.0; (width * height) as usize];
        rasterize(
            "liver",
            14.0,
            [2.0, 2.0 + ascent(14.0)],
            &mut coverage,
            width,
            height,
        );
        let ink: Vec<(u32, u32)> = (0..width * height)
            .filter(|&i| coverage[i as usize] > 0.5)
            .map(|i| (i % width, i / width))
            .collect();
        assert!(ink.len() > 20, "{} inked pixels", ink.len());
        let right = ink.iter().map(|p| p.0).max().unwrap() as f32;
        assert!(
            right <= 2.0 + w1 + 1.0,
            "ink to x = {right}, measured width {w1}"
        );
    }
}
