//! The object table of ObjectStyles in the Inspector, driven by clicks.

use super::selection::select_by_click;
use super::*;

const GRAPH: &str = r#"(
    version: 2,
    nodes: [
        (id: "camera", kind: "Camera", params: {"distance": 3.0}, editor: Some((x: 0.0, y: 0.0))),
        (id: "field", kind: "ProceduralVolume", params: {"resolution": 32, "shape": "sphere"}, editor: Some((x: 0.0, y: 120.0))),
        (id: "labels", kind: "LabelsFromThreshold", params: {"intervals": "-0.2..0.0: 1; 0.0..0.3: 2; 0.3..2: 3"}, editor: Some((x: 260.0, y: 120.0))),
        (id: "objects", kind: "ObjectStyles", params: {"objects": "1: shaded_dvr over; 2: contours mip"}, editor: Some((x: 520.0, y: 120.0))),
        (id: "ray", kind: "TwoLevelRaycast", params: {"jitter": false}, editor: Some((x: 780.0, y: 60.0))),
        (id: "save", kind: "SaveImage", params: {"path": "objects.png"}, editor: Some((x: 1040.0, y: 60.0))),
    ],
    edges: [
        (from: ("field", "volume"), to: ("labels", "volume")),
        (from: ("labels", "labels"), to: ("objects", "labels")),
        (from: ("field", "volume"), to: ("ray", "volume")),
        (from: ("labels", "labels"), to: ("ray", "labels")),
        (from: ("objects", "styles"), to: ("ray", "styles")),
        (from: ("camera", "camera"), to: ("ray", "camera")),
        (from: ("ray", "image"), to: ("save", "image")),
    ],
)"#;

#[test]
fn the_object_table_names_objects_and_edits_rows_by_clicks() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("objects.ron");
    std::fs::write(&path, GRAPH).unwrap();
    let mut state = EditorState::new();
    state.scratch_dir = dir.path().to_path_buf();
    state.open(&path).unwrap();
    let app = EditorApp::new(state);
    let mut h = harness(app);
    h.run();
    wait_for_render(&mut h);
    select_by_click(&mut h, "objects");
    h.run();
    let objects = |h: &Harness<EditorApp>| text_param(h, "objects", "objects");
    let original = objects(&h);

    // A row per object, named after the labels; its check box switches the object off.
    h.get_by_label("1 object 1").click();
    h.run();
    assert_eq!(objects(&h), "1: shaded_dvr over off; 2: contours mip");

    // The rendering mode of row 2 from its combo box (combo boxes in row order: mode,
    // compositing and transfer function of each row).
    let combos: Vec<_> = h.get_all_by_role(Role::ComboBox).collect();
    assert_eq!(combos.len(), 7, "three per row and the add menu");
    combos[3].click();
    h.run();
    h.get_by_label("tone").click();
    h.run();
    assert_eq!(objects(&h), "1: shaded_dvr over off; 2: tone mip");

    // Object 3 is in the labels but not in the table: add it from the menu.
    let combos: Vec<_> = h.get_all_by_role(Role::ComboBox).collect();
    combos[6].click();
    h.run();
    h.get_by_label("3 object 3").click();
    h.run();
    assert_eq!(
        objects(&h),
        "1: shaded_dvr over off; 2: tone mip; 3: shaded_dvr over"
    );

    // Row 2's importance, typed into its field (the numeric field on row 2's line). The table
    // is wider than the Inspector (which keeps its width): scroll it sideways to the field.
    let over = h.get_by_label("2 object 2").rect().center();
    h.event(egui::Event::PointerMoved(over));
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(-400.0, 0.0),
        modifiers: Modifiers::NONE,
        phase: egui::TouchPhase::Move,
    });
    h.run();
    let row = h.get_by_label("2 object 2").rect().center().y;
    let field = h
        .get_all_by_role(Role::SpinButton)
        .map(|n| n.rect())
        .find(|r| (r.center().y - row).abs() < 6.0)
        .expect("an importance field on row 2");
    super::export::type_into(&mut h, field.center(), "0.25");
    assert_eq!(
        objects(&h),
        "1: shaded_dvr over off; 2: tone mip importance=0.25; 3: shaded_dvr over"
    );

    // Row 1's transfer function from its menu: the presets are listed (with their ramps).
    let combos: Vec<_> = h.get_all_by_role(Role::ComboBox).collect();
    combos[2].click();
    h.run();
    h.get_by_label("2 (input tf2)");
    h.get_by_label("bone").click();
    h.run();
    assert_eq!(
        objects(&h),
        "1: shaded_dvr over tf=bone off; 2: tone mip importance=0.25; 3: shaded_dvr over"
    );

    // Each edit is one undo step.
    for _ in 0..5 {
        h.state_mut().state.undo();
    }
    h.run();
    assert_eq!(objects(&h), original);
}
