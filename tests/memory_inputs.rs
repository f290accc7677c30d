//! Graph inputs given data in memory (issue 26, what the Python package does with numpy arrays):
//! the nodes read the data instead of a file, a new array re-runs only what reads it, and a saved
//! graph keeps the files the parameters held.

mod common;

use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::voxels::Voxels;
use hatchery_nodes::memory_inputs::InputData;
use hatchery_nodes::{Session, Value};
use std::sync::Arc;

fn brain() -> Session {
    Session::open(
        &common::repo_root().join("graphs/brain_surface.ron"),
        48,
        32,
    )
    .unwrap()
}

fn ball(n: u32) -> VolumeData {
    common::field_on_cube(n, |p| 100.0 * (1.0 - p.length()).max(0.0))
}

#[test]
fn a_volume_in_memory_is_what_volume_file_gives() {
    let mut session = brain();
    let mut data = ball(20);
    data.geometry = Geometry::axis_aligned([2.0, 1.5, 1.0], [-10.0, 5.0, 3.0]);
    let u8_data = VolumeData::from_voxels(
        data.dims,
        data.geometry,
        Voxels::U8(data.values_f32().iter().map(|v| *v as u8).collect()),
    )
    .unwrap();
    session
        .set_input_data("volume", InputData::Volume(Arc::new(u8_data.clone())))
        .unwrap();
    let Value::Volume(v) = session.evaluate("mri", "volume").unwrap() else {
        panic!("a volume")
    };
    assert_eq!(v.data.dims, u8_data.dims);
    assert_eq!(v.data.geometry, u8_data.geometry);
    assert_eq!(v.data.voxels, u8_data.voxels, "kept as uint8, not widened");
    // Rendering works from it, and a second array re-runs the reader.
    session.run(&["shaded"]).unwrap();
    let report = session.run(&["shaded"]).unwrap();
    assert!(report.executed.is_empty(), "{report:?}");
    session
        .set_input_data("volume", InputData::Volume(Arc::new(data)))
        .unwrap();
    let report = session.run(&["shaded"]).unwrap();
    assert!(report.executed.contains(&"mri".to_string()), "{report:?}");
}

#[test]
fn saving_writes_back_the_files_and_names_the_memory_inputs() {
    let mut session = brain();
    let before = session.graph.to_document(&session.registry).to_ron_string();
    session
        .set_input_data("volume", InputData::Volume(Arc::new(ball(8))))
        .unwrap();
    assert_eq!(session.memory_inputs(), vec!["volume".to_string()]);
    assert_eq!(session.document().to_ron_string(), before);
    // A file given afterwards is what gets saved.
    let file = common::shared_data("volumes/mni152_gm.nii.gz");
    session.set_input("volume", &file).unwrap();
    assert!(session.memory_inputs().is_empty());
    assert!(
        session
            .document()
            .to_ron_string()
            .contains("mni152_gm.nii.gz")
    );
}

#[test]
fn wrong_kinds_and_unknown_keys_are_one_line_errors() {
    let mut session = brain();
    let labels = LabelData::new([2, 2, 2], Geometry::default(), vec![1; 8]);
    let e = session
        .set_input_data("volume", InputData::Labels(Arc::new(labels)))
        .unwrap_err()
        .to_string();
    assert_eq!(e, "input `volume` takes a volume, not a labels");
    let e = session
        .set_input_data("nope", InputData::Volume(Arc::new(ball(4))))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no input `nope`"), "{e}");
    // A key written by hand (or saved from another session) names no data here.
    session
        .set_param_text("mri", "path", "memory:volume#7")
        .unwrap();
    let e = session.run(&["mri"]).unwrap_err().to_string();
    assert!(
        e.contains("`memory:volume#7` names data held in memory by another session"),
        "{e}"
    );
}

#[test]
fn labels_in_memory_keep_their_names_over_a_names_table() {
    let preset = common::repo_root().join("graphs/two_level_frog.ron");
    let mut session = Session::open(&preset, 32, 24).unwrap();
    let mut ids = vec![0u16; 6 * 6 * 6];
    ids[7] = 1;
    ids[100] = 2;
    let mut labels = LabelData::new([6, 6, 6], Geometry::default(), ids);
    labels.objects.insert(1, "heart".into());
    session
        .set_input_data("labels", InputData::Labels(Arc::new(labels)))
        .unwrap();
    // The preset's names table (the frog's CSV) names id 2; id 1 keeps the name given.
    let Value::Labels(l) = session.evaluate("tissues", "labels").unwrap() else {
        panic!("labels")
    };
    assert_eq!(l.data.objects[&1], "heart");
    assert_ne!(l.data.objects[&2], "object 2", "named from the table");
    // The same data through VolumeFile (the labels input also sets frog.path) is the ids.
    let Value::Volume(v) = session.evaluate("frog", "volume").unwrap() else {
        panic!("a volume")
    };
    assert_eq!(v.data.values_f32()[100], 2.0);
}
