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
    let worst = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..4).map(move |c| p[c].abs_diff(q[c])))
        .max()
        .unwrap();
    assert!(
        worst <= 1,
        "the export differs from the CLI render by {worst}/255"
    );
}
