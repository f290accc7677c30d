//! Fused image-space passes seen from the editor: node times name the pass a node ran in, and
//! pinning an inner output of a pass shows it by re-running only what leads to it inside the
//! pass (the editor's passes write the outputs an edited member needs, not every inner one:
//! `Executor::set_keep_fused`).

use super::*;
use selection::{click_mod, node_rect};

/// The screen position of node `id`'s output label `port` (the rightmost such label on it).
fn output_label(h: &Harness<EditorApp>, id: &str, port: &str) -> egui::Pos2 {
    let node = node_rect(h, id);
    h.get_all_by_label(port)
        .map(|n| h.state().canvas_transform * n.rect().center())
        .filter(|p| node.contains(*p))
        .max_by(|a, b| a.x.total_cmp(&b.x))
        .unwrap_or_else(|| panic!("no {port} label on {id}"))
}

#[test]
fn node_times_name_the_fused_pass_and_a_pinned_inner_output_shows_after_a_small_rerun() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/hidden_structures.ron", dir.path());
    app.preview_enabled = true;
    // Wide enough that the framed canvas shows every node of the preset at a legible zoom.
    let mut h = Harness::builder()
        .with_size([5200.0, 1300.0])
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app);
    wait_for_render(&mut h);
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    h.get_by_label("Node times").click();
    wait_for_render(&mut h);

    // A new paper colour re-runs the image-space chain below it as one pass.
    h.state_mut()
        .state
        .set_param(
            "paper",
            "color",
            ParamValue::Color([0.9, 0.85, 0.7, 1.0]),
            false,
        )
        .unwrap();
    wait_for_render(&mut h);
    let times = h.state().preview.times.clone();
    let inner = &times["with_secondary"];
    let carrier = inner
        .fused_into
        .clone()
        .unwrap_or_else(|| panic!("with_secondary ran in a pass of its own: {times:?}"));
    assert!(!inner.cached, "{times:?}");
    let pass = &times[&carrier];
    assert!(
        !pass.cached && pass.fused_into.is_none() && pass.gpu.is_some(),
        "the pass's times are on {carrier}: {times:?}"
    );
    assert!(
        times["layer1"].cached && times["layer2"].cached,
        "{times:?}"
    );
    // What the node shows, as drawn on the canvas.
    let label = format!("⏱ in {carrier}'s pass");
    assert!(
        h.get_all_by_label(&label).count() >= 2,
        "no '{label}' label"
    );

    // The pass did not write its inner output (no member before it was edited): pinning it
    // re-runs the members that lead to it, in a pass of their own, and nothing else.
    // Nodes take their new size a frame after their content changes: let them settle.
    h.run_steps(3);
    let at = output_label(&h, "with_secondary", "image");
    click_mod(&mut h, at, Modifiers::NONE);
    let port = ("with_secondary".to_string(), "image".to_string());
    assert!(
        h.state().preview.pins.contains(&port),
        "the click pinned it"
    );
    wait_for_render(&mut h);
    assert!(
        h.state().preview.thumbnails.contains_key(&port),
        "a thumbnail"
    );
    let times = h.state().preview.times.clone();
    assert!(!times["with_secondary"].cached, "{times:?}");
    for node in [
        "front_lines",
        "front_hatching",
        "paper",
        "layer1",
        "secondary_final",
    ] {
        assert!(times[node].cached, "{node} re-ran: {times:?}");
    }
}
