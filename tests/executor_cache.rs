//! The executor re-runs exactly the changed node and its descendants.

mod common;

use hatchery_graph::executor::PassReport;

const GRAPH: &str = r#"(
    version: 1,
    nodes: [
        (id: "shells", kind: "ProceduralVolume", params: {"resolution": 24}),
        (id: "surface", kind: "MarchingCubes", params: {"iso": 0.0}),
        (id: "moved", kind: "MeshTransform", params: {}),
        (id: "camera", kind: "Camera", params: {}),
        (id: "light", kind: "Light", params: {}),
        (id: "gbuffer", kind: "GBuffer", params: {}),
        (id: "shaded", kind: "ShadedSurface", params: {}),
    ],
    edges: [
        (from: ("shells", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("moved", "mesh")),
        (from: ("moved", "mesh"), to: ("shaded", "mesh")),
        (from: ("moved", "mesh"), to: ("gbuffer", "mesh")),
        (from: ("camera", "camera"), to: ("shaded", "camera")),
        (from: ("camera", "camera"), to: ("gbuffer", "camera")),
        (from: ("light", "light"), to: ("shaded", "light")),
    ],
)"#;

fn sorted(mut ids: Vec<String>) -> Vec<String> {
    ids.sort();
    ids
}

fn executed(report: &PassReport) -> Vec<String> {
    sorted(report.executed.clone())
}

#[test]
fn changing_a_parameter_reruns_only_that_node_and_its_descendants() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    let targets = ["shaded", "gbuffer"];

    let first = session.run(&targets).unwrap();
    assert_eq!(
        first.executed.len(),
        7,
        "first pass runs everything: {first:?}"
    );

    let second = session.run(&targets).unwrap();
    assert!(
        second.executed.is_empty(),
        "nothing changed, nothing runs: {second:?}"
    );
    assert_eq!(second.cached.len(), 7);

    // The light feeds only `shaded`.
    session.set_param_text("light", "ambient", "0.4").unwrap();
    let third = session.run(&targets).unwrap();
    assert_eq!(executed(&third), ["light", "shaded"]);

    // The transform feeds both renderers, but not its own inputs.
    session
        .set_param_text("moved", "translate", "0.1, 0, 0")
        .unwrap();
    let fourth = session.run(&targets).unwrap();
    assert_eq!(executed(&fourth), ["gbuffer", "moved", "shaded"]);

    // The iso value: the surface and everything below it, never the volume.
    session.set_param_text("surface", "iso", "-0.01").unwrap();
    let fifth = session.run(&targets).unwrap();
    assert_eq!(executed(&fifth), ["gbuffer", "moved", "shaded", "surface"]);

    // Execution counts add up over the five passes.
    let stats = session.executor.stats();
    assert_eq!(stats["shells"].executions, 1);
    assert_eq!(stats["shells"].cache_hits, 4);
    assert_eq!(stats["camera"].executions, 1);
    assert_eq!(stats["light"].executions, 2);
    assert_eq!(stats["surface"].executions, 2);
    assert_eq!(stats["shaded"].executions, 4);
    assert_eq!(stats["gbuffer"].executions, 3);
}

#[test]
fn the_frame_size_invalidates_only_frame_dependent_nodes() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    session.run(&["shaded"]).unwrap();
    session.ctx.set_size(32, 32).unwrap();
    let report = session.run(&["shaded"]).unwrap();
    assert_eq!(
        executed(&report),
        ["camera", "shaded"],
        "geometry must not be rebuilt for a new size"
    );
}

#[test]
fn pulling_one_target_runs_only_its_ancestors() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    let report = session.run(&["surface"]).unwrap();
    assert_eq!(executed(&report), ["shells", "surface"]);
}

#[test]
fn execution_errors_name_the_node() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    session.set_param_text("camera", "near", "5000").unwrap();
    let err = session.run(&["shaded"]).unwrap_err().to_string();
    assert!(err.starts_with("node `camera` (Camera)"), "{err}");
    assert!(err.contains("must be less than far"), "{err}");
}

/// Issue 9 item 4: an iso value that yields no surface is a warning on its node, not an error;
/// the rest of the picture renders, and the warning goes when the node runs again with a surface.
#[test]
fn no_surface_is_a_warning_on_the_node_and_the_picture_renders() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    session.set_param_text("surface", "iso", "5.0").unwrap();
    session.run(&["shaded"]).unwrap();
    let warning = session.ctx.warnings().get("surface").cloned();
    assert!(
        warning.as_deref().is_some_and(
            |w| w.contains("outside the volume's value range") && w.contains("no surface")
        ),
        "{warning:?}"
    );
    session.set_param_text("surface", "iso", "0.0").unwrap();
    session.run(&["shaded"]).unwrap();
    assert_eq!(session.ctx.warnings().get("surface"), None);
}

#[test]
fn per_node_times_are_recorded_and_gpu_time_only_for_gpu_work() {
    let mut session = common::session_from_text(GRAPH, 64, 48);
    let timed = session.ctx.enable_gpu_timing();
    session.run(&["shaded", "gbuffer"]).unwrap();
    let stats = session.executor.stats();
    assert!(stats["surface"].cpu_time > std::time::Duration::ZERO);
    // CPU-only nodes submit nothing, so they have no GPU time even when timing is on.
    assert_eq!(stats["surface"].gpu_time, None);
    assert_eq!(stats["shells"].gpu_time, None);
    if timed {
        assert!(
            stats["shaded"]
                .gpu_time
                .is_some_and(|t| t > std::time::Duration::ZERO),
            "{:?}",
            stats["shaded"]
        );
        assert!(
            stats["gbuffer"].gpu_time.is_some(),
            "{:?}",
            stats["gbuffer"]
        );
    } else {
        eprintln!("adapter has no timestamp queries: GPU times not checked");
    }
}
