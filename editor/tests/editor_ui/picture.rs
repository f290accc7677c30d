//! The picture first: beside the canvas in a panel of its own, maximised over the canvas, or the
//! whole window; and its own zoom/pan that leaves the camera alone.

use super::*;
use hatchery_editor::picture::Placement;

#[test]
fn maximise_and_full_window_give_the_picture_the_space() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let beside = h.state().viewport_rect;
    // Beside the canvas: a big panel of its own, not a thumbnail under the Inspector.
    assert!(beside.width() >= 0.3 * 2200.0, "{beside:?}");
    assert!(h.state().canvas_rect.width() > 200.0);

    h.get_by_label("⛶ Maximise").click();
    h.run();
    let maximised = h.state().viewport_rect;
    assert_eq!(h.state().picture.placement, Placement::Maximised);
    assert!(maximised.width() > beside.width() + 200.0, "{maximised:?}");

    h.key_press(Key::F11);
    h.run();
    let full = h.state().viewport_rect;
    assert!(full.width() > 2100.0 && full.height() > 900.0, "{full:?}");
    h.key_press(Key::Escape);
    h.run();
    assert_eq!(h.state().picture.placement, Placement::Beside);
}

#[test]
fn alt_wheel_and_alt_drag_zoom_the_picture_not_the_camera() {
    let dir = tempfile::tempdir().unwrap();
    let (app, _) = open_copy("graphs/shaded_surface.ron", dir.path());
    let mut h = harness(app);
    h.run();
    let before = h.state().state.doc().clone();
    let r = h.state().viewport_rect;
    let at = r.center() + egui::vec2(r.width() * 0.25, 0.0);
    h.event(egui::Event::ModifiersChanged(Modifiers::ALT));
    h.event(egui::Event::PointerMoved(at));
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 200.0),
        modifiers: Modifiers::ALT,
        phase: egui::TouchPhase::Move,
    });
    h.run();
    let zoom = h.state().picture.zoom;
    assert!(zoom > 1.5, "picture zoom {zoom}");
    let centre = h.state().picture.centre;
    assert!(centre.x > 0.5, "zoomed towards the pointer: {centre:?}");
    // Alt-drag moves the picture.
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::ALT,
    });
    h.step();
    for i in 1..=5 {
        h.event(egui::Event::PointerMoved(
            at + egui::vec2(8.0 * i as f32, 0.0),
        ));
        h.step();
    }
    h.event(egui::Event::PointerButton {
        pos: at + egui::vec2(40.0, 0.0),
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::ALT,
    });
    h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
    h.run();
    assert!(
        h.state().picture.centre.x < centre.x,
        "dragged right: the picture follows"
    );
    assert_eq!(h.state().state.doc(), &before, "the camera is untouched");
    h.get_by_label("Fit").click();
    h.run();
    assert_eq!(h.state().picture.zoom, 1.0);
}
