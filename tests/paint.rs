//! `PaintLabels` (volume painting, VolumeShop §6.1) through the graph a user writes: dabs on a
//! volume's grid or over a segmentation, in world units; bad strokes and a missing grid are
//! errors naming the node and the dab. The editor's paint tool is tested in
//! editor/tests/editor_ui/paint.rs.

mod common;

use hatchery_nodes::{Session, Value};

fn graph(paint_params: &str, labels: bool) -> String {
    let source = if labels {
        r#"(from: ("labels", "labels"), to: ("paint", "labels")),"#
    } else {
        r#"(from: ("sphere", "volume"), to: ("paint", "volume")),"#
    };
    format!(
        r#"(
    version: 3,
    nodes: [
        (id: "sphere", kind: "ProceduralVolume", params: {{"shape": "sphere", "resolution": 33, "radius": 0.7}}),
        (id: "labels", kind: "LabelsFromThreshold", params: {{"intervals": "0..1: 5"}}),
        (id: "paint", kind: "PaintLabels", params: {{{paint_params}}}),
    ],
    edges: [
        (from: ("sphere", "volume"), to: ("labels", "volume")),
        {source}
    ],
)"#
    )
}

fn painted(text: &str) -> Result<Vec<u16>, String> {
    let mut session = common::session_from_text(text, 8, 8);
    session.run(&["paint"]).map_err(|e| e.to_string())?;
    match session.output("paint", "labels") {
        Ok(Value::Labels(l)) => Ok(l.data.ids.clone()),
        _ => Err("no labels".into()),
    }
}

#[test]
fn dabs_paint_balls_in_world_units_on_a_volume_or_over_labels() {
    // The grid spans [-1, 1] in 33 voxels (1/16 apart): a dab of radius 0.25 at the centre
    // fills the voxels within 4 voxel spacings, 257 of them.
    let ids = painted(&graph(r#""strokes": "0 0 0 0.25 3""#, false)).unwrap();
    assert_eq!(ids.iter().filter(|&&id| id == 3).count(), 257);
    assert!(ids.iter().all(|&id| id == 0 || id == 3));
    // Over the sphere's labels (id 5 inside): the dab replaces them there, erasing (id 0)
    // with a second dab carves a hole in the painting.
    let ids = painted(&graph(r#""strokes": "0 0 0 0.25 3; 0 0 0 0.13 0""#, true)).unwrap();
    let count = |id| ids.iter().filter(|&&v| v == id).count();
    assert!(count(5) > 5000, "{} sphere voxels", count(5));
    assert_eq!(count(3), 257 - 33, "the shell between 2.08 and 4 voxels");
    assert_eq!(ids[16 * 33 * 33 + 16 * 33 + 16], 0, "the centre is erased");
}

#[test]
fn bad_strokes_and_no_grid_are_errors_naming_the_node() {
    let e = painted(&graph(
        r#""strokes": "0 0 0 0.25 3; 0 0 zero 0.1 1""#,
        false,
    ))
    .unwrap_err();
    assert!(e.contains("paint") && e.contains("dab 2"), "{e}");
    let mut session: Session = common::session_from_text(
        r#"(version: 3, nodes: [(id: "paint", kind: "PaintLabels", params: {})])"#,
        8,
        8,
    );
    let e = session.run(&["paint"]).unwrap_err().to_string();
    assert!(e.contains("connect a volume"), "{e}");
}
