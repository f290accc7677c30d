//! Small findings of issue 24 ("the editor's first hour"), each driven as a user meets it.

use super::*;

fn closes(h: &mut Harness<EditorApp>) -> bool {
    h.step();
    h.step();
    h.output().viewport_output[&egui::ViewportId::ROOT]
        .commands
        .contains(&egui::ViewportCommand::Close)
}

/// An orbit by dragging in the viewport (the edit a user makes first).
fn orbit(h: &mut Harness<EditorApp>) {
    let centre = h.state().viewport_rect.center();
    drag(h, centre, centre + egui::vec2(-30.0, 25.0));
}

#[test]
fn the_quit_prompt_saves_or_discards_and_discarding_drops_the_autosave() {
    // Save: the file gets the edit, then the window closes.
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    orbit(&mut h);
    assert!(close_window(&mut h).contains(&egui::ViewportCommand::CancelClose));
    h.run();
    h.get_by_label("Save").click();
    assert!(closes(&mut h), "closed after saving");
    let saved = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        saved,
        h.state().state.doc().to_ron_string(),
        "the edit was saved"
    );

    // Discard: the window closes and no autosave offers the discarded edit again.
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let before = std::fs::read_to_string(&path).unwrap();
    let mut h = harness(app);
    h.run();
    orbit(&mut h);
    let later = std::time::Instant::now() + std::time::Duration::from_secs(5);
    assert!(h.state_mut().state.autosave_at(later), "an autosave exists");
    let recovery = h.state().state.recovery_path();
    assert!(recovery.is_file());
    close_window(&mut h);
    h.run();
    h.get_by_label("Discard changes").click();
    assert!(closes(&mut h));
    assert!(
        !recovery.exists(),
        "{} stayed after Discard",
        recovery.display()
    );
    assert_eq!(std::fs::read_to_string(&path).unwrap(), before);
}

#[test]
fn an_orbit_stores_round_angles() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    for _ in 0..3 {
        orbit(&mut h);
    }
    let camera = h.state().state.doc().node("camera").unwrap().clone();
    for name in ["azimuth", "elevation"] {
        let Some(ron::Value::Number(n)) = camera.params.get(name) else {
            panic!("{name} not set by the orbit");
        };
        let v = n.into_f64();
        assert_eq!((v * 1000.0).round() / 1000.0, v, "{name} = {v}");
        assert!(format!("{v}").len() <= 8, "{name} written as {v}");
    }
}

#[test]
fn an_angle_parameter_drags_finely() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let halftone = app
        .state
        .add_node("Halftone", EditorPos { x: 300.0, y: 400.0 })
        .unwrap();
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, &halftone);
    let theta = |h: &Harness<EditorApp>| match h
        .state()
        .state
        .doc()
        .node(&halftone)
        .unwrap()
        .params
        .get("theta")
    {
        Some(ron::Value::Number(n)) => n.into_f64(),
        _ => 0.0,
    };
    let before = theta(&h);
    // The widget right of the Inspector's `theta` label, dragged 36 points to the right.
    let label = h
        .get_all_by_label("theta")
        .map(|n| n.rect())
        .max_by(|a, b| a.left().total_cmp(&b.left()))
        .unwrap();
    let widget = h
        .get_all_by_role(egui::accesskit::Role::SpinButton)
        .map(|n| n.rect())
        .find(|r| (r.center().y - label.center().y).abs() < 8.0 && r.left() > label.right())
        .expect("an angle field beside theta");
    let from = widget.center();
    drag(&mut h, from, from + egui::vec2(36.0, 0.0));
    let change = theta(&h) - before;
    // About a degree a point at most (the 720° slider moved it ~290° for this drag).
    assert!(
        change > 5.0 && change <= 40.0,
        "36 points moved theta by {change}°"
    );
}

/// Mouse-wheel notches at `at` (negative: towards the user, zooming out).
pub(super) fn wheel(
    h: &mut Harness<EditorApp>,
    at: egui::Pos2,
    notches: f32,
    modifiers: Modifiers,
) {
    h.event(egui::Event::PointerMoved(at));
    h.event_modifiers(
        egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Line,
            delta: egui::vec2(0.0, notches),
            modifiers,
            phase: egui::TouchPhase::Move,
        },
        modifiers,
    );
    h.run();
}

#[test]
fn the_wheel_zooms_the_canvas_about_the_pointer_and_shift_wheel_scrolls() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let at = super::selection::empty_canvas_point(&h) + egui::vec2(40.0, 40.0);
    let before = h.state().canvas_transform;
    let under = before.inverse() * at;
    for _ in 0..4 {
        wheel(&mut h, at, -1.0, Modifiers::NONE);
    }
    let after = h.state().canvas_transform;
    assert!(
        after.scaling < before.scaling * 0.95,
        "four notches down zoomed out: {} -> {}",
        before.scaling,
        after.scaling
    );
    let moved = (after * under).distance(at);
    assert!(
        moved < 1.0,
        "the graph point under the pointer moved {moved} points"
    );
    // Every node is still on the canvas.
    let canvas = h.state().canvas_rect;
    for id in ["camera", "shells", "surface", "shaded", "save"] {
        let r = h.state().node_screen_rect(id).unwrap();
        assert!(canvas.intersects(r), "{id} left the canvas");
    }
    // Shift+wheel scrolls: the scale stays.
    wheel(&mut h, at, -1.0, Modifiers::SHIFT);
    assert!((h.state().canvas_transform.scaling - after.scaling).abs() < 1e-6);
}

#[test]
fn selecting_a_node_with_a_wide_editor_does_not_move_the_panels() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/two_level_frog.ron", dir.path());
    // The copy's data paths point at the shared frog by absolute path.
    let frog = repo("../shared/data/volumes/frog_tissues.vti")
        .canonicalize()
        .unwrap();
    let names = repo("../shared/data/volumes/frog_tissues_names.csv")
        .canonicalize()
        .unwrap();
    hatchery_editor::data_panel::set_input(&mut app.state, "labels", &frog).unwrap();
    hatchery_editor::data_panel::set_input(&mut app.state, "names", &names).unwrap();
    app.preview_enabled = true;
    let mut h = harness(app);
    wait_for_render(&mut h);
    let (viewport, canvas) = (h.state().viewport_rect, h.state().canvas_rect);
    select_by_click(&mut h, "objects");
    wait_for_render(&mut h);
    // The object table lists the organs by name.
    h.get_by_label_contains("liver");
    h.get_by_label_contains("skeleton");
    let (v, c) = (h.state().viewport_rect, h.state().canvas_rect);
    assert!(
        (v.width() - viewport.width()).abs() < 1.0 && (c.right() - canvas.right()).abs() < 1.0,
        "the picture went from {viewport:?} to {v:?}, the canvas from {canvas:?} to {c:?}"
    );
}

#[test]
fn undo_and_redo_say_what_they_undid_and_ctrl_q_quits_asking_first() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    orbit(&mut h);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(
        h.state().state.status,
        "Undid camera.azimuth, camera.elevation"
    );
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run();
    assert_eq!(
        h.state().state.status,
        "Redid camera.azimuth, camera.elevation"
    );
    // A node added from the palette, undone.
    super::right_click_at(&h, super::selection::empty_canvas_point(&h));
    h.run();
    h.event(egui::Event::Text("fill".into()));
    h.key_press(Key::Enter);
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.status, "Undid adding fill_1");

    // Ctrl+Q with unsaved changes asks (Save / Discard / Cancel) ...
    h.key_press_modifiers(Modifiers::COMMAND, Key::Q);
    h.run();
    assert_eq!(
        h.state().pending(),
        Some(&hatchery_editor::app::Pending::Quit)
    );
    h.get_by_label("Save");
    h.get_by_label("Cancel").click();
    h.run();
    // ... and without them closes the window.
    h.state_mut().state.save().unwrap();
    h.key_press_modifiers(Modifiers::COMMAND, Key::Q);
    assert!(closes(&mut h), "Ctrl+Q closed the window");
}

#[test]
fn a_stale_picture_is_dimmed_while_it_renders_and_another_graph_does_not_show_the_old_one() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.preview_enabled = true;
    let mut h = harness(app);
    wait_for_render(&mut h);
    assert!(h.state().preview.viewport.is_some() && !h.state().picture_stale);
    // An edit: the old picture stays up, dimmed, until the new one arrives.
    orbit(&mut h);
    h.step();
    assert!(h.state().preview.is_busy());
    assert!(h.state().picture_stale, "dimmed while rendering");
    wait_for_render(&mut h);
    assert!(!h.state().picture_stale);
    // Opening another graph drops the old picture at once.
    let other = dir.path().join("volume_styles.ron");
    std::fs::copy(repo("graphs/volume_styles.ron"), &other).unwrap();
    h.state_mut().state.save().unwrap();
    h.state_mut().open(&other);
    assert!(
        h.state().preview.viewport.is_none(),
        "the previous graph's picture is gone"
    );
    wait_for_render(&mut h);
    assert!(h.state().preview.viewport.is_some());
}

#[test]
fn an_error_on_a_new_node_does_not_stretch_it() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // Added from the palette, unconnected: it says its input is missing.
    super::right_click_at(&h, super::selection::empty_canvas_point(&h));
    h.run();
    h.event(egui::Event::Text("MarchingCubes".into()));
    h.key_press(Key::Enter);
    h.run();
    h.run();
    let id = "marching_cubes_1";
    let error = h.state().state.node_error(id).expect("an error").to_owned();
    assert!(error.contains("not connected"), "{error}");
    h.get_by_label_contains("⚠");
    let width =
        h.state().node_screen_rect(id).unwrap().width() / h.state().canvas_transform.scaling;
    // Connected, it has no message: the message made it no wider than that.
    h.state_mut()
        .state
        .connect(("shells", "volume"), (id, "volume"))
        .unwrap();
    for _ in 0..3 {
        h.run();
    }
    assert!(h.state().state.node_error(id).is_none());
    let plain =
        h.state().node_screen_rect(id).unwrap().width() / h.state().canvas_transform.scaling;
    assert!(
        width <= plain + 10.0,
        "the node is {width} points wide with the message ({error}), {plain} without"
    );
}

#[test]
fn a_refused_wire_says_why_inside_the_canvas_until_the_next_click() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // camera's output dropped on `save`'s image input, the node nearest the canvas's right edge.
    let t = h.state().canvas_transform;
    let camera_out = super::port_label(&h, "camera", "camera");
    let image_in = super::port_label(&h, "save", "image");
    let from = t * egui::pos2(camera_out.right() + 14.0, camera_out.center().y);
    let to = t * egui::pos2(image_in.left() - 12.0, image_in.center().y);
    drag(&mut h, from, to);
    let canvas = h.state().canvas_rect;
    let popup = |h: &Harness<EditorApp>| h.query_by_label_contains("⛔").map(|n| n.rect());
    let r = popup(&h).expect("the reason is shown");
    assert!(
        canvas.right() - to.x < 320.0,
        "dropped {} points from the canvas's edge",
        canvas.right() - to.x
    );
    assert!(
        canvas.contains_rect(r),
        "{r:?} is not inside the canvas {canvas:?}"
    );
    // Still up after three seconds of reading (the harness steps a quarter second) ...
    h.run_steps(12);
    assert!(popup(&h).is_some(), "gone after three seconds");
    // ... and gone with the next click.
    let empty = super::selection::empty_canvas_point(&h);
    super::selection::click_mod(&mut h, empty, Modifiers::NONE);
    assert!(popup(&h).is_none(), "still up after a click");
    // Without a click it goes after a while.
    drag(&mut h, from, to);
    assert!(popup(&h).is_some());
    h.run_steps(40);
    assert!(popup(&h).is_none(), "still up after ten seconds");
}
