//! A CustomShader node in the editor, through real input: its parameter edited in the
//! Inspector after a click, a live edit of its file re-rendering the picture, a deliberate
//! syntax error shown on the node with file:line:col while the last good picture stays.

use super::*;
use selection::select_by_click;

const RED: &str = "// One colour over the frame.
struct Params {
    level: f32, // default = 0.9, range = 0..1, the colour's strength
}
@group(0) @binding(0) var<uniform> params: Params;

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return vec4<f32>(params.level, 0.0, 0.0, 1.0);
}
";

const GRAPH: &str = r#"(
    version: 2,
    nodes: [
        (id: "tint", kind: "CustomShader", params: {"shader": "tint.wgsl"}, editor: Some((x: 0.0, y: 0.0))),
        (id: "save", kind: "SaveImage", params: {"path": "out.png"}, editor: Some((x: 320.0, y: 0.0))),
    ],
    edges: [(from: ("tint", "image"), to: ("save", "image"))],
)"#;

/// The harness with the window's wgpu device shared with the render thread (as the editor runs
/// on a GPU), so that a screenshot shows the viewport's picture.
pub(super) fn wgpu_harness(mut app: EditorApp) -> Harness<'static, EditorApp> {
    let mut setup = eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = std::sync::Arc::new(hatchery_gpu::GpuContext::device_descriptor);
    Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu_setup(eframe::egui_wgpu::WgpuSetup::CreateNew(setup))
        .build_eframe(move |cc| {
            let rs = cc.wgpu_render_state.clone().expect("a wgpu render state");
            app.preview.set_render_state(rs, true);
            app
        })
}

/// The mean colour of the middle of the viewport, as drawn on screen.
fn viewport_colour(h: &mut Harness<EditorApp>) -> [f32; 3] {
    let shot = h.render().expect("kittest wgpu render");
    let ppp = shot.width() as f32 / 1280.0;
    let c = h.state().viewport_rect.center();
    let (cx, cy) = ((c.x * ppp) as u32, (c.y * ppp) as u32);
    let mut sum = [0.0f32; 3];
    for y in cy - 4..cy + 4 {
        for x in cx - 4..cx + 4 {
            let p = shot.get_pixel(x, y);
            for i in 0..3 {
                sum[i] += p[i] as f32 / 64.0;
            }
        }
    }
    sum
}

/// Steps frames until `done` holds (the file poll and the render run on frames).
pub(super) fn step_until(
    h: &mut Harness<EditorApp>,
    what: &str,
    done: impl Fn(&Harness<EditorApp>) -> bool,
) {
    let start = std::time::Instant::now();
    while !done(h) {
        assert!(start.elapsed().as_secs() < 60, "waited 60 s for {what}");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
}

#[test]
fn a_custom_shader_follows_its_file_live_and_keeps_the_last_picture_on_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let shader = dir.path().join("tint.wgsl");
    std::fs::write(&shader, RED).unwrap();
    let graph = dir.path().join("custom.ron");
    std::fs::write(&graph, GRAPH).unwrap();
    let mut state = EditorState::new();
    state.scratch_dir = dir.path().to_path_buf();
    state.open(&graph).unwrap();
    let mut app = EditorApp::new(state);
    app.preview_enabled = true;
    let mut h = wgpu_harness(app);
    wait_for_render(&mut h);
    assert!(
        h.state().state.errors().is_empty(),
        "{:?}",
        h.state().state.errors()
    );
    assert!(
        h.state().preview.error.is_none(),
        "{:?}",
        h.state().preview.error
    );
    let [r, g, b] = viewport_colour(&mut h);
    assert!(r > 150.0 && g < 30.0 && b < 30.0, "red first: {r} {g} {b}");

    // The shader's uniform member is a parameter in the Inspector: click the node, type 0.3.
    select_by_click(&mut h, "tint");
    h.get_by_label_contains("One colour over the frame.");
    h.get_by_label("level");
    let field = h
        .get_all_by_role(Role::SpinButton)
        .max_by(|a, b| a.rect().left().total_cmp(&b.rect().left()))
        .expect("the level slider's value field in the Inspector");
    field.click();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.event(egui::Event::Text("0.3".into()));
    h.key_press(Key::Enter);
    h.run();
    let node = h
        .state()
        .state
        .doc()
        .nodes
        .iter()
        .find(|n| n.id == "tint")
        .cloned()
        .unwrap();
    assert_eq!(
        node.params.get("level"),
        Some(&ron::Value::Number(ron::Number::new(0.3)))
    );
    wait_for_render(&mut h);
    let [r_dim, _, _] = viewport_colour(&mut h);
    assert!(r_dim < r - 40.0, "level 0.3 is darker: {r_dim} vs {r}");

    // A live edit of the file: red becomes blue, without touching the editor.
    let answers = h.state().preview.answers;
    std::fs::write(
        &shader,
        RED.replace("params.level, 0.0, 0.0, 1.0", "0.0, 0.0, 1.0, 1.0"),
    )
    .unwrap();
    step_until(&mut h, "the re-render after the edit", |h| {
        h.state().preview.answers > answers && !h.state().preview.is_busy()
    });
    h.run_steps(2);
    let [r, _, b] = viewport_colour(&mut h);
    assert!(
        b > 150.0 && r < 30.0,
        "blue after the edit: {r} {b}; status {:?}, revision {}, answers {} → {}",
        h.state().state.status,
        h.state().state.revision(),
        answers,
        h.state().preview.answers
    );

    // A deliberate syntax error: shown on the node (Inspector) with file:line:col, the last
    // good picture stays on screen, the document keeps its wire and parameter.
    std::fs::write(
        &shader,
        RED.replace(
            "return vec4<f32>(params.level",
            "return vec4<f32>(params.level,,",
        ),
    )
    .unwrap();
    step_until(&mut h, "the error on the node", |h| {
        h.state().state.node_error("tint").is_some()
    });
    h.run_steps(3);
    let error = h.state().state.node_error("tint").unwrap().to_owned();
    assert!(error.contains("tint.wgsl:9:"), "{error}");
    // On the canvas node, in the Inspector and in the status line (the node may be off screen).
    assert_eq!(h.get_all_by_label_contains("tint.wgsl:9:").count(), 3);
    assert!(h.state().state.status.starts_with("shader of `tint`: "));
    assert!(h.state().preview.viewport.is_some());
    let [r, _, b] = viewport_colour(&mut h);
    assert!(
        b > 150.0 && r < 30.0,
        "the last good picture stays: {r} {b}"
    );
    assert_eq!(h.state().state.doc().edges.len(), 1);
    // The node keeps its ports (the last good version's), so the wire is still drawn.
    assert!(h.state().node_screen_rect("tint").is_some());

    // Fixed: the error goes, the picture follows the file again.
    std::fs::write(
        &shader,
        RED.replace("params.level, 0.0, 0.0, 1.0", "0.0, params.level, 0.0, 1.0"),
    )
    .unwrap();
    step_until(&mut h, "the error to clear", |h| {
        h.state().state.node_error("tint").is_none()
    });
    wait_for_render(&mut h);
    let [r, g, b] = viewport_colour(&mut h);
    assert!(
        g > 40.0 && r < 30.0 && b < 30.0,
        "green at level 0.3: {r} {g} {b}"
    );

    // The uniform renamed in the file: the graph stays valid, the stored `level` is kept but
    // unused, listed in the Inspector with a button that removes it.
    h.state_mut().state.status.clear();
    std::fs::write(&shader, RED.replace("level", "strength")).unwrap();
    step_until(&mut h, "the rename to be read", |h| {
        h.state().state.status.contains("read it again")
    });
    h.run_steps(3);
    assert!(h.state().state.node_error("tint").is_none());
    h.get_by_label_contains("Not declared by the shader any more");
    let stored = |h: &Harness<EditorApp>| {
        let doc = h.state().state.doc();
        doc.node("tint").unwrap().params.contains_key("level")
    };
    assert!(stored(&h));
    let at = h.get_by_label("✕ Remove").rect().center();
    selection::click_mod(&mut h, at, Modifiers::NONE);
    assert!(!stored(&h), "removed from the document");
}
