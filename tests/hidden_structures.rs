//! Hidden iso-surface structures (Fischer et al. 2005): a CPU reference of eq. 1–10 and the §3.3.4
//! final colour, applied to the G-buffers the GPU produced, must give the GPU nodes' masks and
//! picture; depth peeling against analytic nested spheres; halftoning against the τ rule; PIP.

mod common;

use glam::{Mat4, Vec3, Vec4};
use hatchery_graph::{ParamValue, Params};
use hatchery_nodes::export::{self, Array};
use hatchery_nodes::value::Mask;
use hatchery_nodes::{Session, Value};
use std::collections::BTreeMap;
use std::sync::Arc;

const W: u32 = 240;
const H: u32 = 180;

fn array(session: &Session, node: &str, port: &str) -> Array {
    export::to_array(session.output(node, port).unwrap(), &session.ctx.gpu).unwrap()
}

/// A read-back G-buffer: depth and normal per pixel.
struct Layer {
    depth: Vec<f32>,
    normal: Vec<Vec3>,
    covered: Vec<bool>,
}

fn layer(session: &Session, node: &str, port: &str) -> Layer {
    let a = array(session, node, port);
    assert_eq!(a.shape, vec![H as usize, W as usize, 4]);
    let mut depth = Vec::new();
    let mut normal = Vec::new();
    for px in a.data.chunks_exact(4) {
        depth.push(px[0]);
        normal.push(Vec3::new(px[1], px[2], px[3]));
    }
    // Coverage is the normal target's w; the dump carries depth + xyz, and empty pixels have
    // depth 1 and a zero normal.
    let covered = normal.iter().map(|n| n.length_squared() > 0.5).collect();
    Layer {
        depth,
        normal,
        covered,
    }
}

fn at(x: i64, y: i64) -> usize {
    let x = x.clamp(0, W as i64 - 1);
    let y = y.clamp(0, H as i64 - 1);
    (y as usize) * W as usize + x as usize
}

/// Eq. 3–5 and their OR, exactly as specified, with neighbours clamped at the image border.
fn silhouette_reference(l: &Layer, depth_threshold: f32, normal_threshold: f32) -> Vec<f32> {
    let mut out = vec![0.0; (W * H) as usize];
    for y in 0..H as i64 {
        for x in 0..W as i64 {
            let d = |dx: i64, dy: i64| l.depth[at(x + dx, y + dy)];
            let gx = (d(1, -1) + 2.0 * d(1, 0) + d(1, 1)) - (d(-1, -1) + 2.0 * d(-1, 0) + d(-1, 1));
            let gy = (d(-1, 1) + 2.0 * d(0, 1) + d(1, 1)) - (d(-1, -1) + 2.0 * d(0, -1) + d(1, -1));
            let depth_response = (gx * gx + gy * gy).sqrt() >= depth_threshold;
            let i = at(x, y);
            let normal_response = l.covered[i] && {
                let n = l.normal[i];
                let similarity = n.dot(l.normal[at(x + 1, y)])
                    + n.dot(l.normal[at(x - 1, y)])
                    + n.dot(l.normal[at(x, y + 1)])
                    + n.dot(l.normal[at(x, y - 1)]);
                similarity < normal_threshold
            };
            out[i] = if depth_response || normal_response {
                1.0
            } else {
                0.0
            };
        }
    }
    out
}

/// Eq. 7–8: the halftone threshold τ at pixel (x, y).
fn tau(x: u32, y: u32, theta: f32, n: f32, c_cross: f32) -> f32 {
    let (x, y) = (x as f32, y as f32);
    let xr = theta.cos() * x - theta.sin() * y;
    let yr = theta.sin() * x + theta.cos() * y;
    let wrap = |v: f32| (v - n * (v / n).floor()) / n;
    let (s, t) = (wrap(xr), wrap(yr));
    if s <= c_cross {
        c_cross * t
    } else {
        (1.0 - c_cross) * s + c_cross
    }
}

/// Pixels where two binary masks differ; each must lie on a border of the reference (its 3×3
/// neighbourhood holds both values), and there may be at most 0.1 % of them.
fn compare_masks(name: &str, gpu: &[f32], reference: &[f32]) -> Vec<usize> {
    let diff = common::diff_images(gpu, reference, W, |_| true, 0.5);
    let on_border = |i: usize| {
        let (x, y) = ((i % W as usize) as i64, (i / W as usize) as i64);
        let mut seen = [false; 2];
        for dy in -1..=1 {
            for dx in -1..=1 {
                seen[(reference[at(x + dx, y + dy)] > 0.5) as usize] = true;
            }
        }
        seen[0] && seen[1]
    };
    let inner: Vec<usize> = diff
        .over
        .iter()
        .copied()
        .filter(|&i| !on_border(i))
        .collect();
    let fraction = diff.over.len() as f64 / gpu.len() as f64;
    if fraction > 0.001 || !inner.is_empty() {
        let why = format!(
            "{} pixels differ ({:.4} %), {} of them off mask borders (first at {:?})",
            diff.over.len(),
            fraction * 100.0,
            inner.len(),
            inner.first().map(|i| (i % W as usize, i / W as usize)),
        );
        diff.fail(name, gpu, reference, why);
    }
    diff.over
}

fn params_of(session: &Session, node: &str) -> Params {
    session.graph.node(node).unwrap().params.clone()
}

#[test]
fn gpu_masks_and_final_colour_match_the_cpu_reference_of_eq_1_to_10() {
    let path = common::repo_root().join("graphs/hidden_structures.ron");
    let mut session = Session::open(&path, W, H).unwrap();
    // Every node whose output is read below is a target: image-space nodes run fused, and a
    // fused pass writes only what something asks for.
    session
        .run(&[
            "front_hatching",
            "silhouette1",
            "silhouette2",
            "hatching",
            "intensity1",
            "secondary",
            "secondary_final",
        ])
        .unwrap();

    let l1 = layer(&session, "layer1", "gbuffer");
    let l2 = layer(&session, "layer2", "gbuffer");
    let s = layer(&session, "secondary", "gbuffer");
    let light = match session.output("light", "light").unwrap() {
        Value::Light(l) => l.clone(),
        _ => unreachable!(),
    };
    let camera = match session.output("camera", "camera").unwrap() {
        Value::Camera(c) => c.clone(),
        _ => unreachable!(),
    };
    let l = light.view_direction(&camera);
    let sil_params = params_of(&session, "silhouette1");
    let halftone = params_of(&session, "hatching");
    let secondary = params_of(&session, "secondary");
    let (alpha, beta) = (secondary.f32("alpha"), secondary.f32("beta"));

    // Eq. 6: diffuse intensity of layer 1 (1 where empty: the node's `empty` default).
    let i_p1: Vec<f32> = (0..l1.depth.len())
        .map(|i| {
            if l1.covered[i] {
                l1.normal[i].normalize().dot(l).max(0.0)
            } else {
                1.0
            }
        })
        .collect();
    // Eq. 3–5 for both layers.
    let (dt, nt) = (
        sil_params.f32("depth_threshold"),
        sil_params.f32("normal_threshold"),
    );
    let sil1 = silhouette_reference(&l1, dt, nt);
    let sil2 = silhouette_reference(&l2, dt, nt);
    // Eq. 7–9.
    let (theta, n, c_cross) = (
        halftone.f32("theta").to_radians(),
        halftone.f32("cell"),
        halftone.f32("c_cross"),
    );
    let hatching: Vec<f32> = (0..W * H)
        .map(|i| {
            if i_p1[i as usize] >= tau(i % W, i / W, theta, n, c_cross) {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    // Eq. 1–2: secondary geometry intensity from S's own normals and depth.
    let i_s: Vec<f32> = (0..s.depth.len())
        .map(|i| {
            if !s.covered[i] {
                return 0.0;
            }
            let v = camera.view_direction_at(i % W as usize, i / W as usize, s.depth[i]);
            let mut normal = s.normal[i].normalize();
            if normal.dot(v) < 0.0 {
                normal = -normal;
            }
            let i0 = normal.dot(l).max(0.0);
            let d = s.depth[i];
            let factor = if d < l1.depth[i] {
                1.0
            } else if d < l2.depth[i] {
                alpha
            } else {
                beta
            };
            i0 * factor
        })
        .collect();
    // Eq. 10.
    let i_s_final: Vec<f32> = (0..i_s.len())
        .map(|i| {
            if sil2[i] > 0.5 && l2.depth[i] <= s.depth[i] {
                0.0
            } else {
                i_s[i]
            }
        })
        .collect();

    let mut suspect = vec![false; (W * H) as usize];
    for (name, node, port, reference) in [
        ("silhouette_p1", "silhouette1", "mask", &sil1),
        ("silhouette_p2", "silhouette2", "mask", &sil2),
        ("hatching", "hatching", "mask", &hatching),
    ] {
        let gpu = array(&session, node, port).data;
        for i in compare_masks(name, &gpu, reference) {
            suspect[i] = true;
        }
    }
    // Continuous masks: within float precision of the reference.
    for (name, node, port, reference, tolerance) in [
        ("intensity_p1", "intensity1", "intensity", &i_p1, 1e-5),
        // The GPU lit S with the unquantised normal, the reference with the 16-bit one read back.
        ("intensity_s", "secondary", "intensity", &i_s, 3e-3),
        (
            "intensity_s_final",
            "secondary_final",
            "mask",
            &i_s_final,
            3e-3,
        ),
    ] {
        let gpu = array(&session, node, port).data;
        let tolerance = common::f32_at_most(tolerance);
        common::assert_images_close_where(name, &gpu, reference, W, tolerance, |i| !suspect[i]);
    }

    // §3.3.4 final colour.
    let colour = |node: &str| match params_of(&session, node).get("color") {
        Some(ParamValue::Color(c)) => Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32),
        _ => panic!("{node} has no colour"),
    };
    let (paper, back, sec) = (
        colour("paper"),
        colour("back_layer"),
        colour("with_secondary"),
    );
    let picture = array(&session, "front_hatching", "image");
    let want: Vec<[f32; 3]> = (0..(W * H) as usize)
        .map(|i| {
            let mut c = paper.lerp(back, sil2[i]);
            c = c.lerp(sec, i_s_final[i]);
            c *= 1.0 - sil1[i];
            c *= hatching[i];
            c.to_array()
        })
        .collect();
    let got: Vec<[f32; 3]> = picture
        .data
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    // Pixels next to a differing mask pixel may differ too (the final mix reads them).
    let far_from_suspects = |i: usize| {
        let (x, y) = ((i % W as usize) as i64, (i / W as usize) as i64);
        !(-1..=1).any(|dy| (-1..=1).any(|dx| suspect[at(x + dx, y + dy)]))
    };
    let compared = (0..(W * H) as usize)
        .filter(|&i| far_from_suspects(i))
        .count();
    assert!(
        compared as f64 > 0.99 * (W * H) as f64,
        "too many pixels excluded"
    );
    common::assert_images_close_where(
        "final_colour",
        &got,
        &want,
        W,
        common::f32_at_most(1.0 / 255.0),
        far_from_suspects,
    );
    // The picture shows all four ingredients.
    let count = |v: &[f32]| v.iter().filter(|x| **x > 0.5).count();
    assert!(
        count(&sil1) > 500 && count(&sil2) > 500,
        "both layers must have silhouettes"
    );
    assert!(
        i_s_final.iter().filter(|x| **x > 0.05).count() > 200,
        "secondary geometry must show"
    );
}

fn sphere_hit(view: Mat4, proj: Mat4, x: u32, y: u32, radius: f32, far_side: bool) -> Option<f32> {
    let ndc_x = (x as f32 + 0.5) / W as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / H as f32 * 2.0;
    let inverse = (proj * view).inverse();
    let unproject = |z: f32| {
        let p = inverse * Vec4::new(ndc_x, ndc_y, z, 1.0);
        p.truncate() / p.w
    };
    let (near, far) = (unproject(0.0), unproject(1.0));
    let dir = (far - near).normalize();
    let b = near.dot(dir);
    let disc = b * b - (near.length_squared() - radius * radius);
    if disc < 0.0 {
        return None;
    }
    let t = if far_side {
        -b + disc.sqrt()
    } else {
        -b - disc.sqrt()
    };
    let clip = proj * view * (near + dir * t).extend(1.0);
    Some(clip.z / clip.w)
}

#[test]
fn depth_peeling_of_nested_spheres_matches_the_analytic_layers() {
    // Shells: spheres of radius 0.85 (outer surface of the outer shell), 0.75 (its inner
    // surface), 0.55, 0.45, … Orthographic, axis-aligned.
    let graph = r#"(
        version: 1,
        nodes: [
            (id: "shells", kind: "ProceduralVolume", params: {"shape": "shells", "resolution": 160}),
            (id: "surface", kind: "MarchingCubes", params: {"iso": 0.0}),
            (id: "camera", kind: "Camera", params: {"projection": "orthographic", "azimuth": 0.0, "elevation": 0.0, "distance": 3.0, "fov": 40.0, "near": 1.0, "far": 5.0}),
            (id: "layer1", kind: "GBuffer", params: {}),
            (id: "layer2", kind: "DepthPeel", params: {}),
            (id: "layer3", kind: "DepthPeel", params: {}),
        ],
        edges: [
            (from: ("shells", "volume"), to: ("surface", "volume")),
            (from: ("surface", "mesh"), to: ("layer1", "mesh")),
            (from: ("camera", "camera"), to: ("layer1", "camera")),
            (from: ("surface", "mesh"), to: ("layer2", "mesh")),
            (from: ("camera", "camera"), to: ("layer2", "camera")),
            (from: ("layer1", "gbuffer"), to: ("layer2", "previous")),
            (from: ("surface", "mesh"), to: ("layer3", "mesh")),
            (from: ("camera", "camera"), to: ("layer3", "camera")),
            (from: ("layer2", "gbuffer"), to: ("layer3", "previous")),
        ],
    )"#;
    let mut session = common::session_from_text(graph, W, H);
    session.run(&["layer3"]).unwrap();
    let camera = match session.output("camera", "camera").unwrap() {
        Value::Camera(c) => c.clone(),
        _ => unreachable!(),
    };
    let (view, proj) = (camera.view, camera.proj);
    let layers = [
        layer(&session, "layer1", "gbuffer"),
        layer(&session, "layer2", "gbuffer"),
        layer(&session, "layer3", "gbuffer"),
    ];
    // Depth per world unit along the view axis, to express errors in world units.
    let depth_per_unit = 1.0 / (camera.far - camera.near);
    let mut samples: BTreeMap<&str, Vec<common::Sample>> = BTreeMap::new();
    for y in (2..H).step_by(4) {
        for x in (2..W).step_by(4) {
            // Expected layers, front to back, and how far the pixel is from any sphere's outline
            // (outlines are skipped: polygonal and true outlines differ by a pixel there).
            let (outer, inner) = (0.85f32, 0.75f32);
            let front = |r| sphere_hit(view, proj, x, y, r, false);
            let back = |r| sphere_hit(view, proj, x, y, r, true);
            let ndc = Vec3::new(
                (x as f32 + 0.5) / W as f32 * 2.0 - 1.0,
                1.0 - (y as f32 + 0.5) / H as f32 * 2.0,
                0.0,
            );
            let world = (proj * view).inverse() * ndc.extend(1.0);
            let radial = (world.x * world.x + world.y * world.y).sqrt();
            if [0.85f32, 0.75, 0.55, 0.45, 0.25, 0.15]
                .iter()
                .any(|r| (radial - r).abs() < 0.03)
            {
                continue;
            }
            let expected: [Option<f32>; 3] = match (front(outer), front(inner)) {
                (None, _) => [None, None, None],
                // Only the outer sphere: its front, then its back.
                (Some(f), None) => [Some(f), back(outer), None],
                // The inner one too: outer front, inner front, then the next sphere (0.55 front, or
                // the inner sphere's back where 0.55 is missed).
                (Some(f), Some(fi)) => [Some(f), Some(fi), front(0.55).or_else(|| back(inner))],
            };
            for (k, name) in ["layer1", "layer2", "layer3"].iter().enumerate() {
                let i = (y * W + x) as usize;
                let got = layers[k].depth[i];
                let (want, what) = match expected[k] {
                    Some(d) => (d, "surface"),
                    None => (1.0, "empty"),
                };
                samples.entry(name).or_default().push(common::Sample {
                    x,
                    y,
                    what: format!("{name}: depth {got}, expected {what} at {want}"),
                    error: ((got - want) / depth_per_unit).abs() as f64,
                });
            }
        }
    }
    for (name, s) in &samples {
        // Half a voxel of the 160³ grid over [-1, 1] is 0.0063 world units.
        common::assert_samples(&format!("peel_{name}"), s, 0.0063, None);
        assert!(s.len() > 400);
    }
}

fn constant_mask(session: &Session, value: f32) -> Value {
    let gpu = &session.ctx.gpu;
    let texture = gpu.render_target("constant", W, H, wgpu::TextureFormat::R32Float);
    let data = vec![value; (W * H) as usize];
    gpu.queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&data),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * W),
            rows_per_image: None,
        },
        wgpu::Extent3d {
            width: W,
            height: H,
            depth_or_array_layers: 1,
        },
    );
    Value::Mask(Arc::new(Mask { texture }))
}

#[test]
fn halftone_of_constant_fields_follows_the_tau_rule_and_whitens_monotonically() {
    let mut session =
        common::session_from_text(r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#, W, H);
    let (theta_deg, n, c_cross) = (20.0f32, 4.0f32, 0.9f32);
    let mut previous_white = -1.0;
    for step in 0..=20 {
        let intensity = step as f32 / 20.0;
        let input = constant_mask(&session, intensity);
        let out = common::run_node(
            &mut session,
            "Halftone",
            vec![("intensity", input)],
            &[
                ("theta", ParamValue::Float(theta_deg as f64)),
                ("cell", ParamValue::Float(n as f64)),
                ("c_cross", ParamValue::Float(c_cross as f64)),
            ],
        );
        let mask = export::to_array(&out[0], &session.ctx.gpu).unwrap().data;
        let mut mismatches = 0;
        for y in 0..H {
            for x in 0..W {
                let t = tau(x, y, theta_deg.to_radians(), n, c_cross);
                let expected = if intensity >= t { 1.0 } else { 0.0 };
                let got = mask[(y * W + x) as usize];
                if got != expected {
                    // GPU and CPU trigonometry may round differently: only exact ties may flip.
                    assert!(
                        (intensity - t).abs() < 1e-4,
                        "pixel ({x}, {y}) at intensity {intensity}: GPU {got}, τ = {t}"
                    );
                    mismatches += 1;
                }
            }
        }
        assert!(
            mismatches <= 2,
            "intensity {intensity}: {mismatches} tie pixels differ"
        );
        let white = mask.iter().sum::<f32>() / mask.len() as f32;
        assert!(
            white >= previous_white,
            "white fraction fell from {previous_white} to {white} at {intensity}"
        );
        previous_white = white;
        if step == 0 {
            assert!(white < 0.01, "intensity 0 must be (almost) all ink");
        }
    }
    assert_eq!(previous_white, 1.0, "intensity 1 is all paper");
}

#[test]
fn pip_with_zero_perturbation_finds_no_edges_and_two_pixels_draw_thicker_lines_than_one() {
    let path = common::repo_root().join("graphs/hidden_structures.ron");
    let mut session = Session::open(&path, W, H).unwrap();
    let count = |session: &mut Session, amount: &str| {
        session
            .set_param_text("silhouette1", "pip", "constant")
            .unwrap();
        session
            .set_param_text("silhouette1", "pip_amount", amount)
            .unwrap();
        session.run(&["silhouette1"]).unwrap();
        array(session, "silhouette1", "mask")
            .data
            .iter()
            .filter(|v| **v > 0.5)
            .count()
    };
    let zero = count(&mut session, "0");
    let one = count(&mut session, "1");
    let two = count(&mut session, "2");
    assert_eq!(zero, 0, "P = 0 samples the centre only: no edges");
    assert!(one > 500, "P = 1 is the plain filter: {one} pixels");
    assert!(
        two as f64 > 1.5 * one as f64,
        "P = 2 must draw clearly thicker lines: {two} vs {one} pixels"
    );
    // P = 1 is exactly the unperturbed filter.
    session
        .set_param_text("silhouette1", "pip", "none")
        .unwrap();
    session.run(&["silhouette1"]).unwrap();
    let plain = array(&session, "silhouette1", "mask")
        .data
        .iter()
        .filter(|v| **v > 0.5)
        .count();
    assert_eq!(plain, one);
}
