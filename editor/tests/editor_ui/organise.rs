//! Organising big graphs — groups, reroutes, frames — through pointer and key events at screen
//! positions, as a user does it.

use super::selection::{click_mod, empty_canvas_point, selection, set, title_pos};
use super::*;
use hatchery_graph::Graph;

/// The centre of a canvas label's text on screen (canvas labels are in graph space), the one
/// furthest left (`min_left`) or right.
fn label_rect(h: &Harness<EditorApp>, label: &str, leftmost: bool) -> egui::Rect {
    let t = h.state().canvas_transform;
    let r = h
        .get_all_by_label(label)
        .map(|n| n.rect())
        .filter(|r| r.left() < h.state().canvas_rect.right() / t.scaling)
        .min_by(|a, b| {
            let o = a.left().total_cmp(&b.left());
            if leftmost { o } else { o.reverse() }
        })
        .unwrap_or_else(|| panic!("no label {label}"));
    egui::Rect::from_min_max(t * r.min, t * r.max)
}

/// A graph-space rectangle on screen.
fn on_screen(h: &Harness<EditorApp>, r: egui::Rect) -> egui::Rect {
    let t = h.state().canvas_transform;
    egui::Rect::from_min_max(t * r.min, t * r.max)
}

/// Where an output pin sits: right of its label, past the room left for it (screen).
fn out_pin(label: egui::Rect) -> egui::Pos2 {
    egui::pos2(label.right() + 14.0, label.center().y)
}

/// Where an input pin sits: just left of its label (screen).
fn in_pin(label: egui::Rect) -> egui::Pos2 {
    egui::pos2(label.left() - 12.0, label.center().y)
}

/// Drags a wire from `from` and drops it at `to` on empty canvas. The menu that opens keeps
/// snarl repainting, so this steps a few frames instead of running until idle.
fn drop_wire(h: &mut Harness<EditorApp>, from: egui::Pos2, to: egui::Pos2) {
    drag_steps(h, from, to, egui::PointerButton::Primary);
    h.run_steps(3);
}

#[test]
fn ctrl_g_groups_tab_enters_and_leaves_ctrl_shift_g_ungroups_and_undo_restores() {
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let before = h.state().state.doc().clone();

    select_by_click(&mut h, "shells");
    let at = title_pos(&h, "surface");
    click_mod(&mut h, at, Modifiers::SHIFT);
    assert_eq!(selection(&h), set(&["shells", "surface"]));
    h.key_press_modifiers(Modifiers::COMMAND, Key::G);
    h.run();

    let doc = h.state().state.doc().clone();
    assert_eq!(doc.groups.len(), 1, "status: {}", h.state().state.status);
    assert_eq!(
        hatchery_graph::organise::members(&doc, "group_1"),
        ["shells", "surface"]
    );
    assert_eq!(doc.edges, before.edges, "grouping keeps every wire");
    assert_eq!(selection(&h), set(&["group_1"]));
    // One group node instead of its members; its exposed port carries the wire to `shaded`.
    h.get_by_label("group_1 (Group)");
    assert!(h.query_by_label("shells (ProceduralVolume)").is_none());
    h.get_by_label("surface.mesh");
    assert!(
        h.query_by_label("surface.volume").is_none(),
        "fed inside the group: not exposed"
    );
    assert!(h.state().state.graph_errors().is_empty() && h.state().state.errors().is_empty());

    // Saved in the current version with the group; the file loads and validates (the CLI can render it).
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("version: 3,"), "{text}");
    assert!(text.contains("group: Some(\"group_1\")"), "{text}");
    assert!(
        text.contains("groups: [\n        (id: \"group_1\""),
        "{text}"
    );
    Graph::load_file(&path, &hatchery_nodes::registry()).unwrap();

    // Tab enters the selected group: only its members are on the canvas.
    h.key_press(Key::Tab);
    h.run();
    assert_eq!(h.state().state.level(), Some("group_1"));
    h.get_by_label("Inside group group_1");
    h.get_by_label("shells (ProceduralVolume)");
    assert!(h.query_by_label("shaded (ShadedSurface)").is_none());
    assert!(h.query_by_label("group_1 (Group)").is_none());
    // Wires to the outside are not drawn inside: surface.mesh (to shaded.mesh) is marked.
    assert_eq!(h.get_all_by_label("➡").count(), 1);
    assert!(
        h.query_by_label("⬅").is_none(),
        "nothing outside feeds the group"
    );
    // Members are edited as usual inside.
    select_by_click(&mut h, "surface");
    // Tab again leaves, with the group selected.
    h.key_press(Key::Tab);
    h.run();
    assert_eq!(h.state().state.level(), None);
    assert_eq!(selection(&h), set(&["group_1"]));
    h.get_by_label("shaded (ShadedSurface)");

    // Ctrl+Shift+G ungroups; the members come back selected.
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::G);
    h.run();
    assert!(h.state().state.doc().groups.is_empty());
    assert_eq!(selection(&h), set(&["shells", "surface"]));
    assert!(
        h.state().node_screen_rect("shells").is_some(),
        "back on the canvas"
    );
    assert!(h.state().node_screen_rect("group_1").is_none());

    // Undo: grouped again, then the graph as it was.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &doc);
    h.get_by_label("group_1 (Group)");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &before);
    assert!(h.query_by_label("group_1 (Group)").is_none());
}

#[test]
fn a_wire_dropped_on_empty_canvas_becomes_a_reroute_that_carries_it() {
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // shells.volume (an output, leftmost) dropped on empty canvas.
    let from = out_pin(on_screen(&h, port_label(&h, "shells", "volume")));
    let to = empty_canvas_point(&h);
    drop_wire(&mut h, from, to);
    h.get_by_label("Add reroute").click();
    h.run();
    let doc = h.state().state.doc().clone();
    let reroute = doc
        .nodes
        .iter()
        .find(|n| n.kind == "Reroute")
        .expect("a reroute was added");
    assert_eq!(reroute.id, "reroute_1");
    let edge = |f: (&str, &str), t: (&str, &str)| hatchery_graph::EdgeDoc {
        from: (f.0.into(), f.1.into()),
        to: (t.0.into(), t.1.into()),
    };
    assert!(
        doc.edges
            .contains(&edge(("shells", "volume"), ("reroute_1", "in"))),
        "{:?}",
        doc.edges
    );

    // Its output (typed Volume now) dragged onto surface.volume replaces the direct wire.
    h.run();
    let out = out_pin(label_rect(&h, "out", true));
    let input = in_pin(on_screen(&h, port_label(&h, "surface", "volume")));
    drag(&mut h, out, input);
    let doc = h.state().state.doc().clone();
    assert!(
        doc.edges
            .contains(&edge(("reroute_1", "out"), ("surface", "volume"))),
        "status: {}",
        h.state().state.status
    );
    assert!(
        !doc.edges
            .contains(&edge(("shells", "volume"), ("surface", "volume")))
    );
    // The graph is valid and runs as if the wire were direct.
    let graph = h
        .state_mut()
        .state
        .validate()
        .expect("valid with a reroute");
    assert_eq!(graph.input_sources("surface")[&0], ("shells", 0));
    assert!(
        graph.node("reroute_1").is_none(),
        "resolved away for rendering"
    );

    // A Camera output cannot go through a Volume reroute.
    let camera = out_pin(on_screen(&h, port_label(&h, "camera", "camera")));
    let reroute_in = in_pin(label_rect(&h, "in", true));
    drag(&mut h, camera, reroute_in);
    assert!(
        h.state().state.status.contains("type mismatch"),
        "{}",
        h.state().state.status
    );

    // It survives saving and loading.
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run();
    let (saved, _) = GraphDocument::load(&path).unwrap();
    assert_eq!(saved.node("reroute_1").unwrap().kind, "Reroute");
    Graph::load_file(&path, &hatchery_nodes::registry()).unwrap();
}

#[test]
fn ctrl_j_frames_the_selection_and_dragging_the_frame_moves_its_nodes_in_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "camera");
    let at = title_pos(&h, "light");
    click_mod(&mut h, at, Modifiers::SHIFT);
    h.key_press_modifiers(Modifiers::COMMAND, Key::J);
    h.run();
    let doc = h.state().state.doc().clone();
    assert_eq!(doc.frames.len(), 1, "status: {}", h.state().state.status);
    let frame = doc.frames[0].clone();
    assert_eq!(frame.label, "Frame 1");
    let area = hatchery_editor::frames::frame_rect(&frame);
    let t = h.state().canvas_transform;
    for id in ["camera", "light"] {
        let r = h.state().node_screen_rect(id).unwrap();
        assert!((t * area).contains_rect(r), "{id} is inside the frame");
    }

    // Drag the title bar (right end: the label is on the left) by 120 × 60 screen points.
    let grip = t * egui::pos2(frame.x + frame.w - 12.0, frame.y + 12.0);
    assert!(h.state().node_at(grip).is_none(), "the title bar is free");
    let by = egui::vec2(120.0, 60.0);
    drag(&mut h, grip, grip + by);
    let moved = h.state().state.doc().clone();
    let expect = by / t.scaling;
    let pos = |d: &GraphDocument, id: &str| d.node(id).unwrap().editor.unwrap();
    for id in ["camera", "light"] {
        let (a, b) = (pos(&doc, id), pos(&moved, id));
        assert!(
            (b.x - a.x - expect.x).abs() < 1.0 && (b.y - a.y - expect.y).abs() < 1.0,
            "{id} moved by ({}, {}), expected {expect:?}",
            b.x - a.x,
            b.y - a.y
        );
    }
    assert!((moved.frames[0].x - frame.x - expect.x).abs() < 1.0);
    assert_eq!(pos(&moved, "shaded"), pos(&doc, "shaded"), "outside: stays");
    assert_eq!(h.state().canvas_transform, t, "the canvas did not pan");

    // One undo step takes frame and nodes back.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &doc);

    // Right-clicking the title bar offers *Rename frame…* (a small window) and *Delete frame*.
    right_click_at(&h, grip);
    h.run();
    h.get_by_label("Rename frame…").click();
    h.run();
    let field = h
        .get_all_by_role(Role::TextInput)
        .find(|n| n.value().as_deref() == Some("Frame 1"))
        .expect("the frame's label field")
        .rect()
        .center();
    click_mod(&mut h, field, Modifiers::NONE);
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.event(egui::Event::Text("Inputs".into()));
    h.key_press(Key::Enter);
    h.run();
    assert_eq!(h.state().state.doc().frames[0].label, "Inputs");
    assert!(h.query_by_label("Frame label").is_none(), "Enter closes it");
    h.key_press(Key::Escape);
    h.run();
    right_click_at(&h, grip);
    h.run();
    h.get_by_label("Delete frame").click();
    h.run();
    assert!(h.state().state.doc().frames.is_empty());
}
