//! Annotation sources and AnnotationLayout through the node path: anchors on their objects,
//! labels outside the hull without overlaps or crossings, hidden anchors left out, and labels
//! that stay put between nearby views (temporal coherence kept by the node).

mod common;

use glam::{Vec2, Vec3};
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_graph::ParamValue;
use hatchery_nodes::annotations::Annotations;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::Labels;
use hatchery_nodes::{Session, Value};
use std::collections::BTreeMap;
use std::sync::Arc;

const N: u32 = 40;
const SIZE: (u32, u32) = (320, 240);

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE.0,
        SIZE.1,
    )
}

/// Six named boxes and an L-shaped object (id 7, concave: its centroid lies outside it) on an
/// N³ grid centred at the origin.
fn labels() -> LabelData {
    let boxes: [(u16, [u32; 3], [u32; 3]); 6] = [
        (1, [2, 2, 2], [8, 8, 8]),
        (2, [30, 3, 5], [37, 9, 12]),
        (3, [4, 30, 20], [10, 37, 27]),
        (4, [28, 28, 28], [36, 36, 36]),
        (5, [16, 16, 2], [22, 22, 6]),
        (6, [16, 2, 30], [24, 6, 37]),
    ];
    let mut ids = vec![0u16; (N * N * N) as usize];
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let at = ((z * N + y) * N + x) as usize;
                for (id, lo, hi) in boxes {
                    if (0..3).all(|a| (lo[a]..=hi[a]).contains(&[x, y, z][a])) {
                        ids[at] = id;
                    }
                }
                // The L: a bar along x and one along y, meeting at the corner (12, 12).
                let bar_x = (12..=26).contains(&x) && (12..=14).contains(&y);
                let bar_y = (12..=14).contains(&x) && (12..=26).contains(&y);
                if (bar_x || bar_y) && (16..=20).contains(&z) {
                    ids[at] = 7;
                }
            }
        }
    }
    let half = (N - 1) as f64 / 2.0;
    let mut data = LabelData::new([N; 3], Geometry::axis_aligned([1.0; 3], [-half; 3]), ids);
    data.objects = BTreeMap::from_iter((1..=7).map(|id| {
        (
            id,
            [
                "", "liver", "lung", "heart", "kidney", "spleen", "stomach", "ileum",
            ][id as usize]
                .to_owned(),
        )
    }));
    data
}

fn camera(session: &mut Session, azimuth: f32) -> Camera {
    session.ctx.set_size(SIZE.0, SIZE.1).unwrap();
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        20.0,
        120.0,
        30.0,
        false,
        1.0,
        500.0,
        false,
        SIZE.0,
        SIZE.1,
    )
}

fn annotations(value: &Value) -> Arc<Annotations> {
    match value {
        Value::Annotations(a) => a.clone(),
        _ => panic!("not annotations"),
    }
}

#[test]
fn annotations_from_labels_anchor_each_object_on_its_own_voxels_with_its_name() {
    let mut session = session();
    let data = labels();
    let out = common::run_node(
        &mut session,
        "AnnotationsFromLabels",
        vec![("labels", Value::Labels(Arc::new(Labels::new(data.clone()))))],
        &[],
    );
    let a = annotations(&out[0]);
    assert_eq!(a.anchors.len(), 7);
    for (anchor, bounds) in a.anchors.iter().zip(&a.bounds) {
        let q = data.geometry.world_to_voxel(anchor.position).round();
        let id = data.id(q.x as u32, q.y as u32, q.z as u32);
        assert_eq!(id, anchor.object, "{} anchored off its object", anchor.text);
        assert_eq!(anchor.text, data.objects[&id]);
        let [lo, hi] = bounds.unwrap();
        assert!(anchor.position.cmpge(lo).all() && anchor.position.cmple(hi).all());
    }
    // Listing objects picks them.
    let out = common::run_node(
        &mut session,
        "AnnotationsFromLabels",
        vec![("labels", Value::Labels(Arc::new(Labels::new(data))))],
        &[("objects", ParamValue::Text("7, 2".into()))],
    );
    let texts: Vec<String> = annotations(&out[0])
        .anchors
        .iter()
        .map(|a| a.text.clone())
        .collect();
    assert_eq!(texts, ["ileum", "lung"]);
}

fn layout(session: &mut Session, cam: &Camera, source: &Value) -> Arc<Annotations> {
    let out = common::run_node(
        session,
        "AnnotationLayout",
        vec![
            ("annotations", source.clone()),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
        ],
        &[("font_size", ParamValue::Float(12.0))],
    );
    annotations(&out[0])
}

#[test]
fn the_layout_places_labels_outside_the_hull_without_overlaps_and_keeps_them_between_frames() {
    let mut session = session();
    let source = common::run_node(
        &mut session,
        "AnnotationsFromLabels",
        vec![("labels", Value::Labels(Arc::new(Labels::new(labels()))))],
        &[],
    )
    .remove(0);
    let mut previous: Option<Vec<Vec2>> = None;
    let mut moved = Vec::new();
    for step in 0..6 {
        let cam = camera(&mut session, 30.0 + step as f32);
        let a = layout(&mut session, &cam, &source);
        let placed = a.placed("annotations").unwrap();
        let shown: Vec<_> = placed.layout.shown().collect();
        assert!(shown.len() >= 5, "only {} of 7 labels shown", shown.len());
        for (i, l) in shown.iter().enumerate() {
            // Outside the hull: no hull vertex inside the label's rectangle, and the label's
            // centre is not inside the hull.
            assert!(!hatchery_annotation::convex_contains(
                &placed.hull,
                l.rect.center()
            ));
            assert!(!hatchery_annotation::rect_intersects_convex_polygon(
                &l.rect,
                &placed.hull
            ));
            for m in &shown[i + 1..] {
                assert!(!l.rect.overlaps(&m.rect), "labels overlap");
                assert!(
                    !hatchery_annotation::segments_cross(
                        l.leader[0],
                        l.leader[1],
                        m.leader[0],
                        m.leader[1]
                    ),
                    "leaders cross"
                );
            }
            // The leader starts at the projected anchor.
            let anchor = placed.projected[l.anchor].screen;
            assert!(l.leader[0].distance(anchor) < 1e-3);
        }
        let centres: Vec<Vec2> = placed
            .layout
            .labels
            .iter()
            .map(|l| l.rect.center())
            .collect();
        if let Some(before) = &previous {
            for (l, (a, b)) in placed.layout.labels.iter().zip(before.iter().zip(&centres)) {
                if l.shown && !l.swapped {
                    moved.push(a.distance(*b));
                }
            }
        }
        previous = Some(centres);
    }
    // 1° steps: labels not swapped move a few pixels at most (the anchors move ~1–2 px).
    let worst = moved.iter().copied().fold(0.0f32, f32::max);
    assert!(
        !moved.is_empty() && worst < 8.0,
        "a label moved {worst} px between 1° views"
    );
}

#[test]
fn anchors_hidden_behind_the_rendered_surface_get_no_label() {
    let mut session = session();
    let cam = camera(&mut session, 0.0);
    // A wall in front of everything: a big box between the camera and the origin.
    let wall = common::run_node(
        &mut session,
        "AnnotationList",
        vec![],
        &[(
            "anchors",
            ParamValue::Text("0 0 0: behind; 0 0 45: in front".into()),
        )],
    )
    .remove(0);
    // The G-buffer of a sphere of radius 0.6·half around the origin… here: a procedural sphere
    // mesh scaled into the world, through the nodes a user would connect.
    let volume = common::run_node(
        &mut session,
        "ProceduralVolume",
        vec![],
        &[
            ("shape", ParamValue::Choice("sphere".into())),
            ("resolution", ParamValue::Int(48)),
        ],
    )
    .remove(0);
    let mesh =
        common::run_node(&mut session, "MarchingCubes", vec![("volume", volume)], &[]).remove(0);
    let mesh = common::run_node(
        &mut session,
        "MeshTransform",
        vec![("mesh", mesh)],
        &[("scale", ParamValue::Vec3([20.0, 20.0, 20.0]))],
    )
    .remove(0);
    let gbuffer = common::run_node(
        &mut session,
        "GBuffer",
        vec![
            ("mesh", mesh),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
        ],
        &[],
    )
    .remove(0);
    let out = common::run_node(
        &mut session,
        "AnnotationLayout",
        vec![
            ("annotations", wall),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
            ("gbuffer", gbuffer),
        ],
        &[("depth_tolerance", ParamValue::Float(1.0))],
    );
    let a = annotations(&out[0]);
    let placed = a.placed("annotations").unwrap();
    let shown: Vec<&str> = placed
        .layout
        .shown()
        .map(|l| a.anchors[l.anchor].text.as_str())
        .collect();
    assert_eq!(
        shown,
        ["in front"],
        "the centre of the sphere is hidden by its surface"
    );
}

#[test]
fn a_frame_too_narrow_for_a_label_leaves_it_out_rather_than_cut() {
    let mut session = session();
    session.ctx.set_size(90, 240).unwrap();
    let cam = Camera::orbit(
        Vec3::ZERO,
        30.0,
        20.0,
        120.0,
        30.0,
        false,
        1.0,
        500.0,
        false,
        90,
        240,
    );
    let source = common::run_node(
        &mut session,
        "AnnotationsFromLabels",
        vec![("labels", Value::Labels(Arc::new(Labels::new(labels()))))],
        &[],
    )
    .remove(0);
    let a = layout(&mut session, &cam, &source);
    let placed = a.placed("annotations").unwrap();
    for l in placed.layout.shown() {
        assert!(
            l.rect.min.x >= 0.0
                && l.rect.min.y >= 0.0
                && l.rect.max.x <= 90.0
                && l.rect.max.y <= 240.0,
            "{} is cut by the frame: {:?}",
            a.anchors[l.anchor].text,
            l.rect
        );
    }
}

/// The frog's organs are labelled by name in the two-level and importance presets (their
/// LabelFile reads the names table; the labels are the object table's drawn rows), and the
/// labelled picture is the one they save.
#[test]
fn the_frog_presets_label_their_organs_by_name() {
    for (preset, want) in [
        (
            "two_level_frog",
            &["liver", "lung", "skeleton", "stomach"][..],
        ),
        (
            "importance_frog_aimc",
            &["large intestine", "liver", "lung", "skeleton", "stomach"],
        ),
        (
            "importance_frog_mimp",
            &["large intestine", "liver", "lung", "skeleton", "stomach"],
        ),
        (
            "importance_frog_vpimc",
            &["large intestine", "liver", "lung", "skeleton", "stomach"],
        ),
    ] {
        let path = common::repo_root().join(format!("graphs/{preset}.ron"));
        let mut session = hatchery_nodes::Session::open(&path, 240, 180).unwrap();
        session.run(&["layout"]).unwrap();
        let hatchery_nodes::Value::Annotations(a) =
            session.output("layout", "annotations").unwrap()
        else {
            panic!("{preset}: layout.annotations is not annotations");
        };
        let mut names: Vec<&str> = a.anchors.iter().map(|x| x.text.as_str()).collect();
        names.sort();
        assert_eq!(names, want, "{preset}");
        // The labelled picture is what the preset saves.
        let saver = common::savers(&session).pop().unwrap();
        let sources = session.graph.input_sources(&saver);
        assert_eq!(sources[&0].0, "labelled", "{preset}");
    }
}
