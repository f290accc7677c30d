//! The add-node palette driven as a user does: a right-click (or a wire dropped on empty
//! canvas), then typing and keys with nothing focused by the test, and pointer clicks at the
//! positions the palette's items are drawn.

use super::selection::{click_mod, empty_canvas_point};
use super::*;
use hatchery_editor::add_menu;

/// The screen rectangle of the palette's search field: the text field on the canvas (the
/// Inspector's are beside it).
fn search_field(h: &Harness<EditorApp>) -> egui::Rect {
    let canvas = h.state().canvas_rect;
    h.get_all_by_role(Role::TextInput)
        .map(|n| n.rect())
        .find(|r| canvas.contains(r.center()))
        .expect("a search field on the canvas")
}

/// The screen rectangle of the palette's item `name` (`search` or a kind), as drawn last frame.
/// The palette is a foreground area in screen space, so its labels' rects are screen points.
fn item(h: &Harness<EditorApp>, label: &str) -> egui::Rect {
    let canvas = h.state().canvas_rect;
    h.get_all_by_label(label)
        .map(|n| n.rect())
        .find(|r| canvas.contains(r.center()) && r.width() < 400.0)
        .unwrap_or_else(|| panic!("{label} is not in the palette"))
}

fn type_text(h: &mut Harness<EditorApp>, text: &str) {
    h.event(egui::Event::Text(text.to_owned()));
    h.run();
}

fn kinds_of(h: &Harness<EditorApp>, kind: &str) -> Vec<String> {
    let doc = h.state().state.doc();
    doc.nodes
        .iter()
        .filter(|n| n.kind == kind)
        .map(|n| n.id.clone())
        .collect()
}

/// Right-click on empty canvas and type at once: the list filters, Enter adds the first match
/// where the menu opened.
#[test]
fn right_click_type_and_enter_adds_the_first_match() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let at = empty_canvas_point(&h);
    right_click_at(&h, at);
    h.run();
    assert!(h.state().add_menu.is_some(), "the palette opened");
    h.get_by_label("Camera");
    type_text(&mut h, "silh");
    assert!(
        h.query_by_label("Camera").is_none(),
        "filtered out by the search"
    );
    let kinds = h.state().state.registry.kinds();
    let first = add_menu::matches(&kinds, "silh")[0];
    assert_eq!(
        first, "Silhouette",
        "a name starting with the search comes first"
    );
    h.key_press(Key::Enter);
    h.run();
    assert!(h.state().add_menu.is_none(), "closed after adding");
    assert_eq!(kinds_of(&h, "Silhouette"), ["silhouette_1"]);
    let placed = h
        .state()
        .state
        .doc()
        .nodes
        .iter()
        .find(|n| n.id == "silhouette_1");
    let p = placed.unwrap().editor.expect("placed on the canvas");
    let screen = h.state().canvas_transform * egui::pos2(p.x, p.y);
    assert!(
        screen.distance(at) < 40.0,
        "added at {screen:?}, menu opened at {at:?}"
    );
    assert_eq!(h.get_all_by_label("silhouette_1 (Silhouette)").count(), 2);
}

/// ↓ moves the highlight; clicking the search field keeps the palette (and the typing) alive;
/// clicking a listed kind adds it.
#[test]
fn arrow_keys_move_and_clicks_in_the_palette_do_not_close_it() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    right_click_at(&h, empty_canvas_point(&h));
    h.run();
    let search = search_field(&h);
    click_mod(&mut h, search.center(), Modifiers::NONE);
    assert!(
        h.state().add_menu.is_some(),
        "a click in the search field keeps it open"
    );
    type_text(&mut h, "curv");
    let kinds = h.state().state.registry.kinds();
    let found = add_menu::matches(&kinds, "curv");
    assert!(found.len() >= 2, "{found:?}");
    h.key_press(Key::ArrowDown);
    h.run();
    assert_eq!(h.state().add_menu.as_ref().unwrap().highlight, 1);
    h.key_press(Key::ArrowDown);
    h.key_press(Key::ArrowUp);
    h.run();
    assert_eq!(h.state().add_menu.as_ref().unwrap().highlight, 1);
    h.key_press(Key::Enter);
    h.run();
    assert_eq!(
        kinds_of(&h, found[1]).len(),
        1,
        "the highlighted kind was added"
    );

    // A pointer click on a listed kind adds that one.
    right_click_at(&h, empty_canvas_point(&h));
    h.run();
    type_text(&mut h, "gbuf");
    let r = item(&h, "GBuffer");
    let before = kinds_of(&h, "GBuffer").len();
    click_mod(&mut h, r.center(), Modifiers::NONE);
    assert_eq!(kinds_of(&h, "GBuffer").len(), before + 1);
    assert!(h.state().add_menu.is_none());
}

/// Escape and a click outside close the palette without adding anything.
#[test]
fn escape_or_a_click_outside_closes_the_palette_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let before = h.state().state.doc().clone();
    right_click_at(&h, empty_canvas_point(&h));
    h.run();
    type_text(&mut h, "silh");
    h.key_press(Key::Escape);
    h.run();
    assert!(h.state().add_menu.is_none());
    right_click_at(&h, empty_canvas_point(&h));
    h.run();
    let rect = search_field(&h);
    let outside = egui::pos2(h.state().canvas_rect.right() - 20.0, rect.center().y);
    click_mod(&mut h, outside, Modifiers::NONE);
    assert!(h.state().add_menu.is_none(), "closed by a click outside");
    assert_eq!(h.state().state.doc(), &before, "nothing added");
}

/// A wire dropped on empty canvas opens the palette with the kinds that take it; typing and
/// Enter add one wired to the dragged output.
#[test]
fn a_dropped_wire_opens_the_palette_and_the_added_node_takes_the_wire() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let t = h.state().canvas_transform;
    let volume = port_label(&h, "shells", "volume"); // an output
    let from = t * egui::pos2(volume.right() + 14.0, volume.center().y);
    let to = empty_canvas_point(&h);
    drag_steps(&mut h, from, to, egui::PointerButton::Primary);
    h.run_steps(3);
    h.get_by_label("Add a node taking Volume");
    assert!(h.query_by_label("Light").is_none(), "Light takes no volume");
    h.get_by_label("MarchingCubes");
    type_text(&mut h, "march");
    h.key_press(Key::Enter);
    h.run();
    assert_eq!(kinds_of(&h, "MarchingCubes").len(), 2);
    let edge = hatchery_graph::EdgeDoc {
        from: ("shells".into(), "volume".into()),
        to: ("marching_cubes_1".into(), "volume".into()),
    };
    let doc = h.state().state.doc();
    assert!(
        doc.edges.contains(&edge),
        "{:?} / {:?}",
        doc.edges,
        kinds_of(&h, "MarchingCubes")
    );
}
