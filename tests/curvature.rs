//! Curvature of iso-surfaces (Hadwiger's deferred shading, the tutorial's §1) against analytic
//! answers: sphere (κ1 = κ2 = 1/r), cylinder (1/r and 0, the first direction around it), torus
//! (1/r and cos v/(R + r cos v)) and a saddle (Monge-patch formulas), seen orthographically
//! along −z through IsoSurfaceRaycast → Curvature.

mod common;

use glam::{Vec2, Vec3};
use hatchery_data::VolumeData;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::Volume;
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 96;
const SIZE: u32 = 64;

/// `f` sampled on an N³ grid over world [-1, 1]³.
fn field(f: impl Fn(Vec3) -> f32) -> VolumeData {
    common::field_on_cube(N, f)
}

/// IsoSurfaceRaycast (iso 0) → Curvature of `volume`, orthographic along −z showing
/// [-1.1, 1.1]²: the session, the curvature image, the G-buffer and the camera.
fn run(volume: VolumeData) -> (Session, Value, Value, Camera) {
    run_with(volume, "trilinear")
}

/// [`run`] with the given `reconstruction` of IsoSurfaceRaycast and Curvature.
fn run_with(volume: VolumeData, reconstruction: &str) -> (Session, Value, Value, Camera) {
    let mut session = common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    );
    let fov = 2.0 * (1.1f32 / 5.0).atan().to_degrees();
    let cam = Camera::orbit(
        Vec3::ZERO,
        0.0,
        0.0,
        5.0,
        fov,
        true,
        0.1,
        20.0,
        false,
        SIZE,
        SIZE,
    );
    let volume = Value::Volume(Arc::new(Volume::new(volume)));
    let gbuffer = common::run_node(
        &mut session,
        "IsoSurfaceRaycast",
        vec![
            ("volume", volume.clone()),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
        ],
        &[
            ("iso", ParamValue::Float(0.0)),
            ("step", ParamValue::Float(0.25)),
            ("reconstruction", ParamValue::Choice(reconstruction.into())),
        ],
    )
    .remove(0);
    let k = common::run_node(
        &mut session,
        "Curvature",
        vec![("gbuffer", gbuffer.clone()), ("volume", volume)],
        &[("reconstruction", ParamValue::Choice(reconstruction.into()))],
    )
    .remove(0);
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    (session, k, gbuffer, cam)
}

/// Per pixel: the hit point (world) and (κ1, κ2, θ) from Curvature, where it found a surface
/// facing the viewer.
fn curvature(volume: VolumeData) -> Vec<Option<(Vec3, [f32; 3])>> {
    curvature_with(volume, "trilinear")
}

/// [`curvature`] with the given reconstruction.
fn curvature_with(volume: VolumeData, reconstruction: &str) -> Vec<Option<(Vec3, [f32; 3])>> {
    let (session, k, gbuffer, cam) = run_with(volume, reconstruction);
    let k = export::to_array(&k, &session.ctx.gpu).unwrap();
    let g = export::to_array(&gbuffer, &session.ctx.gpu).unwrap();
    let inverse = cam.view_proj().inverse();
    (0..(SIZE * SIZE) as usize)
        .map(|i| {
            let c = &k.data[i * 4..i * 4 + 4];
            let depth = g.data[i * 4];
            let normal_z = g.data[i * 4 + 3];
            // Only pixels facing the viewer (grazing hits are refined least precisely).
            if c[2] < -5.0 || depth >= 1.0 || normal_z < 0.5 {
                return None;
            }
            let (x, y) = (
                (i as u32 % SIZE) as f32 + 0.5,
                (i as u32 / SIZE) as f32 + 0.5,
            );
            let ndc = Vec2::new(x / SIZE as f32 * 2.0 - 1.0, 1.0 - y / SIZE as f32 * 2.0);
            let p = inverse.project_point3(ndc.extend(depth));
            Some((p, [c[0], c[1], c[2]]))
        })
        .collect()
}

/// Every valid pixel selected by `which` has κ1, κ2 within 5 % of the larger |κ| of `expected`
/// at its hit point; returns how many were checked.
fn check(
    name: &str,
    pixels: &[Option<(Vec3, [f32; 3])>],
    which: impl Fn(Vec3) -> bool,
    expected: impl Fn(Vec3) -> [f32; 2],
) -> usize {
    let mut checked = 0;
    for (p, k) in pixels.iter().flatten().filter(|(p, _)| which(*p)) {
        let [e1, e2] = expected(*p);
        let scale = e1.abs().max(e2.abs());
        assert!(
            (k[0] - e1).abs() <= 0.05 * scale && (k[1] - e2).abs() <= 0.05 * scale,
            "{name} at {p}: κ = ({}, {}), expected ({e1}, {e2})",
            k[0],
            k[1]
        );
        checked += 1;
    }
    assert!(checked >= 20, "{name}: only {checked} pixels checked");
    checked
}

#[test]
fn a_sphere_has_both_curvatures_one_over_its_radius() {
    let r = 0.6;
    let pixels = curvature(field(|p| r - p.length()));
    check("sphere", &pixels, |_| true, |_| [1.0 / r, 1.0 / r]);
}

/// The largest |κ − 1/r| · r over the pixels of a sphere of radius `r`.
fn worst_sphere_error(pixels: &[Option<(Vec3, [f32; 3])>], r: f32) -> f32 {
    let errors = pixels
        .iter()
        .flatten()
        .map(|(_, k)| (k[0] * r - 1.0).abs().max((k[1] * r - 1.0).abs()));
    assert!(errors.clone().count() >= 20, "too few pixels on the sphere");
    errors.fold(0.0, f32::max)
}

/// The B-spline's own second derivatives (Hadwiger §1.3) give a sphere's curvatures as the
/// differences of the trilinear filter do; on a ball whose edge is a smooth step ~2 voxels wide
/// (not a distance field) they are closer to 1/r than the trilinear differences.
#[test]
fn the_bspline_hessian_gives_a_sphere_both_curvatures_one_over_its_radius() {
    let r = 0.6;
    let pixels = curvature_with(field(|p| r - p.length()), "bspline");
    check(
        "sphere (bspline)",
        &pixels,
        |_| true,
        |_| [1.0 / r, 1.0 / r],
    );
    let step = field(|p| ((r - p.length()) / 0.05).tanh());
    let trilinear = worst_sphere_error(&curvature_with(step.clone(), "trilinear"), r);
    let bspline = worst_sphere_error(&curvature_with(step, "bspline"), r);
    eprintln!(
        "smooth-step ball: worst relative curvature error trilinear {trilinear}, B-spline {bspline}"
    );
    assert!(
        bspline < 0.08 && bspline < trilinear,
        "B-spline {bspline}, trilinear {trilinear}"
    );
}

#[test]
fn a_cylinder_curves_around_and_not_along_its_axis() {
    // Axis along y, radius 0.5: κ1 = 2 around it (screen x at the front), κ2 = 0.
    let r = 0.5;
    let pixels = curvature(field(|p| r - (p.x * p.x + p.z * p.z).sqrt()));
    let inner = |p: Vec3| p.y.abs() < 0.8 && p.x.abs() < 0.3;
    check("cylinder", &pixels, inner, |_| [1.0 / r, 0.0]);
    // The first principal direction: circumferential, on screen along x (θ = 0) within 5°.
    for (p, k) in pixels.iter().flatten().filter(|(p, _)| inner(*p)) {
        assert!(
            k[2].abs() <= 5f32.to_radians(),
            "direction at {p}: θ = {}°",
            k[2].to_degrees()
        );
    }
}

#[test]
fn a_torus_has_the_tube_and_ring_curvatures() {
    // Ring of radius R around z, tube radius r; seen from +z. At a point of the tube at angle v
    // (cos v = (ρ − R)/r, ρ the distance from the axis): 1/r across the tube, cos v/(R + r cos v)
    // = (ρ − R)/(r ρ) along the ring.
    let (big, small) = (0.55f32, 0.28f32);
    let pixels = curvature(field(|p| {
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        small - ((rho - big).powi(2) + p.z * p.z).sqrt()
    }));
    let rho = |p: Vec3| (p.x * p.x + p.y * p.y).sqrt();
    check(
        "torus",
        &pixels,
        |p| (rho(p) - big).abs() < 0.6 * small,
        |p| {
            let ring = (rho(p) - big) / (small * rho(p));
            let tube = 1.0 / small;
            if ring > tube {
                [ring, tube]
            } else {
                [tube, ring]
            }
        },
    );
}

#[test]
fn a_saddle_curves_both_ways_as_the_monge_patch_formulas_say() {
    // The surface z = s(x² − y²), the field larger below it.
    let s = 0.5f32;
    let pixels = curvature(field(|p| s * (p.x * p.x - p.y * p.y) - p.z));
    let expected = |p: Vec3| {
        // Monge patch h(x, y): mean H and Gaussian K with the normal up (+z); κ here is positive
        // where the surface curves away from the outward normal, so κ = −k.
        let (hx, hy, hxx, hyy) = (2.0 * s * p.x, -2.0 * s * p.y, 2.0 * s, -2.0 * s);
        let w = 1.0 + hx * hx + hy * hy;
        let k_gauss = hxx * hyy / (w * w);
        let mean = ((1.0 + hx * hx) * hyy + (1.0 + hy * hy) * hxx) / (2.0 * w.powf(1.5));
        let root = (mean * mean - k_gauss).max(0.0).sqrt();
        [-(mean - root), -(mean + root)]
    };
    check(
        "saddle",
        &pixels,
        |p| p.x.abs() < 0.6 && p.y.abs() < 0.6,
        expected,
    );
    // At the centre the first direction (κ1 = +2s, curving away from the normal) is along y:
    // on screen vertical, θ = ±90° within 5°.
    let centre = pixels
        .iter()
        .flatten()
        .min_by(|a, b| a.0.truncate().length().total_cmp(&b.0.truncate().length()))
        .unwrap();
    let off_vertical = 90.0 - centre.1[2].to_degrees().abs();
    assert!(
        off_vertical <= 5.0,
        "θ at the centre = {}°",
        centre.1[2].to_degrees()
    );
}

#[test]
fn curvature_colour_maps_each_measure_through_the_transfer_function() {
    use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
    use hatchery_nodes::value::TransferFunction;
    // A torus: the measures vary over the picture.
    let (mut session, k, _, _) = run(field(|p| {
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        0.28 - ((rho - 0.55).powi(2) + p.z * p.z).sqrt()
    }));
    let tf = TransferFunction1D::from_points(&[
        ControlPoint {
            value: -4.0,
            rgba: [0.0, 0.2, 1.0, 1.0],
        },
        ControlPoint {
            value: 0.0,
            rgba: [1.0, 1.0, 1.0, 0.6],
        },
        ControlPoint {
            value: 6.0,
            rgba: [1.0, 0.1, 0.0, 1.0],
        },
    ])
    .unwrap();
    let curv = export::to_array(&k, &session.ctx.gpu).unwrap();
    for (measure, f) in [
        ("k1", (|a: f32, _b: f32| a) as fn(f32, f32) -> f32),
        ("k2", |_a, b| b),
        ("mean", |a, b| 0.5 * (a + b)),
        ("gaussian", |a, b| a * b),
        ("curvedness", |a, b| (a * a + b * b).sqrt()),
    ] {
        let out = common::run_node(
            &mut session,
            "CurvatureColor",
            vec![
                ("curvature", k.clone()),
                (
                    "tf",
                    Value::TransferFunction(Arc::new(TransferFunction::Color(tf.clone()))),
                ),
            ],
            &[("measure", ParamValue::Choice(measure.into()))],
        );
        let colour = export::to_array(&out[0], &session.ctx.gpu).unwrap();
        let mut valid = 0;
        for i in 0..(SIZE * SIZE) as usize {
            let c = &curv.data[i * 4..i * 4 + 4];
            let got = &colour.data[i * 4..i * 4 + 4];
            if c[2] < -5.0 {
                assert!(
                    got.iter().all(|&v| v == 0.0),
                    "{measure}: colour without a surface"
                );
                continue;
            }
            valid += 1;
            let e = tf.lookup(f(c[0], c[1]));
            let want = [e[0] * e[3], e[1] * e[3], e[2] * e[3], e[3]];
            for ch in 0..4 {
                assert!(
                    (got[ch] - want[ch]).abs() <= 2.0 / 255.0,
                    "{measure} at pixel {i}: {got:?} vs {want:?}"
                );
            }
        }
        assert!(valid > 300, "{valid} surface pixels");
    }
}

#[test]
fn ridges_and_valleys_lie_on_the_crests_and_troughs_of_a_corrugated_plane() {
    // z = a cos(k x): crests (ridges, κ1 = a k²) at x = 0, ±0.5, ±1; troughs (valleys,
    // κ2 = −a k²) at x = ±0.25, ±0.75. The field is larger below the surface.
    let (a, k) = (0.06f32, std::f32::consts::TAU / 0.5);
    let (mut session, curvature, _, cam) = run(field(|p| a * (k * p.x).cos() - p.z));
    let out = common::run_node(
        &mut session,
        "RidgeValley",
        vec![("curvature", curvature)],
        &[
            ("threshold", ParamValue::Float((0.5 * a * k * k) as f64)),
            ("thickness", ParamValue::Float(1.5)),
        ],
    );
    let to_px = |x: f32| cam.view_proj().project_point3(Vec3::new(x, 0.0, 0.0)).x;
    let column = |x: f32| (to_px(x) + 1.0) * 0.5 * SIZE as f32;
    let rows = |x_ndc_lines: &[f32]| x_ndc_lines.iter().map(|&x| column(x)).collect::<Vec<f32>>();
    for (name, mask, lines) in [
        ("ridges", &out[0], rows(&[-0.5, 0.0, 0.5])),
        ("valleys", &out[1], rows(&[-0.75, -0.25, 0.25, 0.75])),
    ] {
        let m = export::to_array(mask, &session.ctx.gpu).unwrap();
        let on = |x: usize, y: usize| m.data[y * SIZE as usize + x] > 0.5;
        // Every line pixel lies within 1 px of an analytic line (pixel centres at x + 0.5).
        let mut pixels = 0;
        for y in 0..SIZE as usize {
            for x in 0..SIZE as usize {
                if on(x, y) {
                    pixels += 1;
                    let d = lines
                        .iter()
                        .map(|c| (x as f32 + 0.5 - c).abs())
                        .fold(f32::INFINITY, f32::min);
                    assert!(
                        d <= 1.0,
                        "{name}: pixel ({x}, {y}) is {d} px from the lines"
                    );
                }
            }
        }
        // And each analytic line is found along ≥ 95 % of its rows (away from the frame edge).
        let inner: Vec<usize> = (6..SIZE as usize - 6).collect();
        for &c in &lines {
            let found = inner
                .iter()
                .filter(|&&y| {
                    (0..SIZE as usize).any(|x| on(x, y) && (x as f32 + 0.5 - c).abs() <= 1.0)
                })
                .count();
            assert!(
                found as f32 >= 0.95 * inner.len() as f32,
                "{name}: the line at column {c} found in {found} of {} rows",
                inner.len()
            );
        }
        assert!(pixels > 100, "{name}: {pixels} pixels");
    }
}

#[test]
fn constant_curvature_draws_no_ridge_or_valley() {
    // A sphere: κ1 = κ2 = 1/r everywhere, no maximum along any direction.
    let (mut session, curvature, _, _) = run(field(|p| 0.6 - p.length()));
    let out = common::run_node(
        &mut session,
        "RidgeValley",
        vec![("curvature", curvature)],
        &[("threshold", ParamValue::Float(0.5))],
    );
    for (name, mask) in [("ridges", &out[0]), ("valleys", &out[1])] {
        let m = export::to_array(mask, &session.ctx.gpu).unwrap();
        let on = m.data.iter().filter(|&&v| v > 0.5).count();
        assert!(on * 100 <= m.data.len(), "{name}: {on} pixels on a sphere");
    }
}

#[test]
fn curvature_color_maps_both_curvatures_through_a_2d_transfer_function() {
    use hatchery_nodes::curvature_color::{SHAPE_MAP_SIZE, map_lookup, shape_map};
    // The torus: κ1 = 1/r everywhere, κ2 from −0.66 (the inner side: saddle) to 1.2 (the outer
    // side: cap).
    let (mut session, k, _, _) = run(field(|p| {
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        0.28 - ((rho - 0.55).powi(2) + p.z * p.z).sqrt()
    }));
    let curv = export::to_array(&k, &session.ctx.gpu).unwrap();
    // A 5×3 PNG map with distinct colours, and the built-in shape-class map.
    let dir = std::env::temp_dir().join(format!("hatchery-map2d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("map.png");
    let picture = image::RgbaImage::from_fn(5, 3, |x, y| {
        image::Rgba([(x * 60) as u8, (y * 120) as u8, (255 - x * 50) as u8, 255])
    });
    picture.save(&png).unwrap();
    let png_texels: Vec<[f32; 4]> = picture
        .pixels()
        .map(|p| p.0.map(|v| v as f32 / 255.0))
        .collect();
    let range = 6.0;
    for (map_param, texels, (w, h)) in [
        (String::new(), shape_map(), (SHAPE_MAP_SIZE, SHAPE_MAP_SIZE)),
        (png.to_string_lossy().into_owned(), png_texels, (5, 3)),
    ] {
        let out = common::run_node(
            &mut session,
            "CurvatureColor",
            vec![("curvature", k.clone())],
            &[
                ("measure", ParamValue::Choice("k1_k2".into())),
                ("map", ParamValue::Path(map_param.clone())),
                ("range", ParamValue::Float(range)),
            ],
        );
        let colour = export::to_array(&out[0], &session.ctx.gpu).unwrap();
        let (mut valid, mut distinct) = (0, std::collections::BTreeSet::new());
        for i in 0..(SIZE * SIZE) as usize {
            let c = &curv.data[i * 4..i * 4 + 4];
            let got = &colour.data[i * 4..i * 4 + 4];
            if c[2] < -5.0 {
                assert!(got.iter().all(|&v| v == 0.0), "colour without a surface");
                continue;
            }
            valid += 1;
            let e = map_lookup(&texels, w, h, range as f32, [c[0], c[1]]);
            let want = [e[0] * e[3], e[1] * e[3], e[2] * e[3], e[3]];
            for ch in 0..4 {
                assert!(
                    (got[ch] - want[ch]).abs() <= 2.0 / 255.0,
                    "map {map_param:?} at pixel {i} (κ {:?}): {got:?} vs {want:?}",
                    &c[..2]
                );
            }
            distinct.insert(
                got[..3]
                    .iter()
                    .map(|v| (v * 255.0) as i32)
                    .collect::<Vec<_>>(),
            );
        }
        assert!(valid > 300, "{valid} surface pixels");
        assert!(
            distinct.len() > 20,
            "only {} colours over the torus",
            distinct.len()
        );
    }
    // Orientation, by hand: a 2×2 map (top-left red, top-right green, bottom-left blue,
    // bottom-right white) with a tiny range clamps every pixel to a corner: κ1 > 0 is the right
    // column, κ2 > 0 the top row — caps (outer side) green, saddles (inner side) white.
    let corners = image::RgbaImage::from_fn(2, 2, |x, y| match (x, y) {
        (0, 0) => image::Rgba([255, 0, 0, 255]),
        (1, 0) => image::Rgba([0, 255, 0, 255]),
        (0, 1) => image::Rgba([0, 0, 255, 255]),
        _ => image::Rgba([255, 255, 255, 255]),
    });
    let corner_png = dir.join("corners.png");
    corners.save(&corner_png).unwrap();
    let out = common::run_node(
        &mut session,
        "CurvatureColor",
        vec![("curvature", k.clone())],
        &[
            ("measure", ParamValue::Choice("k1_k2".into())),
            (
                "map",
                ParamValue::Path(corner_png.to_string_lossy().into_owned()),
            ),
            ("range", ParamValue::Float(1e-3)),
        ],
    );
    let colour = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    let (mut caps, mut saddles) = (0, 0);
    for i in 0..(SIZE * SIZE) as usize {
        let c = &curv.data[i * 4..i * 4 + 4];
        if c[2] < -5.0 || c[1].abs() < 0.1 {
            continue;
        }
        let got = &colour.data[i * 4..i * 4 + 3];
        let want: [f32; 3] = if c[1] > 0.0 {
            caps += 1;
            [0.0, 1.0, 0.0]
        } else {
            saddles += 1;
            [1.0, 1.0, 1.0]
        };
        for ch in 0..3 {
            assert!(
                (got[ch] - want[ch]).abs() <= 2.0 / 255.0,
                "pixel {i} (κ {:?}): {got:?}, want {want:?}",
                &c[..2]
            );
        }
    }
    assert!(caps > 50 && saddles > 20, "{caps} caps, {saddles} saddles");
    // Without `tf`, the 1-D measures say what is missing.
    let node = session.registry.node("CurvatureColor").unwrap();
    let schema = node.schema();
    let names: Vec<&'static str> = schema.inputs.iter().map(|p| p.name).collect();
    let mut params: std::collections::BTreeMap<String, ParamValue> = schema
        .params
        .iter()
        .map(|p| (p.name.to_owned(), p.default.clone()))
        .collect();
    params.insert("measure".into(), ParamValue::Choice("mean".into()));
    let err = node
        .execute(
            &mut session.ctx,
            &hatchery_graph::NodeInputs::new(names, vec![Some(k.clone()), None]),
            &hatchery_graph::Params::new(params, None),
        )
        .err()
        .expect("a 1-D measure without a transfer function");
    assert_eq!(err.port.as_deref(), Some("tf"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn curvature_controlled_contours_keep_their_thickness_on_spheres_of_any_radius() {
    // Kindlmann's test marks the points whose screen distance to a sphere's outline is at most
    // T: a band `thickness` pixels wide at the outline, for a small and a large sphere alike.
    let thickness = 3.0f32;
    for r in [0.3f32, 0.8] {
        let data = field(|p| r - p.length());
        let (mut session, _, gbuffer, _) = run(data.clone());
        let volume = Value::Volume(Arc::new(Volume::new(data)));
        let out = common::run_node(
            &mut session,
            "CurvatureContours",
            vec![("gbuffer", gbuffer.clone()), ("volume", volume)],
            &[("thickness", ParamValue::Float(thickness as f64))],
        );
        let mask = export::to_array(&out[0], &session.ctx.gpu).unwrap().data;
        let depth = export::to_array(&gbuffer, &session.ctx.gpu).unwrap().data;
        let radius_px = r / 1.1 * SIZE as f32 / 2.0;
        let centre = SIZE as f32 / 2.0;
        // Band widths at both ends of the rows through the centre.
        let mut widths = Vec::new();
        for y in SIZE / 2 - 2..SIZE / 2 + 2 {
            let row = |x: u32| (y * SIZE + x) as usize;
            let surface: Vec<u32> = (0..SIZE).filter(|&x| depth[row(x) * 4] < 1.0).collect();
            let (first, last) = (surface[0], *surface.last().unwrap());
            let left = (first..SIZE).take_while(|&x| mask[row(x)] > 0.5).count();
            let right = (0..=last).rev().take_while(|&x| mask[row(x)] > 0.5).count();
            widths.extend([left as f32, right as f32]);
        }
        // Nothing well inside the band.
        let mut inner = 0;
        for (i, &m) in mask.iter().enumerate() {
            let d = Vec2::new(
                (i as u32 % SIZE) as f32 + 0.5 - centre,
                (i as u32 / SIZE) as f32 + 0.5 - centre,
            )
            .length();
            if d < radius_px - thickness - 1.5 && m > 0.5 {
                inner += 1;
            }
        }
        eprintln!("sphere r = {r} ({radius_px:.1} px): contour widths {widths:?}, {inner} inner");
        for w in &widths {
            assert!(
                (w - thickness).abs() <= 1.0,
                "r = {r}: contour {w} px wide, want {thickness} ± 1"
            );
        }
        assert_eq!(inner, 0, "r = {r}: contour pixels inside the band");
    }
}
