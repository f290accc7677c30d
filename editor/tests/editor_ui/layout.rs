//! A legible canvas: *Frame all* never zooms titles below 11 px, *Arrange* (clicked in the View
//! menu) lays a graph out without overlaps as one undo step, and every preset is arranged.

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

#[test]
fn frame_all_keeps_titles_legible_and_presets_do_not_overlap() {
    let dir = tempfile::tempdir().unwrap();
    for preset in presets() {
        let rel = format!("graphs/{}", preset.file_name().unwrap().to_string_lossy());
        // In the editor's usual window: titles at least 11 px after framing.
        let (app, _) = open_copy(&rel, dir.path());
        let mut h = harness(app);
        h.run();
        h.key_press(Key::F);
        h.run();
        let doc = h.state().state.doc().clone();
        for n in &doc.nodes {
            if h.state().node_screen_rect(&n.id).is_none() {
                continue; // scrolled out of view: titles of drawn nodes are what is checked
            }
            let px = title_height(&h, &n.id, &n.kind);
            assert!(px >= 11.0, "{rel}: title of {} is {px:.1} px high", n.id);
        }
        // Every node of every preset apart from every other.
        let (app, _) = open_copy(&rel, dir.path());
        let mut h = big_harness(app);
        h.run();
        let found = overlaps(&h);
        assert!(found.is_empty(), "{rel}: {found:?}");
    }
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
