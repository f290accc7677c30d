//! Graph inputs in the editor (issue 25), driven by real input: files dropped on the Data
//! panel's rows and picked with its button, the relative iso value in the Inspector with what it
//! resolved to, viewport pans and zooms of a camera that frames its data, the Presets gallery.

use super::*;

fn shared(path: &str) -> PathBuf {
    repo(&format!("../shared/data/{path}"))
        .canonicalize()
        .unwrap()
}

/// The file dialog is open for input `name`.
fn assert_asks_for(h: &Harness<EditorApp>, name: &str) {
    let purpose = hatchery_editor::files::Purpose::Input { name: name.into() };
    assert_eq!(h.state().picker.purpose(), Some(&purpose));
}

/// The Data panel's row of input `name`, on screen.
fn row(h: &Harness<EditorApp>, name: &str) -> egui::Rect {
    h.state()
        .data_rows
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, r)| *r)
        .unwrap_or_else(|| panic!("no Data row for input `{name}`"))
}

fn mri_path(h: &Harness<EditorApp>) -> String {
    match h
        .state()
        .state
        .doc()
        .node("mri")
        .unwrap()
        .params
        .get("path")
    {
        Some(ron::Value::String(s)) => s.clone(),
        other => panic!("mri.path is {other:?}"),
    }
}

#[test]
fn a_file_dropped_on_an_input_replaces_it_and_the_graph_renders_it() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/brain_surface.ron", dir.path());
    app.preview_enabled = true;
    let mut h = harness(app);
    h.run();
    h.get_by_label("Data");
    h.get_by_label("(volume)");
    // A mesh dropped on the volume input is refused, saying why; nothing changes.
    let before = h.state().state.doc().clone();
    let r = row(&h, "volume");
    drop_file(&mut h, &shared("meshes/bunny.obj"), r.center());
    assert_eq!(h.state().state.doc(), &before);
    assert!(
        h.state().state.status.contains("takes a volume file"),
        "{}",
        h.state().state.status
    );
    // The white-matter map dropped on it: mri.path reads it (relative to the graph's folder),
    // as one undo step, and the picture renders from it with the iso value resolved anew.
    let wm = shared("volumes/mni152_wm.nii.gz");
    drop_file(&mut h, &wm, r.center());
    let stored = mri_path(&h);
    assert!(stored.ends_with("mni152_wm.nii.gz"), "{stored}");
    assert_eq!(dir.path().join(&stored).canonicalize().unwrap(), wm);
    assert_eq!(
        h.state().state.doc().nodes.len(),
        before.nodes.len(),
        "no node was added"
    );
    wait_for_render(&mut h);
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let resolved = h.state().preview.resolved["surface"]["iso"].clone();
    assert!(resolved.starts_with("range(0.31"), "{resolved}");
    // The Inspector shows it next to the relative iso value.
    select_by_click(&mut h, "surface");
    let number = resolved.rsplit("= ").next().unwrap();
    h.get_by_label(&format!("= {number}"));
    assert!(h.state_mut().state.undo());
    assert_ne!(mri_path(&h), stored);
}

#[test]
fn the_data_panel_button_picks_a_file_for_an_input() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/brain_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let r = row(&h, "volume");
    // The Pick… button sits at the row's right end.
    let button = h
        .get_all_by_label("Pick…")
        .map(|n| n.rect())
        .find(|b| r.contains(b.center()))
        .expect("a pick button in the volume row");
    // The file dialog repaints while it reads the folder on another thread, as long as the
    // machine takes (a loaded CI machine: more frames): click, then step a few frames instead of
    // running to a frame that asks for no repaint.
    h.event(egui::Event::PointerMoved(button.center()));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: button.center(),
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    h.run_steps(4);
    assert_asks_for(&h, "volume");
}

#[test]
fn panning_and_zooming_a_framing_camera_keeps_it_framing() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/brain_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let target = camera_raw(&h, "target");
    let r = h.state().viewport_rect;
    let centre = r.center();
    drag_with(
        &mut h,
        centre,
        centre + egui::vec2(40.0, 20.0),
        egui::PointerButton::Secondary,
    );
    let param = |h: &Harness<EditorApp>, name: &str| match h
        .state()
        .state
        .doc()
        .node("camera")
        .unwrap()
        .params
        .get(name)
    {
        Some(ron::Value::Number(n)) => Some(n.into_f64()),
        _ => None,
    };
    let across = r.width().min(r.height()) as f64;
    let (pan_x, pan_y) = (param(&h, "pan_x").unwrap(), param(&h, "pan_y").unwrap());
    assert!((pan_x + 40.0 / across).abs() < 1e-3, "pan_x {pan_x}");
    assert!((pan_y - 20.0 / across).abs() < 1e-3, "pan_y {pan_y}");
    assert_eq!(camera_raw(&h, "target"), target, "the target is not panned");
    // The wheel scales `fill`, not `distance`.
    let distance = param(&h, "distance");
    h.event(egui::Event::PointerMoved(centre));
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 50.0),
        modifiers: Modifiers::NONE,
        phase: egui::TouchPhase::Move,
    });
    h.run();
    let fill = param(&h, "fill").expect("the wheel set fill");
    assert!(fill > 0.8, "fill {fill}");
    assert_eq!(param(&h, "distance"), distance);
}

#[test]
fn the_presets_gallery_lists_descriptions_and_applies_a_preset_to_my_data() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    // Thumbnails go to a cache of this test's own.
    app.thumbnail_dir = dir.path().join("thumbnails");
    let mut h = harness(app);
    h.run();
    h.get_by_label("Presets").click();
    // The menu's thumbnail thread keeps repainting: step instead of running until idle.
    for _ in 0..3 {
        h.step();
    }
    h.get_by_label_contains("the MRI brain surface");
    // Thumbnails render off the UI thread, in name order, into the cache: the first one appears.
    let thumbs = dir.path().join("thumbnails");
    let start = std::time::Instant::now();
    let first = loop {
        let found = std::fs::read_dir(&thumbs).ok().and_then(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path())).find(|p| {
                p.file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with("brain_surface-")
            })
        });
        if let Some(found) = found {
            break found;
        }
        assert!(start.elapsed().as_secs() < 120, "no thumbnail after 120 s");
        std::thread::sleep(std::time::Duration::from_millis(50));
        h.step();
    };
    let picture = image::open(&first).unwrap();
    assert_eq!(
        (picture.width(), picture.height()),
        hatchery_editor::gallery::THUMB
    );
    h.run();
    let apply = h
        .get_all_by_label_contains("Apply to my data…")
        .next()
        .expect("an Apply button")
        .rect();
    // Clicked by stepped pointer events: the thumbnail thread and the file dialog that opens
    // keep repainting, so the UI never settles for `run`.
    click_stepped(&mut h, apply.center());
    for _ in 0..5 {
        h.step();
    }
    // The first data preset in name order is brain_surface: it opened, and the dialog asks for
    // its volume.
    let opened = h.state().state.path().unwrap().to_path_buf();
    assert!(
        opened.ends_with("brain_surface.ron"),
        "{}",
        opened.display()
    );
    assert_asks_for(&h, "volume");
}

#[test]
fn an_iso_value_switches_to_a_relative_form_and_takes_one_typed() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "surface");
    let iso = |h: &Harness<EditorApp>| {
        h.state().state.doc().node("surface").unwrap().params["iso"].clone()
    };
    assert!(matches!(iso(&h), ron::Value::Number(n) if n.into_f64() == 0.0));
    // The form menu beside the number: choose otsu.
    let menu = h
        .get_all_by_role(egui::accesskit::Role::ComboBox)
        .find(|n| n.value().as_deref() == Some("value"))
        .expect("the value/relative menu")
        .rect();
    super::selection::click_mod(&mut h, menu.center(), Modifiers::NONE);
    let otsu = h.get_by_label("otsu").rect();
    super::selection::click_mod(&mut h, otsu.center(), Modifiers::NONE);
    assert_eq!(iso(&h), ron::Value::String("otsu".into()));
    // Now a text field: type another form and press Enter.
    let field = h
        .get_all_by_role(Role::TextInput)
        .map(|n| n.rect())
        .find(|r| (r.center().y - menu.center().y).abs() < 8.0)
        .expect("the relative value's text field");
    super::export::type_into(&mut h, field.center(), "percentile(40)");
    assert_eq!(iso(&h), ron::Value::String("percentile(40)".into()));
}
