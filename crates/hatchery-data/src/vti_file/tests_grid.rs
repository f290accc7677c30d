//! Unit tests of array choice, pieces, type conversions and placement, on files written here.

use super::load_vti;
use super::tests::write;
use glam::{DMat3, DVec3};

/// A VTKFile with `grid` attributes on ImageData around `pieces` (markup).
fn image(grid: &str, pieces: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <ImageData {grid}>
{pieces}
  </ImageData>
</VTKFile>
"#
    )
}

/// One piece with ASCII point and cell arrays (`(name, type, values)`).
fn piece(
    extent: &str,
    active: &str,
    point: &[(&str, &str, &str)],
    cell: &[(&str, &str, &str)],
) -> String {
    let arrays = |list: &[(&str, &str, &str)]| -> String {
        list.iter()
            .map(|(name, ty, values)| {
                format!(
                    r#"<DataArray type="{ty}" Name="{name}" format="ascii">{values}</DataArray>"#
                )
            })
            .collect()
    };
    format!(
        r#"<Piece Extent="{extent}"><PointData {active}>{}</PointData><CellData>{}</CellData></Piece>"#,
        arrays(point),
        arrays(cell)
    )
}

fn numbers(n: usize, f: impl Fn(usize) -> String) -> String {
    (0..n).map(f).collect::<Vec<_>>().join(" ")
}

#[test]
fn the_array_option_picks_point_or_cell_arrays() {
    let dir = tempfile::tempdir().unwrap();
    let points = numbers(27, |i| i.to_string());
    let body = image(
        r#"WholeExtent="0 2 0 2 0 2" Origin="0 0 0" Spacing="1 1 1""#,
        &piece(
            "0 2 0 2 0 2",
            r#"Scalars="b""#,
            &[
                ("a", "Float32", &numbers(27, |i| format!("{}.5", i))),
                ("b", "UInt8", &points),
                ("rgb", "UInt8", &numbers(81, |_| "1".into())),
            ],
            &[("c", "Int16", &numbers(8, |i| format!("-{i}")))],
        )
        .replace(r#"Name="rgb""#, r#"Name="rgb" NumberOfComponents="3""#),
    );
    let path = write(&dir, "arrays.vti", body.as_bytes());

    let b = load_vti(&path, None).unwrap();
    assert_eq!(b.stored_type, "uint8");
    assert_eq!(b.value_range, [0.0, 26.0]);
    assert!(b.placement.ends_with("point data `b`"), "{}", b.placement);

    let a = load_vti(&path, Some("a")).unwrap();
    assert_eq!((a.stored_type, a.value_range), ("float32", [0.5, 26.5]));

    let c = load_vti(&path, Some("c")).unwrap();
    assert_eq!(c.dims, [2, 2, 2]);
    assert_eq!(c.value_range, [-7.0, 0.0]);
    assert_eq!(c.origin(), [0.5; 3]);
    assert!(
        c.placement.ends_with("cell data (cell centres) `c`"),
        "{}",
        c.placement
    );

    let e = load_vti(&path, Some("rgb")).unwrap_err().to_string();
    assert!(e.contains("`rgb` has 3 components"), "{e}");
    assert!(e.contains("`rgb` (UInt8 × 3)"), "{e}");
    let e = load_vti(&path, Some("d")).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(
        e.ends_with(
            "has no data array `d`; the file's arrays are: point data `a` (Float32), `b` (UInt8, \
             active), `rgb` (UInt8 × 3); cell data `c` (Int16)"
        ),
        "{e}"
    );

    // No active scalars: the first array that can be read, skipping the 3-component one.
    let body = body.replace(r#"Scalars="b""#, "").replace(
        r#"<DataArray type="Float32" Name="a" format="ascii">"#,
        r#"<DataArray type="String" Name="a" format="ascii">"#,
    );
    let path = write(&dir, "inactive.vti", body.as_bytes());
    assert!(
        load_vti(&path, None)
            .unwrap()
            .placement
            .ends_with("point data `b`")
    );
    let e = load_vti(&path, Some("a")).unwrap_err().to_string();
    assert!(e.contains("has type String"), "{e}");
}

#[test]
fn pieces_are_assembled_and_gaps_are_no_data() {
    let dir = tempfile::tempdir().unwrap();
    // 4 x 2 x 2 points, value 10 x + y + 100 z, in two pieces sharing the points x = 1.
    let values = |x0: usize, x1: usize| {
        let mut v = Vec::new();
        for z in 0..2 {
            for y in 0..2 {
                for x in x0..=x1 {
                    v.push((10 * x + y + 100 * z).to_string());
                }
            }
        }
        v.join(" ")
    };
    let grid = r#"WholeExtent="0 3 0 1 0 1" Origin="0 0 0" Spacing="1 1 1""#;
    let body = image(
        grid,
        &[
            piece("0 1 0 1 0 1", "", &[("v", "UInt8", &values(0, 1))], &[]),
            piece("0 -1 0 -1 0 -1", "", &[], &[]),
            piece("1 3 0 1 0 1", "", &[("v", "UInt8", &values(1, 3))], &[]),
        ]
        .concat(),
    );
    let v = load_vti(&write(&dir, "pieces.vti", body.as_bytes()), None).unwrap();
    assert_eq!(v.dims, [4, 2, 2]);
    assert_eq!(v.stored_type, "uint8");
    assert_eq!(v.value(3, 1, 1), 131.0);
    assert_eq!(v.value(1, 0, 1), 110.0);
    assert!(!v.placement.contains("NaN"), "{}", v.placement);

    // Without the points x = 2 the volume keeps its extent; the gap is NaN, and said so.
    let body = image(
        grid,
        &[
            piece("0 1 0 1 0 1", "", &[("v", "UInt8", &values(0, 1))], &[]),
            piece("3 3 0 1 0 1", "", &[("v", "UInt8", &values(3, 3))], &[]),
        ]
        .concat(),
    );
    let v = load_vti(&write(&dir, "gap.vti", body.as_bytes()), None).unwrap();
    assert_eq!(v.dims, [4, 2, 2]);
    assert!(v.value(2, 1, 0).is_nan());
    assert_eq!(v.value(3, 1, 1), 131.0);
    assert_eq!(v.value_range, [0.0, 131.0]);
    assert!(
        v.placement
            .ends_with("point data `v`; 4 voxels in no piece are NaN"),
        "{}",
        v.placement
    );

    // A piece without the array.
    let body =
        body.replacen(r#"Name="v""#, r#"Name="w""#, 2)
            .replacen(r#"Name="w""#, r#"Name="v""#, 1);
    let e = load_vti(&write(&dir, "missing.vti", body.as_bytes()), None).unwrap_err();
    assert!(
        e.to_string()
            .contains("piece 1 has no point data array `v`"),
        "{e}"
    );
}

#[test]
fn conversions_to_float32_are_noted() {
    let dir = tempfile::tempdir().unwrap();
    let grid = r#"WholeExtent="0 1 0 1 0 1""#;
    let case = |ty: &str, values: &str| {
        let body = image(grid, &piece("0 1 0 1 0 1", "", &[("v", ty, values)], &[]));
        load_vti(&write(&dir, "t.vti", body.as_bytes()), None)
    };
    let v = case("Int64", "16777217 -16777219 3 4 5 6 7 9223372036854775807").unwrap();
    assert_eq!(v.stored_type, "int64");
    assert!(
        v.placement.ends_with("; 3 int64 values rounded to float32"),
        "{}",
        v.placement
    );
    let v = case("Float64", "1e300 -1e300 nan inf 1 2 3 0.1").unwrap();
    assert_eq!(v.stored_type, "float64");
    assert_eq!(v.value_range, [0.1, 3.0]);
    assert!(v.values_f32()[2].is_nan() && v.values_f32()[3] == f32::INFINITY);
    assert!(
        v.placement
            .ends_with("; 2 float64 values beyond the float32 range became ±inf (no data)"),
        "{}",
        v.placement
    );
    let v = case("Int8", "-128 127 0 1 2 3 4 5.0").unwrap();
    assert_eq!((v.stored_type, v.value_range), ("int8", [-128.0, 127.0]));
    for (ty, values, message) in [
        (
            "UInt8",
            "0 1 2 3 4 5 6 256",
            "`256` is not an integer from 0 to 255 (uint8)",
        ),
        (
            "Int16",
            "0 1 2 3 4 5 6 1.5",
            "`1.5` is not an integer from -32768 to 32767 (int16)",
        ),
        (
            "UInt32",
            "0 1 2 3 4 5 6 -1",
            "`-1` is not an integer from 0 to 4294967295 (uint32)",
        ),
        ("Float32", "0 1 2 3 4 5 6 x", "`x` is not a number"),
    ] {
        let e = case(ty, values).unwrap_err().to_string();
        assert!(e.contains(message), "{e}");
    }
}

#[test]
fn direction_columns_and_spacing_signs_keep_the_transform() {
    let dir = tempfile::tempdir().unwrap();
    // Direction columns of length 2 and 1, a zero spacing along k (taken as 1).
    let body = image(
        r#"WholeExtent="1 2 -1 0 3 4" Origin="10 20 30" Spacing="0.5 -3 0" Direction="0 1 0 -2 0 0 0 0 1""#,
        &piece(
            "1 2 -1 0 3 4",
            "",
            &[("v", "Float32", "0 1 2 3 4 5 6 7")],
            &[],
        ),
    );
    let v = load_vti(&write(&dir, "d.vti", body.as_bytes()), None).unwrap();
    // VTK: world = Origin + Direction · (Spacing ⊙ (i, j, k)), (i, j, k) from the extent.
    let d = DMat3::from_cols_array(&[0.0, -2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let s = DVec3::new(0.5, -3.0, 1.0);
    for (i, j, k) in [(1, -1, 3), (2, -1, 3), (1, 0, 4), (2, 0, 4)] {
        let ijk = DVec3::new(i as f64, j as f64, k as f64);
        let expected = DVec3::new(10.0, 20.0, 30.0) + d * (s * ijk);
        let voxel = ijk - DVec3::new(1.0, -1.0, 3.0);
        let got = v.geometry.to_world().transform_point3(voxel);
        assert!((got - expected).length() < 1e-12, "{got} {expected}");
    }
    assert_eq!(v.geometry.spacing, DVec3::new(1.0, 3.0, 1.0));
    assert!(
        v.placement.ends_with("; Spacing 0 along axis 2 taken as 1"),
        "{}",
        v.placement
    );

    let singular = body.replace(
        r#"Direction="0 1 0 -2 0 0 0 0 1""#,
        r#"Direction="1 1 0 1 1 0 0 0 1""#,
    );
    let e = load_vti(&write(&dir, "s.vti", singular.as_bytes()), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("degenerate"), "{e}");
    let short = body.replace(
        r#"Direction="0 1 0 -2 0 0 0 0 1""#,
        r#"Direction="1 0 0 0 1 0""#,
    );
    let e = load_vti(&write(&dir, "b.vti", short.as_bytes()), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("bad Direction"), "{e}");
}
