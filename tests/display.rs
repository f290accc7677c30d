//! The editor's display pictures (display.wgsl) against a CPU reference of the same rule: box
//! filter over the source rectangle under each output pixel, then "over" a checkerboard.

mod common;

use common::session_from_text;
use hatchery_gpu::TextureData;
use hatchery_graph::ParamValue;
use hatchery_nodes::display::{self, checkerboard};
use hatchery_nodes::{Session, Value};

fn shaded_surface(width: u32, height: u32) -> Session {
    let text = std::fs::read_to_string(common::repo_root().join("graphs/shaded_surface.ron"))
        .expect("preset readable");
    session_from_text(&text, width, height)
}

/// The CPU reference of one display pixel from premultiplied source texels.
fn reference(
    source: &TextureData,
    to_premultiplied: fn(&[f32]) -> [f32; 4],
    out: (u32, u32),
    x: u32,
    y: u32,
) -> [f32; 3] {
    let scale = [
        source.width as f32 / out.0 as f32,
        source.height as f32 / out.1 as f32,
    ];
    let taps = scale.map(|s| (s.ceil() as i32).clamp(1, 4));
    let mut sum = [0.0f32; 4];
    for j in 0..taps[1] {
        for i in 0..taps[0] {
            let sx = x as f32 * scale[0] + (i as f32 + 0.5) * scale[0] / taps[0] as f32;
            let sy = y as f32 * scale[1] + (j as f32 + 0.5) * scale[1] / taps[1] as f32;
            let sx = (sx.floor() as u32).min(source.width - 1);
            let sy = (sy.floor() as u32).min(source.height - 1);
            let p = to_premultiplied(source.texel(sx, sy));
            for c in 0..4 {
                sum[c] += p[c];
            }
        }
    }
    let n = (taps[0] * taps[1]) as f32;
    let a = (sum[3] / n).clamp(0.0, 1.0);
    let back = checkerboard(x, y);
    [0, 1, 2].map(|c| ((sum[c] / n).clamp(0.0, 1.0) + (1.0 - a) * back).min(1.0))
}

/// Fails unless every pixel of a display picture is within 1/255 of `want` (RGB); display
/// pictures are opaque.
fn assert_shows(name: &str, shown: &TextureData, want: impl Fn(u32, u32) -> [f32; 3]) {
    let got: Vec<[f32; 3]> = common::texels(shown)
        .into_iter()
        .map(|[r, g, b, a]| {
            assert_eq!(a, 1.0, "display pictures are opaque");
            [r, g, b]
        })
        .collect();
    let want: Vec<[f32; 3]> = (0..shown.width * shown.height)
        .map(|i| want(i % shown.width, i / shown.width))
        .collect();
    // Within 1/255 as compared in f64 before.
    let tolerance = common::f32_at_most(1.0 / 255.0);
    common::assert_images_close(name, &got, &want, shown.width, tolerance);
}

#[test]
fn display_pictures_match_the_cpu_reference_at_full_and_reduced_size() {
    let (w, h) = (160, 120);
    let mut session = shaded_surface(w, h);
    // A transparent background and a half-transparent object, so the checkerboard shows.
    for (name, rgba) in [("background", [0.0; 4]), ("color", [0.85, 0.5, 0.3, 0.6])] {
        session
            .graph
            .set_param(&session.registry, "shaded", name, ParamValue::Color(rgba))
            .expect("valid parameter");
    }
    let image = session.evaluate("shaded", "image").expect("renders");
    let Value::Image(i) = &image else {
        panic!("ShadedSurface gives an image")
    };
    let source = session.ctx.gpu.read_texture(&i.texture).expect("read back");
    let covered = source.data.chunks_exact(4).filter(|p| p[3] > 0.3).count();
    let empty = source.data.chunks_exact(4).filter(|p| p[3] < 0.01).count();
    assert!(
        covered > 1000 && empty > 1000,
        "the test image needs object and background: {covered} covered, {empty} empty"
    );

    for bound in [(w, h), (80, 60), (57, 43)] {
        let texture = display::display_texture(&mut session.ctx, &image, bound).expect("display");
        assert_eq!(texture.format(), display::DISPLAY_FORMAT);
        let shown = session.ctx.gpu.read_texture(&texture).expect("read back");
        let out = (shown.width, shown.height);
        assert_eq!(out, display::fit((w, h), bound));
        assert_shows(
            &format!("display_image_{}x{}", out.0, out.1),
            &shown,
            |x, y| reference(&source, |t| [t[0], t[1], t[2], t[3]], out, x, y),
        );
    }
}

#[test]
fn display_of_gbuffer_normals_and_of_a_volume() {
    let (w, h) = (96, 72);
    let text = r#"(
        version: 1,
        nodes: [
            (id: "camera", kind: "Camera", params: {}),
            (id: "shells", kind: "ProceduralVolume", params: {"resolution": 48, "shape": "sphere"}),
            (id: "surface", kind: "MarchingCubes", params: {"iso": 0.0}),
            (id: "g", kind: "GBuffer", params: {}),
        ],
        edges: [
            (from: ("shells", "volume"), to: ("surface", "volume")),
            (from: ("surface", "mesh"), to: ("g", "mesh")),
            (from: ("camera", "camera"), to: ("g", "camera")),
        ],
    )"#;
    let mut session = session_from_text(text, w, h);
    let gbuffer = session.evaluate("g", "gbuffer").expect("renders");
    let Value::GBuffer(g) = &gbuffer else {
        panic!("a G-buffer")
    };
    let source = session.ctx.gpu.read_texture(&g.normal).expect("read back");
    let texture = display::display_texture(&mut session.ctx, &gbuffer, (w, h)).expect("display");
    let shown = session.ctx.gpu.read_texture(&texture).expect("read back");
    assert_shows("display_normals", &shown, |x, y| {
        reference(
            &source,
            |t| {
                let a = t[3].clamp(0.0, 1.0);
                let c = |v: f32| (v * 0.5 + 0.5) * a;
                [c(t[0]), c(t[1]), c(t[2]), a]
            },
            (w, h),
            x,
            y,
        )
    });

    // Volumes are drawn on the CPU (middle slice) and uploaded at the fitted size.
    let volume = session.evaluate("shells", "volume").expect("volume");
    let texture = display::display_texture(&mut session.ctx, &volume, (200, 100)).expect("display");
    assert_eq!((texture.width(), texture.height()), (100, 100));
    let shown = session.ctx.gpu.read_texture(&texture).expect("read back");
    let (centre, corner) = (shown.texel(50, 50)[0], shown.texel(1, 1)[0]);
    assert!(
        (centre - corner).abs() > 0.2,
        "the sphere's slice differs from its corner: {centre} vs {corner}"
    );

    // Cameras have no picture: a clear error, not a panic.
    let camera = session.evaluate("camera", "camera").expect("camera");
    let e = display::display_texture(&mut session.ctx, &camera, (64, 64))
        .unwrap_err()
        .to_string();
    assert!(e.contains("Camera") || e.contains("camera"), "{e}");
}
