//! OME-Zarr as ome-zarr-py writes it (tests/fixtures/world/ome_v0{4,5}.zarr and their records in
//! truth.json, from scripts/make_world_fixtures.py): label images with their object names, the
//! pyramid's levels placed where their transformations say, and what hatchery writes read back.
//! (Each file's world placement is checked with every other format in tests/formats.rs.)

use glam::DVec3;
use hatchery_data::ome_zarr::{self, ConvertOptions, Multiscale};
use hatchery_data::segmentation::LabelData;
use hatchery_data::volume_file::{LoadOptions, load_volume_with};
use hatchery_data::{VolumeData, load_volume};
use serde_json::Value;
use std::path::PathBuf;

fn world_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/world")
}

fn record(name: &str) -> Value {
    let text = std::fs::read_to_string(world_dir().join("truth.json")).unwrap();
    let truth: Value = serde_json::from_str(&text).unwrap();
    truth["files"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["file"] == name)
        .unwrap_or_else(|| panic!("{name} is not in truth.json"))
        .clone()
}

#[test]
fn label_images_load_with_their_names_on_the_image_grid() {
    for name in ["ome_v04.zarr", "ome_v05.zarr"] {
        let truth = &record(name)["labels"];
        let root = world_dir().join(name);
        let image = load_volume(&root).unwrap();
        // The label image by path, by `array`, and as the group's first label image.
        let by_path = root.join(truth["path"].as_str().unwrap());
        for (volume, names) in [
            ome_zarr::load_label_image(&by_path, None).unwrap(),
            ome_zarr::load_label_image(&root, Some("organs")).unwrap(),
            ome_zarr::load_label_image(&root, None).unwrap(),
        ] {
            assert_eq!(volume.dims, image.dims, "{name}");
            assert_eq!(
                volume.geometry, image.geometry,
                "{name}: labels lie on the image grid"
            );
            let labels = LabelData::from_volume(&volume).unwrap();
            for (id, want) in truth["voxels"].as_object().unwrap() {
                let id: u16 = id.parse().unwrap();
                let n = labels.ids.iter().filter(|&&v| v == id).count() as u64;
                assert_eq!(n, want.as_u64().unwrap(), "{name}: voxels of object {id}");
                let want_name = truth["names"][id.to_string()].as_str().unwrap();
                assert_eq!(
                    names.get(&id).map(String::as_str),
                    Some(want_name),
                    "{name}"
                );
            }
        }
        // VolumeFile's `array` reads a label image as a volume too.
        let options = LoadOptions {
            array: Some("organs".into()),
        };
        let as_volume = load_volume_with(&root, &options).unwrap();
        assert_eq!(as_volume.value_range, [0.0, 2.0], "{name}");
        let err = ome_zarr::load_label_image(&root, Some("nuclei"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("no label image \"nuclei\"") && err.contains("organs"),
            "{err}"
        );
    }
}

/// A file dialog picks files: the group's metadata file stands for the group.
#[test]
fn a_groups_metadata_file_opens_the_group() {
    for (name, file) in [("ome_v05.zarr", "zarr.json"), ("ome_v04.zarr", ".zattrs")] {
        let root = world_dir().join(name);
        assert_eq!(
            load_volume(&root.join(file)).unwrap(),
            load_volume(&root).unwrap()
        );
        let labels = root.join("labels/organs").join(file);
        let (_, names) = ome_zarr::load_label_image(&labels, None).unwrap();
        assert_eq!(names.len(), 2, "{name}");
    }
}

#[test]
fn pyramid_levels_are_placed_by_their_own_transformations() {
    for name in ["ome_v04.zarr", "ome_v05.zarr"] {
        let image = Multiscale::open(&world_dir().join(name)).unwrap();
        assert_eq!(image.levels.len(), 2, "{name}");
        let (l0, l1) = (&image.levels[0], &image.levels[1]);
        // Level 1 keeps every second voxel along y and x (the generator's [::2]): index 0 stays
        // put and the spacing doubles along i and j only.
        assert_eq!(
            l1.dims,
            [l0.dims[0] / 2, l0.dims[1] / 2, l0.dims[2]],
            "{name}"
        );
        let s = l1.geometry.spacing / l0.geometry.spacing;
        assert!(
            (s - DVec3::new(2.0, 2.0, 1.0)).length() < 1e-9,
            "{name}: {s}"
        );
        assert!(
            (l1.geometry.origin - l0.geometry.origin).length() < 1e-9,
            "{name}"
        );
        let coarse = image.read_level(1).unwrap();
        let fine = image.read_level(0).unwrap();
        let at = |v: &VolumeData, [i, j, k]: [u32; 3]| {
            v.values_f32()[(i + v.dims[0] * (j + v.dims[1] * k)) as usize]
        };
        for ijk in [[2, 3, 4], [6, 2, 5], [7, 3, 2]] {
            let fine_ijk = [2 * ijk[0], 2 * ijk[1], ijk[2]];
            assert_eq!(at(&coarse, ijk), at(&fine, fine_ijk), "{name} {ijk:?}");
        }
        assert!(image.warnings.is_empty(), "{name}: {:?}", image.warnings);
    }
}

#[test]
fn written_ome_zarr_reads_back_in_place_with_its_labels() {
    let dir = tempfile::tempdir().unwrap();
    for source in [
        "nifti_las.nii.gz",
        "nifti_oblique.nii.gz",
        "sitk_gzip.nhdr",
        "freesurfer_coronal.mgh",
    ] {
        let volume = load_volume(&world_dir().join(source)).unwrap();
        let mut labels = LabelData::from_volume(
            &hatchery_data::labels::label_mask(&volume, &[volume.value_range[1] as i64], 0.0)
                .unwrap(),
        )
        .unwrap();
        labels.objects.insert(1, "object".into());
        let out = dir.path().join(format!("{source}.zarr"));
        let options = ConvertOptions {
            chunk: 8,
            ..Default::default()
        };
        let warnings =
            ome_zarr::write_ome_zarr(&volume, Some(("mask", &labels)), &out, &options).unwrap();
        let back = load_volume(&out).unwrap();
        // Mirrored (nifti_las, sitk_gzip) and permuted (coronal) grids are written exactly.
        let oblique = source == "nifti_oblique.nii.gz";
        assert_eq!(oblique, !warnings.is_empty(), "{source}: {warnings:?}");
        // The same voxels at the same world points (an oblique grid only centred the same).
        let world_centre = |v: &VolumeData| (v.world_min() + v.world_max()) / 2.0;
        let c = (world_centre(&back) - world_centre(&volume)).length();
        assert!(c < 1e-3, "{source}: centre moved {c} mm");
        if !oblique {
            for (i, &x) in back.values_f32().iter().enumerate().step_by(7) {
                let ijk = glam::UVec3::new(
                    i as u32 % back.dims[0],
                    (i as u32 / back.dims[0]) % back.dims[1],
                    i as u32 / (back.dims[0] * back.dims[1]),
                );
                let p = back.voxel_to_world(ijk.as_vec3());
                let src = volume.world_to_voxel(p).round().as_uvec3();
                let want = volume.values_f32()
                    [(src.x + volume.dims[0] * (src.y + volume.dims[1] * src.z)) as usize];
                assert_eq!(x, want, "{source}: voxel {ijk} at {p}");
            }
        }
        assert_eq!(back.stored_type, volume.stored_type, "{source}");
        let (mask, names) = ome_zarr::load_label_image(&out, None).unwrap();
        assert_eq!(names.get(&1).map(String::as_str), Some("object"));
        assert_eq!(mask.geometry, back.geometry, "{source}");
        let image = Multiscale::open(&out).unwrap();
        assert!(image.levels.len() >= 2, "{source}: a pyramid with chunk 8");
        // Writing over an OME-Zarr replaces it; over anything else is refused.
        let not_zarr = dir.path().join(format!("{source}.txt.zarr"));
        std::fs::create_dir(&not_zarr).unwrap();
        std::fs::write(not_zarr.join("notes.txt"), "mine").unwrap();
        let err = ome_zarr::write_ome_zarr(&volume, None, &not_zarr, &options).unwrap_err();
        assert!(err.to_string().contains("not replaced"), "{err}");
        assert!(not_zarr.join("notes.txt").exists());
    }
}

/// A Zarr v3 array's metadata (uint8, empty: every chunk is the fill value, as a sparse store).
fn empty_array(dir: &std::path::Path, shape: [u64; 3]) {
    std::fs::create_dir_all(dir).unwrap();
    let meta = serde_json::json!({
        "zarr_format": 3, "node_type": "array", "shape": shape, "data_type": "uint8",
        "chunk_grid": {"name": "regular", "configuration": {"chunk_shape": [64, 64, 64]}},
        "chunk_key_encoding": {"name": "default", "configuration": {"separator": "/"}},
        "fill_value": 7, "codecs": [{"name": "bytes"}], "dimension_names": ["z", "y", "x"],
    });
    std::fs::write(dir.join("zarr.json"), meta.to_string()).unwrap();
}

#[test]
fn a_pyramid_too_large_for_memory_opens_at_its_finest_level_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("huge.zarr");
    // Level 0: 1040³ = 1.12 G voxels, beyond the limit of one volume in memory; level 1 fits.
    empty_array(&root.join("0"), [1040; 3]);
    empty_array(&root.join("1"), [520; 3]);
    let level = |k: u32| {
        let s = f64::from(1 << k) * 0.01;
        serde_json::json!({"path": k.to_string(), "coordinateTransformations": [
            {"type": "scale", "scale": [s, s, s]},
            {"type": "translation", "translation": [0.0, 0.0, s / 2.0]}]})
    };
    let group = serde_json::json!({"zarr_format": 3, "node_type": "group", "attributes": {"ome": {
        "version": "0.5", "multiscales": [{"name": "huge", "datasets": [level(0), level(1)],
        "axes": [{"name": "z", "type": "space", "unit": "micrometer"},
                 {"name": "y", "type": "space", "unit": "micrometer"},
                 {"name": "x", "type": "space", "unit": "micrometer"}]}]}}});
    std::fs::write(root.join("zarr.json"), group.to_string()).unwrap();
    let v = load_volume(&root).unwrap();
    assert_eq!(v.dims, [520; 3]);
    assert_eq!(
        v.value_range,
        [7.0, 7.0],
        "unwritten chunks read as the fill value"
    );
    assert!(
        (v.geometry.spacing.x - 2e-5).abs() < 1e-12,
        "{:?}",
        v.geometry
    );
    assert!(
        (v.geometry.origin.x - 1e-5).abs() < 1e-12,
        "translation along x (µm → mm)"
    );
    assert!(
        v.warnings
            .iter()
            .any(|w| w.contains("level 0 (1040×1040×1040") && w.contains("level 1")),
        "{:?}",
        v.warnings
    );
}

#[test]
fn malformed_metadata_is_one_clear_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let axes3 = serde_json::json!([{"name": "z", "type": "space"}, {"name": "y", "type": "space"},
                                   {"name": "x", "type": "space"}]);
    let cases = [
        (
            "no_multiscales",
            serde_json::json!({"ome": {"version": "0.5"}}),
            [8u64, 8, 8],
            "no OME `multiscales`",
        ),
        (
            "two_d",
            serde_json::json!({"ome": {"multiscales": [{"datasets": [{"path": "0"}],
            "axes": [{"name": "c", "type": "channel"}, {"name": "y", "type": "space"},
                     {"name": "x", "type": "space"}]}]}}),
            [8, 8, 8],
            "2 space axes",
        ),
        (
            "short_scale",
            serde_json::json!({"ome": {"multiscales": [{"axes": axes3, "datasets": [
            {"path": "0", "coordinateTransformations": [{"type": "scale", "scale": [1.0, 2.0]}]}]}]}}),
            [8, 8, 8],
            "3 finite numbers",
        ),
        (
            "affine",
            serde_json::json!({"ome": {"multiscales": [{"axes": axes3, "datasets": [
            {"path": "0", "coordinateTransformations": [{"type": "affine", "affine": []}]}]}]}}),
            [8, 8, 8],
            "\"affine\"",
        ),
        (
            "zero_scale",
            serde_json::json!({"ome": {"multiscales": [{"axes": axes3, "datasets": [
            {"path": "0", "coordinateTransformations": [{"type": "scale", "scale": [1.0, 0.0, 1.0]}]}]}]}}),
            [8, 8, 8],
            "zero scale",
        ),
        (
            "escape",
            serde_json::json!({"ome": {"multiscales": [{"axes": axes3, "datasets": [
            {"path": "../0"}]}]}}),
            [8, 8, 8],
            "usable `path`",
        ),
        (
            "missing_level",
            serde_json::json!({"ome": {"multiscales": [{"axes": axes3, "datasets": [
            {"path": "7"}]}]}}),
            [8, 8, 8],
            "level 7",
        ),
    ];
    for (name, attributes, shape, needle) in cases {
        let root = dir.path().join(format!("{name}.zarr"));
        empty_array(&root.join("0"), shape);
        let group =
            serde_json::json!({"zarr_format": 3, "node_type": "group", "attributes": attributes});
        std::fs::write(root.join("zarr.json"), group.to_string()).unwrap();
        let err = load_volume(&root).unwrap_err().to_string();
        assert!(
            err.contains(needle) && err.contains(&format!("{name}.zarr")),
            "{name}: {err}"
        );
    }
}
