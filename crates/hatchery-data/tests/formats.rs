//! One asymmetric anatomy written by independent tools (nibabel, SimpleITK, tifffile, VTK) in every
//! format, loaded here: each must land where the writer's own reader puts it. The files and
//! `truth.json` come from `scripts/make_world_fixtures.py`; nothing in the truth comes from
//! hatchery.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use hatchery_data::marching_cubes::marching_cubes;
use hatchery_data::volume_file::VOLUME_ENDINGS;
use hatchery_data::{VolumeData, load_volume};
use serde_json::Value;

fn world_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/world")
}

fn truth() -> Value {
    let text = std::fs::read_to_string(world_dir().join("truth.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn vec3(v: &Value) -> DVec3 {
    let a: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .collect();
    DVec3::new(a[0], a[1], a[2])
}

/// Mean world position of the voxels above `iso` and their count; `mirror` reflects the voxel
/// indices along one axis first (to show the anatomy is asymmetric enough to catch a flip).
fn voxel_centroid(v: &VolumeData, iso: f32, mirror: Option<usize>) -> (DVec3, usize) {
    let mut sum = DVec3::ZERO;
    let mut count = 0;
    for k in 0..v.dims[2] {
        for j in 0..v.dims[1] {
            for i in 0..v.dims[0] {
                if v.value(i, j, k) > iso {
                    let mut ijk = [i, j, k];
                    if let Some(axis) = mirror {
                        ijk[axis] = v.dims[axis] - 1 - ijk[axis];
                    }
                    let p =
                        v.voxel_to_world(Vec3::new(ijk[0] as f32, ijk[1] as f32, ijk[2] as f32));
                    sum += p.as_dvec3();
                    count += 1;
                }
            }
        }
    }
    (sum / count.max(1) as f64, count)
}

#[test]
fn every_fixture_lands_where_its_writer_put_it() {
    let truth = truth();
    let iso = truth["threshold"].as_f64().unwrap() as f32;
    let object_value = truth["object_value"].as_f64().unwrap() as f32;
    let voxels_above = truth["voxels_above"].as_u64().unwrap() as usize;
    let mut formats = Vec::new();
    for entry in truth["files"].as_array().unwrap() {
        let name = entry["file"].as_str().unwrap();
        if !VOLUME_ENDINGS
            .iter()
            .any(|e| name.to_ascii_lowercase().ends_with(e))
        {
            continue; // a format another reader will bring
        }
        let v = load_volume(&world_dir().join(name)).unwrap_or_else(|e| panic!("{e}"));
        let dims: Vec<u64> = entry["dims"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d.as_u64().unwrap())
            .collect();
        assert_eq!(v.dims.map(u64::from).to_vec(), dims, "{name}");
        assert_eq!(v.value_range, [0.0, object_value], "{name}");

        // (a) The voxel -> world affine, entry by entry.
        let m = v.geometry.to_world();
        let want_affine: Vec<&Vec<Value>> = entry["affine_ras"]
            .as_array()
            .unwrap()
            .iter()
            .map(|row| row.as_array().unwrap())
            .collect();
        for (r, row) in want_affine.iter().enumerate().take(3) {
            for c in 0..4 {
                let (got, want) = (m.col(c)[r], row[c].as_f64().unwrap());
                assert!(
                    (got - want).abs() < 1e-4,
                    "{name}: affine[{r}][{c}] is {got}, the independent reader says {want}\n{}",
                    v.geometry.describe()
                );
            }
        }

        // (b) The object's voxels average to the writer-side centroid...
        let want = vec3(&entry["centroid_ras"]);
        let (centroid, count) = voxel_centroid(&v, iso, None);
        assert_eq!(count, voxels_above, "{name}");
        assert!(
            (centroid - want).length() < 1e-3,
            "{name}: voxel centroid {centroid}, want {want}"
        );
        // ... and the marching-cubes surface around them stays within half a voxel of it: half
        // the shortest voxel edge of the independent reader's affine.
        let half_diagonal = entry["half_voxel_diagonal"].as_f64().unwrap();
        let half_voxel = (0..3)
            .map(|c| {
                let column = DVec3::new(
                    want_affine[0][c].as_f64().unwrap(),
                    want_affine[1][c].as_f64().unwrap(),
                    want_affine[2][c].as_f64().unwrap(),
                );
                0.5 * column.length()
            })
            .fold(f64::INFINITY, f64::min);
        let mesh = marching_cubes(&v, iso);
        assert!(!mesh.positions.is_empty(), "{name}");
        let mean = mesh
            .positions
            .iter()
            .map(|p| Vec3::from_array(*p).as_dvec3())
            .sum::<DVec3>()
            / mesh.positions.len() as f64;
        assert!(
            (mean - want).length() < half_voxel,
            "{name}: surface centroid {mean} is {} mm from {want} (half the shortest voxel edge: \
             {half_voxel})",
            (mean - want).length()
        );
        // A reader that mirrored any axis would be caught: the mirrored centroid is far off.
        for axis in 0..3 {
            let (mirrored, _) = voxel_centroid(&v, iso, Some(axis));
            assert!(
                (mirrored - want).length() > half_diagonal,
                "{name}: axis {axis} symmetric"
            );
        }
        assert!(!v.placement.is_empty(), "{name}");
        formats.push(entry["format"].as_str().unwrap().to_string());
    }
    for format in [
        "nifti",
        "nifti2",
        "mgh",
        "nrrd",
        "metaimage",
        "tiff",
        "vti",
        "ome-zarr",
    ] {
        assert!(
            formats.iter().any(|f| f == format),
            "no {format} fixture was checked"
        );
    }
}

#[test]
fn stored_types_and_placement_notes() {
    let dir = world_dir();
    let cases = [
        ("sitk.nrrd", "int16", "left-posterior-superior"),
        ("sitk_gzip.nhdr", "uint16", "left-posterior-superior"),
        ("sitk.mha", "uint8", "LPS"),
        ("sitk.mhd", "int16", "LPS"),
        ("imagej_stack.tif", "uint16", "ImageJ"),
        ("nifti2_oblique.nii.gz", "int16", "NIfTI-2 sform"),
        ("freesurfer_oblique.mgz", "float32", "MGH vox2ras"),
        ("freesurfer_coronal.mgh", "uint8", "MGH vox2ras"),
        ("ome_v04.zarr", "uint8", "OME-Zarr 0.4 multiscales"),
        ("ome_v05.zarr", "uint8", "OME-Zarr 0.5 multiscales"),
    ];
    for (name, stored, note) in cases {
        let v = load_volume(&dir.join(name)).unwrap();
        assert_eq!(v.stored_type, stored, "{name}");
        assert!(v.placement.contains(note), "{name}: {}", v.placement);
    }
}
