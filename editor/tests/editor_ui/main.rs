//! The editor driven through its real UI with egui_kittest (and through `EditorState` where
//! driving the snarl canvas headlessly is impractical: adding nodes from the right-click menu
//! and dragging wires between pins need exact pin positions).

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use hatchery_editor::{EditorApp, EditorState};
use hatchery_graph::{EditorPos, GraphDocument, ParamValue, SchemaLookup};
use std::path::{Path, PathBuf};

mod add_menu;
mod custom_shader;
mod data_panel;
mod export;
mod first_hour;
mod fused;
mod layout;
mod objects;
mod organise;
mod paint;
mod picture;
mod progress;
mod selection;
mod views;
use selection::select_by_click;

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

/// Copies a graph into a temp dir (so autosaves never land in the repository) and opens it.
fn open_copy(path: &str, dir: &Path) -> (EditorApp, PathBuf) {
    let target = dir.join(Path::new(path).file_name().unwrap());
    std::fs::copy(repo(path), &target).unwrap();
    let mut state = EditorState::new();
    state.scratch_dir = dir.to_path_buf();
    state.open(&target).unwrap();
    let mut app = EditorApp::new(state);
    app.preview_enabled = false;
    (app, target)
}

/// Steps the UI until the render thread's answer to the latest request is shown. Starts with
/// two frames: the canvas is drawn after the viewport, so a change made on the canvas (a pin)
/// is asked for in the frame after.
fn wait_for_render(h: &mut Harness<EditorApp>) {
    let start = std::time::Instant::now();
    h.step();
    h.step();
    while h.state().preview.is_busy() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(300),
            "no picture after 300 s"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    h.step();
}

/// A window wide enough that the canvas beside the picture panel shows a preset's nodes at a
/// legible zoom.
fn harness(app: EditorApp) -> Harness<'static, EditorApp> {
    Harness::builder()
        .with_size([2200.0, 1000.0])
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app)
}

#[test]
fn open_add_connect_refuse_edit_undo_redo_save_and_reload() {
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // The canvas shows every node with id and kind.
    h.get_by_label("shaded (ShadedSurface)");
    h.get_by_label("surface (MarchingCubes)");
    assert!(h.state().state.errors().is_empty());
    assert!(!h.state().state.is_dirty());

    // Add (through the state API: the canvas menu needs a right-click at an exact spot).
    let gbuffer = h
        .state_mut()
        .state
        .add_node("GBuffer", EditorPos { x: 500.0, y: 400.0 })
        .unwrap();
    assert_eq!(gbuffer, "g_buffer_1");
    let silhouette = h
        .state_mut()
        .state
        .add_node("Silhouette", EditorPos { x: 700.0, y: 400.0 })
        .unwrap();
    h.run();
    h.get_by_label("g_buffer_1 (GBuffer)");
    // Added nodes are selected: canvas title + inspector heading.
    assert_eq!(h.get_all_by_label("silhouette_1 (Silhouette)").count(), 2);
    // Unconnected required inputs are errors on the new nodes, the rest is fine.
    assert!(h.state().state.node_error("g_buffer_1").is_some());
    assert!(h.state().state.node_error("shaded").is_none());
    assert!(h.state().state.title().starts_with('*'), "dirty marker");

    // Connect compatible pairs.
    let s = &mut h.state_mut().state;
    s.connect(("camera", "camera"), (&gbuffer, "camera"))
        .unwrap();
    s.connect(("surface", "mesh"), (&gbuffer, "mesh")).unwrap();
    s.connect((&gbuffer, "gbuffer"), (&silhouette, "gbuffer"))
        .unwrap();
    assert!(s.errors().is_empty(), "{:?}", s.errors());
    // Refuse an incompatible one, with the reason in the status line.
    let err = s
        .connect(("shaded", "image"), (&gbuffer, "camera"))
        .unwrap_err();
    assert!(err.contains("type mismatch"), "{err}");
    h.run();
    h.get_by_label_contains("type mismatch");
    let edges = h.state().state.doc().edges.len();
    assert_eq!(edges, 8);

    // Change a parameter through the inspector: click the silhouette, untick `use_depth`.
    select_by_click(&mut h, &silhouette);
    // The title on the canvas and the inspector's heading.
    assert_eq!(h.get_all_by_label("silhouette_1 (Silhouette)").count(), 2);
    let before = h.state().state.doc().clone();
    h.get_all_by_role(Role::CheckBox).next().unwrap().click();
    h.run();
    let raw = |h: &Harness<EditorApp>| {
        h.state()
            .state
            .doc()
            .nodes
            .iter()
            .find(|n| n.id == silhouette)
            .unwrap()
            .params
            .get("use_depth")
            .cloned()
    };
    assert_eq!(raw(&h), Some(ron::Value::Bool(false)));
    let after = h.state().state.doc().clone();

    // Undo / redo with the keyboard.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &before);
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &after);

    // Save as and load back equal.
    let saved = dir.path().join("saved.ron");
    h.state_mut().state.save_as(&saved).unwrap();
    h.run();
    assert!(!h.state().state.is_dirty());
    assert!(!h.state().state.title().starts_with('*'));
    let (loaded, _) = GraphDocument::load(&saved).unwrap();
    assert_eq!(
        loaded.to_ron_string(),
        h.state().state.doc().to_ron_string()
    );
    // The original file is untouched by save-as.
    let (original, _) = GraphDocument::load(&path).unwrap();
    assert_eq!(original.nodes.len(), 6);
}

#[test]
fn a_parameter_drag_is_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let s = &mut app.state;
    let original = s.doc().clone();
    for iso in [0.1, 0.2, 0.3] {
        s.set_param("surface", "iso", ParamValue::Float(iso), true)
            .unwrap();
    }
    s.end_group();
    s.set_param("surface", "iso", ParamValue::Float(0.4), false)
        .unwrap();
    // Out of range: refused, nothing pushed.
    assert!(
        s.set_param("camera", "elevation", ParamValue::Float(1.0e9), false)
            .is_err()
    );
    assert!(s.undo());
    let iso = |s: &EditorState| {
        s.doc()
            .nodes
            .iter()
            .find(|n| n.id == "surface")
            .unwrap()
            .params["iso"]
            .clone()
    };
    assert_eq!(iso(s), ron::Value::Number(ron::Number::new(0.3)));
    assert!(s.undo());
    assert_eq!(s.doc(), &original);
    assert!(!s.undo());
    assert!(s.redo() && s.redo());
    assert_eq!(iso(s), ron::Value::Number(ron::Number::new(0.4)));
}

/// The undo history is bounded: past UNDO_LIMIT steps the oldest go, the newest all undo.
#[test]
fn undo_keeps_the_last_undo_limit_steps() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let s = &mut app.state;
    let limit = hatchery_editor::state::UNDO_LIMIT;
    let extra = 20;
    let mut versions = vec![s.doc().clone()];
    for step in 0..limit + extra {
        let iso = -0.5 + step as f64 / (limit + extra) as f64;
        s.set_param("surface", "iso", ParamValue::Float(iso), false)
            .unwrap();
        versions.push(s.doc().clone());
    }
    let mut undone = 0;
    while s.undo() {
        undone += 1;
        assert_eq!(s.doc(), &versions[versions.len() - 1 - undone]);
    }
    assert_eq!(undone, limit);
    // The oldest kept version, not the file as opened (that step was dropped).
    assert_eq!(s.doc(), &versions[extra]);
    assert_ne!(s.doc(), &versions[0]);
    // Redo goes all the way forward again.
    let mut redone = 0;
    while s.redo() {
        redone += 1;
    }
    assert_eq!(redone, limit);
    assert_eq!(s.doc(), versions.last().unwrap());
}

#[test]
fn a_graph_with_an_error_opens_and_shows_it_on_the_node() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("tests/fixtures/bad/missing_input.ron", dir.path());
    let message = app
        .state
        .node_error("gbuffer")
        .expect("error on gbuffer")
        .to_owned();
    assert!(message.contains("mesh"), "{message}");
    assert!(app.state.node_error("camera").is_none());
    let mut h = harness(app);
    h.run();
    h.get_by_label("gbuffer (GBuffer)");
    h.get_by_label_contains("⚠");
    // Still editable: fixing it clears the error.
    let s = &mut h.state_mut().state;
    let volume = s
        .add_node("ProceduralVolume", EditorPos { x: 0.0, y: 0.0 })
        .unwrap();
    let mc = s
        .add_node("MarchingCubes", EditorPos { x: 200.0, y: 0.0 })
        .unwrap();
    s.connect((&volume, "volume"), (&mc, "volume")).unwrap();
    s.connect((&mc, "mesh"), ("gbuffer", "mesh")).unwrap();
    assert!(s.errors().is_empty(), "{:?}", s.errors());
    h.run();
    assert!(h.query_by_label_contains("⚠").is_none());
}

#[test]
fn unreadable_files_are_refused_without_panicking() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.open(&repo("tests/fixtures/bad/syntax_error.ron"));
    assert!(!app.state.status.is_empty());
    assert_eq!(app.state.doc().nodes.len(), 6, "the open graph stays");
    app.open(&dir.path().join("missing.ron"));
    assert!(
        app.state.status.contains("cannot read"),
        "{}",
        app.state.status
    );
}

#[test]
fn autosave_recovers_an_unsaved_edit() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let start = std::time::Instant::now();
    let s = &mut app.state;
    assert!(
        !s.autosave_at(start + std::time::Duration::from_secs(5)),
        "clean: nothing to save"
    );
    s.set_param("camera", "azimuth", ParamValue::Float(75.0), false)
        .unwrap();
    assert!(!s.autosave_at(start), "less than 2 s after opening");
    assert!(s.autosave_at(start + std::time::Duration::from_secs(3)));
    assert_eq!(
        s.recovery_path(),
        dir.path().join("shaded_surface.ron.recovery")
    );
    let edited = s.doc().clone();
    drop(app); // quit without saving

    let mut state = EditorState::new();
    state.open(&path).unwrap();
    assert!(state.has_recovery());
    assert_ne!(state.doc().to_ron_string(), edited.to_ron_string());
    let mut h = harness(EditorApp::new(state));
    h.state_mut().preview_enabled = false;
    h.run();
    h.get_by_label("Restore").click();
    h.run();
    assert_eq!(
        h.state().state.doc().to_ron_string(),
        edited.to_ron_string()
    );
    assert!(h.state().state.is_dirty());
    // Saving removes the recovery file.
    h.state_mut().state.save().unwrap();
    assert!(!dir.path().join("shaded_surface.ron.recovery").exists());
}

#[test]
fn snapshot_of_the_editor_with_a_preset() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.preview_enabled = true;
    // Room for the thumbnail pinned below.
    app.state
        .move_node("save", EditorPos { x: 900.0, y: 120.0 });
    // The window's device is opened as the editor opens it, and the render thread shares it
    // (forced: on a CPU adapter the editor would otherwise give the thread its own device), so
    // the viewport is a wgpu texture registered with egui-wgpu.
    let mut setup = eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = std::sync::Arc::new(hatchery_gpu::GpuContext::device_descriptor);
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu_setup(eframe::egui_wgpu::WgpuSetup::CreateNew(setup))
        .build_eframe(move |cc| {
            let rs = cc
                .wgpu_render_state
                .clone()
                .expect("kittest gives a wgpu render state");
            app.preview.set_render_state(rs, true);
            app
        });
    wait_for_render(&mut h);
    assert!(h.state().preview.shares_device());
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let shown = h
        .state()
        .preview
        .viewport
        .as_ref()
        .expect("the viewport rendered");
    assert!(shown.is_native(), "shown without a copy");
    // A pinned thumbnail and the node times, as the screenshot in docs/editor.md shows them.
    let port = ("shaded".to_string(), "image".to_string());
    h.state_mut().preview.pins.insert(port.clone());
    h.state_mut().preview.show_times = true;
    h.state_mut()
        .state
        .set_param("camera", "azimuth", ParamValue::Float(90.0), false)
        .unwrap();
    wait_for_render(&mut h);
    assert!(h.state().preview.thumbnails[&port].is_native());
    h.run_steps(3);
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let shot = h.render().expect("kittest wgpu render");
    let out = std::env::temp_dir().join("hatchery-editor-snapshot.png");
    shot.save(&out).unwrap();
    eprintln!("editor snapshot written to {}", out.display());
    assert!(non_blank(&shot), "the editor snapshot is blank");
    // The viewport's part of the screenshot shows the rendered surface, not an empty panel.
    let r = h.state().viewport_rect;
    let ppp = shot.width() as f32 / 1280.0;
    let viewport = image::imageops::crop_imm(
        &shot,
        (r.left() * ppp) as u32,
        (r.top() * ppp) as u32,
        (r.width() * ppp) as u32,
        (r.height() * ppp) as u32,
    )
    .to_image();
    assert!(viewport.width() > 100 && viewport.height() > 50);
    assert!(
        non_blank(&viewport),
        "the viewport in the snapshot is blank"
    );
    // The canvas (left) and the inspector (right of the canvas) are there too.
    h.get_by_label("shaded (ShadedSurface)");
    h.get_by_label("Inspector");
}

/// A primary click at `at` by pointer events, one frame per event and no run to idle (for UIs
/// that keep repainting: a file dialog reading a folder, a thumbnail thread).
fn click_stepped(h: &mut Harness<EditorApp>, at: egui::Pos2) {
    h.event(egui::Event::PointerMoved(at));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
}

/// The window's close button, as the platform reports it; returns the commands the app sent.
fn close_window(h: &mut Harness<EditorApp>) -> Vec<egui::ViewportCommand> {
    h.input_mut()
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .events
        .push(egui::ViewportEvent::Close);
    h.step();
    h.output()
        .viewport_output
        .get(&egui::ViewportId::ROOT)
        .map(|v| v.commands.clone())
        .unwrap_or_default()
}

fn non_blank(img: &image::RgbaImage) -> bool {
    let first = img.get_pixel(0, 0);
    img.pixels().filter(|p| *p != first).count() > (img.width() * img.height() / 100) as usize
}

fn right_click_at(h: &Harness<EditorApp>, pos: egui::Pos2) {
    h.event(egui::Event::PointerMoved(pos));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Secondary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
}

#[test]
fn opening_another_graph_asks_before_discarding_changes() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.state
        .set_param("camera", "azimuth", ParamValue::Float(10.0), false)
        .unwrap();
    let other = dir.path().join("bad.ron");
    std::fs::copy(repo("tests/fixtures/bad/missing_input.ron"), &other).unwrap();
    app.request(hatchery_editor::app::Pending::Open(other.clone()));
    let mut h = harness(app);
    h.run();
    h.get_by_label("Cancel").click();
    h.run();
    assert!(h.state().pending().is_none());
    assert_eq!(h.state().state.doc().nodes.len(), 6, "kept");
    h.state_mut()
        .request(hatchery_editor::app::Pending::Open(other.clone()));
    h.run();
    h.get_by_label("Discard changes").click();
    h.run();
    assert_eq!(h.state().state.path(), Some(other.as_path()));
    assert_eq!(h.state().state.doc().nodes.len(), 2);
}

#[test]
fn dragging_a_node_moves_it_in_the_document_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let pos_of = |h: &Harness<EditorApp>| {
        let n = h
            .state()
            .state
            .doc()
            .nodes
            .iter()
            .find(|n| n.id == "light")
            .unwrap();
        n.editor.unwrap()
    };
    let start = pos_of(&h);
    // Accessibility rects of canvas widgets are in graph space: map them to the screen.
    let title = h.get_by_label("light (Light)").rect();
    let from = h.state().canvas_transform * title.center();
    drag(&mut h, from, from + egui::vec2(80.0, 40.0));
    let end = pos_of(&h);
    assert!(
        end.x > start.x + 40.0 && end.y > start.y + 20.0,
        "{start:?} → {end:?}"
    );
    assert!(h.state().state.is_dirty());
    assert!(h.state_mut().state.undo());
    assert_eq!(pos_of(&h), start, "the whole drag is one step");
}

#[test]
fn an_execution_error_is_shown_on_its_node_and_the_editor_keeps_working() {
    let dir = tempfile::tempdir().unwrap();
    // Copied away from graphs/, the preset's relative mesh path points nowhere.
    let (mut app, _) = open_copy("graphs/bunny_surface.ron", dir.path());
    assert!(
        app.state.errors().is_empty(),
        "valid graph: {:?}",
        app.state.errors()
    );
    app.preview_enabled = true;
    let mut h = harness(app);
    wait_for_render(&mut h);
    let (node, message) = h
        .state()
        .preview
        .failed_node
        .clone()
        .expect("execution failed");
    assert_eq!(node, "bunny", "{message}");
    assert!(h.state().preview.error.is_some());
    h.get_by_label_contains("⚠");
    // Pointing the node at a file that exists fixes it.
    let mesh = repo("../shared/data/meshes/bunny.obj");
    if mesh.is_file() {
        let path = ParamValue::Path(mesh.display().to_string());
        h.state_mut()
            .state
            .set_param("bunny", "path", path, false)
            .unwrap();
        wait_for_render(&mut h);
        assert!(
            h.state().preview.failed_node.is_none(),
            "{:?}",
            h.state().preview.error
        );
        assert!(h.state().preview.viewport.is_some());
    }
}

/// An iso value without a surface is a warning shown on its node (issue 9 item 4); the picture
/// still renders, and the warning goes once the node has a surface again.
#[test]
fn a_warning_is_shown_on_its_node_and_the_picture_still_renders() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.preview_enabled = true;
    let mut h = harness(app);
    wait_for_render(&mut h);
    h.state_mut()
        .state
        .set_param("surface", "iso", ParamValue::Float(3.0), false)
        .unwrap();
    wait_for_render(&mut h);
    assert!(h.state().preview.failed_node.is_none());
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    h.run_steps(2);
    let label = h.get_by_label_contains("outside the volume's value range");
    let at = h.state().canvas_transform * label.rect().center();
    assert_eq!(h.state().node_at(at), Some("surface"), "shown on its node");
    h.state_mut()
        .state
        .set_param("surface", "iso", ParamValue::Float(0.0), false)
        .unwrap();
    wait_for_render(&mut h);
    h.run_steps(2);
    assert_eq!(
        h.query_all_by_label_contains("outside the volume's value range")
            .count(),
        0
    );
}

#[test]
fn the_node_menu_duplicates_previews_and_deletes() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let on_title = |h: &Harness<EditorApp>, label: &str| {
        let rect = h.get_by_label(label).rect();
        h.state().canvas_transform * rect.center()
    };
    let at = on_title(&h, "surface (MarchingCubes)");
    right_click_at(&h, at);
    h.run();
    h.get_by_label("Duplicate").click();
    h.run();
    let doc = h.state().state.doc();
    let copy = doc
        .nodes
        .iter()
        .find(|n| n.id == "surface_1")
        .expect("duplicated");
    assert_eq!(copy.kind, "MarchingCubes");
    assert_eq!(
        copy.params,
        doc.nodes.iter().find(|n| n.id == "surface").unwrap().params
    );

    let at = on_title(&h, "shells (ProceduralVolume)");
    right_click_at(&h, at);
    h.run();
    h.get_by_label("Preview volume").click();
    h.run();
    assert_eq!(
        h.state().preview.chosen,
        Some(("shells".to_string(), "volume".to_string()))
    );

    // The duplicate is selected (its title is also the inspector's heading): deselect (Esc).
    h.key_press(Key::Escape);
    h.run();
    assert!(h.state().state.selection.is_empty());
    let at = on_title(&h, "surface_1 (MarchingCubes)");
    right_click_at(&h, at);
    h.run();
    h.get_by_label("Delete").click();
    h.run();
    assert!(
        h.state()
            .state
            .doc()
            .nodes
            .iter()
            .all(|n| n.id != "surface_1")
    );
    assert_eq!(h.state().state.doc().nodes.len(), 6);
}

/// The canvas label `label` (a port name) drawn on node `id`, in graph space (the canvas
/// transform takes it to the screen). Port names repeat across nodes (the Camera's `volume`
/// input, a source's `volume` output), so the node says which.
fn port_label(h: &Harness<EditorApp>, id: &str, label: &str) -> egui::Rect {
    let t = h.state().canvas_transform;
    let node = h.state().node_screen_rect(id).expect("node on screen");
    h.get_all_by_label(label)
        .map(|n| n.rect())
        .find(|r| node.contains(t * r.center()))
        .unwrap_or_else(|| panic!("no label `{label}` on node {id}"))
}

/// Drags with the primary button from `from` to `to` (screen points) in small steps.
fn drag(h: &mut Harness<EditorApp>, from: egui::Pos2, to: egui::Pos2) {
    drag_with(h, from, to, egui::PointerButton::Primary);
}

fn drag_with(
    h: &mut Harness<EditorApp>,
    from: egui::Pos2,
    to: egui::Pos2,
    button: egui::PointerButton,
) {
    drag_steps(h, from, to, button);
    h.run();
}

/// Presses `button` at `from`, moves to `to` in ten steps and releases it there, without running
/// the UI until idle afterwards (a menu that opens may keep it repainting).
fn drag_steps(
    h: &mut Harness<EditorApp>,
    from: egui::Pos2,
    to: egui::Pos2,
    button: egui::PointerButton,
) {
    h.event(egui::Event::PointerMoved(from));
    h.event(egui::Event::PointerButton {
        pos: from,
        button,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    h.step();
    for i in 1..=10 {
        h.event(egui::Event::PointerMoved(
            from + (to - from) * (i as f32 / 10.0),
        ));
        h.step();
    }
    h.event(egui::Event::PointerButton {
        pos: to,
        button,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
}

#[test]
fn dragging_a_wire_between_incompatible_pins_is_refused_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let t = h.state().canvas_transform;
    // Pin labels in graph space; the pins sit just outside them.
    let volume_out = port_label(&h, "shells", "volume");
    let camera_in = port_label(&h, "shaded", "camera");
    let from = t * egui::pos2(volume_out.right() + 14.0, volume_out.center().y);
    let to = t * egui::pos2(camera_in.left() - 12.0, camera_in.center().y);
    let before = h.state().state.doc().clone();
    drag(&mut h, from, to);
    assert_eq!(h.state().state.doc(), &before, "nothing connected");
    assert!(
        h.state().state.status.contains("type mismatch"),
        "status: {}",
        h.state().state.status
    );
    // In the status line and as a tooltip where the wire was dropped.
    assert_eq!(h.query_all_by_label_contains("type mismatch").count(), 2);
    let refusal = h.state().refusal.clone().expect("a refusal tooltip");
    assert!(
        refusal.reason.contains("type mismatch"),
        "{}",
        refusal.reason
    );
    assert!(
        refusal.at.distance(to) < 20.0,
        "at {:?}, dropped at {to:?}",
        refusal.at
    );
    h.get_by_label_contains("⛔");
}

#[test]
fn dragging_a_wire_between_compatible_pins_connects_them() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let added = app
        .state
        .add_node("MarchingCubes", EditorPos { x: 280.0, y: 520.0 })
        .unwrap();
    let mut h = harness(app);
    h.run();
    h.key_press(Key::Escape);
    h.run();
    let t = h.state().canvas_transform;
    let out = port_label(&h, "shells", "volume");
    let input = port_label(&h, &added, "volume");
    let from = t * egui::pos2(out.right() + 14.0, out.center().y);
    let to = t * egui::pos2(input.left() - 12.0, input.center().y);
    drag(&mut h, from, to);
    let edge = hatchery_graph::EdgeDoc {
        from: ("shells".into(), "volume".into()),
        to: (added.clone(), "volume".into()),
    };
    assert!(
        h.state().state.doc().edges.contains(&edge),
        "status: {}",
        h.state().state.status
    );
    // Said in characters the editor's font has (an arrow glyph drew as a box).
    let said = format!("connected shells.volume -> {added}.volume");
    assert_eq!(h.state().state.status, said);
    assert!(h.state().state.node_error(&added).is_none());
    assert!(h.state_mut().state.undo());
    assert!(!h.state().state.doc().edges.contains(&edge));
}

/// A parameter of the "camera" node as written in the document.
fn camera_raw(h: &Harness<EditorApp>, name: &str) -> Option<ron::Value> {
    let doc = h.state().state.doc();
    let camera = doc.nodes.iter().find(|n| n.id == "camera").unwrap();
    camera.params.get(name).cloned()
}

#[test]
fn dragging_in_the_viewport_orbits_the_camera_node_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let azimuth = |h: &Harness<EditorApp>| match camera_raw(h, "azimuth") {
        Some(ron::Value::Number(n)) => n.into_f64(),
        other => panic!("azimuth is {other:?}"),
    };
    assert_eq!(azimuth(&h), 30.0);
    let centre = h.state().viewport_rect.center();
    assert!(
        h.state().viewport_rect.width() > 10.0,
        "the viewport must be on screen"
    );
    drag(&mut h, centre, centre + egui::vec2(50.0, 0.0));
    let turned = azimuth(&h);
    assert!(
        (turned - 10.0).abs() < 1e-6,
        "a 50-point drag turns the camera by 20°: {turned}"
    );
    // The whole drag is one undo step.
    h.state_mut().state.undo();
    h.run();
    assert_eq!(azimuth(&h), 30.0);
}

#[test]
fn right_dragging_in_the_viewport_pans_the_camera_target() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let target = |h: &Harness<EditorApp>| camera_raw(h, "target");
    assert_eq!(
        target(&h),
        None,
        "the preset uses the default target (origin)"
    );
    let r = h.state().viewport_rect;
    let centre = r.center();
    drag_with(
        &mut h,
        centre,
        centre + egui::vec2(40.0, 0.0),
        egui::PointerButton::Secondary,
    );
    let after: [f64; 3] = match target(&h) {
        Some(raw) => match h
            .state()
            .state
            .registry
            .schema("Camera")
            .unwrap()
            .param("target")
            .unwrap()
            .convert(&raw)
            .unwrap()
        {
            ParamValue::Vec3(v) => v,
            other => panic!("target is {other:?}"),
        },
        None => panic!("panning set no target"),
    };
    // Camera at azimuth 30°, elevation 20°, distance 3.5, fov 40° (across the viewport's shorter
    // side): the scene follows the pointer, so the target moves left along the camera's right
    // axis by 40 points' worth of world units.
    let (az, fov, distance) = (30f64.to_radians(), 40f64.to_radians(), 3.5);
    let world = 40.0 * 2.0 * distance * (fov / 2.0).tan() / r.width().min(r.height()) as f64;
    let right = [az.cos(), 0.0, -az.sin()];
    for i in 0..3 {
        assert!(
            (after[i] + right[i] * world).abs() < 1e-4,
            "target {after:?}, expected {:?}",
            right.map(|x| -x * world)
        );
    }
    // Azimuth and elevation are untouched, and the pan is one undo step.
    let camera = h
        .state()
        .state
        .doc()
        .nodes
        .iter()
        .find(|n| n.id == "camera")
        .unwrap();
    let number = |name: &str| match camera.params.get(name) {
        Some(ron::Value::Number(n)) => n.into_f64(),
        other => panic!("{name} is {other:?}"),
    };
    assert_eq!((number("azimuth"), number("elevation")), (30.0, 20.0));
    h.state_mut().state.undo();
    h.run();
    assert_eq!(target(&h), None);
}

#[test]
fn the_viewport_renders_off_the_ui_thread_and_output_pins_show_thumbnails_and_times() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    app.preview_enabled = true;
    // Room for the thumbnail: a pinned node grows to the right, over the SaveImage node.
    app.state.move_node(
        "save",
        EditorPos {
            x: 1100.0,
            y: 120.0,
        },
    );
    let mut h = harness(app);
    // The first frame asks the render thread and returns without a picture.
    h.step();
    assert!(h.state().preview.is_busy(), "a render was requested");
    assert!(h.state().preview.viewport.is_none());
    h.get_by_label("rendering…");
    wait_for_render(&mut h);
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let viewport = h
        .state()
        .preview
        .viewport
        .as_ref()
        .expect("a picture")
        .size();
    assert!(
        !h.state().preview.shares_device(),
        "no window device: pixels come back"
    );

    // Clicking an output's name pins its thumbnail on the node.
    // Two labels read "image": shaded's output (left) and save's input (right).
    // Canvas rects are in graph coordinates: click where the canvas draws them.
    fn click_leftmost(h: &mut Harness<EditorApp>, label: &str) {
        // Nodes take their new size a frame after their content changes: let them settle.
        h.run_steps(3);
        let mut all: Vec<egui::Rect> = h.get_all_by_label(label).map(|n| n.rect()).collect();
        all.sort_by(|a, b| a.left().total_cmp(&b.left()));
        let at = h.state().canvas_transform * all[0].center();
        click_stepped(h, at);
    }
    click_leftmost(&mut h, "image");
    let port = ("shaded".to_string(), "image".to_string());
    assert!(h.state().preview.pins.contains(&port));
    wait_for_render(&mut h);
    let thumb = h
        .state()
        .preview
        .thumbnails
        .get(&port)
        .expect("a thumbnail")
        .size();
    // Within the 160×120 bound, touching it on one side.
    assert!(
        thumb[0] <= 160 && thumb[1] <= 120 && (thumb[0] >= 150 || thumb[1] >= 112),
        "{thumb:?}"
    );
    let aspect = |s: [u32; 2]| s[0] as f64 / s[1] as f64;
    assert!(
        (aspect(thumb) - aspect(viewport)).abs() < 0.05,
        "{thumb:?} vs {viewport:?}"
    );
    h.get_by_label("shaded.image");

    // Node times on request: everything cached right after, then a parameter change re-runs
    // only the shading node.
    h.get_by_label("Node times").click();
    wait_for_render(&mut h);
    let times = h.state().preview.times.clone();
    assert!(times.values().all(|t| t.cached), "{times:?}");
    h.state_mut()
        .state
        .set_param(
            "shaded",
            "color",
            ParamValue::Color([0.2, 0.4, 0.9, 1.0]),
            false,
        )
        .unwrap();
    wait_for_render(&mut h);
    let times = h.state().preview.times.clone();
    assert!(
        !times["shaded"].cached && times["shaded"].cpu > std::time::Duration::ZERO,
        "{times:?}"
    );
    assert!(
        times["surface"].cached && times["shells"].cached,
        "{times:?}"
    );
    assert!(h.query_all_by_label_contains("⏱").count() >= 4);

    // A port without a picture (a mesh) says so on its node instead of a thumbnail.
    let mesh = ("surface".to_string(), "mesh".to_string());
    h.state_mut().preview.pins.insert(mesh.clone());
    wait_for_render(&mut h);
    let why = h.state().preview.thumbnail_errors.get(&mesh).cloned();
    assert!(
        why.as_deref().is_some_and(|e| e.contains("no picture")),
        "{why:?}"
    );
    h.get_by_label("mesh: no picture");
    h.state_mut().preview.pins.remove(&mesh);

    // Clicking again unpins it.
    click_leftmost(&mut h, "image 👁");
    assert!(!h.state().preview.pins.contains(&port));
    wait_for_render(&mut h);
    assert!(h.state().preview.thumbnails.is_empty());
}

/// Benchmark, not a check (run with `--ignored --nocapture`): UI frame time with the
/// brain-surface preset (and the ray-cast tf1d_phong_brain) open, idle and while the viewport
/// re-renders after a parameter change,
/// with the UI drawn by egui-wgpu every frame (as a window would). Two configurations in one run:
/// the render thread on a device of its own (the default on CPU adapters) and on the window's
/// device (the default on GPUs; its pictures are shown without copies).
#[test]
#[ignore]
fn ui_frame_time_with_the_brain_preset() {
    let mri = repo("../shared/data/volumes/mni152_t1.nii.gz")
        .canonicalize()
        .unwrap();
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let cases = [
        ("graphs/brain_surface.ron", "mri", false),
        ("graphs/brain_surface.ron", "mri", true),
        ("graphs/tf1d_phong_brain.ron", "volume", false),
        ("graphs/tf1d_phong_brain.ron", "volume", true),
    ];
    for (preset, volume_node, share) in cases {
        let dir = tempfile::tempdir().unwrap();
        let (mut app, _) = open_copy(preset, dir.path());
        // The copy lives in a temp dir: point it at the shared MRI by absolute path.
        let path = ParamValue::Path(mri.to_string_lossy().into_owned());
        app.state
            .set_param(volume_node, "path", path, false)
            .unwrap();
        app.preview_enabled = true;
        let mut setup = eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle();
        setup.device_descriptor = std::sync::Arc::new(hatchery_gpu::GpuContext::device_descriptor);
        let mut h = Harness::builder()
            .with_size([1280.0, 800.0])
            .wgpu_setup(eframe::egui_wgpu::WgpuSetup::CreateNew(setup))
            .build_eframe(move |cc| {
                app.preview
                    .set_render_state(cc.wgpu_render_state.clone().unwrap(), share);
                app
            });
        let frame = |h: &mut Harness<EditorApp>| {
            let t = std::time::Instant::now();
            h.step();
            h.render().expect("egui-wgpu draws the UI");
            t.elapsed().as_secs_f64() * 1e3
        };
        let start = std::time::Instant::now();
        wait_for_render(&mut h);
        let first = start.elapsed().as_secs_f64() * 1e3;
        let mut idle: Vec<f64> = (0..10).map(|_| frame(&mut h)).collect();
        let (mut during, mut renders) = (Vec::new(), Vec::new());
        for i in 0..10 {
            h.state_mut()
                .state
                .set_param(
                    "camera",
                    "azimuth",
                    ParamValue::Float(-60.0 + 5.0 * i as f64),
                    false,
                )
                .unwrap();
            let t = std::time::Instant::now();
            during.push(frame(&mut h));
            while h.state().preview.is_busy() {
                during.push(frame(&mut h));
            }
            renders.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let adapter = h
            .state()
            .preview
            .last_render
            .as_ref()
            .map(|(_, a)| a.clone())
            .unwrap_or_default();
        let shown = h.state().preview.viewport.as_ref().unwrap().size();
        let worst = during.iter().copied().fold(0.0, f64::max);
        println!(
            "{preset}, {}: adapter {adapter}; viewport {}×{} px; first picture after {first:.0} ms; UI frame \
             (update + egui-wgpu draw) median idle {:.2} ms; during re-renders median {:.2} ms, \
             worst {worst:.1} ms over {} frames; parameter change → new picture median {:.0} ms",
            if share { "shared device" } else { "own device" },
            shown[0],
            shown[1],
            median(&mut idle),
            median(&mut during),
            during.len(),
            median(&mut renders),
        );
    }
}

/// A text parameter of a node as written in the document.
fn text_param(h: &Harness<EditorApp>, node: &str, name: &str) -> String {
    let doc = h.state().state.doc();
    let node = doc.nodes.iter().find(|n| n.id == node).unwrap();
    match node.params.get(name) {
        Some(ron::Value::String(text)) => text.clone(),
        other => panic!("{name} is {other:?}"),
    }
}

/// The `points` text of node `tf`, parsed.
fn tf_points(h: &Harness<EditorApp>) -> Vec<hatchery_data::transfer_function::ControlPoint> {
    hatchery_data::transfer_function::TransferFunction1D::parse_points(&text_param(
        h, "tf", "points",
    ))
    .unwrap()
}

fn click_with(h: &mut Harness<EditorApp>, at: egui::Pos2, button: egui::PointerButton) {
    h.event(egui::Event::PointerMoved(at));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button,
            pressed,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
}

#[test]
fn the_transfer_function_editor_moves_adds_and_removes_points() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("tests/fixtures/v2_presets/tf1d_phong_brain.ron", dir.path());
    // Frames 1/60 s apart (kittest's default 1/4 s is too slow for a double-click).
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .with_step_dt(1.0 / 60.0)
        .with_max_steps(200)
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app);
    h.run();
    select_by_click(&mut h, "tf");
    let before = tf_points(&h);
    assert_eq!(before.len(), 5);
    let curve = h.get_by_label("transfer function curve").rect();
    let span = before[4].value - before[0].value;

    // Drag point 3 up by 28 points (a fifth of the curve's height) and right by 10.
    let handle = h.get_by_label("transfer function point 3").rect().center();
    drag(&mut h, handle, handle + egui::vec2(10.0, -28.0));
    let after = tf_points(&h);
    assert_eq!(after.len(), 5);
    let lifted = after[2].rgba[3] - before[2].rgba[3];
    assert!(
        (lifted - 28.0 / curve.height()).abs() < 0.01,
        "opacity +{lifted}"
    );
    let moved = after[2].value - before[2].value;
    let expected = 10.0 / curve.width() * span;
    assert!(
        (moved - expected).abs() < 0.02 * span,
        "value +{moved}, expected +{expected}"
    );
    assert_eq!(after[2].rgba[..3], before[2].rgba[..3], "colour kept");
    // One drag is one undo step.
    h.state_mut().state.undo();
    h.run();
    assert_eq!(tf_points(&h), before);

    // A double-click on an empty part of the curve adds a point there, between its neighbours.
    // A pause first: egui counts a click within 0.6 s of the click before last (the one that
    // selected the node) as a triple click.
    for _ in 0..45 {
        h.step();
    }
    let x = curve.left() + curve.width() * 0.05;
    let at = egui::pos2(x, curve.bottom() - curve.height() * 0.5);
    click_with(&mut h, at, egui::PointerButton::Primary);
    click_with(&mut h, at, egui::PointerButton::Primary);
    h.run();
    let added = tf_points(&h);
    assert_eq!(added.len(), 6, "{added:?}");
    assert!(added.windows(2).all(|w| w[0].value < w[1].value));
    let new = added.iter().find(|p| !before.contains(p)).unwrap();
    assert!((new.rgba[3] - 0.5).abs() < 0.02, "{new:?}");

    // A right-click on a point removes it.
    let handle = h.get_by_label("transfer function point 2").rect().center();
    click_with(&mut h, handle, egui::PointerButton::Secondary);
    h.run();
    assert_eq!(tf_points(&h).len(), 5);
}

#[test]
fn the_style_picker_swaps_adds_and_removes_lit_sphere_styles() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/volume_styles.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "styles");
    let styles = |h: &Harness<EditorApp>| text_param(h, "styles", "styles");
    let original = styles(&h);
    assert_eq!(original, "gooch:0.6,0.7,0.9, toon3:0.9,0.45,0.35");
    // Each style is a thumbnail button; clicking it opens the gallery of every style.
    h.get_by_label("gooch").click();
    h.run();
    h.get_by_label("Pick a style");
    h.get_by_label("metal").click();
    h.run();
    assert_eq!(styles(&h), "metal:0.6,0.7,0.9, toon3:0.9,0.45,0.35");
    h.get_by_label("+ Add style").click();
    h.run();
    assert_eq!(
        styles(&h),
        "metal:0.6,0.7,0.9, toon3:0.9,0.45,0.35, shaded:0.85,0.85,0.85"
    );
    let removes: Vec<_> = h.get_all_by_label("✕").collect();
    assert_eq!(removes.len(), 3);
    removes[0].click();
    h.run();
    assert_eq!(styles(&h), "toon3:0.9,0.45,0.35, shaded:0.85,0.85,0.85");
    for _ in 0..3 {
        h.state_mut().state.undo();
    }
    h.run();
    assert_eq!(styles(&h), original);
}

/// A file dropped on the window, as the platform layer reports it.
#[derive(Debug)]
struct DroppedPath(PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &Path {
        &self.0
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn drop_file(h: &mut Harness<EditorApp>, path: &Path, at: egui::Pos2) {
    h.event(egui::Event::PointerMoved(at));
    h.input_mut()
        .dropped_files
        .push(std::sync::Arc::new(DroppedPath(path.to_path_buf())));
    // The frames `Harness::run` would take to settle, without requiring it to settle: a drop that
    // starts a render keeps the worker repainting for as long as the machine takes (a loaded CI
    // machine: more than run's 4 steps). Tests that need the picture wait for it.
    h.run_steps(4);
}

#[test]
fn dropped_files_open_graphs_and_add_source_nodes_where_they_land() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let nodes = h.state().state.doc().nodes.len();

    // A mesh: a MeshFile node reading it, at the drop point, its path relative to the graph.
    let data = dir.path().join("data");
    std::fs::create_dir(&data).unwrap();
    let mesh = data.join("tri.obj");
    std::fs::write(&mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let at = egui::pos2(300.0, 600.0);
    drop_file(&mut h, &mesh, at);
    let doc = h.state().state.doc().clone();
    assert_eq!(doc.nodes.len(), nodes + 1);
    let added = doc
        .nodes
        .iter()
        .find(|n| n.kind == "MeshFile")
        .expect("a MeshFile node");
    assert_eq!(
        added.params.get("path"),
        Some(&ron::Value::String("data/tri.obj".into()))
    );
    let placed = added.editor.expect("placed on the canvas");
    let screen = h.state().canvas_transform * egui::pos2(placed.x, placed.y);
    assert!(
        screen.distance(at) < 1.0,
        "placed at {screen:?}, dropped at {at:?}"
    );
    // Adding it is one undo step.
    h.state_mut().state.undo();
    assert_eq!(h.state().state.doc().nodes.len(), nodes);

    // A WGSL shader: a CustomShader node reading it, with the ports its declarations give.
    let shader = data.join("invert.wgsl");
    std::fs::write(
        &shader,
        "@group(0) @binding(0) var picture: texture_2d<f32>;\n@fragment fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {\n    let c = textureLoad(picture, vec2<i32>(p.xy), 0);\n    return vec4<f32>(c.a - c.rgb, c.a);\n}\n",
    )
    .unwrap();
    drop_file(&mut h, &shader, at);
    let doc = h.state().state.doc().clone();
    let added = doc
        .nodes
        .iter()
        .find(|n| n.kind == "CustomShader")
        .expect("a CustomShader node");
    assert_eq!(
        added.params.get("shader"),
        Some(&ron::Value::String("data/invert.wgsl".into()))
    );
    h.run();
    // Its input pin `picture` is drawn on the canvas (a required input, not yet connected).
    h.get_by_label("picture");
    let error = h.state().state.node_error(&added.id).unwrap_or_default();
    assert!(error.contains("required input `picture`"), "{error}");
    h.state_mut().state.undo();
    assert_eq!(h.state().state.doc().nodes.len(), nodes);

    // Files hatchery does not read are refused with a message.
    let notes = dir.path().join("notes.txt");
    std::fs::write(&notes, "hello").unwrap();
    drop_file(&mut h, &notes, at);
    assert_eq!(h.state().state.doc().nodes.len(), nodes);
    assert!(
        h.state()
            .state
            .status
            .contains("not a graph, volume, mesh or shader"),
        "{}",
        h.state().state.status
    );

    // A graph opens (the document has no unsaved edits after the undo... it does: ask first).
    let other = dir.path().join("other.ron");
    std::fs::copy(repo("graphs/hidden_structures.ron"), &other).unwrap();
    drop_file(&mut h, &other, at);
    if h.state().pending().is_some() {
        h.get_by_label("Discard changes").click();
        h.run();
    }
    assert_eq!(h.state().state.path(), Some(other.as_path()));
}

#[test]
fn the_folder_button_of_a_path_parameter_picks_a_file_with_the_dialog() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/bunny_surface.ron", dir.path());
    std::fs::write(
        dir.path().join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "bunny");
    // The Inspector's 📂 (the Data panel's rows have a Pick… button each).
    let rows = h.state().data_rows.clone();
    let button = h
        .get_all_by_label("📂")
        .map(|n| n.rect())
        .find(|b| !rows.iter().any(|(_, r)| r.contains(b.center())))
        .expect("the path parameter's folder button");
    // Stepped: the dialog repaints while it reads the folder.
    click_stepped(&mut h, button.center());
    // The dialog reads the folder on a thread of its own: step until it lists the file.
    for _ in 0..400 {
        h.step();
        if h.query_by_label_contains("tri.obj").is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    assert_eq!(
        h.state().picker.purpose(),
        Some(&hatchery_editor::files::Purpose::Param {
            node: "bunny".into(),
            param: "path".into()
        })
    );
    h.get_by_label("Choose bunny.path");
    // The dialog lists the graph's folder (the bunny's relative path points there, missing).
    h.get_by_label_contains("tri.obj").click();
    h.step();
    h.get_by_label("🗀  Open").click();
    h.step();
    h.step();
    assert!(h.state().picker.purpose().is_none(), "the dialog closed");
    let doc = h.state().state.doc();
    let bunny = doc.nodes.iter().find(|n| n.id == "bunny").unwrap();
    assert_eq!(
        bunny.params.get("path"),
        Some(&ron::Value::String("tri.obj".into()))
    );
}

#[test]
fn closing_the_window_with_unsaved_changes_asks_first() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let close = close_window;
    // Without edits the window just closes.
    assert!(!close(&mut h).contains(&egui::ViewportCommand::CancelClose));
    h.state_mut()
        .state
        .set_param("camera", "azimuth", ParamValue::Float(45.0), false)
        .unwrap();
    h.run();
    let commands = close(&mut h);
    assert!(
        commands.contains(&egui::ViewportCommand::CancelClose),
        "{commands:?}"
    );
    assert_eq!(
        h.state().pending(),
        Some(&hatchery_editor::app::Pending::Quit)
    );
    h.run();
    h.get_by_label("Discard changes").click();
    h.step();
    h.step();
    let commands = h.output().viewport_output[&egui::ViewportId::ROOT]
        .commands
        .clone();
    assert!(
        commands.contains(&egui::ViewportCommand::Close),
        "{commands:?}"
    );
}

#[test]
fn the_style_transfer_function_editor_moves_points_and_picks_their_styles() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("tests/fixtures/v2_presets/style_tf_brain.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "tf");
    let nodes = |h: &Harness<EditorApp>| {
        hatchery_data::style::StyleTransferFunction::parse(&text_param(h, "tf", "nodes")).unwrap()
    };
    let before = nodes(&h);
    assert_eq!(before.len(), 4);
    let curve = h.get_by_label("style transfer function curve").rect();
    // Dragging point 3 down by a tenth of the curve's height lowers its opacity by 0.1.
    let handle = h
        .get_by_label("style transfer function point 3")
        .rect()
        .center();
    drag(
        &mut h,
        handle,
        handle + egui::vec2(0.0, curve.height() * 0.1),
    );
    let after = nodes(&h);
    assert!(
        (after[2].opacity - (before[2].opacity - 0.1)).abs() < 0.01,
        "{after:?}"
    );
    // A vertical drag keeps the value (up to float rounding of the screen mapping).
    assert!((after[2].value - before[2].value).abs() < 1e-3, "{after:?}");
    assert_eq!(after[2].style, before[2].style);
    // The picked point's style is chosen by name from the connected StyleSet.
    // (The combo box shows "1: toon3"; it is the only one in this inspector.)
    h.get_by_role(Role::ComboBox).click();
    h.run();
    h.get_by_label("2: shaded").click();
    h.run();
    assert_eq!(nodes(&h)[2].style, 2);
}

#[test]
fn save_as_to_another_folder_keeps_naming_the_same_data_files() {
    let dir = tempfile::tempdir().unwrap();
    let mut state = EditorState::new();
    state.open(&repo("graphs/brain_surface.ron")).unwrap();
    let data = |s: &EditorState| {
        let node = s.doc().nodes.iter().find(|n| n.id == "mri").unwrap();
        match &node.params["path"] {
            ron::Value::String(p) => s.base_dir().unwrap().join(p).canonicalize().unwrap(),
            other => panic!("{other:?}"),
        }
    };
    let before = data(&state);
    state
        .set_param("camera", "azimuth", ParamValue::Float(12.0), false)
        .unwrap();
    let nested = dir.path().join("figures/brain");
    std::fs::create_dir_all(&nested).unwrap();
    state.save_as(&nested.join("brain.ron")).unwrap();
    assert_eq!(
        data(&state),
        before,
        "the MRI is still found from the new folder"
    );
    // Undoing after the move keeps the paths valid too.
    assert!(state.undo());
    assert_eq!(data(&state), before, "the undo history moved with the file");
    let reopened = {
        let mut s = EditorState::new();
        s.open(&nested.join("brain.ron")).unwrap();
        s
    };
    assert_eq!(data(&reopened), before);
}
