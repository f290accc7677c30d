//! The SVG a preset writes is the figure its PNG shows (issue 24, item 6): every preset with a
//! SaveSvg is rendered once by `hatchery render -o x.svg` (which writes x.png beside it), the
//! SVG rasterised by resvg with the labels' font, and compared with the PNG pixel by pixel.
//!
//! The tolerance: the picture layer is the PNG's pixels, so differences come only from what is
//! drawn as vectors — the visible line layers (traced masks, anti-aliased where the raster's
//! masks are not), hatching strokes (filled outlines, whose overlaps add where the raster takes
//! the larger coverage) and labels (resvg's glyph rasteriser, not the overlay's). Both pictures
//! are compared as seen at their size: through a 3×3 box filter, which forgives anti-aliasing of
//! an edge but not a line moved, thickened, added or left out. The mean channel difference stays
//! under 4/255 and at most 0.5 % of the pixels differ by more than 64/255 (measured at 480×360:
//! default 0.34/255 and 0.01 %, hatching_brain 2.8/255 and 0.01 %; without the filter 0.44/255
//! and 0.14 %, 3.9/255 and 1.0 %).

mod common;

use std::sync::Arc;

const SIZE: (u32, u32) = (480, 360);

fn svg_presets() -> Vec<std::path::PathBuf> {
    common::presets()
        .into_iter()
        .filter(|p| {
            std::fs::read_to_string(p)
                .unwrap()
                .contains("kind: \"SaveSvg\"")
        })
        .collect()
}

/// Rasterises the SVG at `path` with the label font loaded (`SIZE` pixels).
fn rasterise(path: &std::path::Path) -> image::RgbaImage {
    let text = std::fs::read_to_string(path).unwrap();
    let mut options = usvg::Options::default();
    Arc::make_mut(&mut options.fontdb).load_font_data(hatchery_nodes::label_font::data().to_vec());
    let tree = usvg::Tree::from_str(&text, &options).unwrap();
    let mut pixmap = tiny_skia::Pixmap::new(SIZE.0, SIZE.1).unwrap();
    // On white paper: an SVG without a picture layer (vector-only, as hatching_brain's) leaves
    // its background transparent, where the PNG has the graph's paper.
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    // tiny-skia's pixels are premultiplied; on opaque paper they are not.
    image::RgbaImage::from_raw(SIZE.0, SIZE.1, pixmap.data().to_vec()).unwrap()
}

/// The picture through a 3×3 box filter (edge pixels repeated).
fn box3(picture: &image::RgbaImage) -> image::RgbaImage {
    let (w, h) = picture.dimensions();
    image::RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 4];
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let sx = (x as i64 + dx).clamp(0, w as i64 - 1) as u32;
                let sy = (y as i64 + dy).clamp(0, h as i64 - 1) as u32;
                let p = picture.get_pixel(sx, sy);
                for c in 0..4 {
                    sum[c] += u32::from(p[c]);
                }
            }
        }
        image::Rgba(sum.map(|v| ((v + 4) / 9) as u8))
    })
}

#[test]
fn every_presets_svg_rasterises_to_its_png() {
    let presets = svg_presets();
    assert!(presets.len() >= 2, "{presets:?}");
    let dir = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    for preset in presets {
        let name = preset.file_stem().unwrap().to_str().unwrap().to_owned();
        let svg = dir.path().join(format!("{name}.svg"));
        let out = common::hatchery(&[
            "render",
            preset.to_str().unwrap(),
            "--size",
            &format!("{}x{}", SIZE.0, SIZE.1),
            "-o",
            svg.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let png = common::read_png(&svg.with_extension("png"));
        let drawn = rasterise(&svg);
        if std::env::var_os("HATCHERY_KEEP_SVG_TEST").is_some() {
            let _ = png.save(common::save_failure(
                &format!("svg_equals_png_{name}_png"),
                &png,
            ));
            common::save_failure(&format!("svg_equals_png_{name}"), &drawn);
        }
        assert_eq!(png.dimensions(), drawn.dimensions(), "{name}");
        let rgb = |p: &image::RgbaImage| -> Vec<[u8; 3]> {
            box3(p).pixels().map(|p| [p[0], p[1], p[2]]).collect()
        };
        let (a, b) = (rgb(&png), rgb(&drawn));
        let by_pixel = common::diff_images(&a, &b, png.width(), |_| true, 64.0);
        // The mean over channels: the pictures as rows of 3 × width single channels.
        let by_channel =
            common::diff_images(&a.concat(), &b.concat(), 3 * png.width(), |_| true, 0.0);
        let worst = (by_pixel.worst as u8, by_pixel.x, by_pixel.y);
        let pixels = (SIZE.0 * SIZE.1) as usize;
        let mean = by_channel.sum / (3 * pixels) as f64;
        let far_fraction = by_pixel.over.len() as f64 / pixels as f64;
        let report = format!(
            "{name}: mean difference {mean:.3}/255, {:.3} % of pixels beyond 64/255, worst {} at \
             ({}, {}) (3×3 box filtered)",
            100.0 * far_fraction,
            worst.0,
            worst.1,
            worst.2
        );
        eprintln!("{report}");
        if mean > 4.0 || far_fraction > 0.005 {
            let saved = common::save_failure(&format!("svg_equals_png_{name}"), &drawn);
            failures.push(format!(
                "{report}; the rasterised SVG is {}",
                saved.display()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
