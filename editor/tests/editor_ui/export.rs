//! *File → Export image…* through clicks and typing: the PNG equals what `hatchery render -o`
//! writes for the same graph and size.

use super::*;
use hatchery_nodes::Session;

/// Clicks a numeric or text field and replaces its text.
pub fn type_into(h: &mut Harness<EditorApp>, at: egui::Pos2, text: &str) {
    selection::click_mod(h, at, Modifiers::NONE);
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.event(egui::Event::Text(text.into()));
    h.key_press(Key::Enter);
    h.run();
}

#[test]
fn export_image_writes_what_the_command_line_renders() {
    let dir = tempfile::tempdir().unwrap();
    let (app, graph) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    h.get_by_label("File").click();
    h.run();
    h.get_by_label("Export image…").click();
    h.run();
    // The dialog opens below the menu bar, not over it.
    let menu_bottom = h.get_by_label("File").rect().bottom();
    let title = h.get_by_label("Export image").rect();
    assert!(
        title.top() > menu_bottom + 10.0,
        "dialog title at {title:?}, menu bar ends at {menu_bottom}"
    );
    // The port defaults to what the graph saves.
    assert_eq!(
        h.state().export.port,
        Some(("shaded".to_string(), "image".to_string()))
    );
    let mut fields: Vec<egui::Rect> = h
        .get_all_by_role(Role::SpinButton)
        .map(|n| n.rect())
        .collect();
    fields.sort_by(|a, b| a.top().total_cmp(&b.top()));
    assert_eq!(fields.len(), 2, "width and height fields");
    type_into(&mut h, fields[0].center(), "160");
    type_into(&mut h, fields[1].center(), "120");
    let file = h.get_by_role(Role::TextInput).rect().center();
    type_into(&mut h, file, "exported.png");
    h.get_by_label("Export").click();
    let start = std::time::Instant::now();
    while h.state().export.is_busy() || h.state().export.last.is_none() {
        assert!(start.elapsed().as_secs() < 300, "no export after 300 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    let written = dir.path().join("exported.png");
    assert_eq!(h.state().export.last, Some(Ok(written.clone())));
    h.run();
    // The dialog and the status line both say so.
    assert!(h.get_all_by_label_contains("exported.png").count() >= 2);

    // What `hatchery render graph -o cli.png --size 160x120` does.
    let cli = dir.path().join("cli.png");
    let mut session = Session::open(&graph, 160, 120).unwrap();
    session
        .set_param_text("save", "path", &cli.to_string_lossy())
        .unwrap();
    session.run(&["save"]).unwrap();
    let a = image::open(&written).unwrap().to_rgba8();
    let b = image::open(&cli).unwrap().to_rgba8();
    assert_eq!(a.dimensions(), (160, 120));
    assert_eq!(a.dimensions(), b.dimensions());
    let worst = worst(&a, &b);
    assert!(
        worst <= 1,
        "the export differs from the CLI render by {worst}/255"
    );
}

/// Exports `file` at `size` through the dialog's fields and waits for it.
fn export_through_dialog(h: &mut Harness<EditorApp>, size: [u32; 2], file: &str) {
    let mut fields: Vec<egui::Rect> = h
        .get_all_by_role(Role::SpinButton)
        .map(|n| n.rect())
        .collect();
    fields.sort_by(|a, b| a.top().total_cmp(&b.top()));
    type_into(h, fields[0].center(), &size[0].to_string());
    type_into(h, fields[1].center(), &size[1].to_string());
    let at = h.get_by_role(Role::TextInput).rect().center();
    type_into(h, at, file);
    h.get_by_label("Export").click();
    h.step();
    let start = std::time::Instant::now();
    while h.state().export.is_busy() {
        assert!(start.elapsed().as_secs() < 300, "no export after 300 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
    assert!(
        matches!(&h.state().export.last, Some(Ok(p)) if p.ends_with(file)),
        "export of {file}: {:?}",
        h.state().export.last
    );
}

/// The largest channel difference between two pictures of one size.
fn worst(a: &image::RgbaImage, b: &image::RgbaImage) -> u8 {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..4).map(move |c| p[c].abs_diff(q[c])))
        .max()
        .unwrap()
}

#[test]
fn an_export_at_twice_the_screen_size_is_the_figure_on_screen_scaled() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, graph) = open_copy("graphs/default.ron", dir.path());
    app.preview_enabled = true;
    let mut h = harness(app);
    wait_for_render(&mut h);
    let [w, h0] = h
        .state()
        .preview
        .viewport
        .as_ref()
        .expect("a picture")
        .size();
    h.get_by_label("File").click();
    h.run();
    h.get_by_label("Export image…").click();
    h.run();
    // On by default: hatching, lines and labels scale with the size.
    h.get_by_label_contains("as on screen").rect();
    let twice = [2 * w, 2 * h0];
    export_through_dialog(&mut h, twice, "scaled.png");
    h.get_by_label_contains("as on screen").click();
    h.run();
    assert!(!h.state().export.as_on_screen, "the click unticks the box");
    export_through_dialog(&mut h, twice, "plain.png");

    // What `hatchery render --size {w}x{h} --scale 2` and `--size {2w}x{2h}` render.
    let (node, port) = h.state().export.port.clone().unwrap();
    let cli = |scale: f64, name: &str| {
        let path = dir.path().join(name);
        let mut session = Session::open(&graph, twice[0], twice[1]).unwrap();
        session.ctx.set_pixel_scale(scale);
        session.export_png(&node, &port, &path).unwrap();
        image::open(&path).unwrap().to_rgba8()
    };
    let read = |name: &str| image::open(dir.path().join(name)).unwrap().to_rgba8();
    let (scaled, plain) = (read("scaled.png"), read("plain.png"));
    assert_eq!(scaled.dimensions(), (twice[0], twice[1]));
    assert!(
        worst(&scaled, &cli(2.0, "cli_scaled.png")) <= 1,
        "as on screen = --scale 2"
    );
    assert!(
        worst(&plain, &cli(1.0, "cli_plain.png")) <= 1,
        "unticked = no scale"
    );
    assert!(
        worst(&scaled, &plain) > 128,
        "the scale changed the hatching"
    );
}
