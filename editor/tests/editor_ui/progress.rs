//! Render feedback (issue 24, item 4): a long render says on the picture which node runs and
//! how far its pass is, and a newer edit cancels it at its next node instead of finishing a
//! picture nobody wants.

use super::*;
use hatchery_editor::render_progress;
use hatchery_editor::render_worker::CANCEL_AFTER;

#[test]
fn a_long_render_shows_its_node_and_a_newer_edit_cancels_it() {
    let mri = repo("../shared/data/volumes/mni152_t1.nii.gz")
        .canonicalize()
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _) = open_copy("graphs/tf1d_phong_brain.ron", dir.path());
    let path = ParamValue::Path(mri.to_string_lossy().into_owned());
    app.state.set_param("volume", "path", path, false).unwrap();
    app.preview_enabled = true;
    let mut h = harness(app);
    // Ray casting the MRI with the tricubic B-spline takes seconds on a CPU driver: wait until
    // the render has run long enough to be cancelled, with a node running.
    let start = std::time::Instant::now();
    let seen = loop {
        h.step();
        if let Some((busy, pass)) = h.state().preview.progress()
            && busy >= CANCEL_AFTER
            && pass.current.is_some()
        {
            break (busy, pass);
        }
        assert!(
            start.elapsed().as_secs() < 300,
            "no render running for {CANCEL_AFTER:?} within 300 s"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    };
    let (node, _) = seen.1.current.clone().unwrap();
    assert!(
        seen.1.planned.contains(&node) && h.state().state.doc().nodes.iter().any(|n| n.id == node),
        "the running step {node} is a node of the graph, planned in {:?}",
        seen.1.planned
    );
    // The first render: no earlier time of the node to estimate from.
    assert_eq!(seen.1.estimate, None, "{node} never ran before");
    let (heading, detail) = render_progress::caption(Some(&seen));
    assert!(heading.starts_with("rendering…"), "{heading}");
    let detail = detail.expect("the running node is named");
    assert!(
        detail.starts_with(&format!("{node} (step ")) && !detail.contains("about"),
        "{detail}"
    );
    // A newer edit: orbit the camera. The running render stops at its next node and sends no
    // picture; the newer one is the next (and only) answer.
    let answers = h.state().preview.answers;
    let centre = h.state().viewport_rect.center();
    drag(&mut h, centre, centre + egui::vec2(-30.0, 25.0));
    wait_for_render(&mut h);
    assert_eq!(
        h.state().preview.answers,
        answers + 1,
        "the superseded render sent a picture"
    );
    assert!(
        h.state().preview.viewport.is_some(),
        "{:?}",
        h.state().preview.error
    );
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    // A node that ran before shows its last duration (measured by the Progress: tested in
    // hatchery_nodes::progress) as the estimate.
    let mut again = seen.clone();
    again.1.estimate = Some(std::time::Duration::from_millis(5400));
    let (_, detail) = render_progress::caption(Some(&again));
    let detail = detail.unwrap();
    assert!(detail.ends_with(" of about 5.4 s)"), "{detail}");
}
