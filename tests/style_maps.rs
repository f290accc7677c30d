//! Lit-sphere maps from files: a painted or photographed sphere saved as JPEG loads like the same
//! sphere saved as PNG (StyleSet, Bruckner & Gröller §3.1 style maps).

mod common;

use hatchery_graph::ParamValue;
use hatchery_nodes::Value;

#[test]
fn a_jpeg_lit_sphere_map_loads_like_the_png() {
    let dir = tempfile::tempdir().unwrap();
    // A sphere lit from the upper left: bright there, dark at the lower right, 64 × 64.
    let sphere = image::RgbImage::from_fn(64, 64, |x, y| {
        let v = (255.0 * (1.0 - (x + y) as f32 / 126.0)) as u8;
        image::Rgb([v, v / 2, 40])
    });
    let (png, jpg) = (dir.path().join("sphere.png"), dir.path().join("sphere.JPG"));
    sphere.save(&png).unwrap();
    sphere
        .save_with_format(&jpg, image::ImageFormat::Jpeg)
        .unwrap();
    assert_eq!(
        &std::fs::read(&jpg).unwrap()[..2],
        &[0xFF, 0xD8],
        "a JPEG file"
    );

    let mut session = common::session_from_text("(version: 3, nodes: [], edges: [])", 8, 8);
    let styles = format!("{}, {}", png.display(), jpg.display());
    let out = common::run_node(
        &mut session,
        "StyleSet",
        vec![],
        &[("styles", ParamValue::Text(styles))],
    );
    let Value::StyleSet(set) = &out[0] else {
        panic!("not a style set")
    };
    assert_eq!(set.maps.len(), 2);
    let (a, b) = (&set.maps[0], &set.maps[1]);
    assert_eq!(a.size, b.size);
    // JPEG is lossy: every texel within 12/255 of the PNG's, the lighting the same.
    let rgb = |texels: &[[f32; 4]]| -> Vec<[f32; 3]> {
        texels.iter().map(|&[r, g, b, _]| [r, g, b]).collect()
    };
    let (a_rgb, b_rgb) = (rgb(&a.texels), rgb(&b.texels));
    common::assert_images_close(
        "jpeg_vs_png_style_map",
        &a_rgb,
        &b_rgb,
        a.size,
        12.0 / 255.0,
    );
    // Texels are row-major from the top: the upper left is lit, the lower right dark.
    let texel = |x: u32, y: u32| b.texels[(y * b.size + x) as usize][0];
    let (lit, dark) = (
        texel(b.size / 4, b.size / 4),
        texel(3 * b.size / 4, 3 * b.size / 4),
    );
    assert!(lit > dark + 0.3, "lit {lit}, dark {dark}");
}
