//! The overlay nodes through the node path, on a transparent 128×96 image: AnnotationOverlay
//! (leaders, anchor dots, text with halos; VolumeShop §6.4) and the §6.3 visual conventions
//! Arrow, Fan and BoundingBox. Pixels: top-left origin, y down, centres at (x + 0.5, y + 0.5).

mod common;

use glam::{Vec2, Vec3};
use hatchery_annotation::{
    Anchor, HullPath, Layout, PlacedLabel, ProjectedAnchor, Rect, box_corners,
    point_segment_distance, project_point,
};
use hatchery_graph::{NodeError, NodeInputs, ParamValue, Params};
use hatchery_nodes::annotations::{Annotations, Placed};
use hatchery_nodes::camera::Camera;
use hatchery_nodes::{Session, Value, export, label_font};
use std::collections::BTreeMap;
use std::sync::Arc;

const W: u32 = 128;
const H: u32 = 96;
const FONT: f32 = 14.0;

fn session() -> Session {
    common::session_from_text(r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#, W, H)
}

/// A frame of one colour (straight RGBA).
fn filled(session: &mut Session, rgba: [f64; 4]) -> Value {
    let out = common::run_node(
        session,
        "Fill",
        vec![],
        &[("color", ParamValue::Color(rgba))],
    );
    out[0].clone()
}

/// Like `common::run_node`, but returning the node's error.
fn try_node(
    session: &mut Session,
    kind: &str,
    inputs: Vec<(&'static str, Value)>,
    params: &[(&str, ParamValue)],
) -> Result<Value, NodeError> {
    let node = session.registry.node(kind).expect("node kind");
    let schema = node.schema();
    let mut values: BTreeMap<String, ParamValue> = schema
        .params
        .iter()
        .map(|p| (p.name.to_owned(), p.default.clone()))
        .collect();
    for (name, value) in params {
        values.insert((*name).to_owned(), value.clone());
    }
    let names: Vec<&'static str> = schema.inputs.iter().map(|p| p.name).collect();
    let ordered = names
        .iter()
        .map(|n| inputs.iter().find(|(m, _)| m == n).map(|(_, v)| v.clone()))
        .collect();
    node.execute(
        &mut session.ctx,
        &NodeInputs::new(names, ordered),
        &Params::new(values, None),
    )
    .map(|mut v| v.remove(0))
}

/// Premultiplied RGBA per pixel, row-major.
fn pixels(session: &Session, value: &Value) -> Vec<[f32; 4]> {
    let a = export::to_array(value, &session.ctx.gpu).unwrap();
    assert_eq!(a.shape, vec![H as usize, W as usize, 4]);
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

fn centre(i: usize) -> Vec2 {
    Vec2::new((i % W as usize) as f32 + 0.5, (i / W as usize) as f32 + 0.5)
}

/// Centres of the pixels whose alpha exceeds `threshold`.
fn ink(px: &[[f32; 4]], threshold: f32) -> Vec<Vec2> {
    (0..px.len())
        .filter(|&i| px[i][3] > threshold)
        .map(centre)
        .collect()
}

/// The largest alpha among pixels whose centre lies within `radius` of `p`.
fn alpha_near(px: &[[f32; 4]], p: Vec2, radius: f32) -> f32 {
    (0..px.len())
        .filter(|&i| centre(i).distance(p) <= radius)
        .map(|i| px[i][3])
        .fold(0.0, f32::max)
}

/// Points every `step` pixels from `a` to `b`, both ends included.
fn along(a: Vec2, b: Vec2, step: f32) -> Vec<Vec2> {
    let n = (a.distance(b) / step).ceil().max(1.0) as usize;
    (0..=n).map(|i| a.lerp(b, i as f32 / n as f32)).collect()
}

fn rect_distance(r: &Rect, p: Vec2) -> f32 {
    (r.min - p).max(p - r.max).max(Vec2::ZERO).length()
}

// --- AnnotationOverlay -----------------------------------------------------------------------

const ANCHOR: Vec2 = Vec2::new(30.0, 70.0);

/// One label "liver" with its box at (60, 12) and its leader from the anchor to the box corner
/// nearest it, laid out by hand.
fn labelled(shown: bool, opacity: f32) -> (Value, Rect, [Vec2; 2]) {
    let [w, h] = label_font::measure("liver", FONT);
    let min = Vec2::new(60.0, 12.0);
    let rect = Rect {
        min,
        max: min + Vec2::new(w, h) + 4.0,
    };
    let leader = [ANCHOR, Vec2::new(rect.min.x, rect.max.y)];
    let hull = vec![
        ANCHOR,
        ANCHOR + Vec2::new(10.0, 0.0),
        ANCHOR + Vec2::new(5.0, -8.0),
    ];
    let label = PlacedLabel {
        anchor: 0,
        rect,
        parameter: 0.0,
        path_point: leader[1],
        hull_point: ANCHOR,
        leader,
        opacity,
        shown,
        inside_frame: true,
        swapped: false,
    };
    let placed = Placed {
        layout: Layout {
            labels: vec![label],
            path: HullPath::new(&hull, 8.0),
            iterations: 0,
            swaps: 0,
            disabled: 0,
        },
        projected: vec![ProjectedAnchor {
            screen: ANCHOR,
            depth: 0.5,
            visible: true,
            priority: 1.0,
        }],
        hull,
        width: W,
        height: H,
        font_size: FONT,
        padding: hatchery_nodes::annotation_layout::LABEL_PADDING,
    };
    let annotations = Annotations {
        anchors: vec![Anchor {
            position: Vec3::ZERO,
            text: "liver".into(),
            object: 1,
            priority: 1.0,
        }],
        bounds: vec![None],
        placed: Some(Arc::new(placed)),
    };
    (Value::Annotations(Arc::new(annotations)), rect, leader)
}

const NONE: ParamValue = ParamValue::Color([0.0, 0.0, 0.0, 0.0]);

fn overlay(
    session: &mut Session,
    annotations: Value,
    params: &[(&str, ParamValue)],
) -> Vec<[f32; 4]> {
    let image = filled(session, [0.0; 4]);
    let out = try_node(
        session,
        "AnnotationOverlay",
        vec![("image", image), ("annotations", annotations)],
        params,
    )
    .unwrap();
    pixels(session, &out)
}

#[test]
fn label_text_and_halo_stay_in_the_label_box() {
    let mut s = session();
    let (annotations, rect, _) = labelled(true, 1.0);
    let no_lines = [
        ("leader_width", ParamValue::Float(0.0)),
        ("dot_radius", ParamValue::Float(0.0)),
    ];
    let area = rect.size().x * rect.size().y;

    let mut params = no_lines.to_vec();
    params.push(("halo_color", NONE));
    let text = overlay(&mut s, annotations.clone(), &params);
    let glyphs = ink(&text, 0.02);
    let outside = glyphs
        .iter()
        .filter(|p| rect_distance(&rect, **p) > 1.0)
        .count();
    assert_eq!(outside, 0, "text ink outside the label box {rect:?}");
    let solid = ink(&text, 0.5).len() as f32;
    assert!(
        (0.08..0.6).contains(&(solid / area)),
        "text covers {solid} of the box's {area} px²"
    );
    // Black text: premultiplied colour 0 where it is opaque.
    assert!(text.iter().all(|p| p[0] <= 1e-3));

    let haloed = overlay(&mut s, annotations, &no_lines);
    // Pixels up to the halo width (2 px) from the glyphs, which reach 1 px beyond the box.
    let halo_ink = ink(&haloed, 0.02);
    let far = halo_ink
        .iter()
        .map(|p| rect_distance(&rect, *p))
        .fold(0.0, f32::max);
    assert!(
        far <= 3.0,
        "halo ink {far} px from the box: wider than the halo width (2 px)"
    );
    let covered = ink(&haloed, 0.5).len() as f32;
    assert!(
        covered > 1.5 * solid,
        "the halo widens the ink: {covered} vs {solid}"
    );
    // White halo around black text: both show.
    assert!(haloed.iter().any(|p| p[3] > 0.9 && p[0] > 0.9));
    // (Ubuntu Light's thin strokes reach about 90 % coverage at 14 px.)
    assert!(haloed.iter().any(|p| p[3] > 0.9 && p[0] < 0.25));
}

#[test]
fn leaders_follow_their_segment_with_the_label_opacity() {
    let mut s = session();
    let only_leader = [
        ("dot_radius", ParamValue::Float(0.0)),
        ("text_color", NONE),
        ("halo_color", NONE),
    ];
    let (annotations, _, [a, b]) = labelled(true, 1.0);
    let full = overlay(&mut s, annotations, &only_leader);
    let far = ink(&full, 0.02)
        .into_iter()
        .map(|p| point_segment_distance(p, a, b))
        .fold(0.0, f32::max);
    assert!(far <= 1.5, "leader ink {far} px from its segment");
    for q in along(a, b, 1.0) {
        let alpha = alpha_near(&full, q, 1.0);
        assert!(alpha > 0.5, "leader gap at {q}: alpha {alpha}");
    }

    let (faint, _, _) = labelled(true, 0.4);
    let faint = overlay(&mut s, faint, &only_leader);
    let sum = |px: &[[f32; 4]]| px.iter().map(|p| p[3] as f64).sum::<f64>();
    let ratio = sum(&faint) / sum(&full);
    assert!(
        (ratio - 0.4).abs() < 0.02,
        "opacity 0.4 gives alpha ratio {ratio}"
    );
}

#[test]
fn a_dot_marks_the_anchor() {
    let mut s = session();
    let (annotations, _, _) = labelled(true, 1.0);
    let dot = overlay(
        &mut s,
        annotations,
        &[
            ("leader_width", ParamValue::Float(0.0)),
            ("text_color", NONE),
            ("halo_color", NONE),
        ],
    );
    assert!(alpha_near(&dot, ANCHOR, 0.8) > 0.95);
    let spots = ink(&dot, 0.02);
    assert!(spots.len() >= 12, "{} dot pixels", spots.len());
    assert!(spots.iter().all(|p| p.distance(ANCHOR) < 2.5 + 0.5));
}

#[test]
fn hidden_labels_draw_nothing_and_the_picture_shows_through() {
    let mut s = session();
    let (hidden, _, _) = labelled(false, 1.0);
    let px = overlay(&mut s, hidden, &[]);
    assert!(px.iter().all(|p| p[3] == 0.0));

    let grey = filled(&mut s, [0.5, 0.5, 0.5, 1.0]);
    let (annotations, rect, _) = labelled(true, 1.0);
    let out = try_node(
        &mut s,
        "AnnotationOverlay",
        vec![("image", grey), ("annotations", annotations)],
        &[],
    )
    .unwrap();
    let px = pixels(&s, &out);
    let corner = px[(H as usize - 2) * W as usize + W as usize - 2];
    let grey = [0.5, 0.5, 0.5, 1.0];
    assert!(
        corner.iter().zip(grey).all(|(c, g)| (c - g).abs() < 1e-3),
        "{corner:?}"
    );
    let inside = px[((rect.min.y + 4.0) as usize) * W as usize + rect.min.x as usize + 1];
    assert!(
        (inside[3] - 1.0).abs() < 1e-3,
        "opaque over an opaque picture"
    );
}

#[test]
fn unlaid_annotations_and_wrong_sizes_are_errors_naming_the_port() {
    let mut s = session();
    let image = filled(&mut s, [0.0; 4]);
    let (annotations, _, _) = labelled(true, 1.0);
    let Value::Annotations(a) = &annotations else {
        unreachable!()
    };
    let unlaid = Value::Annotations(Arc::new(Annotations {
        placed: None,
        ..(**a).clone()
    }));
    let e = try_node(
        &mut s,
        "AnnotationOverlay",
        vec![("image", image.clone()), ("annotations", unlaid)],
        &[],
    )
    .err()
    .expect("an error");
    assert_eq!(e.port.as_deref(), Some("annotations"), "{e}");
    let camera = Value::Camera(Arc::new(camera(0.0)));
    let e = try_node(
        &mut s,
        "Arrow",
        vec![
            ("image", image),
            ("annotations", annotations),
            ("camera", camera),
        ],
        &[],
    )
    .err()
    .expect("an error");
    assert!(e.to_string().contains("anchor 1"), "{e}");
}

// --- Arrow, Fan, BoundingBox (§6.3) ----------------------------------------------------------

fn camera(azimuth: f32) -> Camera {
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        15.0,
        10.0,
        40.0,
        false,
        0.1,
        100.0,
        false,
        W,
        H,
    )
}

fn screen(cam: &Camera, p: Vec3) -> Vec2 {
    project_point(p, cam.view_proj(), Vec2::new(W as f32, H as f32)).screen
}

/// Ghost (anchor 0) and selection (anchor 1) with unit-ish boxes around them.
fn ghost_and_selection(ghost: Vec3, selection: Vec3, half: [Vec3; 2]) -> Value {
    let anchor = |position, text: &str| Anchor {
        position,
        text: text.into(),
        object: 1,
        priority: 1.0,
    };
    Value::Annotations(Arc::new(Annotations {
        anchors: vec![anchor(ghost, "ghost"), anchor(selection, "selection")],
        bounds: vec![
            Some([ghost - half[0], ghost + half[0]]),
            Some([selection - half[1], selection + half[1]]),
        ],
        placed: None,
    }))
}

fn draw(
    s: &mut Session,
    kind: &str,
    annotations: Value,
    cam: &Camera,
    params: &[(&str, ParamValue)],
) -> Vec<[f32; 4]> {
    let image = filled(s, [0.0; 4]);
    let camera = Value::Camera(Arc::new(cam.clone()));
    let out = try_node(
        s,
        kind,
        vec![
            ("image", image),
            ("annotations", annotations),
            ("camera", camera),
        ],
        params,
    )
    .unwrap();
    pixels(s, &out)
}

#[test]
fn arrows_run_from_ghost_to_selection_and_bend_with_depth() {
    let mut s = session();
    let cam = camera(0.0);
    let half = [Vec3::splat(0.5); 2];
    let (ghost, selection) = (Vec3::new(-2.5, 0.0, 0.0), Vec3::new(2.5, 0.0, 0.0));
    let (from, to) = (screen(&cam, ghost), screen(&cam, selection));
    let straight = draw(
        &mut s,
        "Arrow",
        ghost_and_selection(ghost, selection, half),
        &cam,
        &[],
    );
    assert!(
        alpha_near(&straight, from, 2.0) > 0.5,
        "no ink at the ghost {from}"
    );
    assert!(
        alpha_near(&straight, to, 2.0) > 0.5,
        "no ink at the selection {to}"
    );
    // The head (12 px long, 12 px wide at width 2) is at the selection end.
    let head = 3.0 * 2.0 + 6.0;
    let count =
        |px: &[[f32; 4]], p: Vec2| ink(px, 0.5).iter().filter(|q| q.distance(p) < head).count();
    let (at_ghost, at_selection) = (count(&straight, from), count(&straight, to));
    assert!(
        at_selection as f32 > 1.8 * at_ghost as f32,
        "{at_selection} vs {at_ghost}"
    );
    let shaft_off = ink(&straight, 0.02)
        .into_iter()
        // The head's back corners are hypot(12, 6) px from its tip.
        .filter(|p| p.distance(to) > head * 1.12 + 1.5)
        .map(|p| point_segment_distance(p, from, to))
        .fold(0.0, f32::max);
    assert!(
        shaft_off <= 1.5,
        "equal depths: ink {shaft_off} px off the chord"
    );
    for q in along(from, to - (to - from).normalize() * head, 1.0) {
        assert!(alpha_near(&straight, q, 1.0) > 0.5, "shaft gap at {q}");
    }

    // The selection moved 3 units towards the viewer: a bent arrow.
    let nearer = Vec3::new(2.5, 0.0, 3.0);
    let to = screen(&cam, nearer);
    let bent = draw(
        &mut s,
        "Arrow",
        ghost_and_selection(ghost, nearer, half),
        &cam,
        &[],
    );
    assert!(alpha_near(&bent, from, 2.0) > 0.5 && alpha_near(&bent, to, 2.0) > 0.5);
    let bulge = ink(&bent, 0.5)
        .into_iter()
        .map(|p| point_segment_distance(p, from, to))
        .fold(0.0, f32::max);
    assert!(
        bulge > 3.0,
        "depth difference bends the arrow only {bulge} px"
    );
    // Towards the viewer bends it left of travel; travelling right that is up (smaller y).
    let mid = (from + to) * 0.5;
    let above = ink(&bent, 0.5).iter().filter(|p| p.y < mid.y - 3.0).count();
    let below = ink(&bent, 0.5)
        .iter()
        .filter(|p| p.y > mid.y + 3.0 && p.distance(to) > head)
        .count();
    assert!(above > below, "{above} above, {below} below the chord");
}

/// The screen rectangle of a world box's projected corners.
fn screen_rect(cam: &Camera, lo: Vec3, hi: Vec3) -> Rect {
    let points = box_corners(lo, hi).map(|c| screen(cam, c));
    Rect {
        min: points.iter().copied().reduce(Vec2::min).unwrap(),
        max: points.iter().copied().reduce(Vec2::max).unwrap(),
    }
}

#[test]
fn fans_outline_both_rectangles_and_join_them() {
    let mut s = session();
    let cam = camera(0.0);
    let (ghost, selection) = (Vec3::new(-2.5, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0));
    let half = [Vec3::new(0.6, 0.6, 0.6), Vec3::new(1.0, 1.4, 0.6)];
    let px = draw(
        &mut s,
        "Fan",
        ghost_and_selection(ghost, selection, half),
        &cam,
        &[],
    );
    let g = screen_rect(&cam, ghost - half[0], ghost + half[0]);
    let r = screen_rect(&cam, selection - half[1], selection + half[1]);
    assert!(
        g.max.x < r.min.x && r.min.y < g.min.y && r.max.y > g.max.y,
        "{g:?} {r:?}"
    );
    for rect in [g, r] {
        let c = [
            rect.min,
            Vec2::new(rect.max.x, rect.min.y),
            rect.max,
            Vec2::new(rect.min.x, rect.max.y),
        ];
        for i in 0..4 {
            for q in along(c[i], c[(i + 1) % 4], 2.0) {
                assert!(
                    alpha_near(&px, q, 1.0) > 0.5,
                    "rectangle outline gap at {q}"
                );
            }
        }
    }
    // The selection is taller and to the right: the outer tangents join the left corners.
    let bridges = [
        (g.min, r.min),
        (Vec2::new(g.min.x, g.max.y), Vec2::new(r.min.x, r.max.y)),
    ];
    for (a, b) in bridges {
        for q in along(a, b, 2.0) {
            assert!(alpha_near(&px, q, 1.0) > 0.5, "connecting line gap at {q}");
        }
    }
    // Translucent fill between the rectangles, none inside them.
    let between = Vec2::new((g.max.x + r.min.x) * 0.5, (g.min.y + g.max.y) * 0.5);
    let fill = alpha_near(&px, between, 0.8);
    assert!((fill - 0.15).abs() < 0.02, "fill alpha {fill}");
    assert!(alpha_near(&px, r.center(), 3.0) == 0.0 && alpha_near(&px, g.center(), 3.0) == 0.0);
}

#[test]
fn bounding_boxes_draw_the_projected_edges() {
    let mut s = session();
    let cam = camera(35.0);
    let (ghost, selection) = (Vec3::new(-2.5, 0.5, 0.0), Vec3::new(2.0, -0.5, 0.0));
    let half = [Vec3::splat(0.8), Vec3::new(1.0, 1.2, 0.7)];
    let annotations = ghost_and_selection(ghost, selection, half);
    let corners = |p: Vec3, h: Vec3| box_corners(p - h, p + h).map(|c| screen(&cam, c));
    let (gc, sc) = (corners(ghost, half[0]), corners(selection, half[1]));

    let px = draw(&mut s, "BoundingBox", annotations.clone(), &cam, &[]);
    for c in sc {
        assert!(
            alpha_near(&px, c, 1.0) > 0.5,
            "no ink at the selection's corner {c}"
        );
    }
    let edges: Vec<(Vec2, Vec2)> = (0..8)
        .flat_map(|a| [1, 2, 4].map(move |bit| (a, a | bit)))
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (sc[a], sc[b]))
        .collect();
    assert_eq!(edges.len(), 12);
    let off = ink(&px, 0.02)
        .into_iter()
        .map(|p| {
            edges
                .iter()
                .map(|(a, b)| point_segment_distance(p, *a, *b))
                .fold(f32::INFINITY, f32::min)
        })
        .fold(0.0, f32::max);
    assert!(off <= 1.0, "ink {off} px away from every edge (width 1)");
    assert!(
        gc.iter().all(|&c| alpha_near(&px, c, 1.0) == 0.0),
        "the ghost's box is not drawn"
    );

    let both = draw(
        &mut s,
        "BoundingBox",
        annotations,
        &cam,
        &[("which", ParamValue::Choice("both".into()))],
    );
    for c in gc.iter().chain(&sc) {
        assert!(alpha_near(&both, *c, 1.0) > 0.5, "no ink at corner {c}");
    }
}
