//! The `.vti` reader on files VTK itself wrote (tests/fixtures/vti at the repository root, made
//! by scripts/make_vti_fixtures.py with the VTK Python package), against the answers VTK gave
//! for them (truth.json: its index → physical transform, the world centroid of the voxels above
//! a threshold, the value range).

use std::path::{Path, PathBuf};

use glam::DVec3;
use hatchery_data::vti_file::load_vti;
use hatchery_data::{DataError, VolumeData};
use serde_json::Value;

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/fixtures/vti");
const TWO_ARRAYS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../../shared/cases/grid_two_arrays.vti"
);

fn fixture(name: &str) -> PathBuf {
    Path::new(FIXTURES).join(name)
}

fn truth() -> Value {
    let text = std::fs::read_to_string(fixture("truth.json")).expect("truth.json");
    serde_json::from_str(&text).expect("truth.json is JSON")
}

fn f64s(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn world(v: &VolumeData, i: usize) -> DVec3 {
    let [nx, ny, _] = v.dims.map(|d| d as usize);
    let ijk = DVec3::new(
        (i % nx) as f64,
        (i / nx % ny) as f64,
        (i / (nx * ny)) as f64,
    );
    v.geometry.to_world().transform_point3(ijk)
}

/// Checks a loaded array against VTK's answers for it.
fn check(v: &VolumeData, t: &Value, what: &str) {
    let dims: Vec<u32> = f64s(&t["dims"]).iter().map(|&d| d as u32).collect();
    assert_eq!(v.dims.to_vec(), dims, "{what}");

    let m = v.geometry.to_world();
    for (r, row) in t["affine"].as_array().unwrap().iter().enumerate() {
        for (c, expected) in f64s(row).into_iter().enumerate() {
            let got = m.col(c)[r];
            assert!(
                (got - expected).abs() < 1e-5,
                "{what}: affine[{r}][{c}] is {got}, VTK says {expected}"
            );
        }
    }

    let range = f64s(&t["value_range"]);
    for (got, expected) in v.value_range.iter().zip(&range) {
        let tolerance = 1e-6 * expected.abs().max(1.0);
        assert!(
            (*got as f64 - expected).abs() <= tolerance,
            "{what}: value range {:?}, VTK says {range:?}",
            v.value_range
        );
    }
    let non_finite = v.values_f32().iter().filter(|x| !x.is_finite()).count();
    assert_eq!(
        non_finite as u64,
        t["non_finite"].as_u64().unwrap(),
        "{what}"
    );

    let threshold = t["threshold"].as_f64().unwrap();
    let above: Vec<usize> = (0..v.values_f32().len())
        .filter(|&i| v.values_f32()[i] as f64 > threshold)
        .collect();
    assert_eq!(above.len() as u64, t["above"].as_u64().unwrap(), "{what}");
    if !above.is_empty() {
        let centroid = above.iter().map(|&i| world(v, i)).sum::<DVec3>() / above.len() as f64;
        let expected = DVec3::from_slice(&f64s(&t["centroid_above"]));
        assert!(
            (centroid - expected).length() < 1e-3,
            "{what}: centroid {centroid}, VTK says {expected}"
        );
    }
    if let Some(first) = t["first"].as_f64() {
        assert_eq!(v.values_f32()[0], first as f32, "{what}");
    }
    assert_eq!(
        *v.values_f32().last().unwrap(),
        t["last"].as_f64().unwrap() as f32,
        "{what}"
    );
}

#[test]
fn every_fixture_reads_as_vtk_reads_it() {
    let truth = truth();
    let files = truth["files"].as_object().unwrap();
    assert!(files.len() >= 13, "{}", files.len());
    let mut checked = 0;
    for (name, records) in files {
        let path = fixture(name);
        for t in records.as_array().unwrap() {
            let array = t["array"].as_str().unwrap();
            let v = load_vti(&path, Some(array)).unwrap_or_else(|e| panic!("{e}"));
            check(&v, t, &format!("{name} `{array}`"));
            let set = if t["cells"].as_bool().unwrap() {
                "cell data (cell centres)"
            } else {
                "point data"
            };
            assert!(
                v.placement.contains(&format!("{set} `{array}`")),
                "{}",
                v.placement
            );
            checked += 1;
        }
    }
    assert!(checked >= 40, "{checked}");
}

#[test]
fn default_array_is_the_active_scalars() {
    let truth = truth();
    for (name, records) in truth["files"].as_object().unwrap() {
        let v = load_vti(&fixture(name), None).unwrap();
        // Point data `density` is active (the second array) where there is point data;
        // cells_only.vti has only its active cell array; types.vti has no active array, so
        // its first one is read.
        let expected = match name.as_str() {
            "cells_only.vti" => "cells",
            "types.vti" => "u8",
            _ => "density",
        };
        let t = records
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["array"] == expected)
            .unwrap();
        check(&v, t, &format!("{name} (default array)"));
    }
}

#[test]
fn native_types_are_named() {
    for (array, stored) in [
        ("u8", "uint8"),
        ("i8", "int8"),
        ("u16", "uint16"),
        ("i16", "int16"),
        ("i32", "int32"),
        ("u32", "uint32"),
        ("i64", "int64"),
        ("u64", "uint64"),
        ("f32", "float32"),
        ("f64", "float64"),
    ] {
        let v = load_vti(&fixture("types.vti"), Some(array)).unwrap();
        assert_eq!(v.stored_type, stored);
        // Every value of these arrays fits float32 exactly: no note.
        assert!(!v.placement.contains("rounded"), "{}", v.placement);
    }
}

#[test]
fn mirrored_and_rotated_grids_keep_a_positive_spacing() {
    let v = load_vti(&fixture("rotated_negative_spacing.vti"), None).unwrap();
    assert!(v.geometry.spacing.min_element() > 0.0);
    // Spacing 0.8, -1.25, 2 with unit direction columns: the sign went into the direction.
    assert!((v.geometry.spacing - DVec3::new(0.8, 1.25, 2.0)).length() < 1e-12);
    assert!(v.geometry.direction.determinant() > 0.0); // mirror × flipped j
    let v = load_vti(&fixture("grid_none_uint32.vti"), None).unwrap();
    assert!(v.geometry.direction.determinant() < 0.0); // diag(-1, 1, 1)
    assert_eq!(
        v.placement,
        "VTK Origin/Spacing/Direction, extent 2..13 0..9 1..8, point data `density`"
    );
}

#[test]
fn shared_case_reads_the_active_temperature() {
    let v = load_vti(Path::new(TWO_ARRAYS), None).unwrap();
    assert!(v.placement.contains("`Temperature`"), "{}", v.placement);
    // "About 250..350" (shared/cases/README.md); VTK reads 270.61434..342.78312.
    let [lo, hi] = v.value_range;
    assert!(
        (lo as f64 - 270.61434).abs() < 1e-3 && (hi as f64 - 342.78312).abs() < 1e-3,
        "{lo}..{hi}"
    );
    assert_eq!(v.stored_type, "float64");
    let var = load_vti(Path::new(TWO_ARRAYS), Some("Temperature_var")).unwrap();
    assert!(
        (var.value_range[0] - 0.01).abs() < 1e-6,
        "{:?}",
        var.value_range
    );
}

fn error_of(path: &Path, array: Option<&str>) -> String {
    let e = load_vti(path, array).expect_err("an error").to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(!e.contains('\n'), "{e}");
    e
}

#[test]
fn unknown_array_is_an_error_listing_the_arrays() {
    let e = error_of(&fixture("grid_lz4_uint32.vti"), Some("Density"));
    assert!(e.contains("no data array `Density`"), "{e}");
    assert!(
        e.contains(
            "point data `noise` (Float64), `density` (Float32, active); \
             cell data `cells` (Int16, active)"
        ),
        "{e}"
    );
}

/// The file's bytes, and where the raw appended data of `array` starts in them.
fn appended_array(name: &str, array: &str) -> (Vec<u8>, usize) {
    let bytes = std::fs::read(fixture(name)).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    let element = text.find(&format!("Name=\"{array}\"")).unwrap();
    let offset = &text[element..];
    let offset = &offset[offset.find("offset=\"").unwrap() + 8..];
    let offset: usize = offset[..offset.find('"').unwrap()].parse().unwrap();
    let section = text.find("<AppendedData encoding=\"raw\">").unwrap();
    let marker = section + text[section..].find('_').unwrap();
    (bytes, marker + 1 + offset)
}

#[test]
fn unknown_compressor_truncated_and_corrupt_blocks_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let write = |content: &[u8]| {
        let path = dir.path().join("bad.vti");
        std::fs::write(&path, content).unwrap();
        path
    };

    let bytes = std::fs::read(fixture("grid_lz4_uint32.vti")).unwrap();
    let text = String::from_utf8_lossy(&bytes).replace("vtkLZ4DataCompressor", "vtkZstdCompressor");
    let mut renamed = bytes.clone();
    let at = text.find("vtkZstdCompressor").unwrap();
    renamed.splice(at..at + "vtkLZ4DataCompressor".len(), *b"vtkZstdCompressor");
    let e = error_of(&write(&renamed), None);
    assert!(
        e.contains("compressor vtkZstdCompressor is not supported"),
        "{e}"
    );

    // (file, header bytes): every compressor, both header types, all appended raw.
    for (name, wide) in [
        ("grid_lz4_uint32.vti", false),
        ("grid_lzma_uint64.vti", true),
        ("grid_three_pieces.vti", false),
    ] {
        let (bytes, start) = appended_array(name, "density");
        let size = if wide { 8 } else { 4 };
        let number = |b: &[u8], i: usize| {
            let mut a = [0u8; 8];
            a[..size].copy_from_slice(&b[start + i * size..start + (i + 1) * size]);
            u64::from_le_bytes(a)
        };
        let blocks = number(&bytes, 0) as usize;
        assert!(blocks > 1, "{name}: {blocks} blocks");
        let data = start + (3 + blocks) * size;

        // The first block's size claims 3 bytes fewer: its stream is cut short.
        let mut cut = bytes.clone();
        let first = number(&bytes, 3) - 3;
        cut[start + 3 * size..start + 3 * size + size]
            .copy_from_slice(&first.to_le_bytes()[..size]);
        let e = error_of(&write(&cut), Some("density"));
        assert!(e.contains("corrupt compressed block 0"), "{name}: {e}");

        // A byte of the second block's data changed (zlib and xz streams carry checksums;
        // LZ4 blocks do not, so there only the length of the output tells).
        if !name.contains("lz4") {
            let mut corrupt = bytes.clone();
            let second = data + number(&bytes, 3) as usize + 20;
            corrupt[second] ^= 0x55;
            let e = error_of(&write(&corrupt), Some("density"));
            assert!(e.contains("corrupt compressed block 1"), "{name}: {e}");
        }

        // The file ends inside the array's blocks or its header.
        for end in [data + 10, start + 2 * size, start + 1] {
            let e = error_of(&write(&bytes[..end]), Some("density"));
            assert!(e.contains("`density`"), "{name}: {e}");
        }
    }
}

#[test]
fn missing_files_are_io_errors() {
    let e = load_vti(&fixture("missing.vti"), None).unwrap_err();
    assert!(matches!(e, DataError::Io { .. }), "{e}");
}

#[test]
fn corrupt_bytes_are_errors_or_values_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("flipped.vti");
    for name in [
        "grid_lz4_uint32.vti",
        "grid_lzma_uint64.vti",
        "grid_three_pieces.vti",
        "grid_none_uint32.vti",
    ] {
        let (bytes, start) = appended_array(name, "density");
        let (_, end) = appended_array(name, "cells");
        // Every byte of the array's header and blocks (up to the next arrays), flipped.
        for at in start..end.min(start + 1200) {
            let mut flipped = bytes.clone();
            flipped[at] ^= 0xa5;
            std::fs::write(&path, &flipped).unwrap();
            match load_vti(&path, Some("density")) {
                Ok(v) => assert_eq!(v.dims, [12, 10, 8]),
                Err(e) => assert!(e.to_string().contains("`density`"), "{name} @{at}: {e}"),
            }
        }
    }
}
