//! Selection by the mouse, through pointer and key events at screen positions (the path a user
//! takes), never by writing `EditorState::selection`.

use super::*;
use std::collections::BTreeSet;

/// Presses and releases the primary button at `at` with `modifiers` held (sent as a real window
/// sends them: a modifier change, then the button events, then the release of the modifier).
pub fn click_mod(h: &mut Harness<EditorApp>, at: egui::Pos2, modifiers: Modifiers) {
    h.event(egui::Event::ModifiersChanged(modifiers));
    h.event(egui::Event::PointerMoved(at));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers,
        });
        h.step();
    }
    h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
    h.run();
}

/// The screen rectangle of node `id` as drawn.
pub fn node_rect(h: &Harness<EditorApp>, id: &str) -> egui::Rect {
    h.state()
        .node_screen_rect(id)
        .unwrap_or_else(|| panic!("node {id} is not on screen"))
}

/// The centre of node `id`'s title text on the canvas, on screen (the canvas label with that
/// text: the Inspector shows the same title on the right). Canvas labels are reported in graph
/// space, so the canvas transform takes them to the screen.
pub fn title_pos(h: &Harness<EditorApp>, id: &str) -> egui::Pos2 {
    let kind = h
        .state()
        .state
        .doc()
        .nodes
        .iter()
        .find(|n| n.id == id)
        .unwrap()
        .kind
        .clone();
    let graph = h
        .get_all_by_label(&format!("{id} ({kind})"))
        .map(|n| n.rect())
        .min_by(|a, b| a.left().total_cmp(&b.left()))
        .unwrap()
        .center();
    let at = h.state().canvas_transform * graph;
    assert_eq!(h.state().node_at(at), Some(id), "title of {id} is covered");
    assert!(
        h.state().canvas_rect.contains(at),
        "title of {id} is off the canvas"
    );
    at
}

/// A point in the lower part of node `id`'s body (below its title), checked to be on that node.
pub fn body_pos(h: &Harness<EditorApp>, id: &str) -> egui::Pos2 {
    let r = node_rect(h, id);
    let p = egui::pos2(r.center().x, r.bottom() - 6.0);
    assert_eq!(
        h.state().node_at(p),
        Some(id),
        "body point of {id} is covered"
    );
    p
}

/// Selects node `id` by clicking its title.
pub fn select_by_click(h: &mut Harness<EditorApp>, id: &str) {
    let at = title_pos(h, id);
    click_mod(h, at, Modifiers::NONE);
    assert_eq!(selection(h), set(&[id]), "clicking {id}'s title selects it");
}

pub fn selection(h: &Harness<EditorApp>) -> BTreeSet<String> {
    h.state().state.selection.clone()
}

pub fn set(ids: &[&str]) -> BTreeSet<String> {
    ids.iter().map(|s| s.to_string()).collect()
}

/// A canvas point on no node (scanning the canvas on a grid).
pub fn empty_canvas_point(h: &Harness<EditorApp>) -> egui::Pos2 {
    let canvas = h.state().canvas_rect.shrink(10.0);
    for y in (canvas.top() as i32..canvas.bottom() as i32).step_by(20) {
        for x in (canvas.left() as i32..canvas.right() as i32).step_by(20) {
            let p = egui::pos2(x as f32, y as f32);
            if h.state().node_at(p).is_none() {
                return p;
            }
        }
    }
    panic!("no empty canvas point");
}

#[test]
fn clicking_a_node_title_or_body_selects_it_and_the_inspector_edits_it() {
    let dir = tempfile::tempdir().unwrap();
    let (app, path) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    h.get_by_label("Click a node to edit its parameters.");

    // Title click.
    select_by_click(&mut h, "surface");
    // The Inspector shows it: its title twice (canvas + Inspector heading).
    assert_eq!(
        h.get_all_by_label("surface (MarchingCubes)").count(),
        2,
        "the Inspector shows the clicked node"
    );

    // Body click on another node moves the selection.
    let p = body_pos(&h, "camera");
    click_mod(&mut h, p, Modifiers::NONE);
    assert_eq!(selection(&h), set(&["camera"]));
    assert_eq!(h.get_all_by_label("camera (Camera)").count(), 2);
    assert_eq!(h.get_all_by_label("surface (MarchingCubes)").count(), 1);

    // Edit a parameter of the clicked node through the Inspector: select the marching cubes
    // node, then type a new iso value into its field (a click on the slider's number, text,
    // Enter) and save with Ctrl+S.
    select_by_click(&mut h, "surface");
    let iso = |h: &Harness<EditorApp>| {
        let doc = h.state().state.doc();
        let node = doc.nodes.iter().find(|n| n.id == "surface").unwrap();
        node.params.get("iso").cloned()
    };
    let iso_before = iso(&h);
    let field = h
        .get_all_by_role(Role::SpinButton)
        .find(|n| n.rect().left() > 900.0)
        .expect("the iso slider's value field in the Inspector");
    field.click();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.event(egui::Event::Text("0.42".into()));
    h.key_press(Key::Enter);
    h.run();
    let iso_after = iso(&h);
    assert_ne!(iso_before, iso_after);
    assert_eq!(iso_after, Some(ron::Value::Number(ron::Number::new(0.42))));
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run();
    let saved = std::fs::read_to_string(&path).unwrap();
    assert!(saved.contains("\"iso\": 0.42"), "saved file:\n{saved}");
}

#[test]
fn shift_click_adds_ctrl_click_toggles_empty_click_and_escape_clear() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "surface");
    let p = title_pos(&h, "shaded");
    click_mod(&mut h, p, Modifiers::SHIFT);
    assert_eq!(selection(&h), set(&["surface", "shaded"]));
    // The Inspector follows the last click and says how many are selected.
    assert_eq!(h.get_all_by_label("shaded (ShadedSurface)").count(), 2);
    h.get_by_label_contains("2 nodes selected");
    let p = title_pos(&h, "camera");
    click_mod(&mut h, p, Modifiers::SHIFT);
    assert_eq!(selection(&h), set(&["surface", "shaded", "camera"]));
    // Ctrl-click toggles off, and on again.
    let p = title_pos(&h, "shaded");
    click_mod(&mut h, p, Modifiers::COMMAND);
    assert_eq!(selection(&h), set(&["surface", "camera"]));
    click_mod(&mut h, p, Modifiers::COMMAND);
    assert_eq!(selection(&h), set(&["surface", "camera", "shaded"]));
    // A plain click on empty canvas clears.
    let empty = empty_canvas_point(&h);
    click_mod(&mut h, empty, Modifiers::NONE);
    assert!(selection(&h).is_empty());
    h.get_by_label("Click a node to edit its parameters.");
    // Esc clears too.
    select_by_click(&mut h, "light");
    h.key_press(Key::Escape);
    h.run();
    assert!(selection(&h).is_empty());
}

#[test]
fn shift_drag_on_empty_canvas_box_selects_without_panning() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    // A box around two nodes, started on empty canvas just outside their union.
    let (a, b) = (node_rect(&h, "shells"), node_rect(&h, "surface"));
    let union = a.union(b);
    let from = union.min - egui::vec2(8.0, 8.0);
    let to = union.max + egui::vec2(4.0, 4.0);
    assert!(h.state().node_at(from).is_none(), "box start must be empty");
    let transform = h.state().canvas_transform;
    // Which nodes the box touches, from the drawn rectangles.
    let area = egui::Rect::from_two_pos(from, to);
    let expected: BTreeSet<String> = h
        .state()
        .state
        .doc()
        .nodes
        .iter()
        .filter(|n| {
            h.state()
                .node_screen_rect(&n.id)
                .is_some_and(|r| r.intersects(area))
        })
        .map(|n| n.id.clone())
        .collect();
    assert!(expected.contains("shells") && expected.contains("surface"));

    h.event(egui::Event::ModifiersChanged(Modifiers::SHIFT));
    h.event(egui::Event::PointerMoved(from));
    h.event(egui::Event::PointerButton {
        pos: from,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::SHIFT,
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
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::SHIFT,
    });
    h.step();
    h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
    h.run();
    assert_eq!(selection(&h), expected);
    assert_eq!(
        h.state().canvas_transform,
        transform,
        "a box drag must not pan the canvas"
    );
}

#[test]
fn dragging_a_selected_node_moves_the_selection_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    select_by_click(&mut h, "shells");
    let p = title_pos(&h, "light");
    click_mod(&mut h, p, Modifiers::SHIFT);
    let before = h.state().state.doc().clone();
    let pos_of = |h: &Harness<EditorApp>, id: &str| {
        let n = h.state().state.doc().nodes.iter().find(|n| n.id == id);
        n.and_then(|n| n.editor).map(|p| egui::vec2(p.x, p.y))
    };
    let (shells0, light0, camera0) = (
        pos_of(&h, "shells").unwrap(),
        pos_of(&h, "light").unwrap(),
        pos_of(&h, "camera"),
    );
    let from = title_pos(&h, "shells");
    drag(&mut h, from, from + egui::vec2(60.0, 30.0));
    let scale = h.state().canvas_transform.scaling;
    let moved = |h: &Harness<EditorApp>, id: &str, start: egui::Vec2| {
        (pos_of(h, id).unwrap() - start) * scale
    };
    for (id, start) in [("shells", shells0), ("light", light0)] {
        let d = moved(&h, id, start);
        assert!(
            (d - egui::vec2(60.0, 30.0)).length() < 2.0,
            "{id} moved by {d:?} on screen"
        );
    }
    assert_eq!(pos_of(&h, "camera"), camera0, "unselected nodes stay");
    assert_eq!(selection(&h), set(&["shells", "light"]));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().state.doc(), &before, "one undo step");
}
