//! Fused image-space passes compute exactly what the nodes compute one pass each: every fusable
//! kind and every constant it folds, in one graph; and every preset.

mod common;

use hatchery_nodes::raycast::Kernel;
use hatchery_nodes::{Session, Value, export};

/// Every fusable kind, every Silhouette PIP mode but `texture`, both switches, all six mask
/// operations, MixByMask with and without an `over` image, an inverted MultiplyByMask,
/// two-sided lighting, a depth test, Over — on two depth layers of the engine block.
const ALL_KINDS: &str = r#"(
    version: 2,
    nodes: [
        (id: "block", kind: "ProceduralVolume", params: {"resolution": 48, "shape": "engine_block"}),
        (id: "surface", kind: "MarchingCubes", params: {"iso": 0.0}),
        (id: "camera", kind: "Camera", params: {"azimuth": 35.0, "distance": 3.4, "elevation": 25.0}),
        (id: "light", kind: "Light", params: {"direction": [-0.3, 0.6, 1.0]}),
        (id: "layer1", kind: "GBuffer", params: {}),
        (id: "layer2", kind: "DepthPeel", params: {}),
        (id: "paper", kind: "Fill", params: {"color": [1.0, 0.95, 0.9, 1.0]}),
        (id: "sil_none", kind: "Silhouette", params: {}),
        (id: "sil_constant", kind: "Silhouette", params: {"pip": "constant", "pip_amount": 1.7}),
        (id: "sil_noise", kind: "Silhouette", params: {"pip": "noise", "pip_amount": 2.5, "pip_seed": 3}),
        (id: "sil_dots", kind: "Silhouette", params: {"pip": "dots", "pip_scale": 6.0, "use_depth": false}),
        (id: "sil_depth", kind: "Silhouette", params: {"use_normals": false, "depth_threshold": 0.002}),
        (id: "lit", kind: "DiffuseIntensity", params: {"two_sided": true}),
        (id: "lit2", kind: "DiffuseIntensity", params: {"empty": 0.25}),
        (id: "screen", kind: "Halftone", params: {"theta": 33.0, "cell": 5.0, "c_cross": 0.6}),
        (id: "c_and", kind: "MaskCombine", params: {"operation": "and"}),
        (id: "c_or", kind: "MaskCombine", params: {"operation": "or"}),
        (id: "c_min", kind: "MaskCombine", params: {"operation": "min"}),
        (id: "c_add", kind: "MaskCombine", params: {"operation": "add"}),
        (id: "c_sub", kind: "MaskCombine", params: {"operation": "subtract"}),
        (id: "c_not", kind: "MaskCombine", params: {"operation": "a_not_b"}),
        (id: "behind", kind: "DepthTestMask", params: {"compare": "a<b"}),
        (id: "gate", kind: "MaskCombine", params: {"operation": "or"}),
        (id: "tint", kind: "MixByMask", params: {"color": [0.2, 0.4, 0.9, 0.7]}),
        (id: "blend", kind: "MixByMask", params: {}),
        (id: "ink", kind: "MultiplyByMask", params: {"invert": true}),
        (id: "shade", kind: "MultiplyByMask", params: {}),
        (id: "final", kind: "Over", params: {}),
    ],
    edges: [
        (from: ("block", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("layer1", "mesh")),
        (from: ("camera", "camera"), to: ("layer1", "camera")),
        (from: ("surface", "mesh"), to: ("layer2", "mesh")),
        (from: ("camera", "camera"), to: ("layer2", "camera")),
        (from: ("layer1", "gbuffer"), to: ("layer2", "previous")),
        (from: ("layer1", "gbuffer"), to: ("sil_none", "gbuffer")),
        (from: ("layer1", "gbuffer"), to: ("sil_constant", "gbuffer")),
        (from: ("layer2", "gbuffer"), to: ("sil_noise", "gbuffer")),
        (from: ("layer1", "gbuffer"), to: ("sil_dots", "gbuffer")),
        (from: ("layer2", "gbuffer"), to: ("sil_depth", "gbuffer")),
        (from: ("layer1", "gbuffer"), to: ("lit", "gbuffer")),
        (from: ("light", "light"), to: ("lit", "light")),
        (from: ("layer2", "gbuffer"), to: ("lit2", "gbuffer")),
        (from: ("light", "light"), to: ("lit2", "light")),
        (from: ("lit", "intensity"), to: ("screen", "intensity")),
        (from: ("sil_none", "mask"), to: ("c_and", "a")),
        (from: ("sil_constant", "mask"), to: ("c_and", "b")),
        (from: ("c_and", "mask"), to: ("c_or", "a")),
        (from: ("sil_noise", "mask"), to: ("c_or", "b")),
        (from: ("c_or", "mask"), to: ("c_min", "a")),
        (from: ("screen", "mask"), to: ("c_min", "b")),
        (from: ("c_min", "mask"), to: ("c_add", "a")),
        (from: ("sil_dots", "mask"), to: ("c_add", "b")),
        (from: ("c_add", "mask"), to: ("c_sub", "a")),
        (from: ("sil_depth", "mask"), to: ("c_sub", "b")),
        (from: ("c_sub", "mask"), to: ("c_not", "a")),
        (from: ("lit2", "intensity"), to: ("c_not", "b")),
        (from: ("paper", "image"), to: ("tint", "base")),
        (from: ("layer2", "gbuffer"), to: ("behind", "a")),
        (from: ("layer1", "gbuffer"), to: ("behind", "b")),
        (from: ("c_not", "mask"), to: ("gate", "a")),
        (from: ("behind", "mask"), to: ("gate", "b")),
        (from: ("gate", "mask"), to: ("tint", "mask")),
        (from: ("paper", "image"), to: ("blend", "base")),
        (from: ("lit2", "intensity"), to: ("blend", "mask")),
        (from: ("tint", "image"), to: ("blend", "over")),
        (from: ("blend", "image"), to: ("ink", "image")),
        (from: ("sil_none", "mask"), to: ("ink", "mask")),
        (from: ("ink", "image"), to: ("shade", "image")),
        (from: ("lit", "intensity"), to: ("shade", "mask")),
        (from: ("shade", "image"), to: ("final", "front")),
        (from: ("tint", "image"), to: ("final", "back")),
    ],
)"#;

const W: u32 = 200;
const H: u32 = 150;

/// Every channel of `node.port` as f32, from a session that has run it.
fn pixels(session: &Session, node: &str, port: &str) -> Vec<f32> {
    let value = session
        .output(node, port)
        .unwrap_or_else(|e| panic!("{node}.{port}: {e}"));
    export::to_array(value, &session.ctx.gpu).unwrap().data
}

/// Fails naming the worst value unless the images of `channels` values a pixel are bit for bit
/// equal.
fn assert_identical(what: &str, fused: &[f32], alone: &[f32], channels: u32) {
    common::assert_images_identical(what, fused, alone, W * channels);
}

#[test]
fn every_fusable_kind_in_one_pass_equals_the_nodes_one_pass_each() {
    let mut fused = common::session_from_text(ALL_KINDS, W, H);
    let mut alone = common::session_from_text(ALL_KINDS, W, H);
    alone.executor.set_fusion(false);
    fused.run(&["final"]).unwrap();
    alone.run(&["final"]).unwrap();

    // The whole image-space part ran as one pass (the 21 nodes below the G-buffers).
    let pass = &fused.executor.stats()["final"].fused_with;
    assert_eq!(pass.len(), 21, "{pass:?}");
    assert!(alone.executor.stats()["final"].fused_with.is_empty());
    assert_identical(
        "final",
        &pixels(&fused, "final", "image"),
        &pixels(&alone, "final", "image"),
        4,
    );
    // Not blank: the test would pass on two empty pictures.
    let final_pixels = pixels(&fused, "final", "image");
    let distinct: std::collections::BTreeSet<u32> =
        final_pixels.iter().map(|v| v.to_bits()).collect();
    assert!(distinct.len() > 50, "{} distinct values", distinct.len());

    // An intermediate node's output was not written; asking for it says why and what to do.
    let Err(error) = fused.output("c_or", "mask") else {
        panic!("c_or's output was written although nothing outside the pass read it");
    };
    let message = error.to_string();
    assert!(
        message.contains("fused pass") && message.contains("run `c_or` as a target"),
        "{message}"
    );

    // Intermediate nodes as targets: one pass writes several outputs (colour targets).
    let targets = ["final", "c_or", "screen", "blend"];
    fused.run(&targets).unwrap();
    alone.run(&targets).unwrap();
    for (node, port, channels) in [
        ("c_or", "mask", 1),
        ("screen", "mask", 1),
        ("blend", "image", 4),
        ("final", "image", 4),
    ] {
        assert_identical(
            node,
            &pixels(&fused, node, port),
            &pixels(&alone, node, port),
            channels,
        );
    }
    assert!(
        fused.executor.stats()["c_or"].fused_with.len() > 1,
        "c_or ran in a fused pass"
    );
}

/// The compute kernel (what adapters with a small graphics part use) computes what the fragment
/// shader does: masks bit for bit; images to within one binary16 step (storage writes may round
/// where colour targets truncate).
#[test]
fn the_compute_kernel_of_a_fused_pass_equals_its_fragment_shader() {
    let mut fragment = common::session_from_text(ALL_KINDS, W, H);
    fragment.ctx.set_image_kernel(Kernel::Fragment);
    let mut compute = common::session_from_text(ALL_KINDS, W, H);
    compute.ctx.set_image_kernel(Kernel::Compute);
    let targets = ["final", "c_or", "screen", "blend"];
    fragment.run(&targets).unwrap();
    compute.run(&targets).unwrap();
    assert!(compute.executor.stats()["final"].fused_with.len() > 1);
    for (node, port) in [("c_or", "mask"), ("screen", "mask")] {
        assert_identical(
            node,
            &pixels(&compute, node, port),
            &pixels(&fragment, node, port),
            1,
        );
    }
    for (node, port) in [("blend", "image"), ("final", "image")] {
        let (c, f) = (pixels(&compute, node, port), pixels(&fragment, node, port));
        assert_eq!(c.len(), f.len());
        let worst = c
            .iter()
            .zip(&f)
            .map(|(a, b)| (a - b).abs() / a.abs().max(b.abs()).max(6.1e-5))
            .fold(0.0f32, f32::max);
        assert!(
            worst <= 1.0 / 1024.0,
            "{node}: compute and fragment differ by {worst} (relative)"
        );
    }
}

#[test]
fn every_preset_renders_the_same_fused_and_unfused() {
    let presets = common::presets();
    let mut with_fused_passes = Vec::new();
    for path in presets {
        let mut fused = Session::open(&path, 160, 120).unwrap();
        let fusable = fused
            .graph
            .nodes()
            .any(|n| hatchery_nodes::fused_pass::fusable(&n.kind).is_some());
        if !fusable {
            continue;
        }
        // One session (the data loads once): each saver's picture unfused, then — after a frame
        // of another size, so every frame-sized node runs again — fused.
        let session = &mut fused;
        for saver in common::savers(session) {
            let (source, port) = {
                let sources = session.graph.input_sources(&saver);
                let (node, port) = sources[&0];
                (node.to_owned(), port)
            };
            let name = format!("{}: {source}", path.display());
            let render = |session: &mut Session, fusion: bool| {
                session.ctx.set_size(16, 12).unwrap();
                session.run(&[&source]).unwrap();
                session.ctx.set_size(160, 120).unwrap();
                session.executor.set_fusion(fusion);
                session.run(&[&source]).unwrap();
                let value = session.executor.output(&source, port).unwrap();
                export::to_array(value, &session.ctx.gpu).unwrap().data
            };
            let alone = render(session, false);
            let fused = render(session, true);
            assert_eq!(fused.len(), alone.len(), "{name}");
            // 120 rows of 160 pixels.
            common::assert_images_identical(&name, &fused, &alone, (fused.len() / 120) as u32);
        }
        if fused
            .executor
            .stats()
            .values()
            .any(|s| s.fused_with.len() > 1)
        {
            with_fused_passes.push(path.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    for preset in ["hidden_layers_brain.ron", "hidden_structures.ron"] {
        assert!(
            with_fused_passes.contains(&preset.to_owned()),
            "{preset} ran no fused pass: {with_fused_passes:?}"
        );
    }
}

/// A stage that fails inside a fused pass is named, with its own message.
#[test]
fn an_error_inside_a_fused_pass_names_its_node() {
    let mut session = common::session_from_text(ALL_KINDS, W, H);
    session
        .set_param_text("sil_dots", "pip", "texture")
        .unwrap();
    let error = session.run(&["final"]).unwrap_err();
    let hatchery_nodes::SessionError::Exec(exec) = &error else {
        panic!("{error}");
    };
    assert_eq!(exec.node, "sil_dots", "{error}");
    assert!(exec.message.contains("pip_texture"), "{error}");
    // Fixed, the pass runs.
    session.set_param_text("sil_dots", "pip", "dots").unwrap();
    session.run(&["final"]).unwrap();
}

/// Issue 34: an edit of one member of a fused pass re-runs that member and what follows it, not
/// the members before it, and the picture equals a fresh render bit for bit. A session that keeps
/// fused outputs (the editor) learns the edited member, so its edits stay that cheap between
/// edits upstream of the whole pass (an orbit); a one-shot session writes only what each pass
/// needs, so only consecutive edits of the member are.
#[test]
fn an_edit_inside_a_fused_pass_re_runs_only_what_follows_it() {
    // Not downstream of the halftone `screen`: its input `lit`, and the silhouettes and mask
    // combinations before `c_min` (they reach `final` only through nodes after `screen`).
    let before = [
        "lit",
        "sil_none",
        "sil_constant",
        "sil_noise",
        "c_and",
        "c_or",
    ];
    let after = [
        "screen", "c_min", "c_add", "c_sub", "c_not", "gate", "final",
    ];
    let runs = |s: &Session, ids: &[&str]| -> Vec<u64> {
        ids.iter()
            .map(|id| s.executor.stats()[*id].executions)
            .collect()
    };
    let plus_one = |runs: &[u64]| -> Vec<u64> { runs.iter().map(|n| n + 1).collect() };
    for keep in [true, false] {
        let mut session = common::session_from_text(ALL_KINDS, W, H);
        session.executor.set_keep_fused(keep);
        session.run(&["final"]).unwrap();
        // The first edit of the halftone: the pass before wrote only what it needed, so the
        // members before `screen` re-run once to write their outputs.
        session.set_param_text("screen", "theta", "40").unwrap();
        let before_runs = runs(&session, &before);
        session.run(&["final"]).unwrap();
        assert_eq!(
            runs(&session, &before),
            plus_one(&before_runs),
            "keep {keep}"
        );
        // An edit upstream of the whole pass, then the halftone again.
        let mut theta = 47.0;
        for azimuth in [50.0, 65.0] {
            session
                .set_param_text("camera", "azimuth", &azimuth.to_string())
                .unwrap();
            session.run(&["final"]).unwrap();
            let (before_runs, after_runs) = (runs(&session, &before), runs(&session, &after));
            session
                .set_param_text("screen", "theta", &theta.to_string())
                .unwrap();
            session.run(&["final"]).unwrap();
            let expected_before = if keep {
                before_runs.clone()
            } else {
                plus_one(&before_runs)
            };
            assert_eq!(
                runs(&session, &before),
                expected_before,
                "keep {keep}: after an orbit, the members before the edited one ({before:?})"
            );
            assert_eq!(
                runs(&session, &after),
                plus_one(&after_runs),
                "keep {keep}: the edited member and what follows ran once ({after:?})"
            );
            // A second edit in a row leaves the members before it cached in either session.
            theta += 3.0;
            let before_runs = runs(&session, &before);
            session
                .set_param_text("screen", "theta", &theta.to_string())
                .unwrap();
            session.run(&["final"]).unwrap();
            assert_eq!(
                runs(&session, &before),
                before_runs,
                "keep {keep}: second edit"
            );
            let mut fresh = common::session_from_text(ALL_KINDS, W, H);
            fresh
                .set_param_text("screen", "theta", &theta.to_string())
                .unwrap();
            fresh
                .set_param_text("camera", "azimuth", &azimuth.to_string())
                .unwrap();
            fresh.run(&["final"]).unwrap();
            assert_identical(
                &format!("final after edits (keep {keep}, azimuth {azimuth})"),
                &pixels(&session, "final", "image"),
                &pixels(&fresh, "final", "image"),
                4,
            );
            theta += 5.0;
        }
    }
}

/// A re-run of a pass draws into the texture of an earlier run once nothing holds that run's
/// picture any more (the editor's θ drag allocates no new frames), and never into a picture
/// someone still holds: a picture kept from the first run is unchanged after many re-runs, and
/// every re-run equals a fresh render bit for bit.
#[test]
fn re_runs_reuse_free_targets_and_never_draw_over_a_held_picture() {
    let mut session = common::session_from_text(ALL_KINDS, W, H);
    session.run(&["final"]).unwrap();
    let texture = |v: &Value| match v {
        Value::Image(i) => i.texture.clone(),
        _ => panic!("not an image"),
    };
    let set_theta = |session: &mut Session, theta: f32| {
        session
            .set_param_text("screen", "theta", &theta.to_string())
            .unwrap();
        session.run(&["final"]).unwrap();
    };
    // The first edits re-plan the pass (the members before the halftone start writing what it
    // reads); from then on a θ drag re-runs the same pass.
    for theta in [31.0, 33.0, 35.0] {
        set_theta(&mut session, theta);
    }
    // A picture someone keeps (the editor's preview, an export in flight).
    let held = session.output("final", "image").unwrap().clone();
    let held_pixels = pixels(&session, "final", "image");
    let mut seen = vec![texture(&held)];
    let mut reused = 0;
    for (k, theta) in [41.0, 46.0, 51.0, 56.0, 61.0].into_iter().enumerate() {
        set_theta(&mut session, theta);
        let t = texture(session.output("final", "image").unwrap());
        assert!(t != seen[0], "run {k} drew into the held picture's texture");
        if seen.contains(&t) {
            reused += 1;
        } else {
            // Two targets take turns: the one the executor holds and the free one; the held
            // picture's is replaced once.
            assert!(k < 2, "run {k} made a new target ({} so far)", seen.len());
            seen.push(t);
        }
        let mut fresh = common::session_from_text(ALL_KINDS, W, H);
        set_theta(&mut fresh, theta);
        assert_identical(
            &format!("θ {theta} after re-runs"),
            &pixels(&session, "final", "image"),
            &pixels(&fresh, "final", "image"),
            4,
        );
    }
    // Still what was drawn when it was taken.
    let data = export::to_array(&held, &session.ctx.gpu).unwrap().data;
    assert_eq!(data, held_pixels, "the held picture changed");
    assert!(
        reused >= 3,
        "{reused} of 5 re-runs drew into a recycled target"
    );
}
