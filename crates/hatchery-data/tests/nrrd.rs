//! NRRD reading from small hand-written headers: every header variant `load_nrrd` accepts, and
//! the errors of bad files. Expected geometries of the `space` variants were checked against
//! ITK's NrrdImageIO (SimpleITK 2.5) reading the same headers.

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::{DMat4, DVec4};
use hatchery_data::nrrd_file::load_nrrd;
use hatchery_data::{DataError, VolumeData, load_volume};

/// 2 x 3 x 4 voxels of value = index (x fastest).
const N: usize = 24;

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// An attached-data `.nrrd`: header lines, the blank line, then `data`.
fn nrrd(dir: &Path, name: &str, fields: &str, data: &[u8]) -> PathBuf {
    let mut bytes = format!("NRRD0004\n# a comment\n{fields}\n").into_bytes();
    bytes.extend_from_slice(data);
    write(dir, name, &bytes)
}

const U8_3D: &str = "type: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\n";

fn index_bytes() -> Vec<u8> {
    (0..N as u8).collect()
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(bytes).unwrap();
    enc.finish().unwrap()
}

fn assert_index_values(v: &VolumeData) {
    assert_eq!(v.dims, [2, 3, 4]);
    let want: Vec<f32> = (0..N).map(|i| i as f32).collect();
    assert_eq!(v.values_f32(), want);
}

/// The 3x4 affine rows of a volume's voxel -> world transform.
fn affine(v: &VolumeData) -> [[f64; 4]; 3] {
    let m: DMat4 = v.geometry.to_world();
    std::array::from_fn(|r| {
        let row: DVec4 = m.row(r);
        row.to_array()
    })
}

fn assert_affine(v: &VolumeData, want: [[f64; 4]; 3]) {
    let got = affine(v);
    for r in 0..3 {
        for c in 0..4 {
            assert!((got[r][c] - want[r][c]).abs() < 1e-9, "{got:?} != {want:?}");
        }
    }
}

fn error(path: &Path) -> String {
    let e = load_nrrd(path).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(!e.contains('\n'), "{e}");
    e
}

const SPACE: &str = "space directions: (2,0,0) (0,3,0) (0,0,4)\nspace origin: (1,2,3)\n";

#[test]
fn spaces_map_to_ras() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    // RAS, 3D-right-handed and a bare space dimension are taken as given.
    let as_given = [
        [2.0, 0.0, 0.0, 1.0],
        [0.0, 3.0, 0.0, 2.0],
        [0.0, 0.0, 4.0, 3.0],
    ];
    for (i, space) in [
        "space: right-anterior-superior",
        "space: RAS",
        "space: 3D-right-handed",
        "space dimension: 3",
    ]
    .iter()
    .enumerate()
    {
        let p = nrrd(
            d,
            &format!("g{i}.nrrd"),
            &format!("{U8_3D}{space}\n{SPACE}"),
            &data,
        );
        let v = load_nrrd(&p).unwrap();
        assert_index_values(&v);
        assert_affine(&v, as_given);
        assert!(
            v.placement.contains("NRRD space directions"),
            "{}",
            v.placement
        );
    }
    // LPS: x and y negated (ITK: origin (-1, -2, 3), direction diag(-1, -1, 1) in its LPS,
    // i.e. the header's numbers as LPS).
    let p = nrrd(
        d,
        "lps.nrrd",
        &format!("{U8_3D}space: left-posterior-superior\n{SPACE}"),
        &data,
    );
    let v = load_nrrd(&p).unwrap();
    assert_affine(
        &v,
        [
            [-2.0, 0.0, 0.0, -1.0],
            [0.0, -3.0, 0.0, -2.0],
            [0.0, 0.0, 4.0, 3.0],
        ],
    );
    assert_eq!(
        v.placement,
        "NRRD space directions/space origin (left-posterior-superior)"
    );
    // LAS: x negated.
    let p = nrrd(d, "las.nrrd", &format!("{U8_3D}space: LAS\n{SPACE}"), &data);
    assert_affine(
        &load_nrrd(&p).unwrap(),
        [
            [-2.0, 0.0, 0.0, -1.0],
            [0.0, 3.0, 0.0, 2.0],
            [0.0, 0.0, 4.0, 3.0],
        ],
    );
    // Oblique directions with spaces inside the vectors; no origin means 0.
    let p = nrrd(
        d,
        "oblique.nrrd",
        &format!("{U8_3D}space: RAS\nspace directions: (0, 2, 0) (-3, 0, 0) (0,0,1)\n"),
        &data,
    );
    assert_affine(
        &load_nrrd(&p).unwrap(),
        [
            [0.0, -3.0, 0.0, 0.0],
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ],
    );
}

#[test]
fn spacings_and_axis_mins_without_space() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    // Unknown centering is cell centring, as ITK reads it: the first voxel centre is half a
    // spacing after the axis min (ITK: origin (2, 3.5, 5)).
    let p = nrrd(
        d,
        "cell.nrrd",
        &format!("{U8_3D}spacings: 2 3 4\naxis mins: 1 2 3\n"),
        &data,
    );
    let v = load_nrrd(&p).unwrap();
    assert_affine(
        &v,
        [
            [2.0, 0.0, 0.0, 2.0],
            [0.0, 3.0, 0.0, 3.5],
            [0.0, 0.0, 4.0, 5.0],
        ],
    );
    assert!(
        v.placement.contains("spacings/axis mins"),
        "{}",
        v.placement
    );
    let p = nrrd(
        d,
        "node.nrrd",
        &format!("{U8_3D}spacings: 2 3 4\naxis mins: 1 2 3\ncenters: node node node\n"),
        &data,
    );
    assert_affine(
        &load_nrrd(&p).unwrap(),
        [
            [2.0, 0.0, 0.0, 1.0],
            [0.0, 3.0, 0.0, 2.0],
            [0.0, 0.0, 4.0, 3.0],
        ],
    );
    let p = nrrd(d, "plain.nrrd", U8_3D, &data);
    let v = load_nrrd(&p).unwrap();
    assert!(v.geometry.is_axis_aligned());
    assert_eq!(v.spacing(), [1.0; 3]);
    assert_eq!(v.origin(), [0.0; 3]);
    assert!(v.placement.contains("unit spacing"), "{}", v.placement);
}

#[test]
fn detached_data_files_skips_and_encodings() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("data")).unwrap();
    let data = index_bytes();

    // Gzip in a subfolder, with line skip (before decompressing) and byte skip (after).
    let mut inflated = b"junk!".to_vec();
    inflated.extend(&data);
    let mut file = b"text line one\nline two\n".to_vec();
    file.extend(gzip(&inflated));
    write(d, "data/v.raw.gz", &file);
    let p = write(
        d,
        "v.nhdr",
        b"NRRD0005\ntype: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: gzip\nline skip: 2\n\
          byte skip: 5\ndata file: data/v.raw.gz\n",
    );
    assert_index_values(&load_nrrd(&p).unwrap());
    assert_index_values(&load_volume(&p).unwrap());

    // byte skip -1: the raw data ends the file.
    let mut file = vec![7u8; 100];
    file.extend(&data);
    write(d, "end.raw", &file);
    let p = write(
        d,
        "end.nhdr",
        b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\nbyte skip: -1\ndatafile: end.raw\n",
    );
    assert_index_values(&load_nrrd(&p).unwrap());

    // LIST: two files of two slices each.
    write(d, "a.raw", &data[..12]);
    write(d, "b.raw", &data[12..]);
    let p = write(
        d,
        "list.nhdr",
        b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\ndata file: LIST 2\na.raw\nb.raw\n",
    );
    assert_index_values(&load_nrrd(&p).unwrap());

    // A numbered series, one slice per file.
    for k in 0..4 {
        write(d, &format!("s{:02}.raw", k + 1), &data[6 * k..6 * k + 6]);
    }
    let p = write(
        d,
        "series.nhdr",
        b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\ndata file: s%02d.raw 1 4 1 2\n",
    );
    assert_index_values(&load_nrrd(&p).unwrap());

    // ASCII after a skipped line, attached.
    let text: Vec<String> = (0..N).map(|i| i.to_string()).collect();
    let text = format!("skip me\n{}\n", text.join(" "));
    let p = nrrd(
        d,
        "text.nrrd",
        "type: short\ndimension: 3\nsizes: 2 3 4\nencoding: ascii\nline skip: 1\n",
        text.as_bytes(),
    );
    let v = load_nrrd(&p).unwrap();
    assert_index_values(&v);
    assert_eq!(v.stored_type, "int16");
}

#[test]
fn types_and_byte_order() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fields = |ty: &str, endian: &str| {
        format!("type: {ty}\ndimension: 3\nsizes: 2 3 4\nencoding: raw\nendian: {endian}\n")
    };
    let be_i16: Vec<u8> = (0..N as i16).flat_map(|v| (v - 5).to_be_bytes()).collect();
    let v = load_nrrd(&nrrd(d, "i16.nrrd", &fields("short", "big"), &be_i16)).unwrap();
    assert_eq!(v.stored_type, "int16");
    assert_eq!(v.value_range, [-5.0, 18.0]);
    assert_eq!(v.value(1, 0, 0), -4.0);

    let le_u16: Vec<u8> = (0..N as u16)
        .flat_map(|v| (v * 1000).to_le_bytes())
        .collect();
    let v = load_nrrd(&nrrd(
        d,
        "u16.nrrd",
        &fields("unsigned short", "little"),
        &le_u16,
    ))
    .unwrap();
    assert_eq!((v.stored_type, v.value(0, 0, 1)), ("uint16", 6000.0));

    // Wider types become f32; the file's type is still reported.
    let cases: [(&str, Vec<u8>); 5] = [
        (
            "uint32",
            (0..N as u32).flat_map(|v| (v * 3).to_be_bytes()).collect(),
        ),
        (
            "int",
            (0..N as i32).flat_map(|v| (v * 3).to_be_bytes()).collect(),
        ),
        (
            "int64",
            (0..N as i64).flat_map(|v| (v * 3).to_be_bytes()).collect(),
        ),
        (
            "unsigned long long",
            (0..N as u64).flat_map(|v| (v * 3).to_be_bytes()).collect(),
        ),
        (
            "double",
            (0..N)
                .flat_map(|v| (v as f64 * 3.0).to_be_bytes())
                .collect(),
        ),
    ];
    for (ty, bytes) in cases {
        let v = load_nrrd(&nrrd(d, "wide.nrrd", &fields(ty, "big"), &bytes)).unwrap();
        assert_eq!(v.value(1, 2, 3), 69.0, "{ty}");
    }
    let f32s: Vec<u8> = (0..N)
        .flat_map(|v| (v as f32 * 0.5).to_le_bytes())
        .collect();
    let v = load_nrrd(&nrrd(d, "f32.nrrd", &fields("float", "little"), &f32s)).unwrap();
    assert_eq!((v.stored_type, v.value(1, 0, 0)), ("float32", 0.5));
    let i8s: Vec<u8> = (0..N as i8).map(|v| (v - 10) as u8).collect();
    let v = load_nrrd(&nrrd(d, "i8.nrrd", &fields("signed char", "big"), &i8s)).unwrap();
    assert_eq!((v.stored_type, v.value(0, 0, 0)), ("int8", -10.0));
}

#[test]
fn four_d_files_give_their_first_volume() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A leading axis of size 1.
    let p = nrrd(
        d,
        "lead1.nrrd",
        "type: uchar\ndimension: 4\nsizes: 1 2 3 4\nencoding: raw\nspace: RAS\n\
         space directions: none (2,0,0) (0,3,0) (0,0,4)\nspace origin: (1,2,3)\n",
        &index_bytes(),
    );
    let v = load_nrrd(&p).unwrap();
    assert_index_values(&v);
    assert_affine(
        &v,
        [
            [2.0, 0.0, 0.0, 1.0],
            [0.0, 3.0, 0.0, 2.0],
            [0.0, 0.0, 4.0, 3.0],
        ],
    );

    // A trailing list of two volumes: the first is read, and placement says so.
    let mut two = index_bytes();
    two.extend(vec![99u8; N]);
    let p = nrrd(
        d,
        "series.nrrd",
        "type: uchar\ndimension: 4\nsizes: 2 3 4 2\nencoding: raw\nkinds: domain domain domain list\n",
        &two,
    );
    let v = load_nrrd(&p).unwrap();
    assert_index_values(&v);
    assert!(
        v.placement
            .contains("first of 2 volumes along axis 3 (list)"),
        "{}",
        v.placement
    );

    // A leading list axis (DWI-style, interleaved): every other value.
    let interleaved: Vec<u8> = (0..N as u8).flat_map(|v| [v, 200]).collect();
    let p = nrrd(
        d,
        "dwi.nrrd",
        "type: uchar\ndimension: 4\nsizes: 2 2 3 4\nencoding: raw\nkinds: list domain domain domain\n\
         space: LPS\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\n",
        &interleaved,
    );
    assert_index_values(&load_nrrd(&p).unwrap());

    // Per-voxel components are not a series: refused, not read as channel 0.
    let p = nrrd(
        d,
        "rgb.nrrd",
        "type: uchar\ndimension: 4\nsizes: 2 2 3 4\nencoding: raw\nkinds: RGB-color domain domain domain\n",
        &interleaved,
    );
    let e = error(&p);
    assert!(
        e.contains("values per voxel") && e.contains("rgb-color"),
        "{e}"
    );
    let p = nrrd(
        d,
        "vec3d.nrrd",
        "type: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\nkinds: vector domain domain\n",
        &index_bytes(),
    );
    assert!(error(&p).contains("not a scalar volume"));
    // No way to tell which axis is not spatial.
    let p = nrrd(
        d,
        "ambiguous.nrrd",
        "type: uchar\ndimension: 4\nsizes: 2 2 3 4\nencoding: raw\n",
        &interleaved,
    );
    assert!(error(&p).contains("cannot tell which axis"));
}

#[test]
fn bad_files_are_refused_with_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    let cases: [(&str, String, &[u8], &str); 17] = [
        ("truncated", U8_3D.into(), &data[..20], "20 of the 24 bytes"),
        (
            "short-sizes",
            "type: uchar\ndimension: 3\nsizes: 2 3\nencoding: raw\n".into(),
            &data,
            "sizes",
        ),
        (
            "zero-size",
            "type: uchar\ndimension: 3\nsizes: 2 0 4\nencoding: raw\n".into(),
            &data,
            "sizes",
        ),
        (
            "bad-size",
            "type: uchar\ndimension: 3\nsizes: 2 x 4\nencoding: raw\n".into(),
            &data,
            "bad sizes",
        ),
        (
            "huge",
            "type: uchar\ndimension: 3\nsizes: 4096 4096 4096\nencoding: raw\n".into(),
            &data,
            "more than the limit",
        ),
        (
            "unknown-type",
            "type: quaternion\ndimension: 3\nsizes: 2 3 4\nencoding: raw\n".into(),
            &data,
            "unknown type `quaternion`",
        ),
        (
            "block",
            "type: block\ndimension: 3\nsizes: 2 3 4\nencoding: raw\n".into(),
            &data,
            "block",
        ),
        (
            "no-endian",
            "type: short\ndimension: 3\nsizes: 2 3 4\nencoding: raw\n".into(),
            &data,
            "endian",
        ),
        (
            "no-type",
            "dimension: 3\nsizes: 2 3 4\nencoding: raw\n".into(),
            &data,
            "no `type`",
        ),
        (
            "bzip2",
            "type: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: bzip2\n".into(),
            &data,
            "bzip2",
        ),
        (
            "dim2",
            "type: uchar\ndimension: 2\nsizes: 6 4\nencoding: raw\n".into(),
            &data,
            "dimension 2",
        ),
        (
            "unknown-field",
            format!("{U8_3D}spaec directions: (1,0,0) (0,1,0) (0,0,1)\n"),
            &data,
            "unknown header field",
        ),
        ("twice", format!("{U8_3D}encoding: raw\n"), &data, "twice"),
        (
            "space-alone",
            format!("{U8_3D}space: LPS\n"),
            &data,
            "without `space directions`",
        ),
        (
            "bad-space",
            format!("{U8_3D}space: RAST\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"),
            &data,
            "space `RAST`",
        ),
        (
            "bad-direction",
            format!("{U8_3D}space: RAS\nspace directions: (1,0,0) (0,1,0)\n"),
            &data,
            "space directions",
        ),
        (
            "gzip-truncated",
            "type: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: gzip\n".into(),
            &gzip(&data)[..15],
            "data",
        ),
    ];
    for (name, fields, body, want) in cases {
        let p = nrrd(d, &format!("{name}.nrrd"), &fields, body);
        let e = error(&p);
        assert!(e.contains(want), "{name}: {e}");
    }
    // Key/value pairs are not fields.
    let p = nrrd(d, "kv.nrrd", &format!("{U8_3D}modality:=DWMRI\n"), &data);
    assert_index_values(&load_nrrd(&p).unwrap());

    let p = write(d, "magic.nrrd", b"P5\n2 3\n255\n");
    assert!(error(&p).contains("not a NRRD file"));
    let p = write(d, "empty.nrrd", b"");
    assert!(error(&p).contains("not a NRRD file"));
    let p = write(d, "nodata.nhdr", format!("NRRD0004\n{U8_3D}").as_bytes());
    assert!(error(&p).contains("no `data file`"));
    // A missing data file is an I/O error naming that file.
    let p = write(
        d,
        "gone.nhdr",
        format!("NRRD0004\n{U8_3D}data file: gone.raw\n").as_bytes(),
    );
    match load_nrrd(&p).unwrap_err() {
        DataError::Io { path, .. } => assert!(path.ends_with("gone.raw")),
        other => panic!("{other}"),
    }
    // A data file too short for byte skip -1.
    write(d, "tiny.raw", &data[..3]);
    let p = write(
        d,
        "tiny.nhdr",
        format!("NRRD0004\n{U8_3D}byte skip: -1\ndata file: tiny.raw\n").as_bytes(),
    );
    assert!(
        load_nrrd(&p)
            .unwrap_err()
            .to_string()
            .contains("shorter than 24 bytes")
    );
}
