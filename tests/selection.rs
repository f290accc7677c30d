//! SelectionRender (VolumeShop selective illustration) against its CPU reference
//! (tests/common/selection_reference.rs): ghosting from "no ghosting" to "full cutaway", and the
//! selection's placement (integrated, pinned, decoupled) under a rotating camera.

mod common;

use common::raycast_reference::{Mode, RayParams, Shading};
use common::selection_reference::{self as reference, Cutaway, Setup};
use glam::{Mat4, Vec3};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::selection_render::{Placement, selection_transform};
use hatchery_nodes::value::{Labels, TransferFunction, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 40;
const SIZE: u32 = 48;
const STEP: f32 = 0.37;

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// The half of a ball (value 100, r < 0.85 of the half-size) towards +z (the viewer of the
/// tests' cameras at azimuth 0), around a cube of voxels 22..=30 (value 200, label 1: the
/// selection), on an N³ grid centred at the origin: over the cube's footprint every
/// background sample lies in front of the cube's far side, in the cutaway region.
fn scene() -> (VolumeData, LabelData) {
    let half = (N - 1) as f32 / 2.0;
    let (mut values, mut ids) = (Vec::new(), Vec::new());
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let cube = [x, y, z].iter().all(|&c| (22..=30).contains(&c));
                let r = Vec3::new(x as f32 - half, y as f32 - half, z as f32 - half).length();
                values.push(if cube {
                    200.0
                } else if (r < 0.85 * half && z >= 20) || z == 0 {
                    // A half-ball, and the grid's last layer along the view: samples beyond
                    // its voxel centres (the half voxel outside) are outside the volume.
                    100.0
                } else {
                    0.0
                });
                ids.push(u16::from(cube));
            }
        }
    }
    let geometry = Geometry::axis_aligned([1.0; 3], [-(half as f64); 3]);
    let volume = VolumeData::with_geometry([N; 3], geometry, values).unwrap();
    (volume, LabelData::new([N; 3], geometry, ids))
}

/// The cube's centre in world units.
const CUBE_CENTRE: Vec3 = Vec3::splat(26.0 - 19.5);

fn tf(points: &[(f32, [f32; 4])]) -> TransferFunction1D {
    TransferFunction1D::from_points(
        &points
            .iter()
            .map(|&(value, rgba)| ControlPoint { value, rgba })
            .collect::<Vec<_>>(),
    )
    .unwrap()
}

struct Tfs {
    background: TransferFunction1D,
    ghost: TransferFunction1D,
    selection: TransferFunction1D,
}

fn tfs(visible_context: bool) -> Tfs {
    let a = if visible_context { 1.0 } else { 0.0 };
    Tfs {
        background: tf(&[
            (0.0, [0.8, 0.7, 0.6, 0.0]),
            (50.0, [0.8, 0.7, 0.6, 0.03 * a]),
            (300.0, [0.8, 0.7, 0.6, 0.03 * a]),
        ]),
        ghost: tf(&[
            (0.0, [1.0, 0.1, 0.1, 0.01 * a]),
            (300.0, [1.0, 0.1, 0.1, 0.01 * a]),
        ]),
        selection: tf(&[
            (0.0, [0.1, 0.8, 0.2, 0.0]),
            (150.0, [0.1, 0.8, 0.2, 0.5]),
            (300.0, [0.1, 0.8, 0.2, 0.5]),
        ]),
    }
}

/// Orthographic along −z rotated by `azimuth` about the y axis, showing 2·22 world units.
fn camera(session: &mut Session, azimuth: f32) -> Camera {
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let fov = 2.0 * (22.0f32 / 60.0).atan().to_degrees();
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        0.0,
        60.0,
        fov,
        true,
        0.05,
        200.0,
        false,
        SIZE,
        SIZE,
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

fn tf_value(f: &TransferFunction1D) -> Value {
    Value::TransferFunction(Arc::new(TransferFunction::Color(f.clone())))
}

/// SelectionRender's volume, labels (the scene), camera and background TF inputs.
fn scene_inputs(cam: &Camera, background: &TransferFunction1D) -> Vec<(&'static str, Value)> {
    let (volume, labels) = scene();
    vec![
        ("volume", Value::Volume(Arc::new(Volume::new(volume)))),
        ("labels", Value::Labels(Arc::new(Labels::new(labels)))),
        ("camera", Value::Camera(Arc::new(cam.clone()))),
        ("tf", tf_value(background)),
    ]
}

fn render_gpu(
    session: &mut Session,
    cam: &Camera,
    tfs: &Tfs,
    params: &[(&str, ParamValue)],
) -> Vec<[f32; 4]> {
    let mut all = vec![
        ("objects", ParamValue::Text("1".into())),
        ("shading", ParamValue::Choice("none".into())),
        ("step", ParamValue::Float(STEP as f64)),
        ("jitter", ParamValue::Bool(false)),
    ];
    all.extend(params.iter().cloned());
    let out = common::run_node(
        session,
        "SelectionRender",
        {
            let mut inputs = scene_inputs(cam, &tfs.background);
            inputs.push(("tf_ghost", tf_value(&tfs.ghost)));
            inputs.push(("tf_selection", tf_value(&tfs.selection)));
            inputs
        },
        &all,
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let a = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// GPU against CPU: at most 1 % of the pixels beyond 1/255 and none beyond 6/255. The sample
/// lattice is anchored at the near plane (`t = k h`, the first k with t ≥ t_in), so where
/// t_in / h lies within float rounding of an integer the GPU and the CPU may start one sample
/// apart: a handful of pixels, each off by about one sample's share.
fn assert_close(name: &str, gpu: &[[f32; 4]], cpu: &[[f32; 4]]) {
    let diff = common::diff_images(gpu, cpu, SIZE, |_| true, 1.0 / 255.0);
    if diff.worst > 6.0 / 255.0 || diff.over.len() * 100 > gpu.len() {
        let why = format!(
            "{} pixels beyond 1/255 (at most 1 %, none beyond 6/255)",
            diff.over.len()
        );
        diff.fail(name, gpu, cpu, why);
    }
}

fn vec3_param(v: Vec3) -> ParamValue {
    ParamValue::Vec3([v.x as f64, v.y as f64, v.z as f64])
}

const MOVE: Vec3 = Vec3::new(-14.0, 0.0, 0.0);

#[test]
fn ghosting_goes_from_no_ghosting_to_a_full_cutaway_as_the_cpu_reference() {
    let mut session = session();
    let cam = camera(&mut session, 0.0);
    let tfs = tfs(true);
    let (volume, labels) = scene();
    let p = ray_params(&cam);
    let transform = Mat4::from_translation(MOVE);
    let render = |session: &mut Session, cutaway: &str, g: f32| {
        render_gpu(
            session,
            &cam,
            &tfs,
            &[
                ("translate", vec3_param(MOVE)),
                ("cutaway", ParamValue::Choice(cutaway.into())),
                ("ghosting", ParamValue::Float(g as f64)),
            ],
        )
    };
    let none = render(&mut session, "none", 0.7);
    // Ghosting 0 is the rendering without cutaway.
    common::assert_images_close(
        "ghosting 0 vs no cutaway",
        &render(&mut session, "ghost", 0.0),
        &none,
        SIZE,
        1.0 / 255.0,
    );
    // Every ghosting factor against the CPU reference, and the background's mean opacity over
    // the ghost's footprint falls as the factor grows.
    let footprint: Vec<usize> = (0..(SIZE * SIZE) as usize)
        .filter(|&i| {
            let (x, y) = ((i as u32 % SIZE) as f32, (i as u32 / SIZE) as f32);
            // The cube (world 2.5..10.5 in x and y) seen along −z, ~1.09 px per unit.
            let to_px = |w: f32| (w + 22.0) / 44.0 * SIZE as f32;
            x + 0.5 > to_px(3.5)
                && x + 0.5 < to_px(9.5)
                && SIZE as f32 - (y + 0.5) > to_px(3.5)
                && SIZE as f32 - (y + 0.5) < to_px(9.5)
        })
        .collect();
    assert!(footprint.len() > 20, "{} footprint pixels", footprint.len());
    let mut previous = f32::INFINITY;
    let mut first = None;
    for g in [0.0f32, 0.25, 0.5, 0.75, 1.0] {
        let gpu = render(&mut session, "ghost", g);
        let setup = Setup {
            ids: &[1],
            background: &tfs.background,
            ghost: &tfs.ghost,
            selection: &tfs.selection,
            transform,
            cutaway: Cutaway::Ghost,
            ghosting: g,
        };
        let cpu = reference::render(&volume, &labels, &setup, &p);
        assert_close(&format!("ghosting {g}"), &gpu, &cpu);
        let mean = footprint.iter().map(|&i| gpu[i][3]).sum::<f32>() / footprint.len() as f32;
        eprintln!("ghosting {g}: mean opacity over the ghost's footprint {mean}");
        assert!(
            mean < previous - 1e-4,
            "ghosting {g}: mean opacity {mean} (before {previous})"
        );
        previous = mean;
        first.get_or_insert(mean);
    }
    let first = first.unwrap();
    // Full cutaway removes most of what covered the footprint (the background in front of the
    // cube's far side; the two voxel layers of the half-ball behind it and the faint ghost stay).
    assert!(
        first - previous > 0.05,
        "the cutaway removed only {} of {first}",
        first - previous
    );
}

/// The screen centroid (pixels) of a picture's opacity.
fn centroid(picture: &[[f32; 4]]) -> glam::Vec2 {
    let (mut sum, mut weight) = (glam::Vec2::ZERO, 0.0);
    for (i, c) in picture.iter().enumerate() {
        let at = glam::Vec2::new(
            (i as u32 % SIZE) as f32 + 0.5,
            (i as u32 / SIZE) as f32 + 0.5,
        );
        sum += at * c[3];
        weight += c[3];
    }
    assert!(weight > 5.0, "the selection is not in the picture");
    sum / weight
}

fn project(cam: &Camera, w: Vec3) -> glam::Vec2 {
    let ndc = cam.view_proj().project_point3(w);
    glam::Vec2::new(
        (ndc.x + 1.0) * 0.5 * SIZE as f32,
        (1.0 - ndc.y) * 0.5 * SIZE as f32,
    )
}

#[test]
fn placements_keep_the_selection_where_vol_shop_says_as_the_camera_turns() {
    let mut session = session();
    // Only the selection is visible.
    let tfs = tfs(false);
    let (volume, labels) = scene();
    let render = |session: &mut Session, cam: &Camera, placement: &str| {
        render_gpu(
            session,
            cam,
            &tfs,
            &[
                ("translate", vec3_param(Vec3::new(0.0, -12.0, 0.0))),
                ("rotate", vec3_param(Vec3::new(0.0, 0.0, 30.0))),
                ("placement", ParamValue::Choice(placement.into())),
                ("pin_x", ParamValue::Float(0.3)),
                ("pin_y", ParamValue::Float(0.4)),
            ],
        )
    };
    let mut decoupled = Vec::new();
    for azimuth in [0.0f32, 35.0] {
        let cam = camera(&mut session, azimuth);
        // Integrated: the selection's centre follows the projection of its moved centre.
        let integrated = render(&mut session, &cam, "integrated");
        let expected = project(&cam, CUBE_CENTRE + Vec3::new(0.0, -12.0, 0.0));
        let got = centroid(&integrated);
        assert!(
            got.distance(expected) < 1.0,
            "integrated at {azimuth}°: {got} vs {expected}"
        );
        // And the picture equals the CPU reference with the same transform.
        let transform = selection_transform(
            &cam,
            Placement::Integrated,
            CUBE_CENTRE,
            Vec3::new(0.0, -12.0, 0.0),
            Vec3::new(0.0, 0.0, 30.0),
            [0.3, 0.4],
        );
        let setup = Setup {
            ids: &[1],
            background: &tfs.background,
            ghost: &tfs.ghost,
            selection: &tfs.selection,
            transform,
            cutaway: Cutaway::None,
            ghosting: 0.0,
        };
        let cpu = reference::render(&volume, &labels, &setup, &ray_params(&cam));
        assert_close(&format!("integrated at {azimuth}°"), &integrated, &cpu);
        // Pinned: the centre stays at the pin point whatever the view.
        let pinned = centroid(&render(&mut session, &cam, "pinned"));
        let pin = glam::Vec2::new(0.3 * SIZE as f32, 0.4 * SIZE as f32);
        assert!(
            pinned.distance(pin) < 1.0,
            "pinned at {azimuth}°: {pinned} vs {pin}"
        );
        decoupled.push(render(&mut session, &cam, "decoupled"));
    }
    // Decoupled: neither position nor orientation follow the view — the same picture.
    assert!(
        centroid(&decoupled[0]).distance(glam::Vec2::new(0.3 * SIZE as f32, 0.4 * SIZE as f32))
            < 1.0
    );
    assert_close("decoupled at 0° vs 35°", &decoupled[1], &decoupled[0]);
}

#[test]
fn the_annotations_output_holds_the_ghost_and_the_moved_selection_with_their_boxes() {
    let mut session = session();
    let cam = camera(&mut session, 0.0);
    let tfs = tfs(true);
    let out = common::run_node(
        &mut session,
        "SelectionRender",
        scene_inputs(&cam, &tfs.background),
        &[
            ("objects", ParamValue::Text("1".into())),
            ("translate", vec3_param(MOVE)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    let Value::Annotations(a) = &out[2] else {
        panic!("the third output is not Annotations");
    };
    assert_eq!(a.anchors.len(), 2);
    assert!(a.anchors[0].position.distance(CUBE_CENTRE) < 1e-3);
    assert!(a.anchors[1].position.distance(CUBE_CENTRE + MOVE) < 1e-3);
    // The cube's voxel centres span 22..=30, world 2.5..10.5; the moved box is shifted by MOVE.
    let [lo, hi] = a.bounds[0].unwrap();
    assert!(lo.distance(Vec3::splat(2.5)) < 1e-3 && hi.distance(Vec3::splat(10.5)) < 1e-3);
    let [lo, hi] = a.bounds[1].unwrap();
    assert!(
        lo.distance(Vec3::splat(2.5) + MOVE) < 1e-3 && hi.distance(Vec3::splat(10.5) + MOVE) < 1e-3
    );
}

#[test]
fn the_svg_figure_carries_the_arrow_fan_and_boxes_as_paths() {
    let mut session = session();
    let cam = camera(&mut session, 0.0);
    let tfs = tfs(true);
    let out = common::run_node(
        &mut session,
        "SelectionRender",
        scene_inputs(&cam, &tfs.background),
        &[
            ("objects", ParamValue::Text("1".into())),
            ("translate", vec3_param(MOVE + Vec3::new(0.0, 0.0, 8.0))),
        ],
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("figure.svg");
    common::run_node(
        &mut session,
        "SaveSvg",
        vec![
            ("image", out[0].clone()),
            ("selection", out[2].clone()),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
        ],
        &[
            (
                "path",
                ParamValue::Path(path.to_string_lossy().into_owned()),
            ),
            ("fan", ParamValue::Bool(true)),
            ("boxes", ParamValue::Choice("both".into())),
        ],
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let arrows = doc
        .descendants()
        .find(|n| n.attribute("id") == Some("arrows"))
        .unwrap();
    let paths: Vec<&str> = arrows
        .descendants()
        .filter(|n| n.tag_name().name() == "path")
        .map(|n| n.attribute("d").unwrap())
        .collect();
    // Fan: fill, two rectangles, two connecting lines; 24 box edges; the arrow's shaft and head.
    assert_eq!(paths.len(), 1 + 2 + 2 + 24 + 2, "{} paths", paths.len());
    // The shaft starts at the projected ghost; the head's tip is the projected selection.
    let first_point = |d: &str| -> glam::Vec2 {
        let v: Vec<f32> = d
            .trim_start_matches('M')
            .split(|c: char| c == ' ' || c == ',' || c.is_ascii_alphabetic())
            .filter(|s| !s.is_empty())
            .take(2)
            .map(|s| s.parse().unwrap())
            .collect();
        glam::Vec2::new(v[0], v[1])
    };
    let shaft = paths[paths.len() - 2];
    let head = paths[paths.len() - 1];
    let ghost = project(&cam, CUBE_CENTRE);
    let moved = project(&cam, CUBE_CENTRE + MOVE + Vec3::new(0.0, 0.0, 8.0));
    assert!(
        first_point(shaft).distance(ghost) < 0.01,
        "shaft from {}",
        first_point(shaft)
    );
    assert!(
        first_point(head).distance(moved) < 0.01,
        "head at {}",
        first_point(head)
    );
    // The depth difference (the selection moved 8 units towards the viewer, 8.7 px here) bends
    // the shaft by curvature 0.5 × 8.7 ≈ 4.4 px: its points leave the chord by more than 3 px.
    let points: Vec<glam::Vec2> = shaft.split('L').map(|s| first_point(s.trim())).collect();
    let chord = (moved - ghost).normalize();
    let off = points
        .iter()
        .map(|q| (*q - ghost).perp_dot(chord).abs())
        .fold(0.0, f32::max);
    assert!(off > 3.0, "a straight arrow ({off} px off the chord)");
}
