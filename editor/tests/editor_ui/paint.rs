//! Volume painting (issue 31, VolumeShop §6.1), driven by pointer events on the picture: the
//! paint tool's drag adds dabs where the pointer meets the sphere's visible surface, the painted
//! selection turns the picture red there, one drag is one undo step, and the painting survives
//! saving and reopening.

use super::custom_shader::{step_until, wgpu_harness};
use super::*;

/// A sphere (radius 0.7 of [-1, 1]³, seen along −z), an empty painting on its grid, and a
/// SelectionRender drawing the sphere grey and the painted selection red.
const GRAPH: &str = r#"(
    version: 3,
    nodes: [
        (id: "sphere", kind: "ProceduralVolume", params: {"shape": "sphere", "resolution": 48, "radius": 0.7}),
        (id: "paint", kind: "PaintLabels", params: {"radius": 0.15}),
        (id: "grey", kind: "TransferFunction1D", params: {"preset": "custom", "points": "-1: 0.8 0.8 0.8 0; -0.01: 0.8 0.8 0.8 0; 0: 0.8 0.8 0.8 1; 1: 0.8 0.8 0.8 1"}),
        (id: "red", kind: "TransferFunction1D", params: {"preset": "custom", "points": "-1: 0.9 0.1 0.1 0; -0.01: 0.9 0.1 0.1 0; 0: 0.9 0.1 0.1 1; 1: 0.9 0.1 0.1 1"}),
        (id: "camera", kind: "Camera", params: {"azimuth": 0.0, "elevation": 0.0, "distance": 4.0}),
        (id: "select", kind: "SelectionRender", params: {"objects": "1"}),
        (id: "paper", kind: "Fill", params: {"color": [1.0, 1.0, 1.0, 1.0]}),
        (id: "over", kind: "Over", params: {}),
        (id: "save", kind: "SaveImage", params: {"path": "painted.png"}),
    ],
    edges: [
        (from: ("sphere", "volume"), to: ("paint", "volume")),
        (from: ("sphere", "volume"), to: ("select", "volume")),
        (from: ("paint", "labels"), to: ("select", "labels")),
        (from: ("grey", "tf"), to: ("select", "tf")),
        (from: ("red", "tf"), to: ("select", "tf_selection")),
        (from: ("camera", "camera"), to: ("select", "camera")),
        (from: ("select", "image"), to: ("over", "front")),
        (from: ("paper", "image"), to: ("over", "back")),
        (from: ("over", "image"), to: ("save", "image")),
    ],
)"#;

fn strokes(h: &Harness<EditorApp>) -> String {
    let doc = h.state().state.doc();
    let node = doc.nodes.iter().find(|n| n.id == "paint").unwrap();
    match node.params.get("strokes") {
        Some(ron::Value::String(s)) => s.clone(),
        None => String::new(),
        Some(other) => panic!("strokes: {other:?}"),
    }
}

/// How much redder than green the middle of the viewport is, as drawn on screen.
fn redness(h: &mut Harness<EditorApp>) -> f32 {
    let shot = h.render().expect("kittest wgpu render");
    let ppp = shot.width() as f32 / 1280.0;
    let c = h.state().viewport_rect.center();
    let (cx, cy) = ((c.x * ppp) as u32, (c.y * ppp) as u32);
    let mut sum = 0.0;
    for y in cy - 3..cy + 3 {
        for x in cx - 3..cx + 3 {
            let p = shot.get_pixel(x, y);
            sum += (p[0] as f32 - p[1] as f32) / 255.0 / 36.0;
        }
    }
    sum
}

#[test]
fn a_drag_with_the_paint_tool_paints_the_visible_surface_and_survives_reopening() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("painted.ron");
    std::fs::write(&path, GRAPH).unwrap();
    let mut state = EditorState::new();
    state.scratch_dir = dir.path().to_path_buf();
    state.open(&path).unwrap();
    let app = EditorApp::new(state);
    let mut h = wgpu_harness(app);
    wait_for_render(&mut h);
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let before = redness(&mut h);
    let camera_raw_before = camera_raw(&h, "azimuth").map(|v| format!("{v:?}"));

    // The tool, by its button; the next render carries the picture's depth.
    h.get_by_label("✏ Paint").click();
    h.run();
    assert!(h.state().preview.paint, "the button turned the tool on");
    step_until(&mut h, "the depth of the picture", |h| {
        !h.state().preview.is_busy() && h.state().preview.depth.is_some()
    });

    // A short stroke across the middle of the picture (the sphere's front, facing the camera).
    let centre = h.state().viewport_rect.center();
    drag_steps(
        &mut h,
        centre - egui::vec2(12.0, 0.0),
        centre + egui::vec2(12.0, 0.0),
        egui::PointerButton::Primary,
    );
    h.run();
    let painted = strokes(&h);
    let dabs = hatchery_data::paint::parse_dabs(&painted).unwrap();
    assert!(dabs.len() >= 2, "dabs: {painted}");
    for dab in &dabs {
        // On the sphere's visible surface: radius 0.7 to about a voxel (2/47), facing +z.
        let r = dab.center.length();
        assert!(
            (r - 0.7).abs() < 0.06,
            "dab off the surface: {dab:?} (|p| = {r})"
        );
        assert!(dab.center.z > 0.6, "dab not on the visible side: {dab:?}");
        assert_eq!((dab.radius, dab.id), (0.15, 1), "the node's brush");
    }
    // The camera did not move: the drag painted instead of orbiting.
    let azimuth = camera_raw(&h, "azimuth").map(|v| format!("{v:?}"));
    assert_eq!(azimuth, camera_raw_before, "the camera moved");

    // The painted selection is drawn red where the stroke went.
    wait_for_render(&mut h);
    let after = redness(&mut h);
    assert!(after > before + 0.3, "redness {before} -> {after}");

    // One drag, one undo step.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(strokes(&h), "", "undo removed the whole stroke");
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run();
    assert_eq!(strokes(&h), painted);

    // Saved and reopened, the painting is still there and renders the same selection.
    h.state_mut().state.save().unwrap();
    let (loaded, _) = GraphDocument::load(&path).unwrap();
    let node = loaded.nodes.iter().find(|n| n.id == "paint").unwrap();
    assert_eq!(
        node.params.get("strokes"),
        Some(&ron::Value::String(painted.clone()))
    );
    let mut session = hatchery_nodes::Session::open(&path, 64, 64).unwrap();
    session.run(&["paint"]).unwrap();
    let Ok(hatchery_nodes::Value::Labels(labels)) = session.output("paint", "labels") else {
        panic!("no labels")
    };
    let selected = labels.data.ids.iter().filter(|&&id| id == 1).count();
    assert!(selected > 20, "{selected} voxels painted");
}
