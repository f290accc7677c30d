//! Colour by the distance to a risk structure (the tutorial's Preim/Tietjen neck dissection
//! planning, §4.3: a discrete scale at 2 and 5 mm): `DistanceToObject` measures, and
//! `TwoLevelRaycast` draws a structure with a transfer function over millimetres. Known answer:
//! a plate seen face-on above a ball shows the bands as rings whose radii follow from the
//! distance sqrt(ρ² + h²) − R.

mod common;

use glam::Vec3;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Compositing, Labels, ObjectStyle, RenderMode};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

/// Odd: the ball's centre column is a column of voxel centres.
const N: u32 = 65;
const SPACING: [f64; 3] = [0.75, 0.75, 1.25];
const SIZE: u32 = 128;
/// The ball's radius and the height of the plate's top voxel centres above its centre (mm):
/// both whole z spacings, so the ball's top and the plate's top are voxel centres. The bands
/// are at 3 and 6 mm here (the paper's 2 and 5 mm in the frog preset).
const R: f32 = 6.25;
const H: f32 = 7.5;

const RED: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
const YELLOW: [f32; 4] = [1.0, 1.0, 0.0, 1.0];
const BLUE: [f32; 4] = [0.2, 0.3, 1.0, 1.0];

/// World position of voxel centres: the grid centred at the origin in x and y, z from 0.
fn geometry() -> Geometry {
    let half = |s: f64| -s * f64::from(N - 1) / 2.0;
    Geometry::axis_aligned(SPACING, [half(SPACING[0]), half(SPACING[1]), 0.0])
}

/// A ball (id 2, radius R, centred at z_c) and above it a plate (id 1) whose top face lies H
/// above the ball's centre; the eye looks down −z onto the plate's top.
fn scene() -> (LabelData, f32) {
    let g = geometry();
    let z_top = (f64::from(N - 1) * SPACING[2]) as f32 - 2.0 * SPACING[2] as f32;
    let z_c = z_top - H;
    let mut ids = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let p = g.voxel_to_world(Vec3::new(x as f32, y as f32, z as f32));
                ids.push(if (p - Vec3::new(0.0, 0.0, z_c)).length() <= R + 1e-3 {
                    2
                } else if p.z <= z_top + 1e-3 && p.z >= z_top - 3.0 {
                    1
                } else {
                    0
                });
            }
        }
    }
    (LabelData::new([N; 3], g, ids), z_top)
}

fn bands() -> TransferFunction1D {
    let point = |value, rgba| ControlPoint { value, rgba };
    TransferFunction1D::from_points(&[
        point(0.0, RED),
        point(2.999, RED),
        point(3.0, YELLOW),
        point(5.999, YELLOW),
        point(6.0, BLUE),
        point(40.0, BLUE),
    ])
    .unwrap()
}

#[test]
fn a_plate_above_a_ball_shows_the_distance_bands_as_rings() {
    let mut session: Session = common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    );
    let (labels, z_top) = scene();
    let labels_value = Value::Labels(Arc::new(Labels::new(labels.clone())));
    let out = common::run_node(
        &mut session,
        "DistanceToObject",
        vec![("labels", labels_value.clone())],
        &[("objects", ParamValue::Text("2".into()))],
    );
    let Value::Volume(distance) = &out[0] else {
        panic!("not a volume")
    };
    // Placed on the labels' grid, and in millimetres: straight above the ball's top, on the
    // plate's top voxel centres, H − R.
    assert_eq!(distance.data.dims, [N; 3]);
    let above = distance
        .data
        .sample_trilinear(distance.data.world_to_voxel(Vec3::new(0.0, 0.0, z_top)));
    // (The ball's top voxel centre lies up to one z spacing below the sphere's top.)
    assert!(
        above >= H - R - 1e-3 && above <= H - R + SPACING[2] as f32,
        "distance above the ball {above} mm"
    );

    session.ctx.set_size(SIZE, SIZE).unwrap();
    let half_width = 0.5 * SPACING[0] as f32 * (N - 1) as f32;
    let fov = 2.0 * (half_width / 200.0).atan().to_degrees();
    let camera = Camera::orbit(
        Vec3::new(0.0, 0.0, z_top),
        0.0,
        0.0,
        200.0,
        fov,
        true,
        1.0,
        500.0,
        false,
        SIZE,
        SIZE,
    );
    let plate = ObjectStyle {
        id: 1,
        name: "plate".into(),
        enabled: true,
        tf: bands(),
        // Opaque: the plate's first sample shows the transfer function at its distance.
        mode: RenderMode::Dvr,
        compositing: Compositing::Over,
        iso: 0.0,
        importance: 1.0,
    };
    let out = common::run_node(
        &mut session,
        "TwoLevelRaycast",
        vec![
            ("volume", out[0].clone()),
            ("labels", labels_value),
            ("styles", Value::ObjectStyles(Arc::new(vec![plate]))),
            ("camera", Value::Camera(Arc::new(camera.clone()))),
        ],
        &[
            ("jitter", ParamValue::Bool(false)),
            ("step", ParamValue::Float(0.25)),
        ],
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let picture = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    let rgba: Vec<[f32; 4]> = picture
        .data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();

    // The expected band at each pixel: the measured distance at the plate's face under it (the
    // filtered mask crosses 0.5 half a voxel above the top voxel centres; the first sample lies
    // within one step below that), leaving out pixels within 0.35 mm of a band edge. The
    // measured distance must also agree with the analytic sqrt(ρ² + H²) − R to within what the
    // voxels allow: never less, and more by at most a z spacing (the ball's voxel centres lie
    // up to that inside the sphere) plus the face's height above the plate's top centres.
    let z_face = z_top + 0.5 * SPACING[2] as f32 - 0.1;
    let class = |c: [f32; 4]| -> usize {
        if c[2] > c[0] {
            2
        } else if c[1] > 0.5 * c[0] {
            1
        } else {
            0
        }
    };
    let inv = camera.view_proj().inverse();
    let mut counts = [0usize; 3];
    let mut wrong = Vec::new();
    for (i, c) in rgba.iter().enumerate() {
        let (x, y) = (
            (i as u32 % SIZE) as f32 + 0.5,
            (i as u32 / SIZE) as f32 + 0.5,
        );
        let ndc = glam::Vec4::new(
            x / SIZE as f32 * 2.0 - 1.0,
            1.0 - y / SIZE as f32 * 2.0,
            0.0,
            1.0,
        );
        let p = inv * ndc;
        let (px, py) = (p.x / p.w, p.y / p.w);
        if px.abs() > half_width - 1.0 || py.abs() > half_width - 1.0 {
            continue; // the plate's rim
        }
        let face = Vec3::new(px, py, z_face);
        let d = distance
            .data
            .sample_trilinear(distance.data.world_to_voxel(face));
        let analytic = (px * px + py * py + H * H).sqrt() - R;
        assert!(
            d >= analytic - 1e-3 && d <= analytic + SPACING[2] as f32 + (z_face - z_top),
            "at ({px}, {py}) mm: measured {d} mm, analytic {analytic} mm"
        );
        if (d - 3.0).abs() < 0.35 || (d - 6.0).abs() < 0.35 {
            continue;
        }
        let want = if d < 3.0 {
            0
        } else if d < 6.0 {
            1
        } else {
            2
        };
        assert!(c[3] > 0.99, "pixel ({x}, {y}) shows no plate: {c:?}");
        counts[want] += 1;
        if class(*c) != want {
            wrong.push(((x, y), d, *c));
        }
    }
    assert!(
        counts.iter().all(|&n| n > 60),
        "pixels per band (red, yellow, blue): {counts:?}"
    );
    assert!(
        wrong.is_empty(),
        "{} pixels in the wrong band, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(5)]
    );
}

#[test]
fn objects_are_named_or_numbered_and_a_missing_one_is_an_error() {
    let mut session: Session =
        common::session_from_text(r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#, 8, 8);
    let (mut labels, _) = scene();
    labels.name_objects(&[(1, "plate".to_owned()), (2, "ball".to_owned())].into());
    let value = Value::Labels(Arc::new(Labels::new(labels)));
    let by_name = common::run_node(
        &mut session,
        "DistanceToObject",
        vec![("labels", value.clone())],
        &[("objects", ParamValue::Text("Ball".into()))],
    );
    let by_id = common::run_node(
        &mut session,
        "DistanceToObject",
        vec![("labels", value.clone())],
        &[("objects", ParamValue::Text("2".into()))],
    );
    let (Value::Volume(a), Value::Volume(b)) = (&by_name[0], &by_id[0]) else {
        panic!("not volumes")
    };
    assert_eq!(a.data.values_f32(), b.data.values_f32());
    // Through the executor: the error names the node and the parameter or port.
    let node = session.registry.node("DistanceToObject").unwrap();
    for (objects, says) in [
        ("kidney", "no object is named `kidney`"),
        ("7", "object id 7"),
    ] {
        let mut params = std::collections::BTreeMap::new();
        params.insert("objects".to_owned(), ParamValue::Text(objects.into()));
        params.insert("signed".to_owned(), ParamValue::Bool(false));
        let e = node
            .execute(
                &mut session.ctx,
                &hatchery_graph::NodeInputs::new(vec!["labels"], vec![Some(value.clone())]),
                &hatchery_graph::Params::new(params, None),
            )
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains(says), "{objects}: {e}");
    }
}
