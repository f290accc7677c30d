//! Two-level volume rendering (Hadwiger §2.2–2.4) against its CPU reference and closed-form
//! values, boundary filtering (§2.3) against point sampling, and ids never interpolated.
//!
//! Over 600 lines: one test file per capability; each case builds its scene and its CPU reference
//! of the paper's equations.

mod common;

use common::raycast_reference::{Mode, RayParams, Shading};
use common::two_level_reference::{self as reference, Global, Local, Object};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Compositing, Labels, ObjectStyle, RenderMode, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 40;
const SIZE: u32 = 48;
/// Not a divisor of a voxel, so no sample lies exactly halfway between two voxels along z.
const STEP: f32 = 0.37;

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// Nested spheres on an N³ grid centred at the origin: id 2 (core) for r < 0.45, id 1 (shell)
/// for r < 0.85 (r relative to the half-size), background outside; data value = 100 · id.
fn nested_spheres() -> (VolumeData, LabelData) {
    let half = (N - 1) as f32 / 2.0;
    let mut ids = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let r =
                    Vec3::new(x as f32 - half, y as f32 - half, z as f32 - half).length() / half;
                ids.push(if r < 0.45 {
                    2
                } else if r < 0.85 {
                    1
                } else {
                    0
                });
            }
        }
    }
    grid(ids)
}

fn grid(ids: Vec<u16>) -> (VolumeData, LabelData) {
    let half = (N - 1) as f64 / 2.0;
    let geometry = Geometry::axis_aligned([1.0; 3], [-half; 3]);
    let values = ids.iter().map(|&id| 100.0 * f32::from(id)).collect();
    let volume = VolumeData::with_geometry([N; 3], geometry, values).unwrap();
    (volume, LabelData::new([N; 3], geometry, ids))
}

/// The same colour and opacity for every value.
fn flat(rgba: [f32; 4]) -> TransferFunction1D {
    TransferFunction1D::from_points(&[
        ControlPoint { value: 0.0, rgba },
        ControlPoint { value: 300.0, rgba },
    ])
    .unwrap()
}

/// Orthographic, looking along −z, the volume filling most of the frame.
fn camera(session: &mut Session) -> Camera {
    zoomed_camera(session, Vec3::ZERO, 22.0)
}

/// Orthographic along −z at `target`, showing 2 · `half_width` world units across.
fn zoomed_camera(session: &mut Session, target: Vec3, half_width: f32) -> Camera {
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let fov = 2.0 * (half_width / 60.0).atan().to_degrees();
    Camera::orbit(
        target, 0.0, 0.0, 60.0, fov, true, 0.05, 200.0, false, SIZE, SIZE,
    )
}

fn ray_params(cam: &Camera) -> RayParams {
    RayParams {
        view_proj: cam.view_proj(),
        view: cam.view,
        width: cam.width,
        height: cam.height,
        orthographic: true,
        step_voxels: STEP,
        mode: Mode::Dvr,
        shading: Shading::None,
        light_dir_view: Vec3::Z,
        early_termination: 0.99,
    }
}

fn style(id: u16, tf: &TransferFunction1D, local: Local) -> ObjectStyle {
    let (compositing, iso) = match local {
        Local::Over => (Compositing::Over, 0.0),
        Local::Mip => (Compositing::Mip, 0.0),
        Local::Iso(iso) => (Compositing::Iso, iso),
        Local::Sum => (Compositing::Sum, 0.0),
    };
    ObjectStyle {
        id,
        name: format!("object {id}"),
        enabled: true,
        tf: tf.clone(),
        mode: RenderMode::Dvr,
        compositing,
        iso,
        importance: 1.0,
    }
}

fn global_name(g: Global) -> &'static str {
    match g {
        Global::Over => "over",
        Global::Mip => "mip",
        Global::Sum => "sum",
    }
}

/// Renders TwoLevelRaycast on the GPU; premultiplied RGBA per pixel.
fn render_gpu(
    session: &mut Session,
    cam: &Camera,
    volume: &VolumeData,
    labels: &LabelData,
    styles: Vec<ObjectStyle>,
    global: Global,
    boundary: &str,
) -> Vec<[f32; 4]> {
    let out = common::run_node(
        session,
        "TwoLevelRaycast",
        vec![
            (
                "volume",
                Value::Volume(Arc::new(Volume::new(volume.clone()))),
            ),
            (
                "labels",
                Value::Labels(Arc::new(Labels::new(labels.clone()))),
            ),
            ("styles", Value::ObjectStyles(Arc::new(styles))),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
        ],
        &[
            ("global", ParamValue::Choice(global_name(global).into())),
            ("boundary", ParamValue::Choice(boundary.into())),
            ("step", ParamValue::Float(STEP as f64)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let a = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

fn centre(image: &[[f32; 4]]) -> [f32; 4] {
    image[(SIZE / 2 * SIZE + SIZE / 2) as usize]
}

const SHELL: [f32; 4] = [1.0, 0.0, 0.0, 0.3];
const CORE: [f32; 4] = [0.0, 1.0, 0.0, 0.6];

#[test]
fn every_local_and_global_compositing_mode_matches_the_cpu_reference() {
    let mut session = session();
    let cam = camera(&mut session);
    let p = ray_params(&cam);
    let (volume, labels) = nested_spheres();
    let (shell, core) = (flat(SHELL), flat(CORE));
    for local in [Local::Over, Local::Mip, Local::Iso(50.0)] {
        for global in [Global::Over, Global::Mip, Global::Sum] {
            let name = format!("local {local:?}, global {global:?}");
            let core_local = match local {
                Local::Iso(_) => Local::Iso(150.0),
                other => other,
            };
            let objects = [
                Object {
                    id: 1,
                    tf: shell.clone(),
                    local,
                },
                Object {
                    id: 2,
                    tf: core.clone(),
                    local: core_local,
                },
            ];
            let styles = objects
                .iter()
                .map(|o| style(o.id, &o.tf, o.local))
                .collect();
            let gpu = render_gpu(
                &mut session,
                &cam,
                &volume,
                &labels,
                styles,
                global,
                "filtered",
            );
            let cpu = reference::render(&volume, &labels, &objects, global, true, &p);
            let covered = cpu.iter().filter(|c| c[3] > 0.01).count();
            assert!(covered > 500, "{name}: only {covered} pixels covered");
            common::assert_images_close(&name, &gpu, &cpu, SIZE, 1.0 / 255.0);
        }
    }
}

#[test]
fn centre_columns_equal_closed_form_two_level_compositing() {
    let mut session = session();
    let cam = camera(&mut session);
    let (volume, labels) = nested_spheres();
    let (shell, core) = (flat(SHELL), flat(CORE));
    let premultiplied = |c: [f32; 4]| [c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]];
    let (s, c) = (premultiplied(SHELL), premultiplied(CORE));
    let cases: [(&str, Local, Local, Global, [f32; 4]); 3] = [
        // MIP of every segment, combined by MIP: the per-channel maximum of the two objects.
        (
            "MIP shell and core, global MIP",
            Local::Mip,
            Local::Mip,
            Global::Mip,
            [
                s[0].max(c[0]),
                s[1].max(c[1]),
                s[2].max(c[2]),
                s[3].max(c[3]),
            ],
        ),
        // The ray meets the shell, the core, the shell again: three segments, summed.
        (
            "MIP shell and core, global sum",
            Local::Mip,
            Local::Mip,
            Global::Sum,
            [
                2.0 * s[0] + c[0],
                2.0 * s[1] + c[1],
                2.0 * s[2] + c[2],
                (2.0 * s[3] + c[3]).min(1.0),
            ],
        ),
        // MIP of the front shell over the core's opaque iso-surface (unshaded: its TF colour).
        (
            "MIP shell over the core's iso-surface",
            Local::Mip,
            Local::Iso(150.0),
            Global::Over,
            [
                s[0] + (1.0 - s[3]) * CORE[0],
                s[1] + (1.0 - s[3]) * CORE[1],
                s[2] + (1.0 - s[3]) * CORE[2],
                1.0,
            ],
        ),
    ];
    for (name, shell_local, core_local, global, expected) in cases {
        let styles = vec![style(1, &shell, shell_local), style(2, &core, core_local)];
        let gpu = render_gpu(
            &mut session,
            &cam,
            &volume,
            &labels,
            styles,
            global,
            "filtered",
        );
        let got = centre(&gpu);
        for k in 0..4 {
            assert!(
                (got[k] - expected[k].min(1.0)).abs() <= 1.0 / 255.0,
                "{name}: centre pixel {got:?}, closed form {expected:?}"
            );
        }
    }
}

/// Per image row, the first column that shows object 2 (green) rather than object 1 (red).
fn edge_columns(image: &[[f32; 4]]) -> Vec<f32> {
    (8..SIZE - 8)
        .map(|y| {
            let row = &image[(y * SIZE) as usize..((y + 1) * SIZE) as usize];
            row.iter()
                .position(|p| p[1] > p[0])
                .unwrap_or(SIZE as usize) as f32
        })
        .collect()
}

/// RMS distance of points (row, column) from their least-squares line.
fn line_residual(columns: &[f32]) -> f32 {
    let n = columns.len() as f32;
    let xs: Vec<f32> = (0..columns.len()).map(|i| i as f32).collect();
    let (mx, my) = (xs.iter().sum::<f32>() / n, columns.iter().sum::<f32>() / n);
    let sxy: f32 = xs
        .iter()
        .zip(columns)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum();
    let sxx: f32 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    let slope = sxy / sxx;
    let ss: f32 = xs
        .iter()
        .zip(columns)
        .map(|(x, y)| (y - (my + slope * (x - mx))).powi(2))
        .sum();
    (ss / n).sqrt()
}

#[test]
fn filtered_boundaries_are_straight_where_point_sampling_shows_voxel_stairs() {
    // Two objects split by a plane slanted across x and y: in voxels, a staircase.
    let ids = (0..N * N * N)
        .map(|i| {
            let (x, y) = ((i % N) as f32, ((i / N) % N) as f32);
            if x < 12.0 + 0.37 * y { 1 } else { 2 }
        })
        .collect();
    let (volume, labels) = grid(ids);
    let mut session = session();
    // Zoomed in on the edge (about 6 pixels per voxel) where it crosses the middle row.
    let half = (N - 1) as f32 / 2.0;
    let edge_x = 12.0 + 0.37 * half - half;
    let cam = zoomed_camera(&mut session, Vec3::new(edge_x, 0.0, 0.0), 4.0);
    let styles = || {
        vec![
            style(1, &flat([1.0, 0.0, 0.0, 1.0]), Local::Over),
            style(2, &flat([0.0, 1.0, 0.0, 1.0]), Local::Over),
        ]
    };
    let filtered = render_gpu(
        &mut session,
        &cam,
        &volume,
        &labels,
        styles(),
        Global::Over,
        "filtered",
    );
    let point = render_gpu(
        &mut session,
        &cam,
        &volume,
        &labels,
        styles(),
        Global::Over,
        "point",
    );
    let (filtered_edge, point_edge) = (edge_columns(&filtered), edge_columns(&point));
    // A voxel staircase jumps a whole voxel (about 6 pixels here) between two image rows and
    // then runs straight; the filtered edge advances by about 0.37 voxel per voxel row, spread
    // over the rows between.
    let largest_jump = |edge: &[f32]| {
        edge.windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0f32, f32::max)
    };
    let (smooth_jump, stair_jump) = (largest_jump(&filtered_edge), largest_jump(&point_edge));
    let (smooth, stairs) = (line_residual(&filtered_edge), line_residual(&point_edge));
    assert!(
        stair_jump >= 5.0 && smooth_jump <= 3.0 && smooth < stairs,
        "largest step between rows: filtered {smooth_jump} px, point-sampled {stair_jump} px; \
         residual from a straight line: filtered {smooth} px, point-sampled {stairs} px\n\
         filtered edge {filtered_edge:?}\npoint edge {point_edge:?}"
    );
}

#[test]
fn ids_are_never_interpolated_no_sample_between_ids_1_and_3_is_object_2() {
    let ids = (0..N * N * N)
        .map(|i| if (i % N) < N / 2 { 1 } else { 3 })
        .collect();
    let (volume, labels) = grid(ids);
    let mut session = session();
    let cam = camera(&mut session);
    let styles = vec![
        style(1, &flat([1.0, 0.0, 0.0, 0.5]), Local::Over),
        style(2, &flat([0.0, 0.0, 1.0, 1.0]), Local::Over),
        style(3, &flat([0.0, 1.0, 0.0, 0.5]), Local::Over),
    ];
    for boundary in ["filtered", "point"] {
        let image = render_gpu(
            &mut session,
            &cam,
            &volume,
            &labels,
            styles.clone(),
            Global::Over,
            boundary,
        );
        let blue = image.iter().filter(|p| p[2] > 0.01).count();
        assert_eq!(blue, 0, "{boundary}: {blue} pixels show object 2");
        let red = image.iter().filter(|p| p[0] > 0.1).count();
        let green = image.iter().filter(|p| p[1] > 0.1).count();
        assert!(
            red > 300 && green > 300,
            "{boundary}: red {red}, green {green}"
        );
    }
}

/// A bright ball (v = 255 · (1 − r)) with labels: 2 for r < 0.45, 1 for the shell to 0.85.
fn graded_ball() -> (VolumeData, LabelData) {
    let (_, labels) = nested_spheres();
    let half = (N - 1) as f32 / 2.0;
    let mut values = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let r =
                    Vec3::new(x as f32 - half, y as f32 - half, z as f32 - half).length() / half;
                values.push(255.0 * (1.0 - r).max(0.0));
            }
        }
    }
    let volume = VolumeData::with_geometry([N; 3], labels.geometry, values).unwrap();
    (volume, labels)
}

#[test]
fn one_object_alone_renders_like_raycast_with_its_transfer_function_and_mode() {
    let (volume, labels) = graded_ball();
    let mut session = session();
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let cam = Camera::orbit(
        Vec3::ZERO,
        30.0,
        20.0,
        35.0,
        40.0,
        false,
        0.05,
        200.0,
        false,
        SIZE,
        SIZE,
    );
    // Visible only well inside the core (r < 0.33), so the object mask decides nothing there:
    // the core alone, masked, is what Raycast shows of the whole volume with this function.
    let tf = TransferFunction1D::from_points(&[
        ControlPoint {
            value: 0.0,
            rgba: [0.0; 4],
        },
        ControlPoint {
            value: 170.0,
            rgba: [0.9, 0.5, 0.2, 0.0],
        },
        ControlPoint {
            value: 255.0,
            rgba: [1.0, 0.9, 0.6, 0.35],
        },
    ])
    .unwrap();
    let cases = [
        (
            "shaded DVR",
            RenderMode::ShadedDvr,
            Compositing::Over,
            "dvr",
            "phong",
        ),
        (
            "unshaded DVR",
            RenderMode::Dvr,
            Compositing::Over,
            "dvr",
            "none",
        ),
        ("MIP", RenderMode::Mip, Compositing::Mip, "mip", "none"),
        (
            "iso-surface",
            RenderMode::Iso,
            Compositing::Iso,
            "iso",
            "phong",
        ),
    ];
    let volume_value = Value::Volume(Arc::new(Volume::new(volume.clone())));
    // Both reconstructions (issue 36): the filters are shared, so the pictures still agree.
    let runs = cases
        .iter()
        .flat_map(|c| ["trilinear", "bspline"].map(|r| (*c, r)));
    for ((name, mode, compositing, ray_mode, shading), reconstruction) in runs {
        let name = &format!("{name} ({reconstruction})");
        let styles = vec![
            ObjectStyle {
                mode,
                compositing,
                iso: 200.0,
                ..style(2, &tf, Local::Over)
            },
            ObjectStyle {
                enabled: false,
                ..style(1, &tf, Local::Over)
            },
        ];
        let out = common::run_node(
            &mut session,
            "TwoLevelRaycast",
            vec![
                ("volume", volume_value.clone()),
                (
                    "labels",
                    Value::Labels(Arc::new(Labels::new(labels.clone()))),
                ),
                ("styles", Value::ObjectStyles(Arc::new(styles))),
                ("camera", Value::Camera(Arc::new(cam.clone()))),
            ],
            &[
                ("step", ParamValue::Float(STEP as f64)),
                ("jitter", ParamValue::Bool(false)),
                ("early_termination", ParamValue::Float(0.99)),
                ("reconstruction", ParamValue::Choice(reconstruction.into())),
            ],
        );
        let two_level = export::to_array(&out[0], &session.ctx.gpu).unwrap();
        let out = common::run_node(
            &mut session,
            "Raycast",
            vec![
                ("volume", volume_value.clone()),
                ("camera", Value::Camera(Arc::new(cam.clone()))),
                (
                    "tf",
                    Value::TransferFunction(Arc::new(
                        hatchery_nodes::value::TransferFunction::Color(tf.clone()),
                    )),
                ),
            ],
            &[
                ("mode", ParamValue::Choice(ray_mode.into())),
                ("shading", ParamValue::Choice(shading.into())),
                ("iso", ParamValue::Float(200.0)),
                ("step", ParamValue::Float(STEP as f64)),
                ("jitter", ParamValue::Bool(false)),
                ("early_termination", ParamValue::Float(0.99)),
                ("reconstruction", ParamValue::Choice(reconstruction.into())),
            ],
        );
        let raycast = export::to_array(&out[0], &session.ctx.gpu).unwrap();
        let pixels = |a: &export::Array| -> Vec<[f32; 4]> {
            a.data
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect()
        };
        let (two_level, raycast) = (pixels(&two_level), pixels(&raycast));
        let covered = raycast.iter().filter(|p| p[3] > 0.05).count();
        assert!(covered > 100, "{name}: only {covered} pixels covered");
        common::assert_images_close(name, &two_level, &raycast, SIZE, 1.0 / 255.0);
    }
}

#[test]
fn label_mask_reads_labels_as_it_reads_a_label_volume() {
    let (volume, labels) = nested_spheres();
    let mut session = session();
    let params = [
        ("labels", ParamValue::Text("2".into())),
        ("smooth", ParamValue::Float(1.0)),
    ];
    let mask_of = |session: &mut Session, input: (&'static str, Value)| {
        let out = common::run_node(session, "LabelMask", vec![input], &params);
        match &out[0] {
            Value::Volume(v) => v.data.values_f32().into_owned(),
            _ => panic!("not a volume"),
        }
    };
    let from_labels = mask_of(
        &mut session,
        ("objects", Value::Labels(Arc::new(Labels::new(labels)))),
    );
    // The label volume as numbers: ids 0, 1, 2 (the data is 100 × id).
    let ids = volume.values_f32().iter().map(|v| v / 100.0).collect();
    let as_numbers = volume.with_values(ids).unwrap();
    let from_volume = mask_of(
        &mut session,
        ("volume", Value::Volume(Arc::new(Volume::new(as_numbers)))),
    );
    assert_eq!(from_labels, from_volume);
    let inside = from_labels.iter().filter(|&&m| m > 0.5).count();
    assert!(inside > 1000, "core voxels: {inside}");
}

#[test]
fn object_ids_up_to_65535_render_as_small_ones_do() {
    let mut session = session();
    let cam = camera(&mut session);
    let p = ray_params(&cam);
    let (volume, small) = nested_spheres();
    // The same objects as ids 30001 and 65535.
    let ids = small
        .ids
        .iter()
        .map(|&id| match id {
            1 => 30001,
            2 => 65535,
            _ => 0,
        })
        .collect();
    let large = LabelData::new(small.dims, small.geometry, ids);
    let objects = |shell: u16, core: u16| {
        [
            Object {
                id: shell,
                tf: flat(SHELL),
                local: Local::Mip,
            },
            Object {
                id: core,
                tf: flat(CORE),
                local: Local::Over,
            },
        ]
    };
    let styles = |o: &[Object]| o.iter().map(|o| style(o.id, &o.tf, o.local)).collect();
    let large_objects = objects(30001, 65535);
    let gpu = render_gpu(
        &mut session,
        &cam,
        &volume,
        &large,
        styles(&large_objects),
        Global::Over,
        "filtered",
    );
    let cpu = reference::render(&volume, &small, &objects(1, 2), Global::Over, true, &p);
    assert!(cpu.iter().filter(|c| c[3] > 0.01).count() > 500);
    common::assert_images_close("ids 30001 and 65535", &gpu, &cpu, SIZE, 1.0 / 255.0);
}

#[test]
fn label_file_names_objects_from_a_slicer_segmentation_header() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frog.seg.nrrd");
    let mut bytes = b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\
        space: right-anterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n\
        Segment0_Name:=skin\nSegment0_LabelValue:=1\nSegment1_Name:=liver\n\
        Segment1_LabelValue:=3\n\n"
        .to_vec();
    bytes.extend_from_slice(&[1, 1, 3, 3, 0, 0, 3, 3]);
    std::fs::write(&path, bytes).unwrap();
    let mut session = session();
    let out = common::run_node(
        &mut session,
        "LabelFile",
        vec![],
        &[("path", ParamValue::Path(path.display().to_string()))],
    );
    let Value::Labels(labels) = &out[0] else {
        panic!("not labels")
    };
    let names: Vec<(u16, &str)> = labels
        .data
        .objects
        .iter()
        .map(|(id, n)| (*id, n.as_str()))
        .collect();
    assert_eq!(names, vec![(1, "skin"), (3, "liver")]);
}

/// On CPU adapters the ids are read as 2×2 quads (value/id_quads.rs: a footprint's 8 corners in
/// 2 loads); the picture must equal the one-id texture's bit for bit — boundary filtering and
/// the objects' mask normals read every corner — for ids below 256 (Rgba8Uint) and above
/// (Rgba16Uint).
#[test]
fn id_quads_give_the_one_id_textures_picture_bit_for_bit() {
    for offset in [0u16, 300] {
        let (volume, labels) = nested_spheres();
        let ids = labels
            .ids
            .iter()
            .map(|&id| if id == 0 { 0 } else { id + offset })
            .collect();
        let labels = LabelData::new(labels.dims, labels.geometry, ids);
        let mut pictures = Vec::new();
        for quads in [true, false] {
            let mut s = session();
            if !quads {
                s.ctx.gpu.set_volume_limits(hatchery_gpu::VolumeLimits {
                    quads_bytes: 0,
                    ..hatchery_gpu::VolumeLimits::default()
                });
            }
            let shared = Arc::new(Labels::new(labels.clone()));
            let made = shared.id_quads(&s.ctx.gpu).unwrap().is_some();
            let cpu = s.ctx.gpu.adapter_info.device_type == wgpu::DeviceType::Cpu;
            assert_eq!(made, quads && cpu, "id quads made (allowed: {quads})");
            let cam = zoomed_camera(&mut s, Vec3::new(3.0, -2.0, 0.0), 14.0);
            let styles: Vec<ObjectStyle> = [(1, SHELL), (2, CORE)]
                .into_iter()
                .map(|(id, rgba)| ObjectStyle {
                    mode: RenderMode::ShadedDvr,
                    ..style(id + offset, &flat(rgba), Local::Over)
                })
                .collect();
            let out = common::run_node(
                &mut s,
                "TwoLevelRaycast",
                vec![
                    (
                        "volume",
                        Value::Volume(Arc::new(Volume::new(volume.clone()))),
                    ),
                    ("labels", Value::Labels(shared)),
                    ("styles", Value::ObjectStyles(Arc::new(styles))),
                    ("camera", Value::Camera(Arc::new(cam))),
                ],
                &[
                    ("boundary", ParamValue::Choice("filtered".into())),
                    ("normals", ParamValue::Choice("objects".into())),
                    ("step", ParamValue::Float(STEP as f64)),
                    ("jitter", ParamValue::Bool(false)),
                ],
            );
            pictures.push(export::to_array(&out[0], &s.ctx.gpu).unwrap().data);
        }
        let (with, without) = (&pictures[0], &pictures[1]);
        assert!(
            with.chunks(4).filter(|p| p[3] > 0.1).count() > 100,
            "an empty picture"
        );
        let differ = with.iter().zip(without).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ, 0,
            "ids from {offset}: {differ} channels differ with id quads"
        );
    }
}
