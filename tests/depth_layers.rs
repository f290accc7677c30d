//! DepthLayers: the k-buffer's two layers equal GBuffer + DepthPeel's — depth bit for bit,
//! normals within their 16-bit octahedral encoding — on nested spheres (several layers per
//! pixel), in perspective and orthographic views; and its `peel` method is those two passes.

mod common;

use hatchery_nodes::{Session, Value};

const W: u32 = 96;
const H: u32 = 72;

fn session(projection: &str) -> Session {
    let text = format!(
        r#"(version: 2, nodes: [
            (id: "shells", kind: "ProceduralVolume", params: {{"resolution": 64, "shape": "shells"}}),
            (id: "surface", kind: "MarchingCubes", params: {{"iso": 0.0}}),
            (id: "camera", kind: "Camera", params: {{"distance": 3.2, "azimuth": 25.0, "elevation": 15.0, "projection": "{projection}"}}),
            (id: "first", kind: "GBuffer", params: {{}}),
            (id: "second", kind: "DepthPeel", params: {{}}),
            (id: "layers", kind: "DepthLayers", params: {{}}),
            (id: "peeled", kind: "DepthLayers", params: {{"method": "peel"}}),
        ], edges: [
            (from: ("shells", "volume"), to: ("surface", "volume")),
            (from: ("surface", "mesh"), to: ("first", "mesh")),
            (from: ("camera", "camera"), to: ("first", "camera")),
            (from: ("surface", "mesh"), to: ("second", "mesh")),
            (from: ("camera", "camera"), to: ("second", "camera")),
            (from: ("first", "gbuffer"), to: ("second", "previous")),
            (from: ("surface", "mesh"), to: ("layers", "mesh")),
            (from: ("camera", "camera"), to: ("layers", "camera")),
            (from: ("surface", "mesh"), to: ("peeled", "mesh")),
            (from: ("camera", "camera"), to: ("peeled", "camera")),
        ])"#
    );
    let mut session = common::session_from_text(&text, W, H);
    session
        .run(&["second", "layers", "peeled"])
        .unwrap_or_else(|e| panic!("{e}"));
    session
}

/// (depth, normal xyzw) per pixel of a G-buffer output.
fn layer(session: &Session, node: &str, port: &str) -> Vec<(f32, [f32; 4])> {
    let Value::GBuffer(g) = session.output(node, port).unwrap() else {
        panic!("{node}.{port} is not a G-buffer");
    };
    let depth = session.ctx.gpu.read_texture(&g.depth).unwrap();
    let normal = session.ctx.gpu.read_texture(&g.normal).unwrap();
    let mut out = Vec::new();
    for y in 0..H {
        for x in 0..W {
            let n = normal.texel(x, y);
            out.push((depth.texel(x, y)[0], [n[0], n[1], n[2], n[3]]));
        }
    }
    out
}

/// Depth must agree exactly (bit for bit); normals within `tolerance` per component.
fn assert_same(name: &str, got: &[(f32, [f32; 4])], want: &[(f32, [f32; 4])], tolerance: f32) {
    let (got_depth, got_normal): (Vec<f32>, Vec<[f32; 4]>) = got.iter().copied().unzip();
    let (want_depth, want_normal): (Vec<f32>, Vec<[f32; 4]>) = want.iter().copied().unzip();
    common::assert_images_identical(&format!("{name}_depth"), &got_depth, &want_depth, W);
    let name = format!("{name}_normal");
    common::assert_images_close(&name, &got_normal, &want_normal, W, tolerance);
}

#[test]
fn the_k_buffer_layers_equal_gbuffer_and_depth_peel() {
    for projection in ["perspective", "orthographic"] {
        let session = session(projection);
        // Otherwise `layers` would be the two passes themselves and prove nothing. (Lavapipe,
        // which CI runs on, has 64-bit atomics.)
        assert!(
            hatchery_nodes::depth_layers::single_pass_possible(&session.ctx.gpu, W, H),
            "this adapter cannot run the one-pass k-buffer: {}",
            session.ctx.gpu.describe()
        );
        let first = layer(&session, "first", "gbuffer");
        let second = layer(&session, "second", "gbuffer");
        // Both layers cover part of the frame (nested spheres: the second is the inner side).
        let covered = |l: &[(f32, [f32; 4])]| l.iter().filter(|(d, _)| *d < 1.0).count();
        assert!(covered(&first) > 1000, "{projection}: {}", covered(&first));
        assert!(covered(&second) > 500, "{projection}: {}", covered(&second));
        // 16-bit octahedral normals, then Rgba16Float: within a few f16 steps near 1.
        let tolerance = 2e-3;
        assert_same(
            &format!("{projection} layer 1"),
            &layer(&session, "layers", "layer1"),
            &first,
            tolerance,
        );
        assert_same(
            &format!("{projection} layer 2"),
            &layer(&session, "layers", "layer2"),
            &second,
            tolerance,
        );
        // `peel` is exactly the two passes.
        assert_same(
            &format!("{projection} peel 1"),
            &layer(&session, "peeled", "layer1"),
            &first,
            0.0,
        );
        assert_same(
            &format!("{projection} peel 2"),
            &layer(&session, "peeled", "layer2"),
            &second,
            0.0,
        );
    }
}

/// Issue 32: `hidden_layers_brain` takes its two layers from DepthLayers (one geometry pass)
/// instead of GBuffer + DepthPeel. The picture is the peeled one but for a few silhouette
/// pixels: DepthLayers' normals are 16-bit octahedral codes (error ~1e-4), the G-buffer pass
/// writes them to Rgba16Float (~5e-4 near 1), and where eq. 5's normal-difference threshold
/// falls between the two roundings a line pixel flips. At 1024×768 that is 7 of 786 432 pixels
/// on lavapipe (none at presets_unchanged's 160×120). Here, at 512×384: at
/// most 1 in 10 000 pixels may differ, and every differing pixel must lie next to a line in
/// one of the two pictures (a flipped line pixel, not a shifted surface).
#[test]
fn the_hidden_layers_preset_on_one_pass_equals_the_peeled_one_but_for_flipped_line_pixels() {
    let path = common::repo_root().join("graphs/hidden_layers_brain.ron");
    let (w, h) = (512, 384);
    let mut session = Session::open(&path, w, h).unwrap();
    assert!(
        hatchery_nodes::depth_layers::single_pass_possible(&session.ctx.gpu, w, h),
        "this adapter cannot run the one-pass k-buffer: {}",
        session.ctx.gpu.describe()
    );
    let normals = |session: &Session| {
        let Value::GBuffer(g) = session.output("layers", "layer1").unwrap() else {
            panic!("layers.layer1 is not a G-buffer");
        };
        session.ctx.gpu.read_texture(&g.normal).unwrap()
    };
    let one_pass = common::saver_input(&mut session, "save").unwrap();
    let one_pass_normals = normals(&session);
    session.set_param_text("layers", "method", "peel").unwrap();
    let peeled = common::saver_input(&mut session, "save").unwrap();
    // The two runs took different paths: the normals differ in their rounding.
    let peeled_normals = normals(&session);
    let rounded_apart = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| one_pass_normals.texel(x, y) != peeled_normals.texel(x, y))
        .count();
    assert!(
        rounded_apart > 1000,
        "only {rounded_apart} normals differ: one path ran twice?"
    );
    let dark = |p: &image::Rgba<u8>| p.0[..3].iter().map(|&c| c as u32).sum::<u32>() < 3 * 96;
    let near_line = |x: u32, y: u32| {
        (x.saturating_sub(1)..(x + 2).min(w)).any(|u| {
            (y.saturating_sub(1)..(y + 2).min(h))
                .any(|v| dark(one_pass.get_pixel(u, v)) || dark(peeled.get_pixel(u, v)))
        })
    };
    let mut differing = 0;
    for (x, y, p) in one_pass.enumerate_pixels() {
        let q = peeled.get_pixel(x, y);
        if p.0.iter().zip(q.0).any(|(a, b)| a.abs_diff(b) > 1) {
            differing += 1;
            assert!(
                near_line(x, y),
                "pixel ({x}, {y}) differs ({p:?} vs {q:?}) away from any line"
            );
        }
    }
    let limit = (w * h) as usize / 10_000;
    assert!(
        differing <= limit,
        "{differing} pixels differ (at most {limit}); see {} and {}",
        common::save_failure("hidden_layers_one_pass", &one_pass).display(),
        common::save_failure("hidden_layers_peeled", &peeled).display()
    );
    eprintln!("{differing} of {} pixels differ", w * h);
}
