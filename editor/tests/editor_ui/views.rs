//! What the editor keeps (issue 24): the canvas view of each graph and of each group inside it,
//! within a run and in the next one, and the widths of the picture and Inspector panels.

use super::first_hour::wheel;
use super::selection::{click_mod, empty_canvas_point, title_pos};
use super::*;
use egui::emath::TSTransform;

fn view(h: &Harness<EditorApp>) -> TSTransform {
    h.state().canvas_transform
}

fn same(a: TSTransform, b: TSTransform) -> bool {
    (a.scaling - b.scaling).abs() < 1e-3 * a.scaling
        && (a.translation - b.translation).length() < 1.0
}

/// Zooms out two notches and pans by dragging empty canvas: a view no *Frame all* gives.
fn move_view(h: &mut Harness<EditorApp>) -> TSTransform {
    let at = empty_canvas_point(h) + egui::vec2(5.0, 5.0);
    let before = view(h);
    wheel(h, at, -2.0, Modifiers::NONE);
    let at = empty_canvas_point(h) + egui::vec2(5.0, 5.0);
    drag(h, at, at + egui::vec2(70.0, 45.0));
    let after = view(h);
    assert!(
        !same(before, after),
        "the wheel and the drag moved the view"
    );
    after
}

/// An editor keeping its settings in `settings`, with `graph` open.
fn editor(graph: &Path, settings: &Path, scratch: &Path) -> Harness<'static, EditorApp> {
    let mut state = EditorState::new();
    state.scratch_dir = scratch.to_path_buf();
    state.open(graph).unwrap();
    let mut app = EditorApp::new(state).with_settings_file(settings.to_path_buf());
    app.preview_enabled = false;
    let mut h = harness(app);
    h.run();
    h
}

#[test]
fn leaving_a_group_restores_the_view_outside_and_entering_it_again_restores_its_view() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // Group two nodes by clicks and Ctrl+G (the group stays selected).
    select_by_click(&mut h, "shells");
    let at = title_pos(&h, "surface");
    click_mod(&mut h, at, Modifiers::SHIFT);
    h.key_press_modifiers(Modifiers::COMMAND, Key::G);
    h.run();
    let outside = move_view(&mut h);

    h.key_press(Key::Tab);
    h.run();
    assert_eq!(h.state().state.level(), Some("group_1"));
    assert!(
        !same(view(&h), outside),
        "a group first shows all its members"
    );
    let inside = move_view(&mut h);

    h.key_press(Key::Tab);
    h.run();
    assert_eq!(h.state().state.level(), None);
    assert!(
        same(view(&h), outside),
        "left the group: {:?}, outside it was {outside:?}",
        view(&h)
    );
    h.key_press(Key::Tab);
    h.run();
    assert_eq!(h.state().state.level(), Some("group_1"));
    assert!(
        same(view(&h), inside),
        "entered again: {:?}, it was {inside:?}",
        view(&h)
    );
}

#[test]
fn reopening_a_graph_restores_its_view_in_the_same_run_and_the_next() {
    let dir = tempfile::tempdir().unwrap();
    let settings = dir.path().join("config").join("editor.ron");
    let (_, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let (_, other) = open_copy("graphs/volume_styles.ron", dir.path());
    let text = std::fs::read_to_string(&path).unwrap();
    let mut h = editor(&path, &settings, dir.path());
    let mine = move_view(&mut h);

    // Another graph dropped on the canvas opens framed; dropping this one again shows its view.
    let at = empty_canvas_point(&h);
    drop_file(&mut h, &other, at);
    h.run();
    assert_eq!(h.state().state.path(), Some(other.as_path()));
    assert!(!same(view(&h), mine));
    drop_file(&mut h, &path, at);
    h.run();
    assert_eq!(h.state().state.path(), Some(path.as_path()));
    assert!(
        same(view(&h), mine),
        "reopened: {:?}, it was {mine:?}",
        view(&h)
    );

    // Closing the window keeps it; the next editor opening the file shows it.
    close_window(&mut h);
    assert!(settings.is_file(), "closing wrote {}", settings.display());
    let h = editor(&path, &settings, dir.path());
    assert!(
        same(view(&h), mine),
        "next run: {:?}, it was {mine:?}",
        view(&h)
    );
    // The view is the user's: the graph file is untouched.
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
}

#[test]
fn panel_widths_are_kept_between_runs_and_selecting_does_not_move_them() {
    let dir = tempfile::tempdir().unwrap();
    let settings = dir.path().join("config").join("editor.ron");
    let (_, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = editor(&path, &settings, dir.path());
    let width = |h: &Harness<EditorApp>, id: &str| h.state().panel_rects[id].width();
    let (picture, inspector) = (width(&h, "viewport"), width(&h, "inspector"));
    // Drag the canvas/picture divider 150 points left, the Inspector's edge 60 left.
    let r = h.state().panel_rects["viewport"];
    let edge = egui::pos2(r.left(), r.center().y);
    drag(&mut h, edge, edge - egui::vec2(150.0, 0.0));
    let r = h.state().panel_rects["inspector"];
    let edge = egui::pos2(r.left(), r.center().y);
    drag(&mut h, edge, edge - egui::vec2(60.0, 0.0));
    let dragged = (width(&h, "viewport"), width(&h, "inspector"));
    assert!(
        (dragged.0 - picture - 150.0).abs() < 3.0 && (dragged.1 - inspector - 60.0).abs() < 3.0,
        "dragged from {:?} to {dragged:?}",
        (picture, inspector)
    );
    // A click on a node changes neither.
    super::select_by_click(&mut h, "camera");
    assert_eq!((width(&h, "viewport"), width(&h, "inspector")), dragged);

    close_window(&mut h);
    let h = editor(&path, &settings, dir.path());
    let next = (width(&h, "viewport"), width(&h, "inspector"));
    assert!(
        (next.0 - dragged.0).abs() < 1.0 && (next.1 - dragged.1).abs() < 1.0,
        "next run: {next:?}, they were {dragged:?}"
    );
}
