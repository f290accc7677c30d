//! A legible canvas: *Frame all* shows the whole graph with its nodes named in text at least
//! 11 px high (zoomed out, as boxes with their ids), *Arrange* (clicked in the View menu) lays a
//! graph out without overlaps as one undo step, and every preset is arranged.

use super::*;

/// Screen height of node `id`'s title text.
fn title_height(h: &Harness<EditorApp>, id: &str, kind: &str) -> f32 {
    let graph = h
        .get_all_by_label(&format!("{id} ({kind})"))
        .map(|n| n.rect())
        .min_by(|a, b| a.left().total_cmp(&b.left()))
        .unwrap();
    graph.height() * h.state().canvas_transform.scaling
}

fn presets() -> Vec<PathBuf> {
    let mut all: Vec<PathBuf> = std::fs::read_dir(repo("graphs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    all.sort();
    all
}

/// Pairs of overlapping node rectangles (screen space), all nodes being on screen.
fn overlaps(h: &Harness<EditorApp>) -> Vec<String> {
    let doc = h.state().state.doc();
    let rects: Vec<(String, egui::Rect)> = doc
        .nodes
        .iter()
        .map(|n| {
            let r = h
                .state()
                .node_screen_rect(&n.id)
                .unwrap_or_else(|| panic!("{} is not drawn", n.id));
            (n.id.clone(), r.shrink(1.0))
        })
        .collect();
    let mut out = Vec::new();
    for (i, (a, ra)) in rects.iter().enumerate() {
        for (b, rb) in &rects[i + 1..] {
            if ra.intersects(*rb) {
                out.push(format!("{a} overlaps {b}"));
            }
        }
    }
    out
}

/// A harness big enough that any preset fits at zoom 1 (so every node is drawn).
fn big_harness(app: EditorApp) -> Harness<'static, EditorApp> {
    Harness::builder()
        .with_size([6000.0, 3000.0])
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app)
}

/// Screen height of the text naming node `id`: its id in a box when zoomed out, else its title.
fn name_height(h: &Harness<EditorApp>, id: &str, kind: &str) -> f32 {
    match h.state().lod_text_px.get(id) {
        Some(&px) => px,
        None => title_height(h, id, kind),
    }
}

/// `F` in a window of `size`, after zooming in on a corner: every node of the preset is on the
/// canvas, named in text at least 11 px high.
fn frame_all_shows_everything(rel: &str, dir: &Path, size: [f32; 2]) -> f32 {
    let (app, _) = open_copy(rel, dir);
    let mut h = Harness::builder()
        .with_size(size)
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app);
    h.run();
    let corner = h.state().canvas_rect.left_top() + egui::vec2(20.0, 20.0);
    for _ in 0..6 {
        super::first_hour::wheel(&mut h, corner, 3.0, Modifiers::NONE);
    }
    h.key_press(Key::F);
    h.run();
    let canvas = h.state().canvas_rect;
    let doc = h.state().state.doc().clone();
    for (id, _) in hatchery_editor::groups::shown_nodes(&doc, None) {
        let r = h
            .state()
            .node_screen_rect(&id)
            .unwrap_or_else(|| panic!("{rel}: {id} is not drawn"));
        assert!(
            canvas.contains_rect(r),
            "{rel} in {size:?}: {id} at {r:?} is not inside the canvas {canvas:?}"
        );
        let kind = doc.node(&id).map_or("Group", |n| n.kind.as_str());
        let px = name_height(&h, &id, kind);
        // 0: a box too small for legible text has none (its name shows on hover).
        assert!(
            px >= 11.0 || px == 0.0,
            "{rel}: {id} is named in text {px:.1} px high"
        );
    }
    // A box without text names its node on hover.
    let bare = h.state().lod_text_px.iter().find(|(_, px)| **px == 0.0);
    if let Some((id, _)) = bare.map(|(id, px)| (id.clone(), *px)) {
        let kind = doc.node(&id).map_or("Group", |n| n.kind.as_str());
        let name = format!("{id} ({kind})");
        let before = h.get_all_by_label(&name).count();
        let at = h.state().node_screen_rect(&id).unwrap().center();
        h.event(egui::Event::PointerMoved(at));
        h.run_steps(40);
        assert_eq!(
            h.get_all_by_label(&name).count(),
            before + 1,
            "{rel}: hovering {id} shows its name"
        );
    }
    h.state().canvas_transform.scaling
}

#[test]
fn frame_all_shows_the_whole_graph_legibly_and_presets_do_not_overlap() {
    let dir = tempfile::tempdir().unwrap();
    for preset in presets() {
        let rel = format!("graphs/{}", preset.file_name().unwrap().to_string_lossy());
        // In the tests' usual window, then in the editor's default window (1400 x 900, where the
        // big presets are drawn as boxes).
        frame_all_shows_everything(&rel, dir.path(), [2200.0, 1000.0]);
        frame_all_shows_everything(&rel, dir.path(), [1400.0, 900.0]);
        // Every node of every preset apart from every other.
        let (app, _) = open_copy(&rel, dir.path());
        let mut h = big_harness(app);
        h.run();
        let found = overlaps(&h);
        assert!(found.is_empty(), "{rel}: {found:?}");
    }
    // The biggest preset is zoomed out far enough to be drawn as boxes, and all of it shows.
    let scaling = frame_all_shows_everything("graphs/default.ron", dir.path(), [1400.0, 900.0]);
    assert!(
        hatchery_editor::panels::canvas_zoom::boxes(scaling),
        "default.ron framed at zoom {scaling}"
    );
}

#[test]
fn arrange_from_the_view_menu_removes_overlaps_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    // Pile every node onto one spot (a precondition, not the behaviour under test).
    let ids: Vec<String> = app.state.doc().nodes.iter().map(|n| n.id.clone()).collect();
    for id in &ids {
        app.state.move_node(id, EditorPos { x: 10.0, y: 10.0 });
    }
    app.state.end_group();
    let mut h = big_harness(app);
    h.run();
    assert!(!overlaps(&h).is_empty(), "the pile overlaps");
    let before = h.state().state.doc().clone();
    h.get_by_label("View").click();
    h.run();
    h.get_by_label("Arrange").click();
    h.run();
    h.run();
    assert!(overlaps(&h).is_empty(), "{:?}", overlaps(&h));
    // Sources left of what they feed.
    let x = |h: &Harness<EditorApp>, id: &str| {
        h.state()
            .state
            .doc()
            .nodes
            .iter()
            .find(|n| n.id == id)
            .unwrap()
            .editor
            .unwrap()
            .x
    };
    assert!(x(&h, "shells") < x(&h, "surface") && x(&h, "surface") < x(&h, "shaded"));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &before, "one undo step");
}

/// Arranges every preset in graphs/ and saves it there (run on purpose:
/// `cargo test --release -p hatchery-editor --test editor_ui -- --ignored arrange_every_preset`).
#[test]
#[ignore]
fn arrange_every_preset() {
    for preset in presets() {
        let mut state = EditorState::new();
        state.scratch_dir = std::env::temp_dir();
        state.open(&preset).unwrap();
        let mut app = EditorApp::new(state);
        app.preview_enabled = false;
        let mut h = big_harness(app);
        h.run();
        h.state_mut().arrange();
        h.run();
        h.state_mut().state.save().unwrap();
        eprintln!("arranged {}", preset.display());
    }
}

/// Output labels on node `id` (screen rects), the rightmost label of each output's text.
fn output_labels(h: &Harness<EditorApp>, id: &str) -> Vec<(String, egui::Rect)> {
    let t = h.state().canvas_transform;
    let node = h.state().node_screen_rect(id).unwrap();
    let state = &h.state().state;
    let ports = hatchery_editor::groups::view_ports(state.doc(), &state.registry, id, true);
    ports
        .iter()
        .map(|p| {
            let text = hatchery_editor::groups::port_label(id, p);
            let r = h
                .get_all_by_label(&text)
                .map(|n| egui::Rect::from_min_max(t * n.rect().min, t * n.rect().max))
                .filter(|r| node.contains(r.center()))
                .max_by(|a, b| a.right().total_cmp(&b.right()))
                .unwrap_or_else(|| panic!("no output label {text} on {id}"));
            (text, r)
        })
        .collect()
}

#[test]
fn output_labels_end_before_their_pins_on_nodes_and_groups() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/default.ron", dir.path());
    let mut h = big_harness(app);
    h.run();
    // A group exposing `piston_surface.mesh`, made by clicks and Ctrl+G.
    super::select_by_click(&mut h, "pistons");
    let at = super::selection::title_pos(&h, "piston_surface");
    super::selection::click_mod(&mut h, at, Modifiers::SHIFT);
    h.key_press_modifiers(Modifiers::COMMAND, Key::G);
    h.run();
    h.run();
    let scaling = h.state().canvas_transform.scaling;
    assert!(
        !hatchery_editor::panels::canvas_zoom::boxes(scaling),
        "zoom {scaling}"
    );
    let doc = h.state().state.doc().clone();
    let mut checked = 0;
    for (id, _) in hatchery_editor::groups::shown_nodes(&doc, None) {
        let node = h.state().node_screen_rect(&id).unwrap();
        // The pin: 10.8 points (egui-snarl's, 0.6 of the interact height) inside the frame's
        // 6-point margin, at the canvas's zoom.
        let pin_left = node.right() - (6.0 + 10.8) * scaling;
        for (text, r) in output_labels(&h, &id) {
            assert!(
                r.right() <= pin_left + 1.0,
                "{id}: `{text}` ends at {}, under its pin (from {pin_left})",
                r.right()
            );
            checked += 1;
        }
    }
    assert!(checked > 20, "{checked} labels");
    h.get_by_label("piston_surface.mesh");
}
